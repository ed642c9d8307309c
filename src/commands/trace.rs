//! `grinlight trace`: one ray through one medium, its summary, its CSV and its picture.

use super::{positive, Observer};
use crate::color::Rgb;
use crate::curve::{
    march_with, Bounds, MarchLimits, MarchOutcome, RayState, StepControl, StepperKind,
};
use crate::error::{Error, Result};
use crate::media::Medium;
use crate::output::{Kind, Outputs};
use crate::plot::{self, Labels, Panel};
use crate::polarization::RytovTransport;
use crate::scene::Scene;
use crate::spectrum::{LAMBDA_MAX, LAMBDA_MIN};
use glam::DVec3;
use std::io::Write;
use std::path::{Path, PathBuf};

/// How a traced ray's steps are chosen (missing values take the defaults below).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TraceControl {
    /// Error-controlled steps at this position error per unit arclength (None: the
    /// stepper's default tolerance).
    Adaptive {
        /// Tolerance.
        tolerance: Option<f64>,
    },
    /// Fixed steps of this length (required).
    Fixed {
        /// Step length.
        step: Option<f64>,
    },
    /// Tessendorf (2022) §4's control.
    Tessendorf {
        /// Initial step (None: the medium's step hint, at most a hundredth of the length).
        step: Option<f64>,
        /// T_max.
        t_max: f64,
        /// T_min.
        t_min: f64,
        /// Seed of the random ξ.
        seed: u64,
    },
}

/// What `grinlight trace` is asked to do.
#[derive(Clone, Debug)]
pub struct TraceJob {
    /// The scene file.
    pub scene: PathBuf,
    /// The ray.
    pub ray: RayTrace,
    /// Write every accepted step here as CSV.
    pub csv: Option<PathBuf>,
    /// Draw the path here as PNG.
    pub plot: Option<PathBuf>,
}

/// One ray to follow through a medium of a scene.
#[derive(Clone, Debug)]
pub struct RayTrace {
    /// The name of one of the scene's media (traced unbounded, with no surfaces).
    pub medium: String,
    /// Start point.
    pub from: DVec3,
    /// Initial direction (any non-zero length).
    pub dir: DVec3,
    /// Arclength to trace (scene units).
    pub length: f64,
    /// Vacuum wavelength, nm (None: [`crate::spectrum::LAMBDA_D`]); a dispersive medium is traced as it is
    /// at this wavelength.
    pub wavelength: Option<f64>,
    /// The stepper.
    pub stepper: StepperKind,
    /// The step control.
    pub control: TraceControl,
    /// Maximum number of step attempts (N_max).
    pub max_steps: u64,
    /// The field's direction at the start (its part perpendicular to `dir`), to be carried
    /// along the ray by Rytov's law ([`crate::polarization`]); None: no field is followed.
    pub polarization: Option<DVec3>,
}

impl RayTrace {
    /// The stepper when none is given.
    pub const STEPPER: StepperKind = StepperKind::Linearize;
    /// Step attempts (N_max) when none is given.
    pub const MAX_STEPS: u64 = 1_000_000;
}

/// A followed ray: how its march ended, and every accepted point (the start first).
#[derive(Clone, Debug)]
pub struct Traced {
    /// How the march ended.
    pub outcome: MarchOutcome,
    /// Every accepted point.
    pub points: Vec<PathPoint>,
    /// The field at the end, where one was asked for ([`RayTrace::polarization`]).
    pub polarization: Option<FieldAtEnd>,
}

/// How one ray's march ended, and the field it carried to its end if asked.
struct Followed {
    /// How the march ended.
    outcome: MarchOutcome,
    /// The field at the end ([`RayTrace::polarization`]).
    polarization: Option<FieldAtEnd>,
}

/// The field carried along a traced ray by Rytov's law, at the ray's end
/// ([`crate::polarization::RytovTransport`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldAtEnd {
    /// The field's direction (unit, perpendicular to the ray's direction there).
    pub field: DVec3,
    /// The geometric phase Γ (radians): the solid angle the ray's direction swept, closed by
    /// the shortest arc back to its start's; the field is the start's carried by the shortest
    /// turn of the start's direction into the end's, then turned by Γ counterclockwise about
    /// the end's direction.
    pub phase: f64,
}

impl TraceControl {
    /// Tessendorf's T_max when none is given.
    pub const T_MAX: f64 = 1e-2;
    /// Tessendorf's T_min when none is given.
    pub const T_MIN: f64 = 1e-4;
    /// The seed of Tessendorf's random ξ when none is given.
    pub const SEED: u64 = 1;

    /// The step control, checked, for a ray from `from` in `medium` over `length`.
    fn resolve(
        self,
        stepper: StepperKind,
        medium: &dyn Medium,
        from: DVec3,
        dir: DVec3,
        length: f64,
    ) -> Result<StepControl> {
        Ok(match self {
            TraceControl::Adaptive { tolerance } => StepControl::Adaptive {
                tolerance: positive(
                    "tolerance",
                    tolerance.unwrap_or(stepper.default_tolerance()),
                )?,
            },
            TraceControl::Fixed { step } => StepControl::Fixed {
                step: positive(
                    "step",
                    step.ok_or_else(|| Error::Setting {
                        key: "step",
                        message: "is needed by the fixed control".into(),
                    })?,
                )?,
            },
            TraceControl::Tessendorf {
                step,
                t_max,
                t_min,
                seed,
            } => {
                if !(t_min >= 0.0 && t_max > t_min) {
                    return Err(Error::Setting {
                        key: "t_min",
                        message: format!(
                            "must be ≥ 0 and below t_max, got {} and t_max {}",
                            crate::error::number(t_min),
                            crate::error::number(t_max)
                        ),
                    });
                }
                StepControl::Tessendorf {
                    initial_step: positive(
                        "step",
                        step.unwrap_or_else(|| medium.step_hint(from, dir).min(length / 100.0)),
                    )?,
                    t_max,
                    t_min,
                    seed,
                }
            }
        })
    }
}

/// Runs `grinlight trace`: the ray's summary, and its CSV and plot if asked, written
/// atomically after checking that neither can overwrite an input or another output. The CSV
/// is written as the ray goes (a trace of 10⁹ steps is 10⁹ rows, not 10⁹ points held); the
/// plot draws at most [`PLOT_POINTS`] of them, evenly spread. An interrupt ends the ray where
/// it is (reason: stopped), its files written up to there.
pub fn trace(job: &TraceJob, observer: &dyn Observer) -> Result<MarchOutcome> {
    let (description, _) = crate::import::load_description(&job.scene, &Default::default())?;
    for w in &description.warnings {
        observer.warning(w);
    }
    let scene = description.build();
    let mut outputs = Outputs::new(&scene.inputs);
    if let Some(csv) = &job.csv {
        outputs.add(csv, Kind::Csv)?;
    }
    if let Some(plot) = &job.plot {
        outputs.add(plot, Kind::Png)?;
    }
    let mut drawn = Decimated::default();
    let mut rows = 0u64;
    let followed = match &job.csv {
        None => follow(&scene, &job.ray, observer, &mut |p| {
            if job.plot.is_some() {
                drawn.push(*p);
            }
            Ok(())
        })?,
        Some(path) => {
            let mut followed = None;
            crate::output::write_atomic(path, |tmp| {
                let io = |e| Error::io(path, e);
                let mut w = std::io::BufWriter::new(std::fs::File::create(tmp).map_err(io)?);
                writeln!(w, "# {}: a traced ray's path", crate::output::signature()).map_err(io)?;
                writeln!(w, "step,s,x,y,z,dx,dy,dz,n").map_err(io)?;
                followed = Some(follow(&scene, &job.ray, observer, &mut |p| {
                    let (x, d) = (p.state.position, p.state.direction);
                    writeln!(
                        w,
                        "{rows},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
                        p.s, x.x, x.y, x.z, d.x, d.y, d.z, p.state.index.n
                    )
                    .map_err(io)?;
                    rows += 1;
                    if job.plot.is_some() {
                        drawn.push(*p);
                    }
                    Ok(())
                })?);
                w.flush().map_err(io)
            })?;
            followed.expect("followed while writing")
        }
    };
    let medium = scene.medium(&job.ray.medium)?;
    let legend = match &job.plot {
        Some(path) => Some(plot_path(medium, &drawn.points, path)?),
        None => None,
    };
    observer.line(&summary(&followed.outcome));
    if let Some(p) = &followed.polarization {
        observer.line(&field_summary(p));
    }
    if let Some(path) = &job.csv {
        observer.line(&format!("wrote {} ({rows} rows)", path.display()));
    }
    if let (Some(path), Some(legend)) = (&job.plot, legend) {
        observer.line(&format!("wrote {}: {legend}", path.display()));
    }
    Ok(followed.outcome)
}

/// The most points a traced ray's plot draws.
pub const PLOT_POINTS: usize = 1 << 17;

/// Points of a path kept for a plot: every one until [`PLOT_POINTS`], then every other of
/// them and of those that follow, and so on — evenly spread over the whole path, in bounded
/// memory.
#[derive(Default)]
struct Decimated {
    points: Vec<PathPoint>,
    /// Keep every `stride`-th point (0 before the first).
    stride: usize,
    seen: usize,
}

impl Decimated {
    fn push(&mut self, p: PathPoint) {
        self.stride = self.stride.max(1);
        if self.seen.is_multiple_of(self.stride) {
            if self.points.len() == PLOT_POINTS {
                self.points = self.points.iter().step_by(2).copied().collect();
                self.stride *= 2;
            }
            if self.seen.is_multiple_of(self.stride) {
                self.points.push(p);
            }
        }
        self.seen += 1;
    }
}

/// Follows one ray through a medium of a loaded scene, keeping every accepted point (the start
/// first), after checking every value of the request (each error names its setting) and that
/// `max_steps` points fit in memory; warns where the stepper cannot bend it; an interrupt (the
/// observer's) ends it where it is.
pub fn trace_ray(scene: &Scene, job: &RayTrace, observer: &dyn Observer) -> Result<Traced> {
    // What a point takes here, and as the numpy arrays the Python package makes of it.
    let per_point = (std::mem::size_of::<PathPoint>() + 10 * 8) as u64;
    crate::resources::check_memory(
        job.max_steps.saturating_add(1).saturating_mul(per_point),
        &format!(
            "a traced ray of up to {} steps, every point kept (max_steps)",
            job.max_steps
        ),
    )?;
    let mut points = Vec::new();
    let followed = follow(scene, job, observer, &mut |p| {
        points.push(*p);
        Ok(())
    })?;
    Ok(Traced {
        outcome: followed.outcome,
        points,
        polarization: followed.polarization,
    })
}

/// Follows one ray as [`trace_ray`] says, showing `visit` each accepted point (the start
/// first); stopped by the observer (or an error of `visit`) where it is.
fn follow(
    scene: &Scene,
    job: &RayTrace,
    observer: &dyn Observer,
    visit: &mut dyn FnMut(&PathPoint) -> Result<()>,
) -> Result<Followed> {
    let reference = scene.medium(&job.medium)?;
    let dispersed = match job.wavelength {
        None => None,
        Some(nm) if (LAMBDA_MIN..=LAMBDA_MAX).contains(&nm) => scene
            .media()
            .index(&job.medium)
            .and_then(|i| scene.media().at_wavelength(i, nm)),
        Some(nm) => {
            return Err(Error::Setting {
                key: "wavelength",
                message: format!(
                    "must be from {LAMBDA_MIN} to {LAMBDA_MAX} nm, got {}",
                    crate::error::number(nm)
                ),
            })
        }
    };
    let medium = dispersed.as_ref().map_or(reference, |p| p.as_medium());
    let length = positive("length", job.length)?;
    for (key, v) in [("origin", job.from), ("direction", job.dir)] {
        if !v.is_finite() {
            return Err(Error::Setting {
                key,
                message: format!("{v} is not finite"),
            });
        }
    }
    if job.from.abs().max_element() > crate::scene::table::MAX_MAGNITUDE {
        return Err(Error::Setting {
            key: "origin",
            message: format!(
                "{}: coordinates must be within ±{:e}",
                job.from.to_array().map(crate::error::number).join(", "),
                crate::scene::table::MAX_MAGNITUDE
            ),
        });
    }
    if job.dir == DVec3::ZERO {
        return Err(Error::Setting {
            key: "direction",
            message: "must be a non-zero vector".into(),
        });
    }
    let start = RayState::new(medium, job.from, job.dir).ok_or_else(|| Error::Setting {
        key: "origin",
        message: format!(
            "{}: the medium captures rays there (singular or non-positive index)",
            job.from
        ),
    })?;
    let control = job
        .control
        .resolve(job.stepper, medium, job.from, start.direction, length)?;
    let mut rytov = job
        .polarization
        .map(|field| {
            RytovTransport::new(start.direction, field).ok_or_else(|| Error::Setting {
                key: "polarization",
                message: format!(
                    "{}: must be finite and not parallel to the direction",
                    field.to_array().map(crate::error::number).join(", ")
                ),
            })
        })
        .transpose()?;
    if job.stepper == StepperKind::Snell && at_turning_point(&start) {
        observer.warning(
            "--dir is perpendicular to ∇n at --from (a turning point): Snell steps cannot bend a ray there and it will run straight; use --stepper rk4, rkn or arc",
        );
    }
    let limits = MarchLimits {
        length,
        max_steps: crate::settings::MAX_STEPS
            .count(job.max_steps)
            .map_err(|message| Error::Setting {
                key: "max_steps",
                message,
            })?,
        bounds: Bounds::Unbounded,
    };
    let mut failed = None;
    let radiometry = scene
        .media()
        .index(&job.medium)
        .map(|i| scene.media().participating(i));
    let (mut opl, mut optical_depth, mut last) = (0.0, Rgb::ZERO, start.position);
    let outcome = march_with(job.stepper, medium, control, start, &limits, |s, st| {
        opl += st.optical_path;
        if let Some(r) = radiometry {
            optical_depth += r.step_depth(last, st.state.position, st.length);
        }
        last = st.state.position;
        if let Some(r) = &mut rytov {
            r.push(st.state.direction);
        }
        let point = PathPoint {
            s,
            opl,
            optical_depth,
            state: st.state,
        };
        if let Err(e) = visit(&point) {
            failed = Some(e);
            return std::ops::ControlFlow::Break(());
        }
        match observer.stop_requested() {
            true => std::ops::ControlFlow::Break(()),
            false => std::ops::ControlFlow::Continue(()),
        }
    });
    match failed {
        Some(e) => Err(e),
        None => Ok(Followed {
            outcome,
            polarization: rytov.map(|r| FieldAtEnd {
                field: r.field(),
                phase: r.phase(),
            }),
        }),
    }
}

/// One accepted point of a traced path.
#[derive(Clone, Copy, Debug)]
pub struct PathPoint {
    /// Arclength from the start.
    pub s: f64,
    /// Optical path length ∫ n ds from the start (the sum of the steps' own, as
    /// [`MarchOutcome::optical_path`]).
    pub opl: f64,
    /// Optical depth ∫ σa ds of absorption per channel from the start (the medium's
    /// [`crate::volume::Participating`], summed step by step along the chords).
    pub optical_depth: Rgb,
    /// The state there.
    pub state: RayState,
}

/// Whether a ray starts exactly perpendicular to ∇n (to 1e-12), where Snell steps cannot
/// bend it (see [`crate::curve::SnellSteps`]).
pub fn at_turning_point(start: &RayState) -> bool {
    let g = start.index.grad;
    g != DVec3::ZERO && start.direction.dot(g).abs() <= 1e-12 * g.length()
}

/// The one-line summary the CLI prints.
pub fn summary(out: &MarchOutcome) -> String {
    let p = out.state.position;
    let d = out.state.direction;
    format!(
        "end ({:.12}, {:.12}, {:.12}) dir ({:.12}, {:.12}, {:.12}) s {:.12} opl {:.12} steps {} attempts {} reason: {}",
        p.x, p.y, p.z, d.x, d.y, d.z, out.arclength, out.optical_path, out.steps, out.attempts, out.reason.name()
    )
}

/// The line `grinlight trace --polarization` prints: the field at the end and the geometric
/// phase.
pub fn field_summary(p: &FieldAtEnd) -> String {
    let e = p.field;
    format!(
        "field ({:.12}, {:.12}, {:.12}) geometric phase {:.12} rad",
        e.x, e.y, e.z, p.phase
    )
}

/// Draws the path in two projections over the index as a grey shade (darker = lower n):
/// left, the plane of the path's two widest coordinates; right, the widest and the third.
/// Each panel is a slice through the path's mean position along the hidden axis, with its
/// own scale per axis (so thin fiber paths stay visible). Returns a legend line.
pub fn plot_path(medium: &dyn Medium, points: &[PathPoint], path: &Path) -> Result<String> {
    let pos: Vec<DVec3> = points.iter().map(|p| p.state.position).collect();
    let mut ranges: Vec<(f64, f64)> = (0..3)
        .map(|a| plot::range_of(pos.iter().map(|p| p[a])))
        .collect();
    // A flat coordinate (a planar path) still gets a panel showing the index around it.
    let widest = ranges.iter().map(|r| r.1 - r.0).fold(0.0, f64::max);
    for r in &mut ranges {
        let grow = 0.5 * (0.1 * widest - (r.1 - r.0)).max(0.0);
        *r = (r.0 - grow, r.1 + grow);
    }
    let mean = pos.iter().copied().sum::<DVec3>() / pos.len().max(1) as f64;
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| (ranges[b].1 - ranges[b].0).total_cmp(&(ranges[a].1 - ranges[a].0)));
    let names = ["x", "y", "z"];
    let (w, h, margin) = (520u32, 420u32, 80u32);
    let mut img = plot::canvas(2 * (w + 2 * margin), h + 2 * margin);
    let mut legend = Vec::new();
    for (k, (u, v)) in [(axes[0], axes[1]), (axes[0], axes[2])]
        .into_iter()
        .enumerate()
    {
        let hidden = 3 - u - v;
        let at = |x: f64, y: f64| {
            let mut p = mean;
            p[u] = x;
            p[v] = y;
            p[hidden] = mean[hidden];
            medium.sample(p).map_or(f64::NAN, |s| s.n)
        };
        let mut samples = Vec::new();
        for j in 0..32 {
            for i in 0..32 {
                let x = ranges[u].0 + (i as f64 + 0.5) / 32.0 * (ranges[u].1 - ranges[u].0);
                let y = ranges[v].0 + (j as f64 + 0.5) / 32.0 * (ranges[v].1 - ranges[v].0);
                samples.push(at(x, y));
            }
        }
        let n_range = plot::range_of(samples.into_iter());
        let left = k as u32 * (w + 2 * margin) + margin;
        let mut panel = Panel::new(
            &mut img,
            (left, margin, w, h),
            ranges[u],
            ranges[v],
            (false, false),
        );
        panel.shade(n_range, at);
        let line: Vec<(f64, f64)> = pos.iter().map(|p| (p[u], p[v])).collect();
        panel.polyline(&line, plot::PALETTE[0]);
        if let (Some(a), Some(b)) = (line.first(), line.last()) {
            panel.marker(a.0, a.1, plot::PALETTE[2]);
            panel.marker(b.0, b.1, plot::PALETTE[1]);
        }
        let title = format!(
            "slice {} = {:.4}; index shaded {:.5} (dark) – {:.5} (light)",
            names[hidden], mean[hidden], n_range.0, n_range.1
        );
        panel.axes(&Labels {
            title: &title,
            x: &format!("{} (scene units)", names[u]),
            y: &format!("{} (scene units)", names[v]),
        });
        panel.legend(&[
            (plot::PALETTE[0], "ray path"),
            (plot::PALETTE[2], "start"),
            (plot::PALETTE[1], "end"),
        ]);
        legend.push(format!(
            "panel {}: horizontal {} in [{:.6}, {:.6}], vertical {} in [{:.6}, {:.6}], {} = {:.6}, n shaded over [{:.6}, {:.6}]",
            k + 1, names[u], ranges[u].0, ranges[u].1, names[v], ranges[v].0, ranges[v].1, names[hidden], mean[hidden], n_range.0, n_range.1
        ));
    }
    plot::save(&img, path)?;
    Ok(format!("{} (green start, blue end)", legend.join("; ")))
}
