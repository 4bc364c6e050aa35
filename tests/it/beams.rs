//! The beam modes (`beams16`; `index::kit::box_tree::beam`): `bvh`, `bvh4` and `bvh8` return
//! every ray's single-ray answer bit for bit on the bunny's primary, shadow and incoherent rays
//! (closest and any hit, tiles and row segments, counted and not); the beam path is really taken
//! (its box-test counts are not the packet walk's); and only the box trees get beam rows.
//! `packets.rs` runs the beam modes over its adversarial packets too.

use crate::common;

use accelbench::geometry::{Hit, Ray, TriangleKernelKind};
use accelbench::harness::verify::compare_closest;
use accelbench::harness::workload::{self, RaySet, SetSizes};
use accelbench::index::{
    Counters, IndexSpec, TraceIndex, TraceMode, build_index, index_names, is_peer,
};
use accelbench::scene::{Scene, generators};

const TREES: [&str; 3] = ["bvh", "bvh4", "bvh8"];
const BEAMS16: TraceMode = TraceMode::Beams(16);

/// Asserts that `index` traced in `beams16` gives `expected` (its single-ray closest hits) bit
/// for bit and the matching any-hit answers, as row segments and, with `width`, as an image.
fn assert_beams_agree(
    what: &str,
    scene: &Scene,
    index: &dyn TraceIndex,
    rays: &[Ray],
    expected: &[Option<Hit>],
    width: Option<usize>,
) {
    let n = rays.len();
    for width in std::iter::once(None).chain(width.map(Some)) {
        let what = format!("{what}, {} in beams16, image width {width:?}", index.name());
        let mut got = vec![None; n];
        let mut counters = vec![Counters::default(); n];
        for c in [None, Some(&mut counters[..])] {
            let counted = c.is_some();
            match width {
                Some(w) => index.closest_hits_image(BEAMS16, rays, w, &mut got, c),
                None => index.closest_hits_in(BEAMS16, rays, &mut got, c),
            }
            let m = compare_closest(rays, expected, &got);
            common::assert_no_mismatch(&format!("{what}, counted {counted}"), scene, n, &m);
        }
        let mut any = vec![false; n];
        match width {
            Some(w) => index.any_hits_image(BEAMS16, rays, w, &mut any, None),
            None => index.any_hits_in(BEAMS16, rays, &mut any, None),
        }
        let mut single_any = vec![false; n];
        index.any_hits(rays, &mut single_any);
        let wrong = (0..n).filter(|&i| any[i] != single_any[i]).count();
        assert_eq!(wrong, 0, "{what} any-hit: {wrong} wrong");
        let wrong = (0..n).filter(|&i| any[i] != expected[i].is_some()).count();
        assert_eq!(wrong, 0, "{what} any-hit against closest: {wrong} wrong");
    }
}

/// The bunny's primary rays (a 256 x 256 image), its shadow rays (row segments, not an image)
/// and 65,536 incoherent rays: every box tree in `beams16` gives its single-ray answers.
#[test]
fn beams16_give_single_ray_answers_on_the_bunny() {
    let Some(bunny) = common::bunny() else {
        eprintln!("bunny mesh not found: skipped");
        return;
    };
    let sizes = SetSizes {
        primary_side: 256,
        incoherent: 1 << 16,
        ao_fraction: 0.05,
    };
    let primary = workload::primary(&bunny, &sizes).unwrap();
    let reference = common::build("bvh", &bunny, TriangleKernelKind::Exact);
    let primary_hits = common::closest(reference.as_ref(), &primary);
    let shadow = workload::secondary(RaySet::Shadow, &bunny, &sizes, &primary, &primary_hits);
    let incoherent = workload::incoherent(&bunny, &sizes);
    assert!(shadow.len() > 10_000, "{} shadow rays", shadow.len());
    for name in TREES {
        let index = common::build(name, &bunny, TriangleKernelKind::Exact);
        for (set, rays, width) in [
            ("primary", &primary, Some(256)),
            ("shadow", &shadow, None),
            ("incoherent", &incoherent, None),
        ] {
            let expected = common::closest(index.as_ref(), rays);
            let what = format!("bunny {set}");
            assert_beams_agree(&what, &bunny, index.as_ref(), rays, &expected, width);
        }
    }
}

/// Summed box tests and node visits of `rays` (an image `width` wide) traced in `mode`.
fn counted(index: &dyn TraceIndex, mode: TraceMode, rays: &[Ray], width: usize) -> Counters {
    let mut got = vec![None; rays.len()];
    let mut c = vec![Counters::default(); rays.len()];
    index.closest_hits_image(mode, rays, width, &mut got, Some(&mut c[..]));
    c.iter().fold(Counters::default(), |mut t, r| {
        t.box_tests += r.box_tests;
        t.node_visits += r.node_visits;
        t
    })
}

/// On camera tiles the beam walk decides most nodes with the first active ray alone, so its
/// rays are charged fewer box tests than in the packet walk (where every active ray is charged
/// each node's child tests), though they visit more nodes (rays kept live untested): a
/// `beams16` that ran the packet walk, or ray by ray, has the packet walk's box tests (or the
/// single rays', about the same) and fails this. Measured when written: bvh on terrain 24,730
/// against 39,536.
#[test]
fn beams16_take_the_beam_path_on_camera_tiles() {
    let mut scenes = vec![generators::generate("terrain", 2000, 5).unwrap()];
    scenes.extend(common::bunny());
    let mut wrong = Vec::new();
    for scene in scenes {
        let b = scene.ray_set_bounds();
        let rays = accelbench::rays::primary_rays(&b, 64, 64).unwrap();
        for name in TREES {
            let index = common::build(name, &scene, TriangleKernelKind::Exact);
            let beams = counted(index.as_ref(), BEAMS16, &rays, 64);
            let packets = counted(index.as_ref(), TraceMode::Packets(16), &rays, 64);
            if beams.box_tests >= packets.box_tests {
                let s = &scene.name;
                wrong.push(format!(
                    "{name} on {s}: beams16 {beams:?}, packets16 {packets:?}"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

/// Only `bvh`, `bvh4` and `bvh8` are traced in the beam modes; the suite gives them
/// `INDEX+beams16` rows (batch family, verified) and no other index one.
#[test]
fn only_the_box_trees_get_beam_rows() {
    use accelbench::harness::suite::run_suite;
    use accelbench::index::ModeFamily;
    let scene = generators::generate("icosphere", 2000, 1).unwrap();
    let geom = scene.geometry();
    for name in index_names().into_iter().filter(|n| !is_peer(n)) {
        let spec = IndexSpec::named(name);
        let index = build_index(&spec, &geom, TriangleKernelKind::Exact).unwrap();
        assert_eq!(index.traces_in(BEAMS16), TREES.contains(&name), "{name}");
    }
    assert_eq!(TraceMode::parse("beams16"), Ok(BEAMS16));
    assert_eq!(BEAMS16.label(), "beams16");
    assert_eq!(BEAMS16.family(), ModeFamily::Batch);
    let mut cfg = crate::suite::config(&["bvh", "bvh8", "kdtree"]);
    cfg.sets = vec![RaySet::Primary, RaySet::Shadow, RaySet::Incoherent];
    cfg.threads = vec![1];
    cfg.modes = vec![TraceMode::Single, BEAMS16];
    let res = run_suite(&[scene], &cfg, &indicatif::ProgressBar::hidden()).unwrap();
    assert_eq!(res.mismatch_total, 0);
    let labels: Vec<(&str, &str)> = res
        .rows
        .iter()
        .map(|r| (r.index.as_str(), r.ray_set.as_str()))
        .collect();
    for set in ["primary", "shadow"] {
        for index in ["bvh+beams16", "bvh8+beams16"] {
            assert!(labels.contains(&(index, set)), "no {index} on {set}");
        }
    }
    assert!(!labels.iter().any(|(i, _)| i.starts_with("kdtree+")));
    assert!(!labels.contains(&("bvh+beams16", "incoherent")));
}
