//! `accelbench compare RUN_A RUN_B`: run B's speed over run A's per scene x index x ray set x
//! threads, with a noise estimate from each run's repeats, so a change can be told from noise
//! (and CI can fail on a slowdown).
//!
//! Noise: each row's 95% interval of its median speed (`mrays_ci_low`, `mrays_ci_high`;
//! `harness::median_interval`). A change is outside the noise when the two rows' intervals do
//! not overlap. Rows of reports written before the interval columns existed take the interval
//! `median * (1 -+ spread / median)` from their repeats' spread (max - min).

use super::ReportError;
use serde::Deserialize;
use std::fmt::Write as _;
use std::path::Path;

/// The fields of a `results.csv` row that a comparison reads (other columns are ignored, so
/// runs of other versions compare as long as these are there).
#[derive(Debug, Clone, Deserialize)]
pub struct TimedRow {
    pub scene: String,
    pub index: String,
    pub params: String,
    pub ray_set: String,
    pub threads: usize,
    pub trace_ms_median: f64,
    pub trace_ms_spread: f64,
    pub mrays_per_s: f64,
    #[serde(default = "nan")]
    pub mrays_ci_low: f64,
    #[serde(default = "nan")]
    pub mrays_ci_high: f64,
}

fn nan() -> f64 {
    f64::NAN
}

impl TimedRow {
    /// `scene / index [params] / ray set / N threads`: what identifies a row across runs.
    pub fn key(&self) -> String {
        format!(
            "{} / {} [{}] / {} / {} threads",
            self.scene, self.index, self.params, self.ray_set, self.threads
        )
    }

    /// The row's interval of Mrays/s: its own, or from its spread in older reports.
    fn interval(&self) -> (f64, f64) {
        if self.mrays_ci_low.is_finite() && self.mrays_ci_high.is_finite() {
            return (self.mrays_ci_low, self.mrays_ci_high);
        }
        let rel = self.trace_ms_spread / self.trace_ms_median;
        (
            self.mrays_per_s * (1.0 - rel),
            self.mrays_per_s * (1.0 + rel),
        )
    }
}

/// One row present in both runs.
#[derive(Debug, Clone)]
pub struct Change {
    pub key: String,
    pub a_mrays: f64,
    pub b_mrays: f64,
    /// The rows' intervals of Mrays/s, `(low, high)`.
    pub a_interval: (f64, f64),
    pub b_interval: (f64, f64),
}

impl Change {
    /// B's speed over A's (above 1: B is faster).
    pub fn ratio(&self) -> f64 {
        self.b_mrays / self.a_mrays
    }

    /// How much longer B takes than A, in percent (negative when B is faster).
    pub fn slower_pct(&self) -> f64 {
        (self.a_mrays / self.b_mrays - 1.0) * 100.0
    }

    /// The wider of the two intervals, relative to its median (a fraction).
    pub fn noise(&self) -> f64 {
        let rel = |(lo, hi): (f64, f64), m: f64| (hi - lo) / m;
        rel(self.a_interval, self.a_mrays).max(rel(self.b_interval, self.b_mrays))
    }

    /// Whether the two intervals are apart.
    pub fn outside_noise(&self) -> bool {
        self.a_interval.1 < self.b_interval.0 || self.b_interval.1 < self.a_interval.0
    }

    /// Slower by more than `pct` percent and by more than the noise.
    pub fn fails(&self, pct: f64) -> bool {
        self.slower_pct() > pct && self.outside_noise()
    }
}

/// The comparison of two runs.
#[derive(Debug, Clone, Default)]
pub struct Comparison {
    /// Rows in both runs with finite speeds, in A's order.
    pub changes: Vec<Change>,
    /// Rows of A that B lacks, and rows in both without a finite speed in one of them.
    pub missing_in_b: Vec<String>,
    /// Rows of B that A lacks.
    pub new_in_b: Vec<String>,
}

/// Reads `results.csv` of a report folder (or the CSV file itself).
pub fn load_timed_rows(run: &Path) -> Result<Vec<TimedRow>, ReportError> {
    let path = if run.is_dir() {
        run.join("results.csv")
    } else {
        run.to_owned()
    };
    let err = |message: String| ReportError::Read {
        path: path.clone(),
        message,
    };
    let mut r = csv::Reader::from_path(&path).map_err(|e| {
        err(format!(
            "{e}; give a report folder of `accelbench run` (with results.csv) or the CSV file"
        ))
    })?;
    r.deserialize()
        .enumerate()
        .map(|(i, row)| row.map_err(|e| err(format!("row {}: {e}", i + 1))))
        .collect()
}

/// Compares run B with run A row by row.
pub fn compare_runs(a: &[TimedRow], b: &[TimedRow]) -> Comparison {
    let mut c = Comparison::default();
    for ra in a {
        let key = ra.key();
        match b.iter().find(|rb| rb.key() == key) {
            Some(rb) if ra.mrays_per_s.is_finite() && rb.mrays_per_s.is_finite() => {
                c.changes.push(Change {
                    a_interval: ra.interval(),
                    b_interval: rb.interval(),
                    key,
                    a_mrays: ra.mrays_per_s,
                    b_mrays: rb.mrays_per_s,
                })
            }
            Some(_) => c.missing_in_b.push(format!("{key} (not timed in one run)")),
            None => c.missing_in_b.push(key),
        }
    }
    for rb in b {
        let key = rb.key();
        if !a.iter().any(|ra| ra.key() == key) {
            c.new_in_b.push(key);
        }
    }
    c
}

/// The comparison as a text table: a line per row with both speeds, B/A, the noise and a mark
/// (`faster`, `slower`, `~` within the noise, `FAIL` over `fail_above` percent slower), then
/// the missing and new rows.
pub fn comparison_text(c: &Comparison, fail_above: Option<f64>) -> String {
    let w = c
        .changes
        .iter()
        .map(|x| x.key.len())
        .max()
        .unwrap_or(3)
        .max(3);
    let mut s = format!(
        "{:w$}  {:>10}  {:>10}  {:>6}  {:>7}  change\n",
        "row", "A Mrays/s", "B Mrays/s", "B/A", "noise"
    );
    for x in &c.changes {
        let mark = match (fail_above.is_some_and(|p| x.fails(p)), x.outside_noise()) {
            (true, _) => format!("FAIL: {:.0}% slower", x.slower_pct()),
            (false, false) => "~ (within noise)".into(),
            (false, true) if x.ratio() > 1.0 => format!("faster ({:.0}%)", -x.slower_pct()),
            (false, true) => format!("slower ({:.0}%)", x.slower_pct()),
        };
        let _ = writeln!(
            s,
            "{:w$}  {:>10.3}  {:>10.3}  {:>6.3}  {:>6.1}%  {mark}",
            x.key,
            x.a_mrays,
            x.b_mrays,
            x.ratio(),
            x.noise() * 100.0
        );
    }
    for (title, keys) in [
        ("Rows of A missing in B", &c.missing_in_b),
        ("Rows of B not in A", &c.new_in_b),
    ] {
        if !keys.is_empty() {
            let _ = writeln!(s, "\n{title} ({}):", keys.len());
            for k in keys {
                let _ = writeln!(s, "  {k}");
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row of an older report (no interval columns): the interval comes from the spread.
    fn row(scene: &str, threads: usize, ms: f64, spread: f64) -> TimedRow {
        TimedRow {
            mrays_ci_low: f64::NAN,
            mrays_ci_high: f64::NAN,
            scene: scene.into(),
            index: "bvh".into(),
            params: "p".into(),
            ray_set: "primary".into(),
            threads,
            trace_ms_median: ms,
            trace_ms_spread: spread,
            mrays_per_s: 10.0 / ms,
        }
    }

    #[test]
    fn marks_changes_against_the_noise() {
        let a = [
            row("s", 1, 10.0, 0.5),
            row("s", 2, 5.0, 0.1),
            row("t", 1, 1.0, 0.0),
        ];
        let b = [
            row("s", 1, 10.3, 0.5),
            row("s", 2, 10.0, 0.1),
            row("u", 1, 1.0, 0.0),
        ];
        let c = compare_runs(&a, &b);
        assert_eq!(c.changes.len(), 2);
        let (same, slow) = (&c.changes[0], &c.changes[1]);
        assert!(
            !same.outside_noise() && !same.fails(1.0),
            "3% within 5% noise"
        );
        // With interval columns, the intervals decide: apart is a change, overlapping is not.
        let with = |ms: f64, lo: f64, hi: f64| TimedRow {
            mrays_ci_low: lo,
            mrays_ci_high: hi,
            ..row("s", 1, ms, 0.0)
        };
        let apart = compare_runs(&[with(10.0, 0.9, 1.1)], &[with(10.5, 0.8, 0.89)]);
        assert!(apart.changes[0].outside_noise() && apart.changes[0].fails(1.0));
        let overlap = compare_runs(&[with(10.0, 0.9, 1.1)], &[with(12.0, 0.8, 0.95)]);
        assert!(!overlap.changes[0].outside_noise() && !overlap.changes[0].fails(1.0));
        assert!((slow.slower_pct() - 100.0).abs() < 1e-9 && slow.fails(50.0));
        assert!(!slow.fails(150.0));
        assert_eq!(c.missing_in_b, [a[2].key()]);
        assert_eq!(c.new_in_b, [b[2].key()]);
        let text = comparison_text(&c, Some(50.0));
        assert!(text.contains("FAIL: 100% slower") && text.contains("~ (within noise)"));
        assert!(
            text.contains("missing in B (1)") && text.contains("u / bvh"),
            "{text}"
        );
    }
}
