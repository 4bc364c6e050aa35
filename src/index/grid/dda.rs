//! The 3D-DDA (Amanatides & Woo 1987): the cells a ray crosses, front to back, each with the
//! distance at which the ray leaves it.
//!
//! # Why "stop once the best hit is at or before the current cell's exit" is exact
//!
//! The walk starts at the ray's entry into the grid box (clipped to `t_min`) and steps, one
//! cell at a time, to the neighbour across the nearest boundary plane. Crossing distances are
//! computed afresh from the stored planes (`(plane - origin) * inv_dir`), never accumulated, so
//! each carries a few ulps of relative error, and they are monotone along the walk.
//!
//! Suppose the walk stops after cell `C` because `best.t <= exit(C)`, and some primitive `q`
//! would beat `best` (`t_q < best.t`, or `t_q == best.t` with a lower id). Then `t_q <= exit(C)`,
//! and `t_q >= entry into the grid box` (the `Geometry` contract clamps `t_q` into the slab
//! interval of `q`'s bounds, which lie in the grid box, and the slab test is monotone). So the
//! point the ray reaches at `t_q` lies in the part of the ray the walk has covered: in a visited
//! cell, or within rounding distance of one (the computed crossing distances, the computed start
//! point, or a corner cut that the rounded walk stepped around). That point lies on `q` up to the
//! kernel's own rounding of `t_q`. Every cell box was grown by [`super::layout::Layout::margin`]
//! before the conservative overlap test, which exceeds both roundings, so `q` is stored in that
//! visited cell and was tested: `q` cannot beat `best`.
//!
//! Ties on a boundary: when `best.t == exit(C)` exactly and `q` (lower id) is hit at the same
//! `t` in the next cell, its hit point lies on the shared face; cells are closed boxes, so `q`
//! touches `C` and was tested in `C`. Hence "at or before" (`<=`) is enough, and continuing on
//! `<` would only cost time.
//!
//! Robustness: a direction component of `+0.0` or `-0.0` (or so small that its inverse is
//! infinite) never steps on that axis (its crossing distance is `+inf`); a ray on a boundary
//! plane may start in either neighbouring cell (both touch the plane). Each step moves one axis
//! index monotonically, so a walk visits at most `res_x + res_y + res_z - 2` cells and then ends
//! (or ends when no axis can step). No NaN enters the crossing distances: they are only
//! computed for finite inverse directions.

use super::layout::Layout;
use crate::geometry::Ray;

/// The walk of one ray through a grid: an iterator of `(linear cell index, exit distance)`.
///
/// Each axis is stepped by its own monomorphized code ([`Dda::step_on`]), so that a walk inlined
/// into a loop keeps its state in registers (an axis chosen at run time would index the state
/// arrays through memory at every step).
#[derive(Debug, Clone)]
pub struct Dda<'a> {
    layout: &'a Layout,
    origin: [f32; 3],
    inv_dir: [f32; 3],
    cell: [i32; 3],
    /// The cell index at which the walk has left the grid on each axis (`-1` or `res`), or the
    /// current index on an axis that never steps.
    end: [i32; 3],
    /// `-1`, `0` (never steps on this axis) or `+1`.
    step: [i32; 3],
    /// `1` on axes stepping up (a cell's exit plane is its upper one), else `0`.
    exit_plane: [i32; 3],
    linear: usize,
    /// How `linear` changes when stepping on each axis.
    stride: [isize; 3],
    /// Distance at which the ray crosses the next boundary plane on each axis (`+inf` when the
    /// axis does not step).
    t_next: [f32; 3],
    done: bool,
}

impl<'a> Dda<'a> {
    /// The walk of `ray` over `[ray.t_min, ray.t_max]`, or `None` when it misses the grid box.
    #[inline]
    pub fn new(layout: &'a Layout, ray: &Ray) -> Option<Dda<'a>> {
        let (enter, _) = layout.bounds.ray_interval(ray, ray.t_min, ray.t_max)?;
        Some(Dda::starting_at(layout, ray, enter))
    }

    /// The walk of `ray` from parameter `t` on: it starts in the cell holding `ray.at(t)`
    /// (clamped into the grid, so a point just outside starts in the nearest boundary cell) and
    /// ends when it steps out of the grid. A two-level grid walks a cell's own grid this way from
    /// the parameter at which the top-level walk entered the cell: when the inner grid's outer
    /// planes are the cell's planes bit for bit, its last exit is the top-level walk's exit from
    /// the cell (both are the smallest crossing of the same outer planes).
    #[inline(always)]
    pub fn starting_at(layout: &'a Layout, ray: &Ray, t: f32) -> Dda<'a> {
        let start = ray.at(t);
        let origin = ray.origin.to_array();
        let inv_dir = ray.inv_dir.to_array();
        let cell = [0, 1, 2].map(|a| layout.locate(a, start[a]));
        let res = layout.res;
        let base = [1isize, res[0] as isize, res[0] as isize * res[1] as isize];
        let mut step = [0i32; 3];
        let mut end = cell.map(|c| c as i32);
        let mut exit_plane = [0i32; 3];
        let mut stride = [0isize; 3];
        let mut t_next = [f32::INFINITY; 3];
        for a in 0..3 {
            let inv = inv_dir[a];
            if !inv.is_finite() {
                continue;
            }
            let up = inv > 0.0;
            step[a] = if up { 1 } else { -1 };
            end[a] = if up { res[a] as i32 } else { -1 };
            exit_plane[a] = i32::from(up);
            stride[a] = base[a] * step[a] as isize;
            let plane = layout.planes[a][(cell[a] + u32::from(up)) as usize];
            t_next[a] = (plane - origin[a]) * inv;
        }
        Dda {
            layout,
            origin,
            inv_dir,
            linear: layout.linear(cell),
            cell: cell.map(|c| c as i32),
            end,
            step,
            exit_plane,
            stride,
            t_next,
            done: false,
        }
    }

    /// Leaves the current cell across its exit plane on axis `A`; returns the exit distance.
    #[inline(always)]
    fn step_on<const A: usize>(&mut self) -> f32 {
        let exit = self.t_next[A];
        let next = self.cell[A] + self.step[A];
        if next == self.end[A] {
            self.done = true;
        } else {
            self.cell[A] = next;
            self.linear = self.linear.wrapping_add_signed(self.stride[A]);
            let plane = self.layout.planes[A][(next + self.exit_plane[A]) as usize];
            self.t_next[A] = (plane - self.origin[A]) * self.inv_dir[A];
        }
        exit
    }
}

impl Iterator for Dda<'_> {
    type Item = (usize, f32);

    #[inline(always)]
    fn next(&mut self) -> Option<(usize, f32)> {
        if self.done {
            return None;
        }
        let cell = self.linear;
        let [tx, ty, tz] = self.t_next;
        // The nearest crossing; ties (a ray through an edge or corner) to the lowest axis.
        let exit = if tx <= ty && tx <= tz {
            self.step_on::<0>()
        } else if ty <= tz {
            self.step_on::<1>()
        } else {
            self.step_on::<2>()
        };
        Some((cell, exit))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use glam::{Vec3, Vec3A};

    fn layout() -> Layout {
        Layout::new(Aabb::new(Vec3A::ZERO, Vec3A::splat(4.0)), [4, 4, 4])
    }

    fn walk(o: [f32; 3], d: [f32; 3]) -> Vec<(usize, f32)> {
        let l = layout();
        let r = Ray::infinite(Vec3::from(o), Vec3::from(d)).unwrap();
        Dda::new(&l, &r).map(|w| w.collect()).unwrap_or_default()
    }

    #[test]
    fn axis_parallel_walks_with_signed_zeros() {
        let l = layout();
        let row: Vec<usize> = (0..4).map(|x| l.linear([x, 1, 2])).collect();
        for d in [[1.0, 0.0, 0.0], [1.0, -0.0, -0.0]] {
            let w = walk([-1.0, 1.5, 2.5], d);
            assert_eq!(w.iter().map(|c| c.0).collect::<Vec<_>>(), row);
            assert_eq!(
                w.iter().map(|c| c.1).collect::<Vec<_>>(),
                [2.0, 3.0, 4.0, 5.0]
            );
        }
        let back = walk([9.0, 1.5, 2.5], [-1.0, 0.0, -0.0]);
        let mut rev = row.clone();
        rev.reverse();
        assert_eq!(back.iter().map(|c| c.0).collect::<Vec<_>>(), rev);
    }

    #[test]
    fn diagonal_walk_visits_each_axis_step_and_ends() {
        // Through the corners of cells: 4 cells per axis, 3 steps per axis, 10 cells in all.
        let w = walk([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]);
        assert_eq!(w.len(), 10);
        assert!(w.windows(2).all(|p| p[0].1 <= p[1].1));
        // Starting inside, on a boundary plane, and missing the grid.
        let inside = walk([2.0, 0.5, 0.5], [1.0, 0.0, 0.0]);
        assert_eq!(inside.len(), 2);
        assert!(walk([-1.0, 5.0, 0.5], [1.0, 0.0, 0.0]).is_empty());
    }

    #[test]
    fn tiny_direction_components_do_not_step_or_loop() {
        let w = walk([0.5, 0.5, 0.5], [1e-45, 1e-45, 1e-45]);
        assert_eq!(w.len(), 1);
    }
}
