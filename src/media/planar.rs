//! Media whose index depends on one linear coordinate: uniform, linear and exponential.

use super::{IndexSample, Medium};
use glam::DVec3;

/// Constant index n everywhere: rays are straight.
#[derive(Clone, Debug)]
pub struct UniformMedium {
    /// The index.
    pub n: f64,
}

impl Medium for UniformMedium {
    fn sample(&self, _p: DVec3) -> Option<IndexSample> {
        Some(IndexSample::constant(self.n))
    }
    fn step_hint(&self, _p: DVec3) -> f64 {
        f64::INFINITY
    }
    fn is_uniform(&self) -> bool {
        true
    }
}

/// n = n0 + gradient·(x − origin). Where that is ≤ 0 a ray is captured.
#[derive(Clone, Debug)]
pub struct LinearMedium {
    /// Index at `origin`.
    pub n0: f64,
    /// ∇n (1/length).
    pub gradient: DVec3,
    /// Where n = n0.
    pub origin: DVec3,
}

impl Medium for LinearMedium {
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let n = self.n0 + self.gradient.dot(p - self.origin);
        (n > 0.0).then_some(IndexSample {
            n,
            grad: self.gradient,
        })
    }
    /// ∇ln n = ∇n/n changes by a factor e over ~n/|∇n|.
    fn step_hint(&self, p: DVec3) -> f64 {
        let g = self.gradient.length();
        if g == 0.0 {
            return f64::INFINITY;
        }
        let n = self.n0 + self.gradient.dot(p - self.origin);
        0.5 * n.max(0.0) / g
    }
}

/// n = n0·exp(gradient·(x − origin)): ∇ln n = gradient is constant, so the exact arc is exact.
#[derive(Clone, Debug)]
pub struct ExponentialMedium {
    /// Index at `origin`.
    pub n0: f64,
    /// ∇ln n (1/length).
    pub gradient: DVec3,
    /// Where n = n0.
    pub origin: DVec3,
}

impl Medium for ExponentialMedium {
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let n = self.n0 * self.gradient.dot(p - self.origin).exp();
        (n > 0.0 && n.is_finite()).then_some(IndexSample {
            n,
            grad: n * self.gradient,
        })
    }
    fn step_hint(&self, _p: DVec3) -> f64 {
        f64::INFINITY
    }
}
