//! Verdicts a reader can trust: a contender with wrong hits never wins (terminal, `summary.md`,
//! `index.html`), the `single` mode of the wide BVHs walks one ray at a time while `stream`
//! interleaves, and every mode returns brute force's hits.

use crate::common;
use common::call_log::CallLog;
use common::drop_one::NoParams;

use accelbench::geometry::triangle::Exact;
use accelbench::geometry::{Ray, TriangleKernelKind};
use accelbench::harness::suite::{IndexBuilder, Shard, SuiteConfig, SuiteResult, run_suite_with};
use accelbench::harness::workload::{RaySet, SetSizes};
use accelbench::index::{
    BatchIndex, BuildError, Bvh4, Bvh8, HitQuery, Index, IndexInfo, IndexSpec, Stats, TraceIndex,
    TraceMode, build_index, build_index_on,
};
use accelbench::rays::incoherent_rays;
use accelbench::report::suite_report::{RunMeta, write_suite_report};
use accelbench::report::verdict::{verdict_text, verdicts};
use accelbench::scene::{Geometry, Scene, Triangles, generators};
use indicatif::ProgressBar;
use scraper::{Html, Selector};
use std::sync::Arc;

/// The name the blind contender runs under: a registered peer, so the suite classifies its
/// disagreements instead of failing the run.
const BLIND: &str = "obvhs-cwbvh";

/// A contender that answers "miss" at once for every ray: faster than any real index, and wrong
/// on every ray that hits.
struct Blind;

impl Index for Blind {
    type Params = NoParams;
    fn build<G: Geometry>(_: &G, _: &NoParams) -> Result<Self, BuildError> {
        Ok(Blind)
    }
    fn query<Q: HitQuery, G: Geometry, S: Stats>(&self, _: &G, r: &Ray, _: &mut S) -> Q::Answer {
        Q::answer(Q::start(r))
    }
    fn info(&self) -> IndexInfo {
        IndexInfo::default()
    }
}

impl BatchIndex for Blind {}

fn config(indices: &[&str], modes: Vec<TraceMode>) -> SuiteConfig {
    SuiteConfig {
        indices: indices.iter().map(|n| IndexSpec::named(n)).collect(),
        sets: vec![RaySet::Primary],
        threads: vec![1],
        sizes: SetSizes {
            primary_side: 64,
            incoherent: 500,
            ao_fraction: 0.05,
        },
        repeats: 3,
        kernel: TriangleKernelKind::Exact,
        verify_budget: u64::MAX,
        brute_timing_budget: u64::MAX,
        timed: true,
        shard: Shard::WHOLE,
        modes,
    }
}

fn run(scene: Scene, cfg: &SuiteConfig, build: IndexBuilder) -> SuiteResult {
    run_suite_with(&[scene], cfg, &ProgressBar::hidden(), build, &mut |_, _| {}).unwrap()
}

#[test]
fn a_wrong_contender_never_wins() {
    let scene = generators::generate("icosphere", 2000, 1).unwrap();
    let cfg = config(&["bvh", "grid", BLIND], vec![TraceMode::Single]);
    let build = |spec: &IndexSpec, g: &accelbench::scene::SceneGeometry| {
        if spec.name == BLIND {
            let geom = Triangles::<Exact>::new(g.triangles.clone());
            let b = build_index_on::<Blind, _>(BLIND, geom, NoParams {})?;
            Ok(Box::new(b) as Box<dyn TraceIndex>)
        } else {
            build_index(spec, g, TriangleKernelKind::Exact)
        }
    };
    let res = run(scene, &cfg, &build);
    let blind = res.rows.iter().find(|r| r.index == BLIND).unwrap();
    let wrong = blind.peer_wrong.unwrap();
    assert!(wrong > 0, "{blind:?}");
    assert_eq!(
        res.mismatch_total, 0,
        "a peer's wrong hits do not fail the run"
    );
    let fastest = res
        .rows
        .iter()
        .max_by(|a, b| a.mrays_per_s.total_cmp(&b.mrays_per_s))
        .unwrap();
    assert_eq!(
        fastest.index, BLIND,
        "the test needs the wrong one to be fastest"
    );

    // The terminal: the winner is a correct index; the blind one is named as wrong.
    let v = verdicts(&res.rows);
    assert_eq!(v.len(), 1);
    let winner = v[0].winner().unwrap();
    assert_ne!(winner.label, BLIND);
    let text = verdict_text(&v, 4);
    let line = text.lines().find(|l| l.starts_with("icosphere")).unwrap();
    let cell = format!("{BLIND} {:.1} wrong {wrong}", blind.mrays_per_s);
    assert!(line.contains(&cell), "{text}");
    // The fastest column comes before the others: the winner is named before the blind one.
    assert!(line.find(&winner.label) < line.find(BLIND), "{text}");

    // summary.md and index.html.
    let dir = tempfile::tempdir().unwrap();
    let meta = RunMeta::collect("t".into(), "test".into(), &cfg, vec!["icosphere".into()]);
    write_suite_report(dir.path(), &meta, &res, Vec::new()).unwrap();
    let md = std::fs::read_to_string(dir.path().join("summary.md")).unwrap();
    // The set's table (the build table lists the index too): the blind row is marked wrong and
    // the winner is the 1.00 of its race.
    let rows_of = |label: &str| {
        let start = format!("| {label} |");
        md.lines()
            .filter(move |l| l.starts_with(&start))
            .collect::<Vec<_>>()
    };
    let marked = format!("| {:.1} wrong {wrong} |", blind.mrays_per_s);
    assert!(rows_of(BLIND).iter().any(|l| l.contains(&marked)), "{md}");
    assert!(
        rows_of(&winner.label)
            .iter()
            .any(|l| l.contains("| 1.00 |")),
        "{md}"
    );
    let html = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    let page = Html::parse_document(&html);
    let sel = |s: &str| Selector::parse(s).unwrap();
    let tr = page
        .select(&sel("table#verdict tr[data-scene]"))
        .next()
        .unwrap();
    assert_eq!(tr.value().attr("data-fastest"), Some(winner.label.as_str()));
    let td = tr
        .select(&sel(&format!("td.wrong[data-index=\"{BLIND}\"]")))
        .next()
        .expect("the wrong contender's cell is marked wrong");
    assert_eq!(
        td.value().attr("data-wrong"),
        Some(wrong.to_string().as_str())
    );
    assert_eq!(
        td.text().collect::<String>(),
        cell.trim_start_matches(BLIND).trim()
    );
    assert!(
        tr.select(&sel(&format!("td.ratio[data-index=\"{BLIND}\"]")))
            .next()
            .is_none()
    );
}

/// The interval contains the median, and two rows of the same index on the same rays (one
/// measurement under a second label, a hair slower) are a tie, not a ranking.
#[test]
fn the_same_index_on_the_same_rays_is_a_tie() {
    let scene = generators::generate("icosphere", 500, 1).unwrap();
    let cfg = config(&["bvh"], vec![TraceMode::Single]);
    let res = run(scene, &cfg, &|s, g| {
        build_index(s, g, TriangleKernelKind::Exact)
    });
    let mut rows = res.rows.clone();
    let mut twin = rows[0].clone();
    twin.index = "bvh+last-hit".into();
    twin.mode = "last-hit".into();
    twin.mrays_per_s *= 0.999;
    rows.push(twin);
    let r = &rows[0];
    assert!(
        r.mrays_ci_low <= r.mrays_per_s && r.mrays_per_s <= r.mrays_ci_high,
        "{r:?}"
    );
    let v = verdicts(&rows);
    assert_eq!(v.len(), 1);
    assert_eq!(v[0].winner().unwrap().label, "bvh");
    assert!(v[0].tied("bvh+last-hit"));
    assert!(v[0].cell("bvh+last-hit").unwrap().starts_with("≈ "));
}

/// Whether the kernel calls of one pass came ray after ray (never back to an earlier ray).
fn one_ray_at_a_time(calls: &[usize]) -> bool {
    calls.windows(2).all(|w| w[0] <= w[1])
}

fn kernel_call_order<I: BatchIndex>(mode: TraceMode) -> Vec<usize> {
    let scene = generators::generate("soup", 3000, 4).unwrap();
    let rays = incoherent_rays(&scene.ray_set_bounds(), 64, 3);
    // Each call logs its ray's position in `rays`, found by its origin's bits.
    let origins: Arc<Vec<[u32; 3]>> = Arc::new(
        rays.iter()
            .map(|r| r.origin.to_array().map(f32::to_bits))
            .collect(),
    );
    let geom = CallLog {
        inner: Triangles::<Exact>::new(scene.triangles.clone().into()),
        note: move |_, ray: &Ray| {
            let o = ray.origin.to_array().map(f32::to_bits);
            origins.iter().position(|x| *x == o).unwrap()
        },
        calls: Arc::default(),
    };
    let calls = geom.calls.clone();
    let index = build_index_on::<I, _>("wide", geom, Default::default()).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut out = vec![None; rays.len()];
    calls.lock().unwrap().clear();
    pool.install(|| index.closest_hits_in(mode, &rays, &mut out, None));
    let c = calls.lock().unwrap().clone();
    assert!(c.len() > 64, "the rays test primitives");
    c
}

/// `single` rows of `bvh4`/`bvh8` walk one ray at a time; their `stream` rows interleave (the
/// positive control: the same check fails on the stream pass).
#[test]
fn single_mode_of_the_wide_bvhs_walks_one_ray_at_a_time() {
    assert!(one_ray_at_a_time(&kernel_call_order::<Bvh8>(
        TraceMode::Single
    )));
    assert!(one_ray_at_a_time(&kernel_call_order::<Bvh4>(
        TraceMode::Single
    )));
    assert!(!one_ray_at_a_time(&kernel_call_order::<Bvh8>(
        TraceMode::Stream
    )));
    assert!(!one_ray_at_a_time(&kernel_call_order::<Bvh4>(
        TraceMode::Stream
    )));
}

/// Every index of ours returns brute force's hits in `stream` mode (single, last-hit and packets
/// are checked in `agreement`, `last_hit` and `packets`).
#[test]
fn stream_mode_returns_brute_force_hits() {
    common::assert_mode_agrees(TraceMode::Stream);
}
