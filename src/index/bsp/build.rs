//! General BSP construction: at each node a handful of candidate planes (axis planes at
//! quantiles of the primitives' bounds, and the own planes of sampled triangles,
//! autopartition-style) are scored by a cost estimate and the cheapest one splits the node.
//!
//! Every candidate is scored by the SAH `traversal + intersect * (A(below) N(below) + A(above)
//! N(above)) / A` (with the kd-tree's empty-space bonus) over the exact surface areas of the
//! convex cells (Ize, Wald & Parker 2008): each node carries its cell as a
//! [`ConvexPolyhedron`], and a candidate's two areas come from cutting it by the plane. Axis
//! candidates: the best plane of the kd-tree's SAH sweep over perfect-split candidates in the
//! cell's bounding box (box areas find the position, exact areas score it), and optionally
//! `axis_candidates` quantile positions. A plane that leaves either side of the cell without
//! volume is not a candidate. Each node also keeps a conservative box around its cell (the
//! parent's box cut by the plane, [`box_halfspace_bounds`], and by the polyhedron's bounds
//! grown by `pad`) to clip its references' bounds.
//!
//! Classification is conservative: a primitive goes below a plane when its extent along the
//! normal, grown by `pad`, starts below the offset, and above when it ends above it; within
//! `pad` of the plane (touching it, lying in it, or rounding near it) it goes to both sides.
//!
//! Build time is `O(candidates * N)` per level: the candidate counts cap it.

use super::node::{BspNode, MAX_LINK};
use crate::geometry::Aabb;
use crate::geometry::clip::box_halfspace_bounds;
use crate::geometry::polyhedron::ConvexPolyhedron;
use crate::index::BuildError;
use crate::index::build_budget::ensure_within;
use crate::index::kit::near_far::sweep::{Ref, Weights, best_axis_split};
use crate::index::kit::near_far::{Built, SahParams};
use crate::scene::Geometry;
use glam::Vec3A;

/// Weights and limits (validated by the caller).
pub(super) struct Limits {
    pub sah: SahParams,
    pub sweep: bool,
    pub axis_candidates: u32,
    pub plane_candidates: u32,
}

/// A candidate plane `normal . p = offset`; `axis` when the normal is a unit axis.
#[derive(Debug, Clone, Copy)]
struct Plane {
    normal: Vec3A,
    offset: f32,
    axis: Option<usize>,
}

impl Plane {
    /// The axis plane `x[axis] = offset`.
    fn axis(axis: usize, offset: f32) -> Plane {
        let mut normal = Vec3A::ZERO;
        normal[axis] = 1.0;
        Plane {
            normal,
            offset,
            axis: Some(axis),
        }
    }
}

struct Builder<'a, G: Geometry> {
    geom: &'a G,
    limits: &'a Limits,
    pad: f32,
    out: Built<BspNode>,
    /// Interior nodes split by an axis plane.
    axis_splits: usize,
}

pub(super) fn build<G: Geometry>(
    geom: &G,
    root: Aabb,
    pad: f32,
    limits: &Limits,
) -> Result<Built<BspNode>, BuildError> {
    let refs = (0..geom.len() as u32)
        .map(|prim| Ref {
            prim,
            b: geom.bounds(prim),
        })
        .collect();
    let mut b = Builder {
        geom,
        limits,
        pad,
        out: Built {
            nodes: Vec::new(),
            ids: Vec::new(),
            refs: 0,
            depth: 0,
            leaves: 0,
            empty_leaves: 0,
            extra: Vec::new(),
        },
        axis_splits: 0,
    };
    b.node(refs, root, ConvexPolyhedron::from_box(&root), 0)?;
    let interior = b.out.nodes.len() - b.out.leaves;
    let general = (interior - b.axis_splits) as f64 / interior.max(1) as f64;
    b.out.extra = vec![("general_plane_fraction".into(), general)];
    Ok(b.out)
}

fn too_big() -> BuildError {
    BuildError::Failed {
        index: "bsp".into(),
        message:
            "too many nodes or references for 31-bit links; raise leaf_size or lower max_depth"
                .into(),
    }
}

impl<G: Geometry> Builder<'_, G> {
    /// Builds the subtree of the convex cell `poly` (for costs) with the conservative bounding
    /// box `cell` (for clipping references).
    fn node(
        &mut self,
        refs: Vec<Ref>,
        cell: Aabb,
        poly: ConvexPolyhedron,
        depth: u32,
    ) -> Result<(), BuildError> {
        let at = self.out.nodes.len();
        if at as u64 > MAX_LINK as u64 {
            return Err(too_big());
        }
        ensure_within("bsp", 0, "raise leaf_size or lower max_depth")?;
        let sah = &self.limits.sah;
        let plane = if refs.len() as u32 <= sah.leaf_size || depth >= sah.max_depth {
            None
        } else {
            self.best_plane(&refs, &cell, &poly)
        };
        let Some(plane) = plane else {
            return self.leaf(&refs, depth);
        };
        let (below_poly, above_poly) = poly.split(plane.normal, plane.offset);
        drop(poly);
        let (below_cell, above_cell) = self.child_cells(&cell, &plane);
        let (below_cell, above_cell) = (
            self.tighten(below_cell, &below_poly),
            self.tighten(above_cell, &above_poly),
        );
        self.axis_splits += plane.axis.is_some() as usize;
        let (below, above) = self.classify(refs, &plane, &below_cell, &above_cell);
        self.out.nodes.push(BspNode::leaf(0, 0)); // placeholder, patched below
        self.node(below, below_cell, below_poly, depth + 1)?;
        let above_at = self.out.nodes.len() as u32;
        self.node(above, above_cell, above_poly, depth + 1)?;
        self.out.nodes[at] = BspNode::interior(plane.normal, plane.offset, above_at);
        Ok(())
    }

    /// A leaf over `refs`: one primitive is held in the node itself, more as a sorted run of
    /// the id array.
    fn leaf(&mut self, refs: &[Ref], depth: u32) -> Result<(), BuildError> {
        let o = &mut self.out;
        if refs.len() as u64 > MAX_LINK as u64 || o.ids.len() + refs.len() > u32::MAX as usize {
            return Err(too_big());
        }
        let node = if let [one] = refs {
            BspNode::leaf(one.prim, 1)
        } else {
            let first = o.ids.len();
            o.ids.extend(refs.iter().map(|r| r.prim));
            o.ids[first..].sort_unstable();
            BspNode::leaf(first as u32, refs.len() as u32)
        };
        o.nodes.push(node);
        o.refs += refs.len();
        o.leaves += 1;
        o.empty_leaves += refs.is_empty() as usize;
        o.depth = o.depth.max(depth as usize + 1);
        Ok(())
    }

    /// Boxes around the two children of a cell (grown by `pad` for a general plane, whose cut
    /// is rounded).
    fn child_cells(&self, cell: &Aabb, p: &Plane) -> (Aabb, Aabb) {
        if let Some(a) = p.axis {
            let (mut below, mut above) = (*cell, *cell);
            below.max[a] = p.offset;
            above.min[a] = p.offset;
            return (below, above);
        }
        let grow = |b: Aabb| {
            Aabb::new(
                b.min - Vec3A::splat(self.pad),
                b.max + Vec3A::splat(self.pad),
            )
            .intersection(*cell)
        };
        (
            grow(box_halfspace_bounds(cell, p.normal, p.offset, true)),
            grow(box_halfspace_bounds(cell, p.normal, p.offset, false)),
        )
    }

    /// `cell` cut to the bounds of the cell's polyhedron grown by `pad` (which covers the
    /// polyhedron's `f64` rounding many times over), or `cell` when rounding emptied either.
    fn tighten(&self, cell: Aabb, poly: &ConvexPolyhedron) -> Aabb {
        let b = poly.bounds();
        if b.is_empty() {
            return cell;
        }
        let pad = Vec3A::splat(self.pad);
        let t = cell.intersection(Aabb::new(b.min - pad, b.max + pad));
        if t.is_empty() { cell } else { t }
    }

    /// `(below, above)`: the sides a reference goes to (at least one).
    #[inline]
    fn sides(&self, r: &Ref, p: &Plane) -> (bool, bool) {
        let (lo, hi) = match p.axis {
            Some(a) => (r.b.min[a], r.b.max[a]),
            None => self.geom.extent_along(r.prim, p.normal),
        };
        let above = hi + self.pad > p.offset;
        let below = lo - self.pad < p.offset || !above;
        (below, above)
    }

    /// Axis planes at quantiles of the references' padded bounds (perfect-split positions,
    /// strictly inside the cell) and the
    /// own planes of references sampled evenly.
    fn candidates(&self, refs: &[Ref], cell: &Aabb) -> Vec<Plane> {
        let per_axis = self.limits.axis_candidates as usize;
        let own = self.limits.plane_candidates as usize;
        let mut planes = Vec::with_capacity(3 * per_axis + own);
        let mut positions: Vec<f32> = Vec::with_capacity(refs.len());
        for axis in 0..3 {
            positions.clear();
            positions.extend(refs.iter().map(|r| r.b.min[axis] - self.pad));
            positions.extend(refs.iter().map(|r| r.b.max[axis] + self.pad));
            positions.sort_unstable_by(f32::total_cmp);
            for q in 1..=per_axis {
                let s = positions[q * (positions.len() - 1) / (per_axis + 1)];
                if s > cell.min[axis] && s < cell.max[axis] {
                    planes.push(Plane::axis(axis, s));
                }
            }
        }
        let step = refs.len().checked_div(own).unwrap_or(1).max(1);
        for r in refs.iter().step_by(step).take(own) {
            if let Some((normal, offset)) = self.geom.own_plane(r.prim) {
                planes.push(Plane {
                    normal,
                    offset,
                    axis: None,
                });
            }
        }
        planes
    }

    /// The cheapest plane, if cheaper than a leaf and separating something: the best axis
    /// plane of the full SAH sweep over the cell's box (as in the kd-tree, when `sweep` is
    /// on), axis planes at `axis_candidates` quantiles and the own planes of sampled
    /// primitives, all scored by the SAH over the exact surface areas of the cell's polyhedron
    /// and of its two parts (Ize, Wald & Parker 2008).
    fn best_plane(&self, refs: &[Ref], cell: &Aabb, poly: &ConvexPolyhedron) -> Option<Plane> {
        let area = poly.area();
        if area <= 0.0 || !area.is_finite() || cell.surface_area() <= 0.0 {
            return None;
        }
        let l = self.limits;
        let n = refs.len();
        let mut planes = Vec::new();
        if l.sweep {
            let w = Weights::from(&l.sah);
            let mut events = Default::default();
            if let Some((axis, s, _)) =
                best_axis_split(n, |i| refs[i].b, cell, self.pad, &w, &mut events)
            {
                planes.push(Plane::axis(axis, s));
            }
        }
        planes.extend(self.candidates(refs, cell));
        let mut best = None;
        let mut best_cost = l.sah.intersect as f64 * n as f64;
        for p in planes {
            let (mut nb, mut na) = (0usize, 0usize);
            for r in refs {
                let (below, above) = self.sides(r, &p);
                nb += below as usize;
                na += above as usize;
            }
            if nb == n && na == n {
                continue; // separates nothing
            }
            let (ab, aa) = poly.split_areas(p.normal, p.offset);
            if ab <= 0.0 || aa <= 0.0 {
                continue; // misses the cell
            }
            let bonus = if nb == 0 || na == 0 {
                1.0 - l.sah.empty_bonus as f64
            } else {
                1.0
            };
            let cost = l.sah.traversal as f64
                + l.sah.intersect as f64 * bonus * (ab * nb as f64 + aa * na as f64) / area;
            if cost < best_cost {
                best_cost = cost;
                best = Some(p);
            }
        }
        best
    }

    /// Sends each reference to its side(s); references on both sides of an axis plane are
    /// clipped again to each child's box (grown by `pad`).
    fn classify(
        &self,
        refs: Vec<Ref>,
        p: &Plane,
        below_cell: &Aabb,
        above_cell: &Aabb,
    ) -> (Vec<Ref>, Vec<Ref>) {
        let grow = |c: &Aabb| {
            Aabb::new(
                c.min - Vec3A::splat(self.pad),
                c.max + Vec3A::splat(self.pad),
            )
        };
        let (below_clip, above_clip) = (grow(below_cell), grow(above_cell));
        let (mut below, mut above) = (Vec::new(), Vec::new());
        for r in refs {
            match self.sides(&r, p) {
                (true, true) if p.axis.is_some() => {
                    for (clip, out) in [(&below_clip, &mut below), (&above_clip, &mut above)] {
                        let b = self.geom.clipped_bounds(r.prim, clip);
                        let b = if b.is_empty() {
                            self.geom.bounds(r.prim).intersection(*clip)
                        } else {
                            b
                        };
                        if !b.is_empty() {
                            out.push(Ref { prim: r.prim, b });
                        }
                    }
                }
                (true, true) => {
                    for (clip, out) in [(&below_clip, &mut below), (&above_clip, &mut above)] {
                        let b = r.b.intersection(*clip);
                        out.push(Ref {
                            prim: r.prim,
                            b: if b.is_empty() { r.b } else { b },
                        });
                    }
                }
                (true, false) => below.push(r),
                _ => above.push(r),
            }
        }
        (below, above)
    }
}
