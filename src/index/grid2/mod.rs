//! Two-level grid (Kalojanov, Stich and Slusallek 2011, "Two-Level Grids for Ray Tracing on
//! GPUs"): a coarse uniform top grid whose every non-empty cell holds its own uniform grid, sized
//! by the cube-root heuristic to the primitives of that cell. Dense clusters get fine cells,
//! empty space is crossed in coarse steps.
//!
//! Both levels are the uniform grid's pieces ([`crate::index::grid`]): the layout and its shared
//! planes, the exact overlap fill with the build margin, and the 3D-DDA. The traversal walks the
//! top grid; in a non-empty top cell it walks the cell's grid from the parameter at which the
//! top walk entered the cell ([`Dda::starting_at`]) to its exit, which is the top walk's exit
//! from the cell (the inner grid's outer planes are the cell's planes bit for bit).
//!
//! # Why stopping at the current inner cell's exit is exact
//!
//! The argument of the `grid::dda` module, applied to the cells actually visited: the walks
//! cover the ray from its entry into the grid box to the current exit (top cells without
//! primitives hold no primitive within the margin, inner walks cover their top cell's stretch),
//! up to the same roundings, and every inner cell box is grown by the top grid's margin before
//! the overlap test. An inner cell's grown box lies inside its top cell's grown box, so the
//! primitives the inner fill considers (the top cell's) include every primitive it must store.
//!
//! Each primitive is tested at most once per ray (the shared per-thread mailbox).

mod build;

use super::grid::{Dda, Layout, check_lambda, finite_bounds};
use crate::geometry::Ray;
use crate::index::kit::cell_walk::{CellVisit, CellWalk, cell_walk_index};
use crate::index::{BatchIndex, BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
use build::{Levels, NO_INNER, build_levels};
use serde::{Deserialize, Serialize};

/// Default top-level density (cells per primitive): coarse, so the top walk crosses empty space
/// in few steps and the inner grids do the fine work. Chosen by `sweep grid2` and suite runs
/// over 1/128 to 1/4 (docs/sweeps.md): 1/64 was fastest on `stadium` (0.62-0.67x `bvh` on
/// primary rays against 0.45x at 1/16) and no worse on the bunny.
pub const DEFAULT_TOP_LAMBDA: f32 = 1.0 / 64.0;
/// Default density of each top cell's own grid (cells per primitive of that cell).
pub const DEFAULT_LAMBDA: f32 = 2.0;

/// Two-level grid parameters (`grid2:top_lambda=0.1,lambda=3`).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Grid2Params {
    /// Cells per primitive of the top grid (cube-root heuristic over the scene).
    pub top_lambda: f32,
    /// Cells per primitive of each top cell's grid (cube-root heuristic over the cell).
    pub lambda: f32,
}

impl Default for Grid2Params {
    fn default() -> Self {
        Grid2Params {
            top_lambda: DEFAULT_TOP_LAMBDA,
            lambda: DEFAULT_LAMBDA,
        }
    }
}

/// A two-level grid over the scene's bounds.
#[derive(Debug, Clone)]
pub struct Grid2 {
    levels: Levels,
    prim_count: usize,
}

impl Grid2 {
    /// The top grid's layout, then every inner grid's (for tests that aim rays at cell planes).
    pub fn layouts(&self) -> impl Iterator<Item = &Layout> {
        std::iter::once(&self.levels.top).chain(self.levels.inner.iter().map(|i| &i.layout))
    }
}

/// The walk: the top grid's 3D-DDA, and in each non-empty top cell the cell's own grid's (exact:
/// see the module documentation).
impl CellWalk for Grid2 {
    /// Hands the primitives of the cells `ray` crosses, front to back, to `visit`, which returns
    /// the cutoff (the best `t`, or `-inf` to stop); the walk stops after a cell whose exit is at
    /// or beyond the cutoff (exact: see the module documentation).
    #[inline(always)]
    fn for_each_cell<S: Stats>(&self, ray: &Ray, stats: &mut S, mut visit: impl CellVisit<S>) {
        stats.box_tests(1);
        let top = &self.levels.top;
        let Some((mut enter, _)) = top.bounds.ray_interval(ray, ray.t_min, ray.t_max) else {
            return;
        };
        let mut cutoff = ray.t_max;
        for (cell, exit) in Dda::starting_at(top, ray, enter) {
            stats.node_visit();
            let inner = self.levels.top_cells[cell];
            if inner != NO_INNER {
                let inner = &self.levels.inner[inner as usize];
                if inner.layout.res == [1, 1, 1] {
                    // One inner cell: its walk would yield it with the top walk's exit, which
                    // the check below compares with.
                    stats.node_visit();
                    cutoff = visit(self.levels.cells.of(inner.first as usize), stats);
                } else {
                    for (c, inner_exit) in Dda::starting_at(&inner.layout, ray, enter) {
                        stats.node_visit();
                        cutoff = visit(self.levels.cells.of(inner.first as usize + c), stats);
                        if cutoff <= inner_exit {
                            return;
                        }
                    }
                }
            }
            if cutoff <= exit {
                return;
            }
            enter = exit;
        }
    }
}

impl Index for Grid2 {
    type Params = Grid2Params;

    fn build<G: Geometry>(geom: &G, params: &Grid2Params) -> Result<Self, BuildError> {
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        for (name, value) in [("top_lambda", params.top_lambda), ("lambda", params.lambda)] {
            check_lambda(value).map_err(|message| BuildError::Params {
                index: "grid2".into(),
                message: format!("{name}: {message}"),
            })?;
        }
        let bounds = finite_bounds(geom, "grid2")?;
        let levels = build_levels(geom, bounds, params.top_lambda, params.lambda)?;
        Ok(Grid2 {
            levels,
            prim_count: geom.len(),
        })
    }

    // The build's peak heap a primitive: about 70 B measured (soup, bunny, icosphere), with a
    // margin; long thin primitives span more cells, and the fill checks the budget as it goes.
    cell_walk_index!(80);

    fn info(&self) -> IndexInfo {
        let l = &self.levels;
        let inner_cells = l.cells.offsets.len() - 1;
        let refs = l.cells.prims.len();
        let filled = l.cells.offsets.windows(2).filter(|w| w[0] < w[1]).count();
        let planes: usize = self
            .layouts()
            .map(|layout| layout.planes.iter().map(|p| p.len()).sum::<usize>())
            .sum();
        let [rx, ry, rz] = l.top.res;
        IndexInfo {
            nodes: l.top.cell_count() + inner_cells,
            leaves: filled,
            depth: 2,
            memory_bytes: 4 * (l.top_cells.len() + l.cells.offsets.len() + refs + planes)
                + l.inner.len() * size_of::<build::Inner>(),
            prim_refs: refs,
            extra: vec![
                ("top_res_x".into(), rx as f64),
                ("top_res_y".into(), ry as f64),
                ("top_res_z".into(), rz as f64),
                ("inner_grids".into(), l.inner.len() as f64),
                ("inner_cells".into(), inner_cells as f64),
                (
                    "refs_per_prim".into(),
                    refs as f64 / self.prim_count.max(1) as f64,
                ),
            ],
            ..IndexInfo::default()
        }
    }
}

impl BatchIndex for Grid2 {}
