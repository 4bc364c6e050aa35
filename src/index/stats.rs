//! Traversal statistics as a type parameter: [`NoStats`] compiles to nothing in timed runs,
//! [`Counters`] counts in a separate counting pass.

use serde::Serialize;
use std::ops::AddAssign;

/// What a traversal reports as it goes. Every method is a no-op for [`NoStats`], so a traversal
/// generic over `S: Stats` costs nothing extra when timed.
pub trait Stats: Default + Send {
    /// One ray–primitive kernel call.
    fn prim_test(&mut self);
    /// One node (tree) or cell (grid) visited.
    fn node_visit(&mut self);
    /// `n` ray–box slab tests.
    fn box_tests(&mut self, n: u32);
}

/// The zero-sized statistics of timed runs.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoStats;

impl Stats for NoStats {
    #[inline(always)]
    fn prim_test(&mut self) {}
    #[inline(always)]
    fn node_visit(&mut self) {}
    #[inline(always)]
    fn box_tests(&mut self, _n: u32) {}
}

/// Real counters for counting runs (per ray, or summed over a batch).
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Counters {
    pub prim_tests: u64,
    pub node_visits: u64,
    pub box_tests: u64,
}

impl Stats for Counters {
    #[inline]
    fn prim_test(&mut self) {
        self.prim_tests += 1;
    }
    #[inline]
    fn node_visit(&mut self) {
        self.node_visits += 1;
    }
    #[inline]
    fn box_tests(&mut self, n: u32) {
        self.box_tests += n as u64;
    }
}

impl AddAssign for Counters {
    fn add_assign(&mut self, o: Counters) {
        self.prim_tests += o.prim_tests;
        self.node_visits += o.node_visits;
        self.box_tests += o.box_tests;
    }
}

impl std::iter::Sum for Counters {
    fn sum<I: Iterator<Item = Counters>>(iter: I) -> Counters {
        iter.fold(Counters::default(), |mut a, b| {
            a += b;
            a
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_stats_is_zero_sized_and_counters_count() {
        assert_eq!(std::mem::size_of::<NoStats>(), 0);
        let mut c = Counters::default();
        c.prim_test();
        c.node_visit();
        c.box_tests(2);
        let total: Counters = [c, c].into_iter().sum();
        assert_eq!(
            total,
            Counters {
                prim_tests: 2,
                node_visits: 2,
                box_tests: 4
            }
        );
    }
}
