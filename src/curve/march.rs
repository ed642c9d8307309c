//! The march: repeated steps under a step control until an explicit termination.

use super::bounds::Bounds;
use super::state::RayState;
use super::stepper::{
    ArcChain, Linearize, Rk4Sharma, Rkn64, SnellSteps, Step, Stepper, StepperKind,
};
use crate::media::Medium;
use glam::DVec3;
use rand::Rng;
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// How step lengths are chosen.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum StepControl {
    /// Every step has length `step` (the last one is clipped to the requested length).
    Fixed {
        /// Step length (scene units).
        step: f64,
    },
    /// Tessendorf (2022) §4 as intended: a trial step is rejected and the step multiplied
    /// by a random ξ ∈ (0, 1] while ε = |F' − F|/|F| > `t_max`; after an accepted step with
    /// ε < `t_min` the step is divided by ξ. ξ comes from a PCG stream keyed by `seed`, so runs
    /// repeat. Every trial counts against the march's step limit (N_max).
    Tessendorf {
        /// Initial step (scene units).
        initial_step: f64,
        /// Rejection threshold on the relative change of F across a step.
        t_max: f64,
        /// Growth threshold (< t_max).
        t_min: f64,
        /// Seed of the ξ stream.
        seed: u64,
    },
    /// Deterministic error control: a step is accepted when the stepper's local position-error
    /// estimate is ≤ `tolerance`·h, so the position error per unit arclength stays ≤ `tolerance`
    /// (dimensionless), or is below the rounding of the position (16 ε |x|∞). The next step is
    /// h·clamp(0.9 (allowed/error)^(1/p), 0.2, 5), never longer than the step hint
    /// ([`Stepper::step_hint`]: the medium's, for every stepper that errs).
    Adaptive {
        /// Position error per unit arclength.
        tolerance: f64,
    },
}

impl StepControl {
    /// The default control for a stepper: adaptive at its default tolerance.
    pub fn default_for(kind: StepperKind) -> StepControl {
        StepControl::Adaptive {
            tolerance: kind.default_tolerance(),
        }
    }
}

/// What ends a march; every march ends with exactly one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Termination {
    /// The requested arclength was travelled.
    LengthReached,
    /// The ray crossed the boundary of the bounds; the final state is on the boundary.
    LeftBounds,
    /// The ray reached a region where the medium captures it (singular or non-positive index).
    Captured,
    /// The adaptive step fell below a few ulps of the position: the ray cannot advance (a
    /// singularity that the medium does not flag).
    StepUnderflow,
    /// The step limit (N_max) was reached first.
    MaxSteps,
    /// The caller's observer stopped the march (e.g. the step crossed a surface).
    Stopped,
}

impl Termination {
    /// A short lower-case name for summaries and CSV.
    pub fn name(self) -> &'static str {
        match self {
            Termination::LengthReached => "length reached",
            Termination::LeftBounds => "left bounds",
            Termination::Captured => "captured",
            Termination::StepUnderflow => "step underflow",
            Termination::MaxSteps => "max steps",
            Termination::Stopped => "stopped",
        }
    }
}

/// Limits of one march.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchLimits {
    /// Arclength to travel (scene units).
    pub length: f64,
    /// Maximum number of step attempts (accepted and rejected), N_max.
    pub max_steps: u64,
    /// Region the ray is confined to.
    pub bounds: Bounds,
}

/// The result of a march.
#[derive(Clone, Copy, Debug)]
pub struct MarchOutcome {
    /// The final state (on the boundary for `LeftBounds`, the last good state otherwise).
    pub state: RayState,
    /// Arclength travelled.
    pub arclength: f64,
    /// Optical path length ∫ n ds travelled: the sum of the steps' own
    /// [`Step::optical_path`], each to its stepper's order.
    pub optical_path: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Step attempts, accepted and rejected.
    pub attempts: u64,
    /// Shortest accepted step (∞ when none).
    pub min_step: f64,
    /// Why the march ended.
    pub reason: Termination,
}

impl MarchOutcome {
    /// Nothing travelled yet: at `start`, no steps, ending `LengthReached` unless told.
    fn at(start: RayState) -> Self {
        MarchOutcome {
            state: start,
            arclength: 0.0,
            optical_path: 0.0,
            steps: 0,
            attempts: 0,
            min_step: f64::INFINITY,
            reason: Termination::LengthReached,
        }
    }
}

/// Marches a ray from `start` with `stepper` under `control` until one of `limits` ends it.
/// `observe` sees every accepted step (first the start, as a step of length 0) with the
/// arclength at its end; returning `ControlFlow::Break` ends the march with
/// [`Termination::Stopped`] at that step's end.
pub fn march<S, M, O>(
    stepper: &S,
    medium: &M,
    control: StepControl,
    start: RayState,
    limits: &MarchLimits,
    mut observe: O,
) -> MarchOutcome
where
    S: Stepper,
    M: Medium + ?Sized,
    O: FnMut(f64, &Step) -> ControlFlow<()>,
{
    let mut out = MarchOutcome::at(start);
    let radial = Radial::of(medium, &start);
    let at_start = Step {
        state: start,
        length: 0.0,
        optical_path: 0.0,
        path: None,
    };
    if observe(0.0, &at_start).is_break() {
        out.reason = Termination::Stopped;
        return out;
    }
    let mut rng = match control {
        StepControl::Tessendorf { seed, .. } => Some(Pcg64Mcg::new(u128::from(seed) | 1)),
        StepControl::Adaptive { .. } | StepControl::Fixed { .. } => None,
    };
    // ξ ∈ (0, 1]: never zero (Tessendorf's (2022) shader left ξ = 0 unguarded).
    let mut xi = || 1.0 - rng.as_mut().map_or(0.5, |r| r.gen::<f64>());
    let mut h = match control {
        StepControl::Fixed { step } => step,
        StepControl::Tessendorf { initial_step, .. } => initial_step,
        StepControl::Adaptive { .. } => stepper
            .step_hint(medium, start.position, start.direction)
            .min(limits.length),
    };
    let done_within = 1e-12 * limits.length;
    loop {
        let remaining = limits.length - out.arclength;
        if remaining <= done_within {
            out.reason = Termination::LengthReached;
            return out;
        }
        if out.attempts >= limits.max_steps {
            out.reason = Termination::MaxSteps;
            return out;
        }
        out.attempts += 1;
        let state = out.state;
        let h_try = h.min(remaining);
        // One trial: the step, whether to accept it, and the next h.
        let (step, next_h, requested) = match control {
            // A fixed step below the rounding of the position would not move the ray.
            StepControl::Fixed { step } if step <= round_off_floor(state.position) => {
                out.reason = Termination::StepUnderflow;
                return out;
            }
            StepControl::Fixed { step } => match stepper.step(medium, &state, h_try) {
                Some(s) if plausible(&state, &s, h_try) => (s, step, h_try),
                // A step that did not advance about h (RK4 flung out by a near-singular n∇n)
                // is retried at half the length; the fixed length resumes afterwards.
                Some(_) => {
                    h = 0.5 * h_try;
                    if h <= round_off_floor(state.position) {
                        out.reason = Termination::StepUnderflow;
                        return out;
                    }
                    continue;
                }
                None => {
                    out.reason = Termination::Captured;
                    return out;
                }
            },
            StepControl::Tessendorf { t_max, t_min, .. } => {
                match stepper.step(medium, &state, h_try) {
                    // A step that leaves the region ends the march whatever its ε (seed step 2).
                    Some(s) if !plausible(&state, &s, h_try) => {
                        h = h_try * xi();
                        continue;
                    }
                    Some(s) if leaves(limits, s.state.position) => (s, h_try, h_try),
                    Some(s) => {
                        let eps = relative_force_change(&state, &s.state);
                        if eps > t_max {
                            h = h_try * xi();
                            continue;
                        }
                        (s, if eps < t_min { h_try / xi() } else { h_try }, h_try)
                    }
                    // Landing where the index is singular counts as an unbounded ε: rejected.
                    None => {
                        h = h_try * xi();
                        continue;
                    }
                }
            }
            StepControl::Adaptive { tolerance } => {
                let h_try = h_try.min(stepper.step_hint(medium, state.position, state.direction));
                let floor = round_off_floor(state.position);
                if h_try <= floor || h_try.is_nan() {
                    out.reason = Termination::StepUnderflow;
                    return out;
                }
                let Some(est) = stepper
                    .estimated_step(medium, &state, h_try)
                    .filter(|e| plausible(&state, &e.step, h_try))
                else {
                    // The step reached a capture region (or was flung out by it): approach it
                    // with shorter steps.
                    h = 0.25 * h_try;
                    if h <= floor {
                        out.reason = Termination::Captured;
                        return out;
                    }
                    continue;
                };
                // What a step may err by: the tolerance per unit length, and never less than
                // the rounding of the position itself (else tight tolerances stall).
                let allowed =
                    tolerance * h_try + 16.0 * f64::EPSILON * state.position.abs().max_element();
                let factor = 0.9 * root(allowed / est.error, stepper.estimate_order());
                if est.error > allowed {
                    h = h_try * factor.clamp(0.1, 0.9);
                    continue;
                }
                (est.step, h_try * factor.clamp(0.2, 5.0), h_try)
            }
        };
        // A stepper that advances in optical time (RK4) may overshoot the requested length
        // by O(h |∇n|/n): shorten the last step until it ends on the length (secant on h).
        let mut step = step;
        for _ in 0..8 {
            if step.length <= remaining + done_within {
                break;
            }
            match stepper.step(medium, &state, step_request(requested, &step, remaining)) {
                Some(s) => step = s,
                None => break,
            }
        }
        if let Some(line) = &radial {
            line.keep(&mut step);
        }
        if leaves(limits, step.state.position) {
            let exit = locate_exit(stepper, medium, &state, step, limits);
            let flow = accept(&mut out, exit, &mut observe);
            out.reason = if flow.is_break() {
                Termination::Stopped
            } else {
                Termination::LeftBounds
            };
            return out;
        }
        if accept(&mut out, step, &mut observe).is_break() {
            out.reason = Termination::Stopped;
            return out;
        }
        h = next_h;
    }
}

/// The line a ray keeps in a spherically symmetric medium when it starts through the centre
/// (from the centre, or along the line to it): ∇n lies along the line, so the ray never leaves
/// it. A stepper's rounding does — and off the line the ray is a circle, which about a small
/// lens (a fish-eye of radius 10⁻¹⁵⁰, seen from its centre) closes within rounding distance of
/// the centre, and a million steps never carried a camera ray out. So each step's end is put
/// back on the line, heading along it.
struct Radial {
    center: DVec3,
    /// Unit direction along the line.
    axis: DVec3,
}

impl Radial {
    /// How far (relative) a radial ray may stray from its line before it is put back: off the
    /// line by δ at distance r, a ray in a fish-eye turns back within about r/δ of the centre,
    /// so it still reaches 10¹⁴ times as far.
    const STRAY: f64 = 1e-14;

    /// The line of a ray from `start` in `medium`, if it starts through the centre (within
    /// 10⁻¹² of its distance from it).
    fn of<M: Medium + ?Sized>(medium: &M, start: &RayState) -> Option<Radial> {
        let center = medium.symmetry_center()?;
        let off = start.position - center;
        (off.cross(start.direction).length() <= 1e-12 * off.length()).then_some(Radial {
            center,
            axis: start.direction,
        })
    }

    /// `step`'s end put back on the line, heading along it, once it has strayed from it by
    /// more than [`Radial::STRAY`] of its distance from the centre (a stepper's rounding,
    /// ~10⁻¹⁶ a step, partly corrects itself; put back each step, the rounding of the point
    /// put back cost RKN's radial rays 10⁻¹² of their accuracy). Its index sample stays the
    /// stepper's own (the next step starts from it).
    fn keep(&self, step: &mut Step) {
        let off = step.state.position - self.center;
        let along = off.dot(self.axis);
        let strayed = (off - self.axis * along).length() > Self::STRAY * along.abs()
            || step.state.direction.cross(self.axis).length() > Self::STRAY;
        if strayed {
            step.state.position = self.center + self.axis * along;
            step.state.direction = match step.state.direction.dot(self.axis) < 0.0 {
                true => -self.axis,
                false => self.axis,
            };
        }
    }
}

/// x^(1/p), by square and cube roots for the orders the steppers have (a general power
/// costs ~6 % of a march).
fn root(x: f64, p: u32) -> f64 {
    match p {
        1 => x,
        2 => x.sqrt(),
        3 => x.cbrt(),
        4 => x.sqrt().sqrt(),
        _ => x.powf(1.0 / f64::from(p)),
    }
}

/// A step length below which a step cannot move a ray at `position` (a few ulps of it).
pub fn round_off_floor(position: glam::DVec3) -> f64 {
    4.0 * f64::EPSILON * position.abs().max_element()
}

/// Whether a step advanced about the arclength requested, as every stepper does on a smooth
/// index: RK4 in optical time can be flung far where n∇n is near-singular, and such a step is
/// not a solution of anything.
fn plausible(state: &RayState, step: &Step, requested: f64) -> bool {
    (step.length - requested).abs() <= 0.5 * requested
        && (step.state.position - state.position).length() <= 1.5 * requested
}

/// The step length to request so that a step that advanced `step.length` for a request of
/// `requested` advances `target` instead (the two are proportional to first order).
fn step_request(requested: f64, step: &Step, target: f64) -> f64 {
    requested * target / step.length
}

fn accept<O: FnMut(f64, &Step) -> ControlFlow<()>>(
    out: &mut MarchOutcome,
    step: Step,
    observe: &mut O,
) -> ControlFlow<()> {
    let len = step.length;
    out.optical_path += step.optical_path;
    out.arclength += len;
    out.steps += 1;
    out.min_step = out.min_step.min(len);
    out.state = step.state;
    observe(out.arclength, &step)
}

fn leaves(limits: &MarchLimits, p: glam::DVec3) -> bool {
    limits.bounds.signed_distance(p) > 0.0
}

/// ε = |F' − F|/|F| of Tessendorf (2022) §4, with F = 0 guarded: 0 when both vanish, ∞ when only F does.
fn relative_force_change(a: &RayState, b: &RayState) -> f64 {
    let f0 = a.index.log_gradient();
    let f1 = b.index.log_gradient();
    let diff = (f1 - f0).length();
    if diff == 0.0 {
        0.0
    } else {
        diff / f0.length()
    }
}

/// The part of `step` (taken from `state`) up to where it crosses the boundary, by the
/// Illinois variant of regula falsi on the step length (the boundary's signed distance
/// changes sign on [0, step.length]); to ~1e-12 of the region's scale.
fn locate_exit<S, M>(
    stepper: &S,
    medium: &M,
    state: &RayState,
    step: Step,
    limits: &MarchLimits,
) -> Step
where
    S: Stepper,
    M: Medium + ?Sized,
{
    let h = step.length;
    let sd = |hh: f64| -> Option<(f64, Step)> {
        let s = stepper.step(medium, state, hh)?;
        Some((limits.bounds.signed_distance(s.state.position), s))
    };
    let tol = 1e-12 * limits.bounds.scale();
    let (mut a, mut fa) = (0.0, limits.bounds.signed_distance(state.position).min(0.0));
    // A step from a point of the boundary to rounding (a ray started on a face, going in):
    // the crossing out is beyond some point of the step well inside; bracket from the first
    // one halving finds (none: the ray leaves at its start). Else the search would stop at
    // the start, where the boundary's distance is already within its tolerance.
    let mut inner = 0.5 * h;
    while fa >= -tol && inner > 1e-15 * h {
        match sd(inner) {
            Some((f, _)) if f < -tol => (a, fa) = (inner, f),
            _ => inner *= 0.5,
        }
    }
    let at_start = Step {
        state: *state,
        length: 0.0,
        optical_path: 0.0,
        path: None,
    };
    let Some((mut fb, mut best)) = sd(h) else {
        return at_start;
    };
    let mut b = h;
    let mut side = 0i8;
    for _ in 0..100 {
        if fb.abs() <= tol || (b - a) <= 1e-15 * h {
            break;
        }
        let c = (a * fb - b * fa) / (fb - fa);
        let Some((fc, st)) = sd(c) else { break };
        if fc > 0.0 {
            (b, fb, best) = (c, fc, st);
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            (a, fa) = (c, fc);
            if fc.abs() <= tol {
                return st;
            }
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    best
}

/// Marches from `start` with the given step lengths (no error control), then on with the
/// last length until the ray leaves `limits.bounds`, whose crossing is located as [`march`]
/// does. An adaptive march's step sequence jumps as its start moves, so its end is a
/// function of the start only to its tolerance; a march with a fixed sequence is a smooth
/// function of the start, which makes it the one to difference for derivatives (Bock's
/// internal numerical differentiation): replay the sequence of a neighbouring adaptive march
/// (the lengths its observer saw) and it is as accurate as that march. Ends `LeftBounds`,
/// `Captured`, `LengthReached` or `MaxSteps`.
pub fn march_replay<S, M>(
    stepper: &S,
    medium: &M,
    start: RayState,
    lengths: &[f64],
    limits: &MarchLimits,
) -> MarchOutcome
where
    S: Stepper,
    M: Medium + ?Sized,
{
    let mut out = MarchOutcome::at(start);
    let radial = Radial::of(medium, &start);
    let Some(&last) = lengths.last() else {
        return out;
    };
    let mut observe = |_: f64, _: &Step| ControlFlow::Continue(());
    for h in lengths.iter().copied().chain(std::iter::repeat(last)) {
        if out.arclength >= limits.length {
            return out;
        }
        if out.attempts >= limits.max_steps {
            out.reason = Termination::MaxSteps;
            return out;
        }
        out.attempts += 1;
        let state = out.state;
        // The step an adaptive march keeps (RK4's is its two half steps, not one whole).
        let Some(mut step) = stepper.estimated_step(medium, &state, h).map(|e| e.step) else {
            out.reason = Termination::Captured;
            return out;
        };
        if let Some(line) = &radial {
            line.keep(&mut step);
        }
        if leaves(limits, step.state.position) {
            let exit = locate_exit(stepper, medium, &state, step, limits);
            let _ = accept(&mut out, exit, &mut observe);
            out.reason = Termination::LeftBounds;
            return out;
        }
        let _ = accept(&mut out, step, &mut observe);
    }
    unreachable!("the step lengths repeat without end")
}

/// [`march_replay`] with the stepper chosen at run time.
pub fn march_replay_with<M: Medium + ?Sized>(
    kind: StepperKind,
    medium: &M,
    start: RayState,
    lengths: &[f64],
    limits: &MarchLimits,
) -> MarchOutcome {
    match kind {
        StepperKind::Arc => march_replay(&ArcChain, medium, start, lengths, limits),
        StepperKind::Rk4 => march_replay(&Rk4Sharma, medium, start, lengths, limits),
        StepperKind::Rkn => march_replay(&Rkn64, medium, start, lengths, limits),
        StepperKind::Snell => march_replay(&SnellSteps, medium, start, lengths, limits),
        StepperKind::Linearize => march_replay(&Linearize, medium, start, lengths, limits),
    }
}

/// [`march`] with the stepper chosen at run time.
pub fn march_with<M, O>(
    kind: StepperKind,
    medium: &M,
    control: StepControl,
    start: RayState,
    limits: &MarchLimits,
    observe: O,
) -> MarchOutcome
where
    M: Medium + ?Sized,
    O: FnMut(f64, &Step) -> ControlFlow<()>,
{
    match kind {
        StepperKind::Arc => march(&ArcChain, medium, control, start, limits, observe),
        StepperKind::Rk4 => march(&Rk4Sharma, medium, control, start, limits, observe),
        StepperKind::Rkn => march(&Rkn64, medium, control, start, limits, observe),
        StepperKind::Snell => march(&SnellSteps, medium, control, start, limits, observe),
        StepperKind::Linearize => march(&Linearize, medium, control, start, limits, observe),
    }
}
