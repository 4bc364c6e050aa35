//! Files of `accelbench accuracy`: `accuracy.csv`, `watertight.csv`, the time-against-error
//! scatter plot with its Pareto front, the leak-rate-against-offset plot and `accuracy.md`.

use super::families::Family;
use super::metrics::rate;
use super::study::{AccuracyRow, Kernel, Precision};
use super::watertight::LeakRow;
use crate::report::{Chart, ReportError, Series, line_chart, scatter_chart_with_lines, write_csv};
use std::fmt::Write as _;
use std::path::Path;

/// Errors below this are drawn at it on the log axis (an exact result has error 0).
pub const ERROR_FLOOR: f64 = 1e-18;

/// One point of the time-against-error plot: a kernel in one precision on one family.
#[derive(Debug, Clone, PartialEq)]
pub struct TradeOff {
    pub kernel: Kernel,
    pub precision: Precision,
    pub family: Family,
    pub ns_per_test: f64,
    /// Mean over offsets of the mean relative `t` error.
    pub error: f64,
}

/// A plot's points, in row order: one per kernel, precision and family, of the shape kernels
/// (`shapes`) or of the triangle and sphere kernels.
pub fn trade_offs(rows: &[AccuracyRow], shapes: bool) -> Vec<TradeOff> {
    let rows: Vec<&AccuracyRow> = rows
        .iter()
        .filter(|r| r.kernel.is_shape() == shapes)
        .collect();
    let mut out: Vec<TradeOff> = Vec::new();
    for r in &rows {
        let key = (r.kernel, r.precision, r.family);
        if out.iter().any(|p| (p.kernel, p.precision, p.family) == key) {
            continue;
        }
        let same: Vec<&&AccuracyRow> = rows
            .iter()
            .filter(|q| (q.kernel, q.precision, q.family) == key)
            .collect();
        out.push(TradeOff {
            kernel: r.kernel,
            precision: r.precision,
            family: r.family,
            ns_per_test: r.ns_per_test,
            error: same.iter().map(|q| q.mean_rel_t_error).sum::<f64>() / same.len() as f64,
        });
    }
    out
}

/// Indices of the points no other point beats in both time and error (an exact duplicate of a
/// front point is left out),
/// sorted by time.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    idx.sort_by(|&a, &b| points[a].partial_cmp(&points[b]).unwrap());
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for i in idx {
        if points[i].1 < best {
            best = points[i].1;
            front.push(i);
        }
    }
    front
}

/// Writes every accuracy file into `dir`.
pub fn write_all(dir: &Path, rows: &[AccuracyRow], leaks: &[LeakRow]) -> Result<(), ReportError> {
    write_csv(&dir.join("accuracy.csv"), rows)?;
    write_csv(&dir.join("watertight.csv"), leaks)?;
    time_vs_error_chart(&dir.join("time_vs_error.svg"), rows)?;
    if rows.iter().any(|r| r.kernel.is_shape()) {
        shape_time_vs_error_chart(&dir.join("shapes_time_vs_error.svg"), rows)?;
    }
    leak_chart(&dir.join("leaks_vs_offset.svg"), rows)?;
    let md = markdown(rows, leaks);
    std::fs::write(dir.join("accuracy.md"), md).map_err(|e| ReportError::Write {
        path: dir.join("accuracy.md"),
        message: e.to_string(),
    })
}

fn label(k: Kernel, p: Precision) -> String {
    format!("{} {}", k.name(), p.name())
}

/// One series per family, each point labelled by kernel (and precision).
fn family_series(pts: &[TradeOff], families: &[Family], precision_in_label: bool) -> Vec<Series> {
    families
        .iter()
        .map(|&f| {
            let mine: Vec<&TradeOff> = pts.iter().filter(|p| p.family == f).collect();
            Series {
                name: f.name().to_owned(),
                points: mine
                    .iter()
                    .map(|p| (p.ns_per_test, p.error.max(ERROR_FLOOR)))
                    .collect(),
                labels: mine
                    .iter()
                    .map(|p| match precision_in_label {
                        true => label(p.kernel, p.precision),
                        false => p.kernel.name().to_owned(),
                    })
                    .collect(),
            }
        })
        .collect()
}

/// Log-log scatter: one series per family for the triangle and sphere kernels, points labelled
/// by kernel and precision, and the Pareto fronts (triangle kernels, sphere kernels) as lines.
pub fn time_vs_error_chart(path: &Path, rows: &[AccuracyRow]) -> Result<(), ReportError> {
    let pts = trade_offs(rows, false);
    let xy: Vec<(f64, f64)> = pts
        .iter()
        .map(|p| (p.ns_per_test, p.error.max(ERROR_FLOOR)))
        .collect();
    let series = family_series(&pts, &Family::MESH, true);
    // Triangle and sphere kernels are measured on different primitives: one front each (the
    // shapes are all different primitives, so they get none).
    let fronts: Vec<Series> = [("triangles", false), ("spheres", true)]
        .iter()
        .map(|&(name, spheres)| {
            let mine: Vec<usize> = (0..pts.len())
                .filter(|&i| pts[i].kernel.is_sphere() == spheres)
                .collect();
            let sub: Vec<(f64, f64)> = mine.iter().map(|&i| xy[i]).collect();
            Series::new(
                format!("Pareto front ({name})"),
                pareto_front(&sub).into_iter().map(|i| sub[i]).collect(),
            )
        })
        .collect();
    let chart = time_vs_error_axes("Ray-primitive kernels: time against error");
    scatter_chart_with_lines(path, &chart, &series, &fronts)
}

/// A log-log chart of ns per test (x) against the mean relative `t` error (y).
fn time_vs_error_axes(title: &str) -> Chart {
    let mut chart = Chart::new(
        title,
        "ns per primitive test (single thread, best of repeats)",
        "mean relative t error (0 drawn at 1e-18)",
    );
    chart.log_x = true;
    chart.log_y = true;
    chart
}

/// Log-log scatter of the shape kernels (`f32` against their `f64` mirrors): one series per
/// family, points labelled by kernel. No Pareto front: every shape is a different primitive.
pub fn shape_time_vs_error_chart(path: &Path, rows: &[AccuracyRow]) -> Result<(), ReportError> {
    let pts = trade_offs(rows, true);
    let series = family_series(&pts, &Family::ALL, false);
    let chart = time_vs_error_axes("Shape kernels (f32 against an f64 mirror): time against error");
    scatter_chart_with_lines(path, &chart, &series, &[])
}

/// False-miss (leak) rate of each triangle kernel against the offset, rays from inside the
/// closed mesh aimed at its shared vertices and edges.
pub fn leak_chart(path: &Path, rows: &[AccuracyRow]) -> Result<(), ReportError> {
    let mut series: Vec<Series> = Vec::new();
    for k in Kernel::ALL.into_iter().filter(|k| k.is_triangle()) {
        for p in [Precision::F32, Precision::F64] {
            let points = rows
                .iter()
                .filter(|r| r.kernel == k && r.precision == p && r.family == Family::EdgesInside)
                .map(|r| (r.offset.max(0.1), r.false_miss_rate))
                .collect::<Vec<_>>();
            if !points.is_empty() {
                series.push(Series::new(label(k, p), points));
            }
        }
    }
    let mut chart = Chart::new(
        "Leaks through shared edges and vertices (rays from inside)",
        "offset from the origin (0 drawn at 0.1)",
        "false-miss rate",
    );
    chart.log_x = true;
    line_chart(path, &chart, &series)
}

/// The measured figures per kernel and precision (pooled over offsets and families), and the
/// watertightness table.
pub fn markdown(rows: &[AccuracyRow], leaks: &[LeakRow]) -> String {
    let mut s = String::from(
        "# Kernel accuracy\n\nPooled over families and offsets; rates against the exact \
         reference (exact edge-function signs, double-double t) for triangles and spheres, \
         against the f64 mirror of each kernel for the shapes (rays whose mirror decision lies \
         within its rounding bound are unverifiable and left out). A primitive other than the \
         reference's is wrong unless its exact t ties the reference's (to 1e-12 relative, or, \
         for an f32 kernel, rounding to the same f32, where the suite's lowest-id rule \
         decides).\n\n\
         | kernel | precision | rays | unverifiable | false-miss rate | false-hit rate | \
         wrong-primitive rate | max rel t error | mean rel t error | ns/test (random) |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for k in Kernel::ALL {
        for p in [Precision::F32, Precision::F64] {
            let mine: Vec<&AccuracyRow> = rows
                .iter()
                .filter(|r| r.kernel == k && r.precision == p)
                .collect();
            if mine.is_empty() {
                continue;
            }
            let ns = mine
                .iter()
                .find(|r| r.family == Family::Random)
                .map_or(f64::NAN, |r| r.ns_per_test);
            pooled_line(&mut s, [k.name(), p.name()], &mine, true, ns);
        }
    }
    fallback_table(&mut s, rows);
    shape_table(&mut s, rows);
    s.push_str(
        "\n# Watertightness (rays from inside closed meshes)\n\n\
         | mesh | offset | kernel | index | rays | misses | miss rate | aimed rays | aimed misses |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for l in leaks {
        let _ = writeln!(
            s,
            "| {} | {:e} | {} | {} | {} | {} | {:.3e} | {} | {} |",
            l.mesh,
            l.offset,
            l.kernel,
            l.index,
            l.rays,
            l.misses,
            l.miss_rate,
            l.aimed_rays,
            l.aimed_misses
        );
    }
    s
}

/// The exact kernel's wrong decisions and fallback rate per family (pooled over offsets).
fn fallback_table(s: &mut String, rows: &[AccuracyRow]) {
    s.push_str(
        "\n# Exact kernel per family\n\nWrong decisions (false misses + false hits + wrong \
         primitives) and the share of edge functions decided by the exact fallback.\n\n\
         | family | rays | wrong decisions | exact fallback rate |\n|---|---|---|---|\n",
    );
    for family in Family::MESH {
        let mine: Vec<&AccuracyRow> = rows
            .iter()
            .filter(|r| r.kernel == Kernel::Exact && r.family == family)
            .collect();
        if mine.is_empty() {
            continue;
        }
        let rays: usize = mine.iter().map(|r| r.rays).sum();
        let wrong: usize = mine
            .iter()
            .map(|r| r.false_misses + r.false_hits + r.wrong_primitives)
            .sum();
        let rate = mine.iter().map(|r| r.exact_fallback_rate).sum::<f64>() / mine.len() as f64;
        let _ = writeln!(s, "| {} | {rays} | {wrong} | {rate:.3e} |", family.name());
    }
}

/// The shape kernels per family (pooled over offsets).
fn shape_table(s: &mut String, rows: &[AccuracyRow]) {
    if !rows.iter().any(|r| r.kernel.is_shape()) {
        return;
    }
    s.push_str(
        "\n# Shape kernels per family (f32 against the f64 mirror, pooled over offsets)\n\n\
         | kernel | family | rays | unverifiable | false-miss rate | false-hit rate | \
         max rel t error | mean rel t error | ns/test |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for k in Kernel::SHAPES {
        for f in Family::ALL {
            let mine: Vec<&AccuracyRow> = rows
                .iter()
                .filter(|r| r.kernel == k && r.family == f)
                .collect();
            let Some(first) = mine.first() else {
                continue;
            };
            pooled_line(s, [k.name(), f.name()], &mine, false, first.ns_per_test);
        }
    }
}

/// Appends the table line `| a | b | rays | unverifiable | false-miss rate | false-hit rate |
/// [wrong-primitive rate |] max rel t error | mean rel t error | ns |` for `rows` pooled: counts
/// summed, rates over the pooled reference hits (misses for false hits), the largest and the
/// mean of the rows' `t` errors.
fn pooled_line(s: &mut String, [a, b]: [&str; 2], rows: &[&AccuracyRow], wrong: bool, ns: f64) {
    let sum = |f: fn(&AccuracyRow) -> usize| rows.iter().map(|r| f(r)).sum::<usize>();
    let hits = sum(|r| r.reference_hits);
    let misses = sum(|r| r.rays - r.unverifiable - r.reference_hits);
    let (rays, unverifiable) = (sum(|r| r.rays), sum(|r| r.unverifiable));
    let _ = write!(s, "| {a} | {b} | {rays} | {unverifiable} | ");
    let _ = write!(s, "{:.3e} | ", rate(sum(|r| r.false_misses), hits));
    let _ = write!(s, "{:.3e} | ", rate(sum(|r| r.false_hits), misses));
    if wrong {
        let _ = write!(s, "{:.3e} | ", rate(sum(|r| r.wrong_primitives), hits));
    }
    let max_err = rows.iter().map(|r| r.max_rel_t_error).fold(0.0, f64::max);
    let mean_err = rows.iter().map(|r| r.mean_rel_t_error).sum::<f64>() / rows.len() as f64;
    let _ = writeln!(s, "{max_err:.3e} | {mean_err:.3e} | {ns:.2} |");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pareto_front_keeps_only_undominated_points() {
        let pts = [
            (1.0, 5.0),
            (2.0, 1.0),
            (3.0, 2.0),
            (0.5, 9.0),
            (4.0, 0.5),
            (2.0, 1.0),
        ];
        assert_eq!(pareto_front(&pts), vec![3, 0, 1, 4]);
        assert!(pareto_front(&[(f64::NAN, 1.0)]).is_empty());
    }
}
