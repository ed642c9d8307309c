//! What the user sees while a command runs: progress bars on standard error, the report on
//! standard output, and the interrupt that asks a render to stop.

use grinlight::commands::{Observer, Progress};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::Write;
use std::sync::Mutex;
use std::time::Instant;

/// The exit code of a run cut short by an interrupt (128 + SIGINT).
pub const INTERRUPTED: i32 = 130;

/// On the first interrupt, asks the running command to stop and write what it has; on the
/// second, quits at once (every output is written atomically, so no file is left half
/// written either way).
pub fn install_interrupt_handler() {
    let result = ctrlc::set_handler(|| {
        if grinlight::interrupt::requested() {
            eprintln!("\ninterrupted again: quitting at once");
            std::process::exit(INTERRUPTED);
        }
        grinlight::interrupt::request();
        eprintln!(
            "\ninterrupted: stopping and writing what is done (interrupt again to quit at once)"
        );
    });
    if let Err(e) = result {
        eprintln!("warning: cannot catch interrupts ({e}); Ctrl-C will lose the render");
    }
}

/// The terminal's view of a command.
pub struct Console {
    bar: Mutex<Option<Bar>>,
}

/// The current progress bar and what it counts.
struct Bar {
    bar: ProgressBar,
    /// A time budget (s) the bar shows instead of passes and tiles.
    budget: Option<f64>,
    passes: Option<u32>,
    pass: u32,
    start: Instant,
}

impl Console {
    /// A console with no bar yet.
    pub fn new() -> Self {
        Self {
            bar: Mutex::new(None),
        }
    }

    /// Removes the progress bar, if any.
    pub fn clear(&self) {
        if let Some(b) = self.bar.lock().expect("console lock").take() {
            b.bar.finish_and_clear();
        }
    }

    fn show(&self, bar: Bar) {
        self.clear();
        *self.bar.lock().expect("console lock") = Some(bar);
    }
}

impl Observer for Console {
    fn progress(&self, p: Progress) {
        match p {
            Progress::Measuring {
                photons: (first, end),
                of,
                receivers,
            } => {
                let what = match (first, end) {
                    (0, e) if e == of => format!("{of} photons"),
                    _ => format!("photons {first}..{end} of {of}"),
                };
                let bar = ProgressBar::new_spinner()
                    .with_message(format!("tracing {what} for {receivers} receiver(s)"));
                bar.enable_steady_tick(std::time::Duration::from_millis(200));
                self.show(Bar {
                    bar,
                    budget: None,
                    passes: None,
                    pass: 0,
                    start: Instant::now(),
                });
            }
            Progress::Rendering {
                tiles,
                passes,
                time_budget,
            } => {
                // With a time budget and no pass count, the bar is the budget's time.
                let (len, template) = match (passes, time_budget) {
                    (None, Some(b)) => ((b * 1000.0) as u64, "{elapsed_precise} [{bar:40}] {msg}"),
                    (p, _) => (
                        tiles * p.unwrap_or(1) as u64,
                        "{elapsed_precise} [{bar:40}] {msg} ETA {eta}",
                    ),
                };
                let bar = ProgressBar::new(len.max(1))
                    .with_style(ProgressStyle::with_template(template).expect("valid template"));
                self.show(Bar {
                    bar,
                    budget: time_budget.filter(|_| passes.is_none()),
                    passes,
                    pass: 0,
                    start: Instant::now(),
                });
            }
            Progress::Pass(i) => {
                if let Some(b) = self.bar.lock().expect("console lock").as_mut() {
                    b.pass = i;
                    b.update(false);
                }
            }
            Progress::Tile => {
                if let Some(b) = self.bar.lock().expect("console lock").as_mut() {
                    b.update(true);
                }
            }
            Progress::Done => self.clear(),
        }
    }

    fn line(&self, text: &str) {
        let print = || {
            // A closed standard output (`grinlight … | head`) must not stop the run: its
            // files are what matters.
            let _ = writeln!(std::io::stdout().lock(), "{text}");
        };
        match self.bar.lock().expect("console lock").as_ref() {
            Some(b) => b.bar.suspend(print),
            None => print(),
        }
    }

    fn warning(&self, text: &str) {
        let print = || eprintln!("warning: {text}");
        match self.bar.lock().expect("console lock").as_ref() {
            Some(b) => b.bar.suspend(print),
            None => print(),
        }
    }

    fn stop_requested(&self) -> bool {
        grinlight::interrupt::requested()
    }
}

impl Bar {
    /// Shows the pass and, after a tile, one more tile done (or, against a time budget, the
    /// time spent and left; with as many passes as a target error takes, the current pass's
    /// tiles).
    fn update(&mut self, tile: bool) {
        let pass = self.pass + 1;
        match (self.budget, self.passes) {
            (Some(budget), _) => {
                let spent = self.start.elapsed().as_secs_f64();
                self.bar.set_position((spent.min(budget) * 1000.0) as u64);
                self.bar.set_message(format!(
                    "pass {pass}, {:.0} s of the {budget} s budget left",
                    (budget - spent).max(0.0)
                ));
            }
            (None, Some(passes)) => {
                if tile {
                    self.bar.inc(1);
                }
                self.bar.set_message(format!("pass {pass}/{passes}"));
            }
            // As many passes as a target error takes: the bar is the current pass's tiles.
            (None, None) => {
                match tile {
                    true => self.bar.inc(1),
                    false => self.bar.set_position(0),
                }
                self.bar.set_message(format!(
                    "pass {pass}, until the estimated error reaches the target"
                ));
            }
        }
    }
}
