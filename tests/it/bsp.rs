//! The general BSP returns brute force's hits bit for bit: on the agreement scenes, on rays in
//! and near its split planes (axis planes exactly, general planes to rounding) and through
//! their crossings, and on degenerate input; it tests each primitive at most once per ray; bad
//! parameters are typed errors.
use crate::common;
use crate::partition_kit;

use accelbench::geometry::Ray;
use accelbench::index::bsp::BspNode;
use accelbench::index::{Bsp, Index};
use accelbench::rays::SplitMix64;
use accelbench::scene::{Scene, generators};
use glam::{Vec3, Vec3A};
use partition_kit::*;

fn bsp_on(scene: &Scene, params: &str) -> Bsp {
    build_on::<Bsp>("bsp", scene, params)
}

/// Axis planes of the tree as `(axis, offset)`; the others as `(normal, offset)`.
#[allow(clippy::type_complexity)]
fn planes(tree: &Bsp) -> (Vec<(usize, f32)>, Vec<(Vec3A, f32)>) {
    let (mut axis, mut general) = (Vec::new(), Vec::new());
    for (n, d) in tree.split_planes() {
        match (0..3).find(|&a| n[a] == 1.0) {
            Some(a) if n.abs().element_sum() == 1.0 => axis.push((a, d)),
            _ => general.push((n, d)),
        }
    }
    (axis, general)
}

/// Rays in general planes (origin projected on the plane, direction projected into it) and
/// through the crossing lines of two planes (aimed at a point projected on both).
fn rays_in_general_planes(planes: &[(Vec3A, f32)], scene: &Scene, per_plane: usize) -> Vec<Ray> {
    let b = scene.bounds();
    let mut rng = SplitMix64::new(21);
    let mut rays = Vec::new();
    let project = |p: Vec3A, (n, d): (Vec3A, f32)| p - n * (n.dot(p) - d);
    for (i, &pl) in planes.iter().enumerate() {
        for _ in 0..per_plane {
            let o = project(Vec3A::from(point_near(&b, &mut rng)), pl);
            let dir = Vec3A::from(direction(&mut rng));
            let dir = dir - pl.0 * pl.0.dot(dir);
            if let Ok(r) = Ray::infinite(Vec3::from(o), Vec3::from(dir)) {
                rays.push(r);
            }
            // Through a point on this plane and the next one (alternating projections).
            let other = planes[(i + 1) % planes.len()];
            let mut p = Vec3A::from(point_near(&b, &mut rng));
            for _ in 0..20 {
                p = project(project(p, pl), other);
            }
            let from = Vec3A::from(point_near(&b, &mut rng));
            if let Ok(r) = Ray::infinite(Vec3::from(from), Vec3::from(p - from)) {
                rays.push(r);
            }
            let along = pl.0.cross(other.0);
            if let Ok(r) = Ray::infinite(Vec3::from(p), Vec3::from(along)) {
                rays.push(r);
            }
        }
    }
    rays
}

#[test]
fn agrees_with_other_parameters() {
    assert_agrees_with_parameters(&[
        "bsp:sweep=false,axis_candidates=1,plane_candidates=0",
        "bsp:sweep=false,plane_candidates=30,leaf_size=1",
        "bsp:max_depth=3",
        "bsp:mailbox=false",
    ]);
}

#[test]
fn rays_in_split_planes_and_through_their_crossings() {
    for (name, params) in [
        ("icosphere", ""),
        ("soup", ""),
        ("stadium", ""),
        ("room", ""),
        // Only primitives' own planes: a pure autopartition.
        ("terrain", ":sweep=false"),
        ("soup", ":sweep=false"),
    ] {
        let scene = generators::generate(name, 2000, 5).unwrap();
        let tree = bsp_on(&scene, params);
        let (axis, general) = planes(&tree);
        assert!(axis.len() + general.len() > 0, "{name}: the tree splits");
        if params.contains("sweep=false") {
            assert!(
                axis.is_empty() && !general.is_empty(),
                "{name}: autopartition"
            );
        }
        let b = scene.bounds();
        let mut rays = rays_in_axis_planes(&axis, &b, 4);
        rays.extend(rays_through_plane_crossings(&axis, &b, 300));
        rays.extend(rays_in_general_planes(&spaced(&general, 80), &scene, 8));
        common::assert_agrees("bsp", &scene, &rays);
    }
}

#[test]
fn degenerate_input_terminates_and_agrees() {
    for scene in degenerate_scenes() {
        let tree = bsp_on(&scene, "");
        assert!(tree.info().depth <= 64, "{}", scene.name);
        common::assert_agrees("bsp", &scene, &common::agreement_rays(&scene, 800));
        let (axis, general) = planes(&tree);
        let mut rays = rays_in_axis_planes(&axis, &scene.bounds(), 2);
        rays.extend(rays_in_general_planes(&general, &scene, 2));
        rays.truncate(3000);
        common::assert_agrees("bsp", &scene, &rays);
    }
}

/// Mailboxing, the structure figures and typed parameter errors (`partition_kit`).
#[test]
fn partition_basics_hold() {
    assert_partition_basics::<BspNode>(
        "bsp",
        24,
        &[
            ("sweep=false,plane_candidates=0", "candidates"),
            ("plane_candidates=100000", "candidates"),
            ("planes=3", "unknown field"),
        ],
    );
}

/// Scored by the exact areas of the convex cells, the primitives' own planes win some splits
/// on curved surfaces (with box areas around the cells they almost never did). Prints the
/// share of general planes (`--nocapture`).
#[test]
fn own_planes_win_splits_on_curved_surfaces() {
    for name in ["icosphere", "stadium"] {
        let scene = generators::generate(name, 20000, 1).unwrap();
        let tree = bsp_on(&scene, "");
        let (axis, general) = planes(&tree);
        eprintln!(
            "{name}: {} general of {} splits ({:.2}%)",
            general.len(),
            axis.len() + general.len(),
            100.0 * general.len() as f64 / (axis.len() + general.len()) as f64
        );
        if name == "icosphere" {
            assert!(!general.is_empty(), "{name}: no general plane chosen");
        }
    }
}
