//! The two-level grid's sweep: one line per top-grid density, against the inner density.

use super::plan::crossed;
use super::{SweepPlan, SweepPlot};
use crate::index::{BuildError, Grid2Params, IndexSpec};
use crate::scene::Scene;

/// The two-level grid's plan on `scene` for a ray set named `rays`: a point per pair of
/// `top_lambda` and inner `lambda`.
pub fn grid2_plan(
    scene: &Scene,
    rays: &str,
    top_lambda: &[f32],
    lambda: &[f32],
) -> Result<SweepPlan, BuildError> {
    let d = Grid2Params::default();
    let points = crossed("top_lambda", top_lambda, lambda, |top, l| {
        format!("grid2:top_lambda={top},lambda={l}")
    })?;
    let marker = format!("default (top_lambda={}, lambda={})", d.top_lambda, d.lambda);
    let plot = SweepPlot::log_x(
        format!("grid2 on {}, {rays} rays", scene.name),
        "inner cells per primitive (lambda)",
        (d.lambda as f64, marker),
    );
    let default: IndexSpec =
        format!("grid2:top_lambda={},lambda={}", d.top_lambda, d.lambda).parse()?;
    Ok(SweepPlan {
        index: "grid2".into(),
        size_label: "cells",
        points,
        plot,
        default: default.to_string(),
    })
}
