//! The Black Hole Simulator's deflection table (ebvalaim 2015), generalised: when the only non-uniform part of a
//! scene is one spherically symmetric ambient medium seen against the environment (a black
//! hole, a fish-eye or Luneburg ambient) and nothing else is in it, every camera ray is planar
//! — it stays in the plane of its direction and the centre — and where it leaves depends on
//! one number, the angle α between the ray and the direction from the camera to the centre.
//! The table holds the turn δ(α) of the escaping direction (or that α is captured), traced
//! once per render with the curved engine at the scene's tolerance; a pixel costs a lookup
//! and a rotation. Tabulated in α, not in the impact parameter: nearly equal impact parameters
//! around α = 90° are far apart in α (the Black Hole Simulator's (ebvalaim 2015) smeared strip).
//!
//! Nodes: uniform in α over the view's range of angles (a node at least every pixel, so no
//! feature a pixel wide falls between two), then every interval bisected until linear
//! interpolation of δ meets its traced midpoint within the table's tolerance ([`TOLERANCE`],
//! or 0.003 of a pixel for narrower views) — near the capture angle, where δ diverges
//! logarithmically, this packs nodes geometrically, down to a millionth of a pixel — and
//! every interval holding the capture boundary bisected down to [`BOUNDARY`].
//!
//! The table is checked against rays traced directly; a render uses it only when the check
//! finds every ray within a tenth of a pixel and no capture disagreement
//! ([`TableCheck::accepts`]), and traces every ray otherwise, saying so.

use super::{CameraRay, Integrator, Sample};
use crate::camera::{FilmPoint, PrimaryRay};
use crate::color::Rgb;
use crate::polarization::Recorded;
use crate::report::Report;
use crate::transport::{Event, Stats, Tracer};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;
use std::time::Instant;

super::layers!(
    /// The one layer: what escaping rays see.
    TableLayer {
        /// The environment seen along each ray's turn.
        Emitted: radiance "emitted",
    }
);

/// Fewest uniform nodes in α over the view's range before refinement.
const UNIFORM: usize = 1024;
/// Most uniform nodes (a view 2¹⁶ pixels across).
const MAX_UNIFORM: usize = 1 << 16;
/// Largest error of linearly interpolated δ at an interval's midpoint (rad) in wide views:
/// 0.003 of a pixel of a 40° view over 1920 pixels, and 100× the traced turns' own error at
/// the shipped tolerance, so the bisection does not chase that noise. Narrower views use
/// 0.003 of their pixel.
pub const TOLERANCE: f64 = 1e-6;
/// The fewest nodes a table may trace before it is given up.
const MIN_BUDGET: usize = 1 << 15;
/// Tolerance of the table in pixels (see [`TOLERANCE`]).
const PIXEL_TOLERANCE: f64 = 0.003;
/// The largest error the check may find for the table to be used, in pixels.
const ACCEPTED_PIXELS: f64 = 0.1;
/// Width (rad) to which an interval holding the capture boundary is narrowed; no other
/// interval is split below it.
const BOUNDARY: f64 = 1e-12;
/// Pixels traced directly to check the table, per render.
const CHECKED: usize = 256;

/// One traced node: α and the turn δ of the escaping direction (None: captured or lost).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    alpha: f64,
    turn: Option<f64>,
}

/// What the table's check found: rays traced directly against the table.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TableCheck {
    /// Rays compared.
    pub rays: usize,
    /// Largest angle (rad) between the table's direction and the traced one.
    pub max: f64,
    /// Root mean square of those angles (rad).
    pub rms: f64,
    /// Rays the table and the trace disagree on capturing (within [`BOUNDARY`] of it).
    pub disagreements: usize,
    /// The angle of a pixel at the film's centre (rad).
    pub pixel: f64,
}

impl TableCheck {
    /// Whether the table may stand in for tracing: every checked ray within a tenth of a
    /// pixel of its traced direction, and no capture disagreement.
    pub fn accepts(&self) -> bool {
        self.disagreements == 0 && self.max <= ACCEPTED_PIXELS * self.pixel
    }
}

/// The deflection table of a camera before a spherically symmetric ambient medium.
pub struct DeflectionTable<'a> {
    tracer: &'a Tracer<'a>,
    /// Asked during the build whether to stop (an interrupted render).
    stop: &'a (dyn Fn() -> bool + Sync),
    /// The narrowest interval refined where rays escape at both ends (rad): 10⁻⁶ of the
    /// angle between neighbouring pixels at the film's centre. Near the capture angle α_c the
    /// turn diverges as −ln(α − α_c), and linear interpolation over an interval h at distance
    /// x errs by ≈ (h/x)²/8: within [`TOLERANCE`] from x ≈ 350 h = 3.5·10⁻⁴ pixel on, so only
    /// rays closer than that to the shadow's edge are interpolated more coarsely.
    finest: f64,
    /// The angle of a pixel at the film's centre (rad).
    pixel: f64,
    /// Largest error of interpolated δ at an interval's midpoint (rad).
    tolerance: f64,
    /// The range of α the camera's rays span (rad), with a pixel's margin each side.
    range: (f64, f64),
    /// The camera's position.
    eye: DVec3,
    /// Unit vector from the camera toward the centre.
    axis: DVec3,
    /// n² at the camera: environment radiance arriving there.
    scale: f64,
    /// Nodes, α increasing.
    nodes: Vec<Node>,
    /// Most nodes the build may trace: a table costing more rays than the film's pixels is no
    /// gain (at least [`MIN_BUDGET`]). A build that reaches it — the traced turns noisier than
    /// the tolerance, so bisection chases the noise — is given up.
    budget: usize,
    /// Nodes traced so far by the build.
    traced: std::sync::atomic::AtomicUsize,
    /// Seconds the build took.
    pub build_seconds: f64,
    /// The check against direct tracing.
    pub check: TableCheck,
}

impl<'a> DeflectionTable<'a> {
    /// The table for the tracer's scene, or None when the scene is not one it can render
    /// exactly: anything in it besides the ambient medium (a surface, an area light, a
    /// receiver), an ambient medium that is not spherically symmetric, absorbs, scatters or
    /// disperses,
    /// a thin-lens camera, a camera at the centre, or a world sphere off the camera–centre
    /// axis (the problem must be symmetric about that axis). Once `stop` answers true the
    /// build ends early (the render then stops before its first pass).
    pub fn new(tracer: &'a Tracer<'a>, stop: &'a (dyn Fn() -> bool + Sync)) -> Option<Self> {
        let scene = tracer.scene;
        let camera = scene.camera.as_ref()?;
        let ambient = scene.ambient()?;
        let medium = scene.medium_at(ambient);
        let center = medium.symmetry_center()?;
        let no_surfaces = scene.accel.primitives().is_empty();
        if !no_surfaces
            || scene.media().participating(ambient).absorption.is_some()
            || scene.media().scattering(ambient).is_some()
            || scene.media().is_dispersive(ambient)
            || camera.lens.is_some()
            // Parallel rays do not share the eye's symmetry axis.
            || matches!(camera.projection, crate::camera::Projection::Orthographic { .. })
            // Its rays carry no measurement: behind a polarizer, or where the camera measures
            // the Stokes vector, the camera's rays are traced.
            || camera.polarizer.is_some()
            // The table's rays end in the sky: a camera that hides the sky it sees directly
            // has its rays traced.
            || camera.hide_emitters
            || tracer.settings.stokes
            || tracer.camera_medium != Some(ambient)
        {
            return None;
        }
        let to_center = center - camera.position;
        let axis = to_center.try_normalize()?;
        if let crate::curve::Bounds::Ball { center: c, .. } = tracer.world {
            let off = (c - camera.position).cross(axis).length();
            if off > 1e-9 * to_center.length().max(1.0) {
                return None;
            }
        }
        let n = tracer.index(Some(ambient), camera.position)?;
        let start = Instant::now();
        let pixel = camera.pixel_angle();
        let (lo, hi) = camera.angles_to(axis);
        let mut table = Self {
            tracer,
            stop,
            finest: 1e-6 * pixel,
            pixel,
            tolerance: TOLERANCE.min(PIXEL_TOLERANCE * pixel),
            range: ((lo - pixel).max(0.0), (hi + pixel).min(PI)),
            eye: camera.position,
            axis,
            scale: n * n,
            nodes: Vec::new(),
            budget: (camera.window().width as usize * camera.window().height as usize)
                .max(MIN_BUDGET),
            traced: Default::default(),
            build_seconds: 0.0,
            check: TableCheck::default(),
        };
        table.build();
        table.build_seconds = start.elapsed().as_secs_f64();
        if !table.over_budget() {
            table.check = table.verify();
        }
        Some(table)
    }

    /// Whether the build traced more nodes than its budget (and was given up).
    fn over_budget(&self) -> bool {
        self.traced.load(std::sync::atomic::Ordering::Relaxed) > self.budget
    }

    /// Whether a render may use the table in place of tracing: built within its budget, and
    /// its check accepts it ([`TableCheck::accepts`]).
    pub fn usable(&self) -> bool {
        !self.over_budget() && self.check.accepts()
    }

    /// Nodes in the table.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the table is empty (never, once built).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// A unit vector perpendicular to the axis (the plane of the table's traces).
    fn across(&self) -> DVec3 {
        self.axis.any_orthonormal_vector()
    }

    /// The direction at angle `alpha` from the axis, in the plane of `across`.
    fn direction(&self, alpha: f64, across: DVec3) -> DVec3 {
        alpha.cos() * self.axis + alpha.sin() * across
    }

    /// Traces the ray at `alpha`: its node.
    fn trace(&self, alpha: f64, stats: &mut Stats) -> Node {
        self.traced
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let across = self.across();
        let dir = self.direction(alpha, across);
        let medium = self.tracer.camera_medium;
        let turn = match self.tracer.next_event(self.eye, dir, medium, stats) {
            Event::Escaped { direction, .. } => {
                let out = direction.dot(across).atan2(direction.dot(self.axis));
                Some(out - alpha)
            }
            Event::Surface { .. } | Event::Reached { .. } | Event::Lost => None,
        };
        Node { alpha, turn }
    }

    /// Builds the nodes: uniform over the view's range (at least one a pixel), then refined
    /// in parallel per uniform interval.
    fn build(&mut self) {
        use rayon::prelude::*;
        let (lo, hi) = self.range;
        let pixels = ((hi - lo) / self.pixel).ceil();
        let count = (pixels as usize).clamp(UNIFORM, MAX_UNIFORM);
        let uniform: Vec<Node> = (0..=count)
            .into_par_iter()
            .map(|i| {
                let alpha = lo + (hi - lo) * i as f64 / count as f64;
                self.trace(alpha.min(hi), &mut Stats::default())
            })
            .collect();
        let mut nodes: Vec<Node> = uniform
            .par_windows(2)
            .flat_map_iter(|w| std::iter::once(w[0]).chain(self.refine(w[0], w[1], true)))
            .collect();
        nodes.push(*uniform.last().expect("nodes"));
        // Turns are continuous in α where rays escape: unwrap them across nodes (near the
        // capture angle a ray may wind around the centre more than once).
        let mut last: Option<f64> = None;
        for node in &mut nodes {
            if let (Some(t), Some(prev)) = (node.turn.as_mut(), last) {
                *t += (2.0 * PI) * ((prev - *t) / (2.0 * PI)).round();
            }
            last = node.turn.or(last);
        }
        self.nodes = nodes;
    }

    /// The nodes strictly between `a` and `b` (α increasing), in order; the two halves of a
    /// split interval are refined in parallel.
    fn refine(&self, a: Node, b: Node, first: bool) -> Vec<Node> {
        let width = b.alpha - a.alpha;
        let boundary = a.turn.is_some() != b.turn.is_some();
        let floor = if boundary { BOUNDARY } else { self.finest };
        if width <= floor || (self.stop)() || self.over_budget() {
            return Vec::new();
        }
        let m = self.trace(0.5 * (a.alpha + b.alpha), &mut Stats::default());
        let good = match (a.turn, b.turn, m.turn) {
            (Some(ta), Some(tb), Some(tm)) => {
                let tb = tb + (2.0 * PI) * ((ta - tb) / (2.0 * PI)).round();
                let tm = tm + (2.0 * PI) * ((ta - tm) / (2.0 * PI)).round();
                (0.5 * (ta + tb) - tm).abs() <= self.tolerance
            }
            (None, None, None) => true,
            _ => false,
        };
        if good && !first {
            return vec![m];
        }
        let (mut left, right) =
            rayon::join(|| self.refine(a, m, false), || self.refine(m, b, false));
        left.push(m);
        left.extend(right);
        left
    }

    /// The turn at `alpha` (None: captured), interpolated linearly between nodes; inside an
    /// interval narrowed to the capture boundary, the nearer node decides.
    fn turn(&self, alpha: f64) -> Option<f64> {
        let i = self
            .nodes
            .partition_point(|n| n.alpha <= alpha)
            .clamp(1, self.nodes.len() - 1);
        let (a, b) = (self.nodes[i - 1], self.nodes[i]);
        match (a.turn, b.turn) {
            (Some(ta), Some(tb)) => {
                let t = ((alpha - a.alpha) / (b.alpha - a.alpha)).clamp(0.0, 1.0);
                Some(ta + t * (tb - ta))
            }
            _ if alpha - a.alpha < b.alpha - alpha => a.turn,
            _ => b.turn,
        }
    }

    /// Where the camera ray along unit `dir` leaves (None: captured).
    pub fn escape_direction(&self, dir: DVec3) -> Option<DVec3> {
        let along = dir.dot(self.axis);
        let alpha = crate::math::angle_between(dir, self.axis);
        let turn = self.turn(alpha)?;
        let across = (dir - along * self.axis)
            .try_normalize()
            .unwrap_or_else(|| self.across());
        Some(self.direction(alpha + turn, across))
    }

    /// Traces `CHECKED` directions spread over the camera's field directly and compares.
    fn verify(&self) -> TableCheck {
        use rayon::prelude::*;
        let Some(camera) = self.tracer.scene.camera.as_ref() else {
            return TableCheck::default();
        };
        let side = (CHECKED as f64).sqrt().ceil() as u32;
        let angles: Vec<Option<f64>> = (0..side * side)
            .into_par_iter()
            .map(|k| {
                // Pixel centres on a side × side lattice over the film, off its symmetry lines.
                let px = ((k % side) as f64 + 0.37) / side as f64 * camera.width as f64;
                let py = ((k / side) as f64 + 0.61) / side as f64 * camera.height as f64;
                let PrimaryRay {
                    origin,
                    direction: dir,
                } = camera.ray(FilmPoint {
                    px: px as u32,
                    py: py as u32,
                    u: px.fract(),
                    v: py.fract(),
                    lens: DVec2::splat(0.5),
                });
                let table = self.escape_direction(dir);
                let medium = self.tracer.camera_medium;
                let traced =
                    match self
                        .tracer
                        .next_event(origin, dir, medium, &mut Stats::default())
                    {
                        Event::Escaped { direction, .. } => Some(direction),
                        _ => None,
                    };
                match (table, traced) {
                    (Some(a), Some(b)) => Some(crate::math::angle_between(a, b)),
                    (None, None) => Some(0.0),
                    _ => None,
                }
            })
            .collect();
        let errors: Vec<f64> = angles.iter().flatten().copied().collect();
        TableCheck {
            rays: angles.len(),
            max: errors.iter().copied().fold(0.0, f64::max),
            rms: (errors.iter().map(|e| e * e).sum::<f64>() / errors.len().max(1) as f64).sqrt(),
            disagreements: angles.len() - errors.len(),
            pixel: self.pixel,
        }
    }

    /// One line for the render's report.
    pub fn summary(&self) -> String {
        let c = self.check;
        if self.over_budget() {
            return format!(
                "deflection table: given up after {} nodes over {:.3e}..{:.3e} rad in {:.2} s \
                 (the traced turns vary more than its tolerance of {:.1e} rad between them)",
                self.budget, self.range.0, self.range.1, self.build_seconds, self.tolerance
            );
        }
        format!(
            "deflection table: {} nodes over {:.3e}..{:.3e} rad built in {:.2} s; checked on {} directions traced directly: max angle error {:.2e} rad ({:.1e} pixel), rms {:.2e} rad, {} capture disagreement(s)",
            self.nodes.len(),
            self.range.0,
            self.range.1,
            self.build_seconds,
            c.rays,
            c.max,
            c.max / c.pixel,
            c.rms,
            c.disagreements
        )
    }
}

impl Integrator for DeflectionTable<'_> {
    type Pass = ();
    type Pixel = ();
    type Layer = TableLayer;

    fn begin_pass(
        &self,
        _index: u32,
        report: &mut Report,
        _stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<()> {
        if report.notes.is_empty() {
            report.notes.push(self.summary());
        }
        Some(())
    }

    fn sample(&self, _pass: &(), _pixel: &mut (), ray: CameraRay, sample: &mut Sample<TableLayer>) {
        let radiance = match (
            self.escape_direction(ray.direction),
            self.tracer.scene.environment.as_ref(),
        ) {
            (Some(d), Some(env)) => env.radiance(d) * self.scale,
            _ => Rgb::ZERO,
        };
        sample.record(TableLayer::Emitted, Recorded::radiance(radiance));
    }
}
