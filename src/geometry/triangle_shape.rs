//! The triangle as a primitive: its three corners, bounds, normal, area and barycentrics. The
//! kernels that intersect it are in [`super::triangle`].

use super::Aabb;
use super::float::cross;
use glam::Vec3A;

/// A triangle by its three corners, in the winding of the source file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    pub v: [Vec3A; 3],
}

impl Triangle {
    pub fn new(a: Vec3A, b: Vec3A, c: Vec3A) -> Triangle {
        Triangle { v: [a, b, c] }
    }

    /// A triangle from its corners as `[x, y, z]` arrays (for literals in tests and
    /// generators).
    pub fn from_corners(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Triangle {
        Triangle::new(Vec3A::from(a), Vec3A::from(b), Vec3A::from(c))
    }

    #[inline]
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: self.v[0].min(self.v[1]).min(self.v[2]),
            max: self.v[0].max(self.v[1]).max(self.v[2]),
        }
    }

    /// Geometric normal `(v1 - v0) x (v2 - v0)`, not normalized (length = twice the area).
    #[inline]
    pub fn normal_unnormalized(&self) -> Vec3A {
        cross(self.v[1] - self.v[0], self.v[2] - self.v[0])
    }

    /// Unit geometric normal; zero for a degenerate triangle.
    pub fn normal(&self) -> Vec3A {
        self.normal_unnormalized().normalize_or_zero()
    }

    pub fn area(&self) -> f32 {
        0.5 * self.normal_unnormalized().length()
    }

    /// `true` for a zero-area triangle (collinear or coincident corners).
    pub fn is_degenerate(&self) -> bool {
        self.normal_unnormalized() == Vec3A::ZERO
    }

    /// Barycentric coordinates `(b0, b1, b2)` of the point `p` (assumed in the plane), for the
    /// final hit only. Zero for a degenerate triangle.
    pub fn barycentrics(&self, p: Vec3A) -> Vec3A {
        let n = self.normal_unnormalized();
        let nn = n.length_squared();
        if nn == 0.0 {
            return Vec3A::ZERO;
        }
        let b1 = cross(p - self.v[0], self.v[2] - self.v[0]).dot(n) / nn;
        let b2 = cross(self.v[1] - self.v[0], p - self.v[0]).dot(n) / nn;
        Vec3A::new(1.0 - b1 - b2, b1, b2)
    }
}
