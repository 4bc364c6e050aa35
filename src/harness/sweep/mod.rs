//! Parameter sweeps: build one index per point, time it and count its work on the same rays,
//! check every point returns the same hits, and write a CSV and charts against the swept value.
//! Generic over the index: a point is an x value and an [`IndexSpec`] (`grid:res=[64,64,64]`,
//! `octree:max_depth=12`), grouped into named series (one line per series in the charts).
//! Each index's plan (its points, the charts' axes and marker, its default) is a file here
//! ([`grid_plan`], [`bvh_plan`]; [`grid2_sweep`] and [`octree_sweep`] describe a [`Crossed`]
//! sweep of two parameters, whose `plan` is shared); `accelbench sweep` only reads the
//! arguments and calls one.

mod bvh;
mod grid;
mod grid2;
mod octree;
mod plan;

pub use bvh::bvh_plan;
pub use grid::grid_plan;
pub use grid2::grid2_sweep;
pub use octree::octree_sweep;
pub use plan::{Crossed, SweepPlan, SweepPlot, Swept};

use super::timing::{Query, counting_pass, timed_pass};
use super::verify::{Mismatch, compare_closest};
use crate::geometry::{Ray, TriangleKernelKind};
use crate::index::{BuildError, Counters, IndexSpec, build_index};
use crate::scene::SceneGeometry;
use serde::Serialize;
use thiserror::Error;

/// One point of a sweep.
#[derive(Debug, Clone)]
pub struct SweepPoint {
    /// The line it belongs to (`res`, `lambda`, ...).
    pub series: String,
    /// Its position on the x axis (e.g. cells on the longest axis).
    pub x: f64,
    pub spec: IndexSpec,
}

/// One CSV row: what a point cost to build and store, and how fast it traced.
#[derive(Debug, Clone, Serialize)]
pub struct SweepRow {
    pub series: String,
    pub index: String,
    /// The spec as given (`grid:lambda=4`).
    pub spec: String,
    /// The index's own `key=value` parameters after defaults.
    pub params: String,
    pub x: f64,
    /// Cells (grid) or nodes (trees), leaves included.
    pub cells: usize,
    /// Non-empty cells or leaves.
    pub leaves: usize,
    pub prim_refs: usize,
    pub memory_bytes: usize,
    pub build_ms: f64,
    pub rays: usize,
    /// Closest-hit rays per second (median of the timed repeats).
    pub rays_per_s: f64,
    pub prim_tests_per_ray: f64,
    /// Cells (grid) or nodes (trees) visited per ray.
    pub node_visits_per_ray: f64,
    /// The index's structure-specific figures, `name=value;...` (e.g. `res_x=80;...`).
    pub detail: String,
}

/// Why a sweep could not run.
#[derive(Debug, Error)]
pub enum SweepError {
    #[error("sweep point {spec} (x = {x})")]
    Build {
        spec: String,
        x: f64,
        source: BuildError,
    },
    #[error(
        "sweep point {spec} returns different hits from {reference} on {count} rays; first: {first}"
    )]
    Disagree {
        spec: String,
        reference: String,
        count: usize,
        first: Box<Mismatch>,
    },
    #[error("a sweep needs at least one point and one ray")]
    Empty,
}

/// How the points are measured.
#[derive(Debug, Clone, Copy)]
pub struct SweepSetup<'a> {
    pub geom: &'a SceneGeometry,
    pub kernel: TriangleKernelKind,
    pub rays: &'a [Ray],
    /// Timed repeats per point (the median counts).
    pub repeats: usize,
}

/// Runs every point on the current rayon pool (build, timed closest-hit pass, counting pass),
/// calling `progress` after each, and checks that all points return the first point's hits bit
/// for bit. A point whose build exceeds a structure's limits (e.g. the octree's node cap) is
/// skipped and reported through `skipped`; bad parameters are an error.
pub fn run_sweep(
    setup: &SweepSetup<'_>,
    points: &[SweepPoint],
    mut progress: impl FnMut(&SweepRow),
    mut skipped: impl FnMut(&SweepPoint, &BuildError),
) -> Result<Vec<SweepRow>, SweepError> {
    if points.is_empty() || setup.rays.is_empty() {
        return Err(SweepError::Empty);
    }
    let mut reference = None;
    let mut rows = Vec::with_capacity(points.len());
    for p in points {
        let index = match build_index(&p.spec, setup.geom, setup.kernel) {
            Ok(i) => i,
            Err(e @ BuildError::Failed { .. }) => {
                skipped(p, &e);
                continue;
            }
            Err(source) => {
                return Err(SweepError::Build {
                    spec: p.spec.to_string(),
                    x: p.x,
                    source,
                });
            }
        };
        let (timing, hits) = timed_pass(index.as_ref(), Query::Closest, setup.rays, setup.repeats);
        let (counters, _) = counting_pass(index.as_ref(), Query::Closest, setup.rays);
        match &reference {
            None => reference = Some((p.spec.to_string(), hits)),
            Some((name, want)) => {
                let m = compare_closest(setup.rays, want, &hits);
                if let Some(first) = m.first() {
                    return Err(SweepError::Disagree {
                        spec: p.spec.to_string(),
                        reference: name.clone(),
                        count: m.len(),
                        first: Box::new(first.clone()),
                    });
                }
            }
        }
        let total: Counters = counters.into_iter().sum();
        let n = setup.rays.len() as f64;
        let info = index.info();
        let row = SweepRow {
            series: p.series.clone(),
            index: index.name().to_owned(),
            spec: p.spec.to_string(),
            params: index.params().to_owned(),
            x: p.x,
            cells: info.nodes,
            leaves: info.leaves,
            prim_refs: info.prim_refs,
            memory_bytes: info.memory_bytes,
            build_ms: info.build_time.as_secs_f64() * 1e3,
            rays: setup.rays.len(),
            rays_per_s: timing.rays_per_sec(setup.rays.len()),
            prim_tests_per_ray: total.prim_tests as f64 / n,
            node_visits_per_ray: total.node_visits as f64 / n,
            detail: info
                .extra
                .iter()
                .map(|(k, v)| format!("{k}={v}"))
                .collect::<Vec<_>>()
                .join(";"),
        };
        progress(&row);
        rows.push(row);
    }
    Ok(rows)
}
