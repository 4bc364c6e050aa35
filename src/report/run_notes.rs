//! `notes.json`: what a report shows besides its rows and `meta.json` (verification totals and
//! coverage, notes on what was skipped, the pictures), so `accelbench merge` can rebuild the
//! report of a sharded run from its shards' folders.

use crate::harness::suite::{Note, SuiteResult};
use serde::{Deserialize, Serialize};

/// A picture of the report, by its path relative to the report folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PictureRef {
    pub scene: String,
    /// `shaded`, or the heat map's index and kind (`bvh tests`).
    pub caption: String,
    /// Relative to the report folder, `/`-separated (`pictures/bunny_shaded.png`).
    pub path: String,
}

/// Everything but rows and metadata that the summary and the HTML page show.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct RunNotes {
    /// Mismatching results of our indices: any fails the run.
    pub mismatch_total: usize,
    /// Mismatching results of peer indices: reported, not a failure.
    pub peer_mismatch_total: usize,
    /// Failures of our indices (build errors, panics; each is also a note): any fails the run.
    /// Absent from reports written before it was added.
    #[serde(default)]
    pub failure_total: usize,
    /// What the run skipped or could not build, and why.
    pub notes: Vec<Note>,
    /// Per scene and ray set: how brute-force verification covered the rays.
    pub verification: Vec<Note>,
    pub pictures: Vec<PictureRef>,
}

impl RunNotes {
    /// The notes of a suite result and its pictures.
    pub fn of(res: &SuiteResult, pictures: Vec<PictureRef>) -> RunNotes {
        RunNotes {
            mismatch_total: res.mismatch_total,
            peer_mismatch_total: res.peer_mismatch_total,
            failure_total: res.failure_total,
            notes: res.notes.clone(),
            verification: res.verification.clone(),
            pictures,
        }
    }

    /// Adds `other`'s totals, notes and pictures (a picture path already present is kept once:
    /// shards of one scene each render its shaded picture).
    pub fn absorb(&mut self, other: RunNotes) {
        self.mismatch_total += other.mismatch_total;
        self.peer_mismatch_total += other.peer_mismatch_total;
        self.failure_total += other.failure_total;
        self.notes.extend(other.notes);
        self.verification.extend(other.verification);
        for p in other.pictures {
            if !self.pictures.iter().any(|q| q.path == p.path) {
                self.pictures.push(p);
            }
        }
    }

    /// The pictures grouped per scene (first-seen order): the shaded render(s), then per index
    /// its heat maps in order, as `(index, [(kind, path)])`.
    pub fn picture_groups(&self) -> Vec<SceneImages<'_>> {
        let mut out: Vec<SceneImages> = Vec::new();
        for p in &self.pictures {
            if !out.iter().any(|g| g.scene == p.scene) {
                out.push(SceneImages {
                    scene: &p.scene,
                    shaded: Vec::new(),
                    heatmaps: Vec::new(),
                });
            }
            let g = out.iter_mut().find(|g| g.scene == p.scene).expect("added");
            match p.caption.rsplit_once(' ') {
                None => g.shaded.push(&p.path),
                Some((index, kind)) => match g.heatmaps.iter_mut().find(|(i, _)| *i == index) {
                    Some((_, v)) => v.push((kind, &p.path)),
                    None => g.heatmaps.push((index, vec![(kind, &p.path)])),
                },
            }
        }
        out
    }
}

/// One scene's pictures.
#[derive(Debug)]
pub struct SceneImages<'a> {
    pub scene: &'a str,
    pub shaded: Vec<&'a str>,
    /// `(index, [(kind, path)])`.
    pub heatmaps: Vec<(&'a str, Vec<(&'a str, &'a str)>)>,
}

/// The summary's picture section.
pub fn pictures_markdown(notes: &RunNotes) -> String {
    let groups = notes.picture_groups();
    if groups.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "## Pictures\n\nPer scene: the shaded render (identical through every index), then each \
         index's heat maps of primitive tests and of node/cell visits per camera ray (fixed log \
         scale: black 0, blue 1 ... red 1024+).\n\n",
    );
    for g in groups {
        s.push_str(&format!("### {}\n\n", g.scene));
        for p in &g.shaded {
            s.push_str(&format!("![{} shaded]({p})\n\n", g.scene));
        }
        s.push_str(
            "| index | primitive tests per ray | node/cell visits per ray |\n|---|---|---|\n",
        );
        for (index, cells) in &g.heatmaps {
            let imgs: Vec<String> = cells
                .iter()
                .map(|(_, p)| format!("![{index}]({p})"))
                .collect();
            s.push_str(&format!("| {index} | {} |\n", imgs.join(" | ")));
        }
        s.push('\n');
    }
    s
}
