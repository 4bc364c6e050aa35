//! Ctrl-C (SIGINT) during a suite run: the first one asks the run to stop at the next index's
//! counting pass or the next timed pass, so what was measured (the ray sets finished before) is
//! written as an `interrupted` report; a second one ends the process at once (exit 130, the
//! shell's code for SIGINT).
//!
//! The flag is process-wide: only the handler [`stop_on_sigint`] installs sets it, and the suite
//! reads it between ray sets and between passes ([`requested`]), never inside a timed pass.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, LazyLock};

/// Set by the SIGINT handler once [`stop_on_sigint`] installed it.
static REQUESTED: LazyLock<Arc<AtomicBool>> = LazyLock::new(|| Arc::new(AtomicBool::new(false)));

/// Whether a stop was asked for (a SIGINT arrived since [`stop_on_sigint`]).
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}

/// Installs the handler: the first SIGINT sets the flag [`requested`] reads, a second one
/// exits with code 130 without waiting for the run (signal-hook's handlers only store to an
/// atomic or call `_exit`, which is async-signal-safe).
pub fn stop_on_sigint() -> std::io::Result<()> {
    use signal_hook::consts::SIGINT;
    signal_hook::flag::register_conditional_shutdown(SIGINT, 130, Arc::clone(&REQUESTED))?;
    signal_hook::flag::register(SIGINT, Arc::clone(&REQUESTED))?;
    Ok(())
}
