//! Chart axes: values to axis positions (log axes plot `log10(v)` on a linear axis), tick
//! positions at round values, compact tick labels.

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use std::ops::Range;

/// `log10(v)` on a log axis, `v` otherwise; `None` when it cannot be drawn.
pub(super) fn axis_value(v: f64, log: bool) -> Option<f64> {
    match log {
        true if v > 0.0 && v.is_finite() => Some(v.log10()),
        false if v.is_finite() => Some(v),
        _ => None,
    }
}

/// A compact tick label: three significant digits, exponent form outside `[1e-3, 1e5)`.
pub(super) fn fmt_num(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        let exp = a.log10().floor() as i32;
        let mant = v / 10f64.powi(exp);
        return match (mant - mant.round()).abs() < 1e-9 {
            true => format!("{}e{exp}", mant.round()),
            false => format!("{mant:.1}e{exp}"),
        };
    }
    let decimals = if a == 0.0 {
        0
    } else {
        (2 - a.log10().floor() as i32).max(0) as usize
    };
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// The label of a tick at axis position `v`.
pub(super) fn tick_label(v: f64, log: bool) -> String {
    fmt_num(if log { 10f64.powf(v) } else { v })
}

/// `lo..hi` padded by 5% (a unit around a single value).
pub(super) fn padded(lo: f64, hi: f64) -> Range<f64> {
    if !(lo.is_finite() && hi.is_finite()) {
        return 0.0..1.0;
    }
    if hi - lo <= f64::EPSILON * hi.abs().max(1.0) {
        return lo - 0.5..hi + 0.5;
    }
    let p = (hi - lo) * 0.05;
    lo - p..hi + p
}

/// Tick positions at round values inside `r` (axis positions: `log10` of the value on a log
/// axis). Log axes: the powers of ten (1, 10, 100 or 1e3, 1e4, 1e5), with 2 and 5 times them
/// added when the range spans fewer than two powers. Linear axes: multiples of 1, 2 or 5 times a
/// power of ten, at most 7 of them.
pub(super) fn round_ticks(r: &Range<f64>, log: bool) -> Vec<f64> {
    if log {
        let decades = (r.start.ceil() as i32..=r.end.floor() as i32).map(f64::from);
        let mut t: Vec<f64> = decades.clone().collect();
        if t.len() < 2 {
            let lo = r.start.floor() as i32;
            t = (lo..=r.end.ceil() as i32)
                .flat_map(|e| [1.0, 2.0, 5.0].map(|m| (m * 10f64.powi(e)).log10()))
                .filter(|v| r.contains(v))
                .collect();
        }
        return t;
    }
    let span = r.end - r.start;
    if !(span > 0.0 && span.is_finite()) {
        return vec![r.start];
    }
    let mag = 10f64.powf((span / 5.0).log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| span / s <= 6.0)
        .unwrap_or(10.0 * mag);
    let first = (r.start / step).ceil() as i64;
    let last = (r.end / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// A linear axis over `range` with ticks at chosen values (plotters' own `f64` axis picks them
/// itself, at values such as 0.5 that on a log axis label `10^0.5`).
pub(super) struct RoundAxis {
    range: Range<f64>,
    ticks: Vec<f64>,
    /// Ticks and the light grid lines between them.
    light: Vec<f64>,
}

impl Ranged for RoundAxis {
    type ValueType = f64;
    type FormatOption = NoDefaultFormatting;

    fn range(&self) -> Range<f64> {
        self.range.clone()
    }

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let span = self.range.end - self.range.start;
        if span == 0.0 {
            return (limit.1 - limit.0) / 2;
        }
        let share = (v - self.range.start) / span;
        limit.0 + (f64::from(limit.1 - limit.0) * share + 1e-3).floor() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        match hint.weight().allow_light_points() {
            true => self.light.clone(),
            false => self.ticks.clone(),
        }
    }
}

impl ValueFormatter<f64> for RoundAxis {
    fn format(v: &f64) -> String {
        fmt_num(*v)
    }
}

/// The axis over `r` with ticks at [`round_ticks`] and, on a log axis, light grid lines at 2 to
/// 9 times each power of ten.
pub(super) fn ticked(r: Range<f64>, log: bool) -> RoundAxis {
    let ticks = round_ticks(&r, log);
    let mut light: Vec<f64> = if log {
        (r.start.floor() as i32..=r.end.ceil() as i32)
            .flat_map(|e| (2..10).map(move |m| (f64::from(m) * 10f64.powi(e)).log10()))
            .filter(|v| r.contains(v))
            .collect()
    } else {
        Vec::new()
    };
    light.extend(&ticks);
    RoundAxis {
        range: r,
        ticks,
        light,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_compact() {
        assert_eq!(fmt_num(2.5), "2.5");
        assert_eq!(fmt_num(158.489), "158");
        assert_eq!(fmt_num(0.012589), "0.0126");
        assert_eq!(fmt_num(1000.0), "1000");
        assert_eq!(fmt_num(1e6), "1e6");
        assert_eq!(fmt_num(2.5e-5), "2.5e-5");
        assert_eq!(tick_label(2.0, true), "100");
    }

    #[test]
    fn ticks_sit_at_round_values() {
        let labels = |r: Range<f64>, log| -> Vec<String> {
            round_ticks(&r, log)
                .iter()
                .map(|&v| tick_label(v, log))
                .collect()
        };
        assert_eq!(labels(-0.3..2.4, true), ["1", "10", "100"]);
        assert_eq!(labels(2.9..5.1, true), ["1000", "10000", "1e5"]);
        assert_eq!(labels(0.1..0.9, true), ["2", "5"]);
        assert_eq!(
            labels(0.0..1.0, false),
            ["0", "0.2", "0.4", "0.6", "0.8", "1"]
        );
        assert_eq!(labels(-3.0..37.0, false), ["0", "10", "20", "30"]);
    }
}
