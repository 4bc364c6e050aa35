//! `keyframes`: every keyframed entry of a scene file ([`crate::scene::keyframes`]) moved
//! rigidly by its track at time `t`; the other primitives stay where they are. Unlike the
//! deformations this is no [`super::Motion`] of points: the pose depends on which entry
//! produced a primitive ([`Scene::keyframed`]).

use crate::scene::{Scene, SceneGeometry};
use rayon::prelude::*;
use std::sync::Arc;

/// The primitives of `scene` at time `t` (in `[0, 1]`) under its keyframes: triangle corners,
/// sphere centres and shapes of each keyframed entry placed by its pose, each coordinate
/// rounded to `f32` once from the static placement (an identity pose keeps every bit). The
/// same scene and `t` give the same primitives, bit for bit. An error (naming the entry) where
/// a moved shape would be invalid, which a rigid motion of a valid shape does not cause beyond
/// rounding, or where a key's translation carries a coordinate beyond `f32`'s range.
pub fn keyframed_geometry(scene: &Scene, t: f32) -> Result<SceneGeometry, String> {
    let mut triangles = scene.triangles.clone();
    let mut spheres = scene.spheres.clone();
    let mut shapes = scene.shapes.clone();
    for object in &scene.keyframed {
        let pose = object.track.at(t);
        if pose.is_identity() {
            continue;
        }
        let bad = |e: &dyn std::fmt::Display| format!("{} at t = {t}: {e}", object.entry);
        let moved = &mut triangles[object.triangles.clone()];
        moved
            .par_iter_mut()
            .for_each(|tri| *tri = pose.triangle(tri));
        let beyond_f32 = "a moved coordinate is beyond f32's range: keep the keys' translations \
                          (and the object) within about ±3.4e38";
        if !moved.iter().all(|tri| tri.v.iter().all(|v| v.is_finite())) {
            return Err(bad(&beyond_f32));
        }
        for s in &mut spheres[object.spheres.clone()] {
            *s = pose.sphere(s).map_err(|e| bad(&e))?;
            if !s.center.is_finite() {
                return Err(bad(&beyond_f32));
            }
        }
        for s in &mut shapes[object.shapes.clone()] {
            *s = pose.shape(s).map_err(|e| bad(&e))?;
        }
    }
    Ok(SceneGeometry {
        triangles: Arc::from(triangles),
        spheres: Arc::from(spheres),
        shapes: Arc::from(shapes),
        // A moved frame is not the placements' scene any more: traced flattened.
        instances: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::shapes::Obb;
    use crate::geometry::{Shape, Sphere, Triangle};
    use crate::scene::keyframes::{Key, KeyframedObject, Track};
    use glam::{DVec3, Mat3A, Vec3A};

    /// Two triangles, a sphere and a box; the second triangle and the box are keyframed,
    /// from rest at `t = 0` to a quarter turn about +z (pivot (1, 0, 0)) and a move by
    /// (0, 0, 4) at `t = 0.5`.
    fn scene() -> Scene {
        let tri = |x: f32| Triangle::new(Vec3A::X * x, Vec3A::new(x, 1.0, 0.0), Vec3A::Z);
        let cube = Obb::new(Vec3A::new(2.0, 0.0, 0.0), Vec3A::ONE, Mat3A::IDENTITY).unwrap();
        let keys = vec![
            Key::new(0.0, None, [0.0; 3]),
            Key::new(0.5, Some(([0.0, 0.0, 1.0], 90.0)), [0.0, 0.0, 4.0]),
        ];
        let track = Track::new(keys, DVec3::X).unwrap();
        Scene {
            triangles: vec![tri(3.0), tri(2.0)],
            spheres: vec![Sphere::new(Vec3A::ZERO, 0.5)],
            shapes: vec![Shape::Box(cube)],
            keyframed: vec![KeyframedObject {
                entry: "test".into(),
                triangles: 1..2,
                spheres: 0..0,
                shapes: 0..1,
                track,
            }],
            ..Scene::default()
        }
    }

    #[test]
    fn the_first_identity_key_is_the_static_scene_and_later_keys_are_met() {
        let s = scene();
        let start = keyframed_geometry(&s, 0.0).unwrap();
        assert_eq!(start.triangles[..], s.triangles[..]);
        assert_eq!(start.spheres[..], s.spheres[..]);
        assert_eq!(start.shapes[..], s.shapes[..]);
        // At the key and after it: the key's pose exactly; only the keyframed entry moves.
        let pose = s.keyframed[0].track.at(0.5);
        for t in [0.5, 0.75, 1.0] {
            let g = keyframed_geometry(&s, t).unwrap();
            assert_eq!(g.triangles[0], s.triangles[0]);
            assert_eq!(g.triangles[1], pose.triangle(&s.triangles[1]));
            assert_eq!(g.shapes[0], pose.shape(&s.shapes[0]).unwrap());
            assert_eq!(g.spheres[..], s.spheres[..]);
        }
        // (2, 0, 0) turned a quarter about +z through (1, 0, 0) is (1, 1, 0), then + (0, 0, 4).
        let corner = keyframed_geometry(&s, 0.5).unwrap().triangles[1].v[0];
        assert!(
            (corner - Vec3A::new(1.0, 1.0, 4.0)).length() < 1e-6,
            "{corner}"
        );
        let Shape::Box(b) = &keyframed_geometry(&s, 0.5).unwrap().shapes[0] else {
            panic!("a box stays a box")
        };
        assert!((b.center() - Vec3A::new(1.0, 1.0, 4.0)).length() < 1e-6);
    }

    /// A key that moves the object beyond `f32`'s range is an error naming the entry and the
    /// time, not infinite coordinates handed to the indices.
    #[test]
    fn a_key_beyond_f32_range_is_an_error() {
        let mut s = scene();
        let keys = vec![
            Key::new(0.0, None, [0.0; 3]),
            Key::new(1.0, None, [1e300, 0.0, 0.0]),
        ];
        s.keyframed[0].track = Track::new(keys, DVec3::X).unwrap();
        assert!(keyframed_geometry(&s, 0.0).is_ok());
        let e = keyframed_geometry(&s, 1.0).unwrap_err();
        assert!(
            e.contains("test at t = 1") && e.contains("beyond f32's range"),
            "{e}"
        );
    }

    #[test]
    fn midpoints_interpolate_and_frames_repeat_bit_for_bit() {
        let s = scene();
        let mid = keyframed_geometry(&s, 0.25).unwrap();
        // Half the turn (45 degrees) about (1, 0, 0) and half the move.
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let corner = mid.triangles[1].v[0];
        let expected = Vec3A::new(1.0 + h, h, 2.0);
        assert!((corner - expected).length() < 1e-6, "{corner}");
        let again = keyframed_geometry(&s, 0.25).unwrap();
        assert_eq!(mid.triangles[..], again.triangles[..]);
        assert_eq!(mid.shapes[..], again.shapes[..]);
    }
}
