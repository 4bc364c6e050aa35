//! Geometry: rays, boxes, hits and the ray–primitive kernels every index shares.

mod aabb;
mod aabb_kernel;
pub mod clip;
pub mod dd;
pub mod expansion;
pub mod float;
mod hit;
pub mod overlap;
mod plane;
pub mod polyhedron;
pub mod quadratic;
mod ray;
pub mod real;
pub mod reference;
pub mod shapes;
pub mod sphere;
#[cfg(test)]
pub(crate) mod test_support;
pub mod triangle;
mod triangle_shape;

pub use aabb::{Aabb, SLAB_FAR_SCALE};
pub use aabb_kernel::intersect_box;
pub use hit::{ClosestHit, Hit, closer};
pub use plane::intersect_plane;
pub use ray::{Ray, RayError};
pub use real::Shear;
pub use shapes::{Shape, ShapeError};
pub use sphere::Sphere;
pub use triangle::{Triangle, TriangleKernel, TriangleKernelKind};
