//! The process's interrupt: asked for by a signal (the command line's Ctrl-C, SIGTERM, SIGHUP)
//! or a `KeyboardInterrupt` (the Python package), and polled by the long loops that have no
//! observer to ask — reading a mesh, a grid or a density file — so that no input, however
//! large or strange, keeps the program from stopping. Renders also ask their observer
//! ([`crate::render::Observer::stop_requested`]), which the front ends answer from it.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Asks whatever runs to stop.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Whether a stop was asked for (and not cleared since).
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// Forgets a stop asked for earlier (before new work from a front end that lives on, as the
/// Python interpreter does).
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}

/// Records a loop polls at most this often (a record of a mesh or a grid is cheap to read).
pub const POLL_EVERY: usize = 1 << 16;

/// For a loop at step `i`: an error saying reading `what` was interrupted, when a stop was
/// asked for (looked at every [`POLL_EVERY`] steps).
pub fn check(i: usize, what: &str) -> Result<(), String> {
    match i.is_multiple_of(POLL_EVERY) && requested() {
        true => Err(format!("interrupted while reading {what}")),
        false => Ok(()),
    }
}
