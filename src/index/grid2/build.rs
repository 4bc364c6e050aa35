//! Building the two-level grid: a coarse top grid filled as the uniform grid fills its cells,
//! then, in parallel, each non-empty top cell's own grid sized to its contents and filled with
//! that cell's primitives only. All inner cells share one compressed-row array.

use crate::index::BuildError;
use crate::index::grid::{
    Cells, Layout, MAX_REFS, fill_cells, fill_cells_with, heuristic_resolution,
};
use crate::index::kit::huge_pages::huge_page_vec;
use crate::scene::Geometry;
use rayon::prelude::*;

/// Top cells with at most this many primitives keep a single inner cell: testing a few
/// primitives' boxes costs less than setting up a walk through a finer grid. `stadium` ran at
/// 0.56x / 0.59x `bvh` (primary / incoherent, one thread, best of 7) without this and 0.63x /
/// 0.75x at 16 (8 to 32 were within noise of each other); the bunny's primary rays gained too.
pub const INNER_MIN_PRIMS: usize = 16;

/// Marks a top cell without primitives (no inner grid).
pub const NO_INNER: u32 = u32::MAX;

/// The grid inside one non-empty top cell.
///
/// Invariant: `layout` is `top.inner(cell, res)` (outer planes and margin shared with the top
/// cell); its local cell `c` is global cell `first + c` of [`Levels::cells`].
#[derive(Debug, Clone)]
pub struct Inner {
    pub layout: Layout,
    pub first: u32,
}

/// Both levels of a two-level grid.
///
/// Invariants: `top_cells.len() == top.cell_count()`; `top_cells[c]` is [`NO_INNER`] when top
/// cell `c` holds no primitive, else an index into `inner`; every primitive whose grown box
/// test accepts an inner cell is stored in it (ids ascending).
#[derive(Debug, Clone)]
pub struct Levels {
    pub top: Layout,
    pub top_cells: Box<[u32]>,
    pub inner: Vec<Inner>,
    pub cells: Cells,
}

/// Builds both levels over `bounds` (finite, checked by the caller): the top grid at
/// `top_lambda` cells per primitive, each non-empty top cell's grid at `lambda` cells per
/// primitive it holds (the cube-root heuristic over the cell's extent), or a single cell when it
/// holds at most [`INNER_MIN_PRIMS`].
pub fn build_levels<G: Geometry>(
    geom: &G,
    bounds: crate::geometry::Aabb,
    top_lambda: f32,
    lambda: f32,
) -> Result<Levels, BuildError> {
    let top = Layout::new(
        bounds,
        heuristic_resolution(bounds.extent(), geom.len(), top_lambda),
    );
    let top_fill = fill_cells(geom, &top, "grid2")?;
    let filled: Vec<usize> = (0..top.cell_count())
        .filter(|&c| !top_fill.of(c).is_empty())
        .collect();
    let grids = filled
        .par_iter()
        .map(|&c| {
            let ids = top_fill.of(c);
            let coords = top.coords(c);
            let res = if ids.len() <= INNER_MIN_PRIMS {
                [1, 1, 1]
            } else {
                heuristic_resolution(top.cell_box(coords).extent(), ids.len(), lambda)
            };
            let layout = top.inner(coords, res);
            let cells = fill_cells_with(geom, &layout, ids, "grid2")?;
            Ok((layout, cells))
        })
        .collect::<Result<Vec<_>, BuildError>>()?;
    let cell_total: usize = grids.iter().map(|(l, _)| l.cell_count()).sum();
    let ref_total: usize = grids.iter().map(|(_, c)| c.prims.len()).sum();
    if ref_total > MAX_REFS || cell_total >= u32::MAX as usize {
        return Err(BuildError::Failed {
            index: "grid2".into(),
            message: format!(
                "{ref_total} primitive references in {cell_total} inner cells: more than the \
                 {MAX_REFS} references (or 2^32 cells) a grid may hold; lower lambda or \
                 top_lambda"
            ),
        });
    }
    let mut top_cells = vec![NO_INNER; top.cell_count()].into_boxed_slice();
    let mut offsets = Vec::with_capacity(cell_total + 1);
    offsets.push(0u32);
    let mut prims = Vec::with_capacity(ref_total);
    let mut inner = Vec::with_capacity(grids.len());
    for (&c, (layout, cells)) in filled.iter().zip(grids) {
        top_cells[c] = inner.len() as u32;
        let base = prims.len() as u32;
        inner.push(Inner {
            layout,
            first: (offsets.len() - 1) as u32,
        });
        offsets.extend(cells.offsets[1..].iter().map(|&o| base + o));
        prims.extend_from_slice(&cells.prims);
    }
    Ok(Levels {
        top,
        top_cells,
        inner,
        cells: Cells {
            offsets: huge_page_vec(offsets).into_boxed_slice(),
            prims: huge_page_vec(prims).into_boxed_slice(),
        },
    })
}
