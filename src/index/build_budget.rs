//! The memory budget index builds are held to. A command sets it once ([`set_build_budget`],
//! from `--memory-budget` or its default share of the available memory); every build is then
//! checked twice:
//!
//! - **before** it allocates: its estimate ([`crate::index::Index::estimated_build_bytes`]) on
//!   top of the heap held now must fit ([`ensure_fits`], called by
//!   [`crate::index::build_index_on`]);
//! - **while** it builds, by the structures whose size depends on more than the primitive
//!   count (the grids' references, the octrees', kd-tree's and BSP's nodes, which thin
//!   primitives spanning many cells multiply): each step checks that the heap held is still
//!   within the budget ([`ensure_within`]) and stops the build when it is not, so a build that
//!   outgrows its estimate is refused instead of being killed by the kernel.
//!
//! Both refusals are [`BuildError::OverBudget`], which the suite reports as a skipped index.
//! The heap counted is Rust's ([`crate::heap_meter`]), and Embree's through its memory monitor
//! ([`room_for`]); tinybvh's allocations are counted through its hooks for its peak, but not
//! refused (it cannot take a failed allocation), so it is checked before its build only.

use super::BuildError;
use crate::heap_meter::{held_bytes, human};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The budget in bytes; `usize::MAX` when none is set.
static LIMIT: AtomicUsize = AtomicUsize::new(usize::MAX);

/// Where the budget comes from, e.g. "--memory-budget", for the messages.
static SOURCE: Mutex<String> = Mutex::new(String::new());

/// Holds every later build in this process to `bytes` of heap, whose origin `source` the
/// refusals name (e.g. "--memory-budget", "80% of the 3.1 GiB available").
pub fn set_build_budget(bytes: u64, source: &str) {
    let mut s = SOURCE.lock().unwrap_or_else(|e| e.into_inner());
    *s = source.to_owned();
    LIMIT.store(
        usize::try_from(bytes).unwrap_or(usize::MAX),
        Ordering::Relaxed,
    );
}

/// The budget and its origin, `None` when none is set.
fn budget() -> Option<(usize, String)> {
    let limit = LIMIT.load(Ordering::Relaxed);
    (limit != usize::MAX).then(|| {
        let s = SOURCE.lock().unwrap_or_else(|e| e.into_inner());
        (limit, s.clone())
    })
}

/// Refuses the build of `index` over `prims` primitives when its estimated `need` in bytes,
/// on top of the heap held now, would exceed the budget.
pub fn ensure_fits(index: &str, prims: usize, need: usize) -> Result<(), BuildError> {
    let Some((limit, source)) = budget() else {
        return Ok(());
    };
    let held = held_bytes();
    if held.saturating_add(need) <= limit {
        return Ok(());
    }
    Err(BuildError::OverBudget {
        index: index.to_owned(),
        message: format!(
            "{index} over {prims} primitives would need about {} to build (its estimate), with \
             {} already held: over the memory budget of {} ({source}); use a smaller scene, or \
             raise --memory-budget",
            human(need as u64),
            human(held as u64),
            human(limit as u64),
        ),
    })
}

/// Stops the build of `index` when the heap held, with the `allocating` bytes the builder is
/// about to allocate, would be past the budget; `lower` names the parameters that make the
/// structure smaller (e.g. "raise leaf_size or lower max_depth"). One atomic load when within
/// the budget, so builders may call it at every node.
#[inline]
pub fn ensure_within(index: &str, allocating: usize, lower: &str) -> Result<(), BuildError> {
    match room_for(allocating) {
        true => Ok(()),
        false => Err(stopped(
            index,
            held_bytes().saturating_add(allocating),
            lower,
        )),
    }
}

/// Whether `allocating` more bytes beside the heap held now stay within the budget (always,
/// when none is set). For a library's own allocator (Embree's memory monitor) as for ours.
#[inline]
pub fn room_for(allocating: usize) -> bool {
    held_bytes().saturating_add(allocating) <= LIMIT.load(Ordering::Relaxed)
}

/// The refusal of a build of `index` stopped when its heap would have reached `reached` bytes.
pub fn stopped(index: &str, reached: usize, lower: &str) -> BuildError {
    let (limit, source) = budget().unwrap_or_default();
    BuildError::OverBudget {
        index: index.to_owned(),
        message: format!(
            "{index} stopped building when its heap would reach {}, over the memory budget of {} \
             ({source}): this scene makes it larger than its estimate; {lower}, use a smaller \
             scene, or raise --memory-budget",
            human(reached as u64),
            human(limit as u64),
        ),
    }
}

/// Heap every build may hold beyond its per-primitive share (vectors' first blocks, rayon's
/// splits), in bytes, so small scenes' estimates hold too.
const FIXED_BYTES: usize = 64 << 10;

/// The estimate of a build holding `bytes_per_prim` bytes per primitive at its peak: what
/// [`crate::index::Index::estimated_build_bytes`] returns for most structures.
pub fn per_primitive(prims: usize, bytes_per_prim: usize) -> Option<usize> {
    Some(FIXED_BYTES.saturating_add(prims.saturating_mul(bytes_per_prim)))
}
