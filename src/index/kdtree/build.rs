//! SAH kd-tree construction with perfect splits.
//!
//! Candidate planes are the faces of the primitives' bounds clipped to the node (perfect splits,
//! Havran 2000), padded outward by `pad`. At every node the events of each axis are sorted and
//! swept once (the O(N log^2 N) variant of Wald & Havran 2006: a sort per node instead of one
//! global sort kept in order by splitting; simpler, and the bunny still builds in well under a
//! few seconds). The cost is the SAH with an empty-space bonus; a node becomes a leaf when no
//! split is cheaper than testing its primitives, at `max_depth`, or at `leaf_size` primitives.
//!
//! Classification is conservative: a primitive goes below a plane `s` when its clipped bounds,
//! grown by `pad`, start before `s`, and above when they end after `s`. So a primitive within
//! `pad` of the plane (touching it, lying in it, or rounding near it) is stored on both sides.
//! A primitive stored on both sides is clipped again to each child's cell (grown by `pad`).

use super::node::{KdNode, MAX_PAYLOAD};
use super::sweep::{Event, Weights, best_axis_split};
use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::scene::Geometry;
use glam::Vec3A;

/// The SAH weights and limits (validated by the caller).
pub(super) struct Costs {
    pub intersect: f32,
    pub traversal: f32,
    pub empty_bonus: f32,
    pub max_depth: u32,
    pub leaf_size: u32,
}

/// A primitive reference in a node: its id and the conservative bounds of its part in the cell.
#[derive(Debug, Clone, Copy)]
struct Ref {
    prim: u32,
    b: Aabb,
}

/// The flattened tree and figures for reports.
pub(super) struct Built {
    pub nodes: Vec<KdNode>,
    pub ids: Vec<u32>,
    pub depth: usize,
    pub leaves: usize,
    pub empty_leaves: usize,
}

struct Builder<'a, G: Geometry> {
    geom: &'a G,
    costs: &'a Costs,
    pad: f32,
    nodes: Vec<KdNode>,
    ids: Vec<u32>,
    events: Vec<Event>,
    depth: usize,
    leaves: usize,
    empty_leaves: usize,
}

/// Builds the tree over all primitives of `geom` in the cell `root` (their bounds), with
/// classification padding `pad` (world units, > 0).
pub(super) fn build<G: Geometry>(
    geom: &G,
    root: Aabb,
    pad: f32,
    costs: &Costs,
) -> Result<Built, BuildError> {
    let refs: Vec<Ref> = (0..geom.len() as u32)
        .map(|prim| Ref {
            prim,
            b: geom.bounds(prim),
        })
        .collect();
    let mut b = Builder {
        geom,
        costs,
        pad,
        nodes: Vec::new(),
        ids: Vec::new(),
        events: Vec::new(),
        depth: 0,
        leaves: 0,
        empty_leaves: 0,
    };
    b.node(refs, root, 0)?;
    Ok(Built {
        nodes: b.nodes,
        ids: b.ids,
        depth: b.depth,
        leaves: b.leaves,
        empty_leaves: b.empty_leaves,
    })
}

fn too_big(what: &str) -> BuildError {
    BuildError::Failed {
        index: "kdtree".into(),
        message: format!(
            "too many {what} for 30-bit node fields; raise leaf_size or lower max_depth"
        ),
    }
}

impl<G: Geometry> Builder<'_, G> {
    fn node(&mut self, refs: Vec<Ref>, cell: Aabb, depth: u32) -> Result<(), BuildError> {
        let at = self.nodes.len();
        if at as u64 > MAX_PAYLOAD as u64 {
            return Err(too_big("nodes"));
        }
        let split = if refs.len() as u32 <= self.costs.leaf_size || depth >= self.costs.max_depth {
            None
        } else {
            self.best_split(&refs, &cell)
        };
        let Some((axis, s)) = split else {
            return self.leaf(&refs, depth);
        };
        let (below_cell, above_cell) = split_cell(&cell, axis, s);
        let (below, above) = self.classify(refs, axis, s, &below_cell, &above_cell);
        self.nodes.push(KdNode::leaf(0, 0)); // placeholder, patched below
        self.node(below, below_cell, depth + 1)?;
        let above_at = self.nodes.len() as u32;
        self.node(above, above_cell, depth + 1)?;
        self.nodes[at] = KdNode::interior(axis, s, above_at);
        Ok(())
    }

    fn leaf(&mut self, refs: &[Ref], depth: u32) -> Result<(), BuildError> {
        if refs.len() as u64 > MAX_PAYLOAD as u64 || self.ids.len() + refs.len() > u32::MAX as usize
        {
            return Err(too_big("primitive references"));
        }
        let first = self.ids.len() as u32;
        let start = self.ids.len();
        self.ids.extend(refs.iter().map(|r| r.prim));
        self.ids[start..].sort_unstable();
        self.nodes.push(KdNode::leaf(first, refs.len() as u32));
        self.leaves += 1;
        self.empty_leaves += refs.is_empty() as usize;
        self.depth = self.depth.max(depth as usize + 1);
        Ok(())
    }

    /// The cheapest plane `(axis, position)` strictly inside the cell, if cheaper than a leaf.
    fn best_split(&mut self, refs: &[Ref], cell: &Aabb) -> Option<(usize, f32)> {
        let w = Weights {
            intersect: self.costs.intersect,
            traversal: self.costs.traversal,
            empty_bonus: self.costs.empty_bonus,
        };
        best_axis_split(
            refs.len(),
            |i| refs[i].b,
            cell,
            self.pad,
            &w,
            &mut self.events,
        )
        .map(|(axis, s, _)| (axis, s))
    }

    /// Sends each reference to the side(s) it touches (within `pad`); references on both sides
    /// are clipped again to each child's cell.
    fn classify(
        &self,
        refs: Vec<Ref>,
        axis: usize,
        s: f32,
        below_cell: &Aabb,
        above_cell: &Aabb,
    ) -> (Vec<Ref>, Vec<Ref>) {
        let (mut below, mut above) = (Vec::new(), Vec::new());
        let grow = |c: &Aabb| {
            Aabb::new(
                c.min - Vec3A::splat(self.pad),
                c.max + Vec3A::splat(self.pad),
            )
        };
        let (below_clip, above_clip) = (grow(below_cell), grow(above_cell));
        for r in refs {
            let to_above = r.b.max[axis] + self.pad > s;
            let to_below = r.b.min[axis] - self.pad < s || !to_above;
            if to_below && to_above {
                if let Some(b) = self.clip(r.prim, &below_clip) {
                    below.push(Ref { prim: r.prim, b });
                }
                if let Some(b) = self.clip(r.prim, &above_clip) {
                    above.push(Ref { prim: r.prim, b });
                }
            } else if to_below {
                below.push(r);
            } else {
                above.push(r);
            }
        }
        (below, above)
    }

    /// Conservative bounds of the primitive's part in `cell`, or `None` when it does not even
    /// touch the cell's box.
    fn clip(&self, prim: u32, cell: &Aabb) -> Option<Aabb> {
        let b = self.geom.clipped_bounds(prim, cell);
        if !b.is_empty() {
            return Some(b);
        }
        // Rounding in the clipper: fall back to the box overlap.
        let b = self.geom.bounds(prim).intersection(*cell);
        (!b.is_empty()).then_some(b)
    }
}

/// The two children of `cell` split at `s` on `axis`.
fn split_cell(cell: &Aabb, axis: usize, s: f32) -> (Aabb, Aabb) {
    let (mut below, mut above) = (*cell, *cell);
    below.max[axis] = s;
    above.min[axis] = s;
    (below, above)
}
