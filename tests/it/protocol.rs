//! The generated ray sets reproduce ../shared/PROTOCOL.md: checksums on the shared bunny and an
//! independent straightforward computation of the camera on a simple box.
use accelbench::geometry::Aabb;
use accelbench::rays::{incoherent_rays, primary_rays};
use glam::Vec3A;

use crate::common;

#[test]
fn bunny_ray_sets_match_protocol_checksums() {
    let Some(bunny) = common::bunny() else { return };
    let b = bunny.ray_set_bounds();
    assert_eq!(
        common::checksum::md5_of_rays(&primary_rays(&b, 1024, 1024).unwrap()),
        "ce45bc03556f0152be8f45958a49e59f"
    );
    assert_eq!(
        common::checksum::md5_of_rays(&incoherent_rays(&b, 1 << 20, 42)),
        "14642e7a02a6bda489a74402a0b4af6c"
    );
}

#[test]
fn camera_matches_an_independent_computation() {
    // Box [0,2]^3: c = (1,1,1), d = sqrt(12). Written out here without the library's helpers.
    let b = Aabb::new(Vec3A::ZERO, Vec3A::splat(2.0));
    let rays = primary_rays(&b, 4, 3).unwrap();
    let c = [1.0f64; 3];
    let d = 12f64.sqrt();
    let l = (0.3f64 * 0.3 + 0.35 * 0.35 + 1.0).sqrt();
    let n = [0.3 / l, 0.35 / l, 1.0 / l];
    let eye: Vec<f64> = (0..3).map(|k| c[k] + d * n[k] * 1.1).collect();
    let f0: Vec<f64> = (0..3).map(|k| c[k] - eye[k]).collect();
    let fl = (f0[0] * f0[0] + f0[1] * f0[1] + f0[2] * f0[2]).sqrt();
    let f: Vec<f64> = f0.iter().map(|x| x / fl).collect();
    // right = f x (0,1,0) = (-f.z, 0, f.x)
    let r0 = [-f[2], 0.0, f[0]];
    let rl = (r0[0] * r0[0] + r0[2] * r0[2]).sqrt();
    let r = [r0[0] / rl, 0.0, r0[2] / rl];
    let u = [
        r[1] * f[2] - r[2] * f[1],
        r[2] * f[0] - r[0] * f[2],
        r[0] * f[1] - r[1] * f[0],
    ];
    let t = (45f64.to_radians() / 2.0).tan();
    for j in 0..3u32 {
        for i in 0..4u32 {
            let uu = ((i as f64 + 0.5) / 4.0) * 2.0 - 1.0;
            let vv = 1.0 - ((j as f64 + 0.5) / 3.0) * 2.0;
            let dir: Vec<f64> = (0..3)
                .map(|k| f[k] + uu * t * r[k] + vv * t * u[k])
                .collect();
            let dl = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
            let ray = &rays[(j * 4 + i) as usize];
            for k in 0..3 {
                assert!(
                    (ray.dir[k] as f64 - dir[k] / dl).abs() < 1e-6,
                    "pixel {i},{j}"
                );
                assert!((ray.origin[k] as f64 - eye[k]).abs() < 1e-6);
            }
            assert_eq!((ray.t_min, ray.t_max), (0.0, f32::INFINITY));
        }
    }
}
