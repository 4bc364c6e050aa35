//! `.rays` and `.hits` files: little-endian `f32`/`u32` records without a header.
//! `.rays`: `org.x, org.y, org.z, tnear, dir.x, dir.y, dir.z, tfar` (32 bytes).
//! `.hits`: `t` (`+inf` for a miss), `prim` (`0xFFFFFFFF` for a miss) (8 bytes).

use crate::geometry::{Hit, Ray, RayError};
use glam::Vec3;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

#[derive(Debug, Error)]
pub enum RayFileError {
    #[error("cannot read or write {path}: {cause}")]
    Io {
        path: PathBuf,
        /// In the message, not a chained source (so `{:#}` prints it once).
        cause: std::io::Error,
    },
    #[error("{path}: size {size} bytes is not a multiple of {record} (one record per ray/hit)")]
    Size {
        path: PathBuf,
        size: usize,
        record: usize,
    },
    #[error("{path}: record {record} is not a valid ray: {cause}")]
    BadRay {
        path: PathBuf,
        record: usize,
        /// In the message, not a chained source (so `{:#}` prints it once).
        cause: RayError,
    },
    #[error(
        "{path}: record {record} has prim {prim} with t = {t} (a miss must be +inf with 0xFFFFFFFF)"
    )]
    BadHit {
        path: PathBuf,
        record: usize,
        t: f32,
        prim: u32,
    },
}

fn read(path: &Path, record: usize) -> Result<Vec<u8>, RayFileError> {
    let bytes = std::fs::read(path).map_err(|source| RayFileError::Io {
        path: path.to_owned(),
        cause: source,
    })?;
    if bytes.len() % record != 0 {
        return Err(RayFileError::Size {
            path: path.to_owned(),
            size: bytes.len(),
            record,
        });
    }
    Ok(bytes)
}

fn f32_at(b: &[u8], i: usize) -> f32 {
    f32::from_le_bytes(b[i * 4..i * 4 + 4].try_into().unwrap())
}

/// The raw 8 floats of every record (no validation), for tools that report bad records.
pub fn read_rays_raw(path: &Path) -> Result<Vec<[f32; 8]>, RayFileError> {
    let bytes = read(path, 32)?;
    Ok(bytes
        .chunks_exact(32)
        .map(|r| std::array::from_fn(|i| f32_at(r, i)))
        .collect())
}

/// Reads and validates a `.rays` file; the first bad record is named in the error.
pub fn read_rays(path: &Path) -> Result<Vec<Ray>, RayFileError> {
    read_rays_raw(path)?
        .iter()
        .enumerate()
        .map(|(i, r)| {
            Ray::new(
                Vec3::new(r[0], r[1], r[2]),
                Vec3::new(r[4], r[5], r[6]),
                r[3],
                r[7],
            )
            .map_err(|source| RayFileError::BadRay {
                path: path.to_owned(),
                record: i,
                cause: source,
            })
        })
        .collect()
}

/// The protocol record of a ray.
pub fn ray_to_record(r: &Ray) -> [f32; 8] {
    [
        r.origin.x, r.origin.y, r.origin.z, r.t_min, r.dir.x, r.dir.y, r.dir.z, r.t_max,
    ]
}

fn write_all(
    path: &Path,
    f: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), RayFileError> {
    let io = |source| RayFileError::Io {
        path: path.to_owned(),
        cause: source,
    };
    let file = std::fs::File::create(path).map_err(io)?;
    let mut w = BufWriter::new(file);
    f(&mut w).map_err(io)?;
    w.flush().map_err(io)
}

pub fn write_rays(path: &Path, rays: &[Ray]) -> Result<(), RayFileError> {
    write_all(path, |w| {
        for r in rays {
            for x in ray_to_record(r) {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        Ok(())
    })
}

pub fn write_hits(path: &Path, hits: &[Option<Hit>]) -> Result<(), RayFileError> {
    write_all(path, |w| {
        for h in hits {
            let (t, p) = h.map_or((f32::INFINITY, u32::MAX), |h| (h.t, h.prim));
            w.write_all(&t.to_le_bytes())?;
            w.write_all(&p.to_le_bytes())?;
        }
        Ok(())
    })
}

pub fn read_hits(path: &Path) -> Result<Vec<Option<Hit>>, RayFileError> {
    let bytes = read(path, 8)?;
    bytes
        .chunks_exact(8)
        .enumerate()
        .map(|(i, r)| {
            let t = f32_at(r, 0);
            let prim = u32::from_le_bytes(r[4..8].try_into().unwrap());
            match (prim, t) {
                (u32::MAX, t) if t == f32::INFINITY => Ok(None),
                (p, t) if p != u32::MAX && !t.is_nan() => Ok(Some(Hit { t, prim: p })),
                _ => Err(RayFileError::BadHit {
                    path: path.to_owned(),
                    record: i,
                    t,
                    prim,
                }),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_bad_sizes() {
        let dir = tempfile::tempdir().unwrap();
        let rp = dir.path().join("a.rays");
        let rays = vec![
            Ray::new(
                Vec3::new(1.0, 2.0, 3.0),
                Vec3::new(0.0, -0.0, 1.0),
                0.5,
                9.0,
            )
            .unwrap(),
            Ray::infinite(Vec3::splat(-1.0), Vec3::X).unwrap(),
        ];
        write_rays(&rp, &rays).unwrap();
        let back = read_rays(&rp).unwrap();
        assert_eq!(back.len(), 2);
        for (a, b) in rays.iter().zip(&back) {
            assert_eq!(
                ray_to_record(a).map(f32::to_bits),
                ray_to_record(b).map(f32::to_bits)
            );
        }
        let hp = dir.path().join("a.hits");
        let hits = vec![Some(Hit { t: 1.25, prim: 7 }), None];
        write_hits(&hp, &hits).unwrap();
        assert_eq!(read_hits(&hp).unwrap(), hits);

        std::fs::write(&rp, [0u8; 33]).unwrap();
        assert!(matches!(
            read_rays(&rp),
            Err(RayFileError::Size { size: 33, .. })
        ));
        std::fs::write(&hp, [0u8; 9]).unwrap();
        assert!(matches!(read_hits(&hp), Err(RayFileError::Size { .. })));
    }

    #[test]
    fn bad_record_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let rp = dir.path().join("bad.rays");
        let mut bytes = Vec::new();
        for rec in [
            [0.0f32, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0],
            [0.0, f32::NAN, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0],
        ] {
            for x in rec {
                bytes.extend_from_slice(&x.to_le_bytes());
            }
        }
        std::fs::write(&rp, bytes).unwrap();
        match read_rays(&rp) {
            Err(RayFileError::BadRay { record, .. }) => assert_eq!(record, 1),
            other => panic!("{other:?}"),
        }
    }
}
