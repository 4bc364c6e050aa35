//! What a sweep of one index is ([`SweepPlan`]): its points, how its charts read
//! ([`SweepPlot`]), what its size column counts, and the default it is compared with.

use super::SweepPoint;
use crate::index::{BuildError, IndexSpec};
use crate::scene::Scene;
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

/// One swept parameter of an index: its key in specs, the values to sweep and its default.
pub struct Swept<'a, T> {
    key: &'static str,
    values: &'a [T],
    default: T,
}

impl<'a, T> Swept<'a, T> {
    pub fn new(key: &'static str, values: &'a [T], default: T) -> Self {
        Swept {
            key,
            values,
            default,
        }
    }
}

/// A sweep of two parameters of `index`, crossed: a series per value of `series` (named
/// `{key}={value}`), along it a point per value of `x` at that x (a logarithmic axis labelled
/// `x_label`). The default parameters are the chart's marker and the comparison.
pub struct Crossed<'a, S, X> {
    pub index: &'a str,
    /// What the structure's size counts ([`SweepPlan::size_label`]).
    pub size_label: &'static str,
    pub series: Swept<'a, S>,
    pub x: Swept<'a, X>,
    pub x_label: &'static str,
}

impl<S: Copy + Display, X: Copy + Display + Into<f64>> Crossed<'_, S, X> {
    /// The plan on `scene` for a ray set named `rays`.
    pub fn plan(&self, scene: &Scene, rays: &str) -> Result<SweepPlan, BuildError> {
        let (series, x) = (&self.series, &self.x);
        let spec = |s: S, v: X| format!("{}:{}={s},{}={v}", self.index, series.key, x.key);
        let mut points = Vec::new();
        for &s in series.values {
            for &v in x.values {
                points.push(SweepPoint {
                    series: format!("{}={s}", series.key),
                    x: v.into(),
                    spec: spec(s, v).parse()?,
                });
            }
        }
        let marker = format!(
            "default ({}={}, {}={})",
            series.key, series.default, x.key, x.default
        );
        let plot = SweepPlot::log_x(
            format!("{} on {}, {rays} rays", self.index, scene.name),
            self.x_label,
            (x.default.into(), marker),
        );
        let default: IndexSpec = spec(series.default, x.default).parse()?;
        Ok(SweepPlan {
            index: self.index.into(),
            size_label: self.size_label,
            points,
            plot,
            default: default.to_string(),
        })
    }
}
