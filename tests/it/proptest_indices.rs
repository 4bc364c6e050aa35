//! Property test: on random small scenes (triangles, spheres, mixed; with zero-area,
//! duplicate, opposite-winding and axis-aligned triangles) and random rays (free, axis-parallel
//! with +0.0/-0.0, aimed exactly at vertices, starting on vertices)
//! and intervals (including `t_min == t_max`), with any of the triangle kernels, every
//! registered index returns brute force's hits bit for bit.
//!
//! The default is 32 cases so CI stays fast; run many more locally with
//! `PROPTEST_CASES=10000 cargo test --release --test proptest_indices`.
//! Peers (`accelbench::index::is_peer`) are reported, not asserted.

use accelbench::geometry::{Ray, Sphere, Triangle, TriangleKernelKind};
use accelbench::harness::verify::verify_against_brute;
use accelbench::index::{IndexSpec, index_names, is_peer};
use accelbench::scene::SceneGeometry;
use glam::{Vec3, Vec3A};
use proptest::prelude::*;
use std::sync::Arc;

fn config() -> ProptestConfig {
    crate::common::proptest_config(32)
}

/// Coordinates: a few shared grid values (so vertices, planes and cell boundaries coincide)
/// or any value in `[-2, 2]`.
fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![(-4i32..=4).prop_map(|i| i as f32 * 0.25), -2.0f32..2.0]
}

fn point() -> impl Strategy<Value = Vec3A> {
    (coord(), coord(), coord()).prop_map(|(x, y, z)| Vec3A::new(x, y, z))
}

/// A triangle: general, zero-area (repeated or collinear corner), or axis-aligned.
fn triangle() -> impl Strategy<Value = Triangle> {
    (point(), point(), point(), 0u8..5).prop_map(|(a, b, c, kind)| match kind {
        0 => Triangle::new(a, b, b),
        1 => Triangle::new(a, b, (a + b) * 0.5),
        2 => Triangle::new(a, Vec3A::new(b.x, a.y, b.z), Vec3A::new(c.x, a.y, c.z)),
        _ => Triangle::new(a, b, c),
    })
}

fn sphere() -> impl Strategy<Value = Sphere> {
    (point(), 0.01f32..1.0).prop_map(|(c, r)| Sphere::new(c, r))
}

/// A scene of up to 12 triangles (some duplicated, some with the opposite winding) and up to
/// 4 spheres, never empty.
fn scene() -> impl Strategy<Value = (Vec<Triangle>, Vec<Sphere>)> {
    (
        prop::collection::vec(triangle(), 0..12),
        prop::collection::vec(sphere(), 0..4),
        0u8..3,
        sphere(),
    )
        .prop_map(|(mut tris, mut spheres, dup, fallback)| {
            if let Some(&t) = tris.first() {
                match dup {
                    0 => tris.push(t),
                    1 => tris.push(Triangle::new(t.v[0], t.v[2], t.v[1])),
                    _ => {}
                }
            }
            if tris.is_empty() && spheres.is_empty() {
                spheres.push(fallback);
            }
            (tris, spheres)
        })
}

/// How a ray is made; resolved against the scene (vertices) in [`make_ray`].
#[derive(Debug, Clone)]
enum RaySpec {
    Free(Vec3A, Vec3A),
    /// Axis, sign of the axis component, and the signs of the two zero components.
    Axis(Vec3A, usize, bool, bool, bool),
    AtVertex(Vec3A, usize),
    FromVertex(usize, Vec3A),
}

fn ray_spec() -> impl Strategy<Value = RaySpec> {
    prop_oneof![
        (point(), point()).prop_map(|(o, d)| RaySpec::Free(o, d)),
        (
            point(),
            0usize..3,
            any::<bool>(),
            any::<bool>(),
            any::<bool>()
        )
            .prop_map(|(o, a, s, z1, z2)| RaySpec::Axis(o, a, s, z1, z2)),
        (point(), any::<usize>()).prop_map(|(o, v)| RaySpec::AtVertex(o, v)),
        (any::<usize>(), point()).prop_map(|(v, d)| RaySpec::FromVertex(v, d)),
    ]
}

/// The ray interval: `[0, inf]`, empty (`t_min == t_max`), or any closed range.
fn interval() -> impl Strategy<Value = (f32, f32)> {
    prop_oneof![
        Just((0.0, f32::INFINITY)),
        (0.0f32..3.0).prop_map(|t| (t, t)),
        (0.0f32..3.0, 0.0f32..6.0).prop_map(|(a, b)| (a.min(b), a.max(b))),
    ]
}

fn make_ray(spec: &RaySpec, (t_min, t_max): (f32, f32), verts: &[Vec3A]) -> Option<Ray> {
    let vertex = |i: usize| verts.get(i % verts.len().max(1)).copied();
    let (o, d) = match *spec {
        RaySpec::Free(o, d) => (o, d),
        RaySpec::Axis(o, axis, neg, z1, z2) => {
            let mut d = [0.0f32; 3];
            d[axis] = if neg { -1.0 } else { 1.0 };
            d[(axis + 1) % 3] = if z1 { -0.0 } else { 0.0 };
            d[(axis + 2) % 3] = if z2 { -0.0 } else { 0.0 };
            (o - Vec3A::from(d) * 3.0, Vec3A::from(d))
        }
        RaySpec::AtVertex(o, i) => {
            let v = vertex(i)?;
            (o * 2.0, v - o * 2.0)
        }
        RaySpec::FromVertex(i, d) => (vertex(i)?, d),
    };
    Ray::new(Vec3::from(o), Vec3::from(d), t_min, t_max).ok()
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn every_index_matches_brute_force(
        (tris, spheres) in scene(),
        specs in prop::collection::vec((ray_spec(), interval()), 1..64),
        kernel in 0..TriangleKernelKind::ALL.len(),
    ) {
        let kernel = TriangleKernelKind::ALL[kernel];
        let verts: Vec<Vec3A> = tris.iter().flat_map(|t| t.v).collect();
        let rays: Vec<Ray> = specs
            .iter()
            .filter_map(|(s, i)| make_ray(s, *i, &verts))
            .collect();
        let geom = SceneGeometry {
            triangles: Arc::from(tris.as_slice()),
            spheres: Arc::from(spheres.as_slice()),
            ..SceneGeometry::default()
        };
        // Every registered index, and the BVHs with spatial splits (primitives in several
        // leaves, cut at one-primitive leaves so the small scenes split too).
        let spatial = ["bvh", "bvh4", "bvh8"]
            .map(|n| format!("{n}:spatial_splits=true,leaf_size=1,split_budget=8"));
        let names = index_names().into_iter().map(String::from).chain(spatial);
        for name in names {
            let spec: IndexSpec = name
                .parse()
                .map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
            let m = match verify_against_brute(&spec, &geom, kernel, &rays) {
                Ok(m) => m,
                // Embree and tinybvh take triangles only: a scene with spheres skips them.
                Err(e) if is_peer(&name) => {
                    eprintln!("peer {name}: {e}");
                    continue;
                }
                Err(e) => return Err(TestCaseError::fail(format!("{name} ({kernel}): {e}"))),
            };
            if is_peer(&name) {
                if !m.is_empty() {
                    eprintln!("peer {name}: {} of {} rays mismatch", m.len(), rays.len());
                }
                continue;
            }
            prop_assert!(m.is_empty(), "{name} ({kernel}): {}", m[0]);
        }
    }
}
