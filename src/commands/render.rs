//! `grinlight render`: the scene's receivers measured (with the energy budget and, on request,
//! Zhdanov et al.'s (2020) fiber figure), then its camera view rendered to a multi-layer EXR and a PNG.

use super::Observer;
use crate::error::{Error, Result};
use crate::fiber::GrinFiber;
use crate::film::Film;
use crate::output::{Kind, Outputs};
use crate::photon::Budget;
use crate::receiver::{self, Measurement};
use crate::report::Report;
use crate::scene::{Description, Scene};
use crate::settings::{apply_all, Given, Key, Settings, Target};
use crate::shard::file::Opened;
use crate::shard::{Header, Partial, Role, Saving, Shard};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

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
    /// Save the partial (and write the EXR and PNG) every this many passes and after every
    /// block of receiver photons (0: every minute, and at the end).
    pub checkpoint: u32,
    /// Draw the paths of this many receiver photons through the scene's GRIN fiber (0: none).
    pub paths: u64,
    /// Render only this slice of the work, into a partial result (`output`: the partial
    /// file, ending in `.partial`; default `<scene stem>.shard-K-of-N.partial`).
    pub shard: Option<Shard>,
    /// Continue the partial a killed or interrupted run of the same job saved.
    pub resume: bool,
    /// How a scene of another renderer (`.xml`, `.pbrt`) is read.
    pub import: crate::import::ImportOptions,
}

/// Settings given apart from the scene file — the command line's flags, Python's keywords —
/// that replace its `[render]` and `[camera]` keys of the same names. They are kept as given
/// and read by the settings table ([`crate::settings::keys`]) when applied, so a value is
/// refused in the scene file's words.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// Each setting given and its value, in the order given (a later one of a setting wins).
    values: Vec<(&'static Key, Given)>,
}

impl Overrides {
    /// Gives setting `key` the value `value`.
    pub fn set(&mut self, key: &'static Key, value: impl Into<Given>) {
        self.unset(key);
        self.values.push((key, value.into()));
    }

    /// Takes back what was given for `key`: the scene file's value holds.
    pub fn unset(&mut self, key: &Key) {
        self.values.retain(|(k, _)| k.name != key.name);
    }

    /// The settings given, in order.
    pub fn values(&self) -> &[(&'static Key, Given)] {
        &self.values
    }

    /// Applies the values to a loaded scene's settings and camera: the one place values given
    /// apart meet the scene file's.
    pub fn apply(&self, scene: &mut Description, s: &mut Settings) -> Result<()> {
        let assignments = self
            .values
            .iter()
            .map(|(key, given)| {
                key.read(given).map_err(|message| Error::Setting {
                    key: key.name,
                    message,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        apply_all(
            &assignments,
            &mut Target {
                settings: s,
                camera: scene.camera.as_mut(),
            },
        );
        s.threads = crate::resources::check_threads(s.threads)?;
        Ok(())
    }
}

/// What a render produced (its files are written; its report was shown line by line).
#[derive(Default)]
pub struct RenderOutcome {
    /// The camera render's film, if the scene has a camera (and, with a shard, its film
    /// holds passes).
    pub film: Option<Rendered>,
    /// Each receiver's measurement, in scene order (none for a shard: its partial holds the
    /// tallies).
    pub measurements: Vec<Measurement>,
    /// Where the receiver photons' power went.
    pub budget: Option<Budget>,
    /// Whether an interrupt stopped it early: the files hold what was done, and the partial
    /// saved beside them lets `--resume` continue.
    pub interrupted: bool,
    /// Whether its results hold less than the whole render's work (interrupted, or a merge
    /// of some of the shards with `--allow-missing`); the report says so.
    pub incomplete: bool,
}

/// A camera render's result.
pub struct Rendered {
    /// The film.
    pub film: Film,
    /// The passes it holds (all the render's, a resumed render's earlier ones included).
    pub passes: u32,
    /// The report of the work that made it (empty for a merge).
    pub report: Report,
}

/// How often a running render saves its partial when no `--checkpoint` asks for more.
const SAVE_INTERVAL: Duration = Duration::from_secs(60);

/// The files a render writes.
pub(super) struct Files {
    exr: PathBuf,
    png: Option<PathBuf>,
    /// The false-colour picture of the light's linear polarization (with the preview, where
    /// the render writes the Stokes layers).
    polarization: Option<PathBuf>,
    /// Per receiver: bins CSV, heat map, radial CSV, radial plot.
    receivers: Vec<[PathBuf; 4]>,
    /// The fiber figure.
    paths: Option<PathBuf>,
}

impl Files {
    /// Names every file the render of `scene` writes (`png`: with the preview) and adds each
    /// to `outputs` (see [`Outputs`]).
    pub(super) fn plan(
        scene: &Scene,
        exr: PathBuf,
        png: bool,
        stokes: bool,
        paths: u64,
        outputs: &mut Outputs,
    ) -> Result<Self> {
        if !crate::output::is_exr(&exr) {
            return Err(Error::Usage(format!(
                "{}: the output is a multi-layer EXR and must end in .exr (the PNG preview and \
                 receiver files are written beside it)",
                exr.display()
            )));
        }
        let beside = |suffix: &str| beside(&exr, suffix);
        let files = Files {
            png: (scene.camera.is_some() && png).then(|| exr.with_extension("png")),
            polarization: (scene.camera.is_some() && png && stokes)
                .then(|| beside("polarization.png")),
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
        if scene.camera.is_some() {
            outputs.add(&files.exr, Kind::Exr)?;
        }
        let previews = files.png.iter().chain(&files.polarization);
        for (path, kind) in previews.map(|p| (p, Kind::Png)).chain(
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
        if let Some(png) = &self.polarization {
            film.write_polarization_png(png, exposure)?;
        }
        Ok(())
    }
}

/// `path` without its extension, then `.suffix`.
fn beside(path: &Path, suffix: &str) -> PathBuf {
    PathBuf::from(format!("{}.{suffix}", path.with_extension("").display()))
}

/// Runs `grinlight render`: loads the scene, applies the job's overrides, checks every output
/// file and the memory and threads it needs before any work, then does the work of the job's
/// shard (all of it without one) — receiver photons, then passes — saving its partial as it
/// goes. Without a shard it writes the results (EXR, PNG, receiver files) atomically; with
/// one, the shard's partial, for `grinlight merge`. `--resume` continues the partial a killed
/// or interrupted run left. The observer is shown the report line by line; when it asks to
/// stop, the files hold what was done and the outcome is marked partial.
pub fn render(job: &RenderJob, observer: &dyn Observer) -> Result<RenderOutcome> {
    let (mut description, mut settings) = crate::import::load_description(&job.scene, &job.import)?;
    for w in &description.warnings {
        observer.warning(w);
    }
    job.overrides.apply(&mut description, &mut settings)?;
    let fiber = fiber_to_draw(job, &description)?;
    let scene = build_checked(description, &settings, observer)?;
    if settings.target_error.is_some() && scene.camera.is_none() {
        observer.warning(
            "target_error judges the camera's image, and the scene has no [camera]: the \
             receivers are measured with receiver_photons photons regardless",
        );
    }
    let shard = job.shard.unwrap_or(Shard::WHOLE);
    let open_ended = settings.time_budget.is_some() || settings.target_error.is_some();
    if job.shard.is_some() && (open_ended || job.paths > 0) {
        return Err(Error::Setting {
            key: "shard",
            message: "renders a fixed share of the work: give passes, not time_budget or \
                      target_error, and draw paths from a whole render"
                .into(),
        });
    }
    let mut outputs = Outputs::new(&scene.inputs);
    let (files, state) = match job.shard {
        Some(s) => {
            let state = job
                .output
                .clone()
                .unwrap_or_else(|| shard_partial(&job.scene, s));
            if state.extension().is_none_or(|e| e != "partial") {
                return Err(Error::Usage(format!(
                    "{}: a shard writes a partial result, whose name ends in .partial",
                    state.display()
                )));
            }
            (None, state)
        }
        None => {
            let exr = output_exr(job.output.clone(), &settings, &job.scene);
            let state = beside(&exr, "partial");
            let files = Files::plan(
                &scene,
                exr,
                settings.output.png,
                settings.trace.stokes,
                job.paths,
                &mut outputs,
            )?;
            (Some(files), state)
        }
    };
    outputs.add(&state, Kind::Partial)?;
    crate::resources::check_memory(
        crate::render::memory_needed(&scene, &settings),
        &format!("rendering {}", job.scene.display()),
    )?;
    let role = match job.shard {
        Some(_) => Role::Shard,
        None => Role::Checkpoint,
    };
    let header = Header::new(&scene, &settings, shard, role)?;
    let partial = start_partial(header.clone(), &state, job.resume, observer)?;
    partial.fits(&scene, &state)?;
    let save = |p: &Partial| -> Result<()> {
        crate::output::together(|| {
            p.write(&state)?;
            match (&files, &p.film) {
                (Some(files), Some(film)) => files.write_film(film, settings.output.exposure),
                _ => Ok(()),
            }
        })?;
        observer.line(&format!(
            "saved {} ({} of the passes, {} receiver photons){}",
            state.display(),
            p.passes.len(),
            p.photons.len(),
            if files.is_some() {
                ", and the images"
            } else {
                ""
            }
        ));
        Ok(())
    };
    let saving = Saving {
        every: job.checkpoint,
        interval: SAVE_INTERVAL,
        save: &save,
    };
    let start = Instant::now();
    let ran = crate::shard::run(&scene, &settings, partial, observer, &saving)?;
    let interrupted = ran.interrupted();
    let Some(files) = files else {
        ran.partial.write(&state)?;
        let (passes, photons) = ran.partial.remaining();
        observer.line(&format!(
            "shard {shard} of {} in {:.2} s: wrote {} (passes {}, receiver photons {}){}",
            job.scene.display(),
            start.elapsed().as_secs_f64(),
            state.display(),
            ran.partial.passes,
            ran.partial.photons,
            if interrupted {
                format!(
                    "; PARTIAL (interrupted): passes {passes} and photons {photons} remain, \
                     continue by resuming (--resume; Python: resume=True)"
                )
            } else {
                "; merge the shards with `grinlight merge`".into()
            }
        ));
        return Ok(RenderOutcome {
            interrupted,
            incomplete: interrupted,
            film: ran
                .partial
                .film
                .zip(ran.camera)
                .map(|(film, report)| Rendered {
                    film,
                    passes: ran.partial.passes.len() as u32,
                    report,
                }),
            ..RenderOutcome::default()
        });
    };
    if interrupted {
        ran.partial.write(&state)?;
        observer.line(&format!(
            "PARTIAL (interrupted): saved {}; `grinlight render {} --resume` (with the same \
             options) continues it",
            state.display(),
            job.scene.display()
        ));
    }
    let work = Work {
        receivers: ran.receivers.as_ref(),
        camera: ran.camera.as_ref(),
    };
    let mut outcome = publish(&scene, &settings, ran.partial, work, &files, observer)?;
    outcome.interrupted = interrupted;
    outcome.incomplete = interrupted;
    if let (Some(fiber), false) = (fiber, interrupted) {
        let paths = Paths {
            fiber,
            count: job.paths,
            first: &outcome.measurements[0],
        };
        draw_paths(&scene, &settings, paths, &files, observer)?;
    }
    if !interrupted {
        remove_own_checkpoint(&state, &header)?;
    }
    Ok(outcome)
}

/// Renders a scene given as its description and settings (a file's, or data's) in memory,
/// with `overrides` applied: its receivers measured, then its camera view rendered, and the
/// results returned — no file written, none saved to resume. The same scene, settings and
/// overrides give the film and measurements [`render`] writes, bit for bit. When the
/// observer asks to stop, the outcome holds the work done and is marked interrupted.
pub fn render_in_memory(
    mut description: Description,
    mut settings: Settings,
    overrides: &Overrides,
    observer: &dyn Observer,
) -> Result<RenderOutcome> {
    for w in &description.warnings {
        observer.warning(w);
    }
    overrides.apply(&mut description, &mut settings)?;
    let scene = build_checked(description, &settings, observer)?;
    crate::resources::check_memory(
        crate::render::memory_needed(&scene, &settings),
        &format!("rendering {}", scene.path().display()),
    )?;
    let header = Header::new(&scene, &settings, Shard::WHOLE, Role::Checkpoint)?;
    let saving = Saving {
        every: 0,
        interval: Duration::MAX,
        save: &|_| Ok(()),
    };
    let ran = crate::shard::run(&scene, &settings, Partial::empty(header), observer, &saving)?;
    let interrupted = ran.interrupted();
    let work = Work {
        receivers: ran.receivers.as_ref(),
        camera: ran.camera.as_ref(),
    };
    let mut outcome = results(&scene, &settings, ran.partial, work, observer);
    outcome.interrupted = interrupted;
    outcome.incomplete = interrupted;
    Ok(outcome)
}

/// Builds a scene to render, refusing one with nothing to render or a camera view no
/// integrator renders, and warning of a camera where its medium captures light and of a
/// dye whose light an image may miss ([`crate::render::dye_light_warning`]).
fn build_checked(
    description: Description,
    settings: &Settings,
    observer: &dyn Observer,
) -> Result<Scene> {
    let scene = description.build();
    if scene.camera.is_none() && scene.receivers.is_empty() {
        return Err(Error::Usage(format!(
            "{}: the scene has no [camera] and no [[receiver]]: nothing to render",
            scene.path().display()
        )));
    }
    let tracer = crate::transport::Tracer::new(&scene, &settings.trace);
    crate::render::sources_outside_crystals(&scene, &tracer)?;
    if let Some(c) = &scene.camera {
        if let Some(w) = crate::render::dye_light_warning(&scene) {
            observer.warning(&w);
        }
        if tracer.index(tracer.camera_medium, c.position).is_none() {
            observer.warning(&format!(
                "the camera at {:?} is where its medium captures light (inside a black hole's \
                 horizon, or where the index is not positive): every camera ray ends there and \
                 the image is black",
                c.position.to_array()
            ));
        }
    }
    Ok(scene)
}

/// Where a shard's partial result goes when no output is named:
/// `<scene stem>.shard-K-of-N.partial` in the working directory.
pub fn shard_partial(scene: &Path, shard: Shard) -> PathBuf {
    PathBuf::from(format!(
        "{}.shard-{}-of-{}.partial",
        scene.file_stem().unwrap_or_default().to_string_lossy(),
        shard.index,
        shard.count
    ))
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

/// The EXR a render writes: the job's, else the scene's `[output] path`, else
/// `<scene stem>.exr` in the working directory.
pub(super) fn output_exr(output: Option<PathBuf>, settings: &Settings, scene: &Path) -> PathBuf {
    output
        .or_else(|| settings.output.path.clone())
        .unwrap_or_else(|| {
            PathBuf::from(scene.file_stem().unwrap_or_default()).with_extension("exr")
        })
}

/// The partial a render starts from: the one saved at `state` when resuming (it must be of
/// the same render), else an empty one. A partial already at `state` is never replaced by
/// another: an unfinished one of this render needs `--resume` (hours of work may be in it), a
/// finished one of this render is finished from (its results are the same), and one of any
/// other render or role — a shard's result at a whole render's state path, say — is refused,
/// as is a damaged one.
fn start_partial(
    header: Header,
    state: &Path,
    resume: bool,
    observer: &dyn Observer,
) -> Result<Partial> {
    if resume && !state.exists() {
        return Err(Error::Setting {
            key: "resume",
            message: format!(
                "{} does not exist: nothing to resume (run without resuming)",
                state.display()
            ),
        });
    }
    if !state.exists() {
        return Ok(Partial::empty(header));
    }
    let saved = Partial::read(state)?;
    let difference = header.difference(&saved.header).or_else(|| {
        (saved.header.shard != header.shard)
            .then(|| format!("shard {} against {}", header.shard, saved.header.shard))
    });
    if saved.header.role != header.role {
        let what = match saved.header.role {
            Role::Shard => "a shard's result (made by `render --shard`, for `grinlight merge`)",
            Role::Checkpoint => {
                "the saved state of a whole render (continued by `render --resume`)"
            }
        };
        return Err(Error::Usage(format!(
            "{} holds {what}: refusing to replace it (move it, or choose another output)",
            state.display()
        )));
    }
    match (difference, resume, saved.is_complete()) {
        (Some(d), true, _) => Err(Error::Setting {
            key: "resume",
            message: format!(
                "{} is a partial of another render ({d}): give the options it was started with",
                state.display()
            ),
        }),
        (Some(d), false, _) => Err(Error::Usage(format!(
            "{} holds the partial result of another render ({d}): refusing to replace it \
             (move it, or choose another output)",
            state.display()
        ))),
        (None, true, _) => Ok(saved),
        (None, false, false) => Err(Error::Usage(format!(
            "{} holds this render unfinished ({} passes, {} receiver photons done): continue \
             it by resuming (--resume; Python: resume=True), or remove it to start again",
            state.display(),
            saved.passes.len(),
            saved.photons.len()
        ))),
        (None, false, true) => {
            observer.line(&format!(
                "{} holds this render finished: its results are written from it",
                state.display()
            ));
            Ok(saved)
        }
    }
}

/// Removes a finished whole render's saved state at `state` — only if it is this render's
/// checkpoint (`header`): a file another run put there since is left alone.
fn remove_own_checkpoint(state: &Path, header: &Header) -> Result<()> {
    if header.role != Role::Checkpoint || !state.exists() {
        return Ok(());
    }
    match Opened::open(state) {
        Ok(o) if o.header == *header => {
            std::fs::remove_file(state).map_err(|e| Error::io(state, e))
        }
        _ => Ok(()),
    }
}

/// The reports of the work a render did (none for a merge).
#[derive(Clone, Copy, Default)]
pub(super) struct Work<'a> {
    /// The receiver photons' report.
    pub receivers: Option<&'a Report>,
    /// The camera's report.
    pub camera: Option<&'a Report>,
}

/// Writes a render's results from its partial (a whole render's, or shards merged): each
/// receiver's files and flux, the energy budget, and the film's EXR and PNG; they land
/// together. The reports of the `work` are shown when given. A partial lacking photons gives
/// an estimate scaled to the whole batch; the report says so.
pub(super) fn publish(
    scene: &Scene,
    settings: &Settings,
    partial: Partial,
    work: Work,
    files: &Files,
    observer: &dyn Observer,
) -> Result<RenderOutcome> {
    crate::output::together(|| write_results(scene, settings, partial, work, files, observer))
}

/// [`publish`]'s writes, each file written to its temporary file.
fn write_results(
    scene: &Scene,
    settings: &Settings,
    partial: Partial,
    work: Work,
    files: &Files,
    observer: &dyn Observer,
) -> Result<RenderOutcome> {
    let outcome = results(scene, settings, partial, work, observer);
    for ((r, m), [csv, png, radial_csv, radial_png]) in scene
        .receivers
        .iter()
        .zip(&outcome.measurements)
        .zip(&files.receivers)
    {
        let profile = receiver::radial_profile(r, m);
        receiver::write_csv(r, m, csv)?;
        receiver::write_png(r, m, png)?;
        receiver::write_radial_csv(&profile, radial_csv)?;
        receiver::write_radial_png(&r.name, &[("measured", &profile)], radial_png)?;
        observer.line(&format!(
            "receiver '{}': wrote {} (.png, .radial.csv, .radial.png)",
            r.name,
            csv.display()
        ));
    }
    if let Some(Rendered { film, .. }) = &outcome.film {
        files.write_film(film, settings.output.exposure)?;
        observer.line(&format!(
            "wrote {} (layers: {})",
            files.exr.display(),
            film.names().join(", ")
        ));
        for png in files.png.iter().chain(&files.polarization) {
            observer.line(&format!("wrote {}", png.display()));
        }
    }
    Ok(outcome)
}

/// A render's results from its partial (a whole render's, or shards merged): each receiver's
/// measurement, the energy budget, and the film, each reported to the observer; the reports
/// of the `work` are shown when given. A partial lacking photons gives an estimate scaled to
/// the whole batch; the report says so.
fn results(
    scene: &Scene,
    settings: &Settings,
    partial: Partial,
    Work { receivers, camera }: Work,
    observer: &dyn Observer,
) -> RenderOutcome {
    let mut outcome = RenderOutcome::default();
    if !scene.receivers.is_empty() {
        let books = &partial.books;
        let total = partial.header.photons;
        let scale = total as f64 / books.traced.max(1) as f64;
        let measurements = books.measurements(&scene.receivers, scale);
        let budget = books.ledger.statement(scale);
        if books.traced < total {
            observer.line(&format!(
                "PARTIAL: {} of {total} receiver photons, fluxes scaled to the whole batch",
                books.traced
            ));
        }
        if let Some(report) = receivers {
            observer.line(&format!(
                "measured {} receiver(s) with {} photons in {:.2} s ({:.0} photons/s)",
                scene.receivers.len(),
                report.stats.photons_emitted,
                report.seconds.photons,
                report.stats.photons_emitted as f64 / report.seconds.photons.max(1e-9)
            ));
            observer.line(&report.stats.summary());
        }
        for (r, m) in scene.receivers.iter().zip(&measurements) {
            observer.line(&format!(
                "receiver '{}': flux {:.6e} ± {:.1e} W",
                r.name, m.flux.0, m.flux.1
            ));
            for ((lo, hi), b) in r.bands.iter().zip(&m.bands) {
                observer.line(&format!(
                    "  band {lo}–{hi} nm: flux {:.6e} ± {:.1e} W",
                    b.flux.0, b.flux.1
                ));
            }
            if let [s1, s2, s3] = &m.stokes[..] {
                let share = |s: &Measurement| s.flux.0 / m.flux.0;
                observer.line(&format!(
                    "  Stokes (basis u = {}): S1/S0 {:.4}, S2/S0 {:.4}, S3/S0 {:.4}",
                    r.stokes_basis(),
                    share(s1),
                    share(s2),
                    share(s3)
                ));
            }
        }
        let media: Vec<&str> = scene.medium_names().collect();
        observer.line(&budget.table(scene.accel.primitives(), &media));
        outcome.measurements = measurements;
        outcome.budget = Some(budget);
    }
    let missing = partial.remaining().0;
    let Some(film) = partial.film else {
        return outcome;
    };
    let what = format!(
        "{} ({}×{}, {} spp × {} passes{})",
        scene.path().display(),
        film.width,
        film.height,
        settings.spp,
        partial.passes.len(),
        match missing.is_empty() {
            true => String::new(),
            false => format!("; PARTIAL: passes {missing} missing"),
        }
    );
    match camera {
        Some(r) => observer.line(&format!("rendered {what} in {:.2} s", r.seconds.total())),
        None => observer.line(&format!("merged {what}")),
    }
    if film.rejected() > 0 {
        observer.warning(&format!(
            "{} pixel values were not finite or beyond ±{:.2e} and were left out of the film",
            film.rejected(),
            crate::exact::Fixed::LIMIT
        ));
    }
    let report = camera.cloned().unwrap_or_default();
    if camera.is_some() {
        observer.line(&report.summary());
        if let Some(text) = report.stats.cut_warning(settings.trace.max_depth) {
            observer.warning(&text);
        }
    }
    if let Some(error) = film.error() {
        observer.line(&format!(
            "estimated error: relative RMSE {:.4} (from the spread of its {} passes; the \
             `{}` layer holds each pixel's standard error)",
            error.relative_rmse(),
            film.passes,
            crate::film::ERROR
        ));
    }
    outcome.film = Some(Rendered {
        film,
        passes: partial.passes.len() as u32,
        report,
    });
    outcome
}

/// Which photon paths Zhdanov et al. (2020) fig. 5 draws: the first `count` of the receiver batch.
struct Paths<'a> {
    fiber: GrinFiber,
    count: u64,
    /// The first receiver's measurement, drawn beside them.
    first: &'a Measurement,
}

/// Draws Zhdanov et al. (2020) fig. 5 for the scene's GRIN fiber.
fn draw_paths(
    scene: &Scene,
    settings: &Settings,
    paths: Paths,
    files: &Files,
    observer: &dyn Observer,
) -> Result<()> {
    let out = files.paths.as_ref().expect("planned with the paths");
    let tracer = crate::transport::Tracer::new(scene, &settings.trace);
    let sources = crate::photon::Sources::for_receivers(&tracer);
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
