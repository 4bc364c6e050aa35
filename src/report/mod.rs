//! Report sinks shared by every command that writes results: CSV tables of `Serialize` rows and
//! SVG charts (line, grouped bar, labelled scatter). Plots are SVG so they need no fonts and
//! open in any browser.

pub mod animate_report;
mod chart;
mod chart_axes;
mod chart_legend;
pub mod cost_fit;
mod csv_out;
mod html;
mod html_sections;
pub mod merge;
pub mod report_dir;
pub mod results_page;
mod rows;
pub mod run_compare;
mod run_meta;
pub mod run_notes;
pub mod scale_report;
mod suite_plots;
pub mod suite_report;
pub mod sweep_report;
pub mod verdict;

pub use chart::{
    BarGroup, Chart, Series, bar_chart, line_chart, scatter_chart, scatter_chart_with_lines,
};
pub use csv_out::write_csv;
pub use rows::differing_peers;

use std::path::PathBuf;
use thiserror::Error;

/// Why a report file could not be written.
#[derive(Debug, Error)]
pub enum ReportError {
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
    #[error("cannot read {path}: {message}")]
    Read { path: PathBuf, message: String },
    #[error("cannot merge: {0}")]
    Merge(String),
    #[error("chart '{0}' has no finite data to draw")]
    NoData(String),
}

/// `v` with `digits` decimals, or an en dash when it is not finite (a table cell).
pub(crate) fn fixed(v: f64, digits: usize) -> String {
    if v.is_finite() {
        format!("{v:.digits$}")
    } else {
        "–".into()
    }
}
