//! The body of an ASCII PLY file: one record per line, as Stanford's tools write and read it.
//! Each element's lines are found first (a fast newline scan), then parsed in parallel in
//! pieces of whole lines; an error's byte offset becomes its line number at the end.

use super::body::{Body, IndexList, check_fits};
use super::header::{Element, Fail, Header, Kind, Problem, Role, malformed};
use crate::scene::coordinate::{self, Bad};
use crate::scene::error::Location;
use glam::Vec3A;
use rayon::prelude::*;

/// Bytes below which an element is parsed as one piece.
const MIN_PIECE: usize = 1 << 16;

/// Reads every element of the body of `bytes` as `h` declares them; only blank space may
/// follow the last element. Errors name the line.
pub fn read(bytes: &[u8], h: &Header) -> Result<Body, Fail> {
    read_at_offsets(bytes, h).map_err(|(at, p)| match at {
        Location::Byte(off) => {
            let body = &bytes[h.body..(off as usize).clamp(h.body, bytes.len())];
            let line = h.lines + 1 + body.iter().filter(|&&b| b == b'\n').count();
            (Location::Line(line), p)
        }
        other => (other, p),
    })
}

fn read_at_offsets(bytes: &[u8], h: &Header) -> Result<Body, Fail> {
    let mut body = Body::default();
    let mut pos = h.body;
    for e in &h.elements {
        // Each value takes a character and a separator at least.
        let min = 2 * e.properties.len() as u64;
        check_fits(
            e,
            min,
            (bytes.len() - pos) as u64,
            Location::Byte(pos as u64),
        )?;
        let end = element_end(bytes, pos, e)?;
        if e.role != Role::Skipped {
            let pieces: Vec<Result<Body, Fail>> = pieces(bytes, pos, end)
                .into_par_iter()
                .map(|(a, b)| piece(bytes, a, b, e, h.vertices))
                .collect();
            for p in pieces {
                let p = p?;
                body.positions.extend_from_slice(&p.positions);
                body.corners.extend_from_slice(&p.corners);
            }
        }
        pos = end;
    }
    if let Some(i) = bytes[pos..].iter().position(|b| !b.is_ascii_whitespace()) {
        return malformed(
            Location::Byte((pos + i) as u64),
            "data after the last element; the header's counts are smaller than the data".into(),
        );
    }
    Ok(body)
}

/// The offset after the `e.count` lines from `pos`, or where the file ends too early.
fn element_end(bytes: &[u8], pos: usize, e: &Element) -> Result<usize, Fail> {
    let Some(last) = (e.count as usize).checked_sub(1) else {
        return Ok(pos);
    };
    let rest = &bytes[pos..];
    if let Some(i) = memchr::memchr_iter(b'\n', rest).nth(last) {
        return Ok(pos + i + 1);
    }
    let lines = memchr::memchr_iter(b'\n', rest).count() + usize::from(!rest.ends_with(b"\n"));
    if lines as u64 == e.count {
        return Ok(bytes.len());
    }
    malformed(
        Location::Byte(bytes.len() as u64),
        format!(
            "the file ends after {lines} of the {} '{}' lines the header declares (line {}); the file is truncated or the count is wrong",
            e.count, e.name, e.line
        ),
    )
}

/// `[pos, end)` cut into pieces of whole lines for the threads.
fn pieces(bytes: &[u8], pos: usize, end: usize) -> Vec<(usize, usize)> {
    let n = ((end - pos) / MIN_PIECE).clamp(1, 8 * rayon::current_num_threads());
    let mut cuts = vec![pos];
    for k in 1..n {
        let guess = pos + (end - pos) * k / n;
        let last = *cuts.last().expect("pos");
        if let Some(i) = memchr::memchr(b'\n', &bytes[guess.max(last)..end]) {
            let cut = guess.max(last) + i + 1;
            if cut < end {
                cuts.push(cut);
            }
        }
    }
    cuts.dedup();
    cuts.iter()
        .zip(cuts.iter().skip(1).chain([&end]))
        .map(|(&a, &b)| (a, b))
        .collect()
}

/// The records of element `e` in the whole lines `[a, b)`.
fn piece(bytes: &[u8], a: usize, b: usize, e: &Element, vertices: u64) -> Result<Body, Fail> {
    let mut out = Body::default();
    let mut list = IndexList::default();
    let mut start = a;
    for line in bytes[a..b].split_inclusive(|&c| c == b'\n') {
        let at = Location::Byte(start as u64);
        start += line.len();
        let mut xyz = [0.0f32; 3];
        record(line, e, &mut xyz, &mut list.items).map_err(|p| (at.clone(), p))?;
        let done = match e.role {
            Role::Vertex(_) => {
                out.positions.push(Vec3A::from(xyz));
                Ok(())
            }
            role => list.push(role, vertices, &mut out.corners),
        };
        done.map_err(|p| (at, p))?;
    }
    Ok(out)
}

/// Reads one record's line: the vertex coordinates into `xyz`, the index list into `items`.
fn record(
    line: &[u8],
    e: &Element,
    xyz: &mut [f32; 3],
    items: &mut Vec<f64>,
) -> Result<(), Problem> {
    let text = || String::from_utf8_lossy(line).trim().to_owned();
    let bad = |m: String| Problem::Malformed(format!("{m} ('{}')", text()));
    let mut toks = line
        .split(|c| c.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| std::str::from_utf8(t).unwrap_or("?"));
    let names = || {
        let n: Vec<&str> = e.properties.iter().map(|p| p.name.as_str()).collect();
        n.join(" ")
    };
    let mut next = || {
        toks.next().ok_or_else(|| {
            bad(format!(
                "too few values for a '{}' record ({})",
                e.name,
                names()
            ))
        })
    };
    let wanted = match e.role {
        Role::Faces(j) | Role::Strips(j) => Some(j),
        _ => None,
    };
    for (j, p) in e.properties.iter().enumerate() {
        match p.kind {
            Kind::Scalar(_) => {
                let tok = next()?;
                if let Role::Vertex(axes) = e.role
                    && let Some(k) = axes.iter().position(|&a| a == j)
                {
                    xyz[k] = match coordinate::parse(tok) {
                        Ok(x) => x,
                        Err(Bad::NonFinite) => return Err(Problem::NonFinite(text())),
                        Err(b) => return Err(bad(b.message(tok))),
                    };
                }
            }
            Kind::List { .. } => {
                let tok = next()?;
                let n: u64 = tok
                    .parse()
                    .map_err(|_| bad(format!("'{tok}' is not the length of list '{}'", p.name)))?;
                if wanted == Some(j) {
                    items.clear();
                }
                for _ in 0..n {
                    let tok = next()?;
                    if wanted == Some(j) {
                        let v: i64 = tok
                            .parse()
                            .map_err(|_| bad(format!("'{tok}' is not a vertex index")))?;
                        items.push(v as f64);
                    }
                }
            }
        }
    }
    if toks.next().is_some() {
        return Err(bad(format!(
            "more values than a '{}' record has ({})",
            e.name,
            names()
        )));
    }
    Ok(())
}
