//! Report sinks shared by every command that writes results: CSV tables of `Serialize` rows and
//! SVG charts (line, grouped bar, labelled scatter). Plots are SVG so they need no fonts and
//! open in any browser.

mod chart;
mod csv_out;
mod run_meta;
pub mod scale_report;
mod suite_plots;
pub mod suite_report;
pub mod sweep_report;

pub use chart::{
    BarGroup, Chart, Series, bar_chart, line_chart, scatter_chart, scatter_chart_with_lines,
};
pub use csv_out::write_csv;

use std::path::PathBuf;
use thiserror::Error;

/// Why a report file could not be written.
#[derive(Debug, Error)]
pub enum ReportError {
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
    #[error("chart '{0}' has no finite data to draw")]
    NoData(String),
}
