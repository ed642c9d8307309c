//! Curved connections to lights a path cannot hit — point, spot and LED lights and parallel
//! light — from a point in a gradient medium, where a straight shadow ray is not a light
//! path (MitsubaER's approach, Pediredla et al. 2020). Two parts:
//!
//! - **The two-point problem**: which launch direction at the point reaches the light's point
//!   (or leaves the world toward a parallel light) along the curved ray. The direction is
//!   ω(a, b) = normalize(ω₀ + a u + b v) around the straight direction ω₀; the residual is
//!   where the ray crosses the plane through the light perpendicular to ω₀ (for parallel
//!   light: its escape direction's components across the light's), and Newton's method with a
//!   central-difference Jacobian drives it to zero from the straight guess (a = b = 0), with a
//!   halving line search. The Jacobian's marches replay the step lengths of the march they
//!   differ from, so it is the derivative of one discrete flow, not of the adaptive control's
//!   step choices.
//! - **The bundle's spread** at the solution, from the same Jacobian: for a point, the area
//!   J = dA⊥/dΩ the rays leaving the surface point in dΩ cover at the light (d² for straight
//!   rays), so with étendue n² dA dΩ conserved the irradiance is E = I n_x²/(n_L² J); for
//!   parallel light, the solid angle J = dΩ∞/dΩ they fan out to (1 for straight rays), E =
//!   E∞ (n_x/n_∞)²/J.
//!
//! Only the root the straight guess leads to is found: where the medium images a light more
//! than once (the low sun of a mirage seen also in the road), the other images' light is not
//! in the connection.

use super::{Event, Stats, Tracer};
use crate::color::Rgb;
use crate::curve::{
    march_replay_with, march_with, Bounds, MarchLimits, MarchOutcome, RayState, Termination,
};
use crate::ids::MediumId;
use crate::lights::Anchor;
use crate::media::Medium;
use crate::volume::{Participating, Scattering};
use glam::{DVec2, DVec3};

/// A solved connection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Link {
    /// Unit launch direction at the point.
    pub direction: DVec3,
    /// Unit direction of the ray where it reaches the light (away from the point).
    pub arrival: DVec3,
    /// The bundle's spread J: area per solid angle at a point light (scene units²/sr),
    /// solid angle per solid angle for parallel light.
    pub spread: f64,
    /// (n at the point / n at the light's end)².
    pub index_ratio2: f64,
    /// Arclength of the path.
    pub length: f64,
    /// Optical depth ∫ σa ds along it, per channel.
    pub optical_depth: Rgb,
    /// The scattering column ∫d ds along its chords in a heterogeneous scattering medium
    /// ([`crate::volume::Scattering::column`]); its arclength otherwise.
    pub column: f64,
}

impl Link {
    /// Irradiance at the point on a surface facing [`Link::direction`], W/m²: from a point
    /// sending `intensity` (W/sr) along −arrival, or from parallel light of `irradiance`.
    pub fn irradiance(&self, anchor: &Anchor, intensity: Rgb) -> Rgb {
        let kept = (-self.optical_depth).exp() * self.index_ratio2 / self.spread;
        match anchor {
            Anchor::Point(_) => intensity * kept,
            Anchor::Direction { irradiance, .. } => *irradiance * kept,
        }
    }
}

/// What the rays must reach.
#[derive(Clone, Copy)]
enum Goal {
    /// A point `distance` from the start along the straight direction.
    Point { at: DVec3, distance: f64 },
    /// The world's edge, leaving along the straight direction.
    Direction,
}

/// One connection problem: from `from` in `medium`, around the straight direction `chord`
/// with the frame (u, v) across it.
struct Problem<'a> {
    tracer: &'a Tracer<'a>,
    medium: &'a dyn Medium,
    /// What the medium does to light's power (the link's optical depth is summed).
    radiometry: &'a Participating,
    /// How the medium scatters, if it is heterogeneous (the link's column is summed).
    scattering: Option<&'a Scattering>,
    from: DVec3,
    chord: DVec3,
    u: DVec3,
    v: DVec3,
    goal: Goal,
}

/// Where a trial direction's ray ended up.
struct Shot {
    residual: DVec2,
    end: RayState,
    length: f64,
    optical_depth: Rgb,
    column: f64,
    /// The lengths of the march's steps, for the Jacobian's replays.
    lengths: Vec<f64>,
}

/// Newton iterations before giving up.
const ITERATIONS: usize = 12;
/// Central-difference step in (a, b) (radians near the chord). The differenced marches
/// replay the central march's step lengths ([`march_replay_with`]), so the residual is a
/// smooth function of (a, b) and δ trades only the O(δ²) truncation against the rounding of
/// the located end (~1e-12 of the scene, divided by δ): measured on a parallel beam through a
/// layered medium, the irradiance is the same to 1e-9 for δ from 1e-4 to 1e-6 (with adaptive
/// marches differenced instead, δ = 1e-3 was the best compromise, noise near 1e-6).
const DELTA: f64 = 1e-4;

impl Problem<'_> {
    fn direction(&self, ab: DVec2) -> DVec3 {
        (self.chord + ab.x * self.u + ab.y * self.v).normalize()
    }

    /// Where the rays end: the half-space beyond the light's plane, or the world.
    fn limits(&self) -> MarchLimits {
        let max_steps = self.tracer.settings.max_steps;
        match self.goal {
            Goal::Point { at, distance } => MarchLimits {
                length: 8.0 * distance,
                max_steps,
                bounds: Bounds::HalfSpace {
                    point: at,
                    normal: self.chord,
                    reach: 4.0 * distance,
                },
            },
            Goal::Direction => MarchLimits {
                length: 100.0 * self.tracer.world.scale(),
                max_steps,
                bounds: self.tracer.world,
            },
        }
    }

    /// The ray launched along ω(ab), marched through the medium (no surfaces) to the plane of
    /// the light or the world's edge, with the lengths of its steps.
    fn shoot(&self, ab: DVec2, stats: &mut Stats) -> Option<Shot> {
        let settings = &self.tracer.settings;
        let start = RayState::new(self.medium, self.from, self.direction(ab))?;
        let mut lengths = Vec::new();
        let (mut last, mut column, mut depth) = (self.from, 0.0, Rgb::ZERO);
        let out = march_with(
            settings.stepper,
            self.medium,
            settings.control,
            start,
            &self.limits(),
            |_, step| {
                if step.length > 0.0 {
                    lengths.push(step.length);
                    let to = step.state.position;
                    depth += self.radiometry.step_depth(last, to, step.length);
                    let chord = (to - last).length();
                    if let Some(sc) = self.scattering.filter(|_| chord > 0.0) {
                        column += sc.column(last, (to - last) / chord, chord);
                    }
                    last = to;
                }
                std::ops::ControlFlow::Continue(())
            },
        );
        stats.curved_marches += 1;
        stats.curved_steps += out.steps;
        Some(Shot {
            residual: self.residual(&out)?,
            end: out.state,
            length: out.arclength,
            optical_depth: depth,
            column: match self.scattering {
                Some(_) => column,
                None => out.arclength,
            },
            lengths,
        })
    }

    /// The residual of a march that ended at the light's plane or the world's edge.
    fn residual(&self, out: &MarchOutcome) -> Option<DVec2> {
        if out.reason != Termination::LeftBounds {
            return None;
        }
        match self.goal {
            Goal::Point { at, distance } => {
                let d = out.state.position - at;
                // Through the plane, not out of the ball around it.
                if d.dot(self.chord).abs() > 1e-6 * distance {
                    return None;
                }
                Some(DVec2::new(d.dot(self.u), d.dot(self.v)))
            }
            Goal::Direction => {
                let e = out.state.direction;
                if e.dot(self.chord) <= 0.0 {
                    return None;
                }
                Some(DVec2::new(e.dot(self.u), e.dot(self.v)))
            }
        }
    }

    /// ∂residual/∂(a, b) at `shot` (launched at `ab`) by central differences of marches that
    /// replay the shot's step lengths, so that the residual is differenced as a smooth
    /// function of (a, b): columns ∂/∂a, ∂/∂b.
    fn jacobian(&self, ab: DVec2, shot: &Shot, stats: &mut Stats) -> Option<[DVec2; 2]> {
        let limits = self.limits();
        let mut replay = |ab: DVec2| {
            let start = RayState::new(self.medium, self.from, self.direction(ab))?;
            let out = march_replay_with(
                self.tracer.settings.stepper,
                self.medium,
                start,
                &shot.lengths,
                &limits,
            );
            stats.curved_marches += 1;
            stats.curved_steps += out.steps;
            self.residual(&out)
        };
        let mut cols = [DVec2::ZERO; 2];
        for (k, e) in [DVec2::X, DVec2::Y].into_iter().enumerate() {
            let plus = replay(ab + DELTA * e)?;
            let minus = replay(ab - DELTA * e)?;
            cols[k] = (plus - minus) / (2.0 * DELTA);
        }
        Some(cols)
    }

    /// How small the residual must be: 1e-7 of the distance for a point (the march itself
    /// errs by about its tolerance times the path), 1e-8 rad for a direction.
    fn tolerance(&self) -> f64 {
        match self.goal {
            Goal::Point { distance, .. } => 1e-7 * distance,
            Goal::Direction => 1e-8,
        }
    }

    /// Newton's method from the straight guess; the link at the root.
    fn solve(&self, stats: &mut Stats) -> Option<Link> {
        let mut ab = DVec2::ZERO;
        let mut shot = self.shoot(ab, stats)?;
        for _ in 0..ITERATIONS {
            let jac = self.jacobian(ab, &shot, stats)?;
            let det = jac[0].perp_dot(jac[1]);
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            if shot.residual.length() <= self.tolerance() {
                return Some(self.link(ab, &shot, det.abs()));
            }
            // Solve [c0 c1] Δ = −r by Cramer's rule.
            let r = -shot.residual;
            let step = DVec2::new(r.perp_dot(jac[1]), jac[0].perp_dot(r)) / det;
            let mut t = 1.0;
            loop {
                match self.shoot(ab + t * step, stats) {
                    Some(next) if next.residual.length() < shot.residual.length() => {
                        ab += t * step;
                        shot = next;
                        break;
                    }
                    _ if t > 1.0 / 64.0 => t *= 0.5,
                    _ => return None,
                }
            }
        }
        None
    }

    /// The link of the converged direction `ab` with the Jacobian determinant `det`.
    fn link(&self, ab: DVec2, shot: &Shot, det: f64) -> Link {
        let w = self.chord + ab.x * self.u + ab.y * self.v;
        let w3 = w.length().powi(3);
        let arrival = shot.end.direction;
        let spread = match self.goal {
            // dA⊥/dΩ: the plane's area element per (a, b), tilted to the ray, per solid angle.
            Goal::Point { .. } => det * arrival.dot(self.chord).abs() * w3,
            // dΩ∞/dΩ: (e·u, e·v) per (a, b), as solid angle, per solid angle.
            Goal::Direction => det * w3 / arrival.dot(self.chord).abs(),
        };
        let n_from = self.medium.sample(self.from).map_or(1.0, |s| s.n);
        let ratio = n_from / shot.end.index.n;
        Link {
            direction: w / w.length(),
            arrival,
            spread,
            index_ratio2: ratio * ratio,
            length: shot.length,
            optical_depth: shot.optical_depth,
            column: shot.column,
        }
    }
}

/// The curved connection from `from` in gradient medium `medium` to `anchor`, if the solver
/// finds one and no surface (receivers' detectors apart) blocks it. Counts it in `stats`.
pub fn connect(
    tracer: &Tracer,
    from: DVec3,
    medium: MediumId,
    anchor: &Anchor,
    stats: &mut Stats,
) -> Option<Link> {
    let (chord, goal) = match *anchor {
        Anchor::Point(at) => {
            let d = at - from;
            let distance = d.length();
            if distance == 0.0 {
                return None;
            }
            (d / distance, Goal::Point { at, distance })
        }
        Anchor::Direction { toward, .. } => (toward, Goal::Direction),
    };
    let u = chord.any_orthonormal_vector();
    let index = tracer.medium(medium);
    let scattering = tracer.scattering(medium).filter(|sc| sc.is_heterogeneous());
    let problem = Problem {
        tracer,
        medium: &*index,
        radiometry: tracer.participating(medium),
        scattering: scattering.as_deref(),
        from,
        chord,
        u,
        v: chord.cross(u),
        goal,
    };
    let link = problem.solve(stats);
    match link {
        Some(l) if unblocked(tracer, from, medium, &l, stats) => {
            stats.connections.0 += 1;
            Some(l)
        }
        Some(_) => {
            stats.connections.0 += 1;
            None
        }
        None => {
            stats.connections.1 += 1;
            None
        }
    }
}

/// Whether the connecting path meets no surface but detectors before its end.
fn unblocked(
    tracer: &Tracer,
    from: DVec3,
    medium: MediumId,
    link: &Link,
    stats: &mut Stats,
) -> bool {
    let scene = tracer.scene;
    let (mut origin, mut dir, mut travelled) = (from, link.direction, 0.0);
    loop {
        match tracer.next_event(origin, dir, Some(medium), stats) {
            Event::Surface { hit, distance, .. } => {
                if travelled + distance >= link.length * (1.0 - 1e-7) {
                    return true;
                }
                if !scene.surface(hit.prim).is_detector() {
                    return false;
                }
                travelled += distance;
                (origin, dir) = (super::offset(hit.position, hit.incoming), hit.incoming);
            }
            Event::Escaped { .. } | Event::Reached { .. } => return true,
            Event::Lost => return false,
        }
    }
}
