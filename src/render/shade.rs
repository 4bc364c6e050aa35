//! Phong shading of the closest hit with shadows by occlusion (any-hit) rays: point lights give
//! hard shadows, rectangular area lights soft ones from a fixed stratified grid of samples.

use super::sampling::{MAX_SPP, Sampling};
use super::view::{pixel_ray, view_camera};
use super::{Image, RenderError, RenderOptions};
use crate::camera::CameraModel;
use crate::geometry::{Hit, Ray};
use crate::index::TraceIndex;
use crate::rays::SplitMix64;
use crate::rays::spawn::{offset_origin_scaled, spawn_scale};
use crate::scene::{AreaLight, Material, PointLight, Scene};
use glam::{Vec3, Vec3A};
use rayon::prelude::*;

/// `t_max` of a shadow ray. Its direction is `light - origin`, so the light sits at `t = 1`; the
/// ray stops 1/1024 of the distance short of it, so a surface the light lies on (a lamp set
/// into a ceiling) does not shadow it, while anything in between does.
pub const SHADOW_T_MAX: f32 = 1.0 - 1.0 / 1024.0;

/// Linear RGB of pixels whose ray hits nothing.
const BACKGROUND: Vec3 = Vec3::new(0.02, 0.02, 0.03);

/// Display gamma applied after clamping to `[0, 1]`.
const GAMMA: f32 = 2.2;

/// Renders the scene through `index`: for each pixel the camera ray ([`pixel_ray`] of
/// [`view_camera`]), its closest hit, and the Phong colour of that hit (see [`Material`]) under
/// the scene's point lights (or one default light when it has neither point nor area lights) and
/// area lights. Two-sided: the normal is flipped towards the viewer. No distance falloff, as in
/// the course's ray caster. Parallel over rows, each row's camera rays traced as one batch in
/// `Sampling::mode` (the image is the same in every mode); no allocation per ray.
pub fn render_shaded(
    scene: &Scene,
    index: &dyn TraceIndex,
    opts: &RenderOptions,
) -> Result<Image, RenderError> {
    render_shaded_with(scene, index, opts, &Sampling::default())
}

/// [`render_shaded`] with `sampling.spp` stratified camera rays per pixel through camera model
/// `sampling.camera` (defaults relative to the scene, [`CameraModel::for_scene`]), averaged in
/// linear RGB with the filter's weights. Sample `k` of pixel `p` seeds its area-light samples
/// with `p * spp + k`, so one sample per pixel through the pinhole is [`render_shaded`].
pub fn render_shaded_with(
    scene: &Scene,
    index: &dyn TraceIndex,
    opts: &RenderOptions,
    sampling: &Sampling,
) -> Result<Image, RenderError> {
    if !(1..=MAX_SPP).contains(&sampling.spp) {
        return Err(RenderError::Samples(sampling.spp));
    }
    let cam = view_camera(scene, opts)?;
    // Fail early, with the error, if the camera cannot make rays (it can for no valid camera).
    pixel_ray(&cam, 0, 0)?;
    let model = CameraModel::for_scene(sampling.camera, &cam, &scene.ray_set_bounds())?;
    let lights = if scene.lights.is_empty() && scene.area_lights.is_empty() {
        scene.lights_or_default()
    } else {
        scene.lights.clone()
    };
    let shader = Shader {
        scene,
        index,
        lights: &lights,
        spawn_scale: spawn_scale(&scene.bounds()),
    };
    let width = opts.width;
    let spp = sampling.spp;
    let mut img = Image::new(opts.width, opts.height);
    let rows: Vec<&mut [u8]> = img.rows_mut().collect();
    rows.into_par_iter().enumerate().for_each(|(j, row)| {
        let j = j as u32;
        let pixel = |i: u32| j as u64 * width as u64 + i as u64;
        // The row's camera rays (those the model can make), traced as one batch in the mode;
        // per sample its filter weight and whether the model made its ray.
        let mut rays: Vec<Ray> = Vec::with_capacity((width * spp) as usize);
        let mut samples: Vec<(f32, bool)> = Vec::with_capacity((width * spp) as usize);
        for i in 0..width {
            for k in 0..spp {
                let (s, w) = sampling.sample(i, j, pixel(i), k);
                let ray = model.ray(&cam, &s).ok();
                samples.push((w, ray.is_some()));
                rays.extend(ray);
            }
        }
        let mut hits = vec![None; rays.len()];
        index.closest_hits_in(sampling.mode, &rays, &mut hits, None);
        let mut traced = rays.iter().zip(hits);
        let mut samples = samples.into_iter();
        for (i, px) in row.chunks_exact_mut(3).enumerate() {
            let i = i as u32;
            let (mut sum, mut weights) = (Vec3::ZERO, 0.0);
            for k in 0..spp {
                let (w, made) = samples.next().expect("one sample per pixel and k");
                let colour = if made {
                    match traced.next().expect("one answer per ray") {
                        (ray, Some(hit)) => {
                            shader.shade(ray, hit, pixel(i) * spp as u64 + k as u64)
                        }
                        (_, None) => BACKGROUND,
                    }
                } else {
                    BACKGROUND
                };
                sum += colour * w;
                weights += w;
            }
            px.copy_from_slice(&to_srgb8(sum / weights));
        }
    });
    Ok(img)
}

/// What shading a hit needs.
struct Shader<'a> {
    scene: &'a Scene,
    index: &'a dyn TraceIndex,
    lights: &'a [PointLight],
    /// Scene size for shadow-ray origins ([`offset_origin_scaled`]).
    spawn_scale: f32,
}

impl Shader<'_> {
    /// The Phong colour (linear RGB, unclamped) of `hit` on `ray`; `pixel` seeds the area-light
    /// samples.
    fn shade(&self, ray: &Ray, hit: Hit, pixel: u64) -> Vec3 {
        let m = self.scene.material(hit.prim);
        let p = ray.at(hit.t);
        let view = -ray.dir.normalize();
        let mut n = self.scene.normal(hit.prim, p);
        if n == Vec3A::ZERO {
            n = view; // a zero-area triangle hit edge-on: light it as if facing the viewer
        } else if n.dot(view) < 0.0 {
            n = -n;
        }
        let surface = Surface {
            p,
            n,
            view,
            origin: offset_origin_scaled(p, n, self.spawn_scale),
            material: m,
        };
        let mut c = m.emission + m.ambient * m.color;
        for l in self.lights {
            c += self.light_sample(&surface, Vec3A::from(l.position), l.intensity);
        }
        for (k, l) in self.scene.area_lights.iter().enumerate() {
            c += self.area_light(&surface, l, stream(pixel, k));
        }
        c
    }

    /// Sum over the `samples x samples` strata of `l`, one jittered point in each, each carrying
    /// `intensity / samples^2`.
    fn area_light(&self, s: &Surface, l: &AreaLight, seed: u64) -> Vec3 {
        let mut rng = SplitMix64::new(seed);
        let n = l.samples;
        let inv = 1.0 / n as f32;
        let intensity = l.intensity * (inv * inv);
        let mut c = Vec3::ZERO;
        for a in 0..n {
            for b in 0..n {
                let ja = rng.next_unit() as f32;
                let jb = rng.next_unit() as f32;
                let q = l.point((a as f32 + ja) * inv, (b as f32 + jb) * inv);
                c += self.light_sample(s, Vec3A::from(q), intensity);
            }
        }
        c
    }

    /// Diffuse and specular light from a point light at `q`, zero when the surface faces away
    /// or a shadow ray from the surface to `q` is blocked.
    fn light_sample(&self, s: &Surface, q: Vec3A, intensity: Vec3) -> Vec3 {
        let l = (q - s.p).normalize_or_zero();
        let n_dot_l = s.n.dot(l);
        if n_dot_l <= 0.0 {
            return Vec3::ZERO;
        }
        let Ok(shadow) = Ray::new(s.origin.into(), (q - s.origin).into(), 0.0, SHADOW_T_MAX) else {
            return Vec3::ZERO; // the light sits on the surface point itself
        };
        if self.index.any_hit(&shadow) {
            return Vec3::ZERO;
        }
        let m = s.material;
        let r = 2.0 * n_dot_l * s.n - l;
        let spec = r.dot(s.view).max(0.0).powf(m.shininess);
        intensity * (m.diffuse * n_dot_l * m.color + Vec3::splat(m.specular * spec))
    }
}

/// A shaded point: position, unit normal facing the viewer, unit direction to the viewer,
/// shadow-ray origin (offset off the surface along `n`) and material.
struct Surface<'a> {
    p: Vec3A,
    n: Vec3A,
    view: Vec3A,
    origin: Vec3A,
    material: &'a Material,
}

/// The random stream of area light `light` at pixel `pixel`: fixed by the two, whichever thread
/// shades the pixel.
fn stream(pixel: u64, light: usize) -> u64 {
    pixel.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ (light as u64).wrapping_mul(0xD1B5_4A32_D192_ED03)
}

/// Clamps to `[0, 1]`, applies the display gamma and rounds to 8 bits.
fn to_srgb8(c: Vec3) -> [u8; 3] {
    c.to_array()
        .map(|x| (x.clamp(0.0, 1.0).powf(1.0 / GAMMA) * 255.0 + 0.5) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_encoding_clamps() {
        assert_eq!(to_srgb8(Vec3::new(-1.0, 0.0, 2.0)), [0, 0, 255]);
        assert_eq!(to_srgb8(Vec3::splat(1.0)), [255; 3]);
        assert_eq!(to_srgb8(Vec3::splat(f32::NAN)), [0; 3]);
    }
}
