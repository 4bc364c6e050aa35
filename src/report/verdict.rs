//! The verdict of a run: per scene, ray set and mode family (one query at a time, or batch), the
//! fastest contender whose results are correct, and every contender's speed as a share of it,
//! at the run's most threads. The HTML report opens with it as a matrix and the terminal prints
//! it as a short table.
//!
//! Three rules make it a verdict a reader can trust:
//! - **Correct before fast.** A contender with wrong results on the set ([`ResultRow::wrong`])
//!   is never the fastest; it is listed after the correct ones, marked with its count.
//! - **Like with like.** One-query-at-a-time rows (`single`, `last-hit`) race each other;
//!   batch rows (`stream`, packets) race each other, and an index without a batch row of its
//!   own is represented there by its single row, marked `(single)`.
//! - **Noise is a tie.** A correct contender whose 95% interval of the median overlaps the
//!   winner's is tied with it (`≈`), not ranked below it.

use super::rows::{base_index, index_label, scenes, uniq};
use crate::harness::suite::ResultRow;
use crate::index::{ModeFamily, TraceMode};
use std::fmt::Write as _;

/// One contender of a race.
#[derive(Debug, Clone, PartialEq)]
pub struct Contender {
    /// The row's label ([`index_label`]).
    pub label: String,
    /// Mrays/s at the median, and its 95% interval.
    pub mrays: f64,
    pub low: f64,
    pub high: f64,
    /// Rays it got wrong, when it got any ([`ResultRow::wrong`]).
    pub wrong: Option<usize>,
    /// A single row standing in for an index without a batch row (batch family only).
    pub stand_in: bool,
}

impl Contender {
    fn of(row: &ResultRow, rows: &[ResultRow], stand_in: bool) -> Contender {
        let finite_or = |v: f64| if v.is_finite() { v } else { row.mrays_per_s };
        Contender {
            label: index_label(row, rows),
            mrays: row.mrays_per_s,
            low: finite_or(row.mrays_ci_low),
            high: finite_or(row.mrays_ci_high),
            wrong: row.wrong(),
            stand_in,
        }
    }

    /// The label as the verdict shows it: with `(single)` when it stands in.
    pub fn shown(&self) -> String {
        match self.stand_in {
            true => format!("{} (single)", self.label),
            false => self.label.clone(),
        }
    }
}

/// The race on one scene, ray set and mode family.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    pub scene: String,
    pub ray_set: String,
    pub family: ModeFamily,
    /// The thread count compared (the run's most).
    pub threads: usize,
    /// Every contender with a finite speed: the correct ones fastest first, then the wrong
    /// ones fastest first.
    pub contenders: Vec<Contender>,
}

impl Verdict {
    /// The fastest correct contender; `None` when every contender got something wrong.
    pub fn winner(&self) -> Option<&Contender> {
        self.contenders.first().filter(|c| c.wrong.is_none())
    }

    /// The contender labelled `label`.
    pub fn get(&self, label: &str) -> Option<&Contender> {
        self.contenders.iter().find(|c| c.label == label)
    }

    /// `label`'s speed divided by the winner's (1 for the winner); `None` when it has no row or
    /// there is no winner.
    pub fn ratio(&self, label: &str) -> Option<f64> {
        Some(self.get(label)?.mrays / self.winner()?.mrays)
    }

    /// Whether `label` is a correct contender other than the winner whose interval overlaps
    /// the winner's.
    pub fn tied(&self, label: &str) -> bool {
        let (Some(c), Some(w)) = (self.get(label), self.winner()) else {
            return false;
        };
        c.wrong.is_none() && c.label != w.label && c.high >= w.low && w.high >= c.low
    }

    /// How `label` reads in a cell: `≈ 0.98` for a tie, `0.45`, `30.3 wrong 17309` (its own
    /// Mrays/s and its wrong rays) for a wrong contender.
    pub fn cell(&self, label: &str) -> Option<String> {
        let c = self.get(label)?;
        if let Some(n) = c.wrong {
            return Some(format!("{:.1} wrong {n}", c.mrays));
        }
        let r = self.ratio(label)?;
        Some(match self.tied(label) {
            true => format!("≈ {r:.2}"),
            false => format!("{r:.2}"),
        })
    }
}

/// A row's trace mode (rows of reports before the `mode` column read as `single`).
fn mode(row: &ResultRow) -> TraceMode {
    TraceMode::parse(&row.mode).unwrap_or_default()
}

/// The verdicts of every scene and ray set (run order) at the most threads in `rows`: the
/// one-at-a-time race, then the batch race when the set has batch rows. A race where no
/// contender has a finite speed is left out.
pub fn verdicts(rows: &[ResultRow]) -> Vec<Verdict> {
    let Some(most) = rows.iter().map(|r| r.threads).max() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for scene in scenes(rows) {
        let in_scene = || rows.iter().filter(move |r| r.scene == scene);
        for set in uniq(in_scene().map(|r| r.ray_set.as_str())) {
            let timed: Vec<&ResultRow> = in_scene()
                .filter(|r| r.ray_set == set && r.threads == most && r.mrays_per_s.is_finite())
                .collect();
            for family in [ModeFamily::OneAtATime, ModeFamily::Batch] {
                let contenders = race(&timed, rows, family);
                if contenders.iter().all(|c| c.stand_in) {
                    continue;
                }
                out.push(Verdict {
                    scene: scene.to_owned(),
                    ray_set: set.to_owned(),
                    family,
                    threads: most,
                    contenders,
                });
            }
        }
    }
    out
}

/// The contenders of one family among one set's timed rows, in verdict order. In the batch
/// family, an index (name and parameters) with no batch row is represented by its single row.
fn race(timed: &[&ResultRow], rows: &[ResultRow], family: ModeFamily) -> Vec<Contender> {
    let base = |r: &ResultRow| (base_index(r).to_owned(), r.params.clone());
    let mut v: Vec<Contender> = timed
        .iter()
        .filter(|r| mode(r).family() == family)
        .map(|r| Contender::of(r, rows, false))
        .collect();
    if family == ModeFamily::Batch {
        let batched: Vec<_> = timed
            .iter()
            .filter(|r| mode(r).family() == ModeFamily::Batch)
            .map(|r| base(r))
            .collect();
        v.extend(
            timed
                .iter()
                .filter(|r| mode(r) == TraceMode::Single && !batched.contains(&base(r)))
                .map(|r| Contender::of(r, rows, true)),
        );
    }
    v.sort_by(|a, b| {
        (a.wrong.is_some(), -a.mrays)
            .partial_cmp(&(b.wrong.is_some(), -b.mrays))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    v
}

/// The terminal's verdict: a line per scene, ray set and family with the fastest correct
/// contender, its Mrays/s and the others as a share of it (at most `others` of them, in
/// verdict order: ties as `≈`, wrong ones with their speed and count).
pub fn verdict_text(verdicts: &[Verdict], others: usize) -> String {
    let Some(first) = verdicts.first() else {
        return "No timed results.\n".into();
    };
    let winner = |v: &Verdict| v.winner().map_or("(none correct)".into(), Contender::shown);
    let w_scene = verdicts.iter().map(|v| v.scene.len()).fold(5, usize::max);
    let w_set = verdicts.iter().map(|v| v.ray_set.len()).fold(4, usize::max);
    let w_fam = verdicts
        .iter()
        .map(|v| v.family.label().len())
        .fold(5, usize::max);
    let w_idx = verdicts.iter().map(|v| winner(v).len()).fold(7, usize::max);
    let mut s = format!(
        "Verdict at {} thread(s): per scene, ray set and mode family the fastest index with \
         correct results, the others as a share of its speed (≈: a tie within the 95% \
         intervals)\n",
        first.threads
    );
    let _ = writeln!(
        s,
        "{:w_scene$}  {:w_set$}  {:w_fam$}  {:w_idx$}  {:>8}  others",
        "scene", "rays", "modes", "fastest", "Mrays/s"
    );
    for v in verdicts {
        let best = v.winner().map_or(f64::NAN, |w| w.mrays);
        let shown =
            |c: &Contender| format!("{} {}", c.shown(), v.cell(&c.label).unwrap_or_default());
        let skip = usize::from(v.winner().is_some());
        let correct: Vec<&Contender> = v.contenders[skip..]
            .iter()
            .filter(|c| c.wrong.is_none())
            .collect();
        let mut rest: Vec<String> = correct.iter().take(others).map(|c| shown(c)).collect();
        if correct.len() > others {
            rest.push(format!("(+{} more)", correct.len() - others));
        }
        // Wrong contenders are always named, however many others there are.
        rest.extend(v.contenders.iter().filter(|c| c.wrong.is_some()).map(shown));
        let _ = writeln!(
            s,
            "{:w_scene$}  {:w_set$}  {:w_fam$}  {:w_idx$}  {best:>8.2}  {}",
            v.scene,
            v.ray_set,
            v.family.label(),
            winner(v),
            rest.join(", ")
        );
    }
    s
}
