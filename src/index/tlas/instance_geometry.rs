//! The instances of a scene as the primitives of a top-level structure: primitive `i` is
//! instance `i`, its bounds the instance's world bounds, its test the instance's mesh
//! structure traced with the ray moved into object space ([`crate::scene::instances`] states
//! the arithmetic).

use crate::geometry::{Aabb, Hit, Ray};
use crate::index::TraceIndex;
use crate::scene::instances::InstanceSet;
use crate::scene::{Geometry, ShapeQueries};
use glam::Vec3A;
use std::sync::Arc;

/// Instances as primitives, each mesh's structure built once and shared by its instances.
#[derive(Clone)]
pub struct InstanceGeometry {
    pub set: Arc<InstanceSet>,
    /// One structure per mesh of [`InstanceSet::meshes`], over its object-space triangles.
    pub meshes: Arc<[Box<dyn TraceIndex>]>,
}

impl InstanceGeometry {
    /// The closest hit of instance `i`'s mesh for `ray` (world space) over the ray's whole
    /// range, in mesh ids; `None` for a miss.
    #[inline]
    pub fn mesh_hit(&self, i: u32, ray: &Ray) -> Option<Hit> {
        let inst = &self.set.instances[i as usize];
        let local = inst.object_ray(ray)?;
        self.meshes[inst.mesh as usize].closest_hit(&local)
    }

    /// The flattened scene's hit of a top-level hit on instance `hit.prim`: the same `t`, the
    /// instance's id of its mesh's closest triangle (the one that gave the `t`: the mesh is
    /// asked the same question again, and answers it the same way).
    #[inline]
    pub fn flattened(&self, ray: &Ray, hit: Hit) -> Hit {
        let inst = &self.set.instances[hit.prim as usize];
        let local = self
            .mesh_hit(hit.prim, ray)
            .expect("an instance's mesh answers the same ray the same way");
        Hit {
            t: hit.t,
            prim: inst.first + local.prim,
        }
    }
}

impl Geometry for InstanceGeometry {
    #[inline]
    fn len(&self) -> usize {
        self.set.instances.len()
    }
    #[inline]
    fn bounds(&self, prim: u32) -> Aabb {
        self.set.instances[prim as usize].bounds
    }
    /// The mesh's closest `t` for the object-space ray (over the ray's whole range, so the
    /// answer does not depend on `t_max`), clamped into the slab interval of the instance's
    /// world bounds; a miss when the slab test rejects them or the clamped `t` is past `t_max`.
    #[inline]
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        let inst = &self.set.instances[prim as usize];
        let (enter, exit) = inst.bounds.ray_interval(ray, ray.t_min, ray.t_max)?;
        let t = self.mesh_hit(prim, ray)?.t.clamp(enter, exit);
        (t.is_finite() && t <= t_max).then_some(t)
    }
}

impl ShapeQueries for InstanceGeometry {
    /// The instance's bounds against the cell (conservative: never a false "no").
    fn overlaps_box(&self, prim: u32, cell: &Aabb) -> bool {
        let b = self.bounds(prim);
        b.min.cmple(cell.max).all() && cell.min.cmple(b.max).all()
    }
    /// The unit world normal of the instance's triangle the ray hits (the mesh's triangle
    /// normal moved by the inverse transpose of the placement); zero when the ray misses it.
    fn normal(&self, prim: u32, ray: &Ray, _t: f32) -> Vec3A {
        let inst = &self.set.instances[prim as usize];
        self.mesh_hit(prim, ray).map_or(Vec3A::ZERO, |h| {
            let tri = &self.set.meshes[inst.mesh as usize][h.prim as usize];
            inst.normal_to_world(tri.normal())
        })
    }
}
