//! accelbench: a benchmark suite for ray-casting acceleration structures.
//!
//! - [`random`]: the protocol's seeded PRNG (SplitMix64), shared by every layer above.
//! - [`geometry`]: rays, boxes, hits and the shared ray–primitive kernels.
//! - [`scene`]: scenes (OBJ, generators), and the [`scene::Geometry`] interface indices use.
//! - [`camera`] and [`rays`]: the pinhole camera, the protocol's ray sets and ray/hit files.
//! - [`index`]: the [`index::Index`] trait, brute force (the reference) and the registry.
//! - [`render`]: Phong renders with shadows and per-pixel cost heat maps through any index.
//! - [`report`]: CSV tables and SVG charts every command writes through.
//! - [`accuracy`] and [`stress`]: kernel accuracy, watertightness, the stress suite.
//! - [`cli`]: the command line (a thin layer over the library).
//! - [`heap_meter`]: the global allocator, counting held and peak heap bytes.

pub mod accuracy;
pub mod camera;
pub mod cli;
pub mod geometry;
pub mod harness;
pub mod heap_meter;
pub mod index;
pub mod random;
pub mod rays;
pub mod render;
pub mod report;
pub mod scene;
pub mod stress;
