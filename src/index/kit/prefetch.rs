//! Cache prefetch hints for the tree walks (BVHs, wide BVHs, kd-tree and BSP): ask for a node's
//! or a leaf's lines before the walk reads them.

/// Asks the cache for every line of `*item` ahead of its use (x86_64; a no-op elsewhere): the
/// lines from the one holding its first byte, as many as a `T` can span (`size / 64` when `T` is
/// aligned to a line, one more otherwise), a count known at compile time, so the loop unrolls
/// into straight prefetches. Reads nothing and cannot fault, so any address is allowed.
#[inline(always)]
pub fn prefetch<T>(item: *const T) {
    let lines = match align_of::<T>() % 64 {
        0 => size_of::<T>() / 64,
        _ => size_of::<T>() / 64 + 1,
    };
    let first = item as usize & !63;
    for i in 0..lines {
        prefetch_line((first + 64 * i) as *const u8);
    }
}

/// Asks the cache for the line holding `*byte` (x86_64; a no-op elsewhere). Reads nothing and
/// cannot fault.
#[inline(always)]
pub fn prefetch_line(byte: *const u8) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: prefetching is a hint; it does not access memory architecturally.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(byte.cast::<i8>())
    };
    #[cfg(not(target_arch = "x86_64"))]
    let _ = byte;
}
