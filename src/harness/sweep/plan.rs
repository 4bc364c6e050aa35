//! What a sweep of one index is ([`SweepPlan`]): its points, how its charts read
//! ([`SweepPlot`]), what its size column counts, and the default it is compared with.

use super::SweepPoint;

/// Titles, axis and marker of a sweep's charts.
#[derive(Debug, Clone, Default)]
pub struct SweepPlot {
    /// What was swept, for titles (`grid on stanford_bunny, primary rays`).
    pub title: String,
    pub x_label: String,
    pub log_x: bool,
    /// The default or heuristic choice `(x, label)`, drawn as a vertical line.
    pub marker: Option<(f64, String)>,
}

/// One index's sweep: the points to time and the charts to draw.
#[derive(Debug, Clone)]
pub struct SweepPlan {
    /// The index as progress lines name it (`grid`, `bvh`).
    pub index: String,
    /// What the structure's size counts (`cells`, `nodes`), for progress lines.
    pub size_label: &'static str,
    pub points: Vec<SweepPoint>,
    pub plot: SweepPlot,
    /// The spec of the default parameters, compared with the fastest point.
    pub default: String,
}
