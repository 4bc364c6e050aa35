//! What the suite produces: the rows of `results.csv`, the mismatches it kept, and notes on
//! what it skipped and how it verified.

use super::verify::Mismatch;
use super::workload::RaySet;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

fn nan() -> f64 {
    f64::NAN
}

fn single() -> String {
    "single".into()
}

/// One row of `results.csv`: scene x index (and trace mode) x ray set x threads. Columns added
/// after the first reports (`mode`, the interval) read back with defaults from older files.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ResultRow {
    pub scene: String,
    pub primitives: usize,
    /// The row's label: the index name, with `+MODE` for every mode but `single`.
    pub index: String,
    pub params: String,
    /// The trace mode (`single`, `stream`, `last-hit`, `packets8`; `index::TraceMode::label`).
    #[serde(default = "single")]
    pub mode: String,
    pub ray_set: String,
    pub rays: usize,
    pub threads: usize,
    pub build_ms: f64,
    pub memory_bytes: usize,
    /// The heap's high-water mark during the build, in bytes (`IndexInfo::peak_build_bytes`);
    /// empty where not measured (tinybvh) and in reports older than the column.
    #[serde(default)]
    pub peak_build_bytes: Option<usize>,
    pub trace_ms_median: f64,
    pub trace_ms_spread: f64,
    pub mrays_per_s: f64,
    /// The 95% interval of the median's Mrays/s over the timed repeats
    /// (`harness::median_interval`; the whole range below 6 repeats).
    #[serde(default = "nan")]
    pub mrays_ci_low: f64,
    #[serde(default = "nan")]
    pub mrays_ci_high: f64,
    pub mtests_per_s: f64,
    pub prim_tests_per_ray: f64,
    pub node_visits_per_ray: f64,
    pub box_tests_per_ray: f64,
    /// Rays with a hit (closest-hit sets) or occluded (any-hit sets).
    pub hits: usize,
    /// Rays on which this index disagreed with brute force, the first index or itself.
    pub mismatches: usize,
    /// Rays compared with brute force (all rays, or the sample's size).
    pub brute_verified_rays: usize,
    pub query: String,
    pub kernel: String,
    pub repeats: usize,
    /// With the exact kernel: the share of edge functions (three per primitive test) whose sign
    /// the fast filter could not certify, so the exact fallback decided it. NaN for other
    /// kernels and for peers (their own triangle tests).
    pub exact_fallback_rate: f64,
    /// Peers only (empty for ours): brute-force-verified rays where the peer differs from brute
    /// force by a tie (both hit, `t` within `1e-6 t`; `harness::peer_check`).
    pub peer_ties: Option<usize>,
    /// Peers only: verified rays where the peer hits brute force's primitive with a `t` more
    /// than `1e-6 t` away.
    pub peer_t_off: Option<usize>,
    /// Peers only: verified rays where the exact reference contradicts the peer.
    pub peer_wrong: Option<usize>,
    /// GPU indices only: the median kernel time of the timed passes in ms (timestamp queries;
    /// `trace_ms_median` is end to end: rays up, dispatch, hits back). Empty elsewhere, and
    /// where the adapter has no timestamps.
    #[serde(default)]
    pub gpu_kernel_ms: Option<f64>,
    /// GPU indices only: the structure's upload in ms, part of `build_ms`
    /// (`IndexInfo::upload_time`).
    #[serde(default)]
    pub gpu_upload_ms: Option<f64>,
}

impl ResultRow {
    /// Rays this row got wrong, when it got any: for peers the verified rays the exact
    /// reference contradicts (`peer_wrong`; ties and `t` off are not wrong), for our indices
    /// any mismatch.
    pub fn wrong(&self) -> Option<usize> {
        let n = self.peer_wrong.unwrap_or(self.mismatches);
        (n > 0).then_some(n)
    }
}

/// A mismatch with where it happened.
#[derive(Debug, Clone)]
pub struct MismatchRecord {
    pub scene: String,
    pub index: String,
    pub ray_set: RaySet,
    /// What it was compared with: `brute`, another index's name, or `counting-pass`.
    pub against: String,
    pub mismatch: Mismatch,
}

/// Something the suite did not run, and why.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Note {
    pub scene: String,
    pub what: String,
    pub reason: String,
}

impl Note {
    /// Whether the note is a contender's failure (a build error, or a panic in a build or a
    /// trace) rather than a skip or a coverage note.
    pub fn is_failure(&self) -> bool {
        self.reason.starts_with("build failed") || self.reason.starts_with("failed:")
    }
}

/// Everything a run produced.
#[derive(Debug, Default)]
pub struct SuiteResult {
    pub rows: Vec<ResultRow>,
    /// Mismatch counts per (scene, index, set, against) are in the rows; the first few of each
    /// are kept here with the ray's bits.
    pub mismatches: Vec<MismatchRecord>,
    /// Mismatching results of our indices: any fails the run.
    pub mismatch_total: usize,
    /// Mismatching results of peer indices ([`crate::index::is_peer`]): reported, not a failure.
    pub peer_mismatch_total: usize,
    /// Failures of our indices (a build error, or a panic in a build or a trace; each is also
    /// a note): any fails the run. Peers' failures are only notes.
    pub failure_total: usize,
    pub notes: Vec<Note>,
    /// Per scene and set: how brute-force verification covered the rays.
    pub verification: Vec<Note>,
    /// The run stopped early on a SIGINT ([`super::interrupt`]): the rows are the ray sets
    /// finished before it.
    pub interrupted: bool,
}

impl SuiteResult {
    /// Notes something about `scene` that is not a result row (an index not built, a ray set
    /// skipped) and why.
    pub(super) fn note(&mut self, scene: &Scene, what: String, reason: String) {
        self.notes.push(Note {
            scene: scene.name.clone(),
            what,
            reason,
        });
    }

    /// Notes that contender `index` failed on `scene` (`what`: the index, or the index and ray
    /// set), counting it in [`SuiteResult::failure_total`] unless it is a peer.
    pub(super) fn fail(&mut self, scene: &Scene, index: &str, what: String, reason: String) {
        if !crate::index::is_peer(index) {
            self.failure_total += 1;
        }
        self.note(scene, what, reason);
    }
}
