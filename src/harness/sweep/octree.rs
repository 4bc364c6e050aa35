//! The octree's sweep (either traversal of the same tree): one line per maximum depth, against
//! the leaf size.

use super::plan::{Crossed, Swept};
use crate::index::OctreeParams;

/// The sweep of octree traversal `name` (`octree` or `octree-topdown`): a point per pair of
/// `max_depth` and `max_prims` ([`Crossed::plan`] makes the plan on a scene).
pub fn octree_sweep<'a>(
    name: &'a str,
    max_prims: &'a [u32],
    max_depth: &'a [u32],
) -> Crossed<'a, u32, u32> {
    let d = OctreeParams::default();
    // The defaults (16 primitives, depth 10) are far within `u32`, the sweep values' type.
    Crossed {
        index: name,
        size_label: "nodes",
        series: Swept::new("max_depth", max_depth, d.max_depth as u32),
        x: Swept::new("max_prims", max_prims, d.max_prims as u32),
        x_label: "max primitives per leaf",
    }
}
