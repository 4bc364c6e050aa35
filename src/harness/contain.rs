//! Containing a contender's panic: [`contained`] runs one build or trace and turns a panic in it
//! (on the calling thread, or on a rayon worker of a pool it waits on, which rayon hands back to
//! the caller) into an error naming the panic's location and message. The suite notes it as that
//! contender's failure and goes on with the others.
//!
//! While a contained call runs, the panic hook records the first panic instead of printing the
//! default "thread panicked" text and backtrace hint; outside one, panics print as usual.

use std::any::Any;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, Once};

/// How many contained calls are running (the hook is quiet while this is non-zero).
static ACTIVE: AtomicUsize = AtomicUsize::new(0);
/// `at FILE:LINE:COL: MESSAGE` of the first panic raised while a contained call ran.
static FIRST: Mutex<Option<String>> = Mutex::new(None);
static HOOK: Once = Once::new();

/// Runs `f`; a panic in it becomes `Err("panic at FILE:LINE:COL: MESSAGE")`. Whatever `f`
/// borrowed may be left half-updated by the panic: the caller must drop or ignore it (the suite
/// drops the contender that panicked and keeps nothing it produced).
pub fn contained<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    HOOK.call_once(install_quiet_hook);
    if ACTIVE.fetch_add(1, Ordering::SeqCst) == 0 {
        first().take();
    }
    let r = panic::catch_unwind(AssertUnwindSafe(f));
    ACTIVE.fetch_sub(1, Ordering::SeqCst);
    r.map_err(|payload| {
        let at = first().take();
        let at = at.unwrap_or_else(|| format!("at an unknown place: {}", panic_message(&*payload)));
        format!("panic {at}")
    })
}

/// The message a panic was raised with (`panic!("...")` or a formatted one), or a placeholder.
pub fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| (*s).to_owned()))
        .unwrap_or_else(|| "(no message)".into())
}

fn first() -> MutexGuard<'static, Option<String>> {
    FIRST.lock().unwrap_or_else(|e| e.into_inner())
}

/// Chains a hook that, while a contained call runs, keeps the first panic's location and
/// message for [`contained`] and prints nothing; otherwise it calls the previous hook.
fn install_quiet_hook() {
    let previous = panic::take_hook();
    panic::set_hook(Box::new(move |info| {
        if ACTIVE.load(Ordering::SeqCst) == 0 {
            return previous(info);
        }
        let at = info.location().map_or_else(
            || "at an unknown place".to_owned(),
            |l| format!("at {}:{}:{}", l.file(), l.line(), l.column()),
        );
        let message = panic_message(info.payload());
        first().get_or_insert(format!("{at}: {message}"));
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_an_error_with_its_place_and_message() {
        let e = contained(|| -> u32 { panic!("boom {}", 7) }).unwrap_err();
        assert!(e.starts_with("panic at src/harness/contain.rs:"), "{e}");
        assert!(e.ends_with(": boom 7"), "{e}");
        assert_eq!(contained(|| 3), Ok(3));
    }

    /// A panic on a rayon worker reaches the contained caller with the worker's location.
    #[test]
    fn a_panic_in_a_pool_worker_is_contained() {
        use rayon::prelude::*;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let e = contained(|| {
            pool.install(|| {
                (0..64)
                    .into_par_iter()
                    .for_each(|i| assert!(i != 40, "ray {i}"));
            })
        })
        .unwrap_err();
        assert!(e.contains("contain.rs") && e.ends_with(": ray 40"), "{e}");
    }
}
