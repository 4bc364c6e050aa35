//! Ray sets and the `.rays`/`.hits` interchange files of `../shared/PROTOCOL.md`.

mod camera_sets;
mod file;
mod sets;
pub mod spawn;

pub use crate::random::SplitMix64;
pub use camera_sets::{CAMERA_SET_SEED, camera_model_rays};
pub use file::{
    RayFileError, ray_to_record, read_hits, read_rays, read_rays_limit, read_rays_raw, write_hits,
    write_rays,
};
pub use sets::{RaySetKind, incoherent_rays, primary_rays, ray_set};
