//! `twist`: the scene turns about the vertical (`y`) axis through the centre of its rest
//! bounds, by an angle that grows linearly with height, from none at the bottom to
//! `turns * 360°` at the top at the last frame (`t = 1`): a mesh is wrung like a towel, and a
//! tree built on the first frame loosens as it turns.

use super::{Motion, fraction};
use crate::geometry::Aabb;
use glam::Vec3A;
use std::f32::consts::TAU;

/// Turns of the top against the bottom at the last frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Twist {
    pub turns: f32,
}

impl Motion for Twist {
    /// At angle 0 (the bottom, or `t = 0`) the point is returned unchanged, bit for bit.
    fn place(&self, p: Vec3A, rest: &Aabb, t: f32) -> Vec3A {
        let up = fraction(p.y, rest.min.y, rest.max.y, 1.0);
        let angle = TAU * self.turns * t * up;
        if angle == 0.0 {
            return p;
        }
        let (sin, cos) = angle.sin_cos();
        let c = rest.center();
        let (dx, dz) = (p.x - c.x, p.z - c.z);
        Vec3A::new(c.x + dx * cos - dz * sin, p.y, c.z + dx * sin + dz * cos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_the_top_by_the_given_angle_and_keeps_the_bottom() {
        let rest = Aabb::new(Vec3A::new(-1.0, 0.0, -1.0), Vec3A::new(1.0, 2.0, 1.0));
        let quarter = Twist { turns: 0.25 };
        let top = quarter.place(Vec3A::new(1.0, 2.0, 0.0), &rest, 1.0);
        assert!((top - Vec3A::new(0.0, 2.0, 1.0)).length() < 1e-6, "{top}");
        let half_way = quarter.place(Vec3A::new(1.0, 2.0, 0.0), &rest, 0.5);
        let expected = Vec3A::new((TAU / 8.0).cos(), 2.0, (TAU / 8.0).sin());
        assert!((half_way - expected).length() < 1e-6, "{half_way}");
        let bottom = Vec3A::new(0.3, 0.0, -0.7);
        assert_eq!(quarter.place(bottom, &rest, 1.0), bottom);
        let any = Vec3A::new(0.1, 1.3, 0.2);
        assert_eq!(quarter.place(any, &rest, 0.0), any);
    }
}
