//! The event-list build against an oracle: the straightforward builder that sorts the
//! events of every node afresh (`O(N log^2 N)`), with the same classification and clipping,
//! and bins the same large nodes.

use super::*;
use crate::geometry::triangle::Watertight;
use crate::index::kdtree::parallel::{self, Parallel, Top};
use crate::index::kit::near_far::default_max_depth;
use crate::index::kit::near_far::sweep::best_axis_split;
use crate::index::kit::near_far::{scene_bounds, scene_pad};
use crate::scene::{Triangles, generators};
use std::sync::Arc;

/// The oracle's tree: nodes and ids in the same layout as [`Built`].
struct Oracle<'a, G: Geometry> {
    b: Builder<'a, G>,
    scratch: Events,
    bins: Bins,
}

impl<G: Geometry> Oracle<'_, G> {
    /// The subtree over `refs`; binned nodes only below binned nodes (once the builder has
    /// sorted a node's events it keeps them).
    fn node(&mut self, refs: Vec<Ref>, cell: Aabb, depth: u32, may_bin: bool) {
        let at = self.b.nodes.len();
        let (c, binning, pad) = (self.b.costs, self.b.binning, self.b.pad);
        let w = Weights::from(c);
        let open = refs.len() as u32 > c.leaf_size && depth < c.max_depth;
        let binned = (may_bin && open && binning.bins > 0 && refs.len() > binning.above)
            .then(|| self.bins.best_split(&refs, &cell, pad, &w, binning.bins))
            .flatten();
        let split = binned.or_else(|| {
            open.then(|| {
                let bounds = |i: usize| refs[i].b;
                best_axis_split(refs.len(), bounds, &cell, pad, &w, &mut self.scratch)
                    .map(|(a, s, _)| (a, s))
            })
            .flatten()
        });
        let Some((axis, s)) = split else {
            let mut ids: Vec<u32> = refs.iter().map(|r| r.prim).collect();
            ids.sort_unstable();
            let first = self.b.ids.len() as u32;
            if let [one] = ids[..] {
                self.b.nodes.push(KdNode::leaf(one, 1));
            } else {
                self.b.ids.extend(&ids);
                self.b.nodes.push(KdNode::leaf(first, ids.len() as u32));
            }
            self.b.refs += ids.len();
            self.b.leaves += 1;
            self.b.empty_leaves += ids.is_empty() as usize;
            self.b.depth = self.b.depth.max(depth as usize + 1);
            return;
        };
        let (bc, ac) = split_cell(&cell, axis, s);
        let (below, above) = self.b.split_refs(refs, axis, s, &bc, &ac);
        let may_bin = binned.is_some();
        self.b.nodes.push(KdNode::leaf(0, 0));
        self.node(below, bc, depth + 1, may_bin);
        let above_at = self.b.nodes.len() as u32;
        self.node(above, ac, depth + 1, may_bin);
        self.b.nodes[at] = KdNode::interior(axis, s, above_at);
    }
}

fn costs(n: usize, intersect: f32, empty_bonus: f32, leaf_size: u32) -> SahParams {
    SahParams {
        intersect,
        traversal: 1.0,
        empty_bonus,
        max_depth: default_max_depth(n),
        leaf_size,
    }
}

/// Exact SAH at every node, and binned SAH above 300 references among 16 slabs.
const BINNINGS: [Binning; 2] = [
    Binning { bins: 0, above: 0 },
    Binning {
        bins: 16,
        above: 300,
    },
];

#[test]
fn event_lists_build_the_tree_of_a_sort_per_node() {
    let mut splits = 0;
    for (name, n, costs_of) in [
        ("icosphere", 3000, (80.0, 0.2, 1)),
        ("soup", 2000, (80.0, 0.2, 1)),
        ("stadium", 3000, (80.0, 0.2, 1)),
        ("slivers", 2000, (2.0, 0.0, 4)),
        ("room", 2000, (80.0, 0.5, 1)),
        ("flat", 1000, (80.0, 0.2, 1)),
    ] {
        let scene = generators::generate(name, n, 7).unwrap();
        let geom = Triangles::<Watertight>::new(Arc::from(scene.triangles.as_slice()));
        let root = scene_bounds(&geom, "kdtree").unwrap();
        let pad = scene_pad(&root);
        let c = costs(geom.len(), costs_of.0, costs_of.1, costs_of.2);
        for binning in BINNINGS {
            let built = parallel::build(&geom, root, pad, &c, binning).unwrap();
            let mut oracle = Oracle {
                b: Builder::new(&geom, &c, binning, pad),
                scratch: Default::default(),
                bins: Bins::default(),
            };
            let refs = (0..geom.len() as u32)
                .map(|prim| Ref {
                    prim,
                    b: geom.bounds(prim),
                })
                .collect();
            oracle.node(refs, root, 0, true);
            let o = oracle.b;
            assert_eq!(built.nodes, o.nodes, "{name} {binning:?}: nodes");
            assert_eq!(built.ids, o.ids, "{name} {binning:?}: ids");
            assert_eq!(
                (built.refs, built.depth, built.leaves, built.empty_leaves),
                (o.refs, o.depth, o.leaves, o.empty_leaves),
                "{name} {binning:?}"
            );
            // Refs are duplicated, so re-clipping and merging were exercised.
            assert!(built.refs > geom.len(), "{name}: no straddlers");
            splits += built.nodes.len() - built.leaves;
        }
    }
    assert!(splits > 1000, "the trees split: {splits}");
}

#[test]
fn parallel_build_equals_the_sequential_one() {
    let scene = generators::generate("stadium", 3000, 4).unwrap();
    let geom = Triangles::<Watertight>::new(Arc::from(scene.triangles.as_slice()));
    let root = scene_bounds(&geom, "kdtree").unwrap();
    let pad = scene_pad(&root);
    let c = costs(geom.len(), 80.0, 0.2, 1);
    for binning in BINNINGS {
        let tree = |levels| {
            let par = Parallel {
                levels,
                min_prims: 1,
            };
            let top = Top {
                geom: &geom,
                costs: &c,
                binning,
                pad,
            };
            let input = root_input(&geom, pad, binning);
            top.subtree(input, geom.len(), root, 0, par).unwrap()
        };
        let (sequential, parallel) = (tree(0), tree(8));
        assert!(sequential.nodes.len() > 1000, "the tree splits");
        assert_eq!(sequential.nodes, parallel.nodes);
        assert_eq!(sequential.ids, parallel.ids);
        assert_eq!(
            (sequential.refs, sequential.depth, sequential.leaves),
            (parallel.refs, parallel.depth, parallel.leaves)
        );
        assert_eq!(sequential.empty_leaves, parallel.empty_leaves);
    }
}

#[test]
fn merge_keeps_the_sweep_order() {
    let mut list = vec![
        Event::end(0.0, 1),
        Event::start(0.0, 2),
        Event::start(2.0, 3),
    ];
    let new = [
        Event::start(-1.0, 4),
        Event::end(0.0, 6),
        Event::start(0.0, 5),
        Event::end(3.0, 7),
    ];
    merge_into(&mut list, &new);
    let got: Vec<(f32, bool)> = list.iter().map(|e| (e.pos, e.is_start())).collect();
    assert_eq!(
        got,
        [
            (-1.0, true),
            (0.0, false),
            (0.0, false),
            (0.0, true),
            (0.0, true),
            (2.0, true),
            (3.0, false)
        ]
    );
}
