//! The verdict of a run: per scene and ray set, the fastest index and every index's speed as a
//! share of it, at the run's most threads. The HTML report opens with it as a matrix and the
//! terminal prints it as a short table.

use super::suite_plots::{scenes, uniq};
use crate::harness::suite::ResultRow;
use std::fmt::Write as _;

/// The race on one scene and ray set.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    pub scene: String,
    pub ray_set: String,
    /// The thread count compared (the run's most).
    pub threads: usize,
    /// Every index with a finite speed, fastest first: `(label, Mrays/s)`.
    pub speeds: Vec<(String, f64)>,
}

impl Verdict {
    /// The fastest index's label and Mrays/s.
    pub fn fastest(&self) -> (&str, f64) {
        (&self.speeds[0].0, self.speeds[0].1)
    }

    /// `label`'s speed divided by the fastest's (1 for the fastest); `None` when it has no row.
    pub fn ratio(&self, label: &str) -> Option<f64> {
        let v = self.speeds.iter().find(|(l, _)| l == label)?.1;
        Some(v / self.fastest().1)
    }
}

/// A row's index label: its name, with its parameters when the run has the same index name
/// with other parameters too (`bvh` and `bvh [preset=sweep]`).
pub fn index_label<'a>(row: &ResultRow, rows: impl IntoIterator<Item = &'a ResultRow>) -> String {
    let clash = rows
        .into_iter()
        .any(|r| r.index == row.index && r.params != row.params);
    match clash {
        true => format!("{} [{}]", row.index, row.params),
        false => row.index.clone(),
    }
}

/// The verdicts of every scene and ray set (run order) at the most threads in `rows`; a scene
/// and set where no index has a finite speed is left out.
pub fn verdicts(rows: &[ResultRow]) -> Vec<Verdict> {
    let Some(most) = rows.iter().map(|r| r.threads).max() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for scene in scenes(rows) {
        let in_scene = || rows.iter().filter(move |r| r.scene == scene);
        for set in uniq(in_scene().map(|r| r.ray_set.as_str())) {
            let mut speeds: Vec<(String, f64)> = in_scene()
                .filter(|r| r.ray_set == set && r.threads == most && r.mrays_per_s.is_finite())
                .map(|r| (index_label(r, rows), r.mrays_per_s))
                .collect();
            if speeds.is_empty() {
                continue;
            }
            speeds.sort_by(|a, b| b.1.total_cmp(&a.1));
            out.push(Verdict {
                scene: scene.to_owned(),
                ray_set: set.to_owned(),
                threads: most,
                speeds,
            });
        }
    }
    out
}

/// The terminal's verdict: a line per scene and ray set with the fastest index, its Mrays/s and
/// the others as a share of it (at most `others` of them, fastest first).
pub fn verdict_text(verdicts: &[Verdict], others: usize) -> String {
    let Some(first) = verdicts.first() else {
        return "No timed results.\n".into();
    };
    // Column widths: the longest entry, at least the header's.
    let width = |len: fn(&Verdict) -> usize, header: &str| {
        verdicts.iter().map(len).fold(header.len(), usize::max)
    };
    let w_scene = width(|v| v.scene.len(), "scene");
    let w_set = width(|v| v.ray_set.len(), "rays");
    let w_idx = width(|v| v.fastest().0.len(), "fastest");
    let mut s = format!(
        "Verdict at {} thread(s): the fastest index per scene and ray set, the others as a share of its speed\n",
        first.threads
    );
    let _ = writeln!(
        s,
        "{:w_scene$}  {:w_set$}  {:w_idx$}  {:>8}  others",
        "scene", "rays", "fastest", "Mrays/s"
    );
    for v in verdicts {
        let (name, best) = v.fastest();
        let mut rest: Vec<String> = v.speeds[1..]
            .iter()
            .take(others)
            .map(|(l, m)| format!("{l} {:.2}", m / best))
            .collect();
        if v.speeds.len() > others + 1 {
            rest.push(format!("(+{} more)", v.speeds.len() - others - 1));
        }
        let _ = writeln!(
            s,
            "{:w_scene$}  {:w_set$}  {name:w_idx$}  {best:>8.2}  {}",
            v.scene,
            v.ray_set,
            rest.join(", ")
        );
    }
    s
}
