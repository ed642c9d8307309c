//! Fiber profiles: the index depends on the distance r from an axis line (GRIN rods and fibers).

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
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let rv = self.axis.radial(p);
        let n = self.n0 * (1.0 - 0.5 * self.a * rv.length_squared());
        (n > 0.0).then_some(IndexSample {
            n,
            grad: -self.n0 * self.a * rv,
        })
    }
    /// A tenth of the paraxial pitch 2π/√a.
    fn step_hint(&self, _p: DVec3) -> f64 {
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
    fn step_hint(&self, _p: DVec3) -> f64 {
        0.2 * std::f64::consts::PI / self.g.abs()
    }
}
