//! What the benches share: the bunny from ../shared/meshes when it is there, else a generated
//! scene of the same size, and the protocol's ray sets for it.
#![allow(dead_code)]

use accelbench::geometry::Ray;
use accelbench::rays::{incoherent_rays, primary_rays};
use accelbench::scene::{Scene, generators};
use std::path::Path;

/// The Stanford bunny (69,451 triangles), or a 70,000-triangle icosphere when ../shared is absent.
pub fn bench_scene() -> Scene {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/meshes/stanford_bunny.obj");
    match Scene::load_obj(&p) {
        Ok(s) => s,
        Err(_) => {
            eprintln!(
                "{} not found: benchmarking a generated icosphere",
                p.display()
            );
            generators::generate("icosphere", 70_000, 1).expect("built-in generator")
        }
    }
}

/// The protocol's primary (1024 x 1024) and incoherent (1,048,576) sets for the scene.
pub fn protocol_sets(scene: &Scene) -> [(&'static str, Vec<Ray>); 2] {
    let b = scene.ray_set_bounds();
    [
        (
            "primary",
            primary_rays(&b, 1024, 1024).expect("valid camera"),
        ),
        ("incoherent", incoherent_rays(&b, 1 << 20, 42)),
    ]
}

/// A one-thread rayon pool (the benches' figures are per thread).
pub fn one_thread() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool")
}

/// A criterion group of ten samples counting `elements` per iteration, with the given
/// warm-up and measurement times (seconds): the long ray sets and builds need few samples.
pub fn group<'a>(
    c: &'a mut criterion::Criterion,
    name: String,
    elements: usize,
    warm_up: f64,
    measure: f64,
) -> criterion::BenchmarkGroup<'a, criterion::measurement::WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(criterion::Throughput::Elements(elements as u64));
    g.sample_size(10);
    g.warm_up_time(std::time::Duration::from_secs_f64(warm_up));
    g.measurement_time(std::time::Duration::from_secs_f64(measure));
    g
}
