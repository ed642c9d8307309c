//! `grinlight render`: the scene's receivers measured (with the energy budget and, on request,
//! seed 004's fiber figure), then its camera view rendered to a multi-layer EXR and a PNG.

use super::{at_least_one, positive, Observer};
use crate::error::{Error, Result};
use crate::fiber::GrinFiber;
use crate::film::Film;
use crate::output::{Kind, Outputs};
use crate::photon::Budget;
use crate::receiver::{self, Measurement};
use crate::report::Report;
use crate::scene::{self, Description, Scene};
use crate::settings::Settings;
use std::path::PathBuf;
use std::time::Instant;

/// The most photon paths a figure draws (each is kept in memory).
pub const MAX_PATHS: u64 = 10_000;

/// What `grinlight render` is asked to do.
#[derive(Clone, Debug, Default)]
pub struct RenderJob {
    /// The scene file.
    pub scene: PathBuf,
    /// The EXR to write (None: the scene's `[output] path`, else `<scene stem>.exr` in the
    /// working directory); it must end in `.exr`. The PNG preview and the receivers' files
    /// are named after it.
    pub output: Option<PathBuf>,
    /// The command line's values of `[render]` and `[camera]` keys.
    pub overrides: Overrides,
    /// Write the EXR and PNG every this many passes (0: only at the end).
    pub checkpoint: u32,
    /// Draw the paths of this many receiver photons through the scene's GRIN fiber (0: none).
    pub paths: u64,
}

/// Values that replace the scene's `[render]` and `[camera]` keys of the same names; each is
/// checked as the scene file's key is.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// Camera samples per pixel per pass (≥ 1).
    pub spp: Option<u32>,
    /// Seed of every random stream.
    pub seed: Option<u64>,
    /// Worker threads (0: one per core; at most 16 per core).
    pub threads: Option<usize>,
    /// The integrator.
    pub integrator: Option<crate::settings::IntegratorKind>,
    /// Trace every camera ray where a deflection table would apply.
    pub no_table: bool,
    /// Image width in pixels (the vertical field of view is kept).
    pub width: Option<u32>,
    /// Image height in pixels.
    pub height: Option<u32>,
    /// Global-map photons per pass.
    pub photons: Option<u64>,
    /// Caustic-map photons per pass.
    pub caustic_photons: Option<u64>,
    /// Final-gather rays per camera sample (0: no secondary light).
    pub gather: Option<u32>,
    /// Photon gather radius (scene units).
    pub radius: Option<f64>,
    /// k of the k-nearest-photon radius (≥ 1).
    pub knn: Option<u32>,
    /// Progressive passes (≥ 1).
    pub passes: Option<u32>,
    /// Start no new pass after this many seconds (with no `passes`: as many as fit).
    pub time_budget: Option<f64>,
    /// Photons traced for the receivers (≥ 1).
    pub receiver_photons: Option<u64>,
}

impl Overrides {
    /// Applies the values to a loaded scene's settings and camera: the one place
    /// command-line values meet the scene file's.
    pub fn apply(&self, scene: &mut Description, s: &mut Settings) -> Result<()> {
        if let Some(n) = self.spp {
            s.spp = at_least_one("spp", n)?;
        }
        s.seed = self.seed.unwrap_or(s.seed);
        s.integrator = self.integrator.unwrap_or(s.integrator);
        s.deflection_table &= !self.no_table;
        s.threads = crate::resources::check_threads(self.threads.unwrap_or(s.threads))?;
        let p = &mut s.photons;
        p.global = self.photons.unwrap_or(p.global);
        p.caustic = self.caustic_photons.unwrap_or(p.caustic);
        p.gather = self.gather.unwrap_or(p.gather);
        if let Some(k) = self.knn {
            p.knn = at_least_one("knn", k)?;
        }
        if let Some(r) = self.radius {
            p.radius = Some(positive("radius", r)?);
        }
        if let Some(b) = self.time_budget {
            s.time_budget = Some(positive("time-budget", b)?);
            if self.passes.is_none() {
                s.passes = u32::MAX;
            }
        }
        if let Some(p) = self.passes {
            s.passes = at_least_one("passes", p)?;
        }
        if let Some(n) = self.receiver_photons {
            s.receiver_photons = at_least_one("receiver-photons", n)?;
        }
        for (flag, v) in [("width", self.width), ("height", self.height)] {
            if v.is_some_and(|v| v == 0 || v > 65_536) {
                return Err(Error::Usage(format!("--{flag} must be in 1..=65536")));
            }
        }
        if let Some(camera) = scene.camera.as_mut() {
            camera.width = self.width.unwrap_or(camera.width);
            camera.height = self.height.unwrap_or(camera.height);
        }
        Ok(())
    }
}

/// What a render produced (its files are written; its report was shown line by line).
#[derive(Default)]
pub struct RenderOutcome {
    /// The camera render's film and report, if the scene has a camera.
    pub film: Option<(Film, Report)>,
    /// Each receiver's measurement, in scene order.
    pub measurements: Vec<Measurement>,
    /// Where the receiver photons' power went.
    pub budget: Option<Budget>,
    /// Whether it was stopped early (an interrupt): the files hold what was done.
    pub partial: bool,
}

/// The files a render writes.
struct Files {
    exr: PathBuf,
    png: Option<PathBuf>,
    /// Per receiver: bins CSV, heat map, radial CSV, radial plot.
    receivers: Vec<[PathBuf; 4]>,
    /// The fiber figure.
    paths: Option<PathBuf>,
}

impl Files {
    /// Names every file the render of `scene` writes (`png`: with the preview) and checks
    /// each (see [`Outputs`]).
    fn plan(scene: &Scene, exr: PathBuf, png: bool, paths: u64) -> Result<Self> {
        if !scene::objects::is_exr(&exr) {
            return Err(Error::Usage(format!(
                "{}: the output is a multi-layer EXR and must end in .exr (the PNG preview and \
                 receiver files are written beside it)",
                exr.display()
            )));
        }
        let stem = exr.with_extension("");
        let beside = |suffix: &str| PathBuf::from(format!("{}.{suffix}", stem.display()));
        let files = Files {
            png: (scene.camera.is_some() && png).then(|| exr.with_extension("png")),
            receivers: scene
                .receivers
                .iter()
                .map(|r| {
                    ["csv", "png", "radial.csv", "radial.png"]
                        .map(|ext| beside(&format!("{}.{ext}", r.name)))
                })
                .collect(),
            paths: (paths > 0).then(|| beside("paths.png")),
            exr,
        };
        let mut outputs = Outputs::new(&scene.inputs);
        if scene.camera.is_some() {
            outputs.add(&files.exr, Kind::Exr)?;
        }
        for (path, kind) in files.png.iter().map(|p| (p, Kind::Png)).chain(
            files
                .receivers
                .iter()
                .flat_map(|f| f.iter().zip([Kind::Csv, Kind::Png, Kind::Csv, Kind::Png])),
        ) {
            outputs.add(path, kind)?;
        }
        if let Some(p) = &files.paths {
            outputs.add(p, Kind::Png)?;
        }
        Ok(files)
    }

    /// Writes the film's EXR and, if asked, its PNG preview.
    fn write_film(&self, film: &Film, exposure: f32) -> Result<()> {
        film.write_exr(&self.exr)?;
        if let Some(png) = &self.png {
            film.write_png(png, exposure)?;
        }
        Ok(())
    }
}

/// Runs `grinlight render`: loads the scene, applies the job's overrides, checks every output
/// file and the memory and threads it needs before any work, measures the receivers (if any),
/// renders the camera view (if any), and writes every file atomically. The observer is shown
/// the report line by line; when it asks to stop, the files hold what was done and the
/// outcome is marked partial.
pub fn render(job: &RenderJob, observer: &dyn Observer) -> Result<RenderOutcome> {
    let (mut description, mut settings) = scene::load_description(&job.scene)?;
    job.overrides.apply(&mut description, &mut settings)?;
    let fiber = fiber_to_draw(job, &description)?;
    let scene = description.build();
    if scene.camera.is_none() && scene.receivers.is_empty() {
        return Err(Error::Usage(format!(
            "{}: the scene has no [camera] and no [[receiver]]: nothing to render",
            job.scene.display()
        )));
    }
    let exr = job
        .output
        .clone()
        .or_else(|| settings.output.path.clone())
        .unwrap_or_else(|| {
            PathBuf::from(job.scene.file_stem().unwrap_or_default()).with_extension("exr")
        });
    let files = Files::plan(&scene, exr, settings.output.png, job.paths)?;
    crate::resources::check_memory(
        crate::render::memory_needed(&scene, &settings),
        &format!("rendering {}", job.scene.display()),
    )?;
    let mut outcome = RenderOutcome::default();
    if !scene.receivers.is_empty() {
        let (measurements, budget, report) =
            measure_receivers(&scene, &settings, &files, observer)?;
        outcome.partial |= report.partial.is_some();
        if let (Some(fiber), false) = (fiber, outcome.partial) {
            let paths = Paths {
                fiber,
                count: job.paths,
                first: &measurements[0],
            };
            draw_paths(&scene, &settings, paths, &files, observer)?;
        }
        outcome.measurements = measurements;
        outcome.budget = Some(budget);
    }
    if scene.camera.is_none() || outcome.partial {
        return Ok(outcome);
    }
    let (film, report) = render_camera(job, (&scene, &settings), &files, observer)?;
    outcome.partial |= report.partial.is_some();
    outcome.film = Some((film, report));
    Ok(outcome)
}

/// The GRIN fiber whose photon paths `--paths` asks to draw, if it does (checked: at most
/// [`MAX_PATHS`], a receiver to show, a fiber to draw).
fn fiber_to_draw(job: &RenderJob, description: &Description) -> Result<Option<GrinFiber>> {
    if job.paths > MAX_PATHS {
        return Err(Error::Usage(format!(
            "--paths {}: a figure shows at most {MAX_PATHS} paths (each is kept in memory)",
            job.paths
        )));
    }
    match job.paths {
        0 => Ok(None),
        _ if description.receivers.is_empty() => Err(Error::Usage(format!(
            "{}: --paths shows the paths with a receiver's irradiance: the scene has no [[receiver]]",
            job.scene.display()
        ))),
        _ => description.grin_fiber().map(Some).ok_or_else(|| {
            Error::Usage(
                "--paths draws a GRIN fiber: the scene has no cylinder filled with a gradient medium"
                    .into(),
            )
        }),
    }
}

/// Renders the camera view, writing the film (and checkpoints), and reports it.
fn render_camera(
    job: &RenderJob,
    (scene, settings): (&Scene, &Settings),
    files: &Files,
    observer: &dyn Observer,
) -> Result<(Film, Report)> {
    let start = Instant::now();
    let checkpoints = Checkpoints {
        outer: observer,
        every: job.checkpoint,
        files,
        exposure: settings.output.exposure,
        start,
    };
    let (film, report) = crate::render::render(scene, settings, &checkpoints)?;
    files.write_film(&film, settings.output.exposure)?;
    let camera = scene.camera.as_ref().expect("render() checked the camera");
    observer.line(&format!(
        "rendered {} ({}×{}, {} spp × {} passes) in {:.2} s",
        job.scene.display(),
        camera.width,
        camera.height,
        settings.spp,
        report.passes,
        start.elapsed().as_secs_f64()
    ));
    observer.line(&report.summary());
    observer.line(&format!(
        "wrote {} (layers: {})",
        files.exr.display(),
        film.names().join(", ")
    ));
    if let Some(png) = &files.png {
        observer.line(&format!("wrote {}", png.display()));
    }
    Ok((film, report))
}

/// Measures the receivers and writes their files; reports the flux of each and the energy
/// budget.
fn measure_receivers(
    scene: &Scene,
    settings: &Settings,
    files: &Files,
    observer: &dyn Observer,
) -> Result<(Vec<Measurement>, Budget, Report)> {
    let start = Instant::now();
    let (measurements, budget, report) = crate::render::measure(scene, settings, 0, observer)?;
    let mut lines = Vec::new();
    for ((r, m), [csv, png, radial_csv, radial_png]) in scene
        .receivers
        .iter()
        .zip(&measurements)
        .zip(&files.receivers)
    {
        let profile = receiver::radial_profile(r, m);
        receiver::write_csv(r, m, csv)?;
        receiver::write_png(r, m, png)?;
        receiver::write_radial_csv(&profile, radial_csv)?;
        receiver::write_radial_png(&r.name, &[("measured", &profile)], radial_png)?;
        lines.push(format!(
            "receiver '{}': flux {:.6e} ± {:.1e} W; wrote {} (.png, .radial.csv, .radial.png)",
            r.name,
            m.flux.0,
            m.flux.1,
            csv.display()
        ));
        for ((lo, hi), b) in r.bands.iter().zip(&m.bands) {
            lines.push(format!(
                "  band {lo}–{hi} nm: flux {:.6e} ± {:.1e} W",
                b.flux.0, b.flux.1
            ));
        }
    }
    if let Some(p) = &report.partial {
        observer.line(&format!("PARTIAL (interrupted): {p}"));
    }
    observer.line(&format!(
        "measured {} receiver(s) with {} photons in {:.2} s ({:.0} photons/s)",
        scene.receivers.len(),
        report.stats.photons_emitted,
        start.elapsed().as_secs_f64(),
        report.stats.photons_emitted as f64 / report.seconds.0.max(1e-9)
    ));
    observer.line(&report.stats.summary());
    for l in lines {
        observer.line(&l);
    }
    observer.line(&budget.table(scene.accel.primitives()));
    Ok((measurements, budget, report))
}

/// Which photon paths seed 004 fig. 5 draws: the first `count` of the receiver batch.
struct Paths<'a> {
    fiber: GrinFiber,
    count: u64,
    /// The first receiver's measurement, drawn beside them.
    first: &'a Measurement,
}

/// Draws seed 004 fig. 5 for the scene's GRIN fiber.
fn draw_paths(
    scene: &Scene,
    settings: &Settings,
    paths: Paths,
    files: &Files,
    observer: &dyn Observer,
) -> Result<()> {
    let out = files.paths.as_ref().expect("planned with the paths");
    let tracer = crate::transport::Tracer::new(scene, &settings.trace);
    let sources = crate::photon::Sources::new(&tracer);
    let drawn = crate::photon::photon_paths(&tracer, &sources, settings.seed, 0, paths.count);
    let legend = crate::fiber::figure::write(
        scene,
        &paths.fiber,
        &drawn,
        (&scene.receivers[0], paths.first),
        out,
    )?;
    observer.line(&format!("wrote {}: {legend}", out.display()));
    Ok(())
}

/// The caller's observer, with the film written every `every` passes.
struct Checkpoints<'a> {
    outer: &'a dyn Observer,
    every: u32,
    files: &'a Files,
    exposure: f32,
    start: Instant,
}

impl Observer for Checkpoints<'_> {
    fn progress(&self, p: crate::render::Progress) {
        self.outer.progress(p);
    }
    fn line(&self, text: &str) {
        self.outer.line(text);
    }
    fn stop_requested(&self) -> bool {
        self.outer.stop_requested()
    }
    fn pass_done(&self, passes: u32, film: &Film) -> Result<()> {
        if self.every > 0 && passes.is_multiple_of(self.every) {
            self.files.write_film(film, self.exposure)?;
            self.outer.line(&format!(
                "pass {passes}: wrote {} at {:.1} s",
                self.files.exr.display(),
                self.start.elapsed().as_secs_f64()
            ));
        }
        self.outer.pass_done(passes, film)
    }
}
