//! The two-level grid's sweep: one line per top-grid density, against the inner density.

use super::{SweepPlan, SweepPlot, SweepPoint};
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
    let mut points: Vec<SweepPoint> = Vec::new();
    for &top in top_lambda {
        for &l in lambda {
            points.push(SweepPoint {
                series: format!("top_lambda={top}"),
                x: l as f64,
                spec: format!("grid2:top_lambda={top},lambda={l}").parse()?,
            });
        }
    }
    let plot = SweepPlot {
        title: format!("grid2 on {}, {rays} rays", scene.name),
        x_label: "inner cells per primitive (lambda)".into(),
        log_x: true,
        marker: Some((
            d.lambda as f64,
            format!("default (top_lambda={}, lambda={})", d.top_lambda, d.lambda),
        )),
    };
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
