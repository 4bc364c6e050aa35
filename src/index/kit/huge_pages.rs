//! Large index arrays on transparent huge pages (Linux).
//!
//! Incoherent rays visit nodes and leaves all over a large tree. With 4 KiB pages nearly every
//! such visit also misses the TLB: a 100 MB tree spans 25,600 pages, far more than the
//! translation caches hold, so each node load waits for a page walk as well. Embree asks the
//! kernel to back its tree memory with 2 MiB pages (`madvise(MADV_HUGEPAGE)` on its
//! allocations); [`huge_page_vec`] does the same for ours.
//!
//! It copies a large array into a fresh allocation that is advised before the copy first writes
//! it, so the kernel can fault it in as huge pages, and afterwards asks the kernel to collapse
//! whatever it still holds in small pages (`MADV_COLLAPSE`, Linux 6.1 and later; an allocation
//! the allocator recycled was already faulted in). The system decides:
//! `/sys/kernel/mm/transparent_hugepage/enabled` must be `madvise` or `always`, and a refused
//! request is ignored. Only the mapping changes, never a byte of the data. Arrays under 2 MiB,
//! and every array on other systems, are only shrunk to their length (no copy).

/// Smallest array worth advising: one huge page.
pub const HUGE_PAGE: usize = 2 << 20;

/// `items` with no spare capacity; when it spans at least [`HUGE_PAGE`] on Linux, copied into
/// a new vector whose memory is advised for huge pages (see the module doc).
pub fn huge_page_vec<T: Copy>(mut items: Vec<T>) -> Vec<T> {
    if !cfg!(target_os = "linux") || size_of_val(&items[..]) < HUGE_PAGE {
        items.shrink_to_fit();
        return items;
    }
    let mut v = Vec::with_capacity(items.len());
    let range = (v.as_ptr() as usize, size_of_val(&items[..]));
    advise(range, Advice::HugePages);
    v.extend_from_slice(&items);
    advise(range, Advice::Collapse);
    v
}

/// What [`advise`] asks of the kernel.
#[derive(Clone, Copy)]
enum Advice {
    /// Back the range with huge pages when it is faulted in.
    HugePages,
    /// Move the range's small pages into huge pages now.
    Collapse,
}

/// Gives `advice` for the whole pages inside `(start, bytes)` (`bytes >= HUGE_PAGE`); errors
/// (an old kernel, huge pages turned off) are ignored.
#[cfg(target_os = "linux")]
fn advise((start, bytes): (usize, usize), advice: Advice) {
    const PAGE: usize = 4096;
    let first = start.next_multiple_of(PAGE);
    let end = (start + bytes) & !(PAGE - 1);
    let flag = match advice {
        Advice::HugePages => libc::MADV_HUGEPAGE,
        // Not exported by the `libc` crate for every Linux target; the value is the kernel's.
        Advice::Collapse => 25,
    };
    // SAFETY: `madvise` with these flags changes only how the pages of the range are backed,
    // never their contents; the range lies inside the caller's allocation (rounded inward to
    // whole pages) and is nonempty since `bytes >= HUGE_PAGE`.
    unsafe { libc::madvise(first as *mut libc::c_void, end - first, flag) };
}

#[cfg(not(target_os = "linux"))]
fn advise(_: (usize, usize), _: Advice) {}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    /// The kernel's transparent huge page mode (`always`, `madvise` or `never`).
    fn thp_mode() -> Option<String> {
        let s = std::fs::read_to_string("/sys/kernel/mm/transparent_hugepage/enabled").ok()?;
        let start = s.find('[')? + 1;
        let end = s.find(']')?;
        Some(s[start..end].to_string())
    }

    /// Kilobytes of huge pages backing the mapping that contains `addr` (`/proc/self/smaps`).
    fn huge_kb_at(addr: usize) -> u64 {
        let smaps = std::fs::read_to_string("/proc/self/smaps").expect("read /proc/self/smaps");
        let mut inside = false;
        for line in smaps.lines() {
            let head = line.split_whitespace().next().unwrap_or("");
            if let Some((lo, hi)) = head.split_once('-')
                && let (Ok(lo), Ok(hi)) =
                    (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
            {
                inside = (lo..hi).contains(&addr);
                continue;
            }
            if inside && let Some(kb) = line.strip_prefix("AnonHugePages:") {
                return kb.trim().trim_end_matches("kB").trim().parse().unwrap_or(0);
            }
        }
        0
    }

    #[test]
    fn the_copy_is_the_slice_and_a_large_one_is_on_huge_pages_where_the_system_allows() {
        let items: Vec<u64> = (0..(16 * HUGE_PAGE / 8) as u64)
            .map(|i| i * 7 + 1)
            .collect();
        let v = huge_page_vec(items.clone());
        assert_eq!(v, items);
        assert_eq!(v.capacity(), v.len());
        let mode = thp_mode();
        if matches!(mode.as_deref(), Some("madvise" | "always")) {
            let middle = v.as_ptr() as usize + size_of_val(&v[..]) / 2;
            let kb = huge_kb_at(middle);
            assert!(
                kb >= 2048,
                "a 32 MiB array advised for huge pages has {kb} kB of them (THP mode {mode:?})"
            );
        }
        assert_eq!(huge_page_vec::<u32>(Vec::new()), Vec::<u32>::new());
        let mut small = Vec::with_capacity(100);
        small.extend([1u8, 2, 3]);
        let small = huge_page_vec(small);
        assert_eq!((small.capacity(), small), (3, vec![1, 2, 3]));
    }
}
