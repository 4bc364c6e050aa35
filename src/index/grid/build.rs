//! Filling the cells: each primitive goes into every cell its grown box really overlaps (the
//! shared conservative overlap test, not just the cells its bounding box touches), stored in
//! compressed rows (one offset per cell into one id array).

use super::layout::Layout;
use crate::index::BuildError;
use crate::index::build_budget::ensure_within;
use crate::index::kit::huge_pages::huge_page_vec;
use crate::scene::Geometry;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Most primitive references a grid may store (128M ids, 512 MiB).
pub const MAX_REFS: usize = 1 << 27;

/// What makes a grid smaller, for the budget's refusal.
const LOWER: &str = "lower the resolution or lambda";

/// Primitives per parallel work item.
const CHUNK: u32 = 1024;

/// The cells' contents in compressed rows.
///
/// Invariants: `offsets.len() == cells + 1`, `offsets[0] == 0`, non-decreasing, last
/// `== prims.len()`; cell `c` holds `prims[offsets[c]..offsets[c + 1]]`, ids ascending and
/// distinct.
#[derive(Debug, Clone)]
pub struct Cells {
    pub offsets: Box<[u32]>,
    pub prims: Box<[u32]>,
}

impl Cells {
    /// The primitives of cell `c`.
    #[inline(always)]
    pub fn of(&self, c: usize) -> &[u32] {
        &self.prims[self.offsets[c] as usize..self.offsets[c + 1] as usize]
    }
}

/// Fills the cells of `layout` with `geom`'s primitives for the grid `index` (its name, for
/// errors), or explains why the grid would be too large (more than [`MAX_REFS`] references, or
/// over the memory budget: the references' count depends on how many cells each primitive
/// spans, so the fill checks the budget as it goes).
pub fn fill_cells<G: Geometry>(
    geom: &G,
    layout: &Layout,
    index: &str,
) -> Result<Cells, BuildError> {
    let all: Vec<u32> = (0..geom.len() as u32).collect();
    fill_cells_with(geom, layout, &all, index)
}

/// Fills the cells of `layout` with the primitives `ids` (ascending), as [`fill_cells`] does
/// with all of them: a two-level grid fills a cell's inner grid with that cell's primitives.
pub fn fill_cells_with<G: Geometry>(
    geom: &G,
    layout: &Layout,
    ids: &[u32],
    index: &str,
) -> Result<Cells, BuildError> {
    let n = ids.len() as u32;
    let total = AtomicUsize::new(0);
    let too_many = || BuildError::Failed {
        index: index.to_owned(),
        message: format!(
            "more than {MAX_REFS} primitive references (primitives spanning many cells): \
             lower the resolution or lambda"
        ),
    };
    // (cell, prim) pairs per chunk, chunks in primitive order.
    let parts = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|chunk| {
            ensure_within(index, 0, LOWER)?;
            let mut pairs: Vec<(u32, u32)> = Vec::new();
            for &prim in &ids[(chunk * CHUNK) as usize..((chunk + 1) * CHUNK).min(n) as usize] {
                let before = pairs.len();
                overlapped_cells(geom, layout, prim, |cell| {
                    pairs.push((cell as u32, prim));
                    pairs.len() <= MAX_REFS
                });
                let sum = total.fetch_add(pairs.len() - before, Ordering::Relaxed);
                if sum + pairs.len() - before > MAX_REFS {
                    return Err(too_many());
                }
            }
            Ok(pairs)
        })
        .collect::<Result<Vec<_>, BuildError>>()?;
    // Counting sort by cell; stable, so ids stay ascending within a cell. Its offsets (twice)
    // and ids are made while the pairs are still held.
    let cells = layout.cell_count();
    let refs: usize = parts.iter().map(Vec::len).sum();
    ensure_within(index, (2 * (cells + 1) + refs) * size_of::<u32>(), LOWER)?;
    let mut offsets = vec![0u32; cells + 1];
    for &(c, _) in parts.iter().flatten() {
        offsets[c as usize + 1] += 1;
    }
    for c in 0..cells {
        offsets[c + 1] += offsets[c];
    }
    let mut cursor = offsets.clone();
    let mut prims = vec![0u32; offsets[cells] as usize];
    for &(c, p) in parts.iter().flatten() {
        let slot = &mut cursor[c as usize];
        prims[*slot as usize] = p;
        *slot += 1;
    }
    Ok(Cells {
        offsets: huge_page_vec(offsets).into_boxed_slice(),
        prims: huge_page_vec(prims).into_boxed_slice(),
    })
}

/// Calls `f(linear cell)` for every cell whose grown box `prim` overlaps; stops early when `f`
/// returns `false`.
fn overlapped_cells<G: Geometry>(
    geom: &G,
    layout: &Layout,
    prim: u32,
    mut f: impl FnMut(usize) -> bool,
) {
    let b = geom.bounds(prim);
    let [rx, ry, rz] = [0, 1, 2].map(|a| layout.cell_range(a, b.min[a], b.max[a]));
    for z in rz {
        for y in ry.clone() {
            for x in rx.clone() {
                let c = [x, y, z];
                if geom.overlaps_box(prim, &layout.grown_cell_box(c)) && !f(layout.linear(c)) {
                    return;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::triangle::Watertight;
    use crate::geometry::{Aabb, Triangle};
    use crate::scene::Triangles;
    use glam::Vec3A;

    #[test]
    fn diagonal_triangle_fills_only_the_cells_it_crosses() {
        // A thin triangle along the diagonal of the xy square, at z = 0.5.
        let tri = Triangle::new(
            Vec3A::new(0.0, 0.0, 0.5),
            Vec3A::new(4.0, 4.0, 0.5),
            Vec3A::new(4.0, 3.9, 0.5),
        );
        // A second small one in the corner cell keeps the bounds a full cube.
        let corner = Triangle::new(Vec3A::ZERO, Vec3A::X * 0.1, Vec3A::splat(4.0));
        let g = Triangles::<Watertight>::new(vec![tri, corner].into());
        let layout = Layout::new(Aabb::new(Vec3A::ZERO, Vec3A::splat(4.0)), [4, 4, 1]);
        let cells = fill_cells(&g, &layout, "grid").unwrap();
        assert_eq!(cells.offsets.len(), 17);
        let holding: Vec<usize> = (0..16).filter(|&c| cells.of(c).contains(&0)).collect();
        // The diagonal cells and their edge/corner neighbours touched at the corners, never the
        // far corners of the square (which its bounding box covers).
        assert!(holding.contains(&layout.linear([0, 0, 0])));
        assert!(holding.contains(&layout.linear([3, 3, 0])));
        assert!(!holding.contains(&layout.linear([3, 0, 0])));
        assert!(!holding.contains(&layout.linear([0, 3, 0])));
        assert!(cells.offsets.windows(2).all(|w| w[0] <= w[1]));
        for c in 0..16 {
            assert!(cells.of(c).windows(2).all(|w| w[0] < w[1]));
        }
    }
}
