//! The octree's sweep (either traversal of the same tree): one line per maximum depth, against
//! the leaf size.

use super::{SweepPlan, SweepPlot, SweepPoint};
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
    let mut points: Vec<SweepPoint> = Vec::new();
    for &depth in max_depth {
        for &m in max_prims {
            points.push(SweepPoint {
                series: format!("max_depth={depth}"),
                x: m as f64,
                spec: format!("{name}:max_prims={m},max_depth={depth}").parse()?,
            });
        }
    }
    let plot = SweepPlot {
        title: format!("{name} on {}, {rays} rays", scene.name),
        x_label: "max primitives per leaf".into(),
        log_x: true,
        marker: Some((
            d.max_prims as f64,
            format!(
                "default (max_prims={}, max_depth={})",
                d.max_prims, d.max_depth
            ),
        )),
    };
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
