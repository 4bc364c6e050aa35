//! The octree's sweep (either traversal of the same tree): one line per maximum depth, against
//! the leaf size.

use super::plan::crossed;
use super::{SweepPlan, SweepPlot};
use crate::index::{BuildError, IndexSpec, OctreeParams};
use crate::scene::Scene;

/// The plan of octree traversal `name` (`octree` or `octree-topdown`) on `scene` for a ray set
/// named `rays`: a point per pair of `max_depth` and `max_prims`.
pub fn octree_plan(
    scene: &Scene,
    rays: &str,
    name: &str,
    max_prims: &[u32],
    max_depth: &[u32],
) -> Result<SweepPlan, BuildError> {
    let d = OctreeParams::default();
    let points = crossed("max_depth", max_depth, max_prims, |depth, m| {
        format!("{name}:max_prims={m},max_depth={depth}")
    })?;
    let marker = format!(
        "default (max_prims={}, max_depth={})",
        d.max_prims, d.max_depth
    );
    let plot = SweepPlot::log_x(
        format!("{name} on {}, {rays} rays", scene.name),
        "max primitives per leaf",
        (d.max_prims as f64, marker),
    );
    let default: IndexSpec =
        format!("{name}:max_prims={},max_depth={}", d.max_prims, d.max_depth).parse()?;
    Ok(SweepPlan {
        index: name.into(),
        size_label: "nodes",
        points,
        plot,
        default: default.to_string(),
    })
}
