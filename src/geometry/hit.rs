//! The closest-hit record and the one ordering every index uses.

/// A ray–primitive hit: the parameter `t` the shared kernel computed and the primitive's index in
/// scene order.
///
/// Ordering (the contract every index keeps): smaller `t` first; at equal `t` (rays through
/// shared edges, vertices, coincident primitives) the lower primitive index wins. Two indices
/// that use the same kernel therefore agree bit for bit.
///
/// Culling is exact because kernels return a `t` inside the slab interval of the primitive's own
/// bounds (see [`crate::scene::Geometry::intersect`]), and the slab test is monotone: a box that
/// contains the primitive's bounds has an entry `<= t`. An index may skip a box or cell whose
/// entry is *strictly greater* than the best `t` so far, never one whose entry equals it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub prim: u32,
}

impl Hit {
    /// `true` when `self` comes before `other` in the closest-hit order.
    #[inline]
    pub fn is_closer_than(&self, other: &Hit) -> bool {
        self.t < other.t || (self.t == other.t && self.prim < other.prim)
    }

    /// Bit-level equality (primitive and the exact bits of `t`), the test of the hit contract.
    #[inline]
    pub fn bits_eq(&self, other: &Hit) -> bool {
        self.prim == other.prim && self.t.to_bits() == other.t.to_bits()
    }
}

/// The running closest hit of one query, kept in registers: starts at `(t_max, u32::MAX)`, so a
/// candidate at exactly `t_max` is accepted (the interval is closed).
#[derive(Debug, Clone, Copy)]
pub struct ClosestHit {
    best: Hit,
}

impl ClosestHit {
    #[inline]
    pub fn new(t_max: f32) -> ClosestHit {
        ClosestHit {
            best: Hit {
                t: t_max,
                prim: u32::MAX,
            },
        }
    }

    /// The current bound on `t`: candidates beyond it cannot win.
    #[inline]
    pub fn t(&self) -> f32 {
        self.best.t
    }

    /// Offers a candidate; keeps it when it comes first in the hit order.
    #[inline]
    pub fn offer(&mut self, t: f32, prim: u32) {
        let c = Hit { t, prim };
        if c.is_closer_than(&self.best) {
            self.best = c;
        }
    }

    #[inline]
    pub fn get(&self) -> Option<Hit> {
        (self.best.prim != u32::MAX).then_some(self.best)
    }
}

/// Picks the closer of two optional hits by the contract order.
#[inline]
pub fn closer(a: Option<Hit>, b: Option<Hit>) -> Option<Hit> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if y.is_closer_than(&x) { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties_go_to_lowest_primitive() {
        let mut c = ClosestHit::new(f32::INFINITY);
        c.offer(2.0, 7);
        c.offer(2.0, 3);
        c.offer(2.0, 5);
        c.offer(3.0, 1);
        assert_eq!(c.get(), Some(Hit { t: 2.0, prim: 3 }));
        assert_eq!(
            closer(Some(Hit { t: 1.0, prim: 9 }), Some(Hit { t: 1.0, prim: 2 })),
            Some(Hit { t: 1.0, prim: 2 })
        );
    }

    #[test]
    fn hit_at_t_max_is_kept() {
        let mut c = ClosestHit::new(4.0);
        c.offer(4.0, 0);
        assert_eq!(c.get(), Some(Hit { t: 4.0, prim: 0 }));
        assert_eq!(ClosestHit::new(4.0).get(), None);
    }
}
