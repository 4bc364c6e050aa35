//! The suite's ray sets: the protocol's **primary** and **incoherent** sets, the camera-model
//! sets **dof**, **motion** and **lens** (`rays::camera_model_rays`), and the secondary
//! rays a renderer really traces from the primary hits (the methodology of Aila & Laine 2009):
//! **shadow** rays toward each point light (any hit), one cosine-distributed **diffuse** bounce
//! (closest hit), and short **ao** rays (ambient occlusion, any hit).
//!
//! Secondary rays leave the surface from [`offset_origin_scaled`] (Wächter & Binder, with the
//! near-origin offset relative to the scene's size) with `t_min = 0`, so they do not re-hit the
//! surface they leave at any scene scale. Every set is deterministic:
//! the same scene and sizes give the same rays, bit for bit.

use super::timing::Query;
use crate::camera::{CameraError, ModelKind};
use crate::geometry::{Hit, Ray};
use crate::index::trace::tiles::square_side;
use crate::rays::spawn::{offset_origin_scaled, spawn_scale};
use crate::rays::{CAMERA_SET_SEED, SplitMix64, camera_model_rays, incoherent_rays, primary_rays};
use crate::scene::Scene;
use glam::Vec3A;
use serde::Serialize;
use std::f32::consts::TAU;

/// A ray set of the suite.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum RaySet {
    Primary,
    Shadow,
    Diffuse,
    Ao,
    Incoherent,
    Dof,
    Motion,
    Lens,
}

impl RaySet {
    /// The sets of a default `accelbench run` (without `--full` or `--rays`): camera rays, and
    /// the shadow, diffuse-bounce and incoherent rays that follow from them, the kinds a
    /// renderer traces most; `--full` adds ambient occlusion and the three camera models.
    pub const FIRST_RUN: [RaySet; 4] = [
        RaySet::Primary,
        RaySet::Shadow,
        RaySet::Diffuse,
        RaySet::Incoherent,
    ];

    pub const ALL: [RaySet; 8] = [
        RaySet::Primary,
        RaySet::Shadow,
        RaySet::Diffuse,
        RaySet::Ao,
        RaySet::Incoherent,
        RaySet::Dof,
        RaySet::Motion,
        RaySet::Lens,
    ];

    pub fn name(self) -> &'static str {
        match self {
            RaySet::Primary => "primary",
            RaySet::Shadow => "shadow",
            RaySet::Diffuse => "diffuse",
            RaySet::Ao => "ao",
            RaySet::Incoherent => "incoherent",
            RaySet::Dof => "dof",
            RaySet::Motion => "motion",
            RaySet::Lens => "lens",
        }
    }

    /// What the set asks of an index: occlusion sets ask for any hit.
    pub fn query(self) -> Query {
        match self {
            RaySet::Shadow | RaySet::Ao => Query::Any,
            _ => Query::Closest,
        }
    }

    /// `true` for the sets whose neighbouring rays come from neighbouring pixels (traced as
    /// packets by `run --packets`): the camera sets and the shadow rays of primary hits.
    pub fn is_coherent(self) -> bool {
        !matches!(self, RaySet::Diffuse | RaySet::Ao | RaySet::Incoherent)
    }

    /// The width of the set's `rays` rays as an image in raster order: the camera sets
    /// (primary, dof, motion, lens) are `side x side` images, whose packets the packet modes
    /// take from screen tiles ([`crate::index::trace::tiles`]). `None` for every other set, even
    /// one whose length happens to be a square (1,048,576 incoherent rays): those are packed
    /// in set order.
    pub fn image_width(self, rays: usize) -> Option<usize> {
        let camera = matches!(
            self,
            RaySet::Primary | RaySet::Dof | RaySet::Motion | RaySet::Lens
        );
        camera.then(|| square_side(rays)).flatten()
    }

    /// The camera model of a camera-model set.
    pub fn camera_model(self) -> Option<ModelKind> {
        match self {
            RaySet::Dof => Some(ModelKind::Dof),
            RaySet::Motion => Some(ModelKind::Motion),
            RaySet::Lens => Some(ModelKind::Lens),
            _ => None,
        }
    }

    /// `true` for the sets traced from primary hits.
    pub fn is_secondary(self) -> bool {
        matches!(self, RaySet::Shadow | RaySet::Diffuse | RaySet::Ao)
    }
}

/// How many rays the generated sets hold.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SetSizes {
    /// Width and height of the primary image (the protocol's is 1024).
    pub primary_side: u32,
    /// Number of incoherent rays (the protocol's is 1,048,576; a smaller count is a prefix of
    /// the protocol set).
    pub incoherent: usize,
    /// Length of the ambient-occlusion rays as a fraction of the scene's bounding-box diagonal.
    pub ao_fraction: f32,
}

/// The protocol camera's rays for the scene (its ray-set bounds).
pub fn primary(scene: &Scene, sizes: &SetSizes) -> Result<Vec<Ray>, CameraError> {
    primary_rays(
        &scene.ray_set_bounds(),
        sizes.primary_side,
        sizes.primary_side,
    )
}

/// The camera-model set of `kind` at the primary set's size (seed [`CAMERA_SET_SEED`]).
pub fn camera_model_set(
    scene: &Scene,
    sizes: &SetSizes,
    kind: ModelKind,
) -> Result<Vec<Ray>, CameraError> {
    camera_model_rays(
        &scene.ray_set_bounds(),
        sizes.primary_side,
        kind,
        CAMERA_SET_SEED,
    )
}

/// The protocol's incoherent rays (SplitMix64 seeded with 42), the first `sizes.incoherent`.
pub fn incoherent(scene: &Scene, sizes: &SetSizes) -> Vec<Ray> {
    incoherent_rays(&scene.ray_set_bounds(), sizes.incoherent, 42)
}

/// A primary hit as a surface point to leave from: the offset origin (scene size `scale`, see
/// [`offset_origin_scaled`]) and the unit normal facing the side the primary ray came from.
/// `None` for a degenerate (zero-normal) triangle.
fn surface(
    scene_geom: &crate::scene::SceneGeometry,
    scale: f32,
    ray: &Ray,
    hit: &Hit,
) -> Option<(Vec3A, Vec3A)> {
    let p = ray.at(hit.t);
    let mut n = scene_geom.normal_at(hit.prim, p);
    if n == Vec3A::ZERO || !n.is_finite() {
        return None;
    }
    if n.dot(ray.dir) > 0.0 {
        n = -n;
    }
    Some((offset_origin_scaled(p, n, scale), n))
}

/// A cosine-distributed unit direction about the unit normal `n` (Malley's method on the
/// branchless orthonormal basis of Duff et al. 2017).
fn cosine_direction(n: Vec3A, rng: &mut SplitMix64) -> Vec3A {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3A::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let s = Vec3A::new(b, sign + n.y * n.y * a, -n.y);
    let (r1, r2) = (rng.next_unit() as f32, rng.next_unit() as f32);
    let r = r2.sqrt();
    let phi = TAU * r1;
    t * (r * phi.cos()) + s * (r * phi.sin()) + n * (1.0 - r2).max(0.0).sqrt()
}

/// The secondary rays of `set` from the primary rays and their hits (same order). Shadow rays
/// go toward every light (the scene's, or a default one) whose side the surface faces, over
/// `[0, 1]` (the light is at `t = 1`); diffuse rays are unbounded; ao rays have length
/// `sizes.ao_fraction` of the bounds' diagonal.
pub fn secondary(
    set: RaySet,
    scene: &Scene,
    sizes: &SetSizes,
    primary: &[Ray],
    hits: &[Option<Hit>],
) -> Vec<Ray> {
    let geom = scene.geometry();
    let lights = scene.lights_or_default();
    let mut rng = SplitMix64::new(match set {
        RaySet::Diffuse => 7,
        _ => 11,
    });
    let bounds = scene.bounds();
    let ao_len = sizes.ao_fraction * bounds.extent().length();
    let scale = spawn_scale(&bounds);
    let mut out = Vec::new();
    for (ray, hit) in primary.iter().zip(hits) {
        let Some((o, n)) = hit.as_ref().and_then(|h| surface(&geom, scale, ray, h)) else {
            continue;
        };
        match set {
            RaySet::Shadow => {
                for l in &lights {
                    let d = Vec3A::from(l.position) - o;
                    if d.dot(n) > 0.0
                        && let Ok(r) = Ray::new(o.into(), d.into(), 0.0, 1.0)
                    {
                        out.push(r);
                    }
                }
            }
            RaySet::Diffuse | RaySet::Ao => {
                let d = cosine_direction(n, &mut rng);
                let t_max = if set == RaySet::Ao {
                    ao_len
                } else {
                    f32::INFINITY
                };
                if let Ok(r) = Ray::new(o.into(), d.into(), 0.0, t_max) {
                    out.push(r);
                }
            }
            _ => unreachable!("not a secondary set"),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleKernelKind;
    use crate::index::{IndexSpec, build_index};

    /// Only camera sets are images; a square count of other rays is not taken for one.
    #[test]
    fn only_camera_sets_are_images() {
        let n = 1024 * 1024;
        for set in [RaySet::Primary, RaySet::Dof, RaySet::Motion, RaySet::Lens] {
            assert_eq!(set.image_width(n), Some(1024), "{set:?}");
        }
        for set in [
            RaySet::Incoherent,
            RaySet::Shadow,
            RaySet::Diffuse,
            RaySet::Ao,
        ] {
            assert_eq!(set.image_width(n), None, "{set:?}");
        }
        assert_eq!(RaySet::Primary.image_width(1024 * 1023), None);
    }
    use crate::scene::generators;

    #[test]
    fn cosine_directions_are_unit_and_in_the_hemisphere() {
        let mut rng = SplitMix64::new(3);
        for n in [Vec3A::Z, -Vec3A::Z, Vec3A::new(0.6, 0.0, 0.8), -Vec3A::Y] {
            let mut mean_cos = 0.0;
            for _ in 0..2000 {
                let d = cosine_direction(n, &mut rng);
                assert!((d.length() - 1.0).abs() < 1e-4, "{d:?}");
                assert!(d.dot(n) >= -1e-6);
                mean_cos += d.dot(n) / 2000.0;
            }
            // E[cos] = 2/3 for a cosine distribution.
            assert!((mean_cos - 2.0 / 3.0).abs() < 0.03, "{mean_cos}");
        }
    }

    #[test]
    fn secondary_sets_leave_the_surface_toward_the_right_side() {
        let scene = generators::generate("icosphere", 2000, 1).unwrap();
        let sizes = SetSizes {
            primary_side: 32,
            incoherent: 100,
            ao_fraction: 0.05,
        };
        let rays = primary(&scene, &sizes).unwrap();
        let brute = build_index(
            &IndexSpec::named("brute"),
            &scene.geometry(),
            TriangleKernelKind::Watertight,
        )
        .unwrap();
        let mut hits = vec![None; rays.len()];
        brute.closest_hits(&rays, &mut hits);
        let n_hits = hits.iter().flatten().count();
        assert!(n_hits > 100);
        let diffuse = secondary(RaySet::Diffuse, &scene, &sizes, &rays, &hits);
        assert_eq!(diffuse.len(), n_hits);
        // From outside a closed convex sphere, diffuse rays leave outward and never re-hit it.
        let mut back = vec![None; diffuse.len()];
        brute.closest_hits(&diffuse, &mut back);
        assert_eq!(back.iter().flatten().count(), 0);
        let ao = secondary(RaySet::Ao, &scene, &sizes, &rays, &hits);
        assert!(ao.iter().all(|r| r.t_max > 0.0 && r.t_max.is_finite()));
        let shadow = secondary(RaySet::Shadow, &scene, &sizes, &rays, &hits);
        assert!(!shadow.is_empty() && shadow.len() < n_hits);
        assert!(shadow.iter().all(|r| r.t_max == 1.0));
    }
}
