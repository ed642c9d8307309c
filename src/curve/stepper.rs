//! Steppers: one step of a ray through a medium, behind one small interface.

use super::hermite::Path;
use super::linearize::{CircleArc, GeodesicRay};
use super::segment::{deviation_bound, ArcHull, ArcPoint, CurvedSegment};
use super::state::RayState;
use crate::media::{IndexSample, Medium};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The result of one step.
#[derive(Clone, Copy, Debug)]
pub struct Step {
    /// The state at the end of the step.
    pub state: RayState,
    /// Arclength actually advanced (RK4 in Sharma's form advances in optical time, so this
    /// differs from the requested length by O(h⁵)).
    pub length: f64,
    /// Optical path ∫ n ds of the step, to the stepper's order.
    pub optical_path: f64,
    /// The path between the ends where the stepper knows it exactly (a chain of exact arcs,
    /// a constant-curvature medium's circle); `None` where only the ends are known.
    pub path: Option<ExactPath>,
}

/// A step's path between its ends, known exactly: surfaces are met on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ExactPath {
    /// The arc chain's two arcs ([`ArcChain`]).
    Arcs(ArcPath),
    /// The ray's own circle ([`Linearize`]).
    Circle(CircleArc),
}

impl ExactPath {
    /// A capsule holding the whole path of a step from `start` to `end`, `length` long.
    pub fn hull(&self, start: &RayState, end: &RayState, length: f64) -> ArcHull {
        match self {
            ExactPath::Arcs(arcs) => arcs.hull(start, end, length),
            ExactPath::Circle(circle) => ArcHull {
                a: start.position,
                b: end.position,
                deviation: deviation_bound(circle.curvature.length(), length),
            },
        }
    }

    /// The point at arclength `along` of a step from `start` of `length`.
    pub fn at(&self, start: &RayState, length: f64, along: f64) -> ArcPoint {
        match self {
            ExactPath::Arcs(arcs) => {
                let half = 0.5 * length;
                let [first, second] = arcs.arcs(start);
                match along <= half {
                    true => first.at(along),
                    false => second.at(along - half),
                }
            }
            ExactPath::Circle(circle) => circle.at(along),
        }
    }
}

/// A step's path as two exact arcs of half its length each: from the step's start under
/// `forces[0]`, then from `joint` under `forces[1]` (kept small: a step is copied often).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPath {
    /// Where the first arc ends and the second starts.
    pub joint: ArcPoint,
    /// F = ∇ln n frozen on each arc (1/length).
    pub forces: [DVec3; 2],
}

impl ArcPath {
    /// The two arcs, for a step that started at `start`.
    pub fn arcs(&self, start: &RayState) -> [CurvedSegment; 2] {
        [
            CurvedSegment::new(start.position, start.direction, self.forces[0]),
            CurvedSegment::new(self.joint.position, self.joint.direction, self.forces[1]),
        ]
    }

    /// A capsule holding the whole path of a step from `start` to `end`, `length` long: the
    /// chain is C¹ with curvature at most the larger |F|, so one arc's bound applies to it.
    pub fn hull(&self, start: &RayState, end: &RayState, length: f64) -> ArcHull {
        let curvature = self.forces[0].length().max(self.forces[1].length());
        ArcHull {
            a: start.position,
            b: end.position,
            deviation: deviation_bound(curvature, length),
        }
    }
}

/// How far apart two solutions of one step are, as a position error: |Δx| + h|Δt̂|, the
/// distance between the ends plus how far the difference of directions moves the ray over
/// the next step of the same length. Controlling only |Δx| lets direction errors, which
/// every later position inherits, go unchecked.
pub fn step_discrepancy(a: &RayState, b: &impl EndPoint, h: f64) -> f64 {
    (a.position - b.position()).length() + h * (a.direction - b.direction()).length()
}

/// Anything with a position and a direction.
pub trait EndPoint {
    /// Position.
    fn position(&self) -> DVec3;
    /// Unit direction.
    fn direction(&self) -> DVec3;
}

impl EndPoint for RayState {
    fn position(&self) -> DVec3 {
        self.position
    }
    fn direction(&self) -> DVec3 {
        self.direction
    }
}

impl From<RayState> for ArcPoint {
    fn from(s: RayState) -> Self {
        ArcPoint {
            position: s.position,
            direction: s.direction,
        }
    }
}

impl EndPoint for ArcPoint {
    fn position(&self) -> DVec3 {
        self.position
    }
    fn direction(&self) -> DVec3 {
        self.direction
    }
}

/// A step together with an estimate of its local position error (length units).
#[derive(Clone, Copy, Debug)]
pub struct EstimatedStep {
    /// The step to accept if the error is small enough.
    pub step: Step,
    /// Estimated position error of the step.
    pub error: f64,
}

/// One method of advancing a ray along the ray equation d/ds(n dx/ds) = ∇n.
pub trait Stepper: Sync {
    /// Advances `state` by arclength `h` > 0. `None` when the path reached a point where the
    /// medium captures rays.
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step>;

    /// Global order p of the method: the position error after a fixed length scales as hᵖ.
    fn order(&self) -> u32;

    /// Order q of the error estimate of [`Self::estimated_step`]: the estimate per unit length
    /// scales as h^q, which the step control inverts. Default: [`Self::order`].
    fn estimate_order(&self) -> u32 {
        self.order()
    }

    /// The longest step adaptive control takes from `p` along `dir`: the medium's own hint
    /// ([`Medium::step_hint`]), so that no feature of the profile is stepped over.
    fn step_hint<M: Medium + ?Sized>(&self, medium: &M, p: DVec3, dir: DVec3) -> f64 {
        medium.step_hint(p, dir)
    }

    /// A step with a local error estimate. The default is [`step_doubling`] in arclength.
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        let step = |s: &RayState, size| self.step(medium, s, size);
        let full = |s: &RayState, size| step(s, size).map(|f| f.state.into());
        step_doubling(self.order(), state, h, h, full, step)
    }
}

/// Step doubling (Richardson): one step of `size` (`full`: only its end is needed) against
/// two of `size`/2 (`step`), whose result is returned, with error =
/// [`step_discrepancy`]/(2ᵖ − 1) for a method of order p. `size` is in the stepper's own
/// parameter (arclength, or optical time for RK4); `h` is the arclength.
pub fn step_doubling(
    order: u32,
    state: &RayState,
    size: f64,
    h: f64,
    full: impl Fn(&RayState, f64) -> Option<ArcPoint>,
    step: impl Fn(&RayState, f64) -> Option<Step>,
) -> Option<EstimatedStep> {
    let full = full(state, size)?;
    let half = step(state, 0.5 * size)?;
    let second = step(&half.state, 0.5 * size)?;
    Some(EstimatedStep {
        step: Step {
            state: second.state,
            length: half.length + second.length,
            optical_path: half.optical_path + second.optical_path,
            path: None,
        },
        error: step_discrepancy(&second.state, &full, h) / f64::from((1u32 << order) - 1),
    })
}

/// The transformation method where it is exact: in a medium whose rays have a closed form
/// ([`Medium::constant_curvature`]: the fish-eye, the hyperbolic medium) a step follows the ray's circle
/// ([`CircleArc`], from the curvature vector at its start) to the requested arclength and takes
/// its optical path from the angle the geodesic turns ([`crate::curve::GeodesicRay`]): no
/// error, so adaptive control lengthens its steps to their longest ([`Stepper::step_hint`]),
/// and surfaces are met on the circle itself ([`ExactPath::Circle`]). In any other medium it
/// is [`Rkn64`].
#[derive(Clone, Copy, Debug, Default)]
pub struct Linearize;

impl Linearize {
    /// The exact step, in a medium with a closed form (None: it has none; Some(None): the
    /// step reached a point where the medium captures rays).
    fn exact<M: Medium + ?Sized>(medium: &M, state: &RayState, h: f64) -> Option<Option<Step>> {
        let ray = GeodesicRay::of(
            medium.constant_curvature()?,
            state.position,
            state.direction,
        )?;
        let circle = CircleArc::new(state.position, state.direction, state.index.log_gradient());
        let end = circle.at(h);
        let Some(index) = medium.sample(end.position) else {
            return Some(None);
        };
        // The angle turned, on the branch nearest the trapezoid estimate ∫n ds / (n0 R/2)
        // (the fish-eye's angle is known modulo 2π; a step turns far less than π from it).
        let per_angle = ray.optical_path(1.0);
        let estimate = 0.5 * h * (state.index.n + index.n) / per_angle;
        let theta = ray.theta_of(end.position, estimate);
        Some(Some(Step {
            state: RayState {
                position: end.position,
                direction: end.direction,
                index,
            },
            length: h,
            optical_path: ray.optical_path(theta),
            path: Some(ExactPath::Circle(circle)),
        }))
    }
}

impl Stepper for Linearize {
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        match Self::exact(medium, state, h) {
            Some(step) => step,
            None => Rkn64.step(medium, state, h),
        }
    }

    fn order(&self) -> u32 {
        Rkn64.order()
    }

    /// Where the ray has a closed form its steps have no error, so they are as long as the
    /// closed form allows ([`Medium::exact_reach`]: a fish-eye ray turns half its great circle,
    /// its x-space circle up to a right angle) or the medium's hint, whichever is longer.
    fn step_hint<M: Medium + ?Sized>(&self, medium: &M, p: DVec3, dir: DVec3) -> f64 {
        let hint = medium.step_hint(p, dir);
        medium.exact_reach().map_or(hint, |reach| hint.max(reach))
    }

    fn estimate_order(&self) -> u32 {
        Rkn64.estimate_order()
    }

    /// The exact step with an error of 0, or [`Rkn64`]'s estimated step.
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        match Self::exact(medium, state, h) {
            Some(step) => step.map(|step| EstimatedStep { step, error: 0.0 }),
            None => Rkn64.estimated_step(medium, state, h),
        }
    }
}

/// Tessendorf's exact arcs (Tessendorf 2022, §2–3) chained into a fourth-order method: the
/// commutator-free composition of Celledoni, Marthinsen & Owren (2003). An arc is
/// the exact flow of the ray equation with F = ∇ln n frozen; a step of length h samples F at
/// three points reached by arcs and takes two arcs of h/2 under two weighted means of the four
/// F's (in that order: swapped, the method is second order). The path is a chain of exact
/// arcs — C¹ at the joints, |t̂| = 1 exactly, exact where ∇ln n is constant (the exponential
/// medium) — so surfaces are tested on the arcs themselves ([`Step::path`]).
///
/// Along a frozen arc ln n grows by L(s) = F·(x(s) − x0) and n = n0 e^L, so the optical path
/// is in closed form on each arc ([`CurvedSegment::relative_optical_path`]); the chain is the
/// same composition applied to (x, t̂, ln n, ∫ n ds), whose frozen fields are also linear in F,
/// so the optical path is fourth order too.
///
/// Embedded estimate: the arc of length h under F at the first half-arc's end, which the step
/// samples anyway — the midpoint-force arc, second order. Its discrepancy from the chain
/// (position, direction and optical path) is the chain's error estimate: a (4, 2) pair.
#[derive(Clone, Copy, Debug, Default)]
pub struct ArcChain;

impl ArcChain {
    /// The step and the midpoint-force arc of length h (the embedded solution, evaluated
    /// only when an estimate is wanted).
    fn step_and_embedded<M: Medium + ?Sized>(
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<(Step, CurvedSegment)> {
        let half = 0.5 * h;
        let (x, t) = (state.position, state.direction);
        let f1 = state.index.log_gradient();
        let p2 = CurvedSegment::new(x, t, f1).at(half);
        let f2 = medium.sample(p2.position)?.log_gradient();
        let midpoint_arc = CurvedSegment::new(x, t, f2);
        let f3 = medium
            .sample(midpoint_arc.at(half).position)?
            .log_gradient();
        let x4 = CurvedSegment::new(p2.position, p2.direction, 2.0 * f3 - f1).at(half);
        let f4 = medium.sample(x4.position)?.log_gradient();
        let fb = 2.0 * (f1 / 4.0 + f2 / 6.0 + f3 / 6.0 - f4 / 12.0);
        let fa = 2.0 * (-f1 / 12.0 + f2 / 6.0 + f3 / 6.0 + f4 / 4.0);
        let first = CurvedSegment::new(x, t, fb);
        let pm = first.at(half);
        let second = CurvedSegment::new(pm.position, pm.direction, fa);
        let end = second.at(half);
        let optical_path = state.index.n
            * (first.relative_optical_path(half)
                + first.log_index_gain(half).exp() * second.relative_optical_path(half));
        let step = Step {
            state: RayState {
                position: end.position,
                direction: end.direction,
                index: medium.sample(end.position)?,
            },
            length: h,
            optical_path,
            path: Some(ExactPath::Arcs(ArcPath {
                joint: pm,
                forces: [fb, fa],
            })),
        };
        Some((step, midpoint_arc))
    }
}

impl Stepper for ArcChain {
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        Self::step_and_embedded(medium, state, h).map(|(step, _)| step)
    }

    fn order(&self) -> u32 {
        4
    }

    /// The (4, 2) pair's estimate is the second-order arc's error, O(h³): the step is sized
    /// for it, and the chain's own error is far smaller (local extrapolation).
    fn estimate_order(&self) -> u32 {
        2
    }

    /// Error estimate: the [`step_discrepancy`] between the chain and the midpoint-force arc,
    /// plus their optical paths' difference over n (a length), so the optical path is
    /// controlled where the position is not (a ray along a radius of a Luneburg lens is
    /// straight, but n varies along it).
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        let (step, midpoint_arc) = Self::step_and_embedded(medium, state, h)?;
        let embedded_path = state.index.n * midpoint_arc.relative_optical_path(h);
        Some(EstimatedStep {
            step,
            error: step_discrepancy(&step.state, &midpoint_arc.at(h), h)
                + (step.optical_path - embedded_path).abs() / state.index.n,
        })
    }
}

/// Classical RK4 for the ray equation in Sharma's form (Appl. Opt. 21 (1982) 984):
/// T = n dx/ds, optical time dt = ds/n, D = n∇n, d²x/dt² = D. With Δt:
/// A = Δt D(x), B = Δt D(x + Δt T/2 + Δt A/8), C = Δt D(x + Δt T + Δt B/2),
/// x' = x + Δt (T + (A + 2B)/6), T' = T + (A + 4B + C)/6. Fourth order.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rk4Sharma;

impl Rk4Sharma {
    /// One step of optical time `dt` (= ∫ds/n).
    fn optical_step<M: Medium + ?Sized>(medium: &M, state: &RayState, dt: f64) -> Option<Step> {
        let (end, length, optical_path) = Self::stages(medium, state, dt)?;
        Some(Step {
            state: RayState {
                position: end.position,
                direction: end.direction,
                index: medium.sample(end.position)?,
            },
            length,
            optical_path,
            path: None,
        })
    }

    /// The stages of one step of optical time `dt`: its end (position, direction; not yet
    /// sampled), arclength and optical path.
    fn stages<M: Medium + ?Sized>(
        medium: &M,
        state: &RayState,
        dt: f64,
    ) -> Option<(ArcPoint, f64, f64)> {
        let x = state.position;
        let n0 = state.index.n;
        let t_vec = n0 * state.direction;
        let a = dt * n0 * state.index.grad;
        let sb = medium.sample(x + dt * (0.5 * t_vec + 0.125 * a))?;
        let b = dt * sb.n * sb.grad;
        let sc = medium.sample(x + dt * (t_vec + 0.5 * b))?;
        let c = dt * sc.n * sc.grad;
        let end = ArcPoint {
            position: x + dt * (t_vec + (a + 2.0 * b) / 6.0),
            direction: (t_vec + (a + 4.0 * b + c) / 6.0).normalize(),
        };
        // Arclength ∫ n dt and optical path ∫ n² dt with the velocity update's weights at the
        // stage points: a quadrature of a function of position along the path is another
        // velocity component of an augmented x″ = f(x) that does not feed back, so the method
        // integrates it to its own (fourth) order.
        let (na, nb, nc) = (n0, sb.n, sc.n);
        let length = dt * (na + 4.0 * nb + nc) / 6.0;
        let optical_path = dt * (na * na + 4.0 * nb * nb + nc * nc) / 6.0;
        Some((end, length, optical_path))
    }
}

impl Stepper for Rk4Sharma {
    /// A step of optical time h/n(x0): arclength ≈ h.
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        Self::optical_step(medium, state, h / state.index.n)
    }

    fn order(&self) -> u32 {
        4
    }

    /// Step doubling at equal optical time (halving the arclength instead would compare two
    /// different optical times and measure the parametrisation, not the error).
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        let dt = h / state.index.n;
        let full = |s: &RayState, size| Self::stages(medium, s, size).map(|(end, ..)| end);
        let step = |s: &RayState, size| Self::optical_step(medium, s, size);
        step_doubling(4, state, dt, h, full, step)
    }
}

/// The coefficients of an embedded, first-same-as-last Runge–Kutta–Nyström pair for
/// x″ = f(x): stage i sits at x + Δt (c_i v + Δt Σ_j a_ij f_j); the last stage is the step's
/// end (c = 1, its row the high-order position weights), so its sample starts the next step.
#[derive(Clone, Copy, Debug)]
pub struct RknTableau<const S: usize> {
    /// Nodes.
    pub c: [f64; S],
    /// Stage matrix; row S − 1 is the high-order position weights.
    pub a: [[f64; S]; S],
    /// High-order velocity weights.
    pub b_velocity: [f64; S],
    /// Low-order position weights.
    pub b_low: [f64; S],
    /// Low-order velocity weights.
    pub b_low_velocity: [f64; S],
    /// Order of the propagated solution.
    pub order: u32,
    /// Order of the embedded one.
    pub low_order: u32,
}

/// RKN6(4)6FM of Dormand, El-Mikkawy & Prince (IMA J. Numer. Anal. 7 (1987) 235), R = √8581:
/// six stages, five new samples a step, sixth order with a fourth-order estimate. The values
/// are the closed forms evaluated in 30-digit arithmetic; their order conditions (quadrature
/// and Σ b′ a c conditions of both solutions) were checked there, and the measured orders are
/// pinned in `tests/validation.rs`.
pub const RKN64: RknTableau<6> = RknTableau {
    c: [
        0.0,
        0.12929590313670442,
        0.25859180627340883,
        0.67029708261548,
        0.9,
        1.0,
    ],
    a: [
        [0.0; 6],
        [0.008358715283968025, 0.0, 0.0, 0.0, 0.0, 0.0],
        [
            0.011144953711957367,
            0.022289907423914734,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.1454747428010918,
            -0.22986064052264746,
            0.3090349872029675,
            0.0,
            0.0,
            0.0,
        ],
        [
            -0.20766826295078994,
            0.6863667842925143,
            -0.19954927787234925,
            0.12585075653062489,
            0.0,
            0.0,
        ],
        [
            0.07811016144349478,
            0.0,
            0.2882917411897668,
            0.12242553717457041,
            0.011172560192168035,
            0.0,
        ],
    ],
    b_velocity: [
        0.07811016144349478,
        0.0,
        0.3888434787059826,
        0.3713207579288423,
        0.11172560192168035,
        0.05,
    ],
    b_low: [
        1.0588592603704183,
        -2.406751371924452,
        1.8478921115540339,
        0.0,
        0.0,
        0.0,
    ],
    b_low_velocity: [
        0.054605887939221276,
        0.0,
        0.46126678590362685,
        0.19588085947931266,
        0.38824646667783924,
        -0.1,
    ],
    order: 6,
    low_order: 4,
};

/// The embedded Runge–Kutta–Nyström pair [`RKN64`] for the ray equation in Sharma's form x″ = D(x) = n∇n
/// in optical time (dt = ds/n, T = dx/dt, |T| = n): a pair made for a second-order equation
/// whose right side does not depend on the velocity. The last stage is the step's end (first
/// same as last), so an attempt costs five medium samples (RK4 with step doubling: eight).
///
/// Arclength ∫ n dt and optical path ∫ n² dt use the velocity weights at the stages: a
/// quadrature along the path is one more velocity component of an augmented x″ = f(x) that
/// does not feed back, so it is integrated to the method's order; the low-order weights give
/// its error, which is controlled with the position's.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rkn64;

impl Rkn64 {
    /// One step of optical time `dt` from `state`: the high-order step and the error estimate
    /// (|Δx| + h|Δt̂| + |Δ optical path|/n between the two solutions, a length).
    fn optical_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        dt: f64,
    ) -> Option<EstimatedStep> {
        // The tableau as a constant, so its zeros and weights fold into the code.
        const S: usize = 6;
        let tab = &RKN64;
        let x = state.position;
        let t_vec = state.index.n * state.direction;
        let mut samples = [state.index; S];
        let mut g = [DVec3::ZERO; S];
        g[0] = state.index.n * state.index.grad;
        for i in 1..S {
            let pull = (0..i).fold(DVec3::ZERO, |acc, j| acc + tab.a[i][j] * g[j]);
            samples[i] = medium.sample(x + dt * (tab.c[i] * t_vec + dt * pull))?;
            g[i] = samples[i].n * samples[i].grad;
        }
        // One pass over the stages for both solutions' positions, velocities, and the
        // arclength and optical-path quadratures.
        let (mut pull, mut kick, mut pull_low, mut kick_low) =
            (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        let (mut length, mut optical_path, mut low_path) = (0.0, 0.0, 0.0);
        for i in 0..S {
            let n = samples[i].n;
            pull += tab.a[S - 1][i] * g[i];
            kick += tab.b_velocity[i] * g[i];
            pull_low += tab.b_low[i] * g[i];
            kick_low += tab.b_low_velocity[i] * g[i];
            length += tab.b_velocity[i] * n;
            optical_path += tab.b_velocity[i] * n * n;
            low_path += tab.b_low_velocity[i] * n * n;
        }
        let (length, optical_path, low_path) = (dt * length, dt * optical_path, dt * low_path);
        let position = x + dt * (t_vec + dt * pull);
        let t_new = t_vec + dt * kick;
        let low = ArcPoint {
            position: x + dt * (t_vec + dt * pull_low),
            direction: (t_vec + dt * kick_low).normalize(),
        };
        let step = Step {
            state: RayState {
                position,
                direction: t_new.normalize(),
                index: samples[S - 1],
            },
            length,
            optical_path,
            path: None,
        };
        Some(EstimatedStep {
            step,
            error: step_discrepancy(&step.state, &low, length)
                + (optical_path - low_path).abs() / state.index.n,
        })
    }
}

impl Stepper for Rkn64 {
    /// A step of optical time h/n(x0): arclength ≈ h.
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        self.optical_step(medium, state, h / state.index.n)
            .map(|e| e.step)
    }

    fn order(&self) -> u32 {
        RKN64.order
    }

    /// The low-order solution's local error is O(h^(q+1)): per unit length O(h^q).
    fn estimate_order(&self) -> u32 {
        RKN64.low_order
    }

    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        self.optical_step(medium, state, h / state.index.n)
    }
}

/// Iterative Snell steps (the CS 184 nonlinear path tracer): a straight step of length h, then the direction is
/// refracted at a virtual interface normal to ∇n (averaged over the step's ends) from n(x0)
/// to n(x1), conserving the tangential part of n t̂; total internal reflection mirrors it.
/// This is the ray in a medium of thin homogeneous layers normal to ∇n.
///
/// Known limit of the method (measured in `tests/validation.rs`): a ray exactly at a turning
/// point (t̂ ⊥ ∇n, e.g. launched parallel to a fiber's axis away from the axis) sees no index
/// change over a straight step, so it is never bent, as a ray running inside one layer of a
/// layered medium is not. `grinlight trace` warns when a Snell trace starts so.
#[derive(Clone, Copy, Debug, Default)]
pub struct SnellSteps;

impl SnellSteps {
    /// Refracts unit `t` from index `n0` to `n1` across a plane with unit normal `g`.
    fn refract(t: DVec3, g: DVec3, n0: f64, n1: f64) -> DVec3 {
        let cos_i = t.dot(g);
        let tangential = (t - cos_i * g) * (n0 / n1);
        let t2 = tangential.length_squared();
        if t2 >= 1.0 {
            return t - 2.0 * cos_i * g;
        }
        (tangential + cos_i.signum() * (1.0 - t2).sqrt() * g).normalize()
    }
}

impl Stepper for SnellSteps {
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        let position = state.position + h * state.direction;
        let index = medium.sample(position)?;
        let direction = match (state.index.grad + index.grad).try_normalize() {
            Some(g) => Self::refract(state.direction, g, state.index.n, index.n),
            None => state.direction,
        };
        // The straight step's own optical path: the trapezoid rule with its end correction
        // h²/12 (n′(0) − n′(h)), n′ = ∇n·t̂ along the step (fourth order along the segment,
        // so a ray whose direction never changes — along a Luneburg lens' axis — still gets
        // its optical path right).
        let rate = |s: &IndexSample| s.grad.dot(state.direction);
        let optical_path = 0.5 * (state.index.n + index.n) * h
            + h * h / 12.0 * (rate(&state.index) - rate(&index));
        Some(Step {
            optical_path,
            state: RayState {
                position,
                direction,
                index,
            },
            length: h,
            path: None,
        })
    }

    fn order(&self) -> u32 {
        1
    }
}

/// The steppers by name, for the command line and studies: `arc`, `rk4`, `rkn`, `snell`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum StepperKind {
    /// [`ArcChain`].
    Arc,
    /// [`Rk4Sharma`].
    Rk4,
    /// [`Rkn64`].
    Rkn,
    /// [`SnellSteps`].
    Snell,
    /// [`Linearize`].
    Linearize,
}

impl StepperKind {
    /// All steppers.
    pub const ALL: [StepperKind; 5] = [
        StepperKind::Arc,
        StepperKind::Rk4,
        StepperKind::Rkn,
        StepperKind::Snell,
        StepperKind::Linearize,
    ];

    /// The iterative steppers, which work in every medium (`linearize` is one of them where
    /// a medium has no closed form).
    pub const ITERATIVE: [StepperKind; 4] = [
        StepperKind::Arc,
        StepperKind::Rk4,
        StepperKind::Rkn,
        StepperKind::Snell,
    ];

    /// The stepper used when none is given: the exact circles where a medium has them (they
    /// win `examples/linearize_study`: no error, a fifth of RKN's time per ray), and
    /// elsewhere RKN6(4), the one that wins `examples/stepper_study`'s error-against-time
    /// comparison.
    pub const DEFAULT: StepperKind = StepperKind::Linearize;

    /// The adaptive tolerance used when none is given: where `examples/stepper_study`
    /// measured final-position errors of ~1e-8 or better on the fiber (10 periods), the
    /// Luneburg crossing and the black-hole rays at the least cost. The tolerance bounds the error estimate per unit
    /// length, which for the embedded pairs is the lower-order solution's: the arc chain's
    /// (4, 2) and the RKN's (6, 4) pairs deliver far smaller errors than their tolerance, so
    /// theirs are looser than RK4's (whose step doubling estimates its own error).
    pub fn default_tolerance(self) -> f64 {
        match self {
            StepperKind::Arc => 1e-6,
            StepperKind::Rk4 => 1e-9,
            StepperKind::Rkn | StepperKind::Linearize => 1e-6,
            StepperKind::Snell => 1e-5,
        }
    }

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            StepperKind::Arc => "arc",
            StepperKind::Rk4 => "rk4",
            StepperKind::Rkn => "rkn",
            StepperKind::Snell => "snell",
            StepperKind::Linearize => "linearize",
        }
    }
}

impl std::str::FromStr for StepperKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                format!("unknown stepper '{s}' (expected arc, rk4, rkn, snell or linearize)")
            })
    }
}
