//! The two-level grid's sweep: one line per top-grid density, against the inner density.

use super::plan::{Crossed, Swept};
use crate::index::Grid2Params;

/// The two-level grid's sweep: a point per pair of `top_lambda` and inner `lambda`
/// ([`Crossed::plan`] makes the plan on a scene).
pub fn grid2_sweep<'a>(top_lambda: &'a [f32], lambda: &'a [f32]) -> Crossed<'a, f32, f32> {
    let d = Grid2Params::default();
    Crossed {
        index: "grid2",
        size_label: "cells",
        series: Swept::new("top_lambda", top_lambda, d.top_lambda),
        x: Swept::new("lambda", lambda, d.lambda),
        x_label: "inner cells per primitive (lambda)",
    }
}
