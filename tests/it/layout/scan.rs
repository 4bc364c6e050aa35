//! Reads a crate's `src/**/*.rs` into a graph of which file imports which: every path that
//! starts with `crate::`, `$crate::`, `super::`, `self::` or a child module declared in the
//! file (in `use` items and in code, macro bodies included; not in comments or strings),
//! resolved to the file that defines the item, through the `pub use` re-exports of the files on
//! the way (so `crate::index::Index` leads to the file that defines `Index`, not to
//! `index/mod.rs`). A module's `pub use` of its own descendants is a re-export, not an import;
//! an inline `#[cfg(test)]` module is left out (unit tests may import what they test).

use super::cycles::Graph;
use super::tokens::{Tok, tokens};
use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// One module file: its module path and the paths it names.
struct ModFile {
    /// Relative to `src/`, with `/` separators (`index/bvh/walk.rs`).
    file: String,
    /// Module path (`["index", "bvh", "walk"]`; `[]` for `lib.rs`).
    module: Vec<String>,
    uses: Vec<Use>,
}

/// A path the file names: absolute module path segments, whether it is a public `use` (a
/// re-export), and the name it is visible under in the file (`None` for a glob or an inline
/// path).
struct Use {
    path: Vec<String>,
    public: bool,
    name: Option<String>,
}

/// The file-level import graph of the crate whose sources are under `src` (`main.rs` left out:
/// it is another crate). Nodes are file names relative to `src`.
pub fn file_graph(src: &Path) -> Graph {
    let mut files = Vec::new();
    collect(src, src, &mut files);
    let files = with_module_paths(files);
    let by_module: BTreeMap<&[String], usize> = files
        .iter()
        .enumerate()
        .map(|(i, f)| (f.module.as_slice(), i))
        .collect();
    let mut graph = Graph::new();
    for f in &files {
        let edges = graph.entry(f.file.clone()).or_default();
        for u in &f.uses {
            let Some(target) = resolve(&files, &by_module, &u.path, 0) else {
                continue;
            };
            let t = &files[target];
            let re_export = u.public && t.module.starts_with(&f.module);
            if t.file != f.file && !re_export && !t.module.is_empty() {
                edges.insert(t.file.clone());
            }
        }
    }
    graph
}

/// The folder-level graph of a file graph: a file's folder is the directory holding it
/// (`index/bvh` for `index/bvh/walk.rs`, `""` for `random.rs`).
pub fn folder_graph(files: &Graph) -> Graph {
    let folder = |f: &str| f.rsplit_once('/').map_or("", |(d, _)| d).to_owned();
    let mut graph = Graph::new();
    for (f, targets) in files {
        let from = folder(f);
        let edges = graph.entry(from.clone()).or_default();
        edges.extend(targets.iter().map(|t| folder(t)).filter(|t| *t != from));
    }
    graph
}

/// The file defining the item at absolute `path`: the deepest module file on the path, or,
/// when the next segment is a name that file re-exports, the file its `pub use` leads to.
fn resolve(
    files: &[ModFile],
    by_module: &BTreeMap<&[String], usize>,
    path: &[String],
    depth: usize,
) -> Option<usize> {
    let (module, at) = (0..=path.len())
        .rev()
        .find_map(|n| by_module.get(&path[..n]).map(|&i| (n, i)))?;
    let Some(item) = path.get(module) else {
        return Some(at);
    };
    let re_export = files[at]
        .uses
        .iter()
        .find(|u| u.public && u.name.as_ref() == Some(item));
    match re_export {
        Some(u) if depth < 16 => {
            let mut next = u.path.clone();
            next.extend_from_slice(&path[module + 1..]);
            resolve(files, by_module, &next, depth + 1).or(Some(at))
        }
        _ => Some(at),
    }
}

/// Every `.rs` file under `dir`, as (name relative to `src`, text).
fn collect(src: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            collect(src, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let name = path.strip_prefix(src).expect("under src");
            let name = name.to_string_lossy().replace('\\', "/");
            if name != "main.rs" {
                let text = fs::read_to_string(&path).expect("a source file");
                out.push((name, text));
            }
        }
    }
}

/// The module path of every file (`#[path]` attributes honoured), and its parsed paths.
fn with_module_paths(files: Vec<(String, String)>) -> Vec<ModFile> {
    let mut modules: Vec<Vec<String>> = files.iter().map(|(f, _)| default_module(f)).collect();
    // `#[path = "x.rs"] mod name;` in `dir/f.rs`: `dir/x.rs` is module `f::name`.
    for (i, (file, text)) in files.iter().enumerate() {
        let dir = file.rsplit_once('/').map_or("", |(d, _)| d);
        for (name, p) in child_mods(text) {
            let Some(p) = p else { continue };
            let target = if dir.is_empty() {
                p
            } else {
                format!("{dir}/{p}")
            };
            if let Some(j) = files.iter().position(|(f, _)| *f == target) {
                let mut module = modules[i].clone();
                module.push(name);
                modules[j] = module;
            }
        }
    }
    files
        .into_iter()
        .zip(modules)
        .map(|((file, text), module)| {
            let uses = parse(&text, &module);
            ModFile { file, module, uses }
        })
        .collect()
}

/// The module path a file's name gives (`a/b.rs` and `a/b/mod.rs` are `a::b`, `lib.rs` the
/// root).
fn default_module(file: &str) -> Vec<String> {
    let stem = file.strip_suffix(".rs").expect("a .rs file");
    let mut parts: Vec<String> = stem.split('/').map(str::to_owned).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

/// The paths a file of module path `module` names.
fn parse(text: &str, module: &[String]) -> Vec<Use> {
    let toks = tokens(text);
    let children = child_mods(text);
    let child_names: Vec<&str> = children.iter().map(|(n, _)| n.as_str()).collect();
    let mut uses = Vec::new();
    // Inline modules (`mod tests { ... }`) open at a brace depth: their names and depths.
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut i = 0;
    while i < toks.len() {
        let here = || {
            let mut m = module.to_vec();
            m.extend(inline.iter().map(|(n, _)| n.clone()));
            m
        };
        match &toks[i] {
            Tok::Open => depth += 1,
            Tok::Close => {
                depth = depth.saturating_sub(1);
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
            }
            Tok::Ident(k) if k == "mod" => {
                if let (Some(Tok::Ident(name)), Some(Tok::Open)) =
                    (toks.get(i + 1), toks.get(i + 2))
                {
                    if cfg_test(&toks[..i]) {
                        i = matching_close(&toks, i + 2) + 1;
                        continue;
                    }
                    inline.push((name.clone(), depth));
                    depth += 1;
                    i += 3;
                    continue;
                }
            }
            Tok::Ident(k) if k == "use" => {
                let public = i > 0 && is_public(&toks[..i]);
                let end = (i..toks.len())
                    .find(|&j| toks[j] == Tok::Semi)
                    .unwrap_or(toks.len());
                let here = here();
                let top_level = inline.is_empty();
                let mut found = Vec::new();
                use_tree(&toks[i + 1..end], Vec::new(), &mut found);
                for (path, name) in found {
                    let relative_to_child = top_level && child_names.contains(&path[0].as_str());
                    if let Some(path) = absolute(&path, &here, module, relative_to_child) {
                        uses.push(Use { path, public, name });
                    }
                }
                i = end + 1;
                continue;
            }
            Tok::Ident(first) => {
                let after_path = i > 0 && toks[i - 1] == Tok::Path;
                let starts = matches!(first.as_str(), "crate" | "super" | "self")
                    || (inline.is_empty() && child_names.contains(&first.as_str()));
                if starts && !after_path && toks.get(i + 1) == Some(&Tok::Path) {
                    let mut path = vec![first.clone()];
                    let mut j = i + 1;
                    while toks.get(j) == Some(&Tok::Path) {
                        match toks.get(j + 1) {
                            Some(Tok::Ident(s)) => path.push(s.clone()),
                            _ => break,
                        }
                        j += 2;
                    }
                    let child = !matches!(first.as_str(), "crate" | "super" | "self");
                    if let Some(path) = absolute(&path, &here(), module, child) {
                        uses.push(Use {
                            path,
                            public: false,
                            name: None,
                        });
                    }
                    i = j;
                    continue;
                }
            }
            _ => {}
        }
        i += 1;
    }
    uses
}

/// Whether the item after `before` carries `#[cfg(test)]` (a unit-test module: test code may
/// import what it tests from anywhere, and is no part of the library's shape).
fn cfg_test(before: &[Tok]) -> bool {
    let attr = [
        Tok::Other('#'),
        Tok::Other('['),
        Tok::Ident("cfg".into()),
        Tok::Other('('),
        Tok::Ident("test".into()),
        Tok::Other(')'),
        Tok::Other(']'),
    ];
    before.ends_with(&attr)
}

/// The index of the brace that closes the one opened at `open`.
fn matching_close(toks: &[Tok], open: usize) -> usize {
    let mut depth = 0;
    for (j, t) in toks.iter().enumerate().skip(open) {
        match t {
            Tok::Open => depth += 1,
            Tok::Close if depth == 1 => return j,
            Tok::Close => depth -= 1,
            _ => {}
        }
    }
    toks.len()
}

/// Whether the `use` ending `before` is public (`pub use`, `pub(crate) use`, ...).
fn is_public(before: &[Tok]) -> bool {
    match before {
        [.., Tok::Ident(p)] => p == "pub",
        [.., Tok::Ident(p), Tok::Other('('), _, Tok::Other(')')] => p == "pub",
        [.., Tok::Ident(p), Tok::Other('('), _, _, _, Tok::Other(')')] => p == "pub",
        _ => false,
    }
}

/// The leaves of a use tree `toks` under `prefix`: (path, visible name; `None` for a glob).
fn use_tree(toks: &[Tok], prefix: Vec<String>, out: &mut Vec<(Vec<String>, Option<String>)>) {
    let mut path = prefix;
    let mut i = 0;
    while i < toks.len() {
        match &toks[i] {
            Tok::Ident(s) if s == "as" => {
                if let (Some(Tok::Ident(alias)), Some((_, name))) =
                    (toks.get(i + 1), out.last_mut())
                {
                    *name = Some(alias.clone());
                }
                return;
            }
            Tok::Ident(s) if s == "self" && !path.is_empty() => {
                let name = path.last().cloned();
                out.push((path, name));
                return;
            }
            Tok::Ident(s) => {
                path.push(s.clone());
                if !matches!(toks.get(i + 1), Some(Tok::Path)) {
                    out.push((path.clone(), Some(s.clone())));
                }
            }
            Tok::Star => {
                out.push((path, None));
                return;
            }
            Tok::Open => {
                let mut depth = 0;
                let mut start = i + 1;
                for j in i..toks.len() {
                    match toks[j] {
                        Tok::Open => depth += 1,
                        Tok::Close => depth -= 1,
                        Tok::Comma if depth == 1 => {
                            use_tree(&toks[start..j], path.clone(), out);
                            start = j + 1;
                        }
                        _ => {}
                    }
                    if depth == 0 {
                        use_tree(&toks[start..j], path.clone(), out);
                        return;
                    }
                }
                return;
            }
            _ => {}
        }
        i += 1;
    }
}

/// `path` as an absolute module path, seen from the (possibly inline) module `here` inside the
/// file of module `file_module`; `child` when its first segment is a child module of the file.
/// `None` for a path into another crate.
fn absolute(
    path: &[String],
    here: &[String],
    file_module: &[String],
    child: bool,
) -> Option<Vec<String>> {
    let (mut base, mut rest) = match path.first().map(String::as_str) {
        Some("crate") => (Vec::new(), &path[1..]),
        Some("self") => (here.to_vec(), &path[1..]),
        Some("super") => (here.to_vec(), path),
        _ if child => (file_module.to_vec(), path),
        _ => return None,
    };
    while rest.first().map(String::as_str) == Some("super") {
        base.pop()?;
        rest = &rest[1..];
    }
    base.extend_from_slice(rest);
    Some(base)
}

/// The file's `mod NAME;` declarations and their `#[path = "..."]` files.
fn child_mods(text: &str) -> Vec<(String, Option<String>)> {
    let mut out = Vec::new();
    let mut path_attr = None;
    for line in text.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("#[path = \"") {
            path_attr = rest.split('"').next().map(str::to_owned);
            continue;
        }
        let decl = line
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub(super) ")
            .trim_start_matches("pub ");
        if let Some(name) = decl.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
            out.push((name.trim().to_owned(), path_attr.take()));
        } else if !line.starts_with("#[") {
            path_attr = None;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(text: &str, module: &[&str]) -> Vec<String> {
        let module: Vec<String> = module.iter().map(|s| s.to_string()).collect();
        parse(text, &module)
            .into_iter()
            .map(|u| u.path.join("::") + if u.public { " pub" } else { "" })
            .collect()
    }

    #[test]
    fn use_trees_inline_paths_and_inline_modules_resolve() {
        let text = r#"
            use super::a::{self, b::C, d as e};
            pub use child::Thing;
            use crate::x::*; // crate::not_this
            mod child;
            fn f() { let s = "crate::nor_this"; crate::y::z(); child::g(); }
            mod inner { use super::*; use super::super::q; }
            #[cfg(test)]
            mod tests { use crate::skipped; }
        "#;
        assert_eq!(
            names(text, &["m", "n"]),
            [
                "m::a",
                "m::a::b::C",
                "m::a::d",
                "m::n::child::Thing pub",
                "x",
                "y::z",
                "m::n::child::g",
                "m::n",
                "m::q",
            ]
        );
    }
}
