//! Pictures: shaded images are byte-identical across every registered index and thread count,
//! heat-map pixels are the counting statistics of the camera rays, area lights give soft
//! shadows (point lights hard ones), and bad parameters are clear CLI errors.

use crate::common;
use crate::common::temp::temp_path;
use accelbench::geometry::TriangleKernelKind;
use accelbench::index::{
    BuildError, Counters, IndexSpec, TraceIndex, build_index, index_names, is_peer,
};
use accelbench::render::{
    HeatmapKind, Image, RenderOptions, heat_colour, legend_height, pixel_costs, pixel_ray,
    render_heatmap, render_shaded, view_camera,
};
use accelbench::scene::{AreaLight, Material, Scene, generators, load_scene};
use glam::Vec3;
use std::path::Path;

fn build(name: &str, scene: &Scene) -> Box<dyn TraceIndex> {
    build_index(
        &IndexSpec::named(name),
        &scene.geometry(),
        TriangleKernelKind::Watertight,
    )
    .unwrap()
}

/// The registered indices that take `scene`: all of ours, and the peers but those that take
/// triangles only when it has other shapes (Embree, tinybvh with the `peers` feature).
fn indices_for(scene: &Scene) -> Vec<(&'static str, Box<dyn TraceIndex>)> {
    let geom = scene.geometry();
    index_names()
        .into_iter()
        .filter_map(|name| {
            let built = build_index(
                &IndexSpec::named(name),
                &geom,
                TriangleKernelKind::Watertight,
            );
            match built {
                Err(BuildError::Unsupported { .. }) if is_peer(name) => None,
                b => Some((name, b.unwrap())),
            }
        })
        .collect()
}

fn on_threads<R: Send>(n: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(f)
}

/// `mixed` (triangles and spheres) with a red material on the spheres, a point light and an
/// area light, so every shading path (materials, hard and soft shadows) is exercised.
fn lit_mixed() -> Scene {
    let mut s = generators::generate("mixed", 400, 3).unwrap();
    let n_spheres = s.spheres.len();
    assert!(n_spheres > 0);
    s.materials.start_spheres(
        n_spheres / 2,
        Some(Material {
            color: Vec3::new(0.9, 0.2, 0.2),
            specular: 0.6,
            ..Material::DEFAULT
        }),
    );
    s.lights = s.lights_or_default();
    s.area_lights.push(AreaLight {
        corner: Vec3::new(0.2, 1.6, 0.2),
        edge1: Vec3::new(0.6, 0.0, 0.0),
        edge2: Vec3::new(0.0, 0.0, 0.6),
        intensity: Vec3::splat(0.7),
        samples: 3,
    });
    s
}

#[test]
fn shaded_images_are_identical_across_indices_and_threads() {
    let scene = lit_mixed();
    let opts = RenderOptions::new(48, 36);
    let brute = build("brute", &scene);
    let reference = on_threads(1, || render_shaded(&scene, brute.as_ref(), &opts)).unwrap();
    assert_eq!((reference.width(), reference.height()), (48, 36));
    // Not a blank picture: several distinct colours (objects, shadows, background).
    let mut colours: Vec<[u8; 3]> = (0..36)
        .flat_map(|j| (0..48).map(move |i| (i, j)))
        .map(|(i, j)| reference.pixel(i, j))
        .collect();
    colours.sort();
    colours.dedup();
    assert!(colours.len() > 20, "{} colours", colours.len());
    // Area-light samples are seeded by pixel, not by thread.
    let threaded = on_threads(3, || render_shaded(&scene, brute.as_ref(), &opts)).unwrap();
    assert!(threaded == reference, "image depends on the thread count");
    for (name, index) in indices_for(&scene) {
        let img = on_threads(2, || render_shaded(&scene, index.as_ref(), &opts)).unwrap();
        assert!(
            img.as_bytes() == reference.as_bytes(),
            "{name}: shaded image differs from brute force"
        );
    }
}

#[test]
fn heat_map_pixels_are_the_counting_statistics_of_the_camera_rays() {
    let scene = generators::generate("mixed", 300, 5).unwrap();
    let opts = RenderOptions::new(40, 30);
    let cam = view_camera(&scene, &opts).unwrap();
    let rays: Vec<_> = (0..30)
        .flat_map(|j| (0..40).map(move |i| (i, j)))
        .map(|(i, j)| pixel_ray(&cam, i, j).unwrap())
        .collect();
    for (name, index) in indices_for(&scene) {
        let mut hits = vec![None; rays.len()];
        let mut counters = vec![Counters::default(); rays.len()];
        index.closest_hits_counted(&rays, &mut hits, &mut counters);
        assert!(hits.iter().any(|h| h.is_some()) && hits.iter().any(|h| h.is_none()));
        for kind in HeatmapKind::ALL {
            let costs = pixel_costs(&scene, index.as_ref(), &opts, kind).unwrap();
            let expect: Vec<u64> = counters.iter().map(|c| kind.of(c)).collect();
            assert_eq!(costs, expect, "{name} {kind}");
            let img = render_heatmap(&scene, index.as_ref(), &opts, kind).unwrap();
            assert_eq!(img.height(), 30 + legend_height(40));
            for (k, v) in expect.iter().enumerate() {
                let (i, j) = ((k % 40) as u32, (k / 40) as u32);
                assert_eq!(img.pixel(i, j), heat_colour(*v), "{name} {kind} ({i}, {j})");
            }
        }
        // Brute force tests every primitive on every ray.
        if name == "brute" {
            assert!(counters.iter().all(|c| c.prim_tests == scene.len() as u64));
        }
    }
}

/// A floor quad, a sphere above it and one light, from a scene file: `light` is the TOML of the
/// light, `sphere` whether the occluder is there.
fn floor_scene(dir: &Path, light: &str, sphere: bool) -> Scene {
    std::fs::write(
        dir.join("floor.obj"),
        "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 3 2\nf 1 4 3\n",
    )
    .unwrap();
    let occluder = if sphere {
        "[[sphere]]\ncenter = [0, 0.5, 0]\nradius = 0.3\nmaterial = { color = [0.9, 0.2, 0.2], specular = 0.5 }\n"
    } else {
        ""
    };
    let toml = format!(
        r#"
[camera]
eye = [0, 3, 2.5]
look_at = [0, 0, 0]
fov_deg = 50

[material.floor]
color = [1, 1, 1]
ambient = 0
diffuse = 1
specular = 0

[[mesh]]
path = "floor.obj"
material = "floor"

{occluder}
{light}
"#
    );
    let path = dir.join(format!("floor_{sphere}.toml"));
    std::fs::write(&path, toml).unwrap();
    load_scene(path.to_str().unwrap()).unwrap()
}

/// Per floor pixel (camera ray hits the floor in both scenes), the shaded byte with the
/// occluder and without it.
fn floor_pixels(dir: &Path, light: &str) -> Vec<(u8, u8)> {
    let opts = RenderOptions::new(64, 64);
    let with = floor_scene(dir, light, true);
    let without = floor_scene(dir, light, false);
    let (iw, io) = (build("brute", &with), build("brute", &without));
    let a = render_shaded(&with, iw.as_ref(), &opts).unwrap();
    let b = render_shaded(&without, io.as_ref(), &opts).unwrap();
    let cam = view_camera(&with, &opts).unwrap();
    let mut out = Vec::new();
    for j in 0..64 {
        for i in 0..64 {
            let hit = iw.closest_hit(&pixel_ray(&cam, i, j).unwrap());
            if hit.is_some_and(|h| h.prim < 2) {
                out.push((a.pixel(i, j)[0], b.pixel(i, j)[0]));
            }
        }
    }
    out
}

#[test]
fn area_lights_cast_soft_shadows_and_point_lights_hard_ones() {
    let dir = tempfile::tempdir().unwrap();
    let area = "[[area_light]]\ncorner = [-0.5, 2, -0.5]\nedge1 = [1, 0, 0]\nedge2 = [0, 0, 1]\nsamples = 4\n";
    let px = floor_pixels(dir.path(), area);
    assert!(px.len() > 1000, "{} floor pixels", px.len());
    assert!(px.iter().all(|(w, o)| w <= o), "the occluder only darkens");
    let lit = px.iter().filter(|(w, o)| w == o).count();
    let umbra = px.iter().filter(|(w, o)| *w == 0 && *o > 0).count();
    let penumbra = px.iter().filter(|(w, o)| *w > 0 && w < o).count();
    assert!(
        lit > 0 && umbra > 0 && penumbra > 0,
        "{lit} {umbra} {penumbra}"
    );

    let point = "[[light]]\nposition = [0, 2, 0]\n";
    let px = floor_pixels(dir.path(), point);
    let umbra = px.iter().filter(|(w, o)| *w == 0 && *o > 0).count();
    assert!(umbra > 0, "the point light casts a shadow");
    assert!(
        px.iter().all(|(w, o)| w == o || *w == 0),
        "a point light's shadow is hard: lit or black"
    );
}

fn read_png(path: &Path) -> Image {
    let dec = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size()];
    let info = r.next_frame(&mut buf).unwrap();
    let mut img = Image::new(info.width, info.height);
    for j in 0..info.height {
        for i in 0..info.width {
            let k = ((j * info.width + i) * 3) as usize;
            img.set(i, j, [buf[k], buf[k + 1], buf[k + 2]]);
        }
    }
    img
}

#[test]
fn cli_writes_pngs_and_rejects_bad_parameters() {
    let (dir, out) = temp_path("a.png");
    let o = out.to_str().unwrap();
    let render = [
        "render",
        "--scene",
        "icosphere:n=80",
        "--out",
        o,
        "--width",
        "24",
        "--height",
        "16",
    ];
    common::cli::accelbench_ok(&render);
    let img = read_png(&out);
    assert_eq!((img.width(), img.height()), (24, 16));
    common::cli::accelbench_ok(&[&render[..], &["--heatmap", "nodes"]].concat());
    assert_eq!(read_png(&out).height(), 16 + legend_height(24));

    let missing_dir = dir.path().join("no/such/dir/a.png");
    let m = missing_dir.to_str().unwrap();
    for (args, expect) in [
        (vec!["--width", "0"], "image size 0x512 is invalid"),
        (vec!["--height", "0"], "image size 512x0 is invalid"),
        (
            vec!["--width", "100000"],
            "width and height must be 1 to 16384",
        ),
        (vec!["--width", "-3"], "-3"),
        (vec!["--index", "octopus"], "unknown index 'octopus'"),
        (vec!["--index", "brute:leaf=3"], "unknown field"),
        (vec!["--heatmap", "cost"], "choose tests or nodes"),
        (vec!["--kernel", "fast"], "unknown kernel"),
    ] {
        let mut a = vec!["render", "--scene", "icosphere:n=80", "--out", o];
        a.extend(args);
        common::cli::accelbench_fails(&a, &[expect]);
    }
    common::cli::accelbench_fails(
        &[
            "render",
            "--scene",
            "icosphere:n=80",
            "--out",
            m,
            "--width",
            "4",
            "--height",
            "4",
        ],
        &["cannot write"],
    );
    common::cli::accelbench_fails(
        &["render", "--scene", "nope", "--out", o],
        &["unknown scene"],
    );
}

/// A `[[shape]]`'s `material` reaches the shaded image: the same box in front of the camera,
/// once red by its material and once with none (the grey default).
#[test]
fn shape_materials_reach_the_render() {
    let dir = tempfile::tempdir().unwrap();
    let centre_pixel = |material: &str| {
        let toml = format!(
            "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n\n[[light]]\nposition = [0, 0, 5]\n\n\
             [[shape]]\nkind = \"box\"\ncenter = [0, 0, 0]\nhalf_extents = [1, 1, 1]\n{material}\n"
        );
        let path = dir.path().join("box.toml");
        std::fs::write(&path, toml).unwrap();
        let scene = load_scene(path.to_str().unwrap()).unwrap();
        let opts = RenderOptions::new(16, 16);
        let img = render_shaded(&scene, build("bvh", &scene).as_ref(), &opts).unwrap();
        img.pixel(8, 8)
    };
    let red = centre_pixel("material = { color = [1, 0, 0], specular = 0 }");
    let grey = centre_pixel("");
    assert!(red[0] > 100 && red[1] == 0 && red[2] == 0, "{red:?}");
    assert!(
        grey[0] > 100 && grey[0] == grey[1] && grey[1] == grey[2],
        "{grey:?}"
    );
}
