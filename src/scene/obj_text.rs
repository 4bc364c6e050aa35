//! The text of an OBJ file as the loader's scans and tobj read it: a UTF-8 byte-order mark
//! dropped, every `#` comment cut to the end of its line (a trailing comment is then accepted on
//! every statement alike), and bytes that are not UTF-8 accepted only where the loader ignores
//! them (object, group and material names, comments), where they become U+FFFD.

use super::SceneError;
use std::io::Read;
use std::path::Path;

/// Statements whose arguments are names, which the loader ignores (so their bytes may be any
/// encoding, e.g. Latin-1 from older exporters).
const NAME_STATEMENTS: &[&str] = &["o", "g", "usemtl", "mtllib", "s", "mg"];

/// Bytes at the start of a file checked for a NUL byte: OBJ text has none, and a binary file (a
/// PLY or glTF mesh, an archive, zeros) almost always has one within them.
const SNIFF_BYTES: u64 = 64 * 1024;

/// Reads `path` and prepares its text (see the module doc). Errors: unreadable file, a binary
/// file (a NUL byte in its first [`SNIFF_BYTES`], found before the rest is read), or bytes that
/// are not UTF-8 in a statement the loader reads, with the line. Holds the file's bytes once
/// (twice while cutting comments).
pub fn read_obj_text(path: &Path) -> Result<String, SceneError> {
    let io = |cause| SceneError::Io {
        path: path.to_owned(),
        cause,
    };
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    (&mut file)
        .take(SNIFF_BYTES)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if let Some(at) = bytes.iter().position(|&b| b == 0) {
        return Err(SceneError::Obj {
            path: path.to_owned(),
            message: format!(
                "byte {at} is a NUL byte: this is a binary file, not OBJ text; give a Wavefront .obj (text) file"
            ),
        });
    }
    file.read_to_end(&mut bytes).map_err(io)?;
    let mut text = match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let lossy = String::from_utf8_lossy(e.as_bytes()).into_owned();
            check_replaced(path, &without_comments(&lossy))?
        }
    };
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    Ok(match text.contains('#') {
        true => without_comments(&text),
        false => text,
    })
}

/// `text` with each line cut at its first `#`.
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        match line.find('#') {
            Some(i) => {
                out.push_str(&line[..i]);
                if line.ends_with('\n') {
                    out.push('\n');
                }
            }
            None => out.push_str(line),
        }
    }
    out
}

/// `text` (comments already cut) when every line with a replaced byte is a name statement.
fn check_replaced(path: &Path, text: &str) -> Result<String, SceneError> {
    for (n, line) in text.lines().enumerate() {
        let word = line.split_whitespace().next().unwrap_or("");
        if line.contains('\u{fffd}') && !NAME_STATEMENTS.contains(&word) {
            return Err(SceneError::Obj {
                path: path.to_owned(),
                message: format!(
                    "line {}: bytes that are not UTF-8 text in a '{word}' statement; save the file as UTF-8 (or ASCII)",
                    n + 1
                ),
            });
        }
    }
    Ok(text.to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn text_of(bytes: &[u8]) -> Result<String, SceneError> {
        let mut f = tempfile::Builder::new().suffix(".obj").tempfile().unwrap();
        f.write_all(bytes).unwrap();
        read_obj_text(f.path())
    }

    #[test]
    fn comments_are_cut_everywhere_and_the_mark_dropped() {
        let t = text_of("\u{feff}v 0 0 0 # a\n# all\nf 1 2 3#b\n".as_bytes()).unwrap();
        assert_eq!(t, "v 0 0 0 \n\nf 1 2 3\n");
    }

    #[test]
    fn a_binary_file_is_refused_by_its_first_nul_byte() {
        match text_of(b"v 0 0 0\n\0\0\0") {
            Err(SceneError::Obj { message, .. }) => {
                assert!(message.starts_with("byte 8 is a NUL byte"), "{message}")
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn latin1_is_accepted_in_names_only() {
        let t = text_of(b"o caf\xe9\nusemtl m\xfcll\nv 0 0 0 # \xe9\n").unwrap();
        assert!(
            t.starts_with("o caf\u{fffd}\n") && t.ends_with("v 0 0 0 \n"),
            "{t}"
        );
        match text_of(b"v 0 0 0\nv 1 \xe9 0\n") {
            Err(SceneError::Obj { message, .. }) => {
                assert!(message.starts_with("line 2: "), "{message}")
            }
            other => panic!("{other:?}"),
        }
    }
}
