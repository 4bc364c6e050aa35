//! Triangles that log every kernel call ([`CallLog`]), for tests that look at which primitives
//! a walk tests, for which ray and in which order.

use accelbench::geometry::triangle::TriangleKernel;
use accelbench::geometry::{Aabb, Ray};
use accelbench::scene::{Geometry, GeometryWrapper, Triangles};
use std::sync::{Arc, Mutex};

/// Triangles with kernel `K` whose every kernel call pushes `note(prim, ray)` onto `calls`
/// before testing (the counts and answers are `Triangles<K>`'s).
#[derive(Clone)]
pub struct CallLog<K: TriangleKernel, T, F> {
    pub inner: Triangles<K>,
    pub note: F,
    pub calls: Arc<Mutex<Vec<T>>>,
}

impl<K: TriangleKernel, T, F> GeometryWrapper for CallLog<K, T, F> {
    type Inner = Triangles<K>;
    fn inner(&self) -> &Triangles<K> {
        &self.inner
    }
}

impl<K, T, F> Geometry for CallLog<K, T, F>
where
    K: TriangleKernel,
    T: Clone + Send + 'static,
    F: Fn(u32, &Ray) -> T + Clone + Send + Sync + 'static,
{
    fn len(&self) -> usize {
        self.inner.len()
    }
    fn bounds(&self, prim: u32) -> Aabb {
        self.inner.bounds(prim)
    }
    fn intersect(&self, prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
        self.calls.lock().unwrap().push((self.note)(prim, ray));
        self.inner.intersect(prim, ray, t_max)
    }
}
