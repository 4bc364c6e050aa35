//! Unit tests of the octree's pieces: the build invariants (cells, ropes, primitive lists,
//! degenerate guards), the shared crossing rule, the corrected Revelles next-node table, and
//! "each primitive tested at most once per ray" recorded primitive by primitive.

use super::axis_ray::AxisRay;
use super::topdown::next_child;
use super::tree::{NO_ROPE, face};
use super::*;
use crate::geometry::triangle::Watertight;
use crate::geometry::{Aabb, Triangle};
use crate::index::NoStats;
use crate::scene::{GeometryWrapper, ShapeQueries, Triangles, generators};
use glam::{Vec3, Vec3A};
use std::cell::RefCell;
use std::sync::Arc;

fn tris(name: &str, n: usize) -> Triangles<Watertight> {
    let s = generators::generate(name, n, 2).unwrap();
    Triangles::new(Arc::from(s.triangles))
}

fn params(max_prims: usize, max_depth: usize) -> OctreeParams {
    OctreeParams {
        max_prims,
        max_depth,
    }
}

#[test]
fn revelles_next_node_table_with_erratum() {
    // The corrected table of Revelles et al. 2000 (octant bits x = 4, y = 2, z = 1): the child
    // entered after leaving `c` through its far YZ (x), XZ (y) or XY (z) plane; 8 = leave the
    // parent. The published version swaps the x and z columns.
    const TABLE: [[usize; 3]; 8] = [
        [4, 2, 1],
        [5, 3, 8],
        [6, 8, 3],
        [7, 8, 8],
        [8, 6, 5],
        [8, 7, 8],
        [8, 8, 7],
        [8, 8, 8],
    ];
    for (c, row) in TABLE.iter().enumerate() {
        for (axis, &want) in row.iter().enumerate() {
            assert_eq!(next_child(c, axis).unwrap_or(8), want, "c={c} axis={axis}");
        }
    }
}

#[test]
fn cells_tile_the_root_and_leaves_list_exactly_the_overlapping_primitives() {
    let g = tris("soup", 300);
    let t = OctreeTree::build(&g, &params(3, 6)).unwrap();
    let root = t.root_cell();
    let e = root.extent();
    let b = (0..g.len() as u32).fold(Aabb::EMPTY, |b, p| b.union(g.bounds(p)));
    assert!(root.min.cmplt(b.min).all() && b.max.cmplt(root.max).all());
    let mut volume = 0.0f64;
    for n in t.nodes.iter().filter(|n| n.is_leaf()) {
        let want: Vec<u32> = (0..g.len() as u32)
            .filter(|&p| g.overlaps_box(p, &n.cell()))
            .collect();
        // Children are filtered from the parent's list, so a leaf lists every overlapping
        // primitive that its ancestors kept (all of them: the tests are conservative).
        assert_eq!(t.leaf_prims(n), want.as_slice());
        let x = n.cell().extent();
        volume += x.x as f64 * x.y as f64 * x.z as f64;
    }
    let root_volume = e.x as f64 * e.y as f64 * e.z as f64;
    assert!(
        (volume / root_volume - 1.0).abs() < 1e-4,
        "{volume} vs {root_volume}"
    );
    let children: usize = t
        .nodes
        .iter()
        .filter(|n| !n.is_leaf())
        .map(|n| {
            assert!((1..8).contains(&n.split), "{}", n.split);
            n.child_count()
        })
        .sum();
    assert_eq!(t.nodes.len(), 1 + children);
    assert!(t.max_level >= 2 && t.max_level <= 6);
}

#[test]
fn ropes_lead_to_the_deepest_node_covering_each_face() {
    let t = OctreeTree::build(&tris("icosphere", 500), &params(2, 5)).unwrap();
    let root = t.root_cell();
    for (i, n) in t.nodes.iter().enumerate() {
        for axis in 0..3 {
            for upper in [false, true] {
                let rope = n.ropes[face(axis, upper)];
                let plane = if upper { n.cell().max } else { n.cell().min }[axis];
                if rope == NO_ROPE {
                    let edge = if upper { root.max } else { root.min }[axis];
                    assert_eq!(plane, edge, "node {i} axis {axis} upper {upper}");
                    continue;
                }
                let m = &t.nodes[rope as usize].cell();
                let other = if upper { m.min } else { m.max }[axis];
                assert_eq!(plane, other, "node {i} -> {rope}: not adjacent");
                for b in (0..3).filter(|&b| b != axis) {
                    assert!(m.min[b] <= n.cell().min[b] && n.cell().max[b] <= m.max[b]);
                }
                // The deepest such node: none of its children touching the face covers it.
                let target = &t.nodes[rope as usize];
                if !target.is_leaf() {
                    for c in 0..target.child_count() {
                        let k = &t.nodes[target.first as usize + c].cell();
                        let touches = if upper { k.min } else { k.max }[axis] == plane;
                        let covers = (0..3)
                            .filter(|&b| b != axis)
                            .all(|b| k.min[b] <= n.cell().min[b] && n.cell().max[b] <= k.max[b]);
                        assert!(!(touches && covers), "node {i}: rope {rope} not tight");
                    }
                }
            }
        }
    }
}

#[test]
fn flat_and_point_scenes_get_a_padded_box() {
    let flat = Triangles::<Watertight>::new(Arc::from(vec![Triangle::new(
        Vec3A::new(0.0, 0.0, 2.0),
        Vec3A::new(4.0, 0.0, 2.0),
        Vec3A::new(0.0, 1.0, 2.0),
    )]));
    let root = OctreeTree::build(&flat, &OctreeParams::default())
        .unwrap()
        .root_cell();
    let b = flat.bounds(0);
    assert!(
        root.min.cmplt(b.min).all() && b.max.cmplt(root.max).all(),
        "{root:?}"
    );
    let e = root.extent();
    assert!(e.z > 0.0 && e.z < 1e-3 && e.x > 4.0 && e.y > 1.0, "{e}");
    let point = Triangles::<Watertight>::new(Arc::from(vec![Triangle::new(
        Vec3A::ZERO,
        Vec3A::ZERO,
        Vec3A::ZERO,
    )]));
    let root = OctreeTree::build(&point, &OctreeParams::default())
        .unwrap()
        .root_cell();
    assert_eq!(root, Aabb::new(Vec3A::splat(-1.0), Vec3A::ONE));
}

#[test]
fn a_flat_scene_is_split_along_its_plane_only() {
    let t = OctreeTree::build(&tris("flat", 4000), &OctreeParams::default()).unwrap();
    // The root box is thin around y = 0: every split is along x and z only, and no leaf is empty.
    for n in t.nodes.iter().filter(|n| !n.is_leaf()) {
        assert_eq!(n.split & 2, 0, "y split in {:?}", n.cell());
    }
    assert_eq!(t.empty_leaves(), 0);
    assert!(t.leaves() >= 4000 / 16);
}

#[test]
fn duplicates_stop_splitting_but_clusters_are_refined() {
    let tri = Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::Y);
    let dup = Triangles::<Watertight>::new(Arc::from(vec![tri; 100]));
    let t = OctreeTree::build(&dup, &params(1, 16)).unwrap();
    // The first split already puts all copies into several children: it separates nothing.
    assert_eq!(t.nodes.len(), 1);
    // A small cluster far from a lone triangle: splits that move the whole cluster into one
    // child still refine, so the cluster's leaves are small.
    let mut v: Vec<Triangle> = (0..40)
        .map(|i| {
            let o = Vec3A::new(0.9 + 0.001 * i as f32, 0.9, 0.9);
            Triangle::new(o, o + Vec3A::X * 0.001, o + Vec3A::Y * 0.001)
        })
        .collect();
    v.push(Triangle::new(Vec3A::ZERO, Vec3A::X * 0.01, Vec3A::Y * 0.01));
    let t = OctreeTree::build(&Triangles::<Watertight>::new(Arc::from(v)), &params(4, 12)).unwrap();
    assert!(
        t.max_level >= 6,
        "cluster not refined: depth {}",
        t.max_level
    );
}

#[test]
fn absurd_params_are_rejected_with_what_to_fix() {
    let e = OctreeParams {
        max_prims: 0,
        max_depth: 3,
    }
    .validate()
    .unwrap_err();
    assert!(
        e.to_string().contains("max_prims must be at least 1"),
        "{e}"
    );
    assert!(params(1, MAX_DEPTH_LIMIT).validate().is_ok());
    assert!(params(1, MAX_DEPTH_LIMIT + 1).validate().is_err());
}

#[test]
fn a_ray_in_a_split_plane_goes_to_the_upper_child_for_either_zero_sign() {
    let mid = Vec3A::splat(0.5);
    for z in [0.0f32, -0.0] {
        for dx in [1.0f32, -1.0] {
            // Lies in the planes y = 0.5 and z = 0.5; moves along x.
            let ray = Ray::infinite(Vec3::new(0.25, 0.5, 0.5), Vec3::new(dx, z, z)).unwrap();
            let r = AxisRay::new(&ray);
            let c = r.child_at(mid, 0.0);
            assert_eq!(c & 3, 3, "y and z upper (z={z:?}, dx={dx})");
            assert_eq!(c & 4, 0, "x lower at t=0");
            // Past the x split, moving up in x reaches the upper x half, moving down stays.
            let c = r.child_at(mid, 0.25);
            assert_eq!(c & 4 != 0, dx > 0.0);
        }
    }
}

thread_local! {
    static TESTED: RefCell<Vec<u32>> = const { RefCell::new(Vec::new()) };
}

/// Triangles that record every kernel call on this thread.
#[derive(Clone)]
struct Recording(Triangles<Watertight>);

impl GeometryWrapper for Recording {
    type Inner = Triangles<Watertight>;
    fn inner(&self) -> &Triangles<Watertight> {
        &self.0
    }
}

impl Geometry for Recording {
    fn len(&self) -> usize {
        self.0.len()
    }
    fn bounds(&self, prim: u32) -> Aabb {
        self.0.bounds(prim)
    }
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        TESTED.with(|t| t.borrow_mut().push(prim));
        self.0.intersect(prim, ray, t_max)
    }
}

fn tested_once_each<O: LeafOrder>(g: &Recording, rays: &[Ray]) {
    let index = Octree::<O>::build(g, &params(1, 7)).unwrap();
    // Some primitives sit in several leaves, so without the mailbox rays would retest them.
    let refs = index.info().prim_refs;
    assert!(refs > g.len(), "{refs} references");
    for ray in rays {
        for any in [false, true] {
            TESTED.with(|t| t.borrow_mut().clear());
            if any {
                index.any_hit(g, ray, &mut NoStats);
            } else {
                index.closest_hit(g, ray, &mut NoStats);
            }
            let mut seen = TESTED.with(|t| t.borrow().clone());
            let n = seen.len();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), n, "a primitive tested twice on {ray:?}");
        }
    }
}

#[test]
fn each_primitive_is_tested_at_most_once_per_ray() {
    let g = Recording(tris("soup", 60));
    let b = (0..g.len() as u32).fold(Aabb::EMPTY, |b, p| b.union(g.bounds(p)));
    let rays = crate::rays::incoherent_rays(&b, 300, 9);
    tested_once_each::<Neighbor>(&g, &rays);
    tested_once_each::<TopDown>(&g, &rays);
}
