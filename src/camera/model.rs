//! The camera model of a ray set or render: the pinhole, or one of the models built on the
//! same basis, with its defaults relative to the scene.

use super::{Camera, CameraError, Distortion, EyeMotion, ThinLens};
use crate::geometry::{Aabb, Ray, RayError};

/// Which camera model (the names of `render --camera` and of the ray sets).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ModelKind {
    Pinhole,
    /// Thin lens: depth of field.
    Dof,
    /// Eye moving during the shutter: camera motion blur.
    Motion,
    /// Brown-Conrady radial distortion.
    Lens,
}

/// Aperture radius of [`ModelKind::Dof`] as a fraction of the scene's diagonal.
pub const APERTURE_FRACTION: f64 = 0.02;
/// Length of the eye's path of [`ModelKind::Motion`] as a fraction of the scene's diagonal.
pub const MOTION_FRACTION: f64 = 0.05;

/// A camera model with its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CameraModel {
    Pinhole,
    ThinLens(ThinLens),
    Motion(EyeMotion),
    Lens(Distortion),
}

/// Where on the film a ray starts (pixel units, see [`Camera::screen`]) and its lens point and
/// shutter time (unit square and unit interval; ignored by models without a lens or motion).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraSample {
    pub film: [f64; 2],
    pub lens: [f64; 2],
    pub time: f64,
}

impl CameraModel {
    /// The model `kind` with its defaults for a scene with bounds `b` seen by `cam`, `d` the
    /// diagonal of `b` and `c` its centre:
    /// - `dof`: aperture radius `0.02 d`, focal plane through `c` (`(c - eye) . forward`);
    /// - `motion`: the eye moves `0.05 d` along the camera's `right` axis, centred on the eye;
    /// - `lens`: [`Distortion::BARREL`].
    ///
    /// Fails when the scene's centre is not in front of the camera (no focal plane) or the
    /// distortion does not cover the image's corners.
    pub fn for_scene(kind: ModelKind, cam: &Camera, b: &Aabb) -> Result<CameraModel, CameraError> {
        let (min, max) = (b.min.as_dvec3(), b.max.as_dvec3());
        let c = (min + max) / 2.0;
        let e = max - min;
        let d = (e.x * e.x + e.y * e.y + e.z * e.z).sqrt();
        Ok(match kind {
            ModelKind::Pinhole => CameraModel::Pinhole,
            ModelKind::Dof => {
                let focus_distance = (c - cam.eye).dot(cam.forward);
                if !(focus_distance > 0.0 && focus_distance.is_finite()) {
                    return Err(CameraError::FocusBehind(focus_distance));
                }
                CameraModel::ThinLens(ThinLens {
                    aperture_radius: APERTURE_FRACTION * d,
                    focus_distance,
                })
            }
            ModelKind::Motion => CameraModel::Motion(EyeMotion {
                segment: cam.right * (MOTION_FRACTION * d),
            }),
            ModelKind::Lens => {
                let aspect = cam.width as f64 / cam.height as f64;
                let lens = Distortion::BARREL;
                lens.validate((aspect * aspect + 1.0).sqrt())?;
                CameraModel::Lens(lens)
            }
        })
    }

    /// The ray of sample `s`.
    pub fn ray(&self, cam: &Camera, s: &CameraSample) -> Result<Ray, RayError> {
        let (sx, sy) = cam.screen(s.film[0], s.film[1]);
        match self {
            CameraModel::Pinhole => Ray::infinite(
                cam.eye.as_vec3(),
                super::normalize_protocol(cam.through_screen(sx, sy)).as_vec3(),
            ),
            CameraModel::ThinLens(l) => l.ray(cam, sx, sy, s.lens),
            CameraModel::Motion(m) => m.ray(cam, sx, sy, s.time),
            CameraModel::Lens(d) => d.ray(cam, sx, sy),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    #[test]
    fn pinhole_model_is_the_protocol_camera_and_defaults_follow_the_scene() {
        let b = Aabb::new(Vec3A::splat(-1.0), Vec3A::ONE);
        let cam = Camera::protocol(&b, 16, 16).unwrap();
        let centre = |i: u32, j: u32| CameraSample {
            film: [i as f64 + 0.5, j as f64 + 0.5],
            lens: [0.5, 0.5],
            time: 0.5,
        };
        for kind in [
            ModelKind::Pinhole,
            ModelKind::Lens,
            ModelKind::Dof,
            ModelKind::Motion,
        ] {
            let m = CameraModel::for_scene(kind, &cam, &b).unwrap();
            // The image centre, the lens centre and mid-shutter give the pinhole's central ray.
            let r = m.ray(&cam, &centre(8, 8)).unwrap();
            assert!(
                (r.origin - Vec3A::from(cam.eye_f32())).length() < 1e-6,
                "{kind:?}"
            );
            assert!(
                (r.dir - cam.ray(8, 8).unwrap().dir).length() < 1e-3,
                "{kind:?}"
            );
        }
        let pin = CameraModel::Pinhole;
        assert_eq!(pin.ray(&cam, &centre(3, 11)), cam.ray(3, 11));
        let CameraModel::ThinLens(l) = CameraModel::for_scene(ModelKind::Dof, &cam, &b).unwrap()
        else {
            panic!("thin lens expected")
        };
        let d = 12f64.sqrt();
        assert!((l.aperture_radius - 0.02 * d).abs() < 1e-12);
        assert!((l.focus_distance - 1.1 * d).abs() < 1e-9);
    }

    #[test]
    fn a_scene_behind_the_camera_cannot_be_focused() {
        let b = Aabb::new(Vec3A::splat(-1.0), Vec3A::ONE);
        let cam = Camera::look_at(
            glam::DVec3::new(0.0, 0.0, 5.0),
            glam::DVec3::new(0.0, 0.0, 10.0),
            glam::DVec3::Y,
            45.0,
            4,
            4,
        )
        .unwrap();
        let e = CameraModel::for_scene(ModelKind::Dof, &cam, &b).unwrap_err();
        assert!(e.to_string().contains("behind"), "{e}");
    }
}
