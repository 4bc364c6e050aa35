//! The buffers of a glTF document: the BIN chunk of a `.glb`, or `.bin` files beside the
//! `.gltf` (memory-mapped), each checked to hold the `byteLength` the document declares.

use crate::scene::SceneError;
use crate::scene::error::Location;
use crate::scene::mapped::Mapped;
use gltf::buffer::Source;
use std::path::{Path, PathBuf};

/// One buffer's bytes (at least its declared `byteLength`), the file they are in, and the
/// offset of its first byte in that file (for error locations).
pub struct Buffer<'a> {
    pub bytes: &'a [u8],
    pub file: &'a Path,
    pub base: usize,
}

/// Every buffer of a document, in document order.
pub struct Buffers<'a> {
    glb: Option<(&'a [u8], usize)>,
    main: &'a Path,
    /// An external file's mapping and path, per buffer (`None`: the GLB's BIN chunk).
    files: Vec<Option<(Mapped, PathBuf)>>,
}

impl<'a> Buffers<'a> {
    /// Opens every buffer of `doc`, loaded from `main` (a `.glb` with BIN chunk `glb` at its
    /// offset, or a `.gltf`). Errors: a missing or short buffer, an embedded `data:` URI.
    pub fn load(
        doc: &gltf::Document,
        main: &'a Path,
        glb: Option<(&'a [u8], usize)>,
    ) -> Result<Buffers<'a>, SceneError> {
        let bad = |i: usize, message: String| SceneError::Mesh {
            path: main.to_owned(),
            format: "glTF",
            at: Location::Json(format!("buffers[{i}]")),
            message,
        };
        let mut files = Vec::new();
        for b in doc.buffers() {
            let i = b.index();
            let (len, file) = match b.source() {
                Source::Bin => match glb {
                    Some((bin, _)) => (bin.len(), None),
                    None => return Err(bad(i, "the buffer has no uri, so it is a GLB's BIN chunk, which this file does not have; give its .bin file as \"uri\"".into())),
                },
                Source::Uri(uri) if uri.starts_with("data:") => {
                    return Err(bad(i, "the buffer is embedded as a data: URI, which is not supported; save the model as .glb or with a separate .bin file".into()));
                }
                Source::Uri(uri) => {
                    let path = main.parent().unwrap_or(Path::new("")).join(percent_decoded(uri));
                    let map = Mapped::open(&path)?;
                    (map.bytes().len(), Some((map, path)))
                }
            };
            if len < b.length() {
                return Err(bad(
                    i,
                    format!(
                        "the buffer declares byteLength {} but its data has {len} bytes; the .bin is truncated or belongs to another model",
                        b.length()
                    ),
                ));
            }
            files.push(file);
        }
        Ok(Buffers { glb, main, files })
    }

    /// Buffer `i` (an index the document's validation checked).
    pub fn get(&self, i: usize) -> Buffer<'_> {
        match &self.files[i] {
            Some((map, path)) => Buffer {
                bytes: map.bytes(),
                file: path,
                base: 0,
            },
            None => {
                let (bytes, base) = self.glb.expect("checked when loaded");
                Buffer {
                    bytes,
                    file: self.main,
                    base,
                }
            }
        }
    }
}

/// A relative URI's path with its `%XX` escapes decoded (`my%20model.bin`).
fn percent_decoded(uri: &str) -> String {
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = b
            .get(i + 1..i + 3)
            .and_then(|h| u8::from_str_radix(std::str::from_utf8(h).ok()?, 16).ok());
        match (b[i], hex) {
            (b'%', Some(x)) => {
                out.push(x);
                i += 3;
            }
            (c, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    #[test]
    fn escapes_are_decoded() {
        assert_eq!(super::percent_decoded("my%20model.bin"), "my model.bin");
        assert_eq!(super::percent_decoded("a%zz%2"), "a%zz%2");
    }
}
