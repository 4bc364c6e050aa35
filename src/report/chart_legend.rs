//! Chart legends drawn beside the plot, never over the data: a column of coloured marks and
//! names in a strip to the right of the plotting area.

use super::ReportError;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// How an entry's mark looks: like its series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Mark {
    Dot,
    Line,
    Bar,
}

/// Width of the legend strip, in pixels.
pub(super) const LEGEND_WIDTH: u32 = 200;

/// Longest name drawn in full; longer ones end in `…`.
const MAX_CHARS: usize = 26;

/// Draws `entries` (name, colour, mark) top-down in `area` (the strip beside the plot).
pub(super) fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    entries: &[(String, RGBColor, Mark)],
    path: &Path,
) -> Result<(), ReportError> {
    let e = |e: DrawingAreaErrorKind<std::io::Error>| ReportError::Write {
        path: path.to_owned(),
        message: e.to_string(),
    };
    let (x0, y0, row) = (8, 60, 22);
    for (k, (name, col, mark)) in entries.iter().enumerate() {
        let y = y0 + row * k as i32;
        match mark {
            Mark::Dot => area.draw(&Circle::new((x0 + 9, y), 5, col.filled())),
            Mark::Line => area.draw(&PathElement::new(
                [(x0, y), (x0 + 18, y)],
                col.stroke_width(3),
            )),
            Mark::Bar => area.draw(&Rectangle::new(
                [(x0 + 2, y - 6), (x0 + 16, y + 6)],
                col.filled(),
            )),
        }
        .map_err(e)?;
        let text: String = match name.chars().count() > MAX_CHARS {
            true => name.chars().take(MAX_CHARS - 1).chain(['…']).collect(),
            false => name.clone(),
        };
        let style = ("sans-serif", 14).into_font().color(&BLACK);
        area.draw(&Text::new(text, (x0 + 26, y - 8), style))
            .map_err(e)?;
    }
    Ok(())
}
