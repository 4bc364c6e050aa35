//! SAH kd-tree construction with perfect splits in `O(N log N)` (Wald & Havran 2006).
//!
//! Candidate planes are the faces of the primitives' bounds clipped to the node (perfect splits,
//! Havran 2000), padded outward by `pad`. The events of all primitives are sorted once per axis
//! at the root; each node finds its plane by one linear sweep per axis
//! ([`best_split_sorted`]) and hands its children event lists that are still sorted: the events
//! of primitives on one side only are filtered in order, and only the primitives on both sides,
//! clipped again to each child's cell, get new events, which are sorted (there are few) and
//! merged in. The cost is the SAH with an empty-space bonus; a node becomes a leaf when no split
//! is cheaper than testing its primitives, at `max_depth`, or at `leaf_size` primitives.
//!
//! Classification is conservative: a primitive goes below a plane `s` when its clipped bounds,
//! grown by `pad`, start before `s`, and above when they end after `s`. So a primitive within
//! `pad` of the plane (touching it, lying in it, or rounding near it) is stored on both sides.
//! A primitive stored on both sides is clipped again to each child's cell (grown by `pad`).
//!
//! The tree is the one a per-node sort of the same events gives (the test module keeps that
//! builder as an oracle and compares the trees node for node).

use super::node::{KdNode, MAX_PAYLOAD};
use super::sweep::{Event, MAX_ITEM, Weights, best_split_sorted, push_events};
use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::index::near_far::{Built, SahParams};
use crate::scene::Geometry;
use glam::Vec3A;

/// The events of a node's primitives on each axis, each list sorted by [`Event::order`]; the
/// items are primitive ids (a primitive is at most once in a node), and every primitive of the
/// node has exactly one start and one end event per axis.
type Events = [Vec<Event>; 3];

/// Where a node's primitive goes at the chosen plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Below,
    Above,
    Both,
}

struct Builder<'a, G: Geometry> {
    geom: &'a G,
    costs: &'a SahParams,
    pad: f32,
    nodes: Vec<KdNode>,
    ids: Vec<u32>,
    /// References over all leaves so far.
    refs: usize,
    /// Scratch, by primitive id: the side of each primitive of the node being split.
    side: Vec<Side>,
    /// Scratch: the primitives of the node being split that go to both sides.
    straddling: Vec<u32>,
    /// Event lists no node uses any more, kept for their allocations (cleared when taken).
    pool: Vec<Vec<Event>>,
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
    costs: &SahParams,
) -> Result<Built<KdNode>, BuildError> {
    if geom.len() > MAX_ITEM as usize {
        return Err(too_big("primitives"));
    }
    let events = root_events(geom, pad);
    subtree(geom, costs, pad, events, geom.len(), root, 0, PARALLEL)
}

/// The sorted events of all primitives' bounds (grown by `pad`).
fn root_events<G: Geometry>(geom: &G, pad: f32) -> Events {
    let n = geom.len();
    let mut events: Events = std::array::from_fn(|_| Vec::with_capacity(2 * n));
    for prim in 0..n as u32 {
        push_events(&mut events, &geom.bounds(prim), pad, prim);
    }
    for list in &mut events {
        list.sort_unstable_by(Event::order);
    }
    events
}

/// Which nodes build their two children in parallel (`rayon::join`): those of the top `levels`
/// levels with at least `min_prims` primitives.
#[derive(Debug, Clone, Copy)]
struct Parallel {
    levels: u32,
    min_prims: usize,
}

/// Up to `2^6` tasks, enough to keep a few cores busy while the sequential subtrees stay large.
const PARALLEL: Parallel = Parallel {
    levels: 6,
    min_prims: 2048,
};

/// Builds the subtree of `cell` over the `n` primitives with events `events` (`depth` of its
/// root), splitting the work into two `rayon::join` tasks as `par` says. The tree
/// is the one the sequential [`Builder::node`] makes: the same choices, the same depth-first
/// layout ([`join_subtrees`] only shifts the links of each part).
#[allow(clippy::too_many_arguments)]
fn subtree<G: Geometry>(
    geom: &G,
    costs: &SahParams,
    pad: f32,
    events: Events,
    n: usize,
    cell: Aabb,
    depth: u32,
    par: Parallel,
) -> Result<Built<KdNode>, BuildError> {
    let mut b = Builder {
        geom,
        costs,
        pad,
        nodes: Vec::new(),
        ids: Vec::new(),
        refs: 0,
        side: vec![Side::Both; geom.len()],
        straddling: Vec::new(),
        pool: Vec::new(),
        depth: 0,
        leaves: 0,
        empty_leaves: 0,
    };
    let split = (par.levels > 0 && n >= par.min_prims)
        .then(|| b.choose(&events, n, &cell, depth))
        .flatten();
    let Some((axis, s)) = split else {
        b.node(events, n, cell, depth)?;
        return Ok(Built {
            nodes: b.nodes,
            ids: b.ids,
            refs: b.refs,
            depth: b.depth,
            leaves: b.leaves,
            empty_leaves: b.empty_leaves,
            extra: Vec::new(),
        });
    };
    let (below_cell, above_cell) = split_cell(&cell, axis, s);
    let ((below, nb), (above, na)) = b.partition(events, axis, s, &below_cell, &above_cell);
    drop(b);
    let par = Parallel {
        levels: par.levels - 1,
        ..par
    };
    let part = |events, n, cell| subtree(geom, costs, pad, events, n, cell, depth + 1, par);
    let (below, above) = rayon::join(
        || part(below, nb, below_cell),
        || part(above, na, above_cell),
    );
    join_subtrees(axis, s, below?, above?)
}

/// The tree of an interior node on `axis` at `s` over its two built subtrees: the node, then
/// the subtree below (links shifted by one node), then the one above (links shifted by the
/// nodes and ids before it).
fn join_subtrees(
    axis: usize,
    s: f32,
    below: Built<KdNode>,
    above: Built<KdNode>,
) -> Result<Built<KdNode>, BuildError> {
    let above_at = 1 + below.nodes.len();
    if (above_at + above.nodes.len()) as u64 > MAX_PAYLOAD as u64 + 1 {
        return Err(too_big("nodes"));
    }
    if below.ids.len() + above.ids.len() > u32::MAX as usize {
        return Err(too_big("primitive references"));
    }
    let mut nodes = Vec::with_capacity(above_at + above.nodes.len());
    nodes.push(KdNode::interior(axis, s, above_at as u32));
    nodes.extend(below.nodes.iter().map(|n| n.shifted(1, 0)));
    let (node_shift, id_shift) = (above_at as u32, below.ids.len() as u32);
    nodes.extend(above.nodes.iter().map(|n| n.shifted(node_shift, id_shift)));
    let mut ids = below.ids;
    ids.extend(above.ids);
    Ok(Built {
        nodes,
        ids,
        refs: below.refs + above.refs,
        depth: below.depth.max(above.depth),
        leaves: below.leaves + above.leaves,
        empty_leaves: below.empty_leaves + above.empty_leaves,
        extra: Vec::new(),
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
    /// Builds the subtree of `cell` over the `n` primitives with events `events`.
    fn node(&mut self, events: Events, n: usize, cell: Aabb, depth: u32) -> Result<(), BuildError> {
        let at = self.nodes.len();
        if at as u64 > MAX_PAYLOAD as u64 {
            return Err(too_big("nodes"));
        }
        let Some((axis, s)) = self.choose(&events, n, &cell, depth) else {
            let leaf = self.leaf(&events[0], depth);
            self.pool.extend(events);
            return leaf;
        };
        let (below_cell, above_cell) = split_cell(&cell, axis, s);
        let ((below, nb), (above, na)) = self.partition(events, axis, s, &below_cell, &above_cell);
        self.nodes.push(KdNode::leaf(0, 0)); // placeholder, patched below
        self.node(below, nb, below_cell, depth + 1)?;
        let above_at = self.nodes.len() as u32;
        self.node(above, na, above_cell, depth + 1)?;
        self.nodes[at] = KdNode::interior(axis, s, above_at);
        Ok(())
    }

    /// The plane `(axis, position)` that splits the node, or `None` for a leaf.
    fn choose(&self, events: &Events, n: usize, cell: &Aabb, depth: u32) -> Option<(usize, f32)> {
        if n as u32 <= self.costs.leaf_size || depth >= self.costs.max_depth {
            return None;
        }
        best_split_sorted(events, n, cell, &Weights::from(self.costs)).map(|(a, s, _)| (a, s))
    }

    /// A leaf over the primitives whose start events are in `events` (one axis's list): one
    /// primitive is held in the node itself, more as a sorted run of the id array.
    fn leaf(&mut self, events: &[Event], depth: u32) -> Result<(), BuildError> {
        let count = events.len() / 2;
        if count as u64 > MAX_PAYLOAD as u64 || self.ids.len() + count > u32::MAX as usize {
            return Err(too_big("primitive references"));
        }
        let mut starts = events.iter().filter(|e| e.is_start()).map(Event::item);
        let node = if count == 1 {
            KdNode::leaf(starts.next().unwrap_or_default(), 1)
        } else {
            let start = self.ids.len();
            self.ids.extend(starts);
            self.ids[start..].sort_unstable();
            KdNode::leaf(start as u32, count as u32)
        };
        self.nodes.push(node);
        self.refs += count;
        self.leaves += 1;
        self.empty_leaves += (count == 0) as usize;
        self.depth = self.depth.max(depth as usize + 1);
        Ok(())
    }

    /// Splits the node's events at `s` on `axis` into the children's sorted event lists and
    /// primitive counts `((below, n_below), (above, n_above))`.
    ///
    /// A primitive goes below only when its end is at or before `s`, above only when its start
    /// is at or after `s` (and its end after `s`), else to both sides (the sweep's counts).
    fn partition(
        &mut self,
        events: Events,
        axis: usize,
        s: f32,
        below_cell: &Aabb,
        above_cell: &Aabb,
    ) -> ((Events, usize), (Events, usize)) {
        let chosen = &events[axis];
        for e in chosen.iter().filter(|e| e.is_start()) {
            self.side[e.item() as usize] = if e.pos >= s { Side::Above } else { Side::Both };
        }
        for e in chosen.iter().filter(|e| !e.is_start() && e.pos <= s) {
            self.side[e.item() as usize] = Side::Below;
        }
        let mut straddling = std::mem::take(&mut self.straddling);
        straddling.clear();
        let mut counts = [0usize; 2];
        for e in chosen.iter().filter(|e| e.is_start()) {
            match self.side[e.item() as usize] {
                Side::Below => counts[0] += 1,
                Side::Above => counts[1] += 1,
                Side::Both => straddling.push(e.item()),
            }
        }
        // Events of one-sided primitives, filtered in order (still sorted).
        let k = straddling.len();
        let mut below: Events = std::array::from_fn(|_| self.take(2 * (counts[0] + k)));
        let mut above: Events = std::array::from_fn(|_| self.take(2 * (counts[1] + k)));
        for (a, list) in events.iter().enumerate() {
            for e in list {
                match self.side[e.item() as usize] {
                    Side::Below => below[a].push(*e),
                    Side::Above => above[a].push(*e),
                    Side::Both => {}
                }
            }
        }
        self.pool.extend(events);
        // Primitives on both sides: clipped to each child's cell, new events sorted and merged.
        let mut fresh: Events = std::array::from_fn(|_| self.take(2 * k));
        let pad = Vec3A::splat(self.pad);
        let grow = |c: &Aabb| Aabb::new(c.min - pad, c.max + pad);
        for (side, (cell, out)) in [
            (grow(below_cell), &mut below),
            (grow(above_cell), &mut above),
        ]
        .into_iter()
        .enumerate()
        {
            fresh.iter_mut().for_each(Vec::clear);
            for &prim in &straddling {
                if let Some(b) = self.clip(prim, &cell) {
                    push_events(&mut fresh, &b, self.pad, prim);
                    counts[side] += 1;
                }
            }
            for (list, new) in out.iter_mut().zip(&mut fresh) {
                new.sort_unstable_by(Event::order);
                merge_into(list, new);
            }
        }
        self.pool.extend(fresh);
        self.straddling = straddling;
        ((below, counts[0]), (above, counts[1]))
    }

    /// An empty event list with room for `cap` events, from the pool when it has one.
    fn take(&mut self, cap: usize) -> Vec<Event> {
        let mut v = self.pool.pop().unwrap_or_default();
        v.clear();
        v.reserve(cap);
        v
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

/// Merges the sorted `new` into the sorted `list` (both by [`Event::order`]), in place from the
/// back: `O(len)` and no second buffer.
fn merge_into(list: &mut Vec<Event>, new: &[Event]) {
    if new.is_empty() {
        return;
    }
    let old_len = list.len();
    list.resize(old_len + new.len(), new[0]);
    let (mut i, mut j, mut k) = (old_len, new.len(), list.len());
    while j > 0 {
        k -= 1;
        if i > 0 && Event::order(&list[i - 1], &new[j - 1]).is_gt() {
            list[k] = list[i - 1];
            i -= 1;
        } else {
            list[k] = new[j - 1];
            j -= 1;
        }
    }
}

/// The two children of `cell` split at `s` on `axis`.
fn split_cell(cell: &Aabb, axis: usize, s: f32) -> (Aabb, Aabb) {
    let (mut below, mut above) = (*cell, *cell);
    below.max[axis] = s;
    above.min[axis] = s;
    (below, above)
}

#[cfg(test)]
#[path = "build_tests.rs"]
mod tests;
