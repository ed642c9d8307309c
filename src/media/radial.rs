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

/// A tabulated radial profile n(r): values at radii 0 = r₀ < r₁ < … < r_N joined by monotone
/// cubic Hermite pieces (Fritsch–Carlson slopes, n'(0) = 0 so the index is smooth across the
/// axis), so n and ∇n are continuous and no overshoot appears between nodes. Beyond r_N the
/// index stays n_N (∇n = 0).
#[derive(Clone, Debug)]
pub struct RadialTable {
    /// Node radii, strictly increasing from 0.
    r: Vec<f64>,
    /// Node indices (> 0).
    n: Vec<f64>,
    /// dn/dr at the nodes.
    slope: Vec<f64>,
    /// The fiber axis.
    axis: Axis,
}

impl RadialTable {
    /// The profile through the nodes (r, n), or why not, as (the offending key, message): at
    /// least two nodes, r from 0 strictly increasing and finite, every n finite and > 0.
    pub fn new(r: Vec<f64>, n: Vec<f64>, axis: Axis) -> Result<Self, (&'static str, String)> {
        if r.len() != n.len() || r.len() < 2 {
            return Err((
                "n",
                format!(
                    "`r` and `n` need the same number (≥ 2) of values, got {} and {}",
                    r.len(),
                    n.len()
                ),
            ));
        }
        if r[0] != 0.0 || !r.windows(2).all(|w| w[1] > w[0]) || !r.iter().all(|x| x.is_finite()) {
            return Err(("r", "must start at 0 and increase strictly".into()));
        }
        if !n.iter().all(|x| x.is_finite() && *x > 0.0) {
            return Err(("n", "every value must be a finite number > 0".into()));
        }
        // Fritsch–Carlson: secant slopes, averaged inside, zeroed at extrema, limited to 3×.
        let secant: Vec<f64> = (0..r.len() - 1)
            .map(|i| (n[i + 1] - n[i]) / (r[i + 1] - r[i]))
            .collect();
        let mut slope = vec![0.0; r.len()];
        for i in 1..r.len() - 1 {
            if secant[i - 1] * secant[i] > 0.0 {
                slope[i] = 0.5 * (secant[i - 1] + secant[i]);
            }
        }
        let last = r.len() - 1;
        slope[last] = secant[last - 1];
        for (i, &d) in secant.iter().enumerate() {
            if d == 0.0 {
                slope[i] = 0.0;
                slope[i + 1] = 0.0;
            } else {
                let (a, b) = (slope[i] / d, slope[i + 1] / d);
                let s = a * a + b * b;
                if s > 9.0 {
                    let t = 3.0 / s.sqrt();
                    slope[i] = t * a * d;
                    slope[i + 1] = t * b * d;
                }
            }
        }
        slope[0] = 0.0;
        Ok(Self { r, n, slope, axis })
    }

    /// n and dn/dr at radius `x` ≥ 0.
    pub fn at(&self, x: f64) -> (f64, f64) {
        let last = self.r.len() - 1;
        if x >= self.r[last] {
            return (self.n[last], 0.0);
        }
        let i = self.r.partition_point(|&ri| ri <= x) - 1;
        let h = self.r[i + 1] - self.r[i];
        let t = (x - self.r[i]) / h;
        let (t2, t3) = (t * t, t * t * t);
        let (n0, n1, m0, m1) = (
            self.n[i],
            self.n[i + 1],
            self.slope[i] * h,
            self.slope[i + 1] * h,
        );
        let n = (2.0 * t3 - 3.0 * t2 + 1.0) * n0
            + (t3 - 2.0 * t2 + t) * m0
            + (-2.0 * t3 + 3.0 * t2) * n1
            + (t3 - t2) * m1;
        let dn = ((6.0 * t2 - 6.0 * t) * n0
            + (3.0 * t2 - 4.0 * t + 1.0) * m0
            + (-6.0 * t2 + 6.0 * t) * n1
            + (3.0 * t2 - 2.0 * t) * m1)
            / h;
        (n, dn)
    }
}

impl Medium for RadialTable {
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let rv = self.axis.radial(p);
        let r = rv.length();
        let (n, dn) = self.at(r);
        // ∇n = n'(r) r̂; n'(0) = 0 and n' is linear near the axis, so n'/r stays finite.
        let grad = if r > 0.0 { rv * (dn / r) } else { DVec3::ZERO };
        (n > 0.0).then_some(IndexSample { n, grad })
    }
    /// The smallest node spacing.
    fn step_hint(&self, _p: DVec3) -> f64 {
        self.r
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min)
    }
}
