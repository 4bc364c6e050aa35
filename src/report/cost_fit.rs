//! The cost breakdown of an index: time per node step and time per primitive test, fitted by
//! least squares over the run's scenes and ray sets.
//!
//! Model, one point per (scene, ray set) of the index at the fewest threads:
//! `ns per ray = a * steps per ray + b * tests per ray + c`, where `ns per ray` is the timed
//! pass's median thread time per ray (median wall time x threads / rays) and the counts come
//! from the counting pass. `a` (ns per node step) and `b` (ns per primitive test) say whether an
//! index is slower because it takes more steps or because each step costs more; `c` (ns per ray)
//! is the fixed cost of a ray (setup, the batch loop), fitted only with at least six points.
//! Costs are kept non-negative (a coefficient that would come out negative is 0). A count that
//! is zero at every point (brute force takes no node steps) leaves its coefficient out (NaN).
//! Counts that move together over the points (a tree whose steps grow with its tests) make the
//! split uncertain; `r2` and `points` say how well the model explains the times.

use super::fixed;
use super::rows::index_label;
use crate::harness::suite::ResultRow;

impl CostFit {
    /// Its table cells: index, ns per step, ns per test, ns per ray, R², points.
    pub fn cells(&self) -> [String; 6] {
        [
            self.index.clone(),
            fixed(self.ns_per_step, 2),
            fixed(self.ns_per_test, 2),
            fixed(self.ns_per_ray, 1),
            fixed(self.r2, 3),
            self.points.to_string(),
        ]
    }
}

/// One observation: counts per ray and the measured time per ray in nanoseconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostPoint {
    pub steps_per_ray: f64,
    pub tests_per_ray: f64,
    pub ns_per_ray: f64,
}

/// The fitted costs of one index.
#[derive(Debug, Clone, PartialEq)]
pub struct CostFit {
    pub index: String,
    /// Nanoseconds per node or cell step; NaN when the index takes no steps.
    pub ns_per_step: f64,
    /// Nanoseconds per primitive test; NaN when the index tests no primitives.
    pub ns_per_test: f64,
    /// Fixed nanoseconds per ray; NaN when not fitted (too few points).
    pub ns_per_ray: f64,
    /// Coefficient of determination of the fit (1 = the model explains every time).
    pub r2: f64,
    /// Observations the fit used.
    pub points: usize,
}

type Column = fn(&CostPoint) -> f64;

/// The model's columns: steps, tests, and the constant of the fixed cost.
const COLUMNS: [Column; 3] = [|p| p.steps_per_ray, |p| p.tests_per_ray, |_| 1.0];

/// Non-negative least-squares coefficients `(a, b, c, r2)` of `ns = a * steps + b * tests (+ c)`;
/// `c` is a candidate only when `intercept`. Costs cannot be negative, so every subset of the
/// candidate columns is fitted by ordinary least squares and the best fit whose coefficients are
/// all non-negative wins (a column left out has coefficient 0: the constrained optimum puts it
/// on the bound). A count that is zero at every point is no candidate and gets NaN, as does `c`
/// when not a candidate. `None` when no subset can be fitted (no points).
pub fn fit_costs(points: &[CostPoint], intercept: bool) -> Option<(f64, f64, f64, f64)> {
    let candidates: Vec<usize> = (0..3)
        .filter(|&k| match k {
            2 => intercept,
            _ => points.iter().any(|p| COLUMNS[k](p) != 0.0),
        })
        .collect();
    let mut best: Option<([f64; 3], f64)> = None;
    for mask in 1u32..(1 << candidates.len()) {
        let used: Vec<usize> = (0..candidates.len())
            .filter(|i| mask & (1 << i) != 0)
            .map(|i| candidates[i])
            .collect();
        let Some(beta) = solve(points, &used) else {
            continue;
        };
        if used.iter().any(|&k| beta[k] < 0.0) {
            continue;
        }
        let ss = residual(points, &beta);
        if best.is_none_or(|(_, b)| ss < b) {
            best = Some((beta, ss));
        }
    }
    let (mut beta, ss_res) = best?;
    for (k, b) in beta.iter_mut().enumerate() {
        if !candidates.contains(&k) {
            *b = f64::NAN;
        }
    }
    let mean = points.iter().map(|p| p.ns_per_ray).sum::<f64>() / points.len() as f64;
    let ss_tot: f64 = points.iter().map(|p| (p.ns_per_ray - mean).powi(2)).sum();
    let r2 = if ss_tot > 0.0 {
        1.0 - ss_res / ss_tot
    } else {
        f64::NAN
    };
    Some((beta[0], beta[1], beta[2], r2))
}

/// Sum of squared residuals of `beta` (columns outside the fit are 0).
fn residual(points: &[CostPoint], beta: &[f64; 3]) -> f64 {
    points
        .iter()
        .map(|p| {
            let model: f64 = (0..3).map(|k| beta[k] * COLUMNS[k](p)).sum();
            (p.ns_per_ray - model).powi(2)
        })
        .sum()
}

/// Ordinary least squares over the columns `used` (normal equations, Gaussian elimination with
/// partial pivoting); the other coefficients are 0. `None` when the system is singular (fewer
/// independent points than columns).
fn solve(points: &[CostPoint], used: &[usize]) -> Option<[f64; 3]> {
    let m = used.len();
    if points.len() < m {
        return None;
    }
    let mut a = vec![vec![0.0f64; m + 1]; m];
    for p in points {
        for (i, &ci) in used.iter().enumerate() {
            let xi = COLUMNS[ci](p);
            for (j, &cj) in used.iter().enumerate() {
                a[i][j] += xi * COLUMNS[cj](p);
            }
            a[i][m] += xi * p.ns_per_ray;
        }
    }
    let scale = (0..m).map(|i| a[i][i].abs()).fold(0.0, f64::max);
    for col in 0..m {
        let piv = (col..m).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[piv][col].abs() <= 1e-12 * scale {
            return None;
        }
        a.swap(col, piv);
        for r in 0..m {
            if r != col {
                let f = a[r][col] / a[col][col];
                let pivot_row = a[col].clone();
                for (x, p) in a[r][col..].iter_mut().zip(&pivot_row[col..]) {
                    *x -= f * p;
                }
            }
        }
    }
    let mut beta = [0.0; 3];
    for (i, &ci) in used.iter().enumerate() {
        beta[ci] = a[i][m] / a[i][i];
    }
    Some(beta)
}

/// The observations of each index (first-seen order): its rows at the fewest threads of the run
/// with a finite time and at least one ray.
pub fn cost_points(rows: &[ResultRow]) -> Vec<(String, Vec<CostPoint>)> {
    let Some(fewest) = rows.iter().map(|r| r.threads).min() else {
        return Vec::new();
    };
    let mut out: Vec<(String, Vec<CostPoint>)> = Vec::new();
    for r in rows.iter().filter(|r| r.threads == fewest) {
        let ns = r.trace_ms_median * 1e6 * r.threads as f64 / r.rays as f64;
        if !(ns.is_finite() && r.rays > 0) {
            continue;
        }
        let p = CostPoint {
            steps_per_ray: r.node_visits_per_ray,
            tests_per_ray: r.prim_tests_per_ray,
            ns_per_ray: ns,
        };
        let label = index_label(r, rows);
        match out.iter_mut().find(|(i, _)| *i == label) {
            Some((_, v)) => v.push(p),
            None => out.push((label, vec![p])),
        }
    }
    out
}

/// The cost fit of every index in `rows`: with a fixed cost per ray as a candidate when it has
/// at least twice as many points as unknowns (six), else without; an index with no usable point
/// gets NaNs.
pub fn cost_fits(rows: &[ResultRow]) -> Vec<CostFit> {
    cost_points(rows)
        .into_iter()
        .map(|(index, pts)| {
            let fit = fit_costs(&pts, pts.len() >= 6);
            let (a, b, c, r2) = fit.unwrap_or((f64::NAN, f64::NAN, f64::NAN, f64::NAN));
            CostFit {
                index,
                ns_per_step: a,
                ns_per_test: b,
                ns_per_ray: c,
                r2,
                points: pts.len(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn synthetic(a: f64, b: f64, c: f64, noise: f64) -> Vec<CostPoint> {
        (0..12)
            .map(|k| {
                let steps = 5.0 + 3.0 * k as f64;
                let tests = 1.0 + ((k * 7) % 5) as f64 * 0.8;
                let wobble = if k % 2 == 0 { noise } else { -noise };
                CostPoint {
                    steps_per_ray: steps,
                    tests_per_ray: tests,
                    ns_per_ray: a * steps + b * tests + c + wobble,
                }
            })
            .collect()
    }

    #[test]
    fn recovers_known_costs_exactly_without_noise() {
        let (a, b, c, r2) = fit_costs(&synthetic(2.5, 11.0, 40.0, 0.0), true).unwrap();
        assert!((a - 2.5).abs() < 1e-9 && (b - 11.0).abs() < 1e-9, "{a} {b}");
        assert!(
            (c - 40.0).abs() < 1e-7 && (r2 - 1.0).abs() < 1e-12,
            "{c} {r2}"
        );
        let (a, b, c, _) = fit_costs(&synthetic(2.5, 11.0, 0.0, 0.0), false).unwrap();
        assert!((a - 2.5).abs() < 1e-9 && (b - 11.0).abs() < 1e-9 && c.is_nan());
    }

    #[test]
    fn small_noise_moves_the_fit_little() {
        let (a, b, c, r2) = fit_costs(&synthetic(2.5, 11.0, 40.0, 0.5), true).unwrap();
        assert!((a - 2.5).abs() < 0.1 && (b - 11.0).abs() < 0.5, "{a} {b}");
        assert!((c - 40.0).abs() < 2.0 && r2 > 0.99 && r2 < 1.0, "{c} {r2}");
    }

    #[test]
    fn a_count_that_is_always_zero_is_left_out() {
        // Brute force: no node steps; time = 3 ns per test.
        let pts: Vec<CostPoint> = [10.0, 20.0, 40.0]
            .iter()
            .map(|&t| CostPoint {
                steps_per_ray: 0.0,
                tests_per_ray: t,
                ns_per_ray: 3.0 * t,
            })
            .collect();
        let (a, b, _, _) = fit_costs(&pts, false).unwrap();
        assert!(a.is_nan() && (b - 3.0).abs() < 1e-12, "{a} {b}");
    }

    #[test]
    fn costs_stay_non_negative() {
        // Time falls as tests rise: the unconstrained fit would give tests a negative cost.
        let pts: Vec<CostPoint> = (0..6)
            .map(|k| CostPoint {
                steps_per_ray: 10.0 + k as f64,
                tests_per_ray: 1.0 + (k % 3) as f64,
                ns_per_ray: 4.0 * (10.0 + k as f64) - 3.0 * (k % 3) as f64,
            })
            .collect();
        let (a, b, c, _) = fit_costs(&pts, true).unwrap();
        assert!(a > 0.0 && b == 0.0 && c >= 0.0, "{a} {b} {c}");
    }

    #[test]
    fn no_points_no_fit_and_dependent_counts_still_explain_the_times() {
        assert!(fit_costs(&[], false).is_none());
        // Steps always twice the tests: the split between them is undetermined, but the fit
        // (one of them alone) explains every time.
        let dependent: Vec<CostPoint> = (1..5)
            .map(|k| CostPoint {
                steps_per_ray: 2.0 * k as f64,
                tests_per_ray: k as f64,
                ns_per_ray: 5.0 * k as f64,
            })
            .collect();
        let (_, _, _, r2) = fit_costs(&dependent, false).unwrap();
        assert!((r2 - 1.0).abs() < 1e-12, "{r2}");
    }
}
