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

#[test]
fn keyframed_entries_remember_their_primitives_and_move_by_their_keys() {
    use crate::scene::motion::MotionSpec;
    let s = load(
        r#"
[[generator]]
name = "mixed"
n = 60
translate = [0, 0, 5]
keyframes = [
  { t = 0 },
  { t = 0.5, translate = [2, 0, 0], rotate = { axis = [0, 1, 0], degrees = 90 } },
]
[[mesh]]
path = "tri.obj"
[[mesh]]
path = "tri.obj"
[[mesh.keyframes]]
t = 0.25
translate = [0, 1, 0]
[[mesh.keyframes]]
t = 1
translate = [0, 3, 0]
[[sphere]]
center = [1, 0, 0]
radius = 0.5
keyframes = [{ t = 0, rotate = { axis = [0, 0, 1], degrees = 90 } }]
"#,
    )
    .unwrap();
    let mixed = generate("mixed", 60, 1).unwrap();
    let (nt, ns) = (mixed.triangles.len(), mixed.spheres.len());
    let k = &s.keyframed;
    assert_eq!(k.len(), 3);
    assert_eq!(k[0].entry, "line 2, [[generator]] name = \"mixed\"");
    assert_eq!(
        (k[0].triangles.clone(), k[0].spheres.clone()),
        (0..nt, 0..ns)
    );
    assert!(
        k[1].entry.ends_with("[[mesh]] path = \"tri.obj\""),
        "{}",
        k[1].entry
    );
    assert_eq!(
        (k[1].triangles.clone(), k[1].spheres.clone()),
        (nt + 1..nt + 2, ns..ns)
    );
    assert_eq!(
        (k[2].triangles.clone(), k[2].spheres.clone()),
        (nt + 2..nt + 2, ns..ns + 1)
    );
    assert_eq!(k[1].track.keys().len(), 2);

    let frame = |t: f32| MotionSpec::Keyframes.frame(&s, t).unwrap();
    let near = |a: Vec3A, b: Vec3A| (a - b).abs().max_element() < 1e-5;
    // t = 0: the generator's first key is the identity, so it is the static scene, bit for
    // bit; the mesh holds its first key (t = 0.25) and the sphere its only one.
    let start = frame(0.0);
    assert_eq!(start.triangles[..=nt], s.triangles[..=nt]);
    assert_eq!(start.spheres[..ns], s.spheres[..ns]);
    let moved = |t: &crate::geometry::Triangle, dy: f32| t.v.map(|v| v + Vec3A::Y * dy);
    assert_eq!(start.triangles[nt + 1].v, moved(&s.triangles[nt + 1], 1.0));
    assert!(
        near(start.spheres[ns].center, Vec3A::Y),
        "turned about the origin"
    );
    // At the generator's last key: its pose exactly, a quarter turn about its own placement
    // (0, 0, 5), (x, y, z) -> (z, y, -x) about it, then (2, 0, 0) further.
    let key = frame(0.5);
    let pose = k[0].track.at(0.5);
    assert_eq!(key.triangles[3], pose.triangle(&s.triangles[3]));
    let q = mixed.triangles[3].v[0];
    assert!(near(
        key.triangles[3].v[0],
        Vec3A::new(q.z + 2.0, q.y, 5.0 - q.x)
    ));
    // Half way to it: half the turn (45 degrees) and half the move; the mesh between its keys.
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let mid = frame(0.25).triangles[3].v[0];
    let turned = Vec3A::new(h * (q.x + q.z) + 1.0, q.y, h * (q.z - q.x) + 5.0);
    assert!(near(mid, turned), "{mid} {turned}");
    assert_eq!(
        frame(0.25).triangles[nt + 1].v,
        moved(&s.triangles[nt + 1], 1.0)
    );
    let between = frame(0.625).triangles[nt + 1].v;
    assert!(near(between[1], s.triangles[nt + 1].v[1] + Vec3A::Y * 2.0));
}

#[test]
fn bad_keyframes_name_the_file_the_entry_and_the_key() {
    let mesh = "[[mesh]]\npath = \"tri.obj\"\n";
    let entry = "line 1, [[mesh]] path = \"tri.obj\": ";
    for (keys, expect) in [
        ("[]", "keyframes = [] has no key"),
        ("[{ t = 1.5 }]", "keyframe 1 of 1: t = 1.5 is invalid"),
        ("[{ t = -0.01 }]", "keyframe 1 of 1: t = -0.01 is invalid"),
        ("[{ t = nan }]", "keyframe 1 of 1: t = NaN is invalid"),
        (
            "[{ t = 0.5 }, { t = 0.5 }]",
            "keyframe 2 of 2: t = 0.5 is not after the previous key's t = 0.5",
        ),
        ("[{ t = 0.5 }, { t = 0.2 }, { t = 1 }]", "keyframe 2 of 3"),
        (
            "[{ t = 0, rotate = { axis = [0, 0, 0], degrees = 10 } }]",
            "keyframe 1 of 1: rotation axis [0.0, 0.0, 0.0] is invalid",
        ),
        (
            "[{ t = 0, translate = [nan, 0, 0] }]",
            "keyframe 1 of 1: translate [NaN, 0.0, 0.0] is invalid",
        ),
        (
            "[{ t = 0, rotate = { axis = [0, 1, 0], degrees = inf } }]",
            "keyframe 1 of 1: rotation angle inf degrees",
        ),
    ] {
        let msg = error(&format!("{mesh}keyframes = {keys}\n"));
        assert!(msg.contains(&format!("{entry}{expect}")), "{keys}: {msg}");
    }
    for (keys, expect) in [
        ("[{ t = 0, scale = 2 }]", "unknown field `scale`"),
        ("[{ translate = [1, 0, 0] }]", "missing field `t`"),
    ] {
        let msg = error(&format!("{mesh}keyframes = {keys}\n"));
        assert!(msg.contains(expect), "{keys}: {msg}");
    }
    let sphere = error("[[sphere]]\ncenter = [0, 0, 0]\nradius = 1\nkeyframes = [{ t = 2 }]\n");
    assert!(
        sphere.contains("line 1, [[sphere]]: keyframe 1 of 1: t = 2"),
        "{sphere}"
    );
    let shape = error(
        "[[shape]]\nkind = \"box\"\ncenter = [0, 0, 0]\nhalf_extents = [1, 1, 1]\n\
         keyframes = [{ t = 0.5 }, { t = 0.1 }]\n",
    );
    assert!(
        shape.contains("[[shape]] kind = \"box\": keyframe 2 of 2"),
        "{shape}"
    );
}
