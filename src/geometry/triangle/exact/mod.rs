//! The exact ray–triangle kernel: the hit/miss decision is exact for the ray's line (the `f32`
//! origin `o` and direction `d`, infinitely precise) against the closed triangle of the `f32`
//! corners, edges and vertices included. A ray through a shared edge or vertex hits every
//! triangle that contains it, so the kernel is watertight by construction.
//!
//! With `A, B, C` the corners relative to `o`, the edge functions are `U = d.(B x C)`,
//! `V = d.(C x A)`, `W = d.(A x B)` (the same as the accuracy reference's); the line meets the
//! triangle iff they share a sign and are not all zero (a ray in the triangle's plane misses).
//!
//! **Filter.** Each edge function is evaluated in `f64` as `(d x B).C` from the rounded
//! differences `B = fl(v - o)`, the same operation tree as the leading determinant of Shewchuk's
//! `orient3d` with one row (`d`) exact. Its error is at most `(7 eps + 56 eps^2) P` with
//! `eps = 2^-53` and `P` the permanent `sum |d_i| (|B_j||C_k| + |B_k||C_j|)` (Shewchuk 1997,
//! the bound `o3derrboundA`). Since `P <= 2 |d|_1 m^2` with `m` the largest coordinate of
//! `|A|, |B|, |C|`, and the bound's own three roundings cost less than the slack, the static
//! bound is
//!
//! `E = 2^-49 |d|_1 m^2` (computed in `f64`),
//!
//! shared by the three edge functions: `|U| > E` certifies the sign of `U`. Products of `f32`
//! inputs cannot overflow or underflow in `f64` (they lie within `2^-447 .. 2^385`).
//!
//! **Fallback.** An undecided sign is computed exactly: by multilinearity,
//! `d.(B x C) = det[d; v1; v2] - det[d; v1; o] - det[d; o; v2]`, 18 products of three `f32`
//! values, each exactly two `f64` (the product of two `f32` is exact in `f64`), summed by an
//! exact expansion ([`expansion::ExactSum`]). It is exact for any finite inputs; non-finite
//! inputs miss.
//!
//! **Distance.** `t = (U A_k + V B_k + W C_k) / (d_k (U + V + W))` in `f64` (Cramer's rule along
//! the ray's dominant axis `k`), with every fallback-decided edge function replaced by zero when
//! its `f64` value is zero by the exact sign or disagrees with it, then rounded to `f32`. When
//! even that is undefined (the line lies in the triangle's plane to within `f64` rounding) `t`
//! is the entry of the triangle's box. [`crate::scene::Geometry`] clamps it into the box.

mod filter;
mod lanes;
#[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
mod lanes_avx;

use super::lanes::{LaneHits, TriangleLanes};
use super::{Triangle, TriangleKernel, in_interval};
use crate::geometry::Ray;
use crate::geometry::expansion::ExactSum;
use filter::FILTER;
use glam::{DVec3, Vec3A};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

#[derive(Debug, Clone, Copy, Default)]
pub struct Exact;

thread_local! {
    /// Edge functions of this thread whose sign the filter could not decide (counted only on
    /// the rare fallback path; read with [`fallback_count`]).
    static FALLBACKS: Cell<u64> = const { Cell::new(0) };
}

/// Edge functions of all threads that needed the exact fallback (the suite reads it around a
/// pass, when nothing else traces).
static FALLBACKS_TOTAL: AtomicU64 = AtomicU64::new(0);

/// How many edge functions needed the exact fallback, over all threads, since the process
/// started. The difference of two readings around a pass is that pass's count when no other
/// pass ran meanwhile.
pub fn fallback_total() -> u64 {
    FALLBACKS_TOTAL.load(Ordering::Relaxed)
}

/// How many edge functions needed the exact fallback on the calling thread since it started.
/// The difference of two readings around a pass on one thread is that pass's count.
pub fn fallback_count() -> u64 {
    FALLBACKS.with(Cell::get)
}

impl TriangleKernel for Exact {
    const NAME: &'static str = "exact";

    #[inline]
    fn intersect(tri: &Triangle, ray: &Ray, t_max: f32) -> Option<f32> {
        let t = intersect_line(tri, ray)?;
        in_interval(t, ray, t_max)
    }

    #[inline(always)]
    fn intersect_lanes(tris: &TriangleLanes, ray: &Ray) -> LaneHits {
        lanes::intersect_lanes(tris, ray)
    }
}

fn d64(v: Vec3A) -> DVec3 {
    DVec3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// The exact decision and the rounded `t` (before the interval test).
#[inline(always)]
fn intersect_line(tri: &Triangle, ray: &Ray) -> Option<f32> {
    let o = d64(ray.origin);
    let d = d64(ray.dir);
    let a = d64(tri.v[0]) - o;
    let b = d64(tri.v[1]) - o;
    let c = d64(tri.v[2]) - o;
    let (da, db, dc) = (d.cross(a), d.cross(b), d.cross(c));
    let mut u = db.dot(c);
    let mut v = dc.dot(a);
    let mut w = da.dot(b);
    let m = a.abs().max(b.abs()).max(c.abs()).max_element();
    let e = FILTER * d.abs().element_sum() * m * m;
    if !(u.abs() > e && v.abs() > e && w.abs() > e) {
        let [su, sv, sw] = [(&mut u, 1, 2), (&mut v, 2, 0), (&mut w, 0, 1)].map(|(x, i, j)| {
            if x.abs() > e {
                return Some(x.signum() as i32);
            }
            let s = exact_edge_sign(tri.v[i], tri.v[j], ray)?;
            if (*x > 0.0) as i32 - (*x < 0.0) as i32 != s {
                *x = 0.0;
            }
            Some(s)
        });
        let (su, sv, sw) = (su?, sv?, sw?);
        if (su < 0 || sv < 0 || sw < 0) && (su > 0 || sv > 0 || sw > 0) {
            return None;
        }
        if su == 0 && sv == 0 && sw == 0 {
            return None;
        }
    } else if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let k = ray.shear.kz;
    let t = ((u * a[k] + v * b[k] + w * c[k]) / ((u + v + w) * d[k])) as f32;
    if t.is_finite() {
        return Some(t);
    }
    tri.bounds()
        .ray_interval(ray, f32::NEG_INFINITY, f32::INFINITY)
        .map(|(enter, _)| enter)
}

/// The exact sign of the edge function `d.((p - o) x (q - o))` for the ray's `o, d`, or `None`
/// for non-finite inputs. Counts one fallback.
#[cold]
#[inline(never)]
pub fn exact_edge_sign(p: Vec3A, q: Vec3A, ray: &Ray) -> Option<i32> {
    FALLBACKS.with(|n| n.set(n.get() + 1));
    FALLBACKS_TOTAL.fetch_add(1, Ordering::Relaxed);
    let (o, d) = (ray.origin, ray.dir);
    if !(p.is_finite() && q.is_finite() && o.is_finite() && d.is_finite()) {
        return None;
    }
    let mut sum = ExactSum::default();
    // det[d; p; q] - det[d; p; o] - det[d; o; q] = det[d; p; q] + det[d; o; p] + det[d; q; o].
    for (y, z) in [(p, q), (o, p), (q, o)] {
        add_det(&mut sum, d, y, z);
    }
    Some(sum.sign())
}

/// Adds `det[x; y; z]` (rows) exactly: six products of three `f32` values.
fn add_det(sum: &mut ExactSum, x: Vec3A, y: Vec3A, z: Vec3A) {
    for (i, j, k) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
        let (xi, yj, zk, yk, zj) = (
            x[i] as f64,
            y[j] as f64,
            z[k] as f64,
            y[k] as f64,
            z[j] as f64,
        );
        sum.add_product3(xi, yj, zk);
        sum.add_product3(-xi, yk, zj);
    }
}

#[cfg(test)]
mod tests;
