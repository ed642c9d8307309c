//! Doing a partial's remaining work: its receiver photons in blocks, then its passes, saving
//! the partial as whole blocks and passes finish.

use super::Partial;
use crate::error::Result;
use crate::film::Film;
use crate::render::{self, Observer, Passes, Report};
use crate::scene::Scene;
use crate::settings::Settings;
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// Receiver photons per block: the unit of receiver work a saved partial holds (blocks start
/// at multiples of it, so every shard's blocks are the same photons).
pub const BLOCK: u64 = 1 << 18;

/// When a running partial is saved, and how.
pub struct Saving<'a> {
    /// Save after every this many passes and after every receiver block (0: by time only).
    pub every: u32,
    /// Save when a pass or block ends at least this long after the last save.
    pub interval: Duration,
    /// Writes the partial (and whatever goes with it: a preview image).
    pub save: &'a (dyn Fn(&Partial) -> Result<()> + Sync),
}

/// What a run did.
pub struct Ran {
    /// The partial with the work done: whole receiver blocks and whole passes.
    pub partial: Partial,
    /// The receiver photons' report (None: none traced).
    pub receivers: Option<Report>,
    /// The camera's report (None: no pass rendered).
    pub camera: Option<Report>,
}

impl Ran {
    /// Whether an interrupt cut it short.
    pub fn interrupted(&self) -> bool {
        [&self.receivers, &self.camera]
            .iter()
            .any(|r| r.as_ref().is_some_and(|r| r.partial.is_some()))
    }
}

/// Does `partial`'s remaining work on `scene` with `settings` (those its header was made
/// from): the receiver photons first, in [`BLOCK`]s, then the passes; saved as `saving` says.
/// An interrupt (the observer's stop) ends it with the whole blocks and passes done; a time
/// budget ends it whole, with the passes that fitted.
pub fn run(
    scene: &Scene,
    settings: &Settings,
    partial: Partial,
    observer: &dyn Observer,
    saving: &Saving,
) -> Result<Ran> {
    let saver = Saver {
        saving,
        last: Mutex::new((Instant::now(), Duration::ZERO)),
    };
    let (passes, photons) = partial.remaining();
    let mut ran = Ran {
        partial,
        receivers: None,
        camera: None,
    };
    'blocks: for r in photons.ranges() {
        let mut start = r.start;
        while start < r.end {
            let end = ((start / BLOCK + 1) * BLOCK).min(r.end);
            let (books, report) =
                render::trace_receivers(scene, settings, 0, start..end, observer)?;
            let stopped = report.partial.is_some();
            let mut total = ran.receivers.take().unwrap_or_default();
            total.stats.add(&report.stats);
            total.seconds.photons += report.seconds.photons;
            total.passes = 1;
            total.partial = report.partial;
            ran.receivers = Some(total);
            if stopped {
                break 'blocks;
            }
            ran.partial.add_photons(start..end, &books)?;
            if saver.due(saving.every > 0) {
                saver.save(&ran.partial)?;
            }
            start = end;
        }
    }
    if ran.interrupted() {
        return Ok(ran);
    }
    for r in passes.ranges() {
        let watcher = Watcher {
            outer: observer,
            first: r.start,
            partial: &ran.partial,
            saver: &saver,
        };
        let range = Passes {
            first: r.start as u32,
            count: (r.end - r.start) as u32,
            earlier: ran.partial.film.as_ref(),
        };
        let (film, report) = render::render_passes(scene, settings, range, &watcher)?;
        let done = r.start..r.start + report.passes as u64;
        let stopped = report.partial.is_some();
        ran.camera = Some(report);
        ran.partial.add_passes(done, film)?;
        if stopped {
            break;
        }
    }
    let open_ended = settings.time_budget.is_some() || settings.target_error.is_some();
    if open_ended && !ran.interrupted() {
        // The budget or the error reached, not a pass count, ended the render: it is whole
        // with the passes done.
        ran.partial.header.passes = ran.partial.passes.len() as u32;
    }
    Ok(ran)
}

/// Saves a partial when its `Saving` says it is due.
struct Saver<'a> {
    saving: &'a Saving<'a>,
    /// When the last save ended, and how long it took.
    last: Mutex<(Instant, Duration)>,
}

/// Saves by time keep at least this many times their own duration apart (a large film's
/// partial takes seconds to write: at most 5 % of the run goes to saving it).
const SAVE_COST_FACTOR: u32 = 20;

impl Saver<'_> {
    /// Whether to save now: at a `boundary` the saving asks for, or when its interval (and
    /// [`SAVE_COST_FACTOR`] times the last save's duration) is up.
    fn due(&self, boundary: bool) -> bool {
        let (at, cost) = *self.last.lock().expect("saver lock");
        boundary || at.elapsed() >= self.saving.interval.max(cost * SAVE_COST_FACTOR)
    }

    fn save(&self, partial: &Partial) -> Result<()> {
        let t0 = Instant::now();
        (self.saving.save)(partial)?;
        *self.last.lock().expect("saver lock") = (Instant::now(), t0.elapsed());
        Ok(())
    }
}

/// The caller's observer, saving the partial with the passes finished so far when due.
struct Watcher<'a> {
    outer: &'a dyn Observer,
    /// The first pass of the range rendered.
    first: u64,
    /// The partial before the range.
    partial: &'a Partial,
    saver: &'a Saver<'a>,
}

impl Observer for Watcher<'_> {
    fn progress(&self, p: render::Progress) {
        self.outer.progress(p);
    }
    fn line(&self, text: &str) {
        self.outer.line(text);
    }
    fn warning(&self, text: &str) {
        self.outer.warning(text);
    }
    fn stop_requested(&self) -> bool {
        self.outer.stop_requested()
    }
    fn pass_done(&self, passes: u32, film: &dyn Fn() -> Film) -> Result<()> {
        let every = self.saver.saving.every;
        if self.saver.due(every > 0 && passes.is_multiple_of(every)) {
            let mut p = self.partial.clone();
            p.add_passes(self.first..self.first + passes as u64, film())?;
            self.saver.save(&p)?;
        }
        self.outer.pass_done(passes, film)
    }
}
