//! The receivers measured: photons traced from the lights, booked at every receiver crossing
//! and in the energy budget, as [`Books`] that add exactly across photon ranges.

use super::{thread_pool, Observer, Progress, Report};
use crate::error::Result;
use crate::photon::{shoot, Batch, Budget, Ledger, Photons, Sources};
use crate::receiver::{self, Measurement};
use crate::scene::Scene;
use crate::settings::Settings;
use crate::transport::Tracer;
use std::time::Instant;

/// Measures the scene's receivers with `settings.receiver_photons` photons from its lights
/// (stream pass `pass`), traced like global photons (diffuse bounces with Russian
/// roulette) and recorded at every receiver crossing; with where their power went.
///
/// Stopped by `observer`, the measurement holds the photons traced so far (whole chunks, an
/// unbiased subset of the batch), their fluxes and budget scaled to the emitted power, and
/// its report says so.
pub fn measure(
    scene: &Scene,
    settings: &Settings,
    pass: u64,
    observer: &dyn Observer,
) -> Result<(Vec<Measurement>, Budget, Report)> {
    let count = settings.receiver_photons;
    let (books, report) = trace_receivers(scene, settings, pass, 0..count, observer)?;
    let scale = count as f64 / books.traced.max(1) as f64;
    Ok((
        books.measurements(&scene.receivers, scale),
        books.ledger.statement(scale),
        report,
    ))
}

/// What the receiver photons traced left: each receiver's tally, the energy ledger, and how
/// many photons were traced. Books of disjoint photon ranges add exactly ([`Books::add`]).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Books {
    /// Per receiver, in scene order.
    pub tallies: Vec<receiver::Tally>,
    /// Where the photons' power went.
    pub ledger: Ledger,
    /// Photons traced.
    pub traced: u64,
}

impl Books {
    /// Adds the books of other photons of the same batch.
    pub fn add(&mut self, other: &Books) {
        if self.tallies.is_empty() {
            self.tallies = vec![Default::default(); other.tallies.len()];
        }
        for (a, b) in self.tallies.iter_mut().zip(&other.tallies) {
            a.merge(b);
        }
        self.ledger.add(&other.ledger);
        self.traced += other.traced;
    }

    /// Whether books read from a file fit `receivers` and a scene of `primitives` primitives
    /// and `media` media (a tally per receiver, of its bins and bands; a budget of its
    /// primitives and media): the reason when not.
    pub fn fits(
        &self,
        receivers: &[receiver::Receiver],
        primitives: usize,
        media: usize,
    ) -> std::result::Result<(), String> {
        if !self.tallies.is_empty() && self.tallies.len() != receivers.len() {
            return Err(format!(
                "books of {} receivers for a scene of {}",
                self.tallies.len(),
                receivers.len()
            ));
        }
        for (t, r) in self.tallies.iter().zip(receivers) {
            t.fits(r)?;
        }
        self.ledger
            .fits(primitives, media, receiver::distinct_bands(receivers).len())
    }

    /// Each receiver's measurement, every flux times `scale` (1 when the whole batch was
    /// traced).
    pub fn measurements(&self, receivers: &[receiver::Receiver], scale: f64) -> Vec<Measurement> {
        receivers
            .iter()
            .zip(&self.tallies)
            .map(|(r, t)| t.measurement(r, self.traced, scale))
            .collect()
    }
}

/// Traces photons `traced` of the receiver batch of stream pass `pass` (each carrying
/// 1/`settings.receiver_photons` of the lights' power) and books their receiver crossings and
/// fates. Stopped by `observer`, the books hold the whole chunks traced, and the report says
/// so.
pub fn trace_receivers(
    scene: &Scene,
    settings: &Settings,
    pass: u64,
    traced: std::ops::Range<u64>,
    observer: &dyn Observer,
) -> Result<(Books, Report)> {
    super::photons_carry_all_light(scene)?;
    let tracer = Tracer::new(scene, &settings.trace);
    let sources = Sources::for_receivers(&tracer);
    let pool = thread_pool(settings.threads)?;
    let count = traced.end - traced.start;
    observer.progress(Progress::Measuring {
        photons: (traced.start, traced.end),
        of: settings.receiver_photons,
        receivers: scene.receivers.len(),
    });
    let t0 = Instant::now();
    let (sink, stats) = pool.install(|| {
        let photons = Photons {
            traced,
            ..Photons::all(
                Batch::Receivers,
                settings.seed,
                pass,
                settings.receiver_photons,
            )
        };
        shoot(&tracer, &sources, photons, &|| observer.stop_requested())
    });
    observer.progress(Progress::Done);
    let done = stats.photons_emitted;
    let mut report = Report {
        passes: 1,
        stats,
        seconds: crate::report::Seconds {
            photons: t0.elapsed().as_secs_f64(),
            ..Default::default()
        },
        ..Report::default()
    };
    if done < count && !sources.is_empty() {
        report.partial = Some(format!("{done} of {count} receiver photons"));
    }
    let books = Books {
        tallies: receiver::tally(
            &scene.receivers,
            &sink.detections,
            tracer.settings.polarized,
        ),
        ledger: sink.budget,
        traced: if sources.is_empty() { count } else { done },
    };
    Ok((books, report))
}
