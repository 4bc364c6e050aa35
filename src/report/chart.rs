//! SVG charts with plotters: lines (sweeps, scaling), grouped bars (per scene and index) and
//! labelled scatter plots (time against error).
//!
//! Log axes are drawn by plotting `log10(v)` on a linear axis and labelling ticks with `10^v`, so
//! one code path serves every axis combination; ticks sit at round values (`chart_axes`). Values
//! that cannot be drawn (NaN, infinite, or `<= 0` on a log axis) are left out. Legends are drawn
//! in a strip beside the plot, never over the data (`chart_legend`).

use super::ReportError;
use super::chart_axes::{axis_value, padded, tick_label, ticked};
use super::chart_legend::{LEGEND_WIDTH, Mark, draw_legend};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor;
use std::path::Path;

/// One named line (or point set) of `(x, y)` values; `labels`, when not empty, names each point
/// (scatter charts draw them beside the points).
#[derive(Debug, Clone, Default)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub labels: Vec<String>,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            labels: Vec::new(),
        }
    }
}

/// Titles and axes of a chart.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    /// Vertical marker lines `(x, label)`, e.g. a heuristic's choice in a sweep.
    pub markers: Vec<(f64, String)>,
}

impl Chart {
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: &str) -> Chart {
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.to_owned(),
            ..Chart::default()
        }
    }
}

/// One category of a bar chart (e.g. a scene) with one bar per series (e.g. an index).
#[derive(Debug, Clone)]
pub struct BarGroup {
    pub name: String,
    pub bars: Vec<(String, f64)>,
}

/// The whole chart, legend strip included, in pixels.
const SIZE: (u32, u32) = (1100, 600);

fn color(i: usize) -> RGBColor {
    const C: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    C[i % C.len()]
}

fn write_err(path: &Path, e: impl std::fmt::Display) -> ReportError {
    ReportError::Write {
        path: path.to_owned(),
        message: e.to_string(),
    }
}

fn create_root(path: &Path) -> Result<DrawingArea<SVGBackend<'_>, Shift>, ReportError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| write_err(path, e))?;
    }
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| write_err(path, e))?;
    Ok(root)
}

/// A chart on `plot` with the title, margins and axis label areas every chart uses (`x_labels`
/// pixels below the plot for the x axis's labels).
fn frame<'a, DB: DrawingBackend>(
    plot: &'a DrawingArea<DB, Shift>,
    chart: &Chart,
    x_labels: u32,
) -> ChartBuilder<'a, 'a, DB> {
    let mut b = ChartBuilder::on(plot);
    b.caption(&chart.title, ("sans-serif", 22))
        .margin(14)
        .x_label_area_size(x_labels)
        .y_label_area_size(72);
    b
}

/// The transformed, drawable points of each series.
fn drawable(chart: &Chart, series: &[Series]) -> Vec<Vec<(f64, f64, usize)>> {
    series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .enumerate()
                .filter_map(|(i, &(x, y))| {
                    Some((axis_value(x, chart.log_x)?, axis_value(y, chart.log_y)?, i))
                })
                .collect()
        })
        .collect()
}

/// Lines with point markers, one per series, plus the chart's vertical markers.
pub fn line_chart(path: &Path, chart: &Chart, series: &[Series]) -> Result<(), ReportError> {
    xy_chart(path, chart, series, 0)
}

/// Points only, each labelled with its series' `labels` when given.
pub fn scatter_chart(path: &Path, chart: &Chart, series: &[Series]) -> Result<(), ReportError> {
    xy_chart(path, chart, series, series.len())
}

/// A scatter chart of `points` with `lines` drawn over it as lines (e.g. a Pareto front).
pub fn scatter_chart_with_lines(
    path: &Path,
    chart: &Chart,
    points: &[Series],
    lines: &[Series],
) -> Result<(), ReportError> {
    let all: Vec<Series> = points.iter().chain(lines).cloned().collect();
    xy_chart(path, chart, &all, points.len())
}

/// Series `first_line..` are drawn as lines with markers, the ones before as points.
fn xy_chart(
    path: &Path,
    chart: &Chart,
    series: &[Series],
    first_line: usize,
) -> Result<(), ReportError> {
    let pts = drawable(chart, series);
    let all = || pts.iter().flatten();
    if all().next().is_none() {
        return Err(ReportError::NoData(chart.title.clone()));
    }
    let markers: Vec<(f64, &str)> = chart
        .markers
        .iter()
        .filter_map(|(x, l)| Some((axis_value(*x, chart.log_x)?, l.as_str())))
        .collect();
    let xs = all().map(|p| p.0).chain(markers.iter().map(|m| m.0));
    let (x_lo, x_hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let (y_lo, y_hi) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let y_range = if chart.log_y {
        padded(y_lo, y_hi)
    } else {
        padded(y_lo.min(0.0), y_hi)
    };
    let mut x_range = padded(x_lo, x_hi);
    if series.iter().any(|s| !s.labels.is_empty()) {
        // Room for the labels, which are written to the right of their points.
        x_range.end += (x_range.end - x_range.start) * 0.12;
    }
    let root = create_root(path)?;
    let (plot, legend) = root.split_horizontally(SIZE.0 - LEGEND_WIDTH);
    let e = |e| write_err(path, e);
    let mut c = frame(&plot, chart, 46)
        .build_cartesian_2d(
            ticked(x_range, chart.log_x),
            ticked(y_range.clone(), chart.log_y),
        )
        .map_err(e)?;
    let mut entries = Vec::new();
    let (lx, ly) = (chart.log_x, chart.log_y);
    let fx = move |v: &f64| tick_label(*v, lx);
    let fy = move |v: &f64| tick_label(*v, ly);
    c.configure_mesh()
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    for (x, label) in &markers {
        let style = ShapeStyle::from(&BLACK.mix(0.6)).stroke_width(2);
        c.draw_series(LineSeries::new(
            [(*x, y_range.start), (*x, y_range.end)],
            style,
        ))
        .map_err(e)?;
        entries.push((label.to_string(), RGBColor(100, 100, 100), Mark::Line));
    }
    for (i, (s, p)) in series.iter().zip(&pts).enumerate() {
        let col = color(i);
        let xy: Vec<(f64, f64)> = p.iter().map(|&(x, y, _)| (x, y)).collect();
        if i >= first_line {
            c.draw_series(LineSeries::new(xy.clone(), col.stroke_width(2)))
                .map_err(e)?;
            c.draw_series(xy.iter().map(|&q| Circle::new(q, 3, col.filled())))
                .map_err(e)?;
            entries.push((s.name.clone(), col, Mark::Line));
        } else {
            c.draw_series(xy.iter().map(|&q| Circle::new(q, 5, col.filled())))
                .map_err(e)?;
            entries.push((s.name.clone(), col, Mark::Dot));
        }
        if !s.labels.is_empty() {
            c.draw_series(p.iter().filter_map(|&(x, y, k)| {
                let text = s.labels.get(k)?.clone();
                Some(Text::new(text, (x, y), ("sans-serif", 12).into_font()))
            }))
            .map_err(e)?;
        }
    }
    draw_legend(&legend, &entries, path)?;
    root.present().map_err(e)
}

/// Grouped bars: one group per category on the x axis, one coloured bar per series name (the
/// same name keeps the same colour in every group). `chart.log_y` gives a log value axis.
pub fn bar_chart(path: &Path, chart: &Chart, groups: &[BarGroup]) -> Result<(), ReportError> {
    let mut names: Vec<&str> = Vec::new();
    for g in groups {
        for (n, _) in &g.bars {
            if !names.contains(&n.as_str()) {
                names.push(n);
            }
        }
    }
    let vals = || {
        groups
            .iter()
            .flat_map(|g| g.bars.iter().filter_map(|b| axis_value(b.1, chart.log_y)))
    };
    let (lo, hi) = vals().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if !lo.is_finite() {
        return Err(ReportError::NoData(chart.title.clone()));
    }
    // Bars grow from the bottom of the axis (0 on a linear axis, a power of ten on a log axis).
    let y_range = if chart.log_y {
        let r = padded(lo, hi);
        r.start.floor()..r.end
    } else {
        padded(lo.min(0.0), hi)
    };
    let base = if chart.log_y { y_range.start } else { 0.0 };
    let root = create_root(path)?;
    let (plot, legend) = root.split_horizontally(SIZE.0 - LEGEND_WIDTH);
    let e = |e| write_err(path, e);
    let mut c = frame(&plot, chart, 70)
        .build_cartesian_2d(0.0..groups.len() as f64, ticked(y_range, chart.log_y))
        .map_err(e)?;
    let ly = chart.log_y;
    let fy = move |v: &f64| tick_label(*v, ly);
    c.configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc(chart.y_label.as_str())
        .x_desc(chart.x_label.as_str())
        .y_label_formatter(&fy)
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(e)?;
    let w = 0.8 / names.len().max(1) as f64;
    for (si, name) in names.iter().enumerate() {
        let col = color(si);
        let rects = groups.iter().enumerate().filter_map(|(gi, g)| {
            let v = g.bars.iter().find(|b| b.0 == *name)?.1;
            let v = axis_value(v, chart.log_y)?;
            let x0 = gi as f64 + 0.1 + si as f64 * w;
            Some(Rectangle::new(
                [(x0, base), (x0 + w * 0.9, v)],
                col.filled(),
            ))
        });
        c.draw_series(rects).map_err(e)?;
    }
    let entries: Vec<_> = (names.iter().enumerate())
        .map(|(si, n)| (n.to_string(), color(si), Mark::Bar))
        .collect();
    draw_legend(&legend, &entries, path)?;
    // Category names under their groups, in pixel coordinates below the axis.
    let style = ("sans-serif", 13)
        .into_font()
        .color(&BLACK)
        .pos(text_anchor::Pos::new(
            text_anchor::HPos::Center,
            text_anchor::VPos::Top,
        ));
    let bottom = c.backend_coord(&(0.0, base)).1 + 8;
    for (gi, g) in groups.iter().enumerate() {
        let x = c.backend_coord(&(gi as f64 + 0.5, base)).0;
        plot.draw(&Text::new(g.name.clone(), (x, bottom), style.clone()))
            .map_err(e)?;
    }
    root.present().map_err(e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn charts_write_svg_and_refuse_empty_data() {
        let dir = tempfile::tempdir().unwrap();
        let mut chart = Chart::new("t", "x", "y");
        chart.log_x = true;
        chart.markers.push((10.0, "heuristic".into()));
        let s = [Series::new(
            "a",
            vec![(1.0, 2.0), (10.0, 3.0), (100.0, 1.0)],
        )];
        line_chart(&dir.path().join("l.svg"), &chart, &s).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("l.svg")).unwrap();
        assert!(svg.contains("<svg") && svg.contains("heuristic"));
        let mut labelled = s[0].clone();
        labelled.labels = vec!["p".into(), "q".into(), "r".into()];
        scatter_chart(&dir.path().join("s.svg"), &chart, &[labelled.clone()]).unwrap();
        scatter_chart_with_lines(&dir.path().join("f.svg"), &chart, &[labelled], &s).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("f.svg")).unwrap();
        assert!(
            svg.contains("<polyline") || svg.contains("<path"),
            "a line is drawn"
        );
        let groups = [
            BarGroup {
                name: "scene1".into(),
                bars: vec![("bvh".into(), 3.0), ("grid".into(), 1.0)],
            },
            BarGroup {
                name: "scene2".into(),
                bars: vec![("grid".into(), 2.0)],
            },
        ];
        bar_chart(&dir.path().join("b.svg"), &chart, &groups).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("b.svg")).unwrap();
        assert!(svg.contains("scene2") && svg.contains("bvh"));
        let empty = [Series::new("a", vec![(-1.0, f64::NAN)])];
        assert!(matches!(
            line_chart(&dir.path().join("e.svg"), &chart, &empty),
            Err(ReportError::NoData(_))
        ));
    }
}
