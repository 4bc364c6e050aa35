//! The statements of an OBJ file that are not in the format at all (a typo such as `F 1 2 3` or
//! `fo 1 2 3`): tobj drops such lines without a word, so the loader warns about each kind once,
//! with its first line.

/// Every statement keyword of the OBJ format (geometry, grouping, display and free-form
/// attributes); the loader reads `v` and `f` and ignores the rest, on purpose.
const KNOWN: &[&str] = &[
    "v",
    "vt",
    "vn",
    "vp",
    "f",
    "l",
    "p",
    "o",
    "g",
    "s",
    "mg",
    "usemtl",
    "mtllib",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "shadow_obj",
    "trace_obj",
    "maplib",
    "usemap",
    "ctech",
    "stech",
    "call",
    "csh",
];

/// Each statement keyword of `text` that the OBJ format does not have, once, with the
/// (1-based) number of the first line it starts, in order of first appearance. Blank lines and
/// comments (`#` first) are statements of none.
pub fn unknown_statements(text: &str) -> Vec<(String, usize)> {
    let mut found: Vec<(String, usize)> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let Some(word) = line.split_whitespace().next() else {
            continue;
        };
        if word.starts_with('#') || KNOWN.contains(&word) || found.iter().any(|(w, _)| w == word) {
            continue;
        }
        found.push((word.to_owned(), n + 1));
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typos_are_found_once_each_with_their_first_line() {
        let text = "# a comment\nv 0 0 0\nF 2 4 3\n\nfo 2 4 3\nF 1 2 3\ng part\nusemtl red\n";
        let found = unknown_statements(text);
        assert_eq!(found, vec![("F".to_owned(), 3), ("fo".to_owned(), 5)]);
        assert!(unknown_statements("v 0 0 0\nvn 0 0 1\nf 1 1 1\ns off\n#x\n").is_empty());
    }
}
