//! What a sweep of one index is ([`SweepPlan`]): its points, how its charts read
//! ([`SweepPlot`]), what its size column counts, and the default it is compared with.

use super::SweepPoint;
use crate::index::BuildError;
use std::fmt::Display;

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

impl SweepPlot {
    /// A chart of `title` over a logarithmic x axis labelled `x_label`, with the default or
    /// heuristic choice `marker` `(x, label)` drawn as a vertical line.
    pub fn log_x(title: String, x_label: &str, marker: (f64, String)) -> SweepPlot {
        SweepPlot {
            title,
            x_label: x_label.into(),
            log_x: true,
            marker: Some(marker),
        }
    }
}

/// The points of a sweep over two parameters: a series per value `o` of `outer` (named
/// `{outer_name}={o}`), in it a point per value `i` of `inner` at `x = i`, of spec `spec(o, i)`.
pub(super) fn crossed<O: Copy + Display, I: Copy + Into<f64>>(
    outer_name: &str,
    outer: &[O],
    inner: &[I],
    spec: impl Fn(O, I) -> String,
) -> Result<Vec<SweepPoint>, BuildError> {
    let mut points = Vec::new();
    for &o in outer {
        for &i in inner {
            points.push(SweepPoint {
                series: format!("{outer_name}={o}"),
                x: i.into(),
                spec: spec(o, i).parse()?,
            });
        }
    }
    Ok(points)
}
