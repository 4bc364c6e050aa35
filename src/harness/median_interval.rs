//! A distribution-free confidence interval of the median from order statistics.
//!
//! For `n` independent samples of a continuous quantity, the number of samples below the true
//! median is Binomial(n, 1/2), so the interval `[x_(k), x_(n+1-k)]` of the sorted samples
//! (1-based) covers the median with probability `1 - 2 P(B <= k - 1)`. [`rank`] takes the
//! largest `k` whose coverage is at least 95%; with fewer than 6 samples no `k` reaches 95%
//! and the interval is the whole range `[min, max]`, whose coverage is `1 - 2^(1-n)` (93.75%
//! with 5 samples, 87.5% with 4). No bootstrap, no assumption about the shape of the noise.

/// The coverage the interval aims at.
pub const LEVEL: f64 = 0.95;

/// `P(B <= j)` for `B ~ Binomial(n, 1/2)`.
fn binomial_cdf_half(n: usize, j: usize) -> f64 {
    // C(n, i) / 2^n accumulated in f64: exact enough for the repeat counts a run uses.
    let mut term = 0.5f64.powi(n as i32);
    let mut sum = term;
    for i in 1..=j.min(n) {
        term *= (n + 1 - i) as f64 / i as f64;
        sum += term;
    }
    sum
}

/// The 1-based rank `k` of the interval `[x_(k), x_(n+1-k)]` over `n >= 1` sorted samples, and
/// its coverage.
pub fn rank(n: usize) -> (usize, f64) {
    let coverage = |k: usize| 1.0 - 2.0 * binomial_cdf_half(n, k - 1);
    let mut k = 1;
    while k < n.div_ceil(2) && coverage(k + 1) >= LEVEL {
        k += 1;
    }
    (k, coverage(k).max(0.0))
}

/// What the interval of `n` repeats is, for report headers: `"interval of the median: sorted
/// repeats 2 to 8 of 9, coverage 96.1%"`, or the whole range (below 6 repeats with less than
/// 95% coverage).
pub fn describe(n: usize) -> String {
    let n = n.max(1);
    let (k, c) = rank(n);
    let which = match k {
        1 => format!("the whole range of {n} repeats"),
        k => format!("sorted repeats {k} to {} of {n}", n + 1 - k),
    };
    format!(
        "interval of the median: {which}, coverage {:.1}%",
        c * 100.0
    )
}

/// The interval of the median of `sorted` (ascending, non-empty): `(low, high)`.
pub fn of_sorted<T: Copy>(sorted: &[T]) -> (T, T) {
    let n = sorted.len();
    let (k, _) = rank(n);
    (sorted[k - 1], sorted[n - k])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranks_and_coverage() {
        // Below 6 samples the range is all there is.
        assert_eq!(rank(1).0, 1);
        assert_eq!(rank(5), (1, 0.9375));
        // 9 samples: [x_2, x_8], coverage 1 - 2 * 10/512.
        let (k, c) = rank(9);
        assert_eq!(k, 2);
        assert!((c - (1.0 - 20.0 / 512.0)).abs() < 1e-12);
        // Every k chosen covers at least 95% from 6 samples on, and k + 1 would not.
        for n in 6..60 {
            let (k, c) = rank(n);
            assert!(c >= LEVEL, "{n}: {c}");
            let next = 1.0 - 2.0 * binomial_cdf_half(n, k);
            assert!(next < LEVEL || k + 1 >= n.div_ceil(2), "{n}");
        }
        // The textbook value: 20 samples give [x_6, x_15].
        assert_eq!(rank(20).0, 6);
        assert_eq!(
            describe(9),
            "interval of the median: sorted repeats 2 to 8 of 9, coverage 96.1%"
        );
        assert_eq!(
            describe(6),
            "interval of the median: the whole range of 6 repeats, coverage 96.9%"
        );
    }

    #[test]
    fn the_interval_contains_the_median() {
        for n in 1..40 {
            let v: Vec<u32> = (0..n).map(|i| (i * 7919) % 97).collect();
            let mut s = v.clone();
            s.sort();
            let (lo, hi) = of_sorted(&s);
            let median = s[n as usize / 2];
            assert!(lo <= median && median <= hi, "{n}");
        }
    }
}
