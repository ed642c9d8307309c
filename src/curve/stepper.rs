//! Steppers: one step of a ray through a medium, behind one small interface.

use super::segment::CurvedSegment;
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
            direction: direction.normalize(),
            index: medium.sample(position)?,
        })
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

    /// A step with a local error estimate. The default is step doubling (Richardson): one
    /// step of h against two of h/2, whose result is returned; error = |difference|/(2ᵖ − 1).
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        let full = self.step(medium, state, h)?;
        let half = self.step(medium, state, 0.5 * h)?;
        let second = self.step(medium, &half.state, 0.5 * h)?;
        let scale = f64::from((1u32 << self.order()) - 1);
        Some(EstimatedStep {
            step: Step {
                state: second.state,
                length: half.length + second.length,
            },
            error: (second.state.position - full.state.position).length() / scale,
        })
    }
}

/// Tessendorf's exact arc with F = ∇ln n frozen at the start of the step (seed 000 §2–3,
/// DESIGN §5). Exact where ∇ln n is constant (the exponential medium); second order otherwise.
#[derive(Clone, Copy, Debug, Default)]
pub struct ExactArc;

impl Stepper for ExactArc {
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        let end = CurvedSegment::new(state.position, state.direction, state.index.log_gradient()).at(h);
        Some(Step {
            state: RayState {
                position: end.position,
                direction: end.direction,
                index: medium.sample(end.position)?,
            },
            length: h,
        })
    }

    fn order(&self) -> u32 {
        2
    }

    /// The frozen-F arc errs by the change of F across the step: with F(s) ≈ F0 + (F1 − F0)s/h,
    /// the direction error grows as the transverse part of (F1 − F0) s²/2h, and the position
    /// error after h is |(F1 − F0)⊥| h²/6. F1 is the sample the next step needs anyway, so the
    /// estimate costs nothing.
    fn estimated_step<M: Medium + ?Sized>(
        &self,
        medium: &M,
        state: &RayState,
        h: f64,
    ) -> Option<EstimatedStep> {
        let step = self.step(medium, state, h)?;
        let df = step.state.index.log_gradient() - state.index.log_gradient();
        let transverse = df - state.direction * df.dot(state.direction);
        Some(EstimatedStep {
            step,
            error: transverse.length() * h * h / 6.0,
        })
    }
}

/// Classical RK4 for the ray equation in Sharma's form (Appl. Opt. 21 (1982) 984):
/// T = n dx/ds, optical time dt = ds/n, D = n∇n, d²x/dt² = D. With Δt:
/// A = Δt D(x), B = Δt D(x + Δt T/2 + Δt A/8), C = Δt D(x + Δt T + Δt B/2),
/// x' = x + Δt (T + (A + 2B)/6), T' = T + (A + 4B + C)/6. Fourth order.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rk4Sharma;

impl Stepper for Rk4Sharma {
    fn step<M: Medium + ?Sized>(&self, medium: &M, state: &RayState, h: f64) -> Option<Step> {
        let x = state.position;
        let n0 = state.index.n;
        let dt = h / n0;
        let t_vec = n0 * state.direction;
        let a = dt * n0 * state.index.grad;
        let sb = medium.sample(x + dt * (0.5 * t_vec + 0.125 * a))?;
        let b = dt * sb.n * sb.grad;
        let sc = medium.sample(x + dt * (t_vec + 0.5 * b))?;
        let c = dt * sc.n * sc.grad;
        let position = x + dt * (t_vec + (a + 2.0 * b) / 6.0);
        let t_new = t_vec + (a + 4.0 * b + c) / 6.0;
        Some(Step {
            state: RayState {
                position,
                direction: t_new.normalize(),
                index: medium.sample(position)?,
            },
            // ds = n dt, by Simpson's rule over the samples at t, t + Δt/2, ≈ t + Δt.
            length: dt * (n0 + 4.0 * sb.n + sc.n) / 6.0,
        })
    }

    fn order(&self) -> u32 {
        4
    }
}

/// Iterative Snell steps (seed 001): a straight step of length h, then the direction is
/// refracted at a virtual interface normal to ∇n (averaged over the step's ends) from n(x0)
/// to n(x1), conserving the tangential part of n t̂; total internal reflection mirrors it.
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
