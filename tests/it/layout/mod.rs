//! The source tree's shape, checked: no two files or folders of `src/` import each other (no
//! import loop of any length, at either level), and no top-level folder imports one that
//! `ARCHITECTURE.md`'s layer table does not let it import. A failure names the loop or the
//! import.

mod cycles;
mod layers;
mod scan;
mod tokens;

use cycles::{Graph, cycles};
use std::path::PathBuf;

/// The crate root (where `Cargo.toml` is).
fn root() -> PathBuf {
    option_env!("CARGO_MANIFEST_DIR").map_or_else(|| PathBuf::from("."), PathBuf::from)
}

/// The loops of `graph`, one per line (`a -> b -> a`).
fn loops(graph: &Graph) -> String {
    cycles(graph)
        .iter()
        .map(|c| format!("  {}\n", c.join(" -> ")))
        .collect()
}

#[test]
fn no_two_files_import_each_other() {
    let files = scan::file_graph(&root().join("src"));
    assert!(files.len() > 100, "found only {} files", files.len());
    let found = loops(&files);
    assert!(found.is_empty(), "import loops between files:\n{found}");
}

#[test]
fn no_two_folders_import_each_other() {
    let folders = scan::folder_graph(&scan::file_graph(&root().join("src")));
    let found = loops(&folders);
    assert!(found.is_empty(), "import loops between folders:\n{found}");
}

#[test]
fn every_folder_imports_only_the_layers_it_may() {
    let doc = std::fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let layers = layers::layers(&doc);
    let layer = |file: &str| {
        let top = file.split('/').next().unwrap_or(file);
        top.strip_suffix(".rs").unwrap_or(top).to_owned()
    };
    let mut wrong = String::new();
    for (file, targets) in scan::file_graph(&root().join("src")) {
        let from = layer(&file);
        let Some(allowed) = layers.get(&from) else {
            assert_eq!(
                from, "lib",
                "{file} is in no layer of ARCHITECTURE.md's table"
            );
            continue;
        };
        for t in targets {
            let to = layer(&t);
            if to != from && !allowed.contains(&to) {
                wrong.push_str(&format!(
                    "  {file} imports {t} ({from} may not import {to})\n"
                ));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layer table:\n{wrong}"
    );
}

/// A synthetic loop between two folders is found through the file graph.
#[test]
fn a_loop_between_two_folders_is_found() {
    let mut files = Graph::new();
    for (a, b) in [
        ("x/a.rs", "y/b.rs"),
        ("y/c.rs", "x/d.rs"),
        ("x/d.rs", "z.rs"),
    ] {
        files.entry(a.into()).or_default().insert(b.into());
    }
    assert!(cycles(&files).is_empty(), "no loop between the files");
    assert_eq!(
        cycles(&scan::folder_graph(&files)),
        vec![vec!["x", "y", "x"]]
    );
}

/// A loop written in sources is found: two files of a throwaway tree import each other through
/// a re-export, and a third imports one of them without closing a loop.
#[test]
fn a_loop_in_source_files_is_found() {
    let dir = std::env::temp_dir().join(format!("accelbench-layout-{}", std::process::id()));
    let src = dir.join("src");
    std::fs::create_dir_all(src.join("a")).expect("a temporary folder");
    for (file, text) in [
        ("lib.rs", "pub mod a;\npub mod c;\n"),
        ("a/mod.rs", "mod b;\nmod d;\npub use b::Thing;\n"),
        ("a/b.rs", "use super::d::Other;\npub struct Thing;\n"),
        (
            "a/d.rs",
            "use crate::a::Thing; // via the re-export\npub struct Other;\n",
        ),
        ("c.rs", "use crate::a::Thing;\n"),
    ] {
        std::fs::write(src.join(file), text).expect("a temporary file");
    }
    let found = cycles(&scan::file_graph(&src));
    std::fs::remove_dir_all(&dir).expect("removing the temporary folder");
    assert_eq!(found, vec![vec!["a/b.rs", "a/d.rs", "a/b.rs"]]);
}
