//! Uniform grid with 3D-DDA traversal (Amanatides & Woo 1987).
//!
//! - [`resolution`]: cells per axis, from the cube-root heuristic or given explicitly.
//! - [`layout`]: the boundary planes build and traversal share.
//! - [`build`]: primitives into the cells they really overlap, in compressed rows.
//! - [`dda`]: the walk of a ray through the cells, and why its stop condition is exact.
//!
//! Each primitive is tested at most once per ray (the shared per-thread mailbox).

mod build;
pub mod dda;
mod layout;
pub mod resolution;

pub use dda::Dda;
pub use layout::Layout;
pub use resolution::{DEFAULT_LAMBDA, MAX_CELLS, check_lambda, heuristic_resolution};

use crate::geometry::{Aabb, Ray};
use crate::index::kit::cell_walk::{CellVisit, CellWalk, cell_walk_index};
use crate::index::{BatchIndex, BuildError, Index, IndexInfo, Stats};
use crate::scene::Geometry;
pub(crate) use build::{Cells, MAX_REFS, fill_cells, fill_cells_with};
use serde::{Deserialize, Serialize};

/// Grid parameters: either a heuristic density `lambda` or an explicit `res`, not both. With
/// neither, the heuristic with [`DEFAULT_LAMBDA`].
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridParams {
    /// Cells per primitive for the cube-root heuristic (`grid:lambda=8`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda: Option<f32>,
    /// Cells per axis (`grid:res=[64,64,32]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub res: Option<[u32; 3]>,
}

impl GridParams {
    /// The resolution these parameters give for primitives in `bounds`, or why they are invalid.
    pub fn resolution(&self, bounds: &Aabb, prims: usize) -> Result<[u32; 3], String> {
        match (self.lambda, self.res) {
            (Some(_), Some(_)) => Err("give either lambda or res, not both".to_owned()),
            (_, Some(res)) => resolution::check_resolution(res).map(|()| res),
            (lambda, None) => {
                let lambda = lambda.unwrap_or(DEFAULT_LAMBDA);
                resolution::check_lambda(lambda)?;
                Ok(heuristic_resolution(bounds.extent(), prims, lambda))
            }
        }
    }
}

/// A uniform grid over the scene's bounds.
#[derive(Debug, Clone)]
pub struct Grid {
    layout: Layout,
    cells: Cells,
    /// Primitives the grid was built over.
    prim_count: usize,
}

impl Grid {
    /// Where the cells are (resolution, planes).
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Every cell's primitives, as compressed rows (for the GPU upload).
    #[cfg(feature = "gpu")]
    pub(crate) fn cells(&self) -> &Cells {
        &self.cells
    }

    /// The primitives stored in cell `c` (linear index), ascending.
    pub fn cell_prims(&self, c: usize) -> &[u32] {
        self.cells.of(c)
    }

    /// The cells `ray` crosses, front to back, with their exit distances (`None`: misses).
    pub fn walk(&self, ray: &Ray) -> Option<Dda<'_>> {
        Dda::new(&self.layout, ray)
    }
}

/// The 3D-DDA walk; stopping once the cutoff is at or before a cell's exit is exact (see the
/// `dda` module).
impl CellWalk for Grid {
    #[inline(always)]
    fn for_each_cell<S: Stats>(&self, ray: &Ray, stats: &mut S, mut visit: impl CellVisit<S>) {
        stats.box_tests(1);
        let Some(walk) = self.walk(ray) else {
            return;
        };
        for (cell, t_exit) in walk {
            stats.node_visit();
            if visit(self.cells.of(cell), stats) <= t_exit {
                return;
            }
        }
    }
}

/// The bounds of all of `geom`'s primitives, or an error for index `index` when they are not
/// finite.
pub(crate) fn finite_bounds<G: Geometry>(geom: &G, index: &str) -> Result<Aabb, BuildError> {
    let bounds = (0..geom.len() as u32)
        .map(|p| geom.bounds(p))
        .fold(Aabb::EMPTY, Aabb::union);
    if bounds.min.is_finite() && bounds.max.is_finite() {
        Ok(bounds)
    } else {
        Err(BuildError::Failed {
            index: index.to_owned(),
            message: "the scene bounds are not finite (NaN or infinite coordinates)".into(),
        })
    }
}

impl Index for Grid {
    type Params = GridParams;

    fn build<G: Geometry>(geom: &G, params: &GridParams) -> Result<Self, BuildError> {
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        let bad = |message: String| BuildError::Params {
            index: "grid".to_owned(),
            message,
        };
        let bounds = finite_bounds(geom, "grid")?;
        let res = params.resolution(&bounds, geom.len()).map_err(bad)?;
        let layout = Layout::new(bounds, res);
        let cells = fill_cells(geom, &layout, "grid")?;
        Ok(Grid {
            layout,
            cells,
            prim_count: geom.len(),
        })
    }

    // The build's peak heap a primitive: about 120 B measured (soup, bunny, icosphere), with a
    // margin; long thin primitives span more cells, and the fill checks the budget as it goes.
    cell_walk_index!(140);

    fn info(&self) -> IndexInfo {
        let cells = self.layout.cell_count();
        let refs = self.cells.prims.len();
        let filled = self
            .cells
            .offsets
            .windows(2)
            .filter(|w| w[0] < w[1])
            .count();
        let prims = self.prim_count.max(1);
        let planes: usize = self.layout.planes.iter().map(|p| p.len()).sum();
        let [rx, ry, rz] = self.layout.res;
        IndexInfo {
            nodes: cells,
            leaves: filled,
            depth: 1,
            memory_bytes: 4 * (self.cells.offsets.len() + refs + planes),
            prim_refs: refs,
            extra: vec![
                ("res_x".into(), rx as f64),
                ("res_y".into(), ry as f64),
                ("res_z".into(), rz as f64),
                (
                    "empty_cell_fraction".into(),
                    1.0 - filled as f64 / cells as f64,
                ),
                ("refs_per_prim".into(), refs as f64 / prims as f64),
            ],
            ..IndexInfo::default()
        }
    }
}

impl BatchIndex for Grid {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::triangle::Watertight;
    use crate::index::{BruteForce, Counters, NoStats};
    use crate::scene::Triangles;
    use glam::Vec3;

    fn params(s: &str) -> Result<GridParams, toml::de::Error> {
        toml::from_str(s)
    }

    #[test]
    fn params_parse_and_bad_ones_are_typed_errors() {
        let b = Aabb::new(glam::Vec3A::ZERO, glam::Vec3A::ONE);
        assert_eq!(
            params("res = [4, 5, 6]").unwrap().resolution(&b, 10),
            Ok([4, 5, 6])
        );
        assert_eq!(
            params("lambda = 8.0").unwrap().resolution(&b, 1000),
            Ok([20, 20, 20])
        );
        assert!(params("res = [4, 5]").is_err());
        assert!(params("res = [-1, 5, 5]").is_err());
        assert!(params("cells = 4").is_err());
        let both = params("lambda = 2.0\nres = [1, 1, 1]").unwrap();
        assert!(both.resolution(&b, 10).unwrap_err().contains("not both"));
        let g = Triangles::<Watertight>::new(crate::scene::generators::icosphere(1).into());
        for p in [
            "res = [0, 1, 1]",
            "lambda = -1.0",
            "res = [65536, 65536, 65536]",
        ] {
            let err = Grid::build(&g, &params(p).unwrap()).unwrap_err();
            assert!(matches!(err, BuildError::Params { .. }), "{p}: {err}");
        }
    }

    #[test]
    fn finds_brute_force_hits_and_reports_its_shape() {
        let g = Triangles::<Watertight>::new(crate::scene::generators::icosphere(2).into());
        let grid = Grid::build(&g, &GridParams::default()).unwrap();
        let brute = BruteForce::build(&g, &Default::default()).unwrap();
        for i in 0..200 {
            let a = i as f32 * 0.37;
            let o = Vec3::new(3.0 * a.cos(), 0.7 * a.sin(), 3.0 * a.sin());
            let r = Ray::infinite(o, Vec3::new(0.1, 0.05 * a.cos(), 0.0) - o).unwrap();
            let want = brute.closest_hit(&g, &r, &mut NoStats);
            let mut c = Counters::default();
            let got = grid.closest_hit(&g, &r, &mut c);
            assert_eq!(
                want.map(|h| (h.t.to_bits(), h.prim)),
                got.map(|h| (h.t.to_bits(), h.prim))
            );
            assert_eq!(grid.any_hit(&g, &r, &mut NoStats), want.is_some());
            assert!(c.prim_tests <= g.len() as u64);
        }
        let info = grid.info();
        assert_eq!(info.nodes, grid.layout().cell_count());
        assert!(info.leaves > 0 && info.leaves < info.nodes);
        assert!(info.prim_refs >= g.len());
        assert!(info.memory_bytes >= 4 * (info.nodes + 1 + info.prim_refs));
    }
}
