//! What a run may ask of the machine: worker threads and memory, checked before any work so an
//! absurd request is refused at once with a message instead of running until the machine
//! gives out.

use crate::error::{Error, Result};

/// The most worker threads a run may start per core: more only adds switching.
pub const THREADS_PER_CORE: usize = 16;

/// The machine's cores (1 if unknown).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `threads` (0: one per core) if at most [`THREADS_PER_CORE`] per core, else a usage error.
pub fn check_threads(threads: usize) -> Result<usize> {
    let limit = THREADS_PER_CORE * cores();
    if threads > limit {
        return Err(Error::Usage(format!(
            "{threads} threads on a machine with {} core(s): at most {limit} ({THREADS_PER_CORE} per core); 0 uses one per core",
            cores()
        )));
    }
    Ok(threads)
}

/// Memory the system can give a new process without swapping (Linux: `MemAvailable` of
/// /proc/meminfo), in bytes; None where that is not known.
pub fn available_memory() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

/// Refuses a run that needs more than `needed` bytes when the machine has less available,
/// naming `what` needs it.
pub fn check_memory(needed: u64, what: &str) -> Result<()> {
    match available_memory() {
        Some(free) if needed > free => Err(Error::Usage(format!(
            "{what} needs about {} of memory; this machine has {} available: \
             reduce the image size, photon counts or receiver photons",
            human(needed),
            human(free)
        ))),
        _ => Ok(()),
    }
}

/// A byte count for people (GiB/MiB/KiB).
pub fn human(bytes: u64) -> String {
    let b = bytes as f64;
    match bytes {
        0..=1_048_575 => format!("{:.1} KiB", b / 1024.0),
        1_048_576..=1_073_741_823 => format!("{:.1} MiB", b / 1_048_576.0),
        _ => format!("{:.1} GiB", b / 1_073_741_824.0),
    }
}
