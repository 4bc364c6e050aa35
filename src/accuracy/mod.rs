//! Accuracy and numerical stability of the ray–primitive kernels (`accelbench accuracy`).
//!
//! - [`study`]: every triangle and sphere kernel in `f32` and `f64` on random, vertex/edge-aimed
//!   and grazing rays at offsets from the origin, against [`reference`] (exact hit/miss by exact
//!   edge-function signs, double-double `t`), and every shape kernel in `f32` on random,
//!   edge/rim/apex-aimed, grazing and inside rays against its `f64` mirror ([`shapes_f64`],
//!   shapes and rays in [`shape_families`]): false-miss, false-hit and wrong-primitive rates,
//!   relative `t` error, ns per test.
//! - [`watertight`]: rays from inside closed meshes far from the origin; misses per kernel and
//!   per index.
//! - [`report`]: CSV, plots and the Markdown summary.
//! - [`kernels`]: the kernels as data and their timing loop; [`metrics`]: scoring against the
//!   reference.
//! - [`kernels_f64`]: the `f64` mirrors of the kernels; [`dd`]: double-double arithmetic;
//!   [`families`]: the scenes and ray families.

pub mod families;
pub mod kernels;
pub mod kernels_f64;
pub mod metrics;
pub mod report;
pub mod shape_families;
pub mod shapes_f64;
pub mod study;
pub mod watertight;

pub use report::write_all;
pub use study::{AccuracyConfig, AccuracyRow, Kernel, Precision, run};
pub use watertight::{LeakRow, WatertightConfig};
