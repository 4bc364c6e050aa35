//! Structured scenes: a terrain height field, a closed room, a flat plane, and teapot in a
//! stadium (a small dense object in a huge sparse scene).

use super::icosphere::icosphere;
use crate::geometry::Triangle;
use glam::Vec3A;

/// A `k x k`-quad grid over `[0,1]^2` (in x and z) with heights `h(x, z)`, `2 k^2` triangles.
fn height_field(k: usize, h: impl Fn(f32, f32) -> f32) -> Vec<Triangle> {
    let k = k.max(1);
    let p = |i: usize, j: usize| {
        let (x, z) = (i as f32 / k as f32, j as f32 / k as f32);
        Vec3A::new(x, h(x, z), z)
    };
    let mut tris = Vec::with_capacity(2 * k * k);
    push_grid(&mut tris, k, p, true);
    tris
}

/// Appends the `k x k` quads of the grid of points `p(i, j)`, `0 <= i, j <= k`, row by row, two
/// triangles each: with `a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)`, the
/// triangles `a b c` and `a c d`, or `a c b` and `a d c` (the other winding) when `flip`.
fn push_grid(tris: &mut Vec<Triangle>, k: usize, p: impl Fn(usize, usize) -> Vec3A, flip: bool) {
    for j in 0..k {
        for i in 0..k {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            for (u, v) in [(b, c), (c, d)] {
                let (u, v) = if flip { (v, u) } else { (u, v) };
                tris.push(Triangle::new(a, u, v));
            }
        }
    }
}

/// Quads per side so that `2 k^2` is about `n`.
fn side_for(n: usize) -> usize {
    ((n as f64 / 2.0).sqrt().round() as usize).max(1)
}

/// A rolling terrain of about `n` triangles over the unit square (sums of sines, height up to
/// 0.15).
pub fn terrain(n: usize) -> Vec<Triangle> {
    height_field(side_for(n), |x, z| {
        0.06 * (7.0 * x).sin() * (5.0 * z).cos()
            + 0.04 * (17.0 * x + 3.0).sin() * (13.0 * z + 1.0).sin()
            + 0.02 * (41.0 * x * z).cos()
            + 0.05
    })
}

/// A flat (zero-thickness) plane `y = 0` of about `n` triangles over the unit square.
pub fn flat(n: usize) -> Vec<Triangle> {
    height_field(side_for(n), |_, _| 0.0)
}

/// The six walls of the closed box `[0,1]^3`, facing inward, about `n` triangles in all.
pub fn room(n: usize) -> Vec<Triangle> {
    let k = (((n as f64) / 12.0).sqrt().round() as usize).max(1);
    let mut tris = Vec::with_capacity(12 * k * k);
    let s = 1.0 / k as f32;
    // Each wall: (origin, u axis, v axis) with u x v pointing into the room.
    let walls = [
        (Vec3A::ZERO, Vec3A::X, Vec3A::Z), // floor y=0, normal +y
        (Vec3A::Y, Vec3A::Z, Vec3A::X),    // ceiling y=1, normal -y
        (Vec3A::ZERO, Vec3A::Y, Vec3A::X), // z=0, normal +z
        (Vec3A::Z, Vec3A::X, Vec3A::Y),    // z=1, normal -z
        (Vec3A::ZERO, Vec3A::Z, Vec3A::Y), // x=0, normal +x
        (Vec3A::X, Vec3A::Y, Vec3A::Z),    // x=1, normal -x
    ];
    for (o, u, v) in walls {
        let p = |i: usize, j: usize| o + u * (i as f32 * s) + v * (j as f32 * s);
        push_grid(&mut tris, k, p, false);
    }
    tris
}

/// Wall panels of the stadium ring.
const STADIUM_PANELS: usize = 64;

/// Triangles of the stadium itself: a ground quad and the wall panels, two triangles each.
const STADIUM_TRIANGLES: usize = 2 + 2 * STADIUM_PANELS;

/// Teapot in a stadium: a dense icosphere of radius `0.001` (the icosphere closest to the `n`
/// triangles left after the stadium's [`STADIUM_TRIANGLES`]) at the centre of a stadium 1000
/// times larger (a ground plane and a ring of [`STADIUM_PANELS`] large wall panels).
/// Uniform grids fail here: cells sized for the stadium put the whole object in one cell.
pub fn teapot_in_stadium(n: usize) -> Vec<Triangle> {
    let level = level_for(n.saturating_sub(STADIUM_TRIANGLES));
    let mut tris: Vec<Triangle> = icosphere(level)
        .into_iter()
        .map(|t| Triangle::new(t.v[0] * 0.001, t.v[1] * 0.001, t.v[2] * 0.001))
        .collect();
    let r = 1.0f32;
    let g = -0.0015f32;
    tris.push(Triangle::from_corners([-r, g, -r], [r, g, r], [r, g, -r]));
    tris.push(Triangle::from_corners([-r, g, -r], [-r, g, r], [r, g, r]));
    let panels = STADIUM_PANELS;
    for i in 0..panels {
        let a0 = i as f32 / panels as f32 * std::f32::consts::TAU;
        let a1 = (i + 1) as f32 / panels as f32 * std::f32::consts::TAU;
        let p0 = Vec3A::new(a0.cos(), g, a0.sin()) * Vec3A::new(r, 1.0, r);
        let p1 = Vec3A::new(a1.cos(), g, a1.sin()) * Vec3A::new(r, 1.0, r);
        let up = Vec3A::new(0.0, 0.3, 0.0);
        tris.push(Triangle::new(p0, p1, p1 + up));
        tris.push(Triangle::new(p0, p1 + up, p0 + up));
    }
    tris
}

/// The icosphere subdivision level whose `20 * 4^level` triangles is closest to `n` (at least
/// 0, at most 11).
pub fn level_for(n: usize) -> u32 {
    let mut level = 0;
    while level < 11 && 20usize << (2 * (level + 1)) <= n.max(20) * 2 {
        level += 1;
    }
    level
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_track_n() {
        for n in [1000usize, 100_000] {
            for (name, len) in [
                ("terrain", terrain(n).len()),
                ("flat", flat(n).len()),
                ("room", room(n).len()),
                ("stadium", teapot_in_stadium(n).len()),
            ] {
                assert!(len > n / 3 && len < n * 3, "{name}: {len} for {n}");
            }
        }
        assert_eq!(level_for(20), 0);
        assert_eq!(level_for(5120), 4);
    }

    /// The size arithmetic of the structured generators, without generating: within a factor
    /// of 2 of `n` from 1k to 16M.
    #[test]
    fn size_arithmetic_tracks_n_up_to_16m() {
        let mut n = 1000usize;
        while n <= 16_000_000 {
            let within = |len: usize| len >= n / 2 && len <= n * 2;
            let ico = 20usize << (2 * level_for(n));
            assert!(within(ico), "icosphere level {} for {n}", level_for(n));
            let k = side_for(n);
            assert!(within(2 * k * k), "height field side {k} for {n}");
            let teapot = 20usize << (2 * level_for(n - STADIUM_TRIANGLES));
            let stadium = teapot + STADIUM_TRIANGLES;
            if n < 100_000 {
                assert_eq!(teapot_in_stadium(n).len(), stadium);
            }
            assert!(within(stadium), "stadium {stadium} for {n}");
            n = n * 3 / 2 + 1;
        }
    }

    #[test]
    fn flat_is_flat_and_room_closed_box() {
        assert!(flat(200).iter().all(|t| t.v.iter().all(|v| v.y == 0.0)));
        let b = room(100)
            .iter()
            .fold(crate::geometry::Aabb::EMPTY, |b, t| b.union(t.bounds()));
        assert_eq!((b.min, b.max), (Vec3A::ZERO, Vec3A::ONE));
    }
}
