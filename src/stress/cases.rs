//! The stress cases: scenes and rays built to hit the corner cases of every index (signed
//! zeros, cell boundaries, split planes, flat and single-primitive scenes, degenerate and
//! duplicate triangles, extreme scales, giant primitives, empty intervals, origins inside
//! primitives). Each case is run on every registered index against brute force.

use crate::geometry::{Aabb, Ray, Sphere, Triangle, TriangleKernelKind};
use crate::index::{IndexSpec, build_index};
use crate::rays::{SplitMix64, incoherent_rays, primary_rays};
use crate::scene::{Scene, SceneGeometry, generators};
use glam::{Vec3, Vec3A};

/// One stress case: a scene, the triangle kernel, and the rays to shoot at it.
#[derive(Debug, Clone)]
pub struct Case {
    pub name: &'static str,
    pub scene: SceneGeometry,
    pub kernel: TriangleKernelKind,
    pub rays: Vec<Ray>,
}

fn scene(name: &str, n: usize) -> Scene {
    generators::generate(name, n, 3).expect("a known generator")
}

fn case(name: &'static str, s: &Scene, rays: Vec<Ray>) -> Case {
    Case {
        name,
        scene: s.geometry(),
        kernel: TriangleKernelKind::default(),
        rays,
    }
}

/// The same case with another triangle kernel (the hit contract holds for every kernel).
fn with_kernel(c: &Case, name: &'static str, kernel: TriangleKernelKind) -> Case {
    Case {
        name,
        kernel,
        ..c.clone()
    }
}

/// The 24 axis-parallel directions: `+-1` on one axis, `+0.0` or `-0.0` on the two others.
pub fn axis_directions() -> Vec<Vec3> {
    let mut v = Vec::new();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            for z1 in [0.0f32, -0.0] {
                for z2 in [0.0f32, -0.0] {
                    let mut d = [0.0f32; 3];
                    d[axis] = sign;
                    d[(axis + 1) % 3] = z1;
                    d[(axis + 2) % 3] = z2;
                    v.push(Vec3::from(d));
                }
            }
        }
    }
    v
}

/// `min + e * (i / steps)` per axis for `i` in `0..=steps`: the corners of every cell of a
/// grid with `steps` cells per axis (and the faces of an octree or the midpoint kd splits when
/// `steps` is a power of two), computed in `f32` as a builder would.
fn dyadic(b: &Aabb, i: [u32; 3], steps: u32) -> Vec3 {
    let e = b.extent();
    Vec3::from(b.min + e * Vec3A::new(i[0] as f32, i[1] as f32, i[2] as f32) / steps as f32)
}

/// A random point `(i, steps)` of [`dyadic`]: `steps = 2^1 .. 2^max_level` cells per axis,
/// `i` uniform in `0..=steps` per axis.
fn random_dyadic(rng: &mut SplitMix64, max_level: u64) -> ([u32; 3], u32) {
    let steps = 1 << (1 + rng.next_u64() % max_level);
    let i = [0; 3].map(|_| (rng.next_u64() % (steps as u64 + 1)) as u32);
    (i, steps)
}

fn random_dir(rng: &mut SplitMix64) -> Vec3 {
    let w = 1.0 - 2.0 * rng.next_unit();
    let phi = std::f64::consts::TAU * rng.next_unit();
    let s = (1.0 - w * w).max(0.0).sqrt();
    Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, w as f32)
}

/// Rays from `batch` (which appends a few, seeing those made so far) until there are `n` or
/// more.
fn at_least(n: usize, mut batch: impl FnMut(&mut Vec<Ray>)) -> Vec<Ray> {
    let mut rays = Vec::new();
    while rays.len() < n {
        batch(&mut rays);
    }
    rays
}

fn ray(o: Vec3, d: Vec3) -> Option<Ray> {
    Ray::infinite(o, d).ok()
}

/// Axis-parallel rays with signed zeros from a lattice of origins over (and around) the bounds.
fn axis_parallel(s: &Scene, n: usize) -> Vec<Ray> {
    let b = s.bounds();
    let grown = Aabb::new(b.min - b.extent() * 0.1, b.max + b.extent() * 0.1);
    let dirs = axis_directions();
    let mut rng = SplitMix64::new(5);
    at_least(n, |rays| {
        let (i, steps) = random_dyadic(&mut rng, 5);
        // A third of the batches from the bounds themselves.
        let lattice = if rays.len().is_multiple_of(3) {
            &b
        } else {
            &grown
        };
        let o = dyadic(lattice, i, steps);
        rays.extend(dirs.iter().filter_map(|&d| ray(o, d)));
    })
}

/// Rays aimed at every vertex and edge midpoint from outside, from the centre, and from other
/// vertices (origins on the surface).
fn at_vertices_and_edges(tris: &[Triangle], b: &Aabb, n: usize) -> Vec<Ray> {
    let c = Vec3::from(b.center());
    let eye = c + Vec3::from(b.extent()) * Vec3::new(1.3, 0.9, 1.7);
    let mut rays = Vec::new();
    let step = (tris.len() * 6 / n.max(1)).max(1);
    for (i, t) in tris.iter().enumerate().step_by(step.div_ceil(6).max(1)) {
        for k in 0..3 {
            let v = Vec3::from(t.v[k]);
            let m = Vec3::from((t.v[k] + t.v[(k + 1) % 3]) * 0.5);
            let other = Vec3::from(tris[(i * 7 + 3) % tris.len()].v[k]);
            for (o, target) in [(eye, v), (c, v), (eye, m), (c, m), (other, v), (v, m)] {
                rays.extend(ray(o, target - o));
            }
        }
    }
    rays
}

/// Origins exactly on cell corners, faces and split planes (dyadic fractions of the bounds),
/// with random and axis-parallel directions.
fn cell_boundaries(s: &Scene, n: usize) -> Vec<Ray> {
    let b = s.bounds();
    let dirs = axis_directions();
    let mut rng = SplitMix64::new(9);
    at_least(n, |rays| {
        let (i, steps) = random_dyadic(&mut rng, 7);
        let o = dyadic(&b, i, steps);
        rays.extend(ray(o, random_dir(&mut rng)));
        rays.extend(ray(o, dirs[(rng.next_u64() % 24) as usize]));
    })
}

/// Rays lying in a split plane: origin on `axis = min + e * i / 2^k`, direction zero (`+0.0`
/// or `-0.0`) on that axis.
fn in_split_planes(s: &Scene, n: usize) -> Vec<Ray> {
    let b = s.bounds();
    let mut rng = SplitMix64::new(13);
    at_least(n, |rays| {
        let axis = (rng.next_u64() % 3) as usize;
        let (mut i, steps) = random_dyadic(&mut rng, 6);
        i[axis] = (rng.next_u64() % (steps as u64 + 1)) as u32;
        let mut o = dyadic(&b, i, steps);
        // Start outside the bounds on the other axes half of the time.
        if rng.next_u64().is_multiple_of(2) {
            o[(axis + 1) % 3] = b.min[(axis + 1) % 3] - b.extent()[(axis + 1) % 3];
        }
        let mut d = random_dir(&mut rng);
        d[axis] = if rng.next_u64().is_multiple_of(2) {
            0.0
        } else {
            -0.0
        };
        rays.extend(ray(o, d));
    })
}

/// Protocol rays (primary and incoherent) of the scene's bounds.
fn protocol(s: &Scene, n: usize) -> Vec<Ray> {
    let b = s.bounds();
    let side = ((n as f64 / 2.0).sqrt() as u32).max(2);
    let mut rays = primary_rays(&b, side, side).unwrap_or_default();
    rays.extend(incoherent_rays(&b, n / 2, 42));
    rays
}

fn scaled(s: &Scene, k: f32) -> Scene {
    Scene {
        name: s.name.clone(),
        triangles: s
            .triangles
            .iter()
            .map(|t| Triangle::new(t.v[0] * k, t.v[1] * k, t.v[2] * k))
            .collect(),
        spheres: s
            .spheres
            .iter()
            .map(|p| Sphere::new(p.center * k, p.radius * k))
            .collect(),
        ..Scene::default()
    }
}

/// Rays with `t_min == t_max`: exactly at brute force's hit `t`, and at an arbitrary value; and
/// intervals that start or end exactly at the hit.
fn empty_intervals(s: &Scene, n: usize) -> Vec<Ray> {
    let base = protocol(s, n / 4);
    let brute = build_index(
        &IndexSpec::named("brute"),
        &s.geometry(),
        TriangleKernelKind::Watertight,
    )
    .expect("brute force builds on a non-empty scene");
    let mut hits = vec![None; base.len()];
    brute.closest_hits(&base, &mut hits);
    let mut rays = Vec::new();
    for (r, h) in base.iter().zip(&hits) {
        let t = h.map_or(1.0, |h| h.t);
        for (lo, hi) in [(t, t), (0.5, 0.5), (t, f32::INFINITY), (0.0, t)] {
            rays.extend(r.with_interval(lo, hi).ok());
        }
    }
    rays
}

/// Origins at sphere centres, inside spheres, on triangle centroids and at triangle vertices.
fn inside_primitives(s: &Scene, n: usize) -> Vec<Ray> {
    let mut rng = SplitMix64::new(17);
    let mut rays = Vec::new();
    let mut origins: Vec<Vec3> = Vec::new();
    for sp in &s.spheres {
        origins.push(Vec3::from(sp.center));
        origins.push(Vec3::from(
            sp.center + Vec3A::from(random_dir(&mut rng)) * sp.radius * 0.9,
        ));
    }
    for t in &s.triangles {
        origins.push(Vec3::from((t.v[0] + t.v[1] + t.v[2]) / 3.0));
        origins.push(Vec3::from(t.v[0]));
    }
    let mut i = 0;
    while rays.len() < n && !origins.is_empty() {
        let o = origins[i % origins.len()];
        i += 1;
        rays.extend(ray(o, random_dir(&mut rng)));
    }
    rays
}

/// An icosphere with every kind of duplicate and degenerate triangle added: opposite-winding
/// copies, coincident copies, zero-area slivers along edges and point triangles at vertices.
fn degenerate_scene(n: usize) -> Scene {
    let mut s = scene("icosphere", n / 3);
    let base = s.triangles.clone();
    for (i, t) in base.iter().enumerate() {
        match i % 4 {
            0 => s.triangles.push(Triangle::new(t.v[0], t.v[2], t.v[1])),
            1 => s.triangles.push(*t),
            2 => s
                .triangles
                .push(Triangle::new(t.v[0], t.v[1], (t.v[0] + t.v[1]) * 0.5)),
            _ => s.triangles.push(Triangle::new(t.v[2], t.v[2], t.v[2])),
        }
    }
    s.name = "degenerate".into();
    s
}

/// Every stress case; `prims` is the size of the generated scenes, `n` the rays per case.
pub fn all_cases(prims: usize, n: usize) -> Vec<Case> {
    let soup = scene("soup", prims);
    let mixed = scene("mixed", prims);
    let ico = scene("icosphere", prims);
    let stadium = scene("stadium", prims);
    let flat = scene("flat", prims);
    let degenerate = degenerate_scene(prims);

    let mut cases = vec![
        case("axis-parallel-signed-zeros", &soup, axis_parallel(&soup, n)),
        case("axis-parallel-mixed", &mixed, axis_parallel(&mixed, n)),
        case(
            "vertices-and-edges",
            &ico,
            at_vertices_and_edges(&ico.triangles, &ico.bounds(), n),
        ),
        case("cell-boundaries-soup", &soup, cell_boundaries(&soup, n)),
        case(
            "cell-boundaries-stadium",
            &stadium,
            cell_boundaries(&stadium, n),
        ),
        case("in-split-planes", &soup, in_split_planes(&soup, n)),
        case("in-split-planes-mixed", &mixed, in_split_planes(&mixed, n)),
    ];
    let mut flat_rays = protocol(&flat, n / 2);
    flat_rays.extend(in_split_planes(&flat, n / 4));
    flat_rays.extend(at_vertices_and_edges(
        &flat.triangles,
        &flat.bounds(),
        n / 4,
    ));
    cases.push(case("flat-scene", &flat, flat_rays));

    let tri = Scene::from_triangles(
        "single-triangle",
        vec![Triangle::from_corners(
            [0.1, 0.2, 0.3],
            [0.9, 0.25, 0.35],
            [0.4, 0.8, 0.6],
        )],
    );
    let mut tri_rays = protocol(&tri, n / 2);
    tri_rays.extend(at_vertices_and_edges(&tri.triangles, &tri.bounds(), n / 4));
    tri_rays.extend(axis_parallel(&tri, n / 4));
    cases.push(case("single-triangle", &tri, tri_rays));
    let sphere = Scene {
        name: "single-sphere".into(),
        spheres: vec![Sphere::new(Vec3A::new(0.5, -0.25, 2.0), 0.75)],
        ..Scene::default()
    };
    let mut sphere_rays = protocol(&sphere, n / 2);
    sphere_rays.extend(axis_parallel(&sphere, n / 4));
    sphere_rays.extend(inside_primitives(&sphere, n / 4));
    cases.push(case("single-sphere", &sphere, sphere_rays));

    let mut deg_rays = at_vertices_and_edges(&degenerate.triangles, &degenerate.bounds(), n / 2);
    deg_rays.extend(protocol(&degenerate, n / 2));
    cases.push(case("degenerate-and-duplicates", &degenerate, deg_rays));

    for (name, k) in [
        ("scale-1e-6", 1e-6f32),
        ("scale-1e6", 1e6),
        ("mixed-scale-1e-6", 1e-6),
        ("mixed-scale-1e6", 1e6),
    ] {
        let src = if name.starts_with("mixed") {
            &mixed
        } else {
            &soup
        };
        let s = scaled(src, k);
        let mut rays = protocol(&s, n / 2);
        rays.extend(axis_parallel(&s, n / 4));
        rays.extend(cell_boundaries(&s, n / 4));
        cases.push(case(name, &s, rays));
    }

    let mut giant = mixed.clone();
    giant.triangles.push(Triangle::from_corners(
        [-500.0, 0.5, -500.0],
        [500.0, 0.5, -500.0],
        [0.0, 0.5, 700.0],
    ));
    giant
        .spheres
        .push(Sphere::new(Vec3A::new(0.5, 0.5, -400.0), 300.0));
    let local = Scene {
        triangles: mixed.triangles.clone(),
        spheres: mixed.spheres.clone(),
        ..Scene::default()
    };
    let mut giant_rays = protocol(&local, n / 2);
    giant_rays.extend(protocol(&giant, n / 4));
    giant_rays.extend(cell_boundaries(&giant, n / 4));
    cases.push(case("giant-primitives", &giant, giant_rays));

    cases.push(case("t-min-equals-t-max", &soup, empty_intervals(&soup, n)));
    cases.push(case(
        "t-min-equals-t-max-mixed",
        &mixed,
        empty_intervals(&mixed, n),
    ));
    cases.push(case(
        "origins-inside-primitives",
        &mixed,
        inside_primitives(&mixed, n),
    ));
    // Non-watertight kernels report hits just outside edges: indices must still agree.
    let named = |n: &str| {
        cases
            .iter()
            .find(|c| c.name == n)
            .cloned()
            .expect("defined above")
    };
    let (at_edges, cells) = (named("vertices-and-edges"), named("cell-boundaries-soup"));
    cases.push(with_kernel(
        &at_edges,
        "vertices-and-edges-moller-trumbore",
        TriangleKernelKind::MollerTrumbore,
    ));
    cases.push(with_kernel(
        &at_edges,
        "vertices-and-edges-plane-edges",
        TriangleKernelKind::PlaneEdges,
    ));
    cases.push(with_kernel(
        &at_edges,
        "vertices-and-edges-exact",
        TriangleKernelKind::Exact,
    ));
    cases.push(with_kernel(
        &cells,
        "cell-boundaries-parametric",
        TriangleKernelKind::Parametric,
    ));
    cases
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_has_rays_and_primitives() {
        for c in all_cases(300, 200) {
            assert!(c.rays.len() >= 100, "{}: {} rays", c.name, c.rays.len());
            assert!(!c.scene.is_empty(), "{}", c.name);
        }
        let d = axis_directions();
        assert_eq!(d.len(), 24);
        assert!(d.iter().any(|v| v.y.to_bits() == (-0.0f32).to_bits()));
    }
}
