//! The grinlight command line.

use anyhow::Result;
use clap::{Parser, Subcommand, ValueEnum};
use glam::DVec3;
use grinlight::curve::{Bounds, MarchLimits, RayState, StepControl, StepperKind};
use grinlight::error::Error;
use grinlight::{scene, trace};
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
    Render {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Output EXR (default: [output] path, else <scene name>.exr here).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Samples per pixel (overrides [render] spp).
        #[arg(long)]
        spp: Option<u32>,
        /// Seed (overrides [render] seed).
        #[arg(long)]
        seed: Option<u64>,
        /// Worker threads (overrides [render] threads; 0 = all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Image width (overrides [camera] width; the vertical field of view is kept).
        #[arg(long)]
        width: Option<u32>,
        /// Image height (overrides [camera] height).
        #[arg(long)]
        height: Option<u32>,
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

#[allow(clippy::too_many_arguments)]
fn render(
    scene_path: PathBuf,
    output: Option<PathBuf>,
    spp: Option<u32>,
    seed: Option<u64>,
    threads: Option<usize>,
    width: Option<u32>,
    height: Option<u32>,
) -> Result<()> {
    let mut scene = scene::load_scene(&scene_path)?;
    if let Some(n) = spp {
        scene.render.spp = n.max(1);
    }
    if let Some(s) = seed {
        scene.render.seed = s;
    }
    let threads = threads.unwrap_or(scene.render.threads);
    let Some(camera) = scene.camera.as_mut() else {
        return Err(Error::Usage(format!(
            "{}: the scene has no [camera] to render",
            scene_path.display()
        ))
        .into());
    };
    for (flag, v) in [("--width", width), ("--height", height)] {
        if v.is_some_and(|v| v == 0 || v > 65_536) {
            return Err(Error::Usage(format!("{flag} must be in 1..=65536")).into());
        }
    }
    camera.width = width.unwrap_or(camera.width);
    camera.height = height.unwrap_or(camera.height);
    let (w, h) = (camera.width, camera.height);
    let exr = output
        .or_else(|| scene.output.path.clone())
        .unwrap_or_else(|| {
            PathBuf::from(scene_path.file_stem().unwrap_or_default()).with_extension("exr")
        });
    let tiles = (w as u64).div_ceil(16) * (h as u64).div_ceil(16);
    let bar = indicatif::ProgressBar::new(tiles).with_style(
        indicatif::ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} tiles, ETA {eta}",
        )
        .expect("valid template"),
    );
    let start = std::time::Instant::now();
    let (film, stats) = grinlight::render::render(&scene, threads, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    // Write every file before printing, so a closed stdout cannot cut the outputs short.
    film.write_exr(&exr)?;
    let png = scene.output.png.then(|| exr.with_extension("png"));
    if let Some(png) = &png {
        film.write_png(png, scene.output.exposure)?;
    }
    let mut stdout = std::io::stdout().lock();
    writeln!(
        stdout,
        "rendered {} ({w}×{h}, {} spp) in {seconds:.2} s",
        scene_path.display(),
        scene.render.spp
    )?;
    writeln!(stdout, "{}", stats.summary())?;
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
        Command::Render {
            scene,
            output,
            spp,
            seed,
            threads,
            width,
            height,
        } => render(scene, output, spp, seed, threads, width, height),
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
