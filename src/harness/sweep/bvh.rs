//! The BVHs' spatial-split sweep: one line per tree, against the split budget (references per
//! primitive).

use super::{SweepPlan, SweepPlot, SweepPoint};
use crate::index::{BuildError, BvhParams};
use crate::scene::Scene;

/// The plan of `trees` (`bvh`, `bvh4`, `bvh8`; at least one) with spatial splits on `scene`
/// for a ray set named `rays`: a point per tree and `split_budget`.
pub fn bvh_plan(
    scene: &Scene,
    rays: &str,
    trees: &[String],
    split_budget: &[f32],
) -> Result<SweepPlan, BuildError> {
    let spec = |tree: &str, b: f32| format!("{tree}:spatial_splits=true,split_budget={b}");
    let mut points: Vec<SweepPoint> = Vec::new();
    for tree in trees {
        for &b in split_budget {
            points.push(SweepPoint {
                series: tree.clone(),
                x: b as f64,
                spec: spec(tree, b).parse()?,
            });
        }
    }
    let default_budget = BvhParams::default().config()?.split_budget;
    let plot = SweepPlot::log_x(
        format!("spatial splits on {}, {rays} rays", scene.name),
        "references per primitive at most (split_budget)",
        (
            default_budget.into(),
            format!("default (split_budget={default_budget})"),
        ),
    );
    Ok(SweepPlan {
        index: "bvh".into(),
        size_label: "nodes",
        points,
        plot,
        default: spec(&trees[0], default_budget),
    })
}
