//! A city of about `n` triangles: blocks of building lots over the unit square, streets between
//! the blocks, a ground plane under everything and open sky above. Each building is one of two
//! templates (a box, or a box with a set-back tower on top) placed, scaled and given a height by
//! its lot's own seed, and flattened to world-space triangles; rays along the streets and over
//! the roofs travel far before they hit anything, if they do.
//!
//! Lots are generated in parallel, each from its own seed (the scene seed and the lot's index),
//! so the scene depends only on `n` and `seed`, not on the thread count, and its triangles come
//! in lot order.

use crate::geometry::Triangle;
use crate::random::SplitMix64;
use glam::Vec3A;
use rayon::prelude::*;

/// Building lots along one side of a block.
const LOTS_PER_BLOCK: usize = 4;
/// A street's width against a lot's.
const STREET: f32 = 0.6;
/// Triangles of a box without its floor (four walls and a roof, two triangles each).
const BOX_TRIANGLES: usize = 10;
/// Mean triangles per building: half are boxes, half boxes with a tower.
const MEAN_BUILDING_TRIANGLES: f64 = 1.5 * BOX_TRIANGLES as f64;

/// The city's eye: at a corner of the city, a little above the tallest common roofs, looking
/// across it toward the far corner and slightly up, so that much of the image is sky and the
/// street canyons.
pub const CITY_EYE: [f32; 3] = [-0.05, 0.08, -0.05];
/// Where the city's eye looks.
pub const CITY_LOOK_AT: [f32; 3] = [1.0, 0.12, 1.0];

/// Lots per side of the city for about `n` triangles.
fn lots_per_side(n: usize) -> usize {
    let buildings = (n.saturating_sub(2) as f64 / MEAN_BUILDING_TRIANGLES).max(1.0);
    (buildings.sqrt().ceil() as usize).max(1)
}

/// The triangles of about `n` (at least 12) for the seed (see the module doc).
pub fn city(n: usize, seed: u64) -> Vec<Triangle> {
    let lots = lots_per_side(n);
    let blocks = lots.div_ceil(LOTS_PER_BLOCK);
    // One lot is 1 unit wide, a street STREET units; the city is scaled into [0, 1]^2.
    let width = lots as f32 + (blocks - 1) as f32 * STREET;
    let scale = 1.0 / width;
    let at = |i: usize| (i as f32 + (i / LOTS_PER_BLOCK) as f32 * STREET) * scale;
    let mut tris: Vec<Triangle> = (0..lots * lots)
        .into_par_iter()
        .flat_map_iter(|lot| {
            let mut rng = SplitMix64::new(seed ^ (lot as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
            let (x, z) = (at(lot % lots), at(lot / lots));
            building(&mut rng, Vec3A::new(x, 0.0, z), scale)
        })
        .collect();
    let (a, b, c, d) = (
        Vec3A::new(-0.1, 0.0, -0.1),
        Vec3A::new(1.1, 0.0, -0.1),
        Vec3A::new(1.1, 0.0, 1.1),
        Vec3A::new(-0.1, 0.0, 1.1),
    );
    tris.push(Triangle::new(a, c, b));
    tris.push(Triangle::new(a, d, c));
    tris
}

/// One building on the lot whose corner is `corner` and whose side is `lot`: a box inset in the
/// lot, mostly low and now and then a tower (heights from a long-tailed distribution), half of
/// them with a narrower box on top.
fn building(rng: &mut SplitMix64, corner: Vec3A, lot: f32) -> Vec<Triangle> {
    let mut unit = || rng.next_unit() as f32;
    let inset = lot * (0.05 + 0.1 * unit());
    let height = lot * (0.5 + 1.5 * unit()) / (0.08 + unit()).sqrt();
    let lo = corner + Vec3A::new(inset, 0.0, inset);
    let hi = corner + Vec3A::new(lot - inset, height, lot - inset);
    let mut tris = Vec::with_capacity(2 * BOX_TRIANGLES);
    push_box(&mut tris, lo, hi);
    if unit() < 0.5 {
        let step = (hi - lo) * 0.25;
        let top = lo + Vec3A::new(step.x, height, step.z);
        let tower = Vec3A::new(hi.x - step.x, height * (1.3 + unit()), hi.z - step.z);
        push_box(&mut tris, top, tower);
    }
    tris
}

/// The box `[lo, hi]` without its floor: four walls and a roof, two triangles each, facing out.
fn push_box(tris: &mut Vec<Triangle>, lo: Vec3A, hi: Vec3A) {
    let p = |x: bool, y: bool, z: bool| {
        Vec3A::new(
            if x { hi.x } else { lo.x },
            if y { hi.y } else { lo.y },
            if z { hi.z } else { lo.z },
        )
    };
    // Each face as four corners, counter-clockwise seen from outside.
    let faces = [
        [
            p(false, false, false),
            p(true, false, false),
            p(true, true, false),
            p(false, true, false),
        ],
        [
            p(true, false, true),
            p(false, false, true),
            p(false, true, true),
            p(true, true, true),
        ],
        [
            p(false, false, true),
            p(false, false, false),
            p(false, true, false),
            p(false, true, true),
        ],
        [
            p(true, false, false),
            p(true, false, true),
            p(true, true, true),
            p(true, true, false),
        ],
        [
            p(false, true, false),
            p(true, true, false),
            p(true, true, true),
            p(false, true, true),
        ],
    ];
    for [a, b, c, d] in faces {
        tris.push(Triangle::new(a, b, c));
        tris.push(Triangle::new(a, c, d));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within a factor of 2 of `n` from 100 triangles to 1M, every building on the ground
    /// inside the unit square, the same scene for the same seed and another for another seed.
    #[test]
    fn a_city_has_about_n_triangles_on_the_ground() {
        for n in [100, 10_000, 1_000_000] {
            let c = city(n, 3);
            assert!(
                c.len() >= n / 2 && c.len() <= 2 * n,
                "{} for n = {n}",
                c.len()
            );
            let buildings = &c[..c.len() - 2];
            assert!(buildings.iter().flat_map(|t| t.v).all(|v| {
                (0.0..=1.0).contains(&v.x) && (0.0..=1.0).contains(&v.z) && v.y >= 0.0
            }));
        }
        let (a, b) = (city(5000, 1), city(5000, 1));
        assert!(a.iter().zip(&b).all(|(s, t)| s.v == t.v));
        let other = city(5000, 2);
        assert!(a.iter().zip(&other).any(|(s, t)| s.v != t.v));
    }

    /// Streets: a line across the city between two blocks meets no building.
    #[test]
    fn streets_run_between_the_blocks() {
        let c = city(20_000, 1);
        let lots = lots_per_side(20_000);
        assert!(
            lots > LOTS_PER_BLOCK,
            "{lots} lots per side: one block only"
        );
        let width = lots as f32 + (lots.div_ceil(LOTS_PER_BLOCK) - 1) as f32 * STREET;
        let street = (LOTS_PER_BLOCK as f32 + STREET / 2.0) / width;
        let crossing = |t: &Triangle| {
            let (lo, hi) =
                t.v.iter()
                    .fold((f32::MAX, f32::MIN), |(l, h), v| (l.min(v.x), h.max(v.x)));
            lo < street && street < hi
        };
        assert_eq!(c[..c.len() - 2].iter().filter(|t| crossing(t)).count(), 0);
    }
}
