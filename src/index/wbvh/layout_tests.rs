//! Tests of the node layouts (the `layout` parameter) of `bvh`, `bvh4` and `bvh8`: a layout is a
//! permutation of the default tree's nodes (every node once, the same boxes, children and
//! leaves, children after parents), it really moves them, and every ray gets the default's hits
//! and counters bit for bit (closest and any hit, single rays, streams and packets), before and
//! after a refit to moved primitives.

use super::*;
use crate::geometry::triangle::Watertight;
use crate::geometry::{Hit, Triangle};
use crate::index::bvh::params::Layout;
use crate::index::kit::box_tree::layout::{LayoutNode, children_after_parents};
use crate::index::kit::box_tree::node::Node;
use crate::index::{Counters, NoStats};
use crate::rays::{incoherent_rays, primary_rays};
use crate::scene::generators;
use crate::scene::{Mixed, Scene, Triangles};
use glam::Vec3A;
use std::sync::Arc;

fn params(layout: Layout) -> BvhParams {
    BvhParams {
        layout,
        ..BvhParams::default()
    }
}

/// Per ray: the closest hit (id and `t` bits) with its counters, the any-hit answer with its
/// counters; then the stream's and 8-ray packets' closest hits and counters.
type Traced = (
    Vec<(Option<(u32, u32)>, Counters, bool, Counters)>,
    Vec<(Option<(u32, u32)>, Counters)>,
);

fn trace<I: BatchIndex, G: Geometry>(index: &I, g: &G, rays: &[Ray]) -> Traced {
    let key = |h: Option<Hit>| h.map(|h| (h.prim, h.t.to_bits()));
    let single = rays
        .iter()
        .map(|r| {
            let (mut c, mut a) = (Counters::default(), Counters::default());
            let hit = key(index.closest_hit(g, r, &mut c));
            (hit, c, index.any_hit(g, r, &mut a), a)
        })
        .collect();
    let mut batch = Vec::new();
    for (chunk, packet) in [(64, false), (8, true)] {
        for rs in rays.chunks(chunk) {
            let mut out = vec![None; rs.len()];
            let mut stats = vec![Counters::default(); rs.len()];
            match packet {
                true => index.closest_hits_packet(g, rs, &mut out, &mut stats),
                false => index.closest_hits_stream(g, rs, &mut out, &mut stats),
            }
            batch.extend(out.into_iter().map(key).zip(stats));
        }
    }
    (single, batch)
}

/// Walks two trees of the same shape together from their roots and returns, per node of `a`,
/// the index of the same node in `b`, asserting that every node of `b` is met once (a
/// permutation) and that `same` holds for each pair (boxes, leaves).
fn node_map<N: LayoutNode>(
    roots: (Child, Child),
    a: &[N],
    b: &[N],
    same: impl Fn(&N, &N),
) -> Vec<u32> {
    assert_eq!(a.len(), b.len(), "node counts");
    assert!(!roots.0.is_leaf() && !roots.1.is_leaf());
    let mut map = vec![u32::MAX; a.len()];
    let mut met = vec![false; b.len()];
    let mut stack = vec![(roots.0.index, roots.1.index)];
    while let Some((x, y)) = stack.pop() {
        assert!(
            !std::mem::replace(&mut met[y as usize], true),
            "node {y} met twice"
        );
        map[x as usize] = y;
        let (nx, ny) = (&a[x as usize], &b[y as usize]);
        same(nx, ny);
        let (mut kx, mut ky) = (Vec::new(), Vec::new());
        nx.inner_children(|c, _| kx.push(c));
        ny.inner_children(|c, _| ky.push(c));
        assert_eq!(kx.len(), ky.len());
        stack.extend(kx.into_iter().zip(ky));
    }
    assert!(
        met.iter().all(|&m| m),
        "a node of the layout is unreachable"
    );
    assert!(children_after_parents(b), "a child before its parent");
    map
}

/// Whether `map` moves at least one node.
fn moves(map: &[u32]) -> bool {
    map.iter().enumerate().any(|(i, &m)| m != i as u32)
}

fn same_binary(p: &Node, q: &Node) {
    let bits = |n: &Node| [n.x, n.y, n.z].map(|v| v.to_array().map(f32::to_bits));
    assert_eq!(bits(p), bits(q), "child boxes");
    for k in 0..2 {
        let (c, d) = (p.children[k], q.children[k]);
        assert_eq!(c.is_leaf(), d.is_leaf());
        if c.is_leaf() {
            assert_eq!(c, d, "a leaf");
        }
    }
}

/// `bvh` under each layout against its default layout on `g` (and after a refit to `moved`).
fn check_binary<G: Geometry>(g: &G, moved: &G, rays: &[Ray], what: &str) {
    let base = Bvh::build(g, &BvhParams::default()).unwrap();
    assert!(base.info().depth > 3, "{what}: a deep enough tree");
    let want = trace(&base, g, rays);
    let mut refit_base = base.clone();
    refit_base.refit(moved).unwrap();
    let want_moved = trace(&refit_base, moved, rays);
    for layout in [Layout::Veb, Layout::Treelet] {
        let mut bvh = Bvh::build(g, &params(layout)).unwrap();
        let map_of = |a: &Bvh, b: &Bvh| {
            let ((_, ra, na, ia), (_, rb, nb, ib)) = (a.parts(), b.parts());
            assert_eq!(ia, ib, "{what}: leaf ids");
            node_map((ra, rb), na, nb, same_binary)
        };
        let map = map_of(&base, &bvh);
        assert!(moves(&map), "{what} {layout:?}: the layout moved no node");
        assert_eq!(trace(&bvh, g, rays), want, "{what} {layout:?}");
        bvh.refit(moved).unwrap();
        assert_eq!(map_of(&refit_base, &bvh), map, "{what} {layout:?}: refit");
        assert_eq!(
            trace(&bvh, moved, rays),
            want_moved,
            "{what} {layout:?}: refit"
        );
    }
}

/// The leaf `c`'s primitives, in their stored order.
fn leaf_ids(store: &LeafStore, c: Child) -> Vec<u32> {
    let (first, count) = (c.index as usize, c.count as usize);
    match store {
        LeafStore::Ids(ids) => ids[first..first + count].to_vec(),
        LeafStore::Blocks(b) => {
            let end = first + count.div_ceil(BLOCK_LANES as usize);
            b[first..end]
                .iter()
                .flat_map(|b| b.ids)
                .take(count)
                .collect()
        }
    }
}

/// `bvh4` or `bvh8` under each layout against its default layout on `g` (and after a refit).
fn check_wide<const C: usize, G: Geometry>(g: &G, moved: &G, rays: &[Ray], what: &str) {
    let base = WideBvh::<C>::build(g, &BvhParams::default()).unwrap();
    assert!(base.info().depth > 3, "{what} {C}: a deep enough tree");
    let want = trace(&base, g, rays);
    let mut refit_base = base.clone();
    refit_base.refit(moved).unwrap();
    let want_moved = trace(&refit_base, moved, rays);
    let map_of = |a: &WideBvh<C>, b: &WideBvh<C>| {
        let same = |p: &WideNode<C>, q: &WideNode<C>| {
            let bits = |n: &WideNode<C>| {
                n.planes
                    .as_flattened()
                    .as_flattened()
                    .iter()
                    .map(|v| v.to_array().map(f32::to_bits))
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(p), bits(q), "{what}: child boxes");
            assert_eq!(p.width(), q.width());
            for i in 0..p.width() {
                let (c, d) = (p.child(i), q.child(i));
                assert_eq!((c.is_leaf(), c.count), (d.is_leaf(), d.count));
                if c.is_leaf() {
                    let ids = |w: &WideBvh<C>, c| leaf_ids(&w.leaf_store, c);
                    assert_eq!(ids(a, c), ids(b, d), "{what}: a leaf");
                }
            }
        };
        node_map((a.root, b.root), &a.nodes, &b.nodes, same)
    };
    for layout in [Layout::Veb, Layout::Treelet] {
        let mut wide = WideBvh::<C>::build(g, &params(layout)).unwrap();
        let map = map_of(&base, &wide);
        assert!(
            moves(&map),
            "{what} {C} {layout:?}: the layout moved no node"
        );
        assert_eq!(
            wide.leaf_store.bytes(),
            base.leaf_store.bytes(),
            "{what}: leaves"
        );
        assert_eq!(trace(&wide, g, rays), want, "{what} {C} {layout:?}");
        wide.refit(moved).unwrap();
        assert_eq!(map_of(&refit_base, &wide), map, "{what} {layout:?}: refit");
        assert_eq!(
            trace(&wide, moved, rays),
            want_moved,
            "{what} {C} {layout:?}: refit"
        );
    }
}

/// The scene's triangles each moved by a few percent of the scene (a smooth warp).
fn warped(tris: &[Triangle], b: &Aabb) -> Arc<[Triangle]> {
    let s = (b.max - b.min).max_element() * 0.03;
    let warp =
        |v: Vec3A| v + Vec3A::new((v.y * 7.0).sin(), (v.z * 5.0).cos(), (v.x * 3.0).sin()) * s;
    tris.iter()
        .map(|t| Triangle::new(warp(t.v[0]), warp(t.v[1]), warp(t.v[2])))
        .collect()
}

/// Incoherent rays from inside the scene and a small image of camera rays.
fn rays(scene: &Scene) -> Vec<Ray> {
    let b = scene.bounds();
    let mut rays = incoherent_rays(&b, 1500, 42);
    rays.extend(primary_rays(&b, 24, 24).unwrap());
    rays
}

#[test]
fn layouts_keep_every_hit_and_counter_on_triangles() {
    for (name, n) in [("soup", 3000), ("icosphere", 3000), ("stadium", 3000)] {
        let scene = generators::generate(name, n, 3).unwrap();
        let g = Triangles::<Watertight>::new(scene.triangles.clone().into());
        let moved = Triangles::<Watertight>::new(warped(&scene.triangles, &scene.bounds()));
        let rays = rays(&scene);
        check_binary(&g, &moved, &rays, name);
        check_wide::<1, _>(&g, &moved, &rays, name);
        check_wide::<2, _>(&g, &moved, &rays, name);
    }
}

/// Spheres and triangles: the wide trees keep id leaves.
#[test]
fn layouts_keep_every_hit_and_counter_with_id_leaves() {
    let scene = generators::generate("mixed", 3000, 3).unwrap();
    let spheres: Arc<[_]> = scene.spheres.clone().into();
    let g = Mixed::<Watertight>::new(scene.triangles.clone().into(), spheres.clone());
    let moved = Mixed::<Watertight>::new(warped(&scene.triangles, &scene.bounds()), spheres);
    let rays = rays(&scene);
    check_binary(&g, &moved, &rays, "mixed");
    check_wide::<1, _>(&g, &moved, &rays, "mixed");
    check_wide::<2, _>(&g, &moved, &rays, "mixed");
}

/// A scene of one leaf has no nodes to move.
#[test]
fn a_single_leaf_tree_takes_every_layout() {
    let t = Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y);
    let g = Triangles::<Watertight>::new(vec![t].into());
    let r = Ray::infinite(glam::Vec3::new(0.2, 0.2, 1.0), glam::Vec3::NEG_Z).unwrap();
    for layout in Layout::ALL {
        let p = params(layout);
        let hit = |h: Option<Hit>| h.map(|h| h.prim);
        assert_eq!(
            hit(Bvh::build(&g, &p)
                .unwrap()
                .closest_hit(&g, &r, &mut NoStats)),
            Some(0)
        );
        assert_eq!(
            hit(Bvh8::build(&g, &p)
                .unwrap()
                .closest_hit(&g, &r, &mut NoStats)),
            Some(0)
        );
    }
}
