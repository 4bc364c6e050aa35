//! Fuzzing every input format with proptest over bytes (issue 47): the OBJ, PLY and GLB
//! loaders (issue 49), scene TOML files, `.rays` and `.hits` files, index specs (`bvh:leaf_size=2`) and scene specs
//! (`soup:n=10,seed=3`). Each gets its corpus from `tests/fuzz-corpus/<target>/` (small valid
//! `ok-*` and broken `bad-*` inputs), mutated byte by byte (replaced, inserted, removed,
//! truncated), and arbitrary bytes. The property: no panic, an error or a value.
//!
//! 64 cases per target by default; CI's fuzz step and a longer local run set `PROPTEST_CASES`
//! (`PROPTEST_CASES=5000 cargo test --release --test it fuzz::`).

use accelbench::geometry::TriangleKernelKind;
use accelbench::index::{IndexSpec, build_index};
use accelbench::rays::{read_hits, read_rays};
use accelbench::scene::generators::GeneratorSpec;
use accelbench::scene::{generators, load_scene};
use proptest::prelude::*;
use proptest::sample::Index;
use std::path::{Path, PathBuf};

fn config() -> ProptestConfig {
    ProptestConfig {
        failure_persistence: None,
        ..crate::common::proptest_config(64)
    }
}

/// The corpus of `target`: `(file name, bytes)` sorted by name.
fn corpus(target: &str) -> Vec<(String, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz-corpus")
        .join(target);
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| {
            let p = e.unwrap().path();
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&p).unwrap())
        })
        .collect();
    v.sort();
    assert!(v.len() >= 4, "{target}: a corpus of at least 4 inputs");
    v
}

/// One byte edit: replace, insert or remove at a position.
#[derive(Debug, Clone)]
enum Edit {
    Replace(Index, u8),
    Insert(Index, u8),
    Remove(Index),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Edit::Replace(i, b)),
        (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Edit::Insert(i, b)),
        any::<Index>().prop_map(Edit::Remove),
    ]
}

fn apply(mut b: Vec<u8>, edits: &[Edit], cut: Option<Index>) -> Vec<u8> {
    for e in edits {
        match e {
            Edit::Replace(i, x) if !b.is_empty() => {
                let at = i.index(b.len());
                b[at] = *x;
            }
            Edit::Insert(i, x) => {
                let at = i.index(b.len() + 1);
                b.insert(at, *x);
            }
            Edit::Remove(i) if !b.is_empty() => {
                b.remove(i.index(b.len()));
            }
            _ => {}
        }
    }
    if let Some(c) = cut {
        b.truncate(c.index(b.len() + 1));
    }
    b
}

/// Inputs for `target`: mostly its corpus mutated, sometimes arbitrary bytes.
fn inputs(target: &str) -> impl Strategy<Value = Vec<u8>> {
    let seeds: Vec<Vec<u8>> = corpus(target).into_iter().map(|(_, b)| b).collect();
    let mutated = (
        any::<Index>(),
        prop::collection::vec(edit(), 0..6),
        prop::option::weighted(0.2, any::<Index>()),
    )
        .prop_map(move |(pick, edits, cut)| apply(pick.get(&seeds).clone(), &edits, cut));
    prop_oneof![4 => mutated, 1 => prop::collection::vec(any::<u8>(), 0..256)]
}

/// A scratch folder with `name` written from each case, and a one-triangle `tri.obj` beside it
/// for scene files that name a mesh.
struct Scratch {
    _dir: tempfile::TempDir,
    file: PathBuf,
}

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("tri.obj"),
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        )
        .unwrap();
        let file = dir.path().join(name);
        Scratch { _dir: dir, file }
    }

    fn with(&self, bytes: &[u8]) -> &str {
        std::fs::write(&self.file, bytes).unwrap();
        self.file.to_str().unwrap()
    }
}

/// Whether a corpus file is a valid input (`ok-*`) or a broken one (`bad-*`).
fn expect_ok(name: &str) -> bool {
    assert!(
        name.starts_with("ok-") || name.starts_with("bad-"),
        "{name}: name it ok-* or bad-*"
    );
    name.starts_with("ok-")
}

/// Every corpus file of `target` as its name says: valid inputs load, broken ones are refused.
fn corpus_as_named(target: &str, load: impl Fn(&[u8]) -> Result<(), String>) {
    for (name, bytes) in corpus(target) {
        let got = load(&bytes);
        assert_eq!(got.is_ok(), expect_ok(&name), "{target}/{name}: {got:?}");
    }
}

fn scene_file(s: &Scratch, bytes: &[u8]) -> Result<(), String> {
    load_scene(s.with(bytes))
        .map(drop)
        .map_err(|e| e.to_string())
}

fn rays_file(s: &Scratch, bytes: &[u8]) -> Result<(), String> {
    read_rays(Path::new(s.with(bytes)))
        .map(drop)
        .map_err(|e| e.to_string())
}

fn hits_file(s: &Scratch, bytes: &[u8]) -> Result<(), String> {
    read_hits(Path::new(s.with(bytes)))
        .map(drop)
        .map_err(|e| e.to_string())
}

/// Whether every number among an index spec's parameters is small enough that building it on
/// a tiny scene is quick (a fuzzed `res = [99999, 99999, 99999]` is a valid, huge grid).
fn small(v: &toml::Value) -> bool {
    match v {
        toml::Value::Integer(i) => i.abs() <= 64,
        toml::Value::Float(f) => !f.is_finite() || f.abs() <= 64.0,
        toml::Value::Array(a) => a.len() <= 4 && a.iter().all(small),
        toml::Value::Table(t) => t.values().all(small),
        _ => true,
    }
}

/// Parses an index spec and, when its numbers are small, builds it on a tiny scene.
fn index_spec(bytes: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(bytes);
    let spec: IndexSpec = text.trim().parse().map_err(|e| format!("{e}"))?;
    if !spec.params.values().all(small) {
        return Ok(());
    }
    let scene = generators::generate("icosphere", 40, 1).unwrap();
    build_index(&spec, &scene.geometry(), TriangleKernelKind::Exact)
        .map(drop)
        .map_err(|e| e.to_string())
}

/// Parses a scene spec and, when it is small, generates it.
fn scene_spec(bytes: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(bytes);
    let spec = GeneratorSpec::parse(text.trim()).map_err(|e| e.to_string())?;
    if spec.n > 2000 {
        return Ok(());
    }
    spec.generate().map(drop).map_err(|e| e.to_string())
}

/// The targets whose inputs are files: corpus folder, the scratch file's name (its extension
/// picks the loader), and the reader.
type FileReader = fn(&Scratch, &[u8]) -> Result<(), String>;
const FILE_TARGETS: [(&str, &str, FileReader); 6] = [
    ("obj", "m.obj", scene_file),
    ("ply", "m.ply", scene_file),
    ("glb", "m.glb", scene_file),
    ("toml", "scene.toml", scene_file),
    ("rays", "r.rays", rays_file),
    ("hits", "h.hits", hits_file),
];

/// Loads `bytes` as an input of `target` (a file target through a fresh scratch file), its
/// error as text.
fn load_as(target: &str, bytes: &[u8]) -> Result<(), String> {
    match FILE_TARGETS.iter().find(|(t, ..)| *t == target) {
        Some((_, name, read)) => read(&Scratch::new(name), bytes),
        None if target == "index-spec" => index_spec(bytes),
        None => scene_spec(bytes),
    }
}

#[test]
fn every_corpus_input_is_as_its_name_says() {
    for (target, name, read) in FILE_TARGETS {
        let s = Scratch::new(name);
        corpus_as_named(target, |b| read(&s, b));
    }
    corpus_as_named("index-spec", index_spec);
    corpus_as_named("scene-spec", scene_spec);
}

/// A proptest per target (`test name: target`): mutated corpus inputs and arbitrary bytes
/// never make its loader panic.
macro_rules! never_panic {
    ($($test:ident: $target:literal),* $(,)?) => {
        proptest! {
            #![proptest_config(config())]
            $(
                #[test]
                fn $test(bytes in inputs($target)) {
                    let _ = load_as($target, &bytes);
                }
            )*
        }
    };
}

never_panic! {
    obj_files_never_panic: "obj",
    ply_files_never_panic: "ply",
    glb_files_never_panic: "glb",
    scene_files_never_panic: "toml",
    rays_files_never_panic: "rays",
    hits_files_never_panic: "hits",
    index_specs_never_panic: "index-spec",
    scene_specs_never_panic: "scene-spec",
}
