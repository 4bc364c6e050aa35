//! Mailboxing (Amanatides & Woo 1987): in a structure that references one primitive from
//! several cells (grid, octree, kd-tree, BSP), each primitive is tested at most once per ray.
//!
//! Each thread owns one stamp array (one `u32` per primitive) and a ray counter. A query takes a
//! fresh stamp; a primitive is tested only when its stamp differs, and is then stamped. Nothing
//! is allocated per ray: the array grows only when a thread first meets a larger scene, and is
//! cleared only when the counter wraps (every 2^32 - 1 queries).

use std::cell::RefCell;

/// The stamps of one thread.
#[derive(Debug, Default)]
pub struct Mailbox {
    stamps: Vec<u32>,
    current: u32,
}

impl Mailbox {
    /// Starts a new ray over primitives `0..len`.
    fn start(&mut self, len: usize) {
        if self.stamps.len() < len {
            self.stamps.resize(len, 0);
        }
        self.current = self.current.wrapping_add(1);
        if self.current == 0 {
            self.stamps.fill(0);
            self.current = 1;
        }
    }

    /// `true` the first time `prim` is offered during the current ray (and marks it), `false`
    /// afterwards.
    #[inline(always)]
    pub fn first_visit(&mut self, prim: u32) -> bool {
        let stamp = &mut self.stamps[prim as usize];
        if *stamp == self.current {
            false
        } else {
            *stamp = self.current;
            true
        }
    }
}

thread_local! {
    static MAILBOX: RefCell<Mailbox> = RefCell::new(Mailbox::default());
}

/// Runs one ray's traversal `f` with this thread's mailbox, started for primitives `0..len`.
///
/// Not reentrant: `f` must not start another mailboxed query on the same thread (queries never
/// nest; a nested call panics with a message saying so).
#[inline]
pub fn with_mailbox<R>(len: usize, f: impl FnOnce(&mut Mailbox) -> R) -> R {
    MAILBOX.with(|m| {
        let mut m = m
            .try_borrow_mut()
            .expect("mailboxed queries must not nest on one thread");
        m.start(len);
        f(&mut m)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_primitive_once_per_ray() {
        let first = with_mailbox(10, |m| [3, 3, 7, 3, 0, 7].map(|p| m.first_visit(p)));
        assert_eq!(first, [true, false, true, false, true, false]);
        // A new ray sees every primitive afresh, and a larger scene grows the stamps.
        let again = with_mailbox(100, |m| [3, 99, 99].map(|p| m.first_visit(p)));
        assert_eq!(again, [true, true, false]);
    }

    #[test]
    fn counter_wrap_clears_stamps() {
        let mut m = Mailbox::default();
        m.start(4);
        assert!(m.first_visit(2));
        m.current = u32::MAX;
        m.stamps[1] = 1; // a stale stamp that would collide after the wrap
        m.start(4);
        assert_eq!(m.current, 1);
        assert!(m.first_visit(1) && m.first_visit(2));
    }
}
