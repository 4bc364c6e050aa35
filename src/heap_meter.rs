//! The process's global allocator: the system allocator with two counters, the heap bytes held
//! now ([`held_bytes`]) and the high-water mark since a measurement began ([`peak_during`]),
//! so index builds report their peak memory and the memory budget knows what is held.
//!
//! Only allocations through Rust's global allocator are seen: a C or C++ library that calls
//! `malloc` or `new` itself (Embree, tinybvh) is invisible here, and its indices say so
//! ([`crate::index::Index::FOREIGN_HEAP`]). Queries never allocate, so tracing never touches
//! the counters; a build pays two atomic operations per allocation.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting.
struct Meter {
    /// Bytes allocated and not yet freed.
    held: AtomicUsize,
    /// The largest `held` since the measurements in progress began (or since start).
    peak: AtomicUsize,
}

impl Meter {
    fn grow(&self, bytes: usize) {
        let now = self.held.fetch_add(bytes, Ordering::Relaxed) + bytes;
        self.peak.fetch_max(now, Ordering::Relaxed);
    }

    fn shrink(&self, bytes: usize) {
        self.held.fetch_sub(bytes, Ordering::Relaxed);
    }
}

// SAFETY: every call is forwarded to `System` unchanged; the counters only observe sizes.
unsafe impl GlobalAlloc for Meter {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            self.grow(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            self.grow(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        self.shrink(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            // The old and the new block may both exist while the data moves: count the new
            // one before the old one is gone, as a fresh allocation and a free would.
            self.grow(new_size);
            self.shrink(layout.size());
        }
        p
    }
}

#[global_allocator]
static METER: Meter = Meter {
    held: AtomicUsize::new(0),
    peak: AtomicUsize::new(0),
};

/// Heap bytes the process holds now through Rust's allocator.
pub fn held_bytes() -> usize {
    METER.held.load(Ordering::Relaxed)
}

/// Measurements in progress ([`peak_during`]); the high-water mark restarts only when none is.
static MEASURING: AtomicUsize = AtomicUsize::new(0);

/// Runs `f` and returns its result with the high-water mark of the heap during `f`, in bytes
/// above what was held when `f` began. Exact when nothing else allocates meanwhile (`run`,
/// `info` and `animate` build one index at a time); allocations of other threads count too,
/// and a measurement that begins while another is in progress shares its mark, so overlapping
/// measurements give upper bounds. Never blocks: measurements may nest and overlap.
pub fn peak_during<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let start = held_bytes();
    if MEASURING.fetch_add(1, Ordering::AcqRel) == 0 {
        METER.peak.store(start, Ordering::Relaxed);
    }
    /// Ends the measurement also when `f` panics (a contained build), so the mark restarts.
    struct End;
    impl Drop for End {
        fn drop(&mut self) {
            MEASURING.fetch_sub(1, Ordering::AcqRel);
        }
    }
    let _end = End;
    let out = f();
    let peak = METER.peak.load(Ordering::Relaxed).max(held_bytes());
    (out, peak.saturating_sub(start))
}

/// `bytes` as a person reads it: `1.5 GiB`, `12.0 MiB`, `900 B` (1024-based).
pub fn human(bytes: u64) -> String {
    const UNITS: [&str; 5] = ["KiB", "MiB", "GiB", "TiB", "PiB"];
    if bytes < 1024 {
        return format!("{bytes} B");
    }
    let mut v = bytes as f64 / 1024.0;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    format!("{v:.1} {}", UNITS[unit])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vector_built_and_dropped_inside_counts_at_its_size() {
        let (len, peak) = peak_during(|| {
            let v = vec![7u8; 3 << 20];
            std::hint::black_box(&v).len()
        });
        assert_eq!(len, 3 << 20);
        assert!(peak >= 3 << 20, "{peak}");
    }
}
