//! What a suite run is asked to do ([`SuiteConfig`]) and the thread pools it runs in.

use super::shard::Shard;
use super::workload::{RaySet, SetSizes};
use crate::geometry::TriangleKernelKind;
use crate::index::{IndexSpec, TraceMode};
use serde::Serialize;

/// What to run.
#[derive(Debug, Clone, Serialize)]
pub struct SuiteConfig {
    #[serde(serialize_with = "specs_as_strings")]
    pub indices: Vec<IndexSpec>,
    pub sets: Vec<RaySet>,
    pub threads: Vec<usize>,
    pub sizes: SetSizes,
    /// Timed runs per (index, set, threads); the median is reported.
    pub repeats: usize,
    pub kernel: TriangleKernelKind,
    /// Brute-force verification covers every ray while `rays x primitives` is at most this;
    /// beyond it, a deterministic sample of that cost.
    pub verify_budget: u64,
    /// Brute force is timed as an index only while `rays x primitives` is at most this.
    pub brute_timing_budget: u64,
    /// `false` for `accelbench verify`: no timed passes, no rows.
    pub timed: bool,
    /// The share of the scene x index work this run does ([`Shard::WHOLE`] for all of it).
    pub shard: Shard,
    /// The trace modes (`run --modes`): each index is traced in every mode that applies to it
    /// and to the set ([`crate::index::TraceIndex::traces_in`]), its first against brute force
    /// and the first index, the later ones against its first, each with rows of its own.
    pub modes: Vec<TraceMode>,
}

fn specs_as_strings<S: serde::Serializer>(v: &[IndexSpec], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(v.iter().map(|x| x.to_string()))
}

/// A rayon pool per thread count, built once per run.
pub(super) struct Pools(pub(super) Vec<(usize, rayon::ThreadPool)>);

impl Pools {
    pub(super) fn new(threads: &[usize]) -> Result<Pools, rayon::ThreadPoolBuildError> {
        let mut v = Vec::new();
        for &t in threads {
            v.push((t, rayon::ThreadPoolBuilder::new().num_threads(t).build()?));
        }
        Ok(Pools(v))
    }

    /// The pool of the largest thread count (counting passes, references, pictures).
    pub(super) fn all(&self) -> &rayon::ThreadPool {
        &self.0.last().expect("at least one thread count").1
    }
}
