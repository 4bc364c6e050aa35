//! `cloth`: the scene falls like a sheet dropped onto a ball and drapes over it. Every point
//! falls along `y` with the same acceleration, from `drop` times the rest bounds' larger
//! horizontal side above its rest height (`t = 0`) to as far below it (`t = 1`); a ball of
//! radius `ball` times that side, centred under the rest bounds with its top at their lowest
//! point, stops the points above it, which then lie on its surface. A `flat` or `terrain` sheet
//! starts flat, drops and ends draped over the ball: no cloth physics, but a shape that changes
//! as much as a falling sheet does, which loosens a tree built on the first frame quickly.

use super::Motion;
use crate::geometry::Aabb;
use glam::Vec3A;

/// The fall's height and the ball's radius, as fractions of the rest bounds' larger side in
/// `x` and `z`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cloth {
    pub drop: f32,
    pub ball: f32,
}

impl Motion for Cloth {
    fn place(&self, p: Vec3A, rest: &Aabb, t: f32) -> Vec3A {
        let side = rest.extent().x.max(rest.extent().z);
        let fallen = p.y + self.drop * side * (1.0 - 2.0 * t * t);
        let r = self.ball * side;
        let centre = rest.center();
        let (dx, dz) = (p.x - centre.x, p.z - centre.z);
        let under = r * r - dx * dx - dz * dz;
        let y = match under > 0.0 {
            true => fallen.max(rest.min.y - r + under.sqrt()),
            false => fallen,
        };
        Vec3A::new(p.x, y, p.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit sheet at y = 0: at t = 0 it is `drop` above, at t = 1 its centre rests on the
    /// ball's top and its corners, off the ball, are `drop` below; x and z never move.
    #[test]
    fn a_sheet_falls_and_drapes_over_the_ball() {
        let rest = Aabb::new(Vec3A::ZERO, Vec3A::new(1.0, 0.0, 1.0));
        let c = Cloth {
            drop: 0.5,
            ball: 0.3,
        };
        let centre = Vec3A::new(0.5, 0.0, 0.5);
        let corner = Vec3A::new(0.0, 0.0, 1.0);
        assert_eq!(c.place(corner, &rest, 0.0), Vec3A::new(0.0, 0.5, 1.0));
        assert_eq!(c.place(corner, &rest, 1.0), Vec3A::new(0.0, -0.5, 1.0));
        assert_eq!(c.place(centre, &rest, 1.0), centre);
        let side = c.place(Vec3A::new(0.7, 0.0, 0.5), &rest, 1.0);
        let on_ball = Vec3A::new(0.5, -0.3, 0.5).distance(side);
        assert!((on_ball - 0.3).abs() < 1e-6, "{side}");
        let mid = c.place(corner, &rest, 0.5);
        assert!(
            (mid.y - 0.25).abs() < 1e-6 && (mid.x, mid.z) == (0.0, 1.0),
            "{mid}"
        );
    }
}
