//! `run --modes reorder` changes no hit and no counter: every index of ours, tracing a batch
//! sorted by the coherence key, returns brute force's closest hits bit for bit and the same
//! any-hit answers, and every ray's counters are its own `single` counters.

use crate::common;

use accelbench::geometry::TriangleKernelKind;
use accelbench::index::trace::reorder::coherence_order;
use accelbench::index::{Counters, TraceMode};
use accelbench::scene::generators;

#[test]
fn reordering_a_batch_changes_no_hit() {
    common::assert_mode_agrees(TraceMode::Reorder);
}

/// A reordered counting pass puts each ray's counters back at that ray: they equal the
/// `single` pass's ray by ray, on rays the key really does reorder.
#[test]
fn reordered_counters_stay_with_their_rays() {
    let scene = generators::generate("soup", 3000, 7).unwrap();
    let rays = common::agreement_rays(&scene, 2000);
    let order = coherence_order(&rays);
    let moved = order.iter().enumerate().filter(|(k, p)| *k != p.1).count();
    assert!(moved > rays.len() / 2, "only {moved} rays change place");
    for name in ["bvh", "bvh8", "kdtree", "grid", "octree"] {
        let index = common::build(name, &scene, TriangleKernelKind::Exact);
        let n = rays.len();
        let (mut single, mut sorted) = (vec![None; n], vec![None; n]);
        let (mut c_single, mut c_sorted) =
            (vec![Counters::default(); n], vec![Counters::default(); n]);
        index.closest_hits_in(TraceMode::Single, &rays, &mut single, Some(&mut c_single));
        index.closest_hits_in(TraceMode::Reorder, &rays, &mut sorted, Some(&mut c_sorted));
        assert_eq!(single, sorted, "{name}: hits");
        let differ = (0..n).filter(|&i| c_single[i] != c_sorted[i]).count();
        assert_eq!(differ, 0, "{name}: {differ} rays with other counters");
        assert!(
            c_single.iter().any(|c| c.prim_tests > 0),
            "{name} counted nothing"
        );
    }
}

/// The suite traces every set in `reorder` too: rows `INDEX+reorder` in the batch family, each
/// verified against the index's `single` row (no mismatch), with that row's counters.
#[test]
fn the_suite_gives_reorder_rows() {
    use accelbench::harness::suite::run_suite;
    use accelbench::harness::workload::RaySet;
    use accelbench::index::ModeFamily;
    let mut cfg = crate::suite::config(&["bvh", "kdtree"]);
    cfg.sets = vec![RaySet::Primary, RaySet::Shadow, RaySet::Incoherent];
    cfg.threads = vec![1];
    cfg.modes = vec![TraceMode::Single, TraceMode::Reorder];
    let scene = generators::generate("icosphere", 2000, 1).unwrap();
    let res = run_suite(&[scene], &cfg, &indicatif::ProgressBar::hidden()).unwrap();
    assert_eq!(res.mismatch_total, 0);
    for set in ["primary", "shadow", "incoherent"] {
        for index in ["bvh", "kdtree"] {
            let row = |label: &str| {
                res.rows
                    .iter()
                    .find(|r| r.index == label && r.ray_set == set)
                    .unwrap_or_else(|| panic!("no row {label} on {set}"))
            };
            let (single, sorted) = (row(index), row(&format!("{index}+reorder")));
            assert_eq!(sorted.mode, "reorder");
            assert_eq!(TraceMode::Reorder.family(), ModeFamily::Batch);
            assert_eq!(
                (
                    sorted.hits,
                    sorted.prim_tests_per_ray,
                    sorted.node_visits_per_ray
                ),
                (
                    single.hits,
                    single.prim_tests_per_ray,
                    single.node_visits_per_ray
                ),
                "{index} on {set}"
            );
        }
    }
}
