//! The outside peers Embree and tinybvh (features `embree`, `tinybvh`; `peers` = both): they
//! build and trace the bunny and the generated triangle scenes, their disagreements with brute
//! force are classified as ties or wrong (none wrong for the robust `embree` and `embree-p16`
//! on the bunny's protocol sets), `embree-p16`'s packets give every ray what it gets alone, and
//! a scene with spheres skips them with the reason.
#![cfg(any(feature = "embree", feature = "tinybvh"))]

use crate::common;

use accelbench::geometry::{Hit, Ray, TriangleKernelKind};
use accelbench::harness::suite::{Shard, SuiteConfig, run_suite, run_suite_with};
use accelbench::harness::workload::{RaySet, SetSizes};
use accelbench::index::{
    BuildError, IndexSpec, Kind, TraceIndex, TraceMode, build_index, build_index_on, is_peer,
    kind_of, peer_names,
};
use accelbench::scene::{Scene, SceneGeometry, Triangles, generators};
use indicatif::ProgressBar;

/// The peers of this build (obvhs excluded: `tests/it/obvhs_peer.rs`; the GPU indices:
/// `tests/it/gpu.rs`).
fn peers() -> Vec<&'static str> {
    peer_names()
        .into_iter()
        .filter(|n| !n.starts_with("obvhs") && kind_of(n) == Some(Kind::Peer))
        .collect()
}

/// The modes a peer is checked in: one query at a time, and its own batch technique (Embree's
/// ray streams, `embree-p16`'s packets of 16).
const MODES: [TraceMode; 2] = [TraceMode::Single, TraceMode::Stream];

/// Embree's robust (watertight) scene, traced ray by ray or in packets of 16.
fn robust_embree(name: &str) -> bool {
    name == "embree" || name == "embree-p16"
}

fn build(spec: &str, scene: &Scene) -> Box<dyn TraceIndex> {
    common::build(spec, scene, TriangleKernelKind::Exact)
}

use common::judge::judge;

/// The generated triangle scenes: every peer builds and traces them (any-hit consistent with its
/// closest hit); on protocol-like rays (48 x 48 primary, 2000 incoherent) the robust `embree`
/// and `embree-p16` are wrong on at most 1% of the hits. The others' counts are printed: `embree-fast` misses most
/// of the zero-thickness `flat` scene, and on rays aimed exactly at vertices and edges
/// (`common::agreement_rays`) non-watertight peers lose hits through the cracks.
#[test]
fn peers_trace_generated_triangle_scenes_close_to_brute_force() {
    let scenes = common::agreement_scenes()
        .into_iter()
        .filter(|s| s.spheres.is_empty() && s.shapes.is_empty());
    for scene in scenes {
        let brute = build("brute", &scene);
        let rays = common::bunny_protocol_sample(&scene);
        let aimed = common::agreement_rays(&scene, 500);
        let expected = common::closest(brute.as_ref(), &rays);
        let expected_aimed = common::closest(brute.as_ref(), &aimed);
        let hits = expected.iter().flatten().count();
        for name in peers() {
            let index = build(name, &scene);
            assert!(index.info().memory_bytes > 0, "{name}: no memory reported");
            for mode in MODES.into_iter().filter(|m| index.traces_in(*m)) {
                let got = common::closest_in(index.as_ref(), mode, &rays);
                let what = format!("{name} ({}) on {}", mode.label(), scene.name);
                let c = judge(&what, &scene, &rays, &expected, &got);
                let got_aimed = common::closest_in(index.as_ref(), mode, &aimed);
                let c_aimed = judge(&what, &scene, &aimed, &expected_aimed, &got_aimed);
                eprintln!("{what}: {c:?} of {hits} hits; aimed at vertices and edges: {c_aimed:?}");
                if robust_embree(name) {
                    assert!(c.wrong * 100 <= hits, "{what}: {c:?} of {hits} hits");
                }
                common::assert_any_hit_is_closest_hit(index.as_ref(), mode, &rays, &got, &what);
            }
        }
    }
}

/// The bunny's full protocol sets (`common::bunny_protocol_sets`: every ray can be checked).
#[test]
fn embree_is_never_wrong_on_the_bunny_protocol_sets() {
    let Some(bunny) = common::bunny() else { return };
    for (set, rays, expected) in &common::bunny_protocol_sets(&bunny) {
        for name in peers() {
            let index = build(name, &bunny);
            for mode in MODES.into_iter().filter(|m| index.traces_in(*m)) {
                let got = common::closest_in(index.as_ref(), mode, rays);
                let what = format!("{name} ({}) {set}", mode.label());
                let c = judge(&what, &bunny, rays, expected, &got);
                eprintln!("{what}, the bunny: {} rays, {c:?}", rays.len());
                if robust_embree(name) {
                    assert_eq!(c.wrong, 0, "{what}: {c:?}");
                }
            }
        }
    }
}

/// `embree-p16` traces a batch (its stream mode) in packets of 16 consecutive rays, the last packet of a batch
/// shorter (its missing lanes masked off): on 1007 rays (the last chunk of 64 is 47 rays: two
/// packets and one of 15) every ray gets what it gets traced alone (a one-lane packet), so no
/// lane depends on its neighbours or on the mask; any-hit, also in packets, agrees with closest
/// hit, and finds nothing on the rays cut halfway to their closest hit. `embree+packets16`
/// answers as `embree-p16` does.
#[cfg(feature = "embree")]
#[test]
fn embree_p16_packet_lanes_match_rays_traced_alone() {
    let scene = generators::generate("icosphere", 2000, 3).unwrap();
    let rays = &common::bunny_protocol_sample(&scene)[..1007];
    let p16 = build("embree-p16", &scene);
    let got = common::closest_in(p16.as_ref(), TraceMode::Stream, rays);
    let hits = got.iter().flatten().count();
    assert!(
        hits > 100 && hits < rays.len(),
        "{hits} hits of {}",
        rays.len()
    );
    for (i, g) in got.iter().enumerate() {
        let alone = common::closest_in(p16.as_ref(), TraceMode::Stream, &rays[i..=i])[0];
        assert_eq!(
            g.map(|h| (h.prim, h.t.to_bits())),
            alone.map(|h| (h.prim, h.t.to_bits())),
            "ray {i}: {:?}",
            rays[i]
        );
    }
    let mut any = vec![false; rays.len()];
    p16.any_hits_in(TraceMode::Stream, rays, &mut any, None);
    let any_of_closest: Vec<bool> = got.iter().map(Option::is_some).collect();
    assert_eq!(any, any_of_closest);
    let short: Vec<Ray> = rays
        .iter()
        .zip(&got)
        .map(|(r, g)| {
            let t_max = g.map_or(r.t_max, |h| 0.5 * (r.t_min + h.t));
            Ray::new(r.origin.into(), r.dir.into(), r.t_min, t_max).unwrap()
        })
        .collect();
    p16.any_hits_in(TraceMode::Stream, &short, &mut any, None);
    // Nothing lies closer than the closest hit.
    assert_eq!(any.iter().filter(|&&a| a).count(), 0);
    // `embree+packets16` makes the same calls on a batch that is not an image: the packets are
    // the same runs of 16 consecutive rays of each chunk of 64.
    let embree = build("embree", &scene);
    let packets = TraceMode::Packets(16);
    let bits = |h: &[Option<Hit>]| -> Vec<_> {
        h.iter()
            .map(|h| h.map(|h| (h.prim, h.t.to_bits())))
            .collect()
    };
    let in_packets = common::closest_in(embree.as_ref(), packets, rays);
    assert_eq!(bits(&in_packets), bits(&got));
    embree.any_hits_in(packets, rays, &mut any, None);
    assert_eq!(any, any_of_closest);
}

fn config(indices: &[&str], sets: Vec<RaySet>) -> SuiteConfig {
    SuiteConfig {
        indices: indices.iter().map(|n| IndexSpec::named(n)).collect(),
        sets,
        threads: vec![1],
        sizes: SetSizes {
            primary_side: 32,
            incoherent: 1000,
            ao_fraction: 0.05,
        },
        repeats: 1,
        kernel: TriangleKernelKind::Exact,
        verify_budget: u64::MAX,
        brute_timing_budget: 0,
        timed: true,
        shard: Shard::WHOLE,
        modes: vec![accelbench::index::TraceMode::Single],
    }
}

#[test]
fn suite_rows_of_peers_have_ties_and_wrong_and_no_counters() {
    let scene = generators::generate("icosphere", 2000, 3).unwrap();
    let mut names = vec!["bvh"];
    names.extend(peers());
    let mut cfg = config(&names, RaySet::ALL.to_vec());
    cfg.modes = MODES.to_vec();
    let res = run_suite(std::slice::from_ref(&scene), &cfg, &ProgressBar::hidden()).unwrap();
    assert_eq!(res.mismatch_total, 0, "{:?}", res.mismatches.first());
    assert!(res.notes.is_empty(), "{:?}", res.notes);
    // A row per set in every mode the index traces: `+stream` only with a batch technique of
    // its own, and `embree-p16` (a batch technique over `embree`'s single rays) only there.
    let mut want = 0;
    for name in &names {
        let index = build(name, &scene);
        for mode in MODES.into_iter().filter(|m| index.traces_in(*m)) {
            let label = match mode {
                TraceMode::Single => name.to_string(),
                m => format!("{name}+{}", m.label()),
            };
            let rows = res.rows.iter().filter(|r| r.index == label);
            assert!(rows.clone().all(|r| r.mode == mode.label()), "{label}");
            assert_eq!(rows.count(), RaySet::ALL.len(), "{label}");
            want += RaySet::ALL.len();
        }
    }
    assert_eq!(res.rows.len(), want);
    if names.contains(&"embree-p16") {
        assert!(res.rows.iter().all(|r| r.index != "embree-p16"));
        assert!(res.rows.iter().any(|r| r.index == "embree+stream"));
    }
    for r in &res.rows {
        if is_peer(r.index.split('+').next().unwrap()) {
            let (ties, t_off) = (r.peer_ties.unwrap(), r.peer_t_off.unwrap());
            assert!(
                ties + t_off + r.peer_wrong.unwrap() <= r.mismatches,
                "{r:?}"
            );
            assert!(
                r.prim_tests_per_ray.is_nan() && r.node_visits_per_ray.is_nan(),
                "{r:?}"
            );
            assert!(r.mrays_per_s > 0.0 && r.memory_bytes > 0, "{r:?}");
        } else {
            assert_eq!(
                (r.peer_ties, r.peer_t_off, r.peer_wrong),
                (None, None, None),
                "{r:?}"
            );
            assert!(r.prim_tests_per_ray > 0.0, "{r:?}");
        }
    }
}

/// A faulty "peer" (brute force that never reports one primitive, registered under a peer's
/// name) is caught: the rays through that primitive are counted wrong, not as ties.
#[test]
fn a_peer_that_drops_a_primitive_is_counted_wrong() {
    let scene = generators::generate("icosphere", 500, 1).unwrap();
    let name = peers()[0];
    let cfg = config(&[name], vec![RaySet::Primary]);
    let res = run_suite_with(
        &[scene],
        &cfg,
        &ProgressBar::hidden(),
        &|_: &IndexSpec, g: &SceneGeometry| {
            let geom = Triangles::<accelbench::geometry::triangle::Exact>::new(g.triangles.clone());
            Ok(Box::new(build_index_on::<common::drop_one::DropOne, _>(
                name,
                geom,
                Default::default(),
            )?) as Box<dyn TraceIndex>)
        },
        &mut |_, _| {},
    )
    .unwrap();
    let row = &res.rows[0];
    assert!(
        row.mismatches > 0,
        "the dropped primitive is never hit: {row:?}"
    );
    assert_eq!(row.peer_wrong, Some(row.mismatches), "{row:?}");
    assert_eq!(
        res.mismatch_total, 0,
        "a peer's mismatches do not fail the run"
    );
}

#[test]
fn a_scene_with_spheres_skips_the_peers_with_the_reason() {
    let scene = generators::generate("mixed", 600, 2).unwrap();
    let mut names = vec!["bvh"];
    names.extend(peers());
    let res = run_suite(
        std::slice::from_ref(&scene),
        &config(&names, vec![RaySet::Primary]),
        &ProgressBar::hidden(),
    )
    .unwrap();
    assert_eq!(res.rows.len(), 1, "only bvh runs: {:?}", res.rows);
    assert_eq!(res.notes.len(), peers().len(), "{:?}", res.notes);
    for n in &res.notes {
        assert!(
            n.reason
                .starts_with("skipped: the peer tests triangles only, and this scene has spheres"),
            "{n:?}"
        );
    }
    for name in peers() {
        let err = build_index(
            &IndexSpec::named(name),
            &scene.geometry(),
            TriangleKernelKind::Exact,
        )
        .err()
        .unwrap();
        assert!(matches!(err, BuildError::Unsupported { .. }), "{err}");
    }
}

/// Rays outside the C peers' own conventions, all valid rays of ours: `t_max = inf` along
/// (1, 1, 1) (through the 1e30 boxes tinybvh puts in empty child slots), directions of length
/// 1e-15 to 1e-45 and 1e30, coordinates beyond Embree's ±1.844e18 and sums that overflow
/// tinybvh's ray check. Before the shim's guard and Embree's range check, tinybvh segfaulted on
/// the first two kinds and Embree aborted on the third (its assertion `ray.valid()`), killing
/// the run. Now every peer answers every ray in every mode, the refused rays are counted with
/// the reason, and the robust Embree finds the quad along a direction of length 1e-15 at brute
/// force's `t` (tinybvh misses it: it takes direction components below 1e-12 for zero, and is
/// counted wrong there).
#[test]
fn peers_survive_rays_outside_their_own_conventions() {
    let p = |x: f32, y: f32| glam::Vec3A::new(x, y, 0.0);
    let quad = Scene::from_triangles(
        "quad",
        vec![
            accelbench::geometry::Triangle::new(p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)),
            accelbench::geometry::Triangle::new(p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)),
        ],
    );
    let soup = generators::generate("soup", 1000, 1).unwrap();
    let origins = [
        [0.5, 0.5, -2.0],
        [-100.0, -100.0, -100.0],
        [0.5, 0.5, 2.0],
        [5.0, 5.0, -2.0],
        [3e38, 3e38, 0.0],
    ];
    let dirs = [
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [2.0, 2.0, 2.0],
        [1e-3, 1e-3, 1e-3],
        [0.0, 0.0, 1e-15],
        [1e-20, 1e-20, 1e-30],
        [1e-45, 1e-44, 1e-40],
        [0.0, 0.0, 1e30],
        [1e25, 1e25, 1e30],
        [-3e38, -3e38, 1.0],
        [-1.0, -1.0, -1.0],
    ];
    let rays: Vec<Ray> = origins
        .iter()
        .flat_map(|o| dirs.iter().map(move |d| (*o, *d)))
        .map(|(o, d)| Ray::infinite(o.into(), d.into()).unwrap())
        .collect();
    let short = Ray::infinite([0.5, 0.5, -2.0].into(), [0.0, 0.0, 1e-15].into()).unwrap();
    for scene in [&quad, &soup] {
        let brute = build("brute", scene);
        let expected = common::closest(brute.as_ref(), &rays);
        for name in peers() {
            let index = build(name, scene);
            for mode in MODES.into_iter().filter(|m| index.traces_in(*m)) {
                let got = common::closest_in(index.as_ref(), mode, &rays);
                let what = format!("{name} ({}) on {}", mode.label(), scene.name);
                let c = judge(&what, scene, &rays, &expected, &got);
                let mut any = vec![false; rays.len()];
                index.any_hits_in(mode, &rays, &mut any, None);
                eprintln!("{what}: {c:?}");
            }
            let refused = index.refused(&rays).map_or(0, |(n, _)| n);
            let expect = match name.starts_with("embree") {
                // Origins at 3e38 (11 rays) and the other origins' 1e30 and 3e38 directions.
                true => dirs.len() + 3 * (origins.len() - 1),
                // The directions (-3e38, -3e38, 1) overflow tinybvh's check at every origin.
                false => origins.len(),
            };
            assert_eq!(refused, expect, "{name} on {}", scene.name);
        }
    }
    let want = build("brute", &quad).closest_hit(&short).unwrap();
    for name in ["embree", "embree-p16"] {
        if !peers().contains(&name) {
            continue;
        }
        let got = build(name, &quad).closest_hit(&short);
        let t = got.map(|h| h.t);
        assert!(
            t.is_some_and(|t| ((t - want.t) / want.t).abs() < 1e-6),
            "{name}: {got:?}, brute force {want:?}"
        );
    }
}
