//! obvhs as a peer: `obvhs-bvh2` and `obvhs-cwbvh` against brute force.
//!
//! obvhs's own box tests are not conservative in our sense, so exact agreement is asserted only
//! where it holds (protocol rays on the bunny); elsewhere the mismatches are counted, printed
//! (`--nocapture`), and each one must fall in a documented class.

use crate::common;

use accelbench::geometry::{Aabb, Hit, Ray, TriangleKernelKind};
use accelbench::harness::verify::compare_closest;
use accelbench::index::{TraceIndex, peer_names};
use accelbench::scene::Scene;
use common::{agreement_rays, agreement_scenes};

/// The obvhs peers (the other peers are tested in `tests/it/peers.rs`).
fn obvhs_peers() -> Vec<&'static str> {
    peer_names()
        .into_iter()
        .filter(|n| n.starts_with("obvhs-"))
        .collect()
}

fn build(spec: &str, scene: &Scene) -> Box<dyn TraceIndex> {
    common::build(spec, scene, TriangleKernelKind::Watertight)
}

/// Bounds of primitive `prim` of `scene` (triangles first, then spheres).
fn prim_bounds(scene: &Scene, prim: u32) -> Aabb {
    let i = prim as usize;
    match scene.triangles.get(i) {
        Some(t) => t.bounds(),
        None => scene.spheres[i - scene.triangles.len()].bounds(),
    }
}

/// Why obvhs lost brute force's hit on `ray` (`None`: no documented reason).
fn class(scene: &Scene, ray: &Ray, expected: Hit, got: Option<Hit>) -> Option<&'static str> {
    if got.is_some_and(|g| g.t.to_bits() == expected.t.to_bits() && g.prim > expected.prim) {
        // Same t, higher id: a node holding the lower id was culled at (or within rounding of)
        // the tie distance.
        return Some("tie");
    }
    if ray.dir.cmpeq(glam::Vec3A::ZERO).any() {
        // obvhs replaces 1/0 by +-1/EPSILON: a ray in a box's face plane is culled.
        return Some("zero-direction");
    }
    if expected.t < 1e-4 {
        // CWBVH clamps a child's entry to 1e-4: boxes the ray leaves before that are culled.
        return Some("t-below-1e-4");
    }
    // The hit point lies on the primitive's box boundary (rays aimed at vertices and edges):
    // obvhs's unwidened exit distance can fall a rounding error short of its entry.
    let p = ray.at(expected.t);
    let b = prim_bounds(scene, expected.prim);
    let tol = 1e-5 * b.min.abs().max(b.max.abs()).max(glam::Vec3A::ONE);
    let on_face = (p - b.min).abs().cmple(tol) | (p - b.max).abs().cmple(tol);
    Some("grazing").filter(|_| on_face.any())
}

#[test]
fn peers_agree_on_bunny_protocol_rays() {
    let Some(bunny) = common::bunny() else { return };
    let rays = common::bunny_protocol_sample(&bunny);
    let expected = common::closest(build("brute", &bunny).as_ref(), &rays);
    for spec in obvhs_peers() {
        let index = build(spec, &bunny);
        let m = compare_closest(&rays, &expected, &common::closest(index.as_ref(), &rays));
        assert!(
            m.is_empty(),
            "{spec}: {} mismatches, first {}",
            m.len(),
            m[0]
        );
        let mut any = vec![false; rays.len()];
        index.any_hits(&rays, &mut any);
        assert!(expected.iter().zip(&any).all(|(e, a)| e.is_some() == *a));
    }
}

#[test]
fn peer_mismatches_on_agreement_scenes_are_of_documented_kinds() {
    for scene in agreement_scenes() {
        let rays = agreement_rays(&scene, 2000);
        let expected = common::closest(build("brute", &scene).as_ref(), &rays);
        for spec in obvhs_peers() {
            let got = common::closest(build(spec, &scene).as_ref(), &rays);
            let m = compare_closest(&rays, &expected, &got);
            let mut counts = std::collections::BTreeMap::new();
            for mm in &m {
                let e = mm.expected.unwrap_or_else(|| {
                    panic!(
                        "{spec} on {}: a hit brute force does not have: {mm}",
                        scene.name
                    )
                });
                let c = class(&scene, &rays[mm.ray_index], e, mm.got)
                    .unwrap_or_else(|| panic!("{spec} on {}: unexplained {mm}", scene.name));
                *counts.entry(c).or_insert(0) += 1;
            }
            eprintln!(
                "{spec} on {}: {} of {} rays differ {counts:?}",
                scene.name,
                m.len(),
                rays.len()
            );
        }
    }
}
