//! What a running render or measurement tells its caller: its progress, its report line by
//! line, its warnings, each finished pass; and the one question it asks — whether to stop.

use crate::error::Result;
use crate::film::Film;

/// What a render or a measurement reports as it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Progress {
    /// A receiver measurement (or a block of one) starts: photons to trace, receivers.
    Measuring {
        /// The photons traced now (indices in the batch).
        photons: (u64, u64),
        /// Photons in the batch.
        of: u64,
        /// Receivers measured.
        receivers: usize,
    },
    /// A camera render starts.
    Rendering {
        /// Camera tiles per pass.
        tiles: u64,
        /// Passes to render (None: as many as the time budget allows).
        passes: Option<u32>,
        /// Seconds after which no new pass starts.
        time_budget: Option<f64>,
    },
    /// A pass starts (0-based), with its photon pass.
    Pass(u32),
    /// One camera tile of the current pass is done.
    Tile,
    /// The render or measurement has ended.
    Done,
}

/// Who watches a render or a measurement: told of its progress and of every finished pass,
/// and asked whether to stop. `()` watches nothing and never stops.
pub trait Observer: Sync {
    /// A step of progress.
    fn progress(&self, _p: Progress) {}
    /// A line of a command's report, as soon as it is known (see [`crate::commands`]).
    fn line(&self, _text: &str) {}
    /// A warning: the command goes on, but its user should know.
    fn warning(&self, _text: &str) {}
    /// `passes` passes are finished; `film()` assembles their film (a whole film's copy:
    /// only when needed, e.g. to write a checkpoint). An error stops the render with it.
    fn pass_done(&self, _passes: u32, _film: &dyn Fn() -> Film) -> Result<()> {
        Ok(())
    }
    /// Whether to stop as soon as possible (an interrupt): a render abandons its current pass
    /// and returns the passes it finished, marked as partial in its [`Report`].
    fn stop_requested(&self) -> bool {
        false
    }
}

impl Observer for () {}
