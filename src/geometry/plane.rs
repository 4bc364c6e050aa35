//! Ray–plane kernel: the plane `n . p = offset`.

use super::Ray;
use glam::Vec3A;

/// `Some(t)` for the crossing of the plane `n . p = offset` in `[ray.t_min, t_max]`; `None` for
/// a ray parallel to the plane (including one lying in it).
#[inline]
pub fn intersect_plane(normal: Vec3A, offset: f32, ray: &Ray, t_max: f32) -> Option<f32> {
    let denom = normal.dot(ray.dir);
    if denom == 0.0 {
        return None;
    }
    let t = (offset - normal.dot(ray.origin)) / denom;
    (t >= ray.t_min && t <= t_max).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn hand_computed() {
        let r = Ray::infinite(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, -2.0, 0.0)).unwrap();
        assert_eq!(intersect_plane(Vec3A::Y, 0.0, &r, f32::INFINITY), Some(0.5));
        assert_eq!(intersect_plane(Vec3A::Y, 2.0, &r, f32::INFINITY), None);
        let parallel = Ray::infinite(Vec3::ZERO, Vec3::X).unwrap();
        assert_eq!(
            intersect_plane(Vec3A::Y, 0.0, &parallel, f32::INFINITY),
            None
        );
    }
}
