//! The render: an integrator ([`crate::integrator`]) driven over passes and tiles. Each pass
//! asks the integrator to prepare (e.g. trace its photon maps), then runs every tile's camera
//! samples in parallel into the tiles' films; after each pass the tiles are pasted into the
//! whole film, which the observer may write. Every random stream is keyed by (seed, pass,
//! pixel, sample) or (seed, pass, photon), so the image does not depend on the thread count,
//! and passes are independent: a film of passes rendered apart merges into the same image.
//!
//! Also here: the receivers' measurement ([`measure`], [`Books`]: `render/measurement.rs`) and what a render will need of the
//! machine ([`memory_needed`]).

use crate::camera::{FilmPoint, PrimaryRay};
use crate::color::Rgb;
use crate::error::{Error, Result};
use crate::film::{ErrorTotals, Film, Layer, STOKES_LAYERS};
use crate::integrator::{CameraRay, DeflectionTable, Integrator, PathTracer, PhotonMapper, Sample};
use crate::lights::LightSamples;
use crate::pixel_filter::Placement;
pub use crate::report::Report;
use crate::scene::Scene;
use crate::settings::IntegratorKind as Kind;
use crate::settings::Settings;
use crate::transport::{Stats, Tracer};
use rayon::prelude::*;
use std::time::Instant;

mod measurement;
mod progress;
pub mod sampler;
pub use measurement::{measure, trace_receivers, Books};
pub use progress::{Observer, Progress};
use sampler::{PixelPass, SampleStart, Sampling};

/// Tile edge in pixels.
const TILE: usize = 16;

/// The fewest passes after which a target error may end a render: the image's error is
/// estimated from the spread of its passes, and with fewer than four the estimate (from
/// three degrees of freedom a pixel) is too rough to stop on.
pub const MIN_PASSES_FOR_ERROR: u32 = 4;

/// A tile of the render: its film of the passes finished, and while a pass runs, what the
/// pass added to it.
struct Tile {
    film: crate::film::Tile,
    /// The current pass's additions, so that a pass cut short can be taken back exactly.
    pass: Option<PassRecord>,
}

/// What one pass added to a tile's film: per layer and pixel (row-major), the RGB sum of its
/// samples as added (rounded to f32, so a layer's record is a quarter of its sums; none for a
/// layer the pass left at zero), the samples, and which planes the film held before (a plane
/// the pass allocated goes again).
struct PassRecord {
    layers: Vec<Vec<[f32; 3]>>,
    samples: u64,
    held: Vec<bool>,
}

impl PassRecord {
    /// An empty record of a pass adding `samples` samples a pixel to `layers` layers.
    fn new(layers: usize, samples: u64, held: Vec<bool>) -> Self {
        PassRecord {
            layers: vec![Vec::new(); layers],
            samples,
            held,
        }
    }

    /// Records pixel `i`'s `values`, each rounded to f32 in place (as the film is given
    /// them); a layer's record is allocated at its first value other than zero.
    fn record(&mut self, i: usize, pixels: usize, values: &mut [Rgb]) {
        for (record, v) in self.layers.iter_mut().zip(values) {
            let rounded = v.as_vec3().to_array();
            *v = Rgb::new(rounded[0] as f64, rounded[1] as f64, rounded[2] as f64);
            if record.is_empty() {
                if *v == Rgb::ZERO {
                    continue;
                }
                *record = vec![[0.0; 3]; pixels];
            }
            record[i] = rounded;
        }
    }

    /// Pixel `i`'s recorded values.
    fn values(&self, i: usize, out: &mut [Rgb]) {
        for (o, record) in out.iter_mut().zip(&self.layers) {
            *o = record.get(i).map_or(Rgb::ZERO, |p| {
                Rgb::new(p[0] as f64, p[1] as f64, p[2] as f64)
            });
        }
    }
}

impl Tile {
    /// Takes back the current pass's additions, if any: the film is then exactly the film of
    /// the passes before.
    fn take_back(&mut self, layers: usize) {
        let Some(record) = self.pass.take() else {
            return;
        };
        let film = &mut self.film.film;
        let mut values = vec![Rgb::ZERO; layers];
        for i in 0..film.width * film.height {
            record.values(i, &mut values);
            film.remove(i % film.width, i / film.width, &values, record.samples);
        }
        film.keep_planes(&record.held);
    }
}

/// Renders the scene's camera view as `settings` say, with the integrator they name, telling
/// `observer` of every pass and tile and asking it whether to stop.
pub fn render(
    scene: &Scene,
    settings: &Settings,
    observer: &dyn Observer,
) -> Result<(Film, Report)> {
    let passes = Passes {
        first: 0,
        count: settings.passes,
        earlier: None,
    };
    render_passes(scene, settings, passes, observer)
}

/// Renders `passes` of the scene's camera view (of the `settings.passes` a whole render has:
/// pass p is the same pass whichever range it is rendered in, so films of disjoint ranges
/// merge into the film of their union).
pub fn render_passes(
    scene: &Scene,
    settings: &Settings,
    passes: Passes,
    observer: &dyn Observer,
) -> Result<(Film, Report)> {
    let tracer = Tracer::new(scene, &settings.trace);
    match settings.integrator {
        Kind::PhotonMap => {
            photons_carry_all_light(scene)?;
            let tracer = tracer.sampling_lights(LightSamples::Each);
            let stop = || observer.stop_requested();
            let table = settings
                .deflection_table
                .then(|| DeflectionTable::new(&tracer, &stop))
                .flatten();
            match table {
                Some(table) if table.usable() => {
                    return render_with(&table, &tracer, settings, passes, observer);
                }
                Some(table) => observer.warning(&format!(
                    "{}: not within a tenth of a pixel, so every camera ray is traced instead",
                    table.summary()
                )),
                None => {}
            }
            let integrator = PhotonMapper::new(&tracer, settings);
            render_with(&integrator, &tracer, settings, passes, observer)
        }
        Kind::Path => render_with(
            &PathTracer::new(&tracer),
            &tracer,
            settings,
            passes,
            observer,
        ),
    }
}

/// Refuses a scene whose light photons cannot carry: light emitted by a medium (no photon
/// is sent from a volume), which the photon mapper and the receivers would leave out. The
/// path tracer gathers it along every camera path.
fn photons_carry_all_light(scene: &Scene) -> Result<()> {
    match scene.media().first_emitting() {
        None => Ok(()),
        Some(name) => Err(crate::error::Error::Setting {
            key: "integrator",
            message: format!(
                "medium '{name}' emits light (`emission`), and photons are sent only from lights: \
                 render it with integrator = \"path\" (receivers cannot measure it)"
            ),
        }),
    }
}

/// The warning a camera view of `scene` needs where a dye's light may be missing from it: both
/// integrators path trace the light a dye absorbs ([`crate::integrator`]), so light of a
/// point, spot, LED, goniometric or parallel source that reaches the dye only through a
/// refracting or reflecting surface (a lamp shining into a dyed glass block) is found by no
/// sample. None where no medium holds a dye or every light is an area light.
pub fn dye_light_warning(scene: &Scene) -> Option<String> {
    let medium = scene.media().first_fluorescent()?;
    scene.lights.iter().any(|l| !l.is_met_by_rays()).then(|| {
        format!(
            "medium '{medium}' holds a dye: an image shows the light it absorbs from point, \
                 spot, LED, goniometric and parallel lights only where that light reaches it in \
                 a straight line (through index-matched boundaries), not through a refracting \
                 or reflecting surface; its receivers measure all of it"
        )
    })
}

/// Refuses a camera or a light inside a uniaxial crystal: light there travels as the crystal's
/// two waves, and neither a camera's nor a source's light is written for them (paths that would
/// set off in one are lost: [`crate::transport::Stats::lost_in_crystal`]).
pub fn sources_outside_crystals(scene: &Scene, tracer: &Tracer) -> Result<()> {
    let inside = |medium: Option<crate::ids::MediumId>| {
        medium.and_then(|m| scene.media().crystal(m).map(|_| m))
    };
    let camera = scene.camera.as_ref().and(inside(tracer.camera_medium));
    let light = (scene.lights.iter())
        .filter_map(|l| l.origin())
        .find_map(|p| inside(tracer.medium_containing(p)));
    match camera
        .map(|m| ("camera", m))
        .or(light.map(|m| ("a light", m)))
    {
        Some((what, m)) => Err(crate::error::Error::Usage(format!(
            "{}: {what} sits inside crystal '{}': place it outside the crystal, whose faces \
             split the light it sends or receives",
            scene.path().display(),
            scene.media().names().nth(m.index()).unwrap_or_default()
        ))),
        None => Ok(()),
    }
}

/// A range of global pass indices.
#[derive(Clone, Copy, Debug)]
pub struct Passes<'f> {
    /// The first pass's index.
    pub first: u32,
    /// How many (`u32::MAX` with a time budget: as many as fit).
    pub count: u32,
    /// The film of the passes already rendered before this range (a resumed render's): the
    /// target error is judged on them and the range together, as one render would.
    pub earlier: Option<&'f Film>,
}

/// Renders `passes` of the tracer's scene with `integrator` into one film. Stopped by the
/// observer, it returns the film of the passes it finished (a pass cut short is left out, so
/// that the film is exactly those passes), and its report says so.
pub fn render_with<I: Integrator>(
    integrator: &I,
    tracer: &Tracer,
    settings: &Settings,
    passes: Passes,
    observer: &dyn Observer,
) -> Result<(Film, Report)> {
    let (w, h) = film_size(tracer)?;
    // The integrator's layers, then the Stokes vector's where the camera measures it.
    let stokes: &[Layer] = match tracer.settings.stokes {
        true => &STOKES_LAYERS,
        false => &[],
    };
    let layers = &[integrator.layers(), stokes].concat();
    let mut tiles = tiles(w, h, layers);
    let assemble = |tiles: &[Tile], passes: u32| {
        Film::assembled(w, h, layers, passes, tiles.iter().map(|t| &t.film))
    };
    let pool = thread_pool(settings.threads)?;
    let start = Instant::now();
    let mut report = Report::default();
    let mut target = settings
        .target_error
        .map(|t| Target::new(t, passes.earlier, &tiles));
    observer.progress(Progress::Rendering {
        tiles: tiles.len() as u64,
        passes: (passes.count != u32::MAX).then_some(passes.count),
        time_budget: settings.time_budget,
    });
    let stop = || observer.stop_requested();
    for k in 0..passes.count {
        let pass = passes.first.saturating_add(k);
        let over_budget = settings
            .time_budget
            .is_some_and(|b| start.elapsed().as_secs_f64() >= b);
        if (k > 0 && over_budget) || stop() {
            break;
        }
        if target
            .as_mut()
            .is_some_and(|t| t.reached(&tiles, start, observer))
        {
            break;
        }
        observer.progress(Progress::Pass(k));
        let Some(prepared) = pool.install(|| integrator.begin_pass(pass, &mut report, &stop))
        else {
            // Stopped while preparing (e.g. tracing photons): the pass is abandoned.
            report.partial = Some(format!(
                "{k} of {} passes; pass {} abandoned while tracing photons",
                passes.count,
                k + 1
            ));
            break;
        };
        let t0 = Instant::now();
        let sampling = Sampling {
            seed: settings.seed,
            spp: settings.spp.max(1),
            pass,
            kind: settings.sampler,
        };
        let done = pool.install(|| {
            camera_pass(
                integrator, &prepared, tracer, sampling, &mut tiles, observer,
            )
        });
        report.seconds.camera += t0.elapsed().as_secs_f64();
        for (s, _) in &done {
            report.stats.add(s);
        }
        let finished = done.iter().filter(|(_, run)| *run).count();
        if finished < tiles.len() {
            // The film is exactly the passes finished: this one's tiles are taken back.
            tiles.par_iter_mut().for_each(|t| t.take_back(layers.len()));
            report.partial = Some(format!(
                "{k} of {} passes, and pass {} on {finished} of {} tiles of 16 × 16 pixels",
                passes.count,
                k + 1,
                tiles.len()
            ));
            break;
        }
        report.passes = k + 1;
        for t in &mut tiles {
            t.pass = None;
            t.film.film.passes = report.passes;
        }
        observer.pass_done(report.passes, &|| assemble(&tiles, report.passes))?;
    }
    if report.partial.is_none() && stop() && report.passes < passes.count {
        report.partial = Some(format!("{} of {} passes", report.passes, passes.count));
    }
    observer.progress(Progress::Done);
    let film = Film::from_tiles(
        w,
        h,
        layers,
        report.passes,
        tiles.into_iter().map(|t| t.film),
    );
    Ok((film, report))
}

/// The stopping rule of a target error: the film's own estimate of its relative RMSE, over
/// the passes of the range rendered and those rendered before it, after at least
/// [`MIN_PASSES_FOR_ERROR`] passes.
struct Target {
    error: f64,
    /// The earlier passes' film cut as the tiles are (empty without one).
    earlier: Vec<Film>,
    /// Whether the user was told the target looks out of reach.
    warned: bool,
    /// The passes at the last check.
    checked: u32,
}

/// A render this long that is projected to need ten times as long again for its target error
/// says so, once.
const TARGET_OUT_OF_REACH_AFTER: f64 = 60.0;

impl Target {
    fn new(error: f64, earlier: Option<&Film>, tiles: &[Tile]) -> Self {
        let earlier = earlier
            .map(|f| {
                tiles
                    .iter()
                    .map(|t| f.crop(t.film.x0, t.film.y0, t.film.film.width, t.film.film.height))
                    .collect()
            })
            .unwrap_or_default();
        Self {
            error,
            earlier,
            warned: false,
            checked: 0,
        }
    }

    /// Whether the film of the earlier passes and `tiles` has reached the target (printing its
    /// estimate after each pass): its estimate at or below it, or every pass exactly black (no
    /// error to reduce). Warns once when the rate so far puts the target ten times the time
    /// spent (`start`) away.
    fn reached(&mut self, tiles: &[Tile], start: Instant, observer: &dyn Observer) -> bool {
        let totals = tiles
            .par_iter()
            .enumerate()
            .map(|(i, t)| match self.earlier.get(i) {
                Some(e) => {
                    let mut f = e.clone();
                    f.merge(&t.film.film)
                        .expect("a tile and its crop of the earlier film are of one view");
                    (f.error_totals(), f.passes)
                }
                None => (t.film.film.error_totals(), t.film.film.passes),
            })
            .reduce(
                || (ErrorTotals::default(), 0),
                |a, b| (a.0 + b.0, a.1.max(b.1)),
            );
        let (totals, passes) = totals;
        if passes == self.checked {
            return false;
        }
        self.checked = passes;
        if passes < 2 {
            return false;
        }
        if totals.mean <= 0.0 {
            let black = totals.variance == 0.0 && passes >= MIN_PASSES_FOR_ERROR;
            if black {
                observer.line(&format!(
                    "pass {passes}: the image is black in every pass: no error to reduce"
                ));
            }
            return black;
        }
        let error = totals.relative_rmse();
        observer.line(&format!(
            "pass {passes}: estimated error {error:.4} (relative RMSE; target {})",
            self.error
        ));
        let elapsed = start.elapsed().as_secs_f64();
        // The estimate falls as 1/√passes: the target is (error/target)² times the passes away.
        let needed = passes as f64 * (error / self.error).powi(2);
        if !self.warned && elapsed >= TARGET_OUT_OF_REACH_AFTER && needed >= 11.0 * passes as f64 {
            self.warned = true;
            observer.warning(&format!(
                "target error {} looks out of reach: {error:.4} after {passes} passes, about \
                 {needed:.0} passes ({:.0} s more at this rate) to reach it; the render goes on \
                 until then, a time budget or Ctrl-C",
                self.error,
                elapsed * (needed / passes as f64 - 1.0)
            ));
        }
        error <= self.error && passes >= MIN_PASSES_FOR_ERROR
    }
}

/// The camera's film size in pixels, or an error naming the scene that has no camera.
fn film_size(tracer: &Tracer) -> Result<(usize, usize)> {
    let camera = tracer.scene.camera.as_ref().ok_or_else(|| {
        Error::Usage(format!(
            "{}: the scene has no [camera]",
            tracer.scene.path().display()
        ))
    })?;
    let window = camera.window();
    if !window.fits(camera.width, camera.height) {
        return Err(Error::Usage(format!(
            "{}: [camera] crop {}×{} at ({}, {}) does not lie within the {}×{} image",
            tracer.scene.path().display(),
            window.width,
            window.height,
            window.x,
            window.y,
            camera.width,
            camera.height
        )));
    }
    Ok((window.width as usize, window.height as usize))
}

/// The tiles of a `w` × `h` film of `layers`, row by row.
fn tiles(w: usize, h: usize, layers: &[crate::film::Layer]) -> Vec<Tile> {
    let mut tiles = Vec::new();
    for ty in 0..h.div_ceil(TILE) {
        for tx in 0..w.div_ceil(TILE) {
            let (x0, y0) = (tx * TILE, ty * TILE);
            let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
            tiles.push(Tile {
                film: crate::film::Tile {
                    x0,
                    y0,
                    film: Film::new(x1 - x0, y1 - y0, layers),
                },
                pass: None,
            });
        }
    }
    tiles
}

/// One pass of camera samples over every tile, in parallel; per tile its statistics and
/// whether it ran (tiles not started when the observer asks to stop are left as they were).
fn camera_pass<I: Integrator>(
    integrator: &I,
    prepared: &I::Pass,
    tracer: &Tracer,
    sampling: Sampling,
    tiles: &mut [Tile],
    observer: &dyn Observer,
) -> Vec<(Stats, bool)> {
    let placement = (tracer.scene.camera.as_ref())
        .expect("render_with() checked the camera")
        .filter
        .placement();
    tiles
        .par_iter_mut()
        .map(|tile| {
            let mut stats = Stats::default();
            let run = !observer.stop_requested();
            if run {
                camera_tile(
                    integrator, prepared, tracer, sampling, &placement, tile, &mut stats,
                );
            }
            observer.progress(Progress::Tile);
            (stats, run)
        })
        .collect()
}

/// One pass of camera samples over a tile, added to its film, with the pass's sampler.
fn camera_tile<I: Integrator>(
    integrator: &I,
    prepared: &I::Pass,
    tracer: &Tracer,
    sampling: Sampling,
    placement: &Placement,
    tile: &mut Tile,
    stats: &mut Stats,
) {
    let mut sampler = sampling.sampler();
    let camera = tracer
        .scene
        .camera
        .as_ref()
        .expect("render_with() checked the camera");
    let spp = sampler.samples();
    let layers = tile.film.film.layers.len();
    let mut sum = vec![Rgb::ZERO; layers];
    let (tile, film) = (&mut tile.pass, &mut tile.film);
    let pixels = film.film.width * film.film.height;
    let mut record = PassRecord::new(layers, spp as u64, film.film.planes_held());
    let mut values = vec![Rgb::ZERO; layers];
    // The film is the camera's window; its pixels are the image's, keyed as the image's are.
    let window = camera.window();
    for ty in 0..film.film.height {
        for tx in 0..film.film.width {
            let mut state = I::Pixel::default();
            sum.fill(Rgb::ZERO);
            sampler.start_pixel(PixelPass {
                x: window.x + (film.x0 + tx) as u32,
                y: window.y + (film.y0 + ty) as u32,
                width: camera.width,
                height: camera.height,
            });
            for s in 0..spp {
                let SampleStart {
                    film: film_point,
                    choices,
                    first,
                    mut rng,
                } = sampler.sample(s);
                // The filter's support ends at the window's edges.
                let film_point = FilmPoint {
                    u: placement.place(film_point.px - window.x, window.width, film_point.u),
                    v: placement.place(film_point.py - window.y, window.height, film_point.v),
                    ..film_point
                };
                let PrimaryRay { origin, direction } = camera.ray(film_point);
                stats.camera_rays += 1;
                values.fill(Rgb::ZERO);
                let mut sample = Sample::new(&mut rng, stats, &mut values);
                integrator.sample(
                    prepared,
                    &mut state,
                    CameraRay {
                        origin,
                        direction,
                        choices,
                        first,
                        film: film_point,
                    },
                    &mut sample,
                );
                for (a, b) in sum.iter_mut().zip(&values) {
                    *a += *b;
                }
            }
            // Rounded to f32 as recorded, so that taking the pass back is exact.
            record.record(ty * film.film.width + tx, pixels, &mut sum);
            film.film.add(tx, ty, &sum, spp as u64);
        }
    }
    *tile = Some(record);
}

/// Bytes a render of `scene` needs at its peak, estimated from above for typical scenes: the
/// camera pass's accumulators and the films of the passes done (the integrator's layers),
/// what the integrator keeps for a pass ([`PhotonMapper::memory_needed`]: its photon maps),
/// and the receivers' detections (one
/// crossing per photon and receiver, traced and merged). Meshes are already in memory when it
/// is asked.
pub fn memory_needed(scene: &Scene, settings: &Settings) -> u64 {
    use std::mem::size_of;
    let pixels = scene.camera.as_ref().map_or(0, |c| {
        let window = c.window();
        u64::from(window.width) * u64::from(window.height)
    });
    // What the integrator keeps besides the film, and its film's layers.
    let (own, layers) = match settings.integrator {
        Kind::PhotonMap => (
            PhotonMapper::memory_needed(
                scene,
                &settings.photons,
                crate::transport::carries_polarization(scene, &settings.trace),
            ),
            PhotonMapper::LAYERS,
        ),
        Kind::Path => (0, PathTracer::LAYERS),
    };
    // The tiles' films, the whole film of the passes done and the partial's (fixed-point RGB
    // sums per layer written and of the passes' squares; a count), and the preview's developed
    // beauty (f32 RGB; the EXR is developed pixel by pixel as written).
    let planes = layers.len() + 1;
    let sums = planes * size_of::<[crate::exact::Fixed; 3]>() + 8;
    let film = pixels * (3 * sums + 12) as u64;
    let detections = 2
        * settings.receiver_photons
        * scene.receivers.len() as u64
        * size_of::<crate::receiver::Detection>() as u64;
    let bins: u64 = scene
        .receivers
        .iter()
        .map(|r| 32 * (r.bins.0 * r.bins.1) as u64)
        .sum();
    film.saturating_add(own)
        .saturating_add(detections)
        .saturating_add(bins)
}

/// A local pool of `threads` workers (0: one per core), so a render never touches rayon's
/// global pool.
fn thread_pool(threads: usize) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {threads} threads: {e}")))
}
