//! Arguments shared by `accelbench run` and `accelbench verify`: which scenes, indices and ray
//! sets, at which sizes, and the defaults of a full and a `--quick` run.

use crate::geometry::TriangleKernelKind;
use crate::harness::suite::{Shard, SuiteConfig};
use crate::harness::workload::{RaySet, SetSizes};
use crate::index::{IndexSpec, TraceMode, index_names};
use crate::scene::generators::BUILTIN_NAMES;
use crate::scene::{Scene, load_scene, meshes_in};
use anyhow::Context;
use std::path::Path;

#[derive(Debug, Clone, clap::Args)]
pub struct SuiteArgs {
    /// Scenes, comma-separated: built-in names (`soup`, `stadium:n=100000,seed=2`) and paths
    /// to mesh (.obj, .ply, .gltf, .glb) or .toml files [default: every built-in scene plus
    /// every mesh file in meshes/].
    #[arg(long)]
    pub scenes: Option<String>,
    /// Indices, comma-separated, with optional parameters (`bvh,grid:lambda=4`) [default: all].
    #[arg(long)]
    pub indices: Option<String>,
    /// Ray sets, comma-separated [default: all; `run` without --full: primary, shadow,
    /// diffuse, incoherent].
    #[arg(long, value_enum, value_delimiter = ',')]
    pub rays: Vec<RaySet>,
    /// A small, fast configuration (under 2 minutes on 2 cores): smaller built-in scenes and
    /// ray sets, 3 repeats.
    #[arg(long)]
    pub quick: bool,
    /// Width and height of the primary image [default: 256, quick 128; the protocol's is 1024].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=8192))]
    pub primary_size: Option<u32>,
    /// Number of incoherent rays [default: 65536, quick 16384; the protocol's is 1048576].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 26)))]
    pub incoherent: Option<u64>,
    /// Primitives of each default built-in scene [default: 20000, quick 4000].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 25)))]
    pub scene_size: Option<u64>,
    /// Triangle kernel every index uses.
    #[arg(long, default_value = "exact", value_parser = super::kernel_arg::parse_kernel)]
    pub kernel: TriangleKernelKind,
    /// No progress bars.
    #[arg(long)]
    pub quiet: bool,
    /// Run only shard K of N of the scene x index work (`2/4`); combine the shards' report
    /// folders with `accelbench merge`.
    #[arg(long, default_value = "1/1")]
    pub shard: Shard,
    /// Trace modes, comma-separated: single (one query at a time, every index), stream (the
    /// index's own batch technique: bvh4/bvh8 interleaved and lockstep walks, embree-p16's
    /// 16-ray packets; rows `INDEX+stream` only for indices that have one), last-hit (the
    /// previous ray's hit primitive tested first), packets4, packets8, packets16 (the coherent
    /// sets in packets of neighbouring rays; bvh, bvh4 and bvh8 walk packets, the others ray by
    /// ray), beams4, beams8, beams16 (the same packets traced as beams with a frustum test;
    /// rows only for bvh, bvh4 and bvh8), reorder (the batch sorted by origin and direction,
    /// then one query at a time; rows `INDEX+reorder`).
    #[arg(long, value_delimiter = ',', value_parser = TraceMode::parse, default_value = "single,stream")]
    pub modes: Vec<TraceMode>,
    /// Shorthand: add `last-hit` to `--modes`.
    #[arg(long)]
    pub last_hit: bool,
    /// Shorthand: add `packets4`, `packets8` or `packets16` to `--modes`.
    #[arg(long, value_parser = parse_packet_size)]
    pub packets: Option<usize>,
    /// The memory the run may take (`512M`, `4G`; 1024-based): a run whose ray sets would not
    /// fit is refused before it allocates, and an index whose build would not fit (its
    /// estimate, or its growth while building) is skipped [default: 80% of the available
    /// memory].
    #[arg(long, value_parser = crate::harness::memory::parse_bytes)]
    pub memory_budget: Option<u64>,
}

/// A packet size: 4, 8 or 16.
fn parse_packet_size(s: &str) -> Result<usize, String> {
    match s.trim() {
        "4" => Ok(4),
        "8" => Ok(8),
        "16" => Ok(16),
        other => Err(format!(
            "packet size '{other}' is not supported: use 4, 8 or 16"
        )),
    }
}

/// The specs of the `--indices` items `names` (as [`split_list`] splits them): an error naming
/// an item that does not parse, or saying the list is empty.
pub fn parse_index_specs(names: &[String]) -> anyhow::Result<Vec<IndexSpec>> {
    anyhow::ensure!(
        !names.is_empty(),
        "--indices is empty: name at least one index"
    );
    names
        .iter()
        .map(|n| {
            n.parse::<IndexSpec>()
                .with_context(|| format!("index '{n}'"))
        })
        .collect()
}

/// Splits a comma-separated list whose items may carry their own `key=value,key=value`
/// parameters (`soup:n=5,seed=2,bunny.obj`, `grid:res=[4,4,4],bvh`): commas inside brackets or
/// quotes never split, and a piece of the form `key=value` belongs to the item before it.
pub fn split_list(s: &str) -> Vec<String> {
    let mut pieces = Vec::new();
    let (mut depth, mut quoted, mut cur) = (0i32, false, String::new());
    for c in s.chars() {
        match c {
            '"' => quoted = !quoted,
            '[' if !quoted => depth += 1,
            ']' if !quoted => depth -= 1,
            ',' if depth == 0 && !quoted => {
                pieces.push(std::mem::take(&mut cur));
                continue;
            }
            _ => {}
        }
        cur.push(c);
    }
    pieces.push(cur);
    let mut items: Vec<String> = Vec::new();
    for p in pieces.into_iter().map(|p| p.trim().to_owned()) {
        if p.is_empty() {
            continue;
        }
        let is_param = p
            .split_once('=')
            .is_some_and(|(k, _)| !k.contains([':', '/', '.']));
        match items.last_mut() {
            Some(last) if is_param && last.contains(':') => {
                last.push(',');
                last.push_str(&p);
            }
            _ => items.push(p),
        }
    }
    items
}

impl SuiteArgs {
    /// The scene arguments: the given list, or the built-in scenes (at the default or quick
    /// size) plus every `.obj` in `meshes/`.
    pub fn scene_args(&self) -> anyhow::Result<Vec<String>> {
        if let Some(s) = &self.scenes {
            let v = split_list(s);
            anyhow::ensure!(!v.is_empty(), "--scenes is empty: name at least one scene");
            return Ok(v);
        }
        let n = self
            .scene_size
            .unwrap_or(if self.quick { 4000 } else { 20_000 });
        let mut v: Vec<String> = BUILTIN_NAMES.iter().map(|b| format!("{b}:n={n}")).collect();
        for p in meshes_in(Path::new("meshes"))? {
            v.push(p.to_string_lossy().into_owned());
        }
        Ok(v)
    }

    /// Loads every scene before any work starts, so a bad one fails fast.
    pub fn load_scenes(&self) -> anyhow::Result<Vec<Scene>> {
        self.scene_args()?
            .iter()
            .map(|a| load_scene(a).with_context(|| format!("loading scene '{a}'")))
            .collect()
    }

    pub fn index_specs(&self) -> anyhow::Result<Vec<IndexSpec>> {
        let names = match &self.indices {
            Some(s) => split_list(s),
            None => index_names().into_iter().map(str::to_owned).collect(),
        };
        let specs = parse_index_specs(&names)?;
        if let Some((_, twice)) = (specs.iter().enumerate()).find(|(i, s)| specs[..*i].contains(s))
        {
            anyhow::bail!(
                "--indices lists '{twice}' twice (it would be built and traced twice): list each index once"
            );
        }
        Ok(specs)
    }

    pub fn sets(&self) -> Vec<RaySet> {
        if self.rays.is_empty() {
            RaySet::ALL.to_vec()
        } else {
            let mut v = self.rays.clone();
            v.dedup();
            v
        }
    }

    /// The modes of `--modes` with those `--last-hit` and `--packets` add, each once, in the
    /// order given.
    pub fn modes(&self) -> Vec<TraceMode> {
        let extra = self.last_hit.then_some(TraceMode::LastHit);
        let mut v: Vec<TraceMode> = Vec::new();
        for m in self
            .modes
            .iter()
            .copied()
            .chain(extra)
            .chain(self.packets.map(TraceMode::Packets))
        {
            if !v.contains(&m) {
                v.push(m);
            }
        }
        v
    }

    /// Refuses, with one message, a run whose ray sets would take more than `--memory-budget`
    /// ([`crate::harness::memory::suite_need`]), before any is made, and holds the index builds
    /// to that budget (an index that would not fit is skipped).
    pub fn check_memory(&self, scenes: &[Scene], cfg: &SuiteConfig) -> anyhow::Result<()> {
        use crate::harness::memory::{Budget, suite_need};
        let budget = Budget::of(self.memory_budget);
        if let Some(b) = &budget {
            b.hold_builds();
        }
        match (budget, suite_need(scenes, cfg)) {
            (Some(budget), Some(need)) => budget.check(&need),
            _ => Ok(()),
        }
    }

    /// The suite configuration for these arguments.
    pub fn config(
        &self,
        threads: Vec<usize>,
        repeats: usize,
        timed: bool,
    ) -> anyhow::Result<SuiteConfig> {
        let q = self.quick;
        Ok(SuiteConfig {
            indices: self.index_specs()?,
            sets: self.sets(),
            threads,
            sizes: SetSizes {
                primary_side: self.primary_size.unwrap_or(if q { 128 } else { 256 }),
                incoherent: self
                    .incoherent
                    .map_or(if q { 16_384 } else { 65_536 }, |n| n as usize),
                ao_fraction: 0.05,
            },
            repeats,
            kernel: self.kernel,
            verify_budget: if q { 200_000_000 } else { 500_000_000 },
            brute_timing_budget: if q { 20_000_000 } else { 200_000_000 },
            timed,
            shard: self.shard,
            modes: self.modes(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_keep_item_parameters_together() {
        assert_eq!(
            split_list("soup:n=5,seed=2, ../m/bunny.obj,stadium"),
            ["soup:n=5,seed=2", "../m/bunny.obj", "stadium"]
        );
        assert_eq!(
            split_list("grid:res=[4,4,4],lambda=2,bvh,bvh:preset=\"a,b\""),
            ["grid:res=[4,4,4],lambda=2", "bvh", "bvh:preset=\"a,b\""]
        );
        assert!(split_list(" , ").is_empty());
    }
}
