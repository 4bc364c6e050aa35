//! Our binary BVH collapsed into the compressed 8-wide nodes of Ylitie, Karras & Laine (2017):
//! 80-byte nodes with child boxes quantized to 8 bits against a node origin and power-of-two
//! scales, children placed in slots by the octant order, and triangles of a node's leaves
//! stored together (at most 3 per leaf slot, 24 per node).
//!
//! The collapse is greedy: a wide node starts from a binary node's two children and opens the
//! inner child of largest surface area while its children fit in the 8 slots. A binary leaf of
//! `n` primitives takes `ceil(n / 3)` slots (its box for each); one of more than 24 becomes a
//! child node of its own over the same box.

use crate::geometry::Aabb;
use crate::index::kit::box_tree::node::{Child, Node};

/// Words (`u32`) of one node: `p` (3 `f32`), the exponents and `imask` (one word), the child
/// node base, the triangle base, 8 `meta` bytes, then 8 bytes each of `lo.x, lo.y, lo.z,
/// hi.x, hi.y, hi.z`.
pub const NODE_WORDS: usize = 20;
/// Primitives of one leaf slot.
const SLOT_PRIMS: u32 = 3;
/// Primitives one node's leaf slots hold (its low 24 hit bits).
const NODE_PRIMS: u32 = 24;

/// What one slot of a wide node holds before its place is chosen.
#[derive(Clone, Copy)]
enum Item {
    /// The binary inner node `nodes[index]`: a child node.
    Binary(u32, Aabb),
    /// Positions `first..first + count` of the binary tree's leaf order in leaf slots
    /// (`count <= 24`, `ceil(count / 3)` slots).
    Leaf(u32, u32, Aabb),
    /// Positions `first..first + count` as a child node of their own (a leaf too large for
    /// its parent's slots).
    Range(u32, u32, Aabb),
}

impl Item {
    /// The item of a binary tree's reference `c` with box `b`.
    fn of(c: Child, b: Aabb) -> Item {
        match c.count {
            0 => Item::Binary(c.index, b),
            n if n <= NODE_PRIMS => Item::Leaf(c.index, n, b),
            n => Item::Range(c.index, n, b),
        }
    }
    fn bounds(&self) -> Aabb {
        match *self {
            Item::Binary(_, b) | Item::Leaf(_, _, b) | Item::Range(_, _, b) => b,
        }
    }
    /// Slots the item takes in its parent.
    fn slots(&self) -> u32 {
        match *self {
            Item::Leaf(_, n, _) => n.div_ceil(SLOT_PRIMS),
            _ => 1,
        }
    }
    /// Whether it becomes a child node (not leaf slots).
    fn is_node(&self) -> bool {
        !matches!(self, Item::Leaf(..))
    }
}

/// The collapsed tree: nodes (root first) and the leaf-order positions of the binary tree
/// (`ids` of the binary tree index them) in the wide tree's triangle order.
pub struct Collapsed {
    pub nodes: Vec<u32>,
    pub order: Vec<u32>,
    pub depth: usize,
}

/// Collapses the binary tree (root `root` with box `root_bounds`, inner `nodes`).
pub fn collapse(root_bounds: Aabb, root: Child, nodes: &[Node]) -> Collapsed {
    let top = match root.count {
        0 => Item::Binary(root.index, root_bounds),
        n => Item::Range(root.index, n, root_bounds),
    };
    let mut out = Collapsed {
        nodes: vec![0; NODE_WORDS],
        order: Vec::new(),
        depth: 1,
    };
    // Work: (node slot in `out.nodes`, its items, its depth), breadth first.
    let mut work = std::collections::VecDeque::from([(0usize, open(top, nodes), 1usize)]);
    while let Some((at, items, depth)) = work.pop_front() {
        out.depth = out.depth.max(depth);
        let placed = place(&items);
        let child_base = (out.nodes.len() / NODE_WORDS) as u32;
        let tri_base = out.order.len() as u32;
        let mut words = [0u32; NODE_WORDS];
        let bounds = items.iter().fold(Aabb::EMPTY, |a, i| a.union(i.bounds()));
        let (p, exp) = quantization(&bounds);
        words[..3].copy_from_slice(&p.map(f32::to_bits));
        let mut imask = 0u32;
        let mut inner = 0u32;
        for (slot, entry) in placed.iter().enumerate() {
            let Some((item, part)) = *entry else { continue };
            let meta = if item.is_node() {
                imask |= 1 << slot;
                let at = (child_base + inner) as usize * NODE_WORDS;
                inner += 1;
                out.nodes.resize(at + NODE_WORDS, 0);
                work.push_back((at, open(item, nodes), depth + 1));
                0b0010_0000 | (24 + slot as u32)
            } else {
                let Item::Leaf(first, count, _) = item else {
                    unreachable!("a leaf slot")
                };
                let lo = first + part * SLOT_PRIMS;
                let n = SLOT_PRIMS.min(count - part * SLOT_PRIMS);
                let offset = out.order.len() as u32 - tri_base;
                out.order.extend(lo..lo + n);
                (((1u32 << n) - 1) << 5) | offset
            };
            set_byte(&mut words[6..8], slot, meta);
            let b = item.bounds();
            for axis in 0..3 {
                let (q_lo, q_hi) = quantize(b.min[axis], b.max[axis], p[axis], exp[axis]);
                set_byte(&mut words[8 + 2 * axis..10 + 2 * axis], slot, q_lo);
                set_byte(&mut words[14 + 2 * axis..16 + 2 * axis], slot, q_hi);
            }
        }
        words[3] = exp
            .iter()
            .enumerate()
            .map(|(a, &e)| ((e + 127) as u32) << (8 * a))
            .sum::<u32>()
            | (imask << 24);
        words[4] = child_base;
        words[5] = tri_base;
        out.nodes[at..at + NODE_WORDS].copy_from_slice(&words);
    }
    out
}

/// The items of a new wide node made from `item`: its two children, then greedily the inner
/// child of largest area opened while everything fits in 8 slots.
fn open(item: Item, nodes: &[Node]) -> Vec<Item> {
    let children = |i: u32| {
        let n = &nodes[i as usize];
        (0..2).map(move |k| Item::of(n.children[k], n.child_bounds(k)))
    };
    let mut items: Vec<Item> = match item {
        Item::Binary(i, _) => children(i).collect(),
        Item::Leaf(first, count, b) | Item::Range(first, count, b) if count <= NODE_PRIMS => {
            vec![Item::Leaf(first, count, b)]
        }
        // A leaf too large for one node's slots: 8 child nodes over its parts.
        Item::Leaf(first, count, b) | Item::Range(first, count, b) => {
            let per = count.div_ceil(8);
            (0..8)
                .map(|k| (first + k * per, per.min(count.saturating_sub(k * per))))
                .filter(|&(_, n)| n > 0)
                .map(|(f, n)| Item::Range(f, n, b))
                .collect()
        }
    };
    // Two large leaves may need more than 8 slots: the largest become child nodes.
    while items.iter().map(Item::slots).sum::<u32>() > 8 {
        let k = (0..items.len())
            .max_by_key(|&k| items[k].slots())
            .expect("items");
        if let Item::Leaf(f, n, b) = items[k] {
            items[k] = Item::Range(f, n, b);
        }
    }
    loop {
        let used: u32 = items.iter().map(Item::slots).sum();
        let best = items
            .iter()
            .enumerate()
            .filter_map(|(k, it)| match *it {
                Item::Binary(i, b) => {
                    let grow: u32 = children(i).map(|c| c.slots()).sum::<u32>() - 1;
                    (used + grow <= 8).then_some((k, i, b.surface_area()))
                }
                Item::Leaf(..) | Item::Range(..) => None,
            })
            .max_by(|a, b| a.2.total_cmp(&b.2));
        let Some((k, i, _)) = best else { break };
        items.swap_remove(k);
        items.extend(children(i));
    }
    items
}

/// The slot of every item part (an item with several slots has parts 0, 1, ...): greedy by the
/// octant cost of Ylitie et al., slot `s` holding the part nearest for rays whose direction
/// signs are `s` (bit 2: x negative, bit 1: y, bit 0: z).
fn place(items: &[Item]) -> [Option<(Item, u32)>; 8] {
    let parts: Vec<(Item, u32)> = items
        .iter()
        .flat_map(|it| (0..it.slots()).map(move |p| (*it, p)))
        .collect();
    let center = items
        .iter()
        .fold(Aabb::EMPTY, |a, i| a.union(i.bounds()))
        .center();
    let mut costs: Vec<(f32, usize, usize)> = Vec::with_capacity(parts.len() * 8);
    for (k, (it, _)) in parts.iter().enumerate() {
        let d = it.bounds().center() - center;
        for s in 0..8 {
            let sign = |bit: usize| if s & bit != 0 { -1.0 } else { 1.0 };
            costs.push((d.x * sign(4) + d.y * sign(2) + d.z * sign(1), k, s));
        }
    }
    costs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut slots = [None; 8];
    let mut done = vec![false; parts.len()];
    for (_, k, s) in costs {
        if !done[k] && slots[s].is_none() {
            slots[s] = Some(parts[k]);
            done[k] = true;
        }
    }
    slots
}

/// The node origin (its box's minimum) and per-axis exponents `e` with `255 * 2^e` covering
/// the box's extent (within the normal range of `f32`).
fn quantization(b: &Aabb) -> ([f32; 3], [i32; 3]) {
    let p = b.min.to_array();
    let exp = [0, 1, 2].map(|a| {
        let ext = b.max[a] - b.min[a];
        let mut e = if ext > 0.0 {
            (ext / 255.0).log2().ceil() as i32
        } else {
            -126
        };
        e = e.clamp(-126, 127);
        // Rounding: make sure the decoded top reaches the box.
        while e < 127 && p[a] + scale(e) * 255.0 < b.max[a] {
            e += 1;
        }
        e
    });
    (p, exp)
}

fn scale(e: i32) -> f32 {
    f32::from_bits(((e + 127) as u32) << 23)
}

/// The 8-bit planes of `[lo, hi]` against origin `p` and exponent `e`, decoded as the shader
/// does (`p + 2^e q`, exact product, one rounding): `decode(q_lo) <= lo` and
/// `decode(q_hi) >= hi`.
fn quantize(lo: f32, hi: f32, p: f32, e: i32) -> (u32, u32) {
    let s = scale(e);
    let decode = |q: u32| p + s * q as f32;
    let mut q_lo = (((lo - p) / s).floor().max(0.0) as u32).min(255);
    while q_lo > 0 && decode(q_lo) > lo {
        q_lo -= 1;
    }
    let mut q_hi = (((hi - p) / s).ceil().max(0.0) as u32).min(255);
    while q_hi < 255 && decode(q_hi) < hi {
        q_hi += 1;
    }
    (q_lo, q_hi)
}

/// Byte `k` of the 8 bytes in `words`.
fn set_byte(words: &mut [u32], k: usize, v: u32) {
    words[k / 4] |= (v & 0xFF) << (8 * (k % 4));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::triangle::Watertight;
    use crate::index::{Bvh, BvhParams};
    use crate::scene::{Geometry, Triangles, generators};
    use std::sync::Arc;

    fn byte(words: &[u32], k: usize) -> u32 {
        (words[k / 4] >> (8 * (k % 4))) & 0xFF
    }

    /// Child slot `c`'s box as the shader decodes it (`p + 2^e q`).
    fn decoded(node: &[u32], c: usize) -> Aabb {
        let p = [0, 1, 2].map(|a| f32::from_bits(node[a]));
        let e = [0, 1, 2].map(|a| ((node[3] >> (8 * a)) & 0xFF) as i32 - 127);
        let at = |base: usize, a: usize| p[a] + scale(e[a]) * byte(&node[base + 2 * a..], c) as f32;
        Aabb::new(
            glam::Vec3A::from_array([0, 1, 2].map(|a| at(8, a))),
            glam::Vec3A::from_array([0, 1, 2].map(|a| at(14, a))),
        )
    }

    fn contains(outer: &Aabb, inner: &Aabb) -> bool {
        outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all()
    }

    /// The bounds of the triangles under slot `c` of node `n`, checking on the way down that
    /// every decoded box contains them; counts the triangle positions reached.
    fn under<G: Geometry>(
        w: &Collapsed,
        ids: &[u32],
        geom: &G,
        n: usize,
        reached: &mut Vec<u32>,
    ) -> Aabb {
        let node = &w.nodes[n * NODE_WORDS..(n + 1) * NODE_WORDS];
        let imask = node[3] >> 24;
        let mut all = Aabb::EMPTY;
        let mut inner = 0;
        for c in 0..8 {
            let meta = byte(&node[6..8], c);
            if meta == 0 {
                continue;
            }
            let exact = if imask >> c & 1 == 1 {
                inner += 1;
                under(w, ids, geom, node[4] as usize + inner - 1, reached)
            } else {
                let first = node[5] + (meta & 0x1F);
                let count = ((meta >> 5) + 1).ilog2();
                (first..first + count).fold(Aabb::EMPTY, |b, k| {
                    reached.push(w.order[k as usize]);
                    b.union(geom.bounds(ids[w.order[k as usize] as usize]))
                })
            };
            assert!(
                contains(&decoded(node, c), &exact),
                "node {n} slot {c}: {:?} does not hold {exact:?}",
                decoded(node, c)
            );
            all = all.union(exact);
        }
        all
    }

    /// Every decoded child box contains the exact bounds of everything under it, and every
    /// primitive reference of the binary tree is reached exactly once, for default, large and
    /// one-primitive leaves and scenes far from the origin and of tiny extent.
    #[test]
    fn decoded_boxes_hold_what_they_cover() {
        let cases = [
            ("soup", 4000, BvhParams::default()),
            ("slivers", 2000, BvhParams::default()),
            (
                "icosphere",
                3000,
                BvhParams {
                    leaf_size: Some(64),
                    ..BvhParams::default()
                },
            ),
            (
                "terrain",
                3000,
                BvhParams {
                    leaf_size: Some(1),
                    ..BvhParams::default()
                },
            ),
            ("icosphere", 1, BvhParams::default()),
        ];
        for (name, n, params) in cases {
            for shift in [0.0f32, 1.0e5, -3.0e-3] {
                let mut scene = generators::generate(name, n, 5).unwrap();
                for t in &mut scene.triangles {
                    t.v =
                        t.v.map(|v| if shift < 0.0 { v * -shift } else { v + shift });
                }
                let geom = Triangles::<Watertight>::new(Arc::from(scene.triangles.as_slice()));
                let bvh = Bvh::build_tree(&geom, &params, 1).unwrap();
                let (root_bounds, root, nodes, ids) = bvh.parts();
                let w = collapse(root_bounds, root, nodes);
                let mut reached = Vec::new();
                under(&w, ids, &geom, 0, &mut reached);
                reached.sort_unstable();
                assert_eq!(
                    reached,
                    (0..ids.len() as u32).collect::<Vec<_>>(),
                    "{name} {n} {shift}"
                );
            }
        }
    }
}
