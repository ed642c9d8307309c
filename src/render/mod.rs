//! The render: passes of (photon pass, camera pass). A camera path follows specular chains and
//! curved paths to its first diffuse surface — the visible point — where the luminance
//! components of seed 004 §4 are estimated:
//! - **direct**: light sampling, only where a straight shadow connection is valid (the point
//!   lies in a uniform medium and the shadow ray meets no surface); environment light by a
//!   cosine-sampled ray that escapes straight;
//! - **caustic**: the caustic map (L (S|G)+ D paths: exactly the light the direct estimate
//!   cannot connect to), progressive over passes (SPPM: per-pixel radius shrinking with α);
//! - **secondary**: a final gather (cosine rays, the global map's estimate where they land on a
//!   diffuse surface; the only place the global map is looked at directly).
//!
//! Emission seen along the camera's specular chain and the environment behind it go to
//! `emitted`; `beauty` = direct + caustic + secondary + emitted. Every random stream is keyed
//! by (seed, pass, pixel, sample) or (seed, pass, photon), so the image does not depend on the
//! thread count.

mod visible;

use crate::color::Rgb;
use crate::error::{Error, Result};
use crate::film::{Film, PixelSample, Plane};
use crate::photon::{shoot, Batch, Budget, PhotonMap, Sources};
use crate::receiver::{self, Measurement};
use crate::sampling::{stream, Purpose};
use crate::scene::Scene;
use crate::settings::{PhotonSettings, Settings};
use crate::transport::{Stats, Tracer};
use rand::Rng;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::time::Instant;
use visible::{camera_path, Components};

/// Tile edge in pixels.
const TILE: usize = 16;

/// The SPPM radius-reduction parameter α (Hachisuka and Jensen 2009): the fraction of new
/// photons kept per pass.
pub const ALPHA: f64 = 2.0 / 3.0;

/// What a render or a measurement reports as it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Progress {
    /// A receiver measurement starts: photons to trace, receivers.
    Measuring {
        /// Photons to trace.
        photons: u64,
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
    /// The film after `passes` finished passes (e.g. to write a checkpoint); an error stops
    /// the render with it.
    fn pass_done(&self, _passes: u32, _film: &Film) -> Result<()> {
        Ok(())
    }
    /// Whether to stop as soon as possible (an interrupt): a render abandons its current pass
    /// — tiles not yet started keep the passes they have — and returns what it has, marked
    /// as partial in its [`Report`].
    fn stop_requested(&self) -> bool {
        false
    }
}

impl Observer for () {}

/// Which photon maps a scene needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// A caustic map: some light path can meet a specular surface before a diffuse one
    /// (light through gradient media alone is the direct estimate's).
    pub caustic: bool,
    /// A global map: secondary light is on (`gather` > 0) and something is diffuse.
    pub global: bool,
}

impl Plan {
    /// What `scene` needs with `photons`: nothing without diffuse surfaces or without
    /// emitters.
    pub fn of(scene: &Scene, photons: &PhotonSettings) -> Self {
        use crate::material::Material;
        let has = |f: fn(&Material) -> bool| {
            scene
                .surfaces
                .iter()
                .any(|s| f(&scene.materials[s.material]))
        };
        let diffuse = has(|m| matches!(m, Material::Diffuse { .. }));
        let emits = !scene.lights.is_empty() || scene.environment.is_some();
        let specular = has(|m| matches!(m, Material::Mirror { .. } | Material::Dielectric));
        // (A receiver's detector is transparent: it neither bends nor stores light.)
        Self {
            caustic: diffuse && emits && specular && photons.caustic > 0,
            global: diffuse && emits && photons.gather > 0 && photons.global > 0,
        }
    }
}

/// Timings and photon counts of a render.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Passes run.
    pub passes: u32,
    /// Transport counts, summed over both passes of every pass.
    pub stats: Stats,
    /// Photons stored in the caustic and global maps, summed over passes.
    pub stored: (u64, u64),
    /// Seconds tracing photons, building the maps (kd-trees and the global map's precomputed
    /// irradiance), and in the camera pass (which includes the photon queries).
    pub seconds: (f64, f64, f64),
    /// Set when the render was stopped before its end (see [`Observer::stop_requested`]):
    /// what it holds.
    pub partial: Option<String>,
}

impl Report {
    /// A multi-line summary.
    pub fn summary(&self) -> String {
        let (trace, build, camera) = self.seconds;
        let rate = if trace > 0.0 {
            self.stats.photons_emitted as f64 / trace
        } else {
            0.0
        };
        let partial = self
            .partial
            .as_ref()
            .map_or(String::new(), |p| format!("PARTIAL (interrupted): {p}\n"));
        format!(
            "{partial}{} pass(es); photons: {} emitted ({rate:.0}/s), caustic map {} stored, global map {} stored; \
             photon tracing {trace:.2} s, map build {build:.3} s, camera pass {camera:.2} s\n{}",
            self.passes,
            self.stats.photons_emitted,
            self.stored.0,
            self.stored.1,
            self.stats.summary()
        )
    }
}

/// One pixel's accumulators over passes.
#[derive(Clone, Debug, Default)]
struct PixelState {
    /// Sums over passes of each pass's mean, per layer (the caustic slot is unused).
    sum: PixelSample,
    /// SPPM squared radius (0: not set yet).
    r2: f64,
    /// SPPM accumulated photon count N.
    n: f64,
    /// SPPM accumulated flux τ (already weighted by throughput, BRDF and kernel).
    tau: Rgb,
}

/// A tile: its top-left pixel, width, the passes its pixels hold, and its pixels' states, row
/// by row.
struct Tile {
    x0: usize,
    y0: usize,
    width: usize,
    passes: u32,
    pixels: Vec<PixelState>,
}

/// Renders the scene's camera view as `settings` say, telling `observer` of every pass and
/// tile and asking it whether to stop.
pub fn render(
    scene: &Scene,
    settings: &Settings,
    observer: &dyn Observer,
) -> Result<(Film, Report)> {
    let camera = scene.camera.as_ref().ok_or_else(|| {
        Error::Usage(format!(
            "{}: the scene has no [camera]",
            scene.path().display()
        ))
    })?;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let mut tiles: Vec<Tile> = Vec::new();
    for ty in 0..h.div_ceil(TILE) {
        for tx in 0..w.div_ceil(TILE) {
            let (x0, y0) = (tx * TILE, ty * TILE);
            let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
            tiles.push(Tile {
                x0,
                y0,
                width: x1 - x0,
                passes: 0,
                pixels: vec![PixelState::default(); (x1 - x0) * (y1 - y0)],
            });
        }
    }
    let tracer = Tracer::new(scene, &settings.trace);
    let sources = Sources::new(&tracer);
    let plan = Plan::of(scene, &settings.photons);
    let pool = thread_pool(settings.threads)?;
    let max_radius = settings.photons.radius.unwrap_or(0.05 * tracer.ball.1);
    let start = Instant::now();
    let mut report = Report::default();
    let mut film = Film::new(w, h);
    observer.progress(Progress::Rendering {
        tiles: tiles.len() as u64,
        passes: (settings.passes != u32::MAX).then_some(settings.passes),
        time_budget: settings.time_budget,
    });
    for pass in 0..settings.passes {
        if pass > 0
            && settings
                .time_budget
                .is_some_and(|b| start.elapsed().as_secs_f64() >= b)
        {
            break;
        }
        if observer.stop_requested() {
            break;
        }
        observer.progress(Progress::Pass(pass));
        let max_r2 = max_radius * max_radius;
        let build = |batch: Batch, count: u64, report: &mut Report| {
            let t0 = Instant::now();
            let (sink, stats) = pool.install(|| {
                shoot(
                    &tracer,
                    &sources,
                    batch,
                    settings.seed,
                    pass as u64,
                    count,
                    &|| observer.stop_requested(),
                )
            });
            let t1 = Instant::now();
            let mut map = PhotonMap::new(sink.photons);
            if batch == Batch::Global {
                pool.install(|| map.precompute_irradiance(settings.photons.knn as usize, max_r2));
            }
            report.seconds.0 += (t1 - t0).as_secs_f64();
            report.seconds.1 += t1.elapsed().as_secs_f64();
            report.stats.add(&stats);
            map
        };
        let caustic = plan
            .caustic
            .then(|| build(Batch::Caustic, settings.photons.caustic, &mut report));
        let global = plan
            .global
            .then(|| build(Batch::Global, settings.photons.global, &mut report));
        // Stopped while tracing photons: the maps may be incomplete, so the pass is abandoned.
        if observer.stop_requested() {
            report.partial = Some(format!(
                "{pass} of {} passes; pass {} abandoned while tracing photons",
                settings.passes,
                pass + 1
            ));
            break;
        }
        report.stored.0 += caustic.as_ref().map_or(0, |m| m.len() as u64);
        report.stored.1 += global.as_ref().map_or(0, |m| m.len() as u64);
        let maps = Maps {
            caustic: caustic.as_ref(),
            global: global.as_ref(),
            knn: settings.photons.knn as usize,
            gather: settings.photons.gather,
            max_r2,
            initial_r2: settings.photons.radius.map(|r| r * r),
        };
        let t0 = Instant::now();
        let stats: Vec<Stats> = pool.install(|| {
            tiles
                .par_iter_mut()
                .map(|tile| {
                    let mut stats = Stats::default();
                    if !observer.stop_requested() {
                        let sampling = Sampling {
                            seed: settings.seed,
                            spp: settings.spp,
                            pass,
                        };
                        camera_tile(&tracer, &maps, sampling, tile, &mut stats);
                        tile.passes += 1;
                    }
                    observer.progress(Progress::Tile);
                    stats
                })
                .collect()
        });
        report.seconds.2 += t0.elapsed().as_secs_f64();
        for s in &stats {
            report.stats.add(s);
        }
        film = develop(&tiles, w, h);
        let done = tiles.iter().filter(|t| t.passes == pass + 1).count();
        if done < tiles.len() {
            report.partial = Some(format!(
                "{pass} of {} passes, and pass {} on {done} of {} tiles of 16 × 16 pixels",
                settings.passes,
                pass + 1,
                tiles.len()
            ));
            report.passes = pass;
            break;
        }
        report.passes = pass + 1;
        observer.pass_done(report.passes, &film)?;
    }
    if report.partial.is_none() && observer.stop_requested() && report.passes < settings.passes {
        report.partial = Some(format!("{} of {} passes", report.passes, settings.passes));
    }
    observer.progress(Progress::Done);
    Ok((film, report))
}

/// The photon maps of a pass and how to query them.
struct Maps<'a> {
    caustic: Option<&'a PhotonMap>,
    global: Option<&'a PhotonMap>,
    knn: usize,
    /// Final-gather rays per camera sample.
    gather: u32,
    /// Largest squared radius of a k-nearest query.
    max_r2: f64,
    /// A fixed initial squared radius of the caustic estimate (None: k-nearest).
    initial_r2: Option<f64>,
}

/// Which camera samples a pass takes.
#[derive(Clone, Copy)]
struct Sampling {
    seed: u64,
    spp: u32,
    pass: u32,
}

/// One pass of camera samples over a tile, updating its pixels' accumulators.
fn camera_tile(
    tracer: &Tracer,
    maps: &Maps,
    sampling: Sampling,
    tile: &mut Tile,
    stats: &mut Stats,
) {
    let scene = tracer.scene;
    let camera = scene.camera.as_ref().expect("render() checked the camera");
    let (w, h) = (camera.width as u64, camera.height as u64);
    let Sampling { seed, spp, pass } = sampling;
    let spp = spp.max(1);
    let strata = spp.isqrt();
    for (i, state) in tile.pixels.iter_mut().enumerate() {
        let (x, y) = (tile.x0 + i % tile.width, tile.y0 + i / tile.width);
        let pixel = y as u64 * w + x as u64;
        let mut mean = PixelSample::default();
        let (mut phi, mut m) = (Rgb::ZERO, 0.0);
        for s in 0..spp {
            let mut rng = stream(seed, Purpose::Camera, pass as u64 * w * h + pixel, s as u64);
            // Stratified over the pixel: sample s of the first n² lies in cell (s mod n,
            // s div n) of an n × n grid, n = ⌊√spp⌋ (sharp edges such as an emitter's
            // converge much faster); any further samples are uniform.
            let (mut u, mut v) = (rng.gen::<f64>(), rng.gen::<f64>());
            if s < strata * strata {
                u = ((s % strata) as f64 + u) / strata as f64;
                v = ((s / strata) as f64 + v) / strata as f64;
            }
            let (o, d) = camera.ray(x as u32, y as u32, u, v, (rng.gen(), rng.gen()));
            stats.camera_rays += 1;
            let c: Components = camera_path(tracer, o, d, &mut rng, stats);
            mean[Plane::Emitted as usize] += c.emitted;
            let Some(vp) = c.visible else { continue };
            mean[Plane::Albedo as usize] += vp.albedo;
            mean[Plane::Normal as usize] += vp.normal;
            mean[Plane::Direct as usize] += visible::direct(tracer, &vp, &mut rng, stats);
            if let Some(global) = maps.global {
                mean[Plane::Secondary as usize] += visible::secondary(
                    tracer,
                    global,
                    maps.gather,
                    maps.max_r2,
                    &vp,
                    &mut rng,
                    stats,
                );
            }
            if let Some(caustic) = maps.caustic {
                if state.r2 == 0.0 {
                    state.r2 = maps.initial_r2.unwrap_or_else(|| {
                        stats.time_query(|| {
                            caustic.knn_radius2(vp.position, vp.normal, maps.knn, maps.max_r2)
                        })
                    });
                }
                let r2 = state.r2;
                let (irradiance, count) =
                    stats.time_query(|| caustic.irradiance(vp.position, vp.normal, r2));
                // τ is kept so that L = τ / (π r² · passes): Φ-weighted sum of the BRDF times
                // the kernel, (albedo/π)·E·π r² with E the kernel irradiance estimate.
                phi += vp.throughput * vp.albedo * irradiance * state.r2;
                m += count as f64;
            }
        }
        for layer in [
            Plane::Direct,
            Plane::Secondary,
            Plane::Emitted,
            Plane::Albedo,
            Plane::Normal,
        ] {
            state.sum[layer as usize] += mean[layer as usize] / spp as f64;
        }
        let (phi, m) = (phi / spp as f64, m / spp as f64);
        if m > 0.0 {
            let ratio = (state.n + ALPHA * m) / (state.n + m);
            state.r2 *= ratio;
            state.tau = (state.tau + phi) * ratio;
            state.n += ALPHA * m;
        }
    }
}

/// The film of the accumulators (each tile's pixels averaged over the passes it holds).
fn develop(tiles: &[Tile], w: usize, h: usize) -> Film {
    let mut film = Film::new(w, h);
    for tile in tiles {
        let p = tile.passes.max(1) as f64;
        for (i, state) in tile.pixels.iter().enumerate() {
            let mut value = state.sum.map(|v| v / p);
            if state.r2 > 0.0 {
                value[Plane::Caustic as usize] = state.tau / (PI * state.r2 * p);
            }
            value[Plane::Beauty as usize] = value[Plane::Direct as usize]
                + value[Plane::Caustic as usize]
                + value[Plane::Secondary as usize]
                + value[Plane::Emitted as usize];
            film.set(tile.x0 + i % tile.width, tile.y0 + i / tile.width, &value);
        }
    }
    film
}

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
    let tracer = Tracer::new(scene, &settings.trace);
    let sources = Sources::new(&tracer);
    let pool = thread_pool(settings.threads)?;
    let count = settings.receiver_photons;
    observer.progress(Progress::Measuring {
        photons: count,
        receivers: scene.receivers.len(),
    });
    let t0 = Instant::now();
    let (mut sink, stats) = pool.install(|| {
        shoot(
            &tracer,
            &sources,
            Batch::Receivers,
            settings.seed,
            pass,
            count,
            &|| observer.stop_requested(),
        )
    });
    observer.progress(Progress::Done);
    let traced = stats.photons_emitted;
    let mut report = Report {
        passes: 1,
        stats,
        seconds: (t0.elapsed().as_secs_f64(), 0.0, 0.0),
        ..Report::default()
    };
    if traced < count && !sources.is_empty() {
        report.partial = Some(format!("{traced} of {count} receiver photons"));
        let scale = count as f64 / traced.max(1) as f64;
        for d in &mut sink.detections {
            d.flux *= scale;
        }
        sink.budget.scale(scale);
    }
    Ok((
        receiver::measure(&scene.receivers, &sink.detections, traced.max(1)),
        sink.budget,
        report,
    ))
}

/// Bytes a render of `scene` needs at its peak, estimated from above for typical scenes: the
/// camera pass's accumulators and two developed films (one being written), one pass's photon
/// maps (as traced in chunks and merged; global photons stored ≈ 4 times each, the mean path
/// of Russian roulette at albedo 0.75; kd-tree entries), and the receivers' detections (one
/// crossing per photon and receiver, traced and merged). Meshes are already in memory when it
/// is asked.
pub fn memory_needed(scene: &Scene, settings: &Settings) -> u64 {
    use std::mem::size_of;
    let plan = Plan::of(scene, &settings.photons);
    let pixels = scene
        .camera
        .as_ref()
        .map_or(0, |c| c.width as u64 * c.height as u64);
    let film = pixels * (size_of::<PixelState>() + 2 * crate::film::LAYERS.len() * 12) as u64;
    let per_photon = 2 * size_of::<crate::photon::Photon>() as u64 + 32;
    let caustic = if plan.caustic {
        settings.photons.caustic
    } else {
        0
    };
    let global = if plan.global {
        4 * settings.photons.global
    } else {
        0
    };
    let detections = 2
        * settings.receiver_photons
        * scene.receivers.len() as u64
        * size_of::<crate::receiver::Detection>() as u64;
    let bins: u64 = scene
        .receivers
        .iter()
        .map(|r| 32 * (r.bins.0 * r.bins.1) as u64)
        .sum();
    film.saturating_add((caustic + global).saturating_mul(per_photon))
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
