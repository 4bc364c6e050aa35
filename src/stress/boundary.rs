//! Bad rays are rejected at the boundary with a clear error: NaN or infinite components, zero
//! directions and bad intervals in [`Ray::new`], and a `.rays` file with such a record names the
//! record.

use crate::geometry::Ray;
use crate::rays::read_rays;
use glam::Vec3;

/// One boundary check: what was tried and the error it gave (`Err` when the check failed).
#[derive(Debug, Clone)]
pub struct BoundaryCheck {
    pub name: String,
    pub outcome: Result<String, String>,
}

/// Every bad ray must give an error; the `.rays` file with a bad record 2 must name record 2.
pub fn run() -> Vec<BoundaryCheck> {
    let (nan, inf) = (f32::NAN, f32::INFINITY);
    let bad: [(&str, [f32; 8]); 9] = [
        ("NaN origin", [nan, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, inf]),
        ("infinite origin", [0.0, -inf, 0.0, 0.0, 1.0, 0.0, 0.0, inf]),
        ("NaN direction", [0.0, 0.0, 0.0, 0.0, 1.0, nan, 0.0, inf]),
        (
            "infinite direction",
            [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, inf, inf],
        ),
        ("zero direction", [0.0, 0.0, 0.0, 0.0, 0.0, -0.0, 0.0, inf]),
        ("NaN t_min", [0.0, 0.0, 0.0, nan, 1.0, 0.0, 0.0, inf]),
        ("NaN t_max", [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, nan]),
        ("infinite t_min", [0.0, 0.0, 0.0, inf, 1.0, 0.0, 0.0, inf]),
        ("t_min > t_max", [0.0, 0.0, 0.0, 2.0, 1.0, 0.0, 0.0, 1.0]),
    ];
    let mut out: Vec<BoundaryCheck> = bad
        .iter()
        .map(|(name, r)| BoundaryCheck {
            name: format!("Ray::new rejects {name}"),
            outcome: match from_record(r) {
                Ok(ray) => Err(format!("accepted {ray:?}")),
                Err(e) => Ok(e.to_string()),
            },
        })
        .collect();
    out.push(file_check(&bad[0].1));
    out
}

fn from_record(r: &[f32; 8]) -> Result<Ray, crate::geometry::RayError> {
    Ray::new(
        Vec3::new(r[0], r[1], r[2]),
        Vec3::new(r[4], r[5], r[6]),
        r[3],
        r[7],
    )
}

/// Writes two good records and a bad one into a temporary `.rays` file and reads it back.
fn file_check(bad: &[f32; 8]) -> BoundaryCheck {
    let name = "a .rays file names its bad record (record 2)".to_owned();
    let good = [0.0f32, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, f32::INFINITY];
    let bytes: Vec<u8> = [good, good, *bad]
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let path = std::env::temp_dir().join(format!(
        "accelbench-stress-{}-{:?}.rays",
        std::process::id(),
        std::thread::current().id()
    ));
    let outcome = match std::fs::write(&path, bytes) {
        Err(e) => Err(format!("cannot write {}: {e}", path.display())),
        Ok(()) => match read_rays(&path) {
            Ok(_) => Err("the file was accepted".to_owned()),
            Err(e) if e.to_string().contains("record 2") => Ok(e.to_string()),
            Err(e) => Err(format!("the error does not name record 2: {e}")),
        },
    };
    let _ = std::fs::remove_file(&path);
    BoundaryCheck { name, outcome }
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_bad_ray_is_rejected_with_a_message() {
        for c in super::run() {
            assert!(c.outcome.is_ok(), "{}: {:?}", c.name, c.outcome);
        }
    }
}
