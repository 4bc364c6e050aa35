//! The grid's sweep: explicit cells along the longest axis (cubic cells) and cube-root
//! heuristic densities, both against cells along the longest axis.

use super::{SweepPlan, SweepPlot, SweepPoint};
use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::index::grid::{DEFAULT_LAMBDA, MAX_CELLS, heuristic_resolution, resolution};
use crate::scene::Scene;

/// The grid's plan on `scene` for a ray set named `rays`: a point per cells-along-the-longest-
/// axis `res` and per density `lambda`; when both are empty, 1/8 to 4 times the heuristic's
/// resolution (within [`MAX_CELLS`]) and densities 1 to 16.
pub fn grid_plan(
    scene: &Scene,
    rays: &str,
    res: &[u32],
    lambda: &[f32],
) -> Result<SweepPlan, BuildError> {
    let bounds = scene.bounds();
    let n = scene.len();
    let longest = bounds.largest_axis();
    let heuristic = heuristic_resolution(bounds.extent(), n, DEFAULT_LAMBDA)[longest];
    let (mut res, mut lambdas) = (res.to_vec(), lambda.to_vec());
    if res.is_empty() && lambdas.is_empty() {
        lambdas = vec![1.0, 2.0, 4.0, 8.0, 16.0];
        res = [0.125, 0.25, 0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|f| ((heuristic as f64 * f).round() as u32).max(1))
            .filter(|&r| resolution::total_cells(res_for_longest(&bounds, r)) <= MAX_CELLS)
            .collect();
        res.dedup();
    }
    let mut points: Vec<SweepPoint> = Vec::new();
    for &r in &res {
        let [x, y, z] = res_for_longest(&bounds, r);
        points.push(SweepPoint {
            series: "res (cubic cells)".into(),
            x: r as f64,
            spec: format!("grid:res=[{x},{y},{z}]").parse()?,
        });
    }
    for &l in &lambdas {
        points.push(SweepPoint {
            series: "lambda (heuristic)".into(),
            x: heuristic_resolution(bounds.extent(), n, l)[longest] as f64,
            spec: format!("grid:lambda={l}").parse()?,
        });
    }
    let plot = SweepPlot::log_x(
        format!("grid on {}, {rays} rays", scene.name),
        "cells along the longest axis",
        (
            heuristic as f64,
            format!("heuristic (lambda={DEFAULT_LAMBDA})"),
        ),
    );
    Ok(SweepPlan {
        index: "grid".into(),
        size_label: "cells",
        points,
        plot,
        default: format!("grid:lambda={DEFAULT_LAMBDA}"),
    })
}

/// Cells per axis for `r` cells along the longest axis of `bounds` (cubic cells, at least one
/// per axis).
fn res_for_longest(bounds: &Aabb, r: u32) -> [u32; 3] {
    let e = bounds.extent();
    let longest = e.max_element();
    if longest <= 0.0 {
        return [1; 3];
    }
    e.to_array()
        .map(|x| ((x / longest * r as f32).round() as u32).clamp(1, r))
}
