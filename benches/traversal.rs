//! Closest-hit traversal of every registered index (brute force excepted: it would take hours)
//! on the bunny, primary and incoherent protocol sets, one thread; throughput in rays.

mod common;

use accelbench::geometry::TriangleKernelKind;
use accelbench::index::{IndexSpec, build_index, index_names};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn traversal(c: &mut Criterion) {
    let scene = common::bench_scene();
    let geom = scene.geometry();
    let pool = common::one_thread();
    for (set, rays) in common::protocol_sets(&scene) {
        let name = format!("traversal/{}/{set}", scene.name);
        let mut g = common::group(c, name, rays.len(), 1.0, 5.0);
        for name in index_names().into_iter().filter(|n| *n != "brute") {
            let index = pool
                .install(|| {
                    build_index(
                        &IndexSpec::named(name),
                        &geom,
                        TriangleKernelKind::Watertight,
                    )
                })
                .expect("index builds");
            let mut out = vec![None; rays.len()];
            g.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    pool.install(|| index.closest_hits(black_box(&rays), &mut out));
                    black_box(&out);
                })
            });
        }
        g.finish();
    }
}

criterion_group!(benches, traversal);
criterion_main!(benches);
