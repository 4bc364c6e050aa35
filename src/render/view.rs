//! The camera of a picture: the scene's own, or the protocol's standard camera; one ray through
//! each pixel centre, with the horizontal field of view widened by the aspect ratio.

use super::{RenderError, RenderOptions};
use crate::camera::{Camera, normalize_protocol};
use crate::geometry::{Ray, RayError};
use crate::scene::Scene;

/// The scene's camera (`[camera]` of a scene file, or a built-in scene's), else the protocol's
/// standard camera on the scene's ray-set bounds, for an image of `opts`' size.
pub fn view_camera(scene: &Scene, opts: &RenderOptions) -> Result<Camera, RenderError> {
    opts.validate()?;
    let (w, h) = (opts.width, opts.height);
    Ok(match &scene.camera {
        Some(c) => Camera::look_at(
            c.eye.as_dvec3(),
            c.look_at.as_dvec3(),
            c.up.as_dvec3(),
            c.fov_deg as f64,
            w,
            h,
        )?,
        None => Camera::protocol(&scene.ray_set_bounds(), w, h)?,
    })
}

/// The ray through the centre of pixel `(i, j)` (row 0 at the top). The field of view is
/// vertical; horizontally it is scaled by `width / height`, so non-square images are not
/// stretched. For a square image this is exactly [`Camera::ray`], i.e. the protocol's primary
/// ray set.
pub fn pixel_ray(cam: &Camera, i: u32, j: u32) -> Result<Ray, RayError> {
    let aspect = cam.width as f64 / cam.height as f64;
    let u = ((i as f64 + 0.5) / cam.width as f64) * 2.0 - 1.0;
    let v = 1.0 - ((j as f64 + 0.5) / cam.height as f64) * 2.0;
    let t = cam.tan_half_fov;
    let dir = normalize_protocol(cam.forward + ((u * t) * aspect) * cam.right + (v * t) * cam.up);
    Ray::infinite(cam.eye.as_vec3(), dir.as_vec3())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn square_images_use_the_protocol_rays() {
        let cam = Camera::look_at(DVec3::Z * 3.0, DVec3::ZERO, DVec3::Y, 40.0, 7, 7).unwrap();
        for (i, j) in [(0, 0), (3, 5), (6, 6)] {
            assert_eq!(pixel_ray(&cam, i, j), cam.ray(i, j));
        }
        // A 2:1 image spans twice the vertical extent horizontally.
        let wide = Camera::look_at(DVec3::Z, DVec3::ZERO, DVec3::Y, 90.0, 4, 2).unwrap();
        let d = pixel_ray(&wide, 0, 0).unwrap().dir;
        assert!(
            (d.x / d.z - 1.5).abs() < 1e-6 && (d.y / d.z + 0.5).abs() < 1e-6,
            "{d:?}"
        );
    }
}
