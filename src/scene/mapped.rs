//! A mesh file's bytes, memory-mapped rather than copied: the binary loaders (PLY, glTF) read
//! them in place, so a large file is never held twice and pages are read as they are touched.

use super::SceneError;
use std::path::Path;

/// The bytes of a file, mapped read-only (an empty file is an empty slice).
///
/// The mapping assumes that nothing truncates or rewrites the file while it is loaded (as
/// every memory-mapping reader does); the loaders copy what they keep out of it.
pub struct Mapped(Option<memmap2::Mmap>);

impl Mapped {
    /// Maps `path`. Errors: a missing or unreadable file, or a folder.
    pub fn open(path: &Path) -> Result<Mapped, SceneError> {
        let io = |cause| SceneError::Io {
            path: path.to_owned(),
            cause,
        };
        let file = std::fs::File::open(path).map_err(io)?;
        let meta = file.metadata().map_err(io)?;
        if meta.is_dir() {
            return Err(io(std::io::ErrorKind::IsADirectory.into()));
        }
        if meta.len() == 0 {
            return Ok(Mapped(None));
        }
        // SAFETY: read-only, private to this process; see the type's doc on concurrent writers.
        let map = unsafe { memmap2::Mmap::map(&file) }.map_err(io)?;
        Ok(Mapped(Some(map)))
    }

    pub fn bytes(&self) -> &[u8] {
        self.0.as_deref().unwrap_or(&[])
    }
}
