//! Every ray–primitive kernel on the same 4,096 ray–primitive pairs (about half of them hits);
//! throughput in kernel calls.

use accelbench::geometry::sphere::{intersect_algebraic, intersect_geometric};
use accelbench::geometry::{
    Aabb, Ray, Sphere, Triangle, TriangleKernelKind, intersect_box, intersect_plane,
};
use accelbench::rays::SplitMix64;
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec3, Vec3A};
use std::hint::black_box;

const PAIRS: usize = 4096;

/// Rays from random points toward random points near the unit triangle/sphere, so about half hit.
fn rays(rng: &mut SplitMix64) -> Vec<Ray> {
    let mut u = || rng.next_unit() as f32;
    (0..PAIRS)
        .map(|_| {
            let o = Vec3::new(u() * 4.0 - 2.0, u() * 4.0 - 2.0, -3.0);
            let target = Vec3::new(u() * 1.6 - 0.3, u() * 1.6 - 0.3, u() * 0.2);
            Ray::infinite(o, target - o).expect("finite, non-zero")
        })
        .collect()
}

fn kernels(c: &mut Criterion) {
    let mut rng = SplitMix64::new(5);
    let rays = rays(&mut rng);
    let tris: Vec<Triangle> = (0..PAIRS)
        .map(|i| {
            let j = i as f32 * 1e-4;
            Triangle::from_corners([j, 0.0, 0.0], [1.0, j, 0.1], [0.0, 1.0, j])
        })
        .collect();
    let spheres: Vec<Sphere> = (0..PAIRS)
        .map(|i| Sphere::new(Vec3A::new(0.5, 0.5, i as f32 * 1e-4), 0.6))
        .collect();
    let mut g = c.benchmark_group("kernels");
    g.throughput(Throughput::Elements(PAIRS as u64));
    for k in TriangleKernelKind::ALL {
        g.bench_function(BenchmarkId::new("triangle", k.name()), |b| {
            b.iter(|| {
                let mut n = 0u32;
                for (r, t) in rays.iter().zip(&tris) {
                    n += k.intersect(black_box(t), r, r.t_max).is_some() as u32;
                }
                n
            })
        });
    }
    type SphereKernel = fn(&Sphere, &Ray, f32) -> Option<f32>;
    for (name, k) in [
        ("algebraic", intersect_algebraic as SphereKernel),
        ("geometric", intersect_geometric),
    ] {
        g.bench_function(BenchmarkId::new("sphere", name), |b| {
            b.iter(|| {
                let mut n = 0u32;
                for (r, s) in rays.iter().zip(&spheres) {
                    n += k(black_box(s), r, r.t_max).is_some() as u32;
                }
                n
            })
        });
    }
    let boxes: Vec<Aabb> = spheres.iter().map(|s| s.bounds()).collect();
    g.bench_function(BenchmarkId::new("box", "slabs"), |b| {
        b.iter(|| {
            let mut n = 0u32;
            for (r, bx) in rays.iter().zip(&boxes) {
                n += intersect_box(black_box(bx), r, r.t_max).is_some() as u32;
            }
            n
        })
    });
    g.bench_function(BenchmarkId::new("box", "conservative-slab-test"), |b| {
        b.iter(|| {
            let mut n = 0u32;
            for (r, bx) in rays.iter().zip(&boxes) {
                n += black_box(bx).ray_interval(r, r.t_min, r.t_max).is_some() as u32;
            }
            n
        })
    });
    g.bench_function(BenchmarkId::new("plane", "plane"), |b| {
        b.iter(|| {
            let mut n = 0u32;
            for r in &rays {
                n += intersect_plane(black_box(Vec3A::Z), 0.05, r, r.t_max).is_some() as u32;
            }
            n
        })
    });
    g.finish();
}

/// The shape kernels of issue 10 on the same rays, one shape of each kind over the rays' target
/// region.
fn shape_kernels(c: &mut Criterion) {
    use accelbench::geometry::shapes::{Cone, Cylinder, Ellipsoid, Obb, Polygon};
    use accelbench::geometry::shapes::{cone, cylinder, ellipsoid, obb, polygon};
    use glam::Mat3A;
    let rays = rays(&mut SplitMix64::new(5));
    let center = Vec3A::new(0.5, 0.5, 0.1);
    let tilt = Mat3A::from_axis_angle(Vec3::new(1.0, 0.5, 0.2).normalize(), 0.4);
    let ring = |k: usize, r: &dyn Fn(usize) -> f32| -> Vec<Vec3A> {
        (0..k)
            .map(|j| {
                let a = std::f32::consts::TAU * j as f32 / k as f32;
                center + tilt * Vec3A::new(a.cos(), a.sin(), 0.0) * r(j)
            })
            .collect()
    };
    let bx = Obb::new(center, Vec3A::new(0.6, 0.5, 0.3), tilt).unwrap();
    let convex = Polygon::convex(ring(6, &|_| 0.7)).unwrap();
    let star = Polygon::new(ring(10, &|j| if j % 2 == 0 { 0.8 } else { 0.35 })).unwrap();
    let cyl = Cylinder::new(center - tilt.z_axis * 0.4, center + tilt.z_axis * 0.4, 0.6).unwrap();
    let con = Cone::new(center - tilt.z_axis * 0.3, center + tilt.z_axis * 0.5, 0.7).unwrap();
    let ell = Ellipsoid::new(center, Vec3A::new(0.7, 0.5, 0.3), tilt).unwrap();
    let mut g = c.benchmark_group("kernels");
    g.throughput(Throughput::Elements(PAIRS as u64));
    macro_rules! bench {
        ($name:expr, $kernel:path, $shape:expr) => {
            g.bench_function(BenchmarkId::new("shape", $name), |b| {
                b.iter(|| {
                    let mut n = 0u32;
                    for r in &rays {
                        n += $kernel(black_box($shape), r, r.t_max).is_some() as u32;
                    }
                    n
                })
            });
        };
    }
    bench!("box-slabs", obb::intersect_slabs, &bx);
    bench!("box-front-planes", obb::intersect_front_planes, &bx);
    bench!("convex-polygon", polygon::intersect_convex, &convex);
    bench!("concave-polygon", polygon::intersect_concave, &star);
    bench!("cylinder", cylinder::intersect, &cyl);
    bench!("cone", cone::intersect, &con);
    bench!("ellipsoid", ellipsoid::intersect, &ell);
    g.finish();
}

criterion_group!(benches, kernels, shape_kernels);
criterion_main!(benches);
