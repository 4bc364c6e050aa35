//! Instanced scenes: meshes placed several times by rigid-and-scale transforms
//! (`[[instance]]` in scene files), kept beside the flattened triangles every other index
//! traces, so that a two-level index (`tlas`) can share one structure per mesh.
//!
//! Primitive ids are the flattened scene's: each object's triangles form one contiguous range,
//! objects in file order, and instance `i`'s triangle `j` is primitive `first + j`.
//!
//! **The arithmetic of an instanced hit** (what `tlas` and its reference repeat bit for bit):
//! the world ray is moved into the instance's object space by [`Instance::object_ray`] (in
//! `f64`, each coordinate rounded to `f32` once; the identity keeps the ray's bits); the
//! instance's mesh answers that ray with the shared kernel (closest hit over the ray's whole
//! range, the mesh's triangle `t` clamped into its own object-space bounds, ties to the lowest
//! id); that `t` is then clamped into the slab interval of the instance's world bounds
//! ([`Instance::bounds`]) for the world ray, and is a miss when the slab test rejects them.
//! `t` is the same parameter in both spaces (the move is affine), so instances compare by it.

use super::transform::Transform;
use crate::geometry::{Aabb, Ray, Triangle};
use glam::{DMat3, DVec3, Vec3A};
use std::sync::Arc;

/// The meshes of an instanced scene and where each instance places one.
#[derive(Debug, Clone, Default)]
pub struct InstanceSet {
    /// Each distinct mesh once, in object space.
    pub meshes: Vec<Arc<[Triangle]>>,
    /// Every object of the scene that has triangles, in id order: `[[instance]]` entries, and
    /// `[[mesh]]` / `[[generator]]` entries as instances of their own (placed) triangles under
    /// the identity.
    pub instances: Vec<Instance>,
    /// Whether the instances hold every primitive of the scene (no spheres or shapes beside
    /// them): the condition for tracing the scene by its instances.
    pub covers_scene: bool,
}

/// One placement of a mesh.
#[derive(Debug, Clone)]
pub struct Instance {
    /// Which of [`InstanceSet::meshes`].
    pub mesh: u32,
    /// The flattened id of its triangle 0.
    pub first: u32,
    /// Triangles it holds (its mesh's count).
    pub len: u32,
    /// World bounds: the flattened triangles' bounds, padded outward by a millionth of their
    /// largest coordinate's magnitude, so that the rounding of the object-space ray clips few
    /// grazing hits that the flattened scene keeps. Part of the hit's definition (its `t` is
    /// clamped into them), so any box works for the contract; the padding only brings the
    /// instanced answers closer to the flattened ones.
    pub bounds: Aabb,
    /// `None` for the identity, else world-to-object: `(linear, translate)` with
    /// `object = linear * (world - translate)`.
    to_object: Option<(DMat3, DVec3)>,
}

impl Instance {
    /// An instance of `mesh` (its triangles `tris`, object space) placed by `place`, whose
    /// flattened triangles start at `first`; `None` when the placement cannot be inverted in
    /// `f64` (a degenerate scale, already refused by [`Transform::new`]).
    pub fn new(mesh: u32, tris: &[Triangle], place: &Transform, first: u32) -> Option<Instance> {
        let bounds = tris
            .iter()
            .map(|t| place.triangle(t).bounds())
            .fold(Aabb::EMPTY, Aabb::union);
        let to_object = if place.is_identity() {
            None
        } else {
            let linear = place.rotation * DMat3::from_diagonal(place.scale);
            let inverse = linear.inverse();
            if !inverse.is_finite() {
                return None;
            }
            Some((inverse, place.translate))
        };
        let magnitude = bounds.min.abs().max(bounds.max.abs()).max_element();
        let pad = Vec3A::splat(magnitude * 1e-6);
        Some(Instance {
            mesh,
            first,
            len: tris.len() as u32,
            bounds: Aabb::new(bounds.min - pad, bounds.max + pad),
            to_object,
        })
    }

    /// The world ray in object space: origin and direction moved in `f64` and rounded to `f32`
    /// once per coordinate, the same `t_min` and `t_max` (the identity returns the ray as it is).
    /// `None` when the moved direction rounds to zero or overflows (such an instance is missed).
    #[inline]
    pub fn object_ray(&self, ray: &Ray) -> Option<Ray> {
        let Some((linear, translate)) = self.to_object else {
            return Some(*ray);
        };
        let origin = linear * (ray.origin.as_dvec3() - translate);
        let dir = linear * ray.dir.as_dvec3();
        Ray::new(origin.as_vec3(), dir.as_vec3(), ray.t_min, ray.t_max).ok()
    }

    /// An object-space normal in world space (by the inverse transpose of the placement),
    /// unit length; zero for a zero normal.
    pub fn normal_to_world(&self, n: Vec3A) -> Vec3A {
        match self.to_object {
            None => n,
            Some((linear, _)) => (linear.transpose() * n.as_dvec3())
                .normalize_or_zero()
                .as_vec3()
                .into(),
        }
    }

    /// The flattened ids this instance holds.
    pub fn ids(&self) -> std::ops::Range<u32> {
        self.first..self.first + self.len
    }
}

impl InstanceSet {
    /// The instance holding flattened primitive `prim` (instances are in id order).
    pub fn instance_of(&self, prim: u32) -> Option<usize> {
        let i = self.instances.partition_point(|x| x.first + x.len <= prim);
        (i < self.instances.len() && self.instances[i].ids().contains(&prim)).then_some(i)
    }

    /// Triangles the instances place in all (the flattened count).
    pub fn instanced_triangles(&self) -> usize {
        self.instances.iter().map(|i| i.len as usize).sum()
    }

    /// Triangles stored once per mesh.
    pub fn mesh_triangles(&self) -> usize {
        self.meshes.iter().map(|m| m.len()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle {
        Triangle::new(
            Vec3A::new(0.0, 0.0, 0.0),
            Vec3A::new(1.0, 0.0, 0.0),
            Vec3A::new(0.0, 1.0, 0.0),
        )
    }

    #[test]
    fn the_identity_keeps_the_ray_and_a_placement_moves_it_into_object_space() {
        let ray = Ray::new(
            glam::Vec3::new(0.25, 0.25, 5.0),
            glam::Vec3::new(0.0, 0.0, -1.0),
            0.0,
            f32::INFINITY,
        )
        .unwrap();
        let same = Instance::new(0, &[tri()], &Transform::IDENTITY, 0).unwrap();
        let moved = same.object_ray(&ray).unwrap();
        assert_eq!(moved.origin, ray.origin);
        assert_eq!(moved.dir, ray.dir);

        // Scaled by 2 and moved by +10 in x: the world point (10.5, 0.5, 0) is (0.25, 0.25, 0).
        let place = Transform::new([2.0; 3], None, [10.0, 0.0, 0.0]).unwrap();
        let inst = Instance::new(0, &[tri()], &place, 7).unwrap();
        let world = Ray::new(
            glam::Vec3::new(10.5, 0.5, 5.0),
            glam::Vec3::new(0.0, 0.0, -1.0),
            0.0,
            f32::INFINITY,
        )
        .unwrap();
        let local = inst.object_ray(&world).unwrap();
        assert_eq!(local.origin, Vec3A::new(0.25, 0.25, 2.5));
        assert_eq!(local.dir, Vec3A::new(0.0, 0.0, -0.5));
        // The same t reaches the triangle's plane in both spaces.
        assert_eq!(local.origin.z + 5.0 * local.dir.z, 0.0);
        assert_eq!(inst.ids(), 7..8);
        assert!(inst.bounds.min.x < 10.0 && inst.bounds.max.x > 12.0);
    }

    #[test]
    fn ids_map_back_to_their_instance() {
        let place = Transform::IDENTITY;
        let set = InstanceSet {
            meshes: vec![Arc::from(vec![tri(), tri()])],
            instances: (0..3)
                .map(|k| Instance::new(0, &[tri(), tri()], &place, 2 * k).unwrap())
                .collect(),
            covers_scene: true,
        };
        assert_eq!(set.instance_of(0), Some(0));
        assert_eq!(set.instance_of(3), Some(1));
        assert_eq!(set.instance_of(5), Some(2));
        assert_eq!(set.instance_of(6), None);
        assert_eq!(set.instanced_triangles(), 6);
        assert_eq!(set.mesh_triangles(), 2);
    }
}
