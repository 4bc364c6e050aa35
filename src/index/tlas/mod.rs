//! `tlas`: a two-level index for scenes with `[[instance]]` entries. Each distinct mesh gets one
//! structure of ours over its object-space triangles (`inner`, any of our kinds, default
//! `bvh8`), shared by all its instances; a box tree (`top`: `bvh`, `bvh4`, `bvh8`, or `brute`
//! for the reference) is built over the instances' world bounds, and a ray reaching an instance
//! is moved into its object space and traced by the instance's mesh structure.
//!
//! **Hit contract under instancing.** Hits are the flattened scene's ids (instance `i`'s triangle
//! `j` is `first_i + j`), and their `t` is the instanced arithmetic of
//! [`crate::scene::instances`]. Every `tlas:inner=X,top=Y` returns, bit for bit, what brute force
//! over the instances returns with each mesh traced by brute force (`tlas:inner="brute",
//! top="brute"`): the meshes' structures are bound by the hit contract on the object-space rays,
//! and the top level by the same contract over instances as primitives
//! ([`instance_geometry::InstanceGeometry`] is a [`crate::scene::Geometry`]). The flattened
//! scene's triangles, in world space, give other `t` by rounding, so against them (what every
//! other index traces, and brute force checks in a run) `tlas` is classified as peers are (tie,
//! `t off`, wrong), never failed ([`crate::index::Kind::Instanced`]).
//!
//! `index::registry` builds it (parsing `inner` into a spec of ours and passing its builder);
//! `tests/it/instances.rs` checks the contract.
//!
//! Counting: the top level's steps and instance tests are what its walk reports, the work inside
//! the meshes is not seen by it, so the index reports its tests and steps per ray as not counted
//! rather than partial.

mod instance_geometry;

pub use instance_geometry::InstanceGeometry;

use crate::geometry::{Hit, Ray};
use crate::index::{
    BruteForce, BuildError, Bvh, Bvh4, Bvh8, Counters, IndexInfo, TraceIndex, TraceMode,
    build_index_on,
};
use crate::scene::SceneGeometry;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::Instant;

/// `tlas` parameters.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TlasParams {
    /// The structure of each mesh: an index of ours with its parameters (`"kdtree"`,
    /// `"bvh:leaf_size=2"`).
    pub inner: String,
    /// The structure over the instances: `bvh`, `bvh4`, `bvh8`, or `brute`.
    pub top: String,
}

impl Default for TlasParams {
    fn default() -> Self {
        TlasParams {
            inner: "bvh8".into(),
            top: "bvh".into(),
        }
    }
}

/// The kinds `top` may name.
const TOPS: [&str; 4] = ["bvh", "bvh4", "bvh8", "brute"];

impl TlasParams {
    /// Checks `top` (the registry checks that `inner` names one of our indices).
    pub fn check_top(&self, index: &str) -> Result<(), BuildError> {
        match TOPS.contains(&self.top.as_str()) {
            true => Ok(()),
            false => Err(BuildError::Params {
                index: index.to_owned(),
                message: format!(
                    "top = \"{}\" is not a top level: give one of {}",
                    self.top,
                    TOPS.join(", ")
                ),
            }),
        }
    }
}

/// A built mesh structure: how `tlas` builds its `inner` index over one mesh (the registry
/// passes its own builder, with the spec and kernel of the run).
pub type MeshBuilder<'a> = &'a dyn Fn(&SceneGeometry) -> Result<Box<dyn TraceIndex>, BuildError>;

/// Builds `tlas` (named `name`, checked `params`) over the scene's instances, each mesh by
/// `build_mesh`: [`BuildError::Unsupported`] for a scene without `[[instance]]` entries or with
/// spheres or shapes beside them. `tlas` gives no estimate of its own (the registry's count is
/// the flattened scene's, while each mesh is built once): each mesh's structure is held to the
/// memory budget by its own estimate when `build_mesh` builds it.
pub fn build(
    name: &str,
    params: &TlasParams,
    geom: &SceneGeometry,
    build_mesh: MeshBuilder<'_>,
) -> Result<Box<dyn TraceIndex>, BuildError> {
    params.check_top(name)?;
    let unsupported = |reason: &str| BuildError::Unsupported {
        index: name.to_owned(),
        reason: reason.into(),
    };
    let Some(set) = geom.instances.clone() else {
        return Err(unsupported(
            "the scene has no [[instance]] entries (tlas traces scene files that place meshes \
             with [[instance]]; see docs/scenes.md)",
        ));
    };
    if !set.covers_scene {
        return Err(unsupported(
            "the scene has spheres or shapes beside its instances; tlas places triangle meshes only",
        ));
    }
    let ((built, build_time), peak) = crate::heap_meter::peak_during(|| {
        let start = Instant::now();
        let built = build_levels(name, params, set, build_mesh);
        (built, start.elapsed())
    });
    let (top, geometry) = built?;
    let mut info = summary(top.info(), &geometry);
    info.build_time = build_time;
    info.peak_build_bytes = Some(peak);
    Ok(Box::new(Tlas {
        name: name.to_owned(),
        params: format!("inner={},top={}", params.inner, params.top),
        top,
        geometry,
        info,
    }))
}

/// The meshes' structures, then the top level over the instances.
fn build_levels(
    name: &str,
    params: &TlasParams,
    set: Arc<crate::scene::instances::InstanceSet>,
    build_mesh: MeshBuilder<'_>,
) -> Result<(Box<dyn TraceIndex>, InstanceGeometry), BuildError> {
    let meshes = (set.meshes.iter())
        .map(|m| {
            build_mesh(&SceneGeometry {
                triangles: m.clone(),
                ..SceneGeometry::default()
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let geometry = InstanceGeometry {
        set,
        meshes: Arc::from(meshes),
    };
    let g = geometry.clone();
    let top: Box<dyn TraceIndex> = match params.top.as_str() {
        "bvh" => Box::new(build_index_on::<Bvh, _>(name, g, Default::default())?),
        "bvh4" => Box::new(build_index_on::<Bvh4, _>(name, g, Default::default())?),
        "bvh8" => Box::new(build_index_on::<Bvh8, _>(name, g, Default::default())?),
        _ => Box::new(build_index_on::<BruteForce, _>(
            name,
            g,
            Default::default(),
        )?),
    };
    Ok((top, geometry))
}

/// The top level's shape, with the meshes' memory added and the instancing figures in `extra`.
fn summary(top: &IndexInfo, g: &InstanceGeometry) -> IndexInfo {
    let set = &g.set;
    let mesh_bytes: usize = g.meshes.iter().map(|m| m.info().memory_bytes).sum();
    let record = std::mem::size_of::<crate::scene::instances::Instance>();
    let instance_bytes = set.instances.len() * record;
    let memory = top.memory_bytes + mesh_bytes + instance_bytes;
    IndexInfo {
        memory_bytes: memory,
        uncounted: true,
        extra: vec![
            ("instances".into(), set.instances.len() as f64),
            ("meshes".into(), set.meshes.len() as f64),
            ("mesh_triangles".into(), set.mesh_triangles() as f64),
            ("mesh_structure_bytes".into(), mesh_bytes as f64),
            (
                "bytes_per_instance".into(),
                (top.memory_bytes + instance_bytes) as f64 / set.instances.len().max(1) as f64,
            ),
            (
                "bytes_per_instanced_triangle".into(),
                memory as f64 / set.instanced_triangles().max(1) as f64,
            ),
        ],
        ..top.clone()
    }
}

/// A built `tlas`: the top level over [`InstanceGeometry`], whose hits name instances, and the
/// instances, which turn them into flattened ids.
pub struct Tlas {
    name: String,
    params: String,
    top: Box<dyn TraceIndex>,
    geometry: InstanceGeometry,
    info: IndexInfo,
}

impl Tlas {
    /// The top level's answers (instance ids) turned into flattened ids, in parallel.
    fn flatten(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        (out.par_iter_mut().zip(rays.par_iter()))
            .with_min_len(256)
            .for_each(|(hit, ray)| {
                if let Some(h) = hit {
                    *h = self.geometry.flattened(ray, *h);
                }
            });
    }
}

impl TraceIndex for Tlas {
    fn name(&self) -> &str {
        &self.name
    }
    fn params(&self) -> &str {
        &self.params
    }
    fn info(&self) -> &IndexInfo {
        &self.info
    }
    fn has_stream(&self) -> bool {
        self.top.has_stream()
    }
    fn has_single(&self) -> bool {
        self.top.has_single()
    }
    fn refused(&self, rays: &[Ray]) -> Option<(usize, &'static str)> {
        self.top.refused(rays)
    }
    fn can_refit(&self) -> bool {
        false
    }
    fn refit(&mut self, _frame: &SceneGeometry) -> Result<(), BuildError> {
        Err(BuildError::Unsupported {
            index: self.name.clone(),
            reason: "instances do not move; rebuild it".into(),
        })
    }
    fn closest_hit(&self, ray: &Ray) -> Option<Hit> {
        (self.top.closest_hit(ray)).map(|h| self.geometry.flattened(ray, h))
    }
    fn closest_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> Option<Hit> {
        (self.top.closest_hit_counted(ray, counters)).map(|h| self.geometry.flattened(ray, h))
    }
    fn any_hit(&self, ray: &Ray) -> bool {
        self.top.any_hit(ray)
    }
    fn any_hit_counted(&self, ray: &Ray, counters: &mut Counters) -> bool {
        self.top.any_hit_counted(ray, counters)
    }
    fn closest_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        self.top.closest_hits_in(mode, rays, out, counters);
        self.flatten(rays, out);
    }
    fn closest_hits_image(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        width: usize,
        out: &mut [Option<Hit>],
        counters: Option<&mut [Counters]>,
    ) {
        self.top
            .closest_hits_image(mode, rays, width, out, counters);
        self.flatten(rays, out);
    }
    fn any_hits_in(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        self.top.any_hits_in(mode, rays, out, counters);
    }
    fn any_hits_image(
        &self,
        mode: TraceMode,
        rays: &[Ray],
        width: usize,
        out: &mut [bool],
        counters: Option<&mut [Counters]>,
    ) {
        self.top.any_hits_image(mode, rays, width, out, counters);
    }
}
