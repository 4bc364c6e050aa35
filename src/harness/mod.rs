//! The measuring and checking machinery shared by the CLI, benches and tests.

pub mod animate;
pub mod contain;
pub mod interrupt;
pub mod median_interval;
pub mod memory;
pub mod peer_check;
mod set_row;
pub mod shard;
pub mod suite;
mod suite_config;
mod suite_result;
mod suite_set;
pub mod sweep;
pub mod timing;
pub mod verify;
pub mod workload;
