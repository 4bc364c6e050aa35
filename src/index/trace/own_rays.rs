//! A batch of rays in an index's own ray form ([`OwnRays`]): a peer library's ray records, made
//! from our [`crate::geometry::Ray`]s once before the timed passes, as our `Ray` carries its
//! reciprocal direction and shear made when the ray is. The timed passes then measure the
//! library's calls, not the conversion (issue 46: peers at their own speed).

use crate::geometry::Hit;
use std::any::Any;

/// Rays in the form of the index that made them ([`super::BatchIndex::own_rays`]), in batch
/// order, one record per ray of the batch.
pub struct OwnRays(Box<dyn Any + Send + Sync>);

impl OwnRays {
    /// The records `rays`, one per ray of the batch, in batch order.
    pub fn new<T: Send + Sync + 'static>(rays: Vec<T>) -> OwnRays {
        OwnRays(Box::new(rays))
    }

    /// The records as made by [`OwnRays::new`] with records of type `T`.
    ///
    /// # Panics
    /// When they were made of another type: only the index that made them traces them.
    pub fn records<T: 'static>(&self) -> &[T] {
        self.0
            .downcast_ref::<Vec<T>>()
            .expect("own rays traced by the index that made them")
    }
}

/// Where a batch traced from [`OwnRays`] leaves its answers, one per record: closest hits, or
/// whether anything is hit.
pub enum Answers<'a> {
    Closest(&'a mut [Option<Hit>]),
    Any(&'a mut [bool]),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_come_back_as_made() {
        let own = OwnRays::new(vec![[1.0f32, 2.0], [3.0, 4.0]]);
        assert_eq!(own.records::<[f32; 2]>(), &[[1.0, 2.0], [3.0, 4.0]]);
        let wrong =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| own.records::<u32>().len()));
        assert!(wrong.is_err());
    }
}
