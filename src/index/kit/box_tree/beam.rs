//! Beam traversal of the box trees (`bvh`, `bvh4`, `bvh8`): a packet walks the tree as one
//! beam, with the first-active-ray rule and interval-arithmetic culling of Wald, Boulos and
//! Shirley 2007 ("Ray tracing deformable scenes using dynamic bounding volume hierarchies") and
//! Boulos et al. 2007, one walk for both queries ([`LaneQuery`]) and every node width.
//!
//! A packet takes the beam when its rays all take the fast slab test and agree on the sign of
//! every direction component ([`Frustum::new`]); any other packet takes the packet walk
//! ([`super::packet`]). The walk keeps a mask of live rays per node (bit `k` for ray `k`); its
//! lowest bit is the first active ray. Each node is tested when it is visited, against its box
//! (the root's box, or the child box its parent holds), in three steps ([`admit`]):
//!
//! 1. the first active ray's own slab test ([`Frustum::ray_hits`], the single-ray decision): if
//!    it hits, the node is entered with the whole mask, no other ray tested;
//! 2. otherwise the interval test of the packet ([`Frustum::misses`]): the node is culled when
//!    no live ray can hit it before the largest best `t` (any hit: `t_max`) among them;
//! 3. otherwise the packet slab test of [`super::packet_slab`] (every lane its ray's single-ray
//!    test): the node is entered with the live rays that hit it (the lowest the new first active
//!    ray), or skipped if none does.
//!
//! A ray leaves a node's mask only when its own single-ray test misses the box (steps 1 and 3),
//! when the conservative interval test proves that it does (step 2), or, for any hit, once it has
//! a hit. A ray kept in a mask without being tested only costs tests: at a leaf every live ray
//! runs the single-ray leaf test ([`LaneQuery::leaf`]), and a primitive's `t` does not depend on
//! the traversal, so a ray's closest hit (ties to the lowest id) is its single-ray one whatever
//! extra primitives it meets. So every ray gets its single-ray answer bit for bit.
//!
//! Children are visited near to far for closest hits: by the position of their near corner (per
//! axis the plane the packet's direction signs meet first) along the first ray's direction
//! ([`visit_order`]); any-hit walks visit them as stored. A child is pushed with its box and the
//! mask of its parent, and tested when popped, against the rays' best `t` then.
//!
//! Hybrid switch (as in the packet walk, [`go_single`]): when fewer than half the lanes are live
//! at an entered node, each finishes that subtree alone with the single-ray loop.
//!
//! Counting: every live ray is charged a node visit per entered node; box tests are charged to
//! the rays that get them: one to the first active ray for its test (and one more for the
//! interval test when it runs), one to each ray of the packet test.
//!
//! Nothing is allocated: the stack is fixed (`N` entries, the tree's single-ray bound: a node
//! pushes all its children but the one visited next).

use super::frustum::Frustum;
use super::lanes::{F8, Lanes};
use super::lanes16::F16;
use super::node::Child;
use super::packet::{PacketTree, count, go_single};
use super::packet_query::{AnyLanes, ClosestLanes, LaneQuery, bits};
use super::packet_slab::{PacketRays, hit_box_by_sign};
use crate::geometry::{Aabb, Hit, Ray};
use crate::index::Stats;
use crate::index::kit::stack::Stack;
use crate::scene::Geometry;
use glam::{Vec3A, Vec4};

/// The beam methods of [`crate::index::BatchIndex`] for a type whose `tree()` is a
/// [`PacketTree`]: [`crate::index::BatchIndex::BEAMS`] and the beam walk.
macro_rules! tree_beams {
    () => {
        const BEAMS: bool = true;

        fn closest_hits_beam<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            rays: &[$crate::geometry::Ray],
            out: &mut [Option<$crate::geometry::Hit>],
            stats: &mut [S],
        ) {
            $crate::index::kit::box_tree::beam::closest_hits(&self.tree(), geom, rays, out, stats)
        }

        fn any_hits_beam<G: $crate::scene::Geometry, S: $crate::index::Stats>(
            &self,
            geom: &G,
            rays: &[$crate::geometry::Ray],
            out: &mut [bool],
            stats: &mut [S],
        ) {
            $crate::index::kit::box_tree::beam::any_hits(&self.tree(), geom, rays, out, stats)
        }
    };
}
pub(crate) use tree_beams;

/// Closest hits of a packet of at most [`crate::index::MAX_PACKET`] rays as a beam, or by the
/// packet walk when the packet cannot take one.
pub(crate) fn closest_hits<const W: usize, const N: usize, T, G, S>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    stats: &mut [S],
) where
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
{
    match Frustum::new(rays) {
        Some(f) => by_width::<ClosestLanes, W, N, T, G, S>(tree, geom, rays, &f, out, stats),
        None => super::packet::closest_hits(tree, geom, rays, out, stats),
    }
}

/// Any-hit results of a packet as a beam, or by the packet walk.
pub(crate) fn any_hits<const W: usize, const N: usize, T, G, S>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [bool],
    stats: &mut [S],
) where
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
{
    match Frustum::new(rays) {
        Some(f) => by_width::<AnyLanes, W, N, T, G, S>(tree, geom, rays, &f, out, stats),
        None => super::packet::any_hits(tree, geom, rays, out, stats),
    }
}

/// The walk in the narrowest register that holds the packet (for the packet slab tests).
#[inline(always)]
fn by_width<Q, const W: usize, const N: usize, T, G, S>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    f: &Frustum,
    out: &mut [Q::Answer],
    stats: &mut [S],
) where
    Q: LaneQuery,
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
{
    match rays.len() {
        0 => {}
        1..=4 => walk::<Q, W, N, T, G, S, Vec4>(tree, geom, rays, f, out, stats),
        5..=8 => walk::<Q, W, N, T, G, S, F8>(tree, geom, rays, f, out, stats),
        _ => walk::<Q, W, N, T, G, S, F16>(tree, geom, rays, f, out, stats),
    }
}

/// What a node's test needs of the packet.
struct Beam<'a, V> {
    rays: &'a [Ray],
    frustum: &'a Frustum,
    packet: PacketRays<V>,
    near: [usize; 3],
}

/// The live rays of `live` (not empty) that go on into the node of box `b`: all of them when
/// the first one hits it, none when the interval test culls it, else those whose packet slab
/// test hits it (see the module doc). `t_max`: each ray's best `t` (any hit: its `t_max`).
#[inline(always)]
fn admit<V: Lanes, S: Stats>(
    beam: &Beam<V>,
    b: &Aabb,
    live: u32,
    t_max: &[f32; crate::index::MAX_PACKET],
    stats: &mut [S],
) -> u32 {
    let first = live.trailing_zeros() as usize;
    stats[first].box_tests(1);
    if beam.frustum.ray_hits(b, &beam.rays[first], t_max[first]) {
        return live;
    }
    let rest = live & (live - 1);
    if rest == 0 {
        return 0;
    }
    stats[first].box_tests(1);
    let far = bits(rest).fold(f32::NEG_INFINITY, |m, k| m.max(t_max[k]));
    if beam.frustum.misses(b, far) {
        return 0;
    }
    count(rest, stats, |s| s.box_tests(1));
    let (min, max) = (b.min.to_array(), b.max.to_array());
    let (mask, _) = hit_box_by_sign::<false, V>(min, max, beam.near, &beam.packet, V::load(t_max));
    mask & rest
}

/// The order to visit the `n` children of `boxes` in, near to far along `dir` (the position
/// of each box's near corner, `neg` picking per axis the plane the rays meet first), ties to
/// the lower child; as stored when not `ordered`.
#[inline(always)]
fn visit_order<const W: usize>(
    boxes: &[Aabb; W],
    n: usize,
    ordered: bool,
    near: [usize; 3],
    dir: Vec3A,
) -> [usize; W] {
    let mut order: [usize; W] = std::array::from_fn(|i| i);
    if !ordered {
        return order;
    }
    let neg = glam::BVec3A::new(near[0] == 1, near[1] == 1, near[2] == 1);
    let mut key = [0.0f32; W];
    for (i, b) in boxes.iter().enumerate().take(n) {
        let corner = Vec3A::select(neg, b.max, b.min);
        let k = corner.dot(dir);
        let mut j = i;
        while j > 0 && key[j - 1] > k {
            (order[j], key[j]) = (order[j - 1], key[j - 1]);
            j -= 1;
        }
        (order[j], key[j]) = (i, k);
    }
    order
}

/// The beam walk of query `Q` in registers `V` (see the module doc).
#[inline(always)]
fn walk<Q, const W: usize, const N: usize, T, G, S, V>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    frustum: &Frustum,
    out: &mut [Q::Answer],
    stats: &mut [S],
) where
    Q: LaneQuery,
    T: PacketTree<W, N>,
    G: Geometry,
    S: Stats,
    V: Lanes,
{
    let top = tree.top();
    let beam = Beam {
        rays,
        frustum,
        packet: PacketRays::<V>::new(rays),
        near: frustum.near(),
    };
    let dir = rays[0].dir;
    let mut q = Q::new(rays);
    let mut stack = Stack::<(Child, Aabb, u32), N>::new();
    let (mut at, mut b, mut live) = (top.root, *top.root_bounds, u32::MAX >> (32 - rays.len()));
    loop {
        live = q.needing(live);
        if live != 0 {
            live = admit(&beam, &b, live, q.t_max(), stats);
        }
        if live != 0 && go_single::<V>(live) {
            for k in bits(live) {
                q.finish_alone(tree, geom, &rays[k], k, at, &mut stats[k]);
            }
            live = 0;
        }
        if live != 0 {
            count(live, stats, S::node_visit);
            if at.is_leaf() {
                q.leaf(top.leaves, at, geom, rays, live, stats);
            } else {
                let n = tree.boxes(at.index) as usize;
                if n > 0 {
                    let boxes: [Aabb; W] = std::array::from_fn(|i| match i < n {
                        true => tree.child_box(at.index, i),
                        false => Aabb::EMPTY,
                    });
                    let order = visit_order(&boxes, n, Q::ORDERED, beam.near, dir);
                    for &c in order[1..n].iter().rev() {
                        stack.push((tree.child(at.index, c), boxes[c], live));
                    }
                    (at, b) = (tree.child(at.index, order[0]), boxes[order[0]]);
                    continue;
                }
            }
        }
        let Some(next) = stack.pop() else {
            q.answers(out);
            return;
        };
        (at, b, live) = next;
    }
}
