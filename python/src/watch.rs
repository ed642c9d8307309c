//! Running library work from Python: the work on a thread of its own, the interpreter's
//! thread polling for signals (Ctrl-C asks the work to stop at its next tile) and passing
//! progress to a Python callable, the work's report lines and warnings gathered.

use grinlight::commands::{Observer, Progress};
use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Duration;

/// How often the interpreter's thread looks for signals and reports progress.
const POLL: Duration = Duration::from_millis(50);

/// What the work said while it ran.
#[derive(Default)]
pub struct Report {
    /// Its report, line by line.
    pub lines: Vec<String>,
    /// Its warnings.
    pub warnings: Vec<String>,
}

/// The work's result and report.
pub struct Watched<T> {
    /// What the work returned.
    pub result: T,
    /// What it said.
    pub report: Report,
    /// Whether a `KeyboardInterrupt` asked it to stop (work that cannot stop part-way has
    /// finished all the same).
    pub interrupted: bool,
}

/// The observer the work reports to, read by the polling thread.
#[derive(Default)]
struct Watch {
    stop: AtomicBool,
    done: AtomicU64,
    total: AtomicU64,
    /// What is being done: "measuring" (receiver photons) or "rendering" (camera tiles).
    stage: Mutex<&'static str>,
    report: Mutex<Report>,
}

impl Observer for Watch {
    fn progress(&self, p: Progress) {
        match p {
            Progress::Measuring { photons, of, .. } => {
                *self.stage.lock().expect("stage") = "measuring";
                self.total.store(of, Ordering::Relaxed);
                self.done.store(photons.0, Ordering::Relaxed);
            }
            Progress::Rendering { tiles, passes, .. } => {
                *self.stage.lock().expect("stage") = "rendering";
                // With a time budget the count of passes is not known: no total.
                let total = passes.map_or(0, |p| tiles * p as u64);
                self.total.store(total, Ordering::Relaxed);
                self.done.store(0, Ordering::Relaxed);
            }
            Progress::Tile => {
                self.done.fetch_add(1, Ordering::Relaxed);
            }
            Progress::Pass(_) => {}
            Progress::Done => {
                let total = self.total.load(Ordering::Relaxed);
                self.done.fetch_max(total, Ordering::Relaxed);
            }
        }
    }

    fn line(&self, text: &str) {
        self.report.lock().expect("report").lines.push(text.into());
    }

    fn warning(&self, text: &str) {
        self.report
            .lock()
            .expect("report")
            .warnings
            .push(text.into());
    }

    fn stop_requested(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }
}

/// Runs `work` on a thread of its own; this thread releases the interpreter between polls
/// and, at each, runs Python's signal handlers and calls `progress(done, total, stage)`
/// (total 0: unknown). A `KeyboardInterrupt` asks the work to stop and lets it return what
/// it finished (the work's result says it was interrupted); any other exception from a
/// handler or from `progress` stops the work too and is raised once it has returned.
pub fn watched<T: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(&dyn Observer) -> T + Send,
) -> PyResult<Watched<T>> {
    let watch = Watch::default();
    let mut raised: Option<PyErr> = None;
    let mut interrupted = false;
    let result = std::thread::scope(|scope| {
        let running = scope.spawn(|| work(&watch));
        while !running.is_finished() {
            py.detach(|| std::thread::sleep(POLL));
            let polled = py.check_signals().and_then(|()| match progress {
                Some(callback) => {
                    let stage = *watch.stage.lock().expect("stage");
                    let done = watch.done.load(Ordering::Relaxed);
                    let total = watch.total.load(Ordering::Relaxed);
                    callback.call1((done, total, stage)).map(drop)
                }
                None => Ok(()),
            });
            if let Err(e) = polled {
                watch.stop.store(true, Ordering::Relaxed);
                if e.is_instance_of::<PyKeyboardInterrupt>(py) {
                    interrupted = true;
                } else if raised.is_none() {
                    raised = Some(e);
                }
            }
        }
        running.join()
    });
    let result = match result {
        Ok(r) => r,
        Err(panic) => std::panic::resume_unwind(panic),
    };
    if let Some(e) = raised {
        return Err(e);
    }
    Ok(Watched {
        result,
        report: watch.report.into_inner().expect("report"),
        interrupted,
    })
}

impl<T> Watched<T> {
    /// The result, or `KeyboardInterrupt` if one came while the work ran.
    pub fn uninterrupted(self) -> PyResult<T> {
        match self.interrupted {
            true => Err(PyKeyboardInterrupt::new_err("interrupted")),
            false => Ok(self.result),
        }
    }
}
