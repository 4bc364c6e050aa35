//! Building the octree: recursive subdivision of a box around the scene into octants (of the
//! axes [`place`] chooses to split, at the point it chooses), with primitives indexed by the
//! shared conservative overlap test, and face ropes threaded on the way down.

use super::place::{Split, place};
use super::tree::{INTERNAL, NO_ROPE, Node, OctreeTree, face, octant_bit};
use crate::geometry::Aabb;
use crate::geometry::overlap::OVERLAP_PAD;
use crate::index::BuildError;
use crate::index::build_budget::ensure_within;
use crate::index::kit::huge_pages::huge_page_vec;
use crate::scene::Geometry;
use glam::Vec3A;
use serde::{Deserialize, Serialize};

/// Deepest `max_depth` accepted (the split placement's minimum side,
/// [`MIN_SIDE_IN_PADS`](super::place::MIN_SIDE_IN_PADS), bounds the depth in practice).
pub const MAX_DEPTH_LIMIT: usize = 16;

/// Node budget: a build that would need more nodes fails with a typed error instead of
/// exhausting memory (2^24 nodes is about 1.5 GiB with ropes and content boxes).
pub const MAX_NODES: usize = 1 << 24;

/// Build parameters shared by `octree` and `octree-topdown` (plain serde fields, so parameter
/// sweeps can set them by name: `octree:max_prims=4,max_depth=8`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OctreeParams {
    /// A cell holding more primitives than this is subdivided (at least 1). The default, 16, was
    /// chosen by `sweep octree` and suite runs (docs/sweeps.md): against 8 it halves the nodes
    /// on `flat` (whose leaves straddle many triangle edges) and the walk's cache misses with
    /// them, for about 2 more tests per ray.
    pub max_prims: usize,
    /// Deepest level a leaf may have (the root is level 0; at most [`MAX_DEPTH_LIMIT`]).
    pub max_depth: usize,
}

impl Default for OctreeParams {
    fn default() -> Self {
        OctreeParams {
            max_prims: 16,
            max_depth: 10,
        }
    }
}

fn failed(message: String) -> BuildError {
    BuildError::Failed {
        index: "octree".into(),
        message,
    }
}

impl OctreeParams {
    /// Rejects absurd values with a message that says what to change.
    pub fn validate(&self) -> Result<(), BuildError> {
        let bad = |message: String| BuildError::Params {
            index: "octree".into(),
            message,
        };
        if self.max_prims == 0 {
            return Err(bad("max_prims must be at least 1".into()));
        }
        if self.max_depth > MAX_DEPTH_LIMIT {
            return Err(bad(format!(
                "max_depth {} is above the limit {MAX_DEPTH_LIMIT}",
                self.max_depth
            )));
        }
        Ok(())
    }
}

/// The root: a box centred on the scene bounds whose half side on each axis exceeds half the
/// extent by 0.1% plus 1e-5 of the largest coordinate, so every primitive lies strictly inside it
/// even for flat scenes (zero extent on an axis) and after rounding of the centre. A scene that
/// is a single point at the origin gets a unit half side.
fn root_cell(bounds: Aabb) -> Result<Aabb, BuildError> {
    if !(bounds.min.is_finite() && bounds.max.is_finite()) || bounds.is_empty() {
        return Err(failed(format!(
            "scene bounds {bounds:?} are not finite; check the scene for NaN or infinite vertices"
        )));
    }
    let scale = bounds.min.abs().max(bounds.max.abs()).max_element();
    let half = 0.5 * bounds.extent() * (1.0 + 1.0e-3) + 1.0e-5 * scale;
    let half = if scale > 0.0 { half } else { Vec3A::ONE };
    let c = bounds.center();
    Ok(Aabb::new(c - half, c + half))
}

/// The cell of octant `c` of `cell`, split at `mid` (an unsplit axis has `mid` at the cell's
/// upper corner and no bit in `c`).
fn octant_cell(cell: &Aabb, mid: Vec3A, c: usize) -> Aabb {
    let mut b = *cell;
    for axis in 0..3 {
        if c & octant_bit(axis) != 0 {
            b.min[axis] = mid[axis];
        } else {
            b.max[axis] = mid[axis];
        }
    }
    b
}

/// Ropes of the child of octant `c` of `node` (internal, its ropes set): a face toward a
/// sibling leads to that sibling, a face on the parent's boundary to the parent's rope (which
/// covers the parent's whole face, so the child's part of it).
fn child_ropes(node: &Node, c: usize) -> [u32; 6] {
    let mut r = node.ropes;
    for axis in (0..3).filter(|&a| node.split as usize & octant_bit(a) != 0) {
        let bit = octant_bit(axis);
        if c & bit != 0 {
            r[face(axis, false)] = node.child(c ^ bit);
        } else {
            r[face(axis, true)] = node.child(c | bit);
        }
    }
    r
}

/// The octants of a split of `axes`, in increasing order (the order children are stored in).
fn octants(axes: usize) -> impl Iterator<Item = usize> {
    (0..8).filter(move |c| c & !axes == 0)
}

struct Builder<'a, G: Geometry> {
    geom: &'a G,
    params: &'a OctreeParams,
    tree: OctreeTree,
}

impl<G: Geometry> Builder<'_, G> {
    fn make_leaf(&mut self, idx: u32, prims: &[u32]) {
        let node = &mut self.tree.nodes[idx as usize];
        node.first = self.tree.prim_ids.len() as u32;
        node.count = prims.len() as u32;
        self.tree.contents[idx as usize] = prims
            .iter()
            .fold(Aabb::EMPTY, |b, &p| b.union(self.geom.bounds(p)));
        self.tree.prim_ids.extend_from_slice(prims);
    }

    /// The split and the children's primitive lists (in octant order), or `None` when the node
    /// stays a leaf: few enough primitives, the depth limit, no axis worth splitting ([`place`]:
    /// none pays by SAH, or the cell is too narrow against the overlap padding), or a split that
    /// separates nothing (two or more children non-empty and each holding every primitive:
    /// coincident or duplicate primitives, or a fan around a shared vertex). A split that moves
    /// all primitives into a single child is kept: it cuts off empty space or zooms in on a small
    /// cluster, bounded by `max_depth`.
    fn split(&self, cell: &Aabb, prims: &[u32], level: usize) -> Option<(Split, Vec<Vec<u32>>)> {
        if prims.len() <= self.params.max_prims || level >= self.params.max_depth {
            return None;
        }
        let pad =
            cell.min.abs().max(cell.max.abs()).max_element() * OVERLAP_PAD + f32::MIN_POSITIVE;
        let bounds: Vec<Aabb> = prims.iter().map(|&p| self.geom.bounds(p)).collect();
        let split = place(cell, &bounds, pad);
        if split.axes == 0 {
            return None;
        }
        let children: Vec<Vec<u32>> = octants(split.axes)
            .map(|c| {
                let b = octant_cell(cell, split.point, c);
                prims
                    .iter()
                    .copied()
                    .filter(|&p| self.geom.overlaps_box(p, &b))
                    .collect()
            })
            .collect();
        let non_empty = children.iter().filter(|c| !c.is_empty()).count();
        let separates = children
            .iter()
            .any(|c| !c.is_empty() && c.len() < prims.len());
        (non_empty <= 1 || separates).then_some((split, children))
    }

    fn build(
        &mut self,
        idx: u32,
        prims: &[u32],
        level: usize,
        ropes: [u32; 6],
    ) -> Result<(), BuildError> {
        self.tree.nodes[idx as usize].ropes = ropes;
        self.tree.max_level = self.tree.max_level.max(level);
        let cell = self.tree.nodes[idx as usize].cell();
        let Some((split, children)) = self.split(&cell, prims, level) else {
            self.make_leaf(idx, prims);
            return Ok(());
        };
        let first = self.tree.nodes.len();
        ensure_within("octree", 0, "raise max_prims or lower max_depth")?;
        if first + children.len() > MAX_NODES {
            return Err(failed(format!(
                "more than {MAX_NODES} nodes; lower max_depth ({}) or raise max_prims ({})",
                self.params.max_depth, self.params.max_prims
            )));
        }
        for c in octants(split.axes) {
            self.tree
                .nodes
                .push(Node::new(octant_cell(&cell, split.point, c)));
            self.tree.contents.push(Aabb::EMPTY);
        }
        let node = &mut self.tree.nodes[idx as usize];
        node.first = first as u32;
        node.count = INTERNAL;
        node.split = split.axes as u32;
        let node = *node;
        for (c, child) in octants(split.axes).zip(&children) {
            self.build(node.child(c), child, level + 1, child_ropes(&node, c))?;
        }
        Ok(())
    }
}

impl OctreeTree {
    /// Builds the octree over `geom`.
    pub fn build<G: Geometry>(geom: &G, params: &OctreeParams) -> Result<OctreeTree, BuildError> {
        params.validate()?;
        if geom.is_empty() {
            return Err(BuildError::EmptyScene);
        }
        if geom.len() >= u32::MAX as usize {
            return Err(failed(format!("{} primitives exceed u32 ids", geom.len())));
        }
        let n = geom.len() as u32;
        let bounds = (0..n).fold(Aabb::EMPTY, |b, p| b.union(geom.bounds(p)));
        let root = root_cell(bounds)?;
        let mut b = Builder {
            geom,
            params,
            tree: OctreeTree {
                nodes: vec![Node::new(root)],
                contents: vec![Aabb::EMPTY],
                prim_ids: Vec::new(),
                max_level: 0,
                prim_count: geom.len(),
            },
        };
        let all: Vec<u32> = (0..n).collect();
        b.build(0, &all, 0, [NO_ROPE; 6])?;
        let mut tree = b.tree;
        tighten_ropes(&mut tree);
        tree.nodes = huge_page_vec(tree.nodes);
        tree.contents = huge_page_vec(tree.contents);
        tree.prim_ids = huge_page_vec(tree.prim_ids);
        Ok(tree)
    }
}

/// Havran's rope optimization: moves each rope down from the neighbour at the same or a
/// shallower depth to the deepest node that still covers the whole face, so the neighbor
/// traversal descends less.
fn tighten_ropes(tree: &mut OctreeTree) {
    for n in 0..tree.nodes.len() {
        let cell = tree.nodes[n].cell();
        for axis in 0..3 {
            for upper in [false, true] {
                let f = face(axis, upper);
                let mut r = tree.nodes[n].ropes[f];
                while r != NO_ROPE && !tree.nodes[r as usize].is_leaf() {
                    let target = tree.nodes[r as usize];
                    let mid = tree.nodes[target.first as usize].max();
                    // The child on our side of the face, on the side of `cell` elsewhere.
                    let mut c = 0;
                    for b in 0..3 {
                        let above = if b == axis {
                            !upper
                        } else {
                            cell.min[b] >= mid[b]
                        };
                        if above {
                            c |= octant_bit(b);
                        }
                    }
                    let child = target.child(c);
                    let child_cell = tree.nodes[child as usize].cell();
                    let covers = (0..3).filter(|&b| b != axis).all(|b| {
                        child_cell.min[b] <= cell.min[b] && cell.max[b] <= child_cell.max[b]
                    });
                    if !covers {
                        break;
                    }
                    r = child;
                }
                tree.nodes[n].ropes[f] = r;
            }
        }
    }
}
