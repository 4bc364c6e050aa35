//! Build time of every registered index on the bunny, one thread (and all threads for the
//! indices that build in parallel); throughput in primitives.

mod common;

use accelbench::geometry::TriangleKernelKind;
use accelbench::index::{IndexSpec, build_index, index_names};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn build(c: &mut Criterion) {
    let scene = common::bench_scene();
    let geom = scene.geometry();
    let all = rayon::current_num_threads();
    for (threads, pool) in [
        (1, common::one_thread()),
        (
            all,
            rayon::ThreadPoolBuilder::new()
                .num_threads(all)
                .build()
                .expect("pool"),
        ),
    ] {
        let name = format!("build/{}/{threads}t", scene.name);
        let mut g = common::group(c, name, scene.len(), 0.5, 3.0);
        for name in index_names().into_iter().filter(|n| *n != "brute") {
            let spec = IndexSpec::named(name);
            g.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    pool.install(|| {
                        build_index(black_box(&spec), &geom, TriangleKernelKind::Watertight)
                    })
                    .expect("index builds")
                })
            });
        }
        g.finish();
    }
}

criterion_group!(benches, build);
criterion_main!(benches);
