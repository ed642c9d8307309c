//! Fiber profiles: the index depends on the distance r from an axis line (GRIN rods and fibers).

use super::table::MonotoneCubic;
use super::{IndexSample, Medium};
use glam::DVec3;

/// An axis line through `center` with unit direction `axis`.
#[derive(Clone, Copy, Debug)]
pub struct Axis {
    /// A point on the axis.
    pub center: DVec3,
    /// Unit direction of the axis.
    pub axis: DVec3,
}

impl Axis {
    /// The vector from the axis to `p`, perpendicular to the axis (its length is r).
    pub fn radial(&self, p: DVec3) -> DVec3 {
        let d = p - self.center;
        d - self.axis * d.dot(self.axis)
    }
}

/// Parabolic GRIN rod n = n0 (1 − a r²/2); paraxial pitch 2π/√a. Captures where n ≤ 0.
#[derive(Clone, Debug)]
pub struct ParabolicFiber {
    /// Index on the axis.
    pub n0: f64,
    /// Gradient constant a (1/length²).
    pub a: f64,
    /// The fiber axis.
    pub axis: Axis,
}

impl Medium for ParabolicFiber {
    /// Transparent.
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let rv = self.axis.radial(p);
        let n = self.n0 * (1.0 - 0.5 * self.a * rv.length_squared());
        (n > 0.0).then_some(IndexSample {
            n,
            grad: -self.n0 * self.a * rv,
        })
    }
    /// A tenth of the paraxial pitch 2π/√a.
    fn step_hint(&self, _p: DVec3, _dir: DVec3) -> f64 {
        0.2 * std::f64::consts::PI / self.a.abs().sqrt()
    }
}

/// sech fiber n = n0 sech(g r): meridional rays are exactly periodic with period 2π/g.
#[derive(Clone, Debug)]
pub struct SechFiber {
    /// Index on the axis.
    pub n0: f64,
    /// Gradient constant g (1/length).
    pub g: f64,
    /// The fiber axis.
    pub axis: Axis,
}

impl Medium for SechFiber {
    /// Transparent.
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let rv = self.axis.radial(p);
        let r = rv.length();
        let gr = self.g * r;
        let n = self.n0 / gr.cosh();
        // ∇n = −n0 g sech(gr) tanh(gr) r̂; tanh(gr)/r → g at the axis.
        let tanh_over_r = if gr < 1e-8 { self.g } else { gr.tanh() / r };
        (n > 0.0).then_some(IndexSample {
            n,
            grad: -n * self.g * tanh_over_r * rv,
        })
    }
    /// A tenth of the period 2π/g.
    fn step_hint(&self, _p: DVec3, _dir: DVec3) -> f64 {
        0.2 * std::f64::consts::PI / self.g.abs()
    }
}

/// A tabulated radial profile n(r): values at radii 0 = r₀ < r₁ < … < r_N joined by monotone
/// cubic Hermite pieces (Fritsch–Carlson slopes, n'(0) = 0 so the index is smooth across the
/// axis), so n and ∇n are continuous and no overshoot appears between nodes. Beyond r_N the
/// index stays n_N (∇n = 0).
#[derive(Clone, Debug)]
pub struct RadialTable {
    /// n(r).
    table: MonotoneCubic,
    /// The fiber axis.
    axis: Axis,
}

impl RadialTable {
    /// The profile through the nodes (r, n), or why not, as (the offending key, message): at
    /// least two nodes, r from 0 strictly increasing and finite, every n finite and > 0.
    pub fn new(r: Vec<f64>, n: Vec<f64>, axis: Axis) -> Result<Self, (&'static str, String)> {
        let from_zero = r.first() == Some(&0.0);
        let table = match MonotoneCubic::indices(r, n, true, ("r", "n")) {
            Ok(t) if from_zero => t,
            Err((key, message)) if key == "n" => return Err((key, message)),
            _ => return Err(("r", "must start at 0 and increase strictly".into())),
        };
        Ok(Self { table, axis })
    }

    /// n and dn/dr at radius `x` ≥ 0.
    pub fn at(&self, x: f64) -> (f64, f64) {
        self.table.at(x)
    }
}

impl Medium for RadialTable {
    /// Transparent.
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let rv = self.axis.radial(p);
        let r = rv.length();
        let (n, dn) = self.at(r);
        // ∇n = n'(r) r̂; n'(0) = 0 and n' is linear near the axis, so n'/r stays finite.
        let grad = if r > 0.0 { rv * (dn / r) } else { DVec3::ZERO };
        (n > 0.0).then_some(IndexSample { n, grad })
    }
    /// Four node spacings where `p` lies, outside the table the distance to it plus four end
    /// spacings (see [`MonotoneCubic::reach`]) — radii, so along `dir` the step may be
    /// 1/|dir⊥| times longer, dir⊥ the part of `dir` across the axis (at most 10⁴ times: a ray
    /// along the axis). A node search, not a scan: the cost of a step grows with the log of
    /// the node count.
    fn step_hint(&self, p: DVec3, dir: DVec3) -> f64 {
        let across = dir - self.axis.axis * dir.dot(self.axis.axis);
        self.table.reach(self.axis.radial(p).length()) / across.length().max(1e-4)
    }
}
