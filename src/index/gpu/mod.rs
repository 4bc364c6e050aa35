//! The same structures on a GPU (feature `gpu`): WGSL compute shaders over buffers uploaded
//! from our structures, one ray per thread, a batch per dispatch, through `wgpu` (Vulkan,
//! Metal, DX12; a software Vulkan driver such as lavapipe where there is no GPU).
//!
//! - `gpu-cwbvh`: our SAH tree collapsed into the compressed 8-wide nodes of Ylitie, Karras
//!   & Laine (2017) (`cwbvh_layout`), octant-ordered children, a stack of node groups;
//! - `gpu-bvh2`: our binary `bvh` as it is (`bvh2`), the baseline every GPU BVH paper starts
//!   from;
//! - `gpu-grid`: our uniform grid's cells and references with a 3D-DDA per thread (`grid`).
//!
//! The shaders do their own `f32` watertight test (`shaders/common.wgsl`): WGSL has no `f64`
//! for the exact-zero edge recomputation, and its division is accurate to 2.5 ulp. So their
//! hits can differ from ours in the last bits of `t`, and the rows are checked like peers'
//! ([`crate::index::Kind::Gpu`]): every disagreement with brute force classified (tie, `t off`,
//! wrong), never failed. They trace only as a batch: their rows are `INDEX+stream`.
//!
//! The build time is our structure's build plus its upload; the upload alone is
//! `IndexInfo::upload_time` (`gpu_upload_ms` in `results.csv`). `memory_bytes` is the structure's bytes on the device. The kernel time
//! of a batch (timestamp queries, where the adapter has them) is
//! [`crate::index::TraceIndex::kernel_time`].

mod bvh2;
mod context;
mod cwbvh;
mod cwbvh_layout;
mod gpu_index;
mod grid;
mod program;

pub use bvh2::Bvh2;
pub use context::{Gpu, gpu};
pub use cwbvh::CwBvh;
pub use gpu_index::GpuLayout;
pub(crate) use gpu_index::{build, estimate};
pub use grid::GridCells;

/// The shaders' shared part, prefixed to each.
const COMMON: &str = include_str!("shaders/common.wgsl");
