//! The commands of the `grinlight` program as library calls: what a user can do from the
//! command line, a library user does with one call ([`render()`], [`validate()`] (from
//! [`crate::fiber`]), [`trace()`]). Each takes a job (the scene file and the command line's choices) and an
//! [`Observer`] that is told of progress, shown the report line by line and asked whether to
//! stop; each checks every file it will write before any work (see [`crate::output`]) and
//! what it asks of the machine (see [`crate::resources`]).

mod render;
mod trace;

pub use crate::fiber::{validate, ValidateJob};
pub use render::{render, Overrides, RenderJob, RenderOutcome};
pub use trace::{trace, TraceControl, TraceJob};

pub use crate::render::{Observer, Progress};

use crate::error::{Error, Result};

/// `v` if it is a finite number > 0, else a usage error naming the flag.
pub fn positive(flag: &str, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 && v <= crate::scene::table::MAX_MAGNITUDE {
        Ok(v)
    } else {
        Err(Error::Usage(format!(
            "--{flag} must be a number in (0, {:e}], got {v}",
            crate::scene::table::MAX_MAGNITUDE
        )))
    }
}

/// `n` if it is at least 1, else a usage error naming the flag (the scene file refuses 0 for
/// the same keys; so does the command line).
pub(crate) fn at_least_one<T: Copy + PartialOrd + From<u8> + std::fmt::Display>(
    flag: &str,
    n: T,
) -> Result<T> {
    if n >= T::from(1) {
        Ok(n)
    } else {
        Err(Error::Usage(format!(
            "--{flag} must be at least 1, got {n}"
        )))
    }
}
