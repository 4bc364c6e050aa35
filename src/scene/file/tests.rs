use super::*;
use crate::scene::Material;
use crate::scene::generators::generate;
use std::fs;

/// A directory with `scene.toml` holding `toml` and a one-triangle `tri.obj`.
fn scene_dir(toml: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let path = dir.path().join("scene.toml");
    fs::write(&path, toml).unwrap();
    (dir, path)
}

/// [`load_scene_file`] on `toml` in a [`scene_dir`].
pub(super) fn load(toml: &str) -> Result<Scene, SceneError> {
    let (_dir, path) = scene_dir(toml);
    load_scene_file(&path)
}

fn error(toml: &str) -> String {
    let e = load(toml).expect_err("scene should be rejected");
    assert!(matches!(e, SceneError::SceneFile { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(msg.contains("scene.toml"), "message names the file: {msg}");
    msg
}

#[test]
fn objects_in_file_order_with_transforms() {
    let s = load(
        r#"
name = "ordered"
[[generator]]
name = "mixed"
n = 100
seed = 2
[[sphere]]
center = [5, 5, 5]
radius = 0.5
[[mesh]]
path = "tri.obj"
translate = [0, 0, 10]
scale = 2
[[generator]]
name = "soup"
n = 30
rotate = { axis = [0, 1, 0], degrees = 0 }
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[[light]]
position = [1, 2, 3]
"#,
    )
    .unwrap();
    let mixed = generate("mixed", 100, 2).unwrap();
    let soup = generate("soup", 30, 1).unwrap();
    let nt = mixed.triangles.len();
    assert_eq!(s.name, "ordered");
    assert_eq!(s.triangles.len(), nt + 1 + 30);
    assert_eq!(s.triangles[..nt], mixed.triangles[..]);
    assert_eq!(s.triangles[nt].v[1], Vec3A::new(2.0, 0.0, 10.0));
    assert_eq!(s.triangles[nt + 1..], soup.triangles[..]);
    // Spheres: the generator's first (it comes first in the file), then the explicit one.
    assert_eq!(s.spheres[..mixed.spheres.len()], mixed.spheres[..]);
    assert_eq!(s.spheres.last().unwrap().radius, 0.5);
    assert_eq!(s.lights.len(), 1);
    assert_eq!(s.lights[0].intensity, glam::Vec3::ONE);
    assert_eq!(s.camera.unwrap().fov_deg, 45.0);
}

#[test]
fn sphere_generators_take_uniform_scales_only() {
    let s = load("[[generator]]\nname = \"spheres\"\nn = 10\nscale = 2\ntranslate = [1, 0, 0]\n")
        .unwrap();
    let g = generate("spheres", 10, 1).unwrap();
    assert_eq!(s.spheres[3].radius, g.spheres[3].radius * 2.0);
    let msg = error("[[generator]]\nname = \"spheres\"\nn = 10\nscale = [1, 2, 1]\n");
    assert!(
        msg.contains("line 1") && msg.contains("not uniform"),
        "{msg}"
    );
}

#[test]
fn bad_files_name_what_to_fix() {
    for (toml, expect) in [
        (
            "colour = 3\n[[sphere]]\ncenter = [0,0,0]\nradius = 1\n",
            "unknown field",
        ),
        (
            "[[mesh]]\npath = \"tri.obj\"\nscaling = 2\n",
            "unknown field",
        ),
        (
            "[[mesh]]\npath = \"tri.obj\"\nrotate = { axis = [0,1,0], deg = 3 }\n",
            "unknown field",
        ),
        ("[[sphere]]\ncenter = [0,0,0]\nradius = -1\n", "radius > 0"),
        ("[[sphere]]\ncenter = [0,0,0]\nradius = nan\n", "radius > 0"),
        (
            "[[sphere]]\ncenter = [0,inf,0]\nradius = 1\n",
            "finite center",
        ),
        ("[[mesh]]\npath = \"tri.obj\"\nscale = 0\n", "non-zero"),
        (
            "[[mesh]]\npath = \"tri.obj\"\nscale = [1, 1]\n",
            "a number or an array",
        ),
        ("\n\n[[mesh]]\npath = \"missing.obj\"\n", "line 3"),
        (
            "[[generator]]\nname = \"teapot\"\n",
            "unknown scene 'teapot'",
        ),
        ("[[generator]]\nname = \"soup\"\nn = 0\n", "n = 0"),
        ("[[generator]]\nname = \"soup\"\nn = -4\n", "n = -4"),
        ("name = \"nothing\"\n", "empty"),
        ("", "empty"),
        (
            "[camera]\neye = [0,0,0]\nlook_at = [0,0,0]\n[[sphere]]\ncenter = [0,0,0]\nradius = 1\n",
            "[camera]",
        ),
        (
            "[[light]]\nposition = [0,nan,0]\n[[sphere]]\ncenter = [0,0,0]\nradius = 1\n",
            "[[light]] 1",
        ),
        (
            "[[mesh]]\npath = \"tri.obj\"\nscale = 1e38\ntranslate = [3e38, 0, 0]\n",
            "infinite",
        ),
        ("[[sphere]\n", "invalid"),
    ] {
        let msg = error(toml);
        assert!(msg.contains(expect), "expected '{expect}' in: {msg}");
    }
}

#[test]
fn missing_scene_file_is_io_error() {
    let e = load_scene_file(Path::new("/nonexistent/scene.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }), "{e:?}");
}

#[test]
fn materials_by_name_or_inline_per_object_and_area_lights() {
    let s = load(
        r#"
[material.red]
color = [0.9, 0.1, 0.1]
specular = 0
[[mesh]]
path = "tri.obj"
material = "red"
[[generator]]
name = "mixed"
n = 40
material = { color = [0, 0, 1], emission = [0.5, 0.5, 0.5] }
[[mesh]]
path = "tri.obj"
[[sphere]]
center = [5, 5, 5]
radius = 0.5
material = "red"
[[area_light]]
corner = [0, 3, 0]
edge1 = [1, 0, 0]
edge2 = [0, 0, 1]
samples = 3
"#,
    )
    .unwrap();
    let red = Material {
        color: glam::Vec3::new(0.9, 0.1, 0.1),
        specular: 0.0,
        ..Material::DEFAULT
    };
    let mixed = generate("mixed", 40, 1).unwrap();
    let (nt, ns) = (mixed.triangles.len(), mixed.spheres.len());
    assert_eq!(*s.material(0), red);
    assert_eq!(s.material(1).color, glam::Vec3::Z);
    assert_eq!(s.material(nt as u32).emission, glam::Vec3::splat(0.5));
    assert_eq!(*s.material(nt as u32 + 1), Material::DEFAULT, "no material");
    let first_sphere = s.triangles.len() as u32;
    assert_eq!(s.material(first_sphere).color, glam::Vec3::Z);
    assert_eq!(*s.material(first_sphere + ns as u32), red);
    assert_eq!(s.area_lights.len(), 1);
    assert_eq!(s.area_lights[0].samples, 3);
    assert_eq!(s.area_lights[0].intensity, glam::Vec3::ONE);
    // Without materials every primitive uses the default.
    let plain = load("[[mesh]]\npath = \"tri.obj\"\n").unwrap();
    assert_eq!(*plain.material(0), Material::DEFAULT);
}

#[test]
fn bad_materials_and_area_lights_name_what_to_fix() {
    let tri = "[[mesh]]\npath = \"tri.obj\"\n";
    for (toml, expect) in [
        (format!("{tri}material = \"gold\"\n"), "[material.gold]"),
        (
            format!("[material.a]\ncolor = [1, 1, 1]\n{tri}material = \"b\"\n"),
            "use one of a",
        ),
        (format!("[material.a]\ndiffuse = -1\n{tri}"), "[material.a]"),
        (format!("[material.a]\nglow = 1\n{tri}"), "unknown field"),
        (
            format!("{tri}material = {{ shine = 3 }}\n"),
            "a material name",
        ),
        (
            format!("{tri}material = {{ shininess = nan }}\n"),
            "shininess from 0",
        ),
        (
            format!("{tri}[[area_light]]\ncorner = [0,0,0]\nedge1 = [1,0,0]\nedge2 = [2,0,0]\n"),
            "[[area_light]] 1",
        ),
        (
            format!(
                "{tri}[[area_light]]\ncorner = [0,0,0]\nedge1 = [1,0,0]\nedge2 = [0,0,1]\nsamples = 1000\n"
            ),
            "1 to 64 strata",
        ),
        (
            format!("{tri}[[area_light]]\ncorner = [0,0,0]\nedge1 = [1,0,0]\nedge3 = [0,0,1]\n"),
            "unknown field",
        ),
    ] {
        let msg = error(&toml);
        assert!(msg.contains(expect), "expected '{expect}' in: {msg}");
    }
}
