//! The grinlight command line.

use anyhow::Result;
use clap::{Parser, Subcommand, ValueEnum};
use glam::DVec3;
use grinlight::curve::{Bounds, MarchLimits, RayState, StepControl, StepperKind};
use grinlight::error::Error;
use grinlight::render::Progress;
use grinlight::{receiver, scene, trace};
use std::io::Write;
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "grinlight",
    version,
    about = "A renderer for light that bends in gradient-index media"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum Control {
    /// Error-controlled steps (default): --tol is the position error per unit arclength.
    Adaptive,
    /// Seed 000 §4: --tmax, --tmin, random shrink/grow, --max-steps as N_max.
    Tessendorf,
    /// Fixed steps of --step.
    Fixed,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene's camera view to a multi-layer EXR and a PNG preview.
    Render(RenderArgs),
    /// Compare a scene's GRIN fiber with its layered twin (concentric homogeneous cylinders)
    /// on the scene's receivers.
    Validate {
        /// Scene file (TOML) with a GRIN-filled cylinder and at least one [[receiver]].
        scene: PathBuf,
        /// Index step between layers; several, comma-separated, give a convergence table.
        #[arg(long, value_delimiter = ',', default_value = "0.005")]
        dn: Vec<f64>,
        /// Also start a new layer wherever one reaches this width (scene units): equal-Δn
        /// layers are wide near the axis, where paraxial rays then feel no gradient.
        #[arg(long)]
        max_width: Option<f64>,
        /// Photons per measurement (default: [render] receiver_photons).
        #[arg(long)]
        photons: Option<u64>,
        /// Worker threads (0 = all cores).
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// Where to write the radial profiles plot (default: <scene name>.validate.png).
        #[arg(long)]
        plot: Option<PathBuf>,
    },
    /// Trace one ray through a medium of a scene (unbounded) and print where it ends.
    Trace {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Name of a [[medium]] in the scene.
        #[arg(long)]
        medium: String,
        /// Start point X,Y,Z.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vec)]
        from: DVec3,
        /// Initial direction X,Y,Z (need not be normalised).
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vec)]
        dir: DVec3,
        /// Arclength to trace (scene units).
        #[arg(long)]
        length: f64,
        /// Stepper: rk4 (Sharma's RK4, the fastest at every accuracy measured), arc (exact
        /// constant-gradient arc, F at the step's midpoint), snell (iterative Snell steps).
        #[arg(long, default_value = "rk4")]
        stepper: StepperKind,
        /// Step control.
        #[arg(long, value_enum, default_value = "adaptive")]
        control: Control,
        /// Step length for `fixed`, initial step for `tessendorf` (default: the medium's hint).
        #[arg(long)]
        step: Option<f64>,
        /// Tolerance of `adaptive`: position error per unit arclength [default: 1e-8 arc,
        /// 1e-9 rk4, 1e-5 snell].
        #[arg(long)]
        tol: Option<f64>,
        /// T_max of `tessendorf`.
        #[arg(long, default_value_t = 1e-2)]
        tmax: f64,
        /// T_min of `tessendorf`.
        #[arg(long, default_value_t = 1e-4)]
        tmin: f64,
        /// Seed of the random ξ of `tessendorf`.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Maximum number of step attempts (N_max).
        #[arg(long, default_value_t = 1_000_000)]
        max_steps: u64,
        /// Write every accepted step as CSV (step,s,x,y,z,dx,dy,dz,n).
        #[arg(long)]
        csv: Option<PathBuf>,
        /// Draw the path (two projections over the index) as PNG.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
}

/// The most photon paths `render --paths` draws.
const MAX_PATHS: u64 = 10_000;

/// `grinlight render` options; each overrides the scene's `[render]` / `[camera]` key.
#[derive(clap::Args)]
struct RenderArgs {
    /// Scene file (TOML).
    scene: PathBuf,
    /// Output EXR (default: [output] path, else <scene name>.exr here).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Camera samples per pixel per pass.
    #[arg(long)]
    spp: Option<u32>,
    /// Seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Worker threads (0 = all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Image width (the vertical field of view is kept).
    #[arg(long)]
    width: Option<u32>,
    /// Image height.
    #[arg(long)]
    height: Option<u32>,
    /// Global-map photons per pass.
    #[arg(long)]
    photons: Option<u64>,
    /// Caustic-map photons per pass.
    #[arg(long)]
    caustic_photons: Option<u64>,
    /// Final-gather rays per camera sample (0: no secondary light).
    #[arg(long)]
    gather: Option<u32>,
    /// Photon gather radius (scene units): initial caustic radius, largest global radius.
    #[arg(long)]
    radius: Option<f64>,
    /// k of the k-nearest-photon radius.
    #[arg(long)]
    knn: Option<u32>,
    /// Progressive passes (photon pass + camera pass; the caustic radius shrinks).
    #[arg(long)]
    passes: Option<u32>,
    /// Start no new pass after this many seconds (with no --passes: as many as fit).
    #[arg(long)]
    time_budget: Option<f64>,
    /// Write the EXR (and PNG) every N passes, not only at the end.
    #[arg(long)]
    checkpoint: Option<u32>,
    /// Photons traced for the scene's receivers.
    #[arg(long)]
    receiver_photons: Option<u64>,
    /// Also draw the paths of the first N (≤ 10000) receiver photons through the scene's GRIN
    /// fiber, with its index profile and the first receiver's irradiance (seed 004 fig. 5), as
    /// <output stem>.paths.png.
    #[arg(long)]
    paths: Option<u64>,
}

/// Measures the receivers and writes, next to `exr`, per receiver `<stem>.<name>.csv` (bins),
/// `.png` (heat map), `.radial.csv` and `.radial.png` (radial profile); with `paths` N > 0,
/// also `<stem>.paths.png`, the fiber figure with N photon paths.
fn measure_receivers(
    scene: &scene::Scene,
    threads: usize,
    exr: &std::path::Path,
    paths: u64,
) -> Result<()> {
    let fiber = match paths {
        0 => None,
        _ => Some(scene.grin_fiber().ok_or_else(|| {
            Error::Usage(
                "--paths draws a GRIN fiber: the scene has no cylinder filled with a gradient medium"
                    .into(),
            )
        })?),
    };
    let start = std::time::Instant::now();
    let spinner = indicatif::ProgressBar::new_spinner().with_message(format!(
        "tracing {} photons for {} receiver(s)",
        scene.render.receiver_photons,
        scene.receivers.len()
    ));
    spinner.enable_steady_tick(std::time::Duration::from_millis(200));
    let (measurements, budget, report) = grinlight::render::measure(scene, threads, 0)?;
    spinner.finish_and_clear();
    let stem = exr.with_extension("");
    let name = |r: &grinlight::receiver::Receiver, ext: &str| {
        PathBuf::from(format!("{}.{}.{ext}", stem.display(), r.name))
    };
    let mut lines = Vec::new();
    for (r, m) in scene.receivers.iter().zip(&measurements) {
        let profile = receiver::radial_profile(r, m);
        receiver::write_csv(r, m, &name(r, "csv"))?;
        receiver::write_png(r, m, &name(r, "png"))?;
        receiver::write_radial_csv(&profile, &name(r, "radial.csv"))?;
        receiver::write_radial_png(&[&profile], &name(r, "radial.png"))?;
        lines.push(format!(
            "receiver '{}': flux {:.6e} ± {:.1e} W; wrote {} (.png, .radial.csv, .radial.png)",
            r.name,
            m.flux.0,
            m.flux.1,
            name(r, "csv").display()
        ));
    }
    let mut stdout = std::io::stdout().lock();
    writeln!(
        stdout,
        "measured {} receiver(s) with {} photons in {:.2} s ({:.0} photons/s)",
        scene.receivers.len(),
        report.stats.photons_emitted,
        start.elapsed().as_secs_f64(),
        report.stats.photons_emitted as f64 / report.seconds.0.max(1e-9)
    )?;
    writeln!(stdout, "{}", report.stats.summary())?;
    for l in lines {
        writeln!(stdout, "{l}")?;
    }
    writeln!(
        stdout,
        "{}",
        budget_table(&budget, scene.accel.primitives())
    )?;
    if let Some(fiber) = fiber {
        let tracer = grinlight::transport::Tracer::new(scene);
        let sources = grinlight::photon::Sources::new(&tracer);
        let drawn = grinlight::photon::photon_paths(&tracer, &sources, 0, paths);
        let out = PathBuf::from(format!("{}.paths.png", stem.display()));
        let legend = grinlight::fiber_figure::write(
            scene,
            &fiber,
            &drawn,
            (&scene.receivers[0], &measurements[0]),
            &out,
        )?;
        writeln!(stdout, "wrote {}: {legend}", out.display())?;
    }
    Ok(())
}

/// Where the measurement's photon power went, one line per fate with its share.
fn budget_table(
    b: &grinlight::photon::Budget,
    primitives: &[grinlight::shapes::Primitive],
) -> String {
    let share = |w: f64| 100.0 * w / b.emitted.max(f64::MIN_POSITIVE);
    let mut lines = vec![format!(
        "energy budget: emitted {:.6e} W, booked {:.6e} W",
        b.emitted,
        b.booked()
    )];
    for (&p, &w) in &b.out_through {
        lines.push(format!(
            "  {w:.6e} W ({:6.3} %) left through {}",
            share(w),
            primitives[p]
        ));
    }
    for (name, w) in [
        ("reflected without entering a dielectric", b.reflected),
        ("missed every specular surface", b.missed),
        ("absorbed", b.absorbed),
        ("lost (captured, out of steps or cut at max_depth)", b.lost),
    ] {
        lines.push(format!("  {w:.6e} W ({:6.3} %) {name}", share(w)));
    }
    lines.join("\n")
}

fn parse_vec(s: &str) -> std::result::Result<DVec3, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected X,Y,Z, got '{s}'"));
    }
    let mut v = [0.0; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = p
            .parse::<f64>()
            .map_err(|_| format!("'{p}' is not a number"))?;
        if !slot.is_finite() {
            return Err(format!("'{p}' is not finite"));
        }
    }
    Ok(DVec3::from_array(v))
}

fn render(args: RenderArgs) -> Result<()> {
    let scene_path = args.scene;
    let mut scene = scene::load_scene(&scene_path)?;
    let settings = &mut scene.render;
    settings.spp = args.spp.map_or(settings.spp, |n| n.max(1));
    settings.seed = args.seed.unwrap_or(settings.seed);
    settings.photons = args.photons.unwrap_or(settings.photons);
    settings.caustic_photons = args.caustic_photons.unwrap_or(settings.caustic_photons);
    settings.gather = args.gather.unwrap_or(settings.gather);
    settings.knn = args.knn.map_or(settings.knn, |k| k.max(1));
    if let Some(r) = args.radius {
        settings.radius = Some(positive("radius", r)?);
    }
    if let Some(b) = args.time_budget {
        settings.time_budget = Some(positive("time-budget", b)?);
        if args.passes.is_none() {
            settings.passes = u32::MAX;
        }
    }
    settings.passes = args.passes.map_or(settings.passes, |p| p.max(1));
    settings.receiver_photons = args
        .receiver_photons
        .map_or(settings.receiver_photons, |n| n.max(1));
    let threads = args.threads.unwrap_or(settings.threads);
    let exr = args
        .output
        .clone()
        .or_else(|| scene.output.path.clone())
        .unwrap_or_else(|| {
            PathBuf::from(scene_path.file_stem().unwrap_or_default()).with_extension("exr")
        });
    let paths = args.paths.unwrap_or(0);
    if paths > MAX_PATHS {
        return Err(Error::Usage(format!(
            "--paths {paths}: a figure shows at most {MAX_PATHS} paths (each is kept in memory)"
        ))
        .into());
    }
    if paths > 0 && scene.receivers.is_empty() {
        return Err(Error::Usage(format!(
            "{}: --paths shows the paths with a receiver's irradiance: the scene has no [[receiver]]",
            scene_path.display()
        ))
        .into());
    }
    if !scene.receivers.is_empty() {
        measure_receivers(&scene, threads, &exr, paths)?;
    }
    let Some(camera) = scene.camera.as_mut() else {
        if !scene.receivers.is_empty() {
            return Ok(());
        }
        return Err(Error::Usage(format!(
            "{}: the scene has no [camera] and no [[receiver]]: nothing to render",
            scene_path.display()
        ))
        .into());
    };
    for (flag, v) in [("--width", args.width), ("--height", args.height)] {
        if v.is_some_and(|v| v == 0 || v > 65_536) {
            return Err(Error::Usage(format!("{flag} must be in 1..=65536")).into());
        }
    }
    camera.width = args.width.unwrap_or(camera.width);
    camera.height = args.height.unwrap_or(camera.height);
    let (w, h) = (camera.width, camera.height);
    let png = scene.output.png.then(|| exr.with_extension("png"));
    let write = |film: &grinlight::film::Film| -> grinlight::error::Result<()> {
        film.write_exr(&exr)?;
        if let Some(png) = &png {
            film.write_png(png, scene.output.exposure)?;
        }
        Ok(())
    };
    let tiles = (w as u64).div_ceil(16) * (h as u64).div_ceil(16);
    let passes = scene.render.passes;
    let bar = indicatif::ProgressBar::new(tiles * passes as u64).with_style(
        indicatif::ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {msg} ETA {eta}")
            .expect("valid template"),
    );
    let budget = scene.render.time_budget;
    let progress = |p: Progress| match p {
        Progress::Pass(i) => bar.set_message(match (budget, passes) {
            (Some(b), u32::MAX) => format!("pass {} (budget {b} s)", i + 1),
            _ => format!("pass {}/{passes}", i + 1),
        }),
        Progress::Tile => bar.inc(1),
    };
    let checkpoint = args.checkpoint.unwrap_or(0);
    let start = std::time::Instant::now();
    let mut on_pass = |done: u32, film: &grinlight::film::Film| {
        if checkpoint > 0 && done % checkpoint == 0 {
            write(film)?;
            bar.println(format!(
                "pass {done}: wrote {} at {:.1} s",
                exr.display(),
                start.elapsed().as_secs_f64()
            ));
        }
        Ok(())
    };
    let (film, report) = grinlight::render::render(&scene, threads, &progress, &mut on_pass)?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    // Write every file before printing, so a closed stdout cannot cut the outputs short.
    write(&film)?;
    let mut stdout = std::io::stdout().lock();
    writeln!(
        stdout,
        "rendered {} ({w}×{h}, {} spp × {} passes) in {seconds:.2} s",
        scene_path.display(),
        scene.render.spp,
        report.passes
    )?;
    writeln!(stdout, "{}", report.summary())?;
    writeln!(
        stdout,
        "wrote {} (layers: {})",
        exr.display(),
        grinlight::film::LAYERS.join(", ")
    )?;
    if let Some(png) = png {
        writeln!(stdout, "wrote {}", png.display())?;
    }
    Ok(())
}

/// `grinlight validate`: the GRIN fiber and its layered twins for each Δn, measured with
/// independent photon streams, compared bin by bin on the first receiver.
fn validate(
    path: &std::path::Path,
    dns: &[f64],
    max_width: f64,
    photons: Option<u64>,
    threads: usize,
    plot: Option<PathBuf>,
) -> Result<()> {
    let load = || -> Result<scene::Scene> {
        let mut s = scene::load_scene(path)?;
        if let Some(n) = photons {
            s.render.receiver_photons = positive("photons", n as f64)? as u64;
        }
        if s.receivers.is_empty() {
            return Err(
                Error::Usage(format!("{}: no [[receiver]] to compare on", path.display())).into(),
            );
        }
        Ok(s)
    };
    let grin = load()?;
    let rec = &grin.receivers[0];
    let t = std::time::Instant::now();
    let (reference, _, grin_report) = grinlight::render::measure(&grin, threads, 0)?;
    if reference[0].flux.0 <= 0.0 {
        return Err(Error::Usage(format!(
            "{}: receiver '{}' received no light from the GRIN fiber: nothing to compare",
            path.display(),
            rec.name
        ))
        .into());
    }
    let mut stdout = std::io::stdout().lock();
    writeln!(
        stdout,
        "GRIN fiber: receiver '{}' flux {:.6e} ± {:.1e} W ({} photons, {:.2} % cut at max_depth, {:.1} s)",
        rec.name,
        reference[0].flux.0,
        reference[0].flux.1,
        grin.render.receiver_photons,
        100.0 * grin_report.stats.depth_limited as f64
            / grin_report.stats.photons_emitted.max(1) as f64,
        t.elapsed().as_secs_f64()
    )?;
    writeln!(
        stdout,
        "| Δn | layers | widest layer | flux ratio (layered/GRIN) | χ²/dof | dof | max |z| | cut at max_depth | time (s) |"
    )?;
    writeln!(stdout, "|---|---|---|---|---|---|---|---|---|")?;
    let mut profiles = vec![receiver::radial_profile(rec, &reference[0])];
    for (k, &dn) in dns.iter().enumerate() {
        let mut twin = load()?;
        let layers = twin.layer_fiber(dn, max_width)?;
        let t = std::time::Instant::now();
        let (layered, _, report) = grinlight::render::measure(&twin, threads, 1 + k as u64)?;
        let c = receiver::compare(&reference[0], &layered[0]);
        writeln!(
            stdout,
            "| {dn} | {} | {:.4} | {:.5} ± {:.5} | {:.3} | {} | {:.2} | {:.2} % | {:.1} |",
            layers.len(),
            layers.iter().map(|l| l.outer - l.inner).fold(0.0, f64::max),
            c.flux_ratio,
            c.flux_ratio_stderr,
            c.chi2_per_dof,
            c.dof,
            c.max_z,
            100.0 * report.stats.depth_limited as f64 / report.stats.photons_emitted.max(1) as f64,
            t.elapsed().as_secs_f64()
        )?;
        profiles.push(receiver::radial_profile(rec, &layered[0]));
    }
    let plot = plot.unwrap_or_else(|| {
        PathBuf::from(path.file_stem().unwrap_or_default()).with_extension("validate.png")
    });
    let refs: Vec<&[(f64, f64, f64)]> = profiles.iter().map(Vec::as_slice).collect();
    receiver::write_radial_png(&refs, &plot)?;
    writeln!(
        stdout,
        "wrote {} (radial irradiance: GRIN first, then each Δn in order; ±1 standard error)",
        plot.display()
    )?;
    Ok(())
}

fn positive(name: &str, v: f64) -> std::result::Result<f64, Error> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::Usage(format!(
            "--{name} must be a finite number > 0, got {v}"
        )))
    }
}

fn main() {
    if let Err(e) = run(Cli::parse()) {
        // A closed pipe (`grinlight trace … | head`) is not an error worth a message.
        if e.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
        {
            return;
        }
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render(args) => render(args),
        Command::Validate {
            scene,
            dn,
            max_width,
            photons,
            threads,
            plot,
        } => validate(
            &scene,
            &dn,
            max_width.unwrap_or(f64::INFINITY),
            photons,
            threads,
            plot,
        ),
        Command::Trace {
            scene,
            medium,
            from,
            dir,
            length,
            stepper,
            control,
            step,
            tol,
            tmax,
            tmin,
            seed,
            max_steps,
            csv,
            plot,
        } => {
            let scene = scene::load_scene(&scene)?;
            let medium = scene.medium(&medium)?;
            let length = positive("length", length)?;
            if dir.length() == 0.0 {
                return Err(Error::Usage("--dir must be a non-zero vector".into()).into());
            }
            let start = RayState::new(medium, from, dir).ok_or_else(|| {
                Error::Usage(format!("--from {from}: the medium captures rays there (singular or non-positive index)"))
            })?;
            let default_step = || medium.step_hint(from).min(length / 100.0);
            let control = match control {
                Control::Adaptive => StepControl::Adaptive {
                    tolerance: positive("tol", tol.unwrap_or(stepper.default_tolerance()))?,
                },
                Control::Fixed => StepControl::Fixed {
                    step: positive(
                        "step",
                        step.ok_or_else(|| Error::Usage("--control fixed needs --step".into()))?,
                    )?,
                },
                Control::Tessendorf => {
                    if !(tmin >= 0.0 && tmax > tmin) {
                        return Err(Error::Usage(format!(
                            "need 0 ≤ --tmin < --tmax, got {tmin} and {tmax}"
                        ))
                        .into());
                    }
                    StepControl::Tessendorf {
                        initial_step: positive("step", step.unwrap_or_else(default_step))?,
                        t_max: tmax,
                        t_min: tmin,
                        seed,
                    }
                }
            };
            if stepper == StepperKind::Snell && trace::at_turning_point(&start) {
                eprintln!(
                    "warning: --dir is perpendicular to ∇n at --from (a turning point): Snell steps \
                     cannot bend a ray there and it will run straight; use --stepper rk4 or arc"
                );
            }
            let limits = MarchLimits {
                length,
                max_steps,
                bounds: Bounds::Unbounded,
            };
            let (out, points) = trace::trace_path(medium, stepper, control, start, &limits);
            // Write every file before printing, so a closed stdout cannot cut the outputs short.
            if let Some(path) = &csv {
                trace::write_csv(&points, path)?;
            }
            let legend = match &plot {
                Some(path) => Some(trace::plot_path(medium, &points, path)?),
                None => None,
            };
            let mut stdout = std::io::stdout().lock();
            writeln!(stdout, "{}", trace::summary(&out))?;
            if let Some(path) = csv {
                writeln!(stdout, "wrote {} ({} rows)", path.display(), points.len())?;
            }
            if let (Some(path), Some(legend)) = (plot, legend) {
                writeln!(stdout, "wrote {}: {legend}", path.display())?;
            }
            Ok(())
        }
    }
}
