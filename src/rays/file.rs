//! `.rays` and `.hits` files: little-endian `f32`/`u32` records without a header.
//! `.rays`: `org.x, org.y, org.z, tnear, dir.x, dir.y, dir.z, tfar` (32 bytes).
//! `.hits`: `t` (`+inf` for a miss), `prim` (`0xFFFFFFFF` for a miss) (8 bytes).

use crate::geometry::{Hit, Ray, RayError};
use glam::Vec3;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

#[derive(Debug, Error)]
pub enum RayFileError {
    #[error("cannot read {path}: {message}")]
    Read { path: PathBuf, message: String },
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
    #[error("{path}: size {size} bytes is not a multiple of {record} (one record per ray/hit)")]
    Size {
        path: PathBuf,
        size: u64,
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

/// Why `path` could not be read, saying what to fix where the cause is plain (a folder given
/// for a file, a missing file).
fn read_error(path: &Path, e: std::io::Error) -> RayFileError {
    let message = if path.is_dir() {
        "it is a folder, not a file: give the path of the file".to_owned()
    } else if e.kind() == std::io::ErrorKind::NotFound {
        format!("no such file ({e})")
    } else {
        e.to_string()
    };
    RayFileError::Read {
        path: path.to_owned(),
        message,
    }
}

/// Why `path` could not be written, naming a missing folder.
fn write_error(path: &Path, e: std::io::Error) -> RayFileError {
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    let message = match parent {
        _ if path.is_dir() => "it is a folder: give the path of a file to write".to_owned(),
        Some(p) if !p.is_dir() => format!(
            "the folder {} does not exist: create it or give another path",
            p.display()
        ),
        _ => e.to_string(),
    };
    RayFileError::Write {
        path: path.to_owned(),
        message,
    }
}

/// A file of fixed-size records, read one record at a time through a buffer: its length is
/// checked against the record size on opening, and only the records asked for are read.
struct Records {
    path: PathBuf,
    reader: BufReader<File>,
    /// Records still to read (at most the limit given to [`Records::open`]).
    left: u64,
}

impl Records {
    /// Opens `path` for its first `limit` records of `record` bytes (all without a limit).
    fn open(path: &Path, record: usize, limit: Option<u64>) -> Result<Records, RayFileError> {
        let file = File::open(path).map_err(|e| read_error(path, e))?;
        let meta = file.metadata().map_err(|e| read_error(path, e))?;
        if meta.is_dir() {
            return Err(read_error(path, std::io::ErrorKind::IsADirectory.into()));
        }
        let size = meta.len();
        if size % record as u64 != 0 {
            return Err(RayFileError::Size {
                path: path.to_owned(),
                size,
                record,
            });
        }
        let count = size / record as u64;
        Ok(Records {
            path: path.to_owned(),
            reader: BufReader::new(file),
            left: limit.map_or(count, |l| l.min(count)),
        })
    }

    /// Records to read, as a capacity to reserve: capped, so a huge file is not reserved
    /// before its first record is checked.
    fn capacity(&self) -> usize {
        self.left.min(1 << 16) as usize
    }

    /// Reads the next record into `buf`; `false` when none is left.
    fn next_into(&mut self, buf: &mut [u8]) -> Result<bool, RayFileError> {
        if self.left == 0 {
            return Ok(false);
        }
        self.reader
            .read_exact(buf)
            .map_err(|e| read_error(&self.path, e))?;
        self.left -= 1;
        Ok(true)
    }
}

fn f32_at(b: &[u8], i: usize) -> f32 {
    f32::from_le_bytes([b[i * 4], b[i * 4 + 1], b[i * 4 + 2], b[i * 4 + 3]])
}

/// The raw 8 floats of every record (no validation), for tools that report bad records.
pub fn read_rays_raw(path: &Path) -> Result<Vec<[f32; 8]>, RayFileError> {
    let mut records = Records::open(path, 32, None)?;
    let mut out = Vec::with_capacity(records.capacity());
    let mut buf = [0u8; 32];
    while records.next_into(&mut buf)? {
        out.push(std::array::from_fn(|i| f32_at(&buf, i)));
    }
    Ok(out)
}

/// Reads and validates a `.rays` file; the first bad record is named in the error.
pub fn read_rays(path: &Path) -> Result<Vec<Ray>, RayFileError> {
    read_rays_limit(path, None)
}

/// [`read_rays`] of the first `limit` records only (all without a limit): the file is read
/// record by record and each is checked as it is read, so a bad record stops the reading there.
pub fn read_rays_limit(path: &Path, limit: Option<u64>) -> Result<Vec<Ray>, RayFileError> {
    let mut records = Records::open(path, 32, limit)?;
    let mut rays = Vec::with_capacity(records.capacity());
    let mut buf = [0u8; 32];
    while records.next_into(&mut buf)? {
        let r: [f32; 8] = std::array::from_fn(|i| f32_at(&buf, i));
        let ray = Ray::new(
            Vec3::new(r[0], r[1], r[2]),
            Vec3::new(r[4], r[5], r[6]),
            r[3],
            r[7],
        )
        .map_err(|cause| RayFileError::BadRay {
            path: path.to_owned(),
            record: rays.len(),
            cause,
        })?;
        rays.push(ray);
    }
    Ok(rays)
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
    let file = File::create(path).map_err(|e| write_error(path, e))?;
    let mut w = BufWriter::new(file);
    f(&mut w).map_err(|e| write_error(path, e))?;
    w.flush().map_err(|e| write_error(path, e))
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

/// Reads and validates a `.hits` file record by record; the first bad record is named.
pub fn read_hits(path: &Path) -> Result<Vec<Option<Hit>>, RayFileError> {
    let mut records = Records::open(path, 8, None)?;
    let mut hits = Vec::with_capacity(records.capacity());
    let mut buf = [0u8; 8];
    while records.next_into(&mut buf)? {
        let t = f32_at(&buf, 0);
        let prim = u32::from_le_bytes([buf[4], buf[5], buf[6], buf[7]]);
        hits.push(match (prim, t) {
            (u32::MAX, t) if t == f32::INFINITY => None,
            (p, t) if p != u32::MAX && !t.is_nan() => Some(Hit { t, prim: p }),
            _ => {
                return Err(RayFileError::BadHit {
                    path: path.to_owned(),
                    record: hits.len(),
                    t,
                    prim,
                });
            }
        });
    }
    Ok(hits)
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
