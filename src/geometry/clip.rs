//! Clipping triangles to boxes (Sutherland–Hodgman), for the bounds of the part of a triangle
//! inside a kd-tree cell ("perfect splits"), and boxes to half-spaces (BSP cells).
//!
//! Every result is conservative: it contains the exact part of the triangle it stands for. The
//! clipped vertices carry rounding error (a few ulps per clip), so results are padded outward by
//! [`CLIP_PAD_ULPS`] ulps of their largest coordinate, then cut back to the box or bounds the exact
//! part is known to lie in.

use super::{Aabb, Triangle};
use glam::Vec3A;

/// Outward padding of a clipped result, in units of `f32::EPSILON` times its largest absolute
/// coordinate (six clips of about three roundings each, with a margin).
pub const CLIP_PAD_ULPS: f32 = 64.0;

/// Room for a triangle clipped by six planes (each clip adds at most one vertex in exact
/// arithmetic), with a margin for rounding.
const MAX_VERTS: usize = 16;

/// A small convex polygon on the stack. `overflow` is set when rounding produced more vertices
/// than fit; callers then fall back to the unclipped bounds.
#[derive(Clone, Copy)]
struct Polygon {
    v: [Vec3A; MAX_VERTS],
    n: usize,
    overflow: bool,
}

impl Polygon {
    fn triangle(tri: &Triangle) -> Polygon {
        let mut v = [Vec3A::ZERO; MAX_VERTS];
        v[..3].copy_from_slice(&tri.v);
        Polygon {
            v,
            n: 3,
            overflow: false,
        }
    }

    fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.v[..self.n])
    }

    /// Keeps the part where `dist(p) >= 0`; `dist` must be affine in `p`. `on_plane` moves a
    /// computed crossing exactly onto the plane when that can be done exactly (axis planes).
    fn clip(&self, dist: impl Fn(Vec3A) -> f32, on_plane: impl Fn(Vec3A) -> Vec3A) -> Polygon {
        let mut out = Polygon {
            v: [Vec3A::ZERO; MAX_VERTS],
            n: 0,
            overflow: self.overflow,
        };
        let mut push = |p: Vec3A| {
            if out.n < MAX_VERTS {
                out.v[out.n] = p;
                out.n += 1;
            } else {
                out.overflow = true;
            }
        };
        for i in 0..self.n {
            let a = self.v[i];
            let b = self.v[(i + 1) % self.n];
            let (da, db) = (dist(a), dist(b));
            if da >= 0.0 {
                push(a);
            }
            if (da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0) {
                let s = da / (da - db);
                push(on_plane(a + (b - a) * s));
            }
        }
        out
    }
}

/// Pads `b` outward by [`CLIP_PAD_ULPS`] ulps of its largest coordinate.
fn pad(b: Aabb) -> Aabb {
    if b.is_empty() {
        return b;
    }
    b.padded(CLIP_PAD_ULPS * f32::EPSILON)
}

/// Bounds of the part of `tri` inside the closed box `cell` (empty when they do not meet).
/// Conservative: contains the exact part; never larger than `tri.bounds() ∩ cell`.
pub fn triangle_clipped_bounds(tri: &Triangle, cell: &Aabb) -> Aabb {
    let limit = tri.bounds().intersection(*cell);
    if limit.is_empty() {
        return Aabb::EMPTY;
    }
    let mut poly = Polygon::triangle(tri);
    for axis in 0..3 {
        let lo = cell.min[axis];
        let hi = cell.max[axis];
        let snap = |plane: f32| {
            move |mut p: Vec3A| {
                p[axis] = plane;
                p
            }
        };
        poly = poly.clip(|p| p[axis] - lo, snap(lo));
        poly = poly.clip(|p| hi - p[axis], snap(hi));
        if poly.overflow {
            return limit;
        }
        if poly.n == 0 {
            return Aabb::EMPTY;
        }
    }
    pad(poly.bounds()).intersection(limit)
}

/// Bounds of the part of box `b` where `normal . p <= offset` (`below`) or `>= offset`
/// (otherwise): the box corners on that side and the crossings of its edges with the plane.
/// Conservative (padded like the triangle clip), never larger than `b`; empty when the box lies
/// entirely on the other side.
pub fn box_halfspace_bounds(b: &Aabb, normal: Vec3A, offset: f32, below: bool) -> Aabb {
    let corner = |i: usize| {
        Vec3A::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    };
    let sign = if below { -1.0 } else { 1.0 };
    let dist = |p: Vec3A| sign * (normal.dot(p) - offset);
    let mut out = Aabb::EMPTY;
    for i in 0..8 {
        let a = corner(i);
        let da = dist(a);
        if da >= 0.0 {
            out = out.grown(a);
        }
        // Edges to the corners that differ in one higher bit.
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                let c = corner(i | bit);
                let dc = dist(c);
                if (da < 0.0 && dc > 0.0) || (da > 0.0 && dc < 0.0) {
                    out = out.grown(a + (c - a) * (da / (da - dc)));
                }
            }
        }
    }
    pad(out).intersection(*b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Aabb {
        Aabb::new(Vec3A::ZERO, Vec3A::ONE)
    }

    fn contains(outer: &Aabb, inner: &Aabb) -> bool {
        outer.min.cmple(inner.min).all() && inner.max.cmple(outer.max).all()
    }

    #[test]
    fn big_triangle_is_cut_to_its_slice_of_the_box() {
        // The plane z = 0.5 through the whole box: the part inside is the square at z = 0.5.
        let big = Triangle::from_corners([-10.0, -10.0, 0.5], [10.0, -10.0, 0.5], [0.0, 20.0, 0.5]);
        let b = triangle_clipped_bounds(&big, &unit());
        assert_eq!(b.min, Vec3A::new(0.0, 0.0, 0.5));
        assert_eq!(b.max, Vec3A::new(1.0, 1.0, 0.5));
    }

    #[test]
    fn diagonal_triangle_is_tighter_than_box_overlap() {
        // Passes the box corner diagonally: its bounds overlap the box, the triangle only
        // touches a small corner region.
        let t = Triangle::from_corners([0.4, -0.5, 0.5], [2.0, 1.1, 0.5], [2.0, -0.5, 0.5]);
        let b = triangle_clipped_bounds(&t, &unit());
        let naive = t.bounds().intersection(unit());
        assert!(contains(&naive, &b));
        assert!(b.max.y < 0.2 && b.min.x > 0.85, "{b:?}");
        // The exact part is the corner region x in [0.9, 1], 0 <= y <= x - 0.9.
        assert!(b.contains(Vec3A::new(1.0, 0.05, 0.5)));
    }

    #[test]
    fn disjoint_and_touching() {
        let far = Triangle::new(
            Vec3A::splat(2.0),
            Vec3A::splat(3.0),
            Vec3A::new(2.0, 3.0, 2.0),
        );
        assert!(triangle_clipped_bounds(&far, &unit()).is_empty());
        // Touching the face x = 1 with one vertex: a point.
        let touch = Triangle::from_corners([1.0, 0.5, 0.5], [2.0, 0.5, 0.5], [2.0, 0.6, 0.5]);
        let b = triangle_clipped_bounds(&touch, &unit());
        assert!(b.contains(Vec3A::new(1.0, 0.5, 0.5)), "{b:?}");
    }

    #[test]
    fn box_cut_by_a_diagonal_plane() {
        // x + y <= 1 cuts the unit cube into a prism whose bounds are the whole cube; x + y <= 0.5
        // leaves the corner region x, y in [0, 0.5].
        let n = Vec3A::new(1.0, 1.0, 0.0).normalize();
        let b = box_halfspace_bounds(&unit(), n, n.dot(Vec3A::new(0.25, 0.25, 0.0)), true);
        assert!(
            b.max.x >= 0.5 && b.max.x < 0.51 && b.max.y < 0.51 && b.max.z == 1.0,
            "{b:?}"
        );
        let a = box_halfspace_bounds(&unit(), n, n.dot(Vec3A::new(0.25, 0.25, 0.0)), false);
        assert_eq!(a, unit());
        assert!(box_halfspace_bounds(&unit(), Vec3A::Z, 2.0, false).is_empty());
    }
}
