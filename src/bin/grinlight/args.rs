//! The command line's arguments (clap) and the library jobs they describe.

use clap::{Parser, Subcommand, ValueEnum};
use glam::DVec3;
use grinlight::commands::{
    ConvertJob, MergeJob, Overrides, RayTrace, RenderJob, TraceControl, TraceJob, ValidateJob,
};
use grinlight::curve::StepperKind;
use grinlight::import::ImportOptions;
use grinlight::settings::{Given, Key, KEYS};
use grinlight::shard::Shard;
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "grinlight",
    version,
    about = "A renderer for light that bends in gradient-index media"
)]
pub struct Cli {
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// Step controls of `trace`.
#[derive(Clone, Copy, ValueEnum)]
pub enum Control {
    /// Error-controlled steps (default): --tol is the position error per unit arclength.
    Adaptive,
    /// Tessendorf (2022) §4: --tmax, --tmin, random shrink/grow, --max-steps as N_max.
    Tessendorf,
    /// Fixed steps of --step.
    Fixed,
}

/// The commands.
#[derive(Subcommand)]
pub enum Command {
    /// Render a scene's camera view to a multi-layer EXR and a PNG preview, and measure its
    /// receivers. A Mitsuba 3 (.xml) or pbrt-v4 (.pbrt) scene is converted as `convert` does. Ctrl-C writes what is done so far (marked partial) and exits with 130;
    /// a second Ctrl-C quits at once.
    Render(RenderArgs),
    /// Compare a scene's GRIN fiber with its layered twin (concentric homogeneous cylinders)
    /// on the scene's receivers.
    Validate(ValidateArgs),
    /// Trace one ray through a medium of a scene (unbounded) and print where it ends.
    Trace(TraceArgs),
    /// Convert a Mitsuba 3 (.xml) or pbrt-v4 (.pbrt) scene to a grinlight scene file (TOML), to render or to
    /// edit (add a GRIN medium); what converts only approximately is refused unless
    /// --approximate, then listed.
    Convert(ConvertArgs),
    /// Merge the partial results of a render's shards (`render --shard K/N`) into its EXR,
    /// PNG, receiver files and energy budget: bit for bit those of one whole render.
    Merge(MergeArgs),
}

/// How a scene of another renderer is read (`render`, `convert`).
#[derive(clap::Args)]
pub struct ImportArgs {
    /// Give the scene's parameter $NAME the value VALUE (Mitsuba's -D), before its <default>.
    #[arg(short = 'D', long = "define", value_name = "NAME=VALUE", value_parser = parse_define)]
    define: Vec<(String, String)>,
    /// Convert what converts only approximately (each approximation listed) instead of
    /// refusing it.
    #[arg(long)]
    approximate: bool,
}

impl From<ImportArgs> for ImportOptions {
    fn from(a: ImportArgs) -> Self {
        ImportOptions {
            defines: a.define,
            approximate: a.approximate,
        }
    }
}

fn parse_define(s: &str) -> std::result::Result<(String, String), String> {
    match s.split_once('=') {
        Some((name, value)) if !name.is_empty() => Ok((name.to_string(), value.to_string())),
        _ => Err(format!("expected NAME=VALUE, got '{s}'")),
    }
}

/// `grinlight convert` options.
#[derive(clap::Args)]
pub struct ConvertArgs {
    /// The Mitsuba 3 (.xml) or pbrt-v4 (.pbrt) scene.
    scene: PathBuf,
    /// The grinlight scene file to write (.toml); it may replace only a file convert wrote.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    import: ImportArgs,
}

impl From<ConvertArgs> for ConvertJob {
    fn from(a: ConvertArgs) -> Self {
        ConvertJob {
            scene: a.scene,
            output: a.output,
            import: a.import.into(),
        }
    }
}

/// `grinlight merge` options.
#[derive(clap::Args)]
pub struct MergeArgs {
    /// The shards' partial files (.partial), in any order.
    #[arg(required = true)]
    partials: Vec<PathBuf>,
    /// Output EXR, ending in .exr (default: the scene's [output] path, else <scene name>.exr
    /// here); the PNG preview and receiver files are written beside it.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Merge even if shards are missing: an estimate from the work there is (said so).
    #[arg(long)]
    allow_missing: bool,
}

impl From<MergeArgs> for MergeJob {
    fn from(a: MergeArgs) -> Self {
        MergeJob {
            partials: a.partials,
            output: a.output,
            allow_missing: a.allow_missing,
        }
    }
}

/// `grinlight validate` options.
#[derive(clap::Args)]
// A negative number is a value (refused by its range, named), not an unknown option.
#[command(allow_negative_numbers = true)]
pub struct ValidateArgs {
    /// Scene file (TOML) with a GRIN-filled cylinder and at least one [[receiver]].
    scene: PathBuf,
    /// Index step between layers; several, comma-separated, give a convergence table.
    #[arg(long, value_delimiter = ',', default_value = "0.005")]
    dn: Vec<f64>,
    /// Also start a new layer wherever one reaches this width (scene units): equal-Δn
    /// layers are wide near the axis, where paraxial rays then feel no gradient.
    #[arg(long)]
    max_width: Option<f64>,
    /// Photons per measurement (≥ 1; default: [render] receiver_photons).
    #[arg(long)]
    photons: Option<u64>,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Where to write the radial profiles plot (default: <scene name>.validate.png).
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// `grinlight trace` options.
#[derive(clap::Args)]
// A negative number is a value (refused by its range, named), not an unknown option.
#[command(allow_negative_numbers = true)]
pub struct TraceArgs {
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
    /// Vacuum wavelength, nm (360–830), at which a dispersive medium is traced [default:
    /// the d line, 587.5618 nm].
    #[arg(long)]
    wavelength: Option<f64>,
    /// Stepper: rk4 (Sharma's RK4, step doubling), rkn (the RKN6(4) pair: sixth order, the
    /// most accurate per unit time), arc (a fourth-order chain of exact constant-gradient
    /// arcs), snell (iterative Snell steps), linearize (the fish-eye's and the hyperbolic
    /// medium's rays on their exact circles; rkn in other media).
    #[arg(long, default_value = "linearize")]
    stepper: StepperKind,
    /// Step control.
    #[arg(long, value_enum, default_value = "adaptive")]
    control: Control,
    /// Step length for `fixed`, initial step for `tessendorf` (default: the medium's hint).
    #[arg(long)]
    step: Option<f64>,
    /// Tolerance of `adaptive`: the step's error estimate per unit arclength [default: 1e-6
    /// rkn, 1e-9 rk4, 1e-6 arc, 1e-5 snell, 1e-6 linearize].
    #[arg(long)]
    tol: Option<f64>,
    /// T_max of `tessendorf`.
    #[arg(long, default_value_t = TraceControl::T_MAX)]
    tmax: f64,
    /// T_min of `tessendorf`.
    #[arg(long, default_value_t = TraceControl::T_MIN)]
    tmin: f64,
    /// Seed of the random ξ of `tessendorf`.
    #[arg(long, default_value_t = TraceControl::SEED)]
    seed: u64,
    /// Maximum number of step attempts (N_max, ≥ 1).
    #[arg(long, default_value_t = RayTrace::MAX_STEPS)]
    max_steps: u64,
    /// Carry a field (polarization) along the ray, starting along X,Y,Z (its part
    /// perpendicular to --dir), by Rytov's law, and print it at the end with the geometric
    /// phase: the solid angle the ray's direction swept (closed by the shortest arc back to
    /// its start's), by which the field turned about the ray.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vec)]
    polarization: Option<DVec3>,
    /// Write every accepted step as CSV (step,s,x,y,z,dx,dy,dz,n).
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Draw the path (two projections over the index) as PNG.
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// `grinlight render` options; each overrides the scene's `[render]` / `[camera]` key.
#[derive(clap::Args)]
// A negative number is a value (refused by its range, named), not an unknown option.
#[command(allow_negative_numbers = true)]
pub struct RenderArgs {
    /// Scene file: grinlight's TOML, a Mitsuba 3 scene (.xml) or a pbrt-v4 scene (.pbrt).
    scene: PathBuf,
    #[command(flatten)]
    import: ImportArgs,
    /// Output EXR, ending in .exr (default: [output] path, else <scene name>.exr here); the
    /// PNG preview and receiver files are written beside it. With --shard: the partial file,
    /// ending in .partial (default: <scene name>.shard-K-of-N.partial here).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Render only the K-th of N slices of the passes and receiver photons, into a partial
    /// result for `grinlight merge` (e.g. one task of a Slurm job array).
    #[arg(long, value_parser = parse_shard)]
    shard: Option<Shard>,
    /// Continue the render (or shard) a kill or an interrupt stopped, from the partial it
    /// saved (<output>.partial, or the shard's file); give the same options.
    #[arg(long)]
    resume: bool,
    #[command(flatten)]
    settings: SettingArgs,
    /// Trace every camera ray even where a deflection table applies (the same as
    /// --deflection-table false).
    #[arg(long)]
    no_table: bool,
    /// Save the partial and write the EXR (and PNG) every N passes and after every block of
    /// receiver photons (default: every minute and at the end).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    checkpoint: Option<u32>,
    /// Also draw the paths of the first N (≤ 10000) receiver photons through the scene's GRIN
    /// fiber, with its index profile and the first receiver's irradiance (Zhdanov et al. (2020) fig. 5), as
    /// <output stem>.paths.png.
    #[arg(long)]
    paths: Option<u64>,
}

/// The settings of the settings table ([`grinlight::settings::KEYS`]) as options, one
/// `--name VALUE` each: built from the table, so its names, help and refusals are the scene
/// file's.
pub struct SettingArgs {
    given: Vec<(&'static Key, String)>,
}

impl SettingArgs {
    /// The settings given, for the library to read.
    fn overrides(self, no_table: bool) -> Overrides {
        let mut o = Overrides::default();
        for (key, text) in self.given {
            o.set(key, Given::from_text(&text));
        }
        if no_table {
            o.set(&grinlight::settings::DEFLECTION_TABLE, false);
        }
        o
    }
}

impl clap::FromArgMatches for SettingArgs {
    fn from_arg_matches(m: &clap::ArgMatches) -> Result<Self, clap::Error> {
        let given = KEYS
            .iter()
            .filter_map(|&key| {
                let text = m.get_one::<String>(key.name)?;
                Some((key, text.clone()))
            })
            .collect();
        Ok(Self { given })
    }

    fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl clap::Args for SettingArgs {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        KEYS.iter().fold(cmd, |cmd, key| {
            cmd.arg(
                clap::Arg::new(key.name)
                    .long(key.flag().trim_start_matches("--").to_string())
                    .value_name(key.value_name())
                    .allow_negative_numbers(true)
                    .help(format!(
                        "{} [{}; default {}]",
                        key.doc,
                        key.range(),
                        key.default
                    )),
            )
        })
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

fn parse_shard(s: &str) -> std::result::Result<Shard, String> {
    Shard::parse(s).map_err(|e| e.to_string())
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

impl From<RenderArgs> for RenderJob {
    fn from(a: RenderArgs) -> Self {
        RenderJob {
            scene: a.scene,
            output: a.output,
            overrides: a.settings.overrides(a.no_table),
            checkpoint: a.checkpoint.unwrap_or(0),
            paths: a.paths.unwrap_or(0),
            shard: a.shard,
            resume: a.resume,
            import: a.import.into(),
        }
    }
}

impl From<TraceArgs> for TraceJob {
    fn from(a: TraceArgs) -> Self {
        let control = match a.control {
            Control::Adaptive => TraceControl::Adaptive { tolerance: a.tol },
            Control::Fixed => TraceControl::Fixed { step: a.step },
            Control::Tessendorf => TraceControl::Tessendorf {
                step: a.step,
                t_max: a.tmax,
                t_min: a.tmin,
                seed: a.seed,
            },
        };
        TraceJob {
            scene: a.scene,
            ray: RayTrace {
                medium: a.medium,
                from: a.from,
                dir: a.dir,
                length: a.length,
                wavelength: a.wavelength,
                stepper: a.stepper,
                control,
                max_steps: a.max_steps,
                polarization: a.polarization,
            },
            csv: a.csv,
            plot: a.plot,
        }
    }
}

impl From<ValidateArgs> for ValidateJob {
    fn from(a: ValidateArgs) -> Self {
        ValidateJob {
            scene: a.scene,
            dn: a.dn,
            max_width: a.max_width,
            photons: a.photons,
            threads: a.threads,
            plot: a.plot,
        }
    }
}

/// The command-line option of a setting (see [`grinlight::error::Error::Setting`]): `--` and
/// its name with dashes, but for the trace options whose flags are shorter than the names the
/// library and Python give them.
pub fn flag(key: &str) -> String {
    match key {
        "origin" => "--from".into(),
        "direction" => "--dir".into(),
        "tolerance" => "--tol".into(),
        "t_min" => "--tmin".into(),
        "t_max" => "--tmax".into(),
        other => format!("--{}", other.replace('_', "-")),
    }
}
