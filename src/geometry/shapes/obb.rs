//! Oriented boxes and their two kernels: the slab method in the box's frame, and the course's
//! "intersect the three front-facing planes, return the closest".

use super::ShapeError;
use super::hit_support::{checked_frame, first_hit, padded_bounds};
use crate::geometry::aabb_kernel::slab_first_hit;
use crate::geometry::overlap::OVERLAP_PAD;
use crate::geometry::real::Real;
use crate::geometry::{Aabb, Ray};
use glam::{Mat3A, Vec3A};

/// A box `center + axes * l` for local points `l` in `[-half, half]` (closed).
///
/// Invariants: finite centre, half-extents finite and `> 0`, `axes` orthonormal (columns are the
/// box's local x, y, z in world space).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    center: Vec3A,
    half: Vec3A,
    axes: Mat3A,
    /// `axes^T`: world offsets to local coordinates.
    to_local: Mat3A,
    /// Cached [`Self::bounds`] (read on every kernel call by the `Geometry` contract).
    bounds: Aabb,
}

impl Obb {
    pub fn new(center: Vec3A, half_extents: Vec3A, axes: Mat3A) -> Result<Obb, ShapeError> {
        let names = ["box center", "box half-extent", "box axes"];
        let axes = checked_frame(center, half_extents, axes, names)?;
        Ok(Obb {
            center,
            half: half_extents,
            axes,
            to_local: axes.transpose(),
            bounds: padded_bounds(center, abs(axes) * half_extents),
        })
    }

    pub fn center(&self) -> Vec3A {
        self.center
    }

    pub fn half_extents(&self) -> Vec3A {
        self.half
    }

    pub fn axes(&self) -> Mat3A {
        self.axes
    }

    /// World half-extent per axis: `sum_j |axes_ij| half_j`.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The ray's origin and direction in the box frame (`t` is unchanged: a rotation is linear).
    #[inline(always)]
    fn local_ray(&self, ray: &Ray) -> (Vec3A, Vec3A) {
        (
            self.to_local * (ray.origin - self.center),
            self.to_local * ray.dir,
        )
    }

    /// Outward unit normal of the face nearest to `p` (relative to the half-extents).
    pub fn normal_at(&self, p: Vec3A) -> Vec3A {
        let l = self.to_local * (p - self.center);
        let r = l.abs() / self.half;
        let i = if r.x >= r.y && r.x >= r.z {
            0
        } else if r.y >= r.z {
            1
        } else {
            2
        };
        self.axes.col(i) * if l[i] < 0.0 { -1.0 } else { 1.0 }
    }

    /// Separating-axis test against the padded cell (Gottschalk et al. 1996): the cell's three
    /// axes, the box's three and their nine cross products; exact up to the padding, with a few
    /// ulps of slack on each projection.
    pub fn overlaps_box(&self, cell: &Aabb) -> bool {
        let cell = cell.padded(OVERLAP_PAD);
        let t = self.center - cell.center();
        let hc = cell.extent() * 0.5;
        let separated = |axis: Vec3A| -> bool {
            let dist = t.dot(axis).abs();
            let rc = hc.dot(axis.abs());
            let rb = (self.to_local * axis).abs().dot(self.half);
            let slack = 8.0 * f32::EPSILON * (dist + rc + rb + t.abs().dot(axis.abs()));
            dist > rc + rb + slack
        };
        let cell_axes = [Vec3A::X, Vec3A::Y, Vec3A::Z];
        let box_axes = [self.axes.x_axis, self.axes.y_axis, self.axes.z_axis];
        if cell_axes.iter().chain(&box_axes).any(|&a| separated(a)) {
            return false;
        }
        !cell_axes
            .iter()
            .any(|c| box_axes.iter().any(|b| separated(c.cross(*b))))
    }
}

fn abs(m: Mat3A) -> Mat3A {
    Mat3A::from_cols(m.x_axis.abs(), m.y_axis.abs(), m.z_axis.abs())
}

/// Slab method in the box frame: entry distance, or exit when the ray starts inside.
#[inline]
pub fn intersect_slabs(b: &Obb, ray: &Ray, t_max: f32) -> Option<f32> {
    let (o, d) = b.local_ray(ray);
    slab_first_hit(-b.half, b.half, o, Vec3A::ONE / d, ray.t_min, t_max)
}

/// The crossing of the local ray `o + t d` (one axis) with that axis's face plane `±h` that faces
/// the ray (the one behind it if `back`), in the ray's precision; `None` when `d = 0`.
#[inline(always)]
pub fn face_plane_t<S: Real>(h: S, o: S, d: S, back: bool) -> Option<S> {
    if d == S::ZERO {
        return None;
    }
    let plus_face = (d < S::ZERO) != back;
    Some(((if plus_face { h } else { -h }) - o) / d)
}

/// The course's method: intersect the three front-facing face planes (outward normal against
/// the ray) and keep the closest crossing that lands on its face; a ray starting inside sees its
/// front faces behind it, so then the three back faces give the exit.
#[inline]
pub fn intersect_front_planes(b: &Obb, ray: &Ray, t_max: f32) -> Option<f32> {
    let (o, d) = b.local_ray(ray);
    let h = b.half;
    for back in [false, true] {
        let mut cand = [f32::NAN; 3];
        for (i, c) in cand.iter_mut().enumerate() {
            let Some(t) = face_plane_t(h[i], o[i], d[i], back) else {
                continue;
            };
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            if (o[j] + t * d[j]).abs() <= h[j] && (o[k] + t * d[k]).abs() <= h[k] {
                *c = t;
            }
        }
        if let Some(t) = first_hit(cand, ray, f32::INFINITY) {
            return (t <= t_max).then_some(t);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::test_support::{RayCase, assert_bounds_near, close, ray, unit_floats};
    use glam::Vec3;

    type Kernel = fn(&Obb, &Ray, f32) -> Option<f32>;
    const KERNELS: [(&str, Kernel); 2] = [
        ("slabs", intersect_slabs),
        ("front_planes", intersect_front_planes),
    ];

    /// The box [-1,1] x [-2,2] x [-0.5,0.5] rotated 90 degrees about z, centred at (5,0,0): in
    /// world it spans x in [3,7], y in [-1,1], z in [-0.5,0.5].
    fn rotated() -> Obb {
        Obb::new(
            Vec3A::new(5.0, 0.0, 0.0),
            Vec3A::new(1.0, 2.0, 0.5),
            Mat3A::from_rotation_z(std::f32::consts::FRAC_PI_2),
        )
        .unwrap()
    }

    #[test]
    fn hand_computed_cases() {
        let b = rotated();
        let inf = f32::INFINITY;
        // The hit's t within 1e-5, or a miss.
        let cases: [RayCase; 9] = [
            // From the origin along +x: enters the face x = 3.
            ([0.0; 3], [1.0, 0.0, 0.0], inf, Some(3.0)),
            // Scaled direction: t in units of dir.
            ([0.0; 3], [2.0, 0.0, 0.0], inf, Some(1.5)),
            // From above along -z: the top face z = 0.5.
            ([4.0, 0.5, 3.0], [0.0, 0.0, -1.0], inf, Some(2.5)),
            // Inside: the exit through y = 1.
            ([5.0, 0.0, 0.0], [0.0, 1.0, 0.0], inf, Some(1.0)),
            // Misses: beside, behind, beyond t_max.
            ([0.0, 1.5, 0.0], [1.0, 0.0, 0.0], inf, None),
            ([8.0, 0.0, 0.0], [1.0, 0.0, 0.0], inf, None),
            ([0.0; 3], [1.0, 0.0, 0.0], 2.9, None),
            // Through the edge x = 3, y = 1 diagonally: entry at t = 1 (point (3, 1, 0)).
            ([2.0, 2.0, 0.0], [1.0, -1.0, 0.0], inf, Some(1.0)),
            // Grazing the top face (in its plane, y and z fixed): the face is closed, so a hit.
            ([0.0, 0.0, 0.5], [1.0, 0.0, 0.0], inf, Some(3.0)),
        ];
        for (name, k) in KERNELS {
            for (o, d, t_max, expected) in cases {
                let t = k(&b, &ray(o, d), t_max);
                let ok = expected.map_or(t.is_none(), |e| close(t, e));
                assert!(
                    ok,
                    "{name} from {o:?} along {d:?}: {t:?}, expected {expected:?}"
                );
            }
        }
    }

    #[test]
    fn kernels_agree_on_random_rays() {
        let b = Obb::new(
            Vec3A::new(0.3, -0.2, 0.1),
            Vec3A::new(0.7, 0.4, 0.9),
            Mat3A::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7),
        )
        .unwrap();
        let mut unit = unit_floats(99);
        let mut next = || unit() * 4.0 - 2.0;
        let mut hits = 0;
        for _ in 0..4000 {
            let o = Vec3::new(next(), next(), next()) * 1.5;
            let target = Vec3::from(b.center()) + Vec3::new(next(), next(), next()) * 0.6;
            let d = target - o;
            let Ok(r) = Ray::infinite(o, d) else { continue };
            let (a, f) = (
                intersect_slabs(&b, &r, f32::INFINITY),
                intersect_front_planes(&b, &r, f32::INFINITY),
            );
            match (a, f) {
                (Some(a), Some(f)) => {
                    hits += 1;
                    assert!(
                        (a - f).abs() <= 1e-4 * a.abs().max(1.0),
                        "{a} vs {f} for {r:?}"
                    );
                }
                (None, None) => {}
                // Only a ray grazing an edge may differ.
                _ => panic!("slabs {a:?} vs planes {f:?} for {r:?}"),
            }
        }
        assert!(hits > 2000, "{hits}");
    }

    #[test]
    fn bounds_normals_and_overlap() {
        let b = rotated();
        assert_bounds_near(b.bounds(), [3.0, -1.0, -0.5], [7.0, 1.0, 0.5]);
        assert!((b.normal_at(Vec3A::new(3.0, 0.2, 0.1)) - Vec3A::NEG_X).length() < 1e-6);
        assert!((b.normal_at(Vec3A::new(6.0, 0.2, 0.5)) - Vec3A::Z).length() < 1e-6);
        // A box rotated 45 degrees about z: its bounds touch the cell's corner, the box does not.
        let diamond = Obb::new(
            Vec3A::ZERO,
            Vec3A::splat(1.0),
            Mat3A::from_rotation_z(std::f32::consts::FRAC_PI_4),
        )
        .unwrap();
        let corner = Aabb::new(Vec3A::new(1.0, 1.0, -0.1), Vec3A::new(1.3, 1.3, 0.1));
        assert!(diamond.bounds().overlaps(&corner));
        assert!(!diamond.overlaps_box(&corner));
        let on_tip = Aabb::new(Vec3A::new(1.41, -0.1, -0.1), Vec3A::new(2.0, 0.1, 0.1));
        assert!(diamond.overlaps_box(&on_tip));
        assert!(diamond.overlaps_box(&Aabb::new(Vec3A::splat(-0.1), Vec3A::splat(0.1))));
    }

    #[test]
    fn bad_boxes_are_errors() {
        let r = Mat3A::IDENTITY;
        assert!(Obb::new(Vec3A::ZERO, Vec3A::new(1.0, 0.0, 1.0), r).is_err());
        assert!(Obb::new(Vec3A::splat(f32::NAN), Vec3A::ONE, r).is_err());
        assert!(
            Obb::new(
                Vec3A::ZERO,
                Vec3A::ONE,
                Mat3A::from_diagonal(glam::Vec3::splat(2.0))
            )
            .is_err()
        );
    }
}
