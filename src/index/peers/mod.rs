//! The outside libraries raced against our indices, registered as
//! [`crate::index::Kind::Peer`]: obvhs ([`obvhs`]), and with their features Embree (`embree`)
//! and tinybvh (`tinybvh`), which build from the scene's triangles (`triangle_peer`).

#[cfg(feature = "embree")]
pub mod embree;
pub mod obvhs;
#[cfg(feature = "tinybvh")]
pub mod tinybvh;
#[cfg(any(feature = "embree", feature = "tinybvh"))]
mod triangle_peer;

pub use obvhs::{ObvhsBvh2, ObvhsCwBvh};
