//! The exact kernel's lane form: the filtered fast path of [`super::intersect_line`] on four
//! triangles at once, in `f64`, every lane doing the scalar path's operations in the same
//! order (the same `glam` `DVec3` cross and dot product trees, no fused multiply-add), so a
//! decided lane's `t` is the scalar kernel's bit for bit.
//!
//! A lane is decided when all three edge functions pass the static filter (`|U|, |V|, |W| > E`):
//! mixed signs are a miss, equal signs a hit at the rounded Cramer `t` when it is finite and in
//! `[ray.t_min, ray.t_max]`. Every other lane (a sign the filter cannot certify, which the
//! scalar kernel settles by its exact fallback and counts; a non-finite `t`; non-finite inputs,
//! which make the filter fail) is left to the scalar kernel.

use super::filter::FILTER;
use crate::geometry::Ray;
use crate::geometry::triangle::lanes::{LaneHits, TriangleLanes};

/// Four `f64` lanes.
type L = [f64; 4];

#[inline(always)]
fn lanes(f: impl FnMut(usize) -> f64) -> L {
    std::array::from_fn(f)
}

/// `corner - origin` per axis, in `f64` (as `d64(v) - o`).
#[inline(always)]
fn rel(t: &TriangleLanes, corner: usize, o: [f64; 3]) -> [L; 3] {
    [0, 1, 2].map(|k| lanes(|i| t.v[corner][k][i] as f64 - o[k]))
}

/// `d x p` per lane, `glam`'s `DVec3::cross` term for term.
#[inline(always)]
fn cross(d: [f64; 3], p: &[L; 3]) -> [L; 3] {
    [
        lanes(|i| d[1] * p[2][i] - p[1][i] * d[2]),
        lanes(|i| d[2] * p[0][i] - p[2][i] * d[0]),
        lanes(|i| d[0] * p[1][i] - p[0][i] * d[1]),
    ]
}

/// `p . q` per lane, `glam`'s `DVec3::dot` term for term.
#[inline(always)]
fn dot(p: &[L; 3], q: &[L; 3]) -> L {
    lanes(|i| (p[0][i] * q[0][i]) + (p[1][i] * q[1][i]) + (p[2][i] * q[2][i]))
}

/// The larger of two finite values (the order of a max over finite values does not matter).
#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// The lane form (see the module doc and [`crate::geometry::triangle::lanes`]): one AVX pass
/// ([`super::lanes_avx`]) when built with AVX, else [`portable`].
#[inline(always)]
pub fn intersect_lanes(tris: &TriangleLanes, ray: &Ray) -> LaneHits {
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    {
        super::lanes_avx::intersect_lanes(tris, ray)
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
    {
        portable(tris, ray)
    }
}

/// The lane form in plain Rust, a branch per lane (targets without AVX; with AVX the tests
/// compare the AVX pass with it).
#[cfg_attr(all(target_arch = "x86_64", target_feature = "avx"), allow(dead_code))]
#[inline(always)]
pub fn portable(tris: &TriangleLanes, ray: &Ray) -> LaneHits {
    let o = [0, 1, 2].map(|k| ray.origin[k] as f64);
    let d = [0, 1, 2].map(|k| ray.dir[k] as f64);
    let (a, b, c) = (rel(tris, 0, o), rel(tris, 1, o), rel(tris, 2, o));
    let (da, db, dc) = (cross(d, &a), cross(d, &b), cross(d, &c));
    let u = dot(&db, &c);
    let v = dot(&dc, &a);
    let w = dot(&da, &b);
    let d_sum = d[0].abs() + d[1].abs() + d[2].abs();
    let m = lanes(|i| {
        let axis = |k: usize| max(max(a[k][i].abs(), b[k][i].abs()), c[k][i].abs());
        max(axis(0), max(axis(1), axis(2)))
    });
    let e = lanes(|i| FILTER * d_sum * m[i] * m[i]);
    let k = ray.shear.kz;
    let t: [f32; 4] = std::array::from_fn(|i| {
        ((u[i] * a[k][i] + v[i] * b[k][i] + w[i] * c[k][i]) / ((u[i] + v[i] + w[i]) * d[k])) as f32
    });
    let mut out = LaneHits {
        hit: 0,
        scalar: 0,
        t: [0.0; 4],
    };
    for i in 0..4 {
        let (u, v, w) = (u[i], v[i], w[i]);
        if !(u.abs() > e[i] && v.abs() > e[i] && w.abs() > e[i]) {
            out.scalar |= 1 << i;
            continue;
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            continue;
        }
        let ti = t[i];
        if !ti.is_finite() {
            out.scalar |= 1 << i;
        } else if ti >= ray.t_min && ti <= ray.t_max {
            out.hit |= 1 << i;
            out.t[i] = ti;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle;
    use crate::geometry::triangle::Exact;
    use crate::geometry::triangle::lane_check::{check_decided_lanes, ray_target};
    use glam::{Vec3, Vec3A};

    /// Decided lanes equal the scalar kernel bit for bit, on random triangles and rays aimed at
    /// their corners and edges (where the filter hands lanes to the scalar kernel) and beside
    /// them, with rays far from the triangles too; both outcomes, both paths and blocks of
    /// misses only occur.
    #[test]
    fn decided_lanes_equal_the_scalar_kernel() {
        let aim = |point: &mut dyn FnMut(f32) -> Vec3A, tris: &[Triangle; 4], scale, round| {
            let o = point(scale * 8.0);
            let target = ray_target(tris, round, 0);
            Ray::new(o.into(), Vec3::from(target - o), 0.0, f32::INFINITY).ok()
        };
        check_decided_lanes::<Exact>(
            0x1234_5678_9abc_def1,
            &[1.0, 1e3, 1e-3],
            aim,
            intersect_lanes,
        );
    }

    /// The AVX pass answers exactly what the portable form answers (hits, undecided lanes and
    /// `t` bits), including rays in a triangle's plane, through corners and from far away.
    #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
    #[test]
    fn the_avx_pass_equals_the_portable_form() {
        use crate::geometry::triangle::lane_check::{points, random_block, ray_origin};
        let mut point = points(0x0bad_cafe_f00d_d00d);
        let mut seen = LaneHits {
            hit: 0,
            scalar: 0,
            t: [0.0; 4],
        };
        for round in 0..40_000 {
            let scale = [1.0, 1e3, 1e-3, 1e6][round % 4];
            let (tris, lanes) = random_block(&mut point, scale, round);
            let o = ray_origin(&mut point, &tris, scale, round);
            let target = match round % 3 {
                0 => tris[0].v[round % 3],
                _ => tris[0].v[0] * 0.25 + tris[0].v[1] * 0.25 + tris[0].v[2] * 0.5,
            };
            let t_min = [0.0, -1.0, 0.5][round % 3];
            let Ok(ray) = Ray::new(o.into(), Vec3::from(target - o), t_min, 1.5) else {
                continue;
            };
            let got = intersect_lanes(&lanes, &ray);
            let want = portable(&lanes, &ray);
            assert_eq!(got.hit, want.hit, "{ray:?} {lanes:?}");
            assert_eq!(got.scalar, want.scalar, "{ray:?} {lanes:?}");
            assert_eq!(got.t.map(f32::to_bits), want.t.map(f32::to_bits), "{ray:?}");
            seen.hit |= want.hit;
            seen.scalar |= want.scalar;
        }
        assert_eq!((seen.hit, seen.scalar), (0b1111, 0b1111));
    }
}
