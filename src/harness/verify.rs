//! Hit verification: every index must return brute force's hits bit for bit.

use crate::geometry::{Hit, Ray, TriangleKernelKind};
use crate::index::{BuildError, IndexSpec, TraceIndex, build_index};
use crate::rays::ray_to_record;
use crate::scene::SceneGeometry;
use std::fmt;

/// One ray on which two indices disagree, with the ray's exact bits for replay
/// (`accelbench trace` on a `.rays` file holding this record).
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch {
    pub ray_index: usize,
    /// The protocol record `org, tnear, dir, tfar` as `f32` bit patterns.
    pub ray_bits: [u32; 8],
    pub query: &'static str,
    pub expected: Option<Hit>,
    pub got: Option<Hit>,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let show = |h: &Option<Hit>| match h {
            Some(h) if h.t.is_nan() => "occluded (any hit)".to_owned(),
            Some(h) => format!("prim {} t {:e} (0x{:08x})", h.prim, h.t, h.t.to_bits()),
            None => "miss".to_owned(),
        };
        let rec: Vec<String> = self
            .ray_bits
            .iter()
            .map(|b| format!("{:e}", f32::from_bits(*b)))
            .collect();
        let hex: Vec<String> = self.ray_bits.iter().map(|b| format!("{b:08x}")).collect();
        write!(
            f,
            "ray {} ({}): expected {}, got {}; ray record [{}] bits [{}]",
            self.ray_index,
            self.query,
            show(&self.expected),
            show(&self.got),
            rec.join(", "),
            hex.join(" ")
        )
    }
}

fn bits(ray: &Ray) -> [u32; 8] {
    ray_to_record(ray).map(f32::to_bits)
}

fn same(a: &Option<Hit>, b: &Option<Hit>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => a.bits_eq(b),
        (None, None) => true,
        _ => false,
    }
}

/// Compares closest hits ray by ray (bit for bit).
pub fn compare_closest(
    rays: &[Ray],
    expected: &[Option<Hit>],
    got: &[Option<Hit>],
) -> Vec<Mismatch> {
    rays.iter()
        .zip(expected.iter().zip(got))
        .enumerate()
        .filter(|(_, (_, (e, g)))| !same(e, g))
        .map(|(i, (r, (e, g)))| Mismatch {
            ray_index: i,
            ray_bits: bits(r),
            query: "closest",
            expected: *e,
            got: *g,
        })
        .collect()
}

/// Checks `index` against `reference` on `rays`: closest hits bit for bit, and any-hit equal to
/// "the reference found a closest hit".
pub fn compare_indices(
    reference: &dyn TraceIndex,
    index: &dyn TraceIndex,
    rays: &[Ray],
) -> Vec<Mismatch> {
    let mut expected = vec![None; rays.len()];
    reference.closest_hits(rays, &mut expected);
    compare_with_expected(index, rays, &expected)
}

/// Checks `index` against the reference's closest hits `expected` on `rays`: closest hits bit
/// for bit, and any-hit equal to "the reference found a closest hit".
pub fn compare_with_expected(
    index: &dyn TraceIndex,
    rays: &[Ray],
    expected: &[Option<Hit>],
) -> Vec<Mismatch> {
    let mut got = vec![None; rays.len()];
    index.closest_hits(rays, &mut got);
    let mut out = compare_closest(rays, expected, &got);
    let mut any = vec![false; rays.len()];
    index.any_hits(rays, &mut any);
    for (i, (r, (e, a))) in rays.iter().zip(expected.iter().zip(&any)).enumerate() {
        if e.is_some() != *a {
            out.push(Mismatch {
                ray_index: i,
                ray_bits: bits(r),
                query: "any",
                expected: *e,
                got: a.then_some(Hit {
                    t: f32::NAN,
                    prim: u32::MAX,
                }),
            });
        }
    }
    out
}

/// Builds `spec` and brute force over `geom` and compares them on `rays`.
pub fn verify_against_brute(
    spec: &IndexSpec,
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
    rays: &[Ray],
) -> Result<Vec<Mismatch>, BuildError> {
    let brute = build_index(&IndexSpec::named("brute"), geom, kernel)?;
    let index = build_index(spec, geom, kernel)?;
    Ok(compare_indices(brute.as_ref(), index.as_ref(), rays))
}
