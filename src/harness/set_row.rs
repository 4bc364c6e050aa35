//! A result row ([`ResultRow`]) of one index in one trace mode on one ray set at one thread
//! count: its speed from the timed passes, its counters and verification from the counting pass.

use super::peer_check::PeerCounts;
use super::suite_config::SuiteConfig;
use super::suite_result::ResultRow;
use super::timing::{Query, Timing};
use super::workload::RaySet;
use crate::geometry::TriangleKernelKind;
use crate::index::{Counters, TraceIndex, TraceMode, is_peer};
use crate::scene::Scene;

/// A row's index label: the index's name in `single` mode, `INDEX+MODE` otherwise.
pub(super) fn row_label(index: &str, mode: TraceMode) -> String {
    match mode {
        TraceMode::Single => index.to_owned(),
        m => format!("{index}+{}", m.label()),
    }
}

/// What the counting pass and verification found for one index in one mode on one set.
pub(super) struct SetCounts {
    pub mode: TraceMode,
    pub total: Counters,
    pub hits: usize,
    pub mismatches: usize,
    /// Edge functions the exact kernel's fallback decided during the counting pass.
    pub exact_fallbacks: u64,
    pub peer: Option<PeerCounts>,
    /// Rays of the set checked against brute force (all, or a sample).
    pub brute_verified_rays: usize,
}

/// The result row of `index` on `rays` rays of `set` at one thread count (`timed`: the count
/// and its timing, `None` when the run does not time).
pub(super) fn result_row(
    scene: &Scene,
    set: RaySet,
    rays: usize,
    index: &dyn TraceIndex,
    c: &SetCounts,
    (threads, timing): (usize, Option<Timing>),
    cfg: &SuiteConfig,
) -> ResultRow {
    let n = rays as f64;
    let info = index.info();
    // Indices that count nothing (Embree, tinybvh) get NaN ("–" in the summary), not 0.
    let counted = |v: f64| if info.uncounted { f64::NAN } else { v };
    let secs = |d: std::time::Duration| d.as_secs_f64();
    let [median, spread, fastest, slowest] = timing.map_or([f64::NAN; 4], |t| {
        [t.median, t.spread, t.fastest, t.slowest].map(secs)
    });
    ResultRow {
        scene: scene.name.clone(),
        primitives: scene.len(),
        index: row_label(index.name(), c.mode),
        params: index.params().to_owned(),
        mode: c.mode.label(),
        ray_set: set.name().to_owned(),
        rays,
        threads,
        build_ms: info.build_time.as_secs_f64() * 1e3,
        memory_bytes: info.memory_bytes,
        peak_build_bytes: info.peak_build_bytes,
        trace_ms_median: median * 1e3,
        trace_ms_spread: spread * 1e3,
        mrays_per_s: n / median / 1e6,
        mrays_ci_low: n / slowest / 1e6,
        mrays_ci_high: n / fastest / 1e6,
        mtests_per_s: counted(c.total.prim_tests as f64 / median / 1e6),
        prim_tests_per_ray: counted(c.total.prim_tests as f64 / n),
        node_visits_per_ray: counted(c.total.node_visits as f64 / n),
        box_tests_per_ray: counted(c.total.box_tests as f64 / n),
        hits: c.hits,
        mismatches: c.mismatches,
        brute_verified_rays: c.brute_verified_rays,
        query: match set.query() {
            Query::Closest => "closest",
            Query::Any => "any",
        }
        .into(),
        kernel: cfg.kernel.name().into(),
        repeats: if cfg.timed { cfg.repeats } else { 0 },
        exact_fallback_rate: if cfg.kernel == TriangleKernelKind::Exact && !is_peer(index.name()) {
            c.exact_fallbacks as f64 / (3 * c.total.prim_tests.max(1)) as f64
        } else {
            f64::NAN
        },
        peer_ties: c.peer.map(|p| p.ties),
        peer_t_off: c.peer.map(|p| p.t_off),
        peer_wrong: c.peer.map(|p| p.wrong),
        gpu_kernel_ms: timing.and_then(|t| t.kernel).map(|k| secs(k) * 1e3),
        gpu_upload_ms: info.upload_time.map(|u| secs(u) * 1e3),
    }
}
