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
//! Nodes with more references than [`Binning::above`] choose their plane among bin boundaries
//! instead ([`super::binned`]); they carry their references and clipped bounds, not event lists,
//! and the first node at or below that size (or where no bin boundary beats a leaf) sorts its
//! references' events once for its whole subtree.
//!
//! The tree is the one a per-node sort of the same events gives (the test module keeps that
//! builder as an oracle, binning the same nodes, and compares the trees node for node). The
//! parallel top of the build is in [`super::parallel`].

use super::binned::Bins;
use super::node::{KdNode, MAX_PAYLOAD};
use crate::geometry::Aabb;
use crate::index::BuildError;
use crate::index::build_budget::ensure_within;
use crate::index::kit::near_far::sweep::{Event, Ref, Weights, best_split_sorted, push_events};
use crate::index::kit::near_far::{Built, SahParams};
use crate::scene::Geometry;
use glam::Vec3A;

/// The events of a node's primitives on each axis, each list sorted by [`Event::order`]; the
/// items are primitive ids (a primitive is at most once in a node), and every primitive of the
/// node has exactly one start and one end event per axis.
pub(super) type Events = [Vec<Event>; 3];

/// Where a node's primitive goes at the chosen plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Below,
    Above,
    Both,
}

/// The sequential builder: the nodes of one subtree depth-first, and scratch space.
pub(super) struct Builder<'a, G: Geometry> {
    geom: &'a G,
    costs: &'a SahParams,
    binning: Binning,
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
    /// Scratch of the binned nodes.
    bins: Bins,
    depth: usize,
    leaves: usize,
    empty_leaves: usize,
}

/// Which nodes choose their plane by binned SAH: those with more than `above` references, among
/// `bins` slabs per axis (`bins == 0`: none, every plane is a perfect split).
#[derive(Debug, Clone, Copy)]
pub(super) struct Binning {
    pub bins: usize,
    pub above: usize,
}

/// A node's references: with their clipped bounds (a binned node), or as sorted events.
pub(super) enum Input {
    Refs(Vec<Ref>),
    Events(Events),
}

/// A node's fate: a leaf over the primitives of these events, or a plane and its children's
/// references, counts and cells.
pub(super) enum Split {
    Leaf(Events),
    Node {
        axis: usize,
        s: f32,
        below: (Input, usize, Aabb),
        above: (Input, usize, Aabb),
    },
}

/// The references of all primitives of `geom` (their whole bounds) when the root is binned,
/// else their sorted events (grown by `pad`).
pub(super) fn root_input<G: Geometry>(geom: &G, pad: f32, binning: Binning) -> Input {
    let refs = (0..geom.len() as u32).map(|prim| Ref {
        prim,
        b: geom.bounds(prim),
    });
    if binning.bins > 0 && geom.len() > binning.above {
        Input::Refs(refs.collect())
    } else {
        let n = geom.len();
        let mut events: Events = std::array::from_fn(|_| Vec::with_capacity(2 * n));
        refs.for_each(|r| push_events(&mut events, &r.b, pad, r.prim));
        for list in &mut events {
            list.sort_unstable_by(Event::order);
        }
        Input::Events(events)
    }
}

/// What makes a kd-tree smaller, for the budget's refusal.
pub(super) const LOWER: &str = "raise leaf_size or lower max_depth";

pub(super) fn too_big(what: &str) -> BuildError {
    BuildError::Failed {
        index: "kdtree".into(),
        message: format!(
            "too many {what} for 30-bit node fields; raise leaf_size or lower max_depth"
        ),
    }
}

impl<'a, G: Geometry> Builder<'a, G> {
    /// An empty builder.
    pub fn new(geom: &'a G, costs: &'a SahParams, binning: Binning, pad: f32) -> Self {
        Builder {
            geom,
            costs,
            binning,
            pad,
            nodes: Vec::new(),
            ids: Vec::new(),
            refs: 0,
            side: vec![Side::Both; geom.len()],
            straddling: Vec::new(),
            pool: Vec::new(),
            bins: Bins::default(),
            depth: 0,
            leaves: 0,
            empty_leaves: 0,
        }
    }

    /// The nodes and figures built so far.
    pub fn into_built(self) -> Built<KdNode> {
        Built {
            nodes: self.nodes,
            ids: self.ids,
            refs: self.refs,
            depth: self.depth,
            leaves: self.leaves,
            empty_leaves: self.empty_leaves,
            extra: Vec::new(),
        }
    }

    /// Builds the subtree of `cell` over its `n` references `input`, depth-first.
    pub fn node(
        &mut self,
        input: Input,
        n: usize,
        cell: Aabb,
        depth: u32,
    ) -> Result<(), BuildError> {
        let at = self.nodes.len();
        if at as u64 > MAX_PAYLOAD as u64 {
            return Err(too_big("nodes"));
        }
        ensure_within("kdtree", 0, LOWER)?;
        match self.split(input, n, cell, depth) {
            Split::Leaf(events) => self.leaf(events, depth),
            Split::Node {
                axis,
                s,
                below,
                above,
            } => {
                self.nodes.push(KdNode::leaf(0, 0)); // placeholder, patched below
                self.node(below.0, below.1, below.2, depth + 1)?;
                let above_at = self.nodes.len() as u32;
                self.node(above.0, above.1, above.2, depth + 1)?;
                self.nodes[at] = KdNode::interior(axis, s, above_at);
                Ok(())
            }
        }
    }

    /// Chooses the node's plane (binned for a large node, else the exact sweep) and splits
    /// its references, or makes it a leaf.
    pub fn split(&mut self, input: Input, n: usize, cell: Aabb, depth: u32) -> Split {
        let events = match input {
            Input::Refs(refs) => {
                let c = self.costs;
                let open = n as u32 > c.leaf_size && depth < c.max_depth;
                let b = self.binning;
                let plane = (open && b.bins > 0 && n > b.above)
                    .then(|| {
                        let w = Weights::from(c);
                        self.bins.best_split(&refs, &cell, self.pad, &w, b.bins)
                    })
                    .flatten();
                let Some((axis, s)) = plane else {
                    let events = self.events_of(&refs);
                    return self.split(Input::Events(events), n, cell, depth);
                };
                let (bc, ac) = split_cell(&cell, axis, s);
                let (below, above) = self.split_refs(refs, axis, s, &bc, &ac);
                let (nb, na) = (below.len(), above.len());
                return Split::Node {
                    axis,
                    s,
                    below: (Input::Refs(below), nb, bc),
                    above: (Input::Refs(above), na, ac),
                };
            }
            Input::Events(events) => events,
        };
        let Some((axis, s)) = self.choose(&events, n, &cell, depth) else {
            return Split::Leaf(events);
        };
        let (bc, ac) = split_cell(&cell, axis, s);
        let ((below, nb), (above, na)) = self.partition(events, axis, s, &bc, &ac);
        Split::Node {
            axis,
            s,
            below: (Input::Events(below), nb, bc),
            above: (Input::Events(above), na, ac),
        }
    }

    /// The sorted events of `refs` (their bounds grown by `pad`).
    fn events_of(&mut self, refs: &[Ref]) -> Events {
        let mut events: Events = std::array::from_fn(|_| self.take(2 * refs.len()));
        for r in refs {
            push_events(&mut events, &r.b, self.pad, r.prim);
        }
        for list in &mut events {
            list.sort_unstable_by(Event::order);
        }
        events
    }

    /// Sends each reference to its side(s) of the plane at `s` on `axis`, as [`Self::partition`]
    /// does with events; one on both sides is clipped again to each child's cell (grown by
    /// `pad`).
    pub fn split_refs(
        &self,
        refs: Vec<Ref>,
        axis: usize,
        s: f32,
        below_cell: &Aabb,
        above_cell: &Aabb,
    ) -> (Vec<Ref>, Vec<Ref>) {
        let pad = Vec3A::splat(self.pad);
        let grow = |c: &Aabb| Aabb::new(c.min - pad, c.max + pad);
        let (bclip, aclip) = (grow(below_cell), grow(above_cell));
        let (mut below, mut above) = (Vec::new(), Vec::new());
        for r in refs {
            let to_above = r.b.max[axis] + self.pad > s;
            let to_below = r.b.min[axis] - self.pad < s || !to_above;
            match (to_below, to_above) {
                (true, true) => {
                    let clipped = |c: &Aabb| self.clip(r.prim, c).map(|b| Ref { prim: r.prim, b });
                    below.extend(clipped(&bclip));
                    above.extend(clipped(&aclip));
                }
                (true, false) => below.push(r),
                _ => above.push(r),
            }
        }
        (below, above)
    }

    /// The plane `(axis, position)` that splits the node, or `None` for a leaf.
    fn choose(&self, events: &Events, n: usize, cell: &Aabb, depth: u32) -> Option<(usize, f32)> {
        if n as u32 <= self.costs.leaf_size || depth >= self.costs.max_depth {
            return None;
        }
        best_split_sorted(events, n, cell, &Weights::from(self.costs)).map(|(a, s, _)| (a, s))
    }

    /// A leaf over the primitives of `events`: one primitive is held in the node itself, more
    /// as a sorted run of the id array.
    pub fn leaf(&mut self, events: Events, depth: u32) -> Result<(), BuildError> {
        let count = events[0].len() / 2;
        if count as u64 > MAX_PAYLOAD as u64 || self.ids.len() + count > u32::MAX as usize {
            return Err(too_big("primitive references"));
        }
        let mut starts = events[0].iter().filter(|e| e.is_start()).map(Event::item);
        let node = if count == 1 {
            KdNode::leaf(starts.next().unwrap_or_default(), 1)
        } else {
            let start = self.ids.len();
            self.ids.extend(starts);
            self.ids[start..].sort_unstable();
            KdNode::leaf(start as u32, count as u32)
        };
        self.nodes.push(node);
        self.pool.extend(events);
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
pub(super) fn split_cell(cell: &Aabb, axis: usize, s: f32) -> (Aabb, Aabb) {
    let (mut below, mut above) = (*cell, *cell);
    below.max[axis] = s;
    above.min[axis] = s;
    (below, above)
}

#[cfg(test)]
#[path = "build_tests.rs"]
mod tests;
