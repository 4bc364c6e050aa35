//! The size and shape of a built index ([`IndexInfo`]), as reports show it.

use serde::Serialize;
use std::time::Duration;

/// Size and shape of a built index, for reports.
#[derive(Debug, Clone, Default, Serialize)]
pub struct IndexInfo {
    /// All nodes (or cells), leaves included.
    pub nodes: usize,
    /// Leaves (or non-empty cells).
    pub leaves: usize,
    /// Maximum depth (1 for a flat structure).
    pub depth: usize,
    /// Heap bytes the index owns (nodes, cell arrays, primitive id arrays), excluding the scene.
    pub memory_bytes: usize,
    /// The heap's high-water mark during the build, in bytes above what was held before it:
    /// the finished structure and every temporary of its build. The registry measures it
    /// ([`crate::heap_meter::peak_during`]); an index allocating outside Rust's allocator
    /// ([`crate::index::Index::FOREIGN_HEAP`]) gives its own figure, or `None`: not measured.
    pub peak_build_bytes: Option<usize>,
    /// Primitive references stored (an id in a leaf or cell counts once per leaf or cell).
    pub prim_refs: usize,
    /// Build time, measured by the registry around [`crate::index::Index::build`].
    pub build_time: Duration,
    /// GPU indices only: the part of `build_time` spent uploading the structure to the device.
    pub upload_time: Option<Duration>,
    /// Structure-specific figures (name, value), e.g. `("empty_cells", 0.4)`.
    pub extra: Vec<(String, f64)>,
    /// `true` for peers whose traversal reports nothing to [`crate::index::Stats`] (Embree, tinybvh): reports
    /// show their tests and steps per ray as missing, not 0.
    pub uncounted: bool,
}
