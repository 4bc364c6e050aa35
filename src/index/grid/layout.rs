//! Where the cells are: the grid's bounds, its resolution and the boundary planes that both the
//! build (cell boxes for the overlap test) and the 3D-DDA (crossing distances) read, so the two
//! always agree on where a cell ends.

use crate::geometry::Aabb;
use glam::Vec3A;

/// Relative size of the build margin (in units of the grid's diagonal), see [`Layout::margin`].
pub const MARGIN_REL: f32 = 1.0 / 65536.0;

/// The cell structure of a grid over `bounds`.
///
/// Invariants: `res[a] >= 1`; `planes[a]` holds `res[a] + 1` non-decreasing values, the first
/// `bounds.min[a]` and the last `bounds.max[a]`; cell `i` on axis `a` is the closed interval
/// `[planes[a][i], planes[a][i + 1]]`. A zero-extent axis has one cell of zero width.
#[derive(Debug, Clone)]
pub struct Layout {
    pub bounds: Aabb,
    pub res: [u32; 3],
    pub planes: [Box<[f32]>; 3],
    /// `res / extent` per axis (0 on a zero-extent axis): locates a point's cell approximately.
    pub inv_cell: Vec3A,
    /// Distance (scene units) by which every cell box is grown before the overlap test, so a
    /// primitive is stored in every cell it comes within `margin` of. It absorbs the rounding of
    /// the traversal's crossing distances and of the kernel's `t` (a few ulps of the distance from
    /// the ray origin), which the shared overlap pad (relative to the cell's own coordinates) does
    /// not cover for cells near the coordinate origin. With `MARGIN_REL` of the diagonal that is
    /// an estimate (a few ulps of the ray's distance) good for ray origins up to some tens of
    /// diagonals from the grid; `tests/it/grid.rs` checks rays from 60 diagonals away.
    pub margin: f32,
}

impl Layout {
    /// The layout of `res` cells over `bounds` (non-empty, finite; `res` checked by the caller).
    pub fn new(bounds: Aabb, res: [u32; 3]) -> Layout {
        let ext = bounds.extent();
        let planes = [0, 1, 2].map(|a| {
            let n = res[a] as usize;
            let step = ext[a] / res[a] as f32;
            (0..=n)
                .map(|i| match i {
                    0 => bounds.min[a],
                    i if i == n => bounds.max[a],
                    i => (bounds.min[a] + step * i as f32).min(bounds.max[a]),
                })
                .collect::<Box<[f32]>>()
        });
        let inv_cell = Vec3A::from_array([0, 1, 2].map(|a| {
            if ext[a] > 0.0 {
                res[a] as f32 / ext[a]
            } else {
                0.0
            }
        }));
        Layout {
            bounds,
            res,
            planes,
            inv_cell,
            margin: ext.length() * MARGIN_REL,
        }
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.res.iter().map(|&r| r as usize).product()
    }

    /// Linear index of cell `(x, y, z)`: `x + res_x * (y + res_y * z)`.
    #[inline]
    pub fn linear(&self, c: [u32; 3]) -> usize {
        c[0] as usize
            + self.res[0] as usize * (c[1] as usize + self.res[1] as usize * c[2] as usize)
    }

    /// The closed box of cell `c`, from its planes.
    pub fn cell_box(&self, c: [u32; 3]) -> Aabb {
        let lo = Vec3A::from_array([0, 1, 2].map(|a| self.planes[a][c[a] as usize]));
        let hi = Vec3A::from_array([0, 1, 2].map(|a| self.planes[a][c[a] as usize + 1]));
        Aabb::new(lo, hi)
    }

    /// The box of cell `c` grown by [`Layout::margin`] on every side (what the build tests
    /// primitives against).
    pub fn grown_cell_box(&self, c: [u32; 3]) -> Aabb {
        let b = self.cell_box(c);
        Aabb::new(b.min - self.margin, b.max + self.margin)
    }

    /// The layout of a grid of `res` cells inside cell `c` (a two-level grid's inner grid): its
    /// outer planes are `c`'s planes bit for bit, and its margin is this layout's, so a primitive
    /// in an inner cell's grown box is in `c`'s grown box too (it is among `c`'s primitives).
    pub fn inner(&self, c: [u32; 3], res: [u32; 3]) -> Layout {
        Layout {
            margin: self.margin,
            ..Layout::new(self.cell_box(c), res)
        }
    }

    /// The cell coordinates of linear index `i` (the inverse of [`Layout::linear`]).
    pub fn coords(&self, i: usize) -> [u32; 3] {
        let (rx, ry) = (self.res[0] as usize, self.res[1] as usize);
        [
            (i % rx) as u32,
            (i / rx % ry) as u32,
            (i / (rx * ry)) as u32,
        ]
    }

    /// Cells `first..end` on axis `a` whose grown interval meets `[lo, hi]` (a primitive's
    /// bounds): exactly the cells whose grown box can touch it on this axis.
    pub fn cell_range(&self, a: usize, lo: f32, hi: f32) -> std::ops::Range<u32> {
        let p = &self.planes[a];
        let n = self.res[a] as usize;
        let m = self.margin;
        let first = p[1..=n].partition_point(|&upper| upper + m < lo);
        let end = p[..n].partition_point(|&lower| lower - m <= hi);
        first as u32..end.max(first) as u32
    }

    /// The cell holding point coordinate `x` on axis `a`, clamped into the grid (approximate at
    /// a boundary: either neighbour is a correct start, see [`super::dda`]).
    #[inline]
    pub fn locate(&self, a: usize, x: f32) -> u32 {
        let i = ((x - self.bounds.min[a]) * self.inv_cell[a]).floor();
        // `as` saturates (NaN gives 0), then clamp to the last cell.
        (i as i64).clamp(0, self.res[a] as i64 - 1) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_span_the_bounds_and_ranges_cover_touching_cells() {
        let b = Aabb::new(Vec3A::new(-1.0, 0.0, 2.0), Vec3A::new(1.0, 0.0, 5.0));
        let l = Layout::new(b, [4, 1, 3]);
        assert_eq!(&*l.planes[0], &[-1.0, -0.5, 0.0, 0.5, 1.0]);
        assert_eq!(&*l.planes[1], &[0.0, 0.0]);
        assert_eq!(&*l.planes[2], &[2.0, 3.0, 4.0, 5.0]);
        assert_eq!(l.cell_count(), 12);
        assert_eq!(l.linear([3, 0, 2]), 3 + 4 * 2);
        // A value exactly on an interior plane touches both cells.
        assert_eq!(l.cell_range(0, 0.0, 0.0), 1..3);
        assert_eq!(l.cell_range(0, 0.1, 0.2), 2..3);
        assert_eq!(l.cell_range(0, -1.0, 1.0), 0..4);
        // The flat axis has one zero-width cell.
        assert_eq!(l.cell_range(1, 0.0, 0.0), 0..1);
        assert_eq!(l.inv_cell.y, 0.0);
        assert_eq!(l.locate(1, 0.0), 0);
        assert_eq!(l.locate(0, 0.75), 3);
        assert_eq!(l.locate(0, 7.0), 3);
        assert_eq!(l.locate(0, -7.0), 0);
        assert_eq!(l.locate(0, f32::NAN), 0);
        let c = l.grown_cell_box([1, 0, 0]);
        assert!(c.min.x < -0.5 && c.max.x > 0.0 && c.min.x > -0.51);
    }
}
