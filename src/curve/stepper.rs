//! Steppers: one step of a ray through a medium, behind one small interface.

use super::segment::{ArcPoint, CurvedSegment};
use crate::media::{IndexSample, Medium};
use glam::DVec3;

/// Where a ray is, where it goes, and the medium's answer there (reused by the next step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayState {
    /// Position (scene units).
    pub position: DVec3,
    /// Unit direction of propagation.
    pub direction: DVec3,
    /// n and ∇n at `position`.
    pub index: IndexSample,
}

impl RayState {
    /// The state at `position` heading along `direction` (normalised here), or `None` if the
    /// medium captures a ray at that point.
    pub fn new<M: Medium + ?Sized>(medium: &M, position: DVec3, direction: DVec3) -> Option<Self> {
        Some(Self {
            position,
            direction: unit(direction),
            index: medium.sample(position)?,
        })
    }
}

/// `v` normalised; a vector whose squared length overflows or underflows (1e300, 1e300, 0)
/// is scaled by its largest component first.
fn unit(v: DVec3) -> DVec3 {
    let l2 = v.length_squared();
    if l2.is_finite() && l2 >= f64::MIN_POSITIVE {
        v.normalize()
    } else {
        (v / v.abs().max_element()).normalize()
    }
}

/// The result of one step.
#[derive(Clone, Copy, Debug)]
pub struct Step {
    /// The state at the end of the step.
    pub state: RayState,
    /// Arclength actually advanced (RK4 in Sharma's form advances in optical time, so this
    /// differs from the requested length by O(h⁵)).
    pub length: f64,
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

    /// A step with a local error estimate. The default is [`step_doubling`] in arclength.
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        step_doubling(self.order(), state, h, h, |s, size| {
            self.step(medium, s, size)
        })
    }
}

/// Step doubling (Richardson): one step of `size` against two of `size`/2, whose result is
/// returned, with error = [`step_discrepancy`]/(2ᵖ − 1) for a method of order p. `size` is in
/// the stepper's own parameter (arclength, or optical time for RK4); `h` is the arclength.
pub fn step_doubling(
    order: u32,
    state: &RayState,
    size: f64,
    h: f64,
    step: impl Fn(&RayState, f64) -> Option<Step>,
) -> Option<EstimatedStep> {
    let full = step(state, size)?;
    let half = step(state, 0.5 * size)?;
    let second = step(&half.state, 0.5 * size)?;
    Some(EstimatedStep {
        step: Step {
            state: second.state,
            length: half.length + second.length,
        },
        error: step_discrepancy(&second.state, &full.state, h) / f64::from((1u32 << order) - 1),
    })
}

/// Tessendorf's exact arc (seed 000 §2–3, DESIGN §5) with F = ∇ln n frozen over the step at
/// its value at the step's midpoint, which a first arc with F frozen at the start predicts.
///
/// Freezing F at the start (the seed's choice) errs in direction by ∫(F(s) − F0)⊥ ds = O(h²)
/// per step: a first-order method. The midpoint value cancels that term, making the step
/// second order for one extra medium sample; where ∇ln n is constant (the exponential
/// medium) both arcs are exact. The start-frozen arc's end, which costs no sample, is the
/// embedded lower-order solution whose distance from the step's end is its error estimate.
#[derive(Clone, Copy, Debug, Default)]
pub struct ExactArc;

impl ExactArc {
    /// The midpoint-force step and the end (position, direction) of the start-force arc.
    fn step_and_predictor<M: Medium + ?Sized>(
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<(Step, ArcPoint)> {
        let f0 = state.index.log_gradient();
        let predictor = CurvedSegment::new(state.position, state.direction, f0);
        let mid = medium.sample(predictor.at(0.5 * h).position)?;
        let fm = mid.log_gradient();
        let end = if fm == f0 {
            predictor.at(h)
        } else {
            CurvedSegment::new(state.position, state.direction, fm).at(h)
        };
        let step = Step {
            state: RayState {
                position: end.position,
                direction: end.direction,
                index: medium.sample(end.position)?,
            },
            length: h,
        };
        Some((step, predictor.at(h)))
    }
}

impl Stepper for ExactArc {
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        Self::step_and_predictor(medium, state, h).map(|(step, _)| step)
    }

    fn order(&self) -> u32 {
        2
    }

    /// Error estimate: the [`step_discrepancy`] between the midpoint-force and the
    /// start-force arcs. For F(s) ≈ F0 + F′s their position errors are −F′⊥h³/12 and F′⊥h³/6
    /// (the estimate's position part, F′⊥h³/4, bounds the step's own threefold), and their
    /// directions differ by F′⊥h²/2, which over the next h moves the ray by F′⊥h³/2.
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        let (step, predicted) = Self::step_and_predictor(medium, state, h)?;
        Some(EstimatedStep {
            step,
            error: step_discrepancy(&step.state, &predicted, h),
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
        let x = state.position;
        let n0 = state.index.n;
        let t_vec = n0 * state.direction;
        let a = dt * n0 * state.index.grad;
        let sb = medium.sample(x + dt * (0.5 * t_vec + 0.125 * a))?;
        let b = dt * sb.n * sb.grad;
        let sc = medium.sample(x + dt * (t_vec + 0.5 * b))?;
        let c = dt * sc.n * sc.grad;
        let position = x + dt * (t_vec + (a + 2.0 * b) / 6.0);
        let t_new = t_vec + (a + 4.0 * b + c) / 6.0;
        // Arclength ∫|dx/dt| dt by Simpson's rule, with dx/dt = T at the ends and the cubic
        // Hermite derivative at the midpoint, whose error vanishes to O(Δt⁴) there: the
        // arclength is as accurate as the position (a plain Simpson over n at the stage
        // points, which are off the path by O(Δt³), would make it third order).
        let mid_velocity = 1.5 * (position - x) / dt - 0.25 * (t_vec + t_new);
        let length = dt * (n0 + 4.0 * mid_velocity.length() + t_new.length()) / 6.0;
        Some(Step {
            state: RayState {
                position,
                direction: t_new.normalize(),
                index: medium.sample(position)?,
            },
            length,
        })
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
        step_doubling(4, state, dt, h, |s, size| {
            Self::optical_step(medium, s, size)
        })
    }
}

/// Iterative Snell steps (seed 001): a straight step of length h, then the direction is
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
        Some(Step {
            state: RayState {
                position,
                direction,
                index,
            },
            length: h,
        })
    }

    fn order(&self) -> u32 {
        1
    }
}

/// The steppers by name, for the command line and studies: `arc`, `rk4`, `snell`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StepperKind {
    /// [`ExactArc`].
    Arc,
    /// [`Rk4Sharma`].
    Rk4,
    /// [`SnellSteps`].
    Snell,
}

impl StepperKind {
    /// All steppers.
    pub const ALL: [StepperKind; 3] = [StepperKind::Arc, StepperKind::Rk4, StepperKind::Snell];

    /// The adaptive tolerance (position error per unit length) used when none is given: where
    /// `examples/stepper_study` measured final-position errors of ~1e-7 or better on the
    /// fiber, Luneburg and black-hole rays at a cost below a few milliseconds per ray.
    pub fn default_tolerance(self) -> f64 {
        match self {
            StepperKind::Arc => 1e-8,
            StepperKind::Rk4 => 1e-9,
            StepperKind::Snell => 1e-5,
        }
    }

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            StepperKind::Arc => "arc",
            StepperKind::Rk4 => "rk4",
            StepperKind::Snell => "snell",
        }
    }
}

impl std::str::FromStr for StepperKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| format!("unknown stepper '{s}' (expected arc, rk4 or snell)"))
    }
}
