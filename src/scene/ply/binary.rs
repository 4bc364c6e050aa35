//! The body of a binary PLY file (little- or big-endian), read in place from the mapped bytes.
//! Elements of fixed-size records (vertices of scalars; faces that are all triangles) are
//! parsed in parallel; anything else record by record. Every error names its byte offset.

use super::body::{Body, IndexList, check_fits, coordinates, vertex_index};
use super::header::{Element, Encoding, Fail, Header, Kind, Problem, Role, Scalar, malformed};
use crate::scene::error::Location;
use glam::Vec3A;
use rayon::prelude::*;
use std::sync::Mutex;

/// Records below which the parallel paths stay on one thread.
const MIN_PARALLEL: usize = 1 << 14;

/// Reads every element of the body of `bytes` as `h` declares them. The body must end exactly
/// where the last element does.
pub fn read(bytes: &[u8], h: &Header) -> Result<Body, Fail> {
    let big = h.encoding == Encoding::BigEndian;
    let mut body = Body::default();
    let mut pos = h.body;
    for e in &h.elements {
        let left = (bytes.len() - pos) as u64;
        check_fits(e, min_size(e), left, Location::Byte(pos as u64))?;
        let done = match (e.role, e.fixed_size()) {
            (Role::Vertex(xyz), Some(rec)) => {
                body.positions = vertices(bytes, pos, e, rec, xyz, big)?;
                Some(pos + e.count as usize * rec)
            }
            (Role::Faces(list), _) => triangles(bytes, pos, e, list, big, h.vertices, &mut body)?,
            (Role::Skipped, Some(rec)) => Some(pos + e.count as usize * rec),
            _ => None,
        };
        pos = match done {
            Some(end) => end,
            None => walk(bytes, pos, e, big, h.vertices, &mut body)?,
        };
    }
    if pos != bytes.len() {
        return malformed(
            Location::Byte(pos as u64),
            format!(
                "{} bytes follow the last element; the header's counts are smaller than the data (or the file has trailing garbage)",
                bytes.len() - pos
            ),
        );
    }
    Ok(body)
}

/// The fewest bytes one record of `e` takes (lists empty).
fn min_size(e: &Element) -> u64 {
    e.properties
        .iter()
        .map(|p| match p.kind {
            Kind::Scalar(s) => s.size() as u64,
            Kind::List { count, .. } => count.size() as u64,
        })
        .sum()
}

/// Prefixes a problem of record `r` of `e` with the record.
fn in_record(e: &Element, r: u64, p: Problem) -> Problem {
    match p {
        Problem::Malformed(m) => Problem::Malformed(format!("{} {r}: {m}", e.name)),
        non_finite => non_finite,
    }
}

/// Offset in a record of property `j` when every property before it is a scalar.
fn offset_of(e: &Element, j: usize) -> Option<usize> {
    e.properties[..j]
        .iter()
        .map(|p| match p.kind {
            Kind::Scalar(s) => Some(s.size()),
            Kind::List { .. } => None,
        })
        .sum()
}

fn scalar_of(e: &Element, j: usize) -> Scalar {
    match e.properties[j].kind {
        Kind::Scalar(s) => s,
        Kind::List { count, .. } => count,
    }
}

/// The vertex element of fixed-size records `rec` at `pos` (checked to fit), in parallel.
fn vertices(
    bytes: &[u8],
    pos: usize,
    e: &Element,
    rec: usize,
    xyz: [usize; 3],
    big: bool,
) -> Result<Vec<Vec3A>, Fail> {
    let region = &bytes[pos..pos + e.count as usize * rec];
    let fields = xyz.map(|j| (offset_of(e, j).expect("all scalars"), scalar_of(e, j)));
    let read = |r: &[u8]| fields.map(|(o, s)| s.read(&r[o..], big));
    let mut positions = Vec::new();
    region
        .par_chunks_exact(rec)
        .with_min_len(MIN_PARALLEL)
        .map(|r| {
            let c = read(r);
            Vec3A::new(c[0] as f32, c[1] as f32, c[2] as f32)
        })
        .collect_into_vec(&mut positions);
    if let Some(i) = positions.par_iter().position_first(|p| !p.is_finite()) {
        let problem = coordinates(read(&region[i * rec..]), i as u64).expect_err("not finite");
        return Err((
            Location::Byte((pos + i * rec) as u64),
            in_record(e, i as u64, problem),
        ));
    }
    Ok(positions)
}

/// A face element whose records are all triangles of one fixed size, parsed in parallel:
/// `Some(end)` when it was, `None` when a record is not a triangle (the element is then read
/// record by record). An index out of range before the first non-triangle is an error.
fn triangles(
    bytes: &[u8],
    pos: usize,
    e: &Element,
    list: usize,
    big: bool,
    vertices: u64,
    body: &mut Body,
) -> Result<Option<usize>, Fail> {
    let Kind::List { count, item } = e.properties[list].kind else {
        return Ok(None);
    };
    let others: Option<usize> = e
        .properties
        .iter()
        .enumerate()
        .filter(|(j, _)| *j != list)
        .map(|(_, p)| match p.kind {
            Kind::Scalar(s) => Some(s.size()),
            Kind::List { .. } => None,
        })
        .sum();
    let (Some(others), Some(at)) = (others, offset_of(e, list)) else {
        return Ok(None);
    };
    let rec = others + count.size() + 3 * item.size();
    let Some(end) = (e.count as usize)
        .checked_mul(rec)
        .and_then(|n| n.checked_add(pos))
    else {
        return Ok(None);
    };
    if end > bytes.len() {
        return Ok(None);
    }
    // The first record that is not a well-formed triangle: its number, and its problem
    // (`None`: it is not a triangle, so the layout assumed here ends before it).
    let first_bad: Mutex<Option<(usize, Option<Problem>)>> = Mutex::new(None);
    let note = |r: usize, p: Option<Problem>| {
        let mut b = first_bad.lock().expect("not poisoned");
        if b.as_ref().is_none_or(|(s, _)| r < *s) {
            *b = Some((r, p));
        }
    };
    let tris: Vec<[u32; 3]> = bytes[pos..end]
        .par_chunks_exact(rec)
        .with_min_len(MIN_PARALLEL)
        .enumerate()
        .map(|(r, b)| {
            if count.read(&b[at..], big) != 3.0 {
                note(r, None);
                return [0; 3];
            }
            let mut t = [0u32; 3];
            for (k, v) in t.iter_mut().enumerate() {
                let x = item.read(&b[at + count.size() + k * item.size()..], big);
                match vertex_index(x, vertices) {
                    Ok(i) => *v = i,
                    Err(p) => note(r, Some(p)),
                }
            }
            t
        })
        .collect();
    match first_bad.into_inner().expect("not poisoned") {
        None => {
            body.corners.extend_from_slice(&tris);
            Ok(Some(end))
        }
        Some((r, Some(p))) => Err((
            Location::Byte((pos + r * rec) as u64),
            in_record(e, r as u64, p),
        )),
        Some((_, None)) => Ok(None),
    }
}

/// Reads element `e` at `pos` record by record; returns the offset after it.
fn walk(
    bytes: &[u8],
    mut pos: usize,
    e: &Element,
    big: bool,
    vertices: u64,
    body: &mut Body,
) -> Result<usize, Fail> {
    let wanted = match e.role {
        Role::Faces(j) | Role::Strips(j) => Some(j),
        _ => None,
    };
    let mut scalars = vec![0.0f64; e.properties.len()];
    let mut list = IndexList::default();
    for r in 0..e.count {
        let start = pos;
        let mut take = |n: u64| -> Result<&[u8], Fail> {
            let left = (bytes.len() - pos) as u64;
            if n > left {
                return malformed(
                    Location::Byte(pos as u64),
                    format!(
                        "the file ends inside {} {r} of {} (it needs {n} more bytes, {left} are left); the file is truncated or a count is wrong",
                        e.name, e.count
                    ),
                );
            }
            let b = &bytes[pos..pos + n as usize];
            pos += n as usize;
            Ok(b)
        };
        for (j, p) in e.properties.iter().enumerate() {
            match p.kind {
                Kind::Scalar(s) => scalars[j] = s.read(take(s.size() as u64)?, big),
                Kind::List { count, item } => {
                    let n = count.read(take(count.size() as u64)?, big);
                    if n < 0.0 {
                        return malformed(
                            Location::Byte(start as u64),
                            format!(
                                "{} {r}: list '{}' has a negative length {n}",
                                e.name, p.name
                            ),
                        );
                    }
                    let b = take(n as u64 * item.size() as u64)?;
                    if wanted == Some(j) {
                        list.items.clear();
                        list.items
                            .extend(b.chunks_exact(item.size()).map(|x| item.read(x, big)));
                    }
                }
            }
        }
        let at = || Location::Byte(start as u64);
        let done = match e.role {
            Role::Vertex(xyz) => {
                coordinates(xyz.map(|j| scalars[j]), r).map(|p| body.positions.push(p))
            }
            role => list.push(role, vertices, &mut body.corners),
        };
        done.map_err(|p| (at(), in_record(e, r, p)))?;
    }
    Ok(pos)
}
