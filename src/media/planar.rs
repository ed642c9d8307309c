//! Media whose index depends on one linear coordinate: uniform, linear and exponential.

use super::table::MonotoneCubic;
use super::{IndexSample, Medium};
use glam::DVec3;

/// Constant index n everywhere: rays are straight.
#[derive(Clone, Debug)]
pub struct UniformMedium {
    /// The index.
    pub n: f64,
}

impl Medium for UniformMedium {
    /// Transparent.
    fn sample(&self, _p: DVec3) -> Option<IndexSample> {
        Some(IndexSample::constant(self.n))
    }
    fn step_hint(&self, _p: DVec3, _dir: DVec3) -> f64 {
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
    /// Transparent.
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let n = self.n0 + self.gradient.dot(p - self.origin);
        (n > 0.0).then_some(IndexSample {
            n,
            grad: self.gradient,
        })
    }
    /// ∇ln n = ∇n/n changes by a factor e over ~n/|∇n|.
    fn step_hint(&self, p: DVec3, _dir: DVec3) -> f64 {
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
    /// Transparent.
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let n = self.n0 * self.gradient.dot(p - self.origin).exp();
        (n > 0.0 && n.is_finite()).then_some(IndexSample {
            n,
            grad: n * self.gradient,
        })
    }
    fn step_hint(&self, _p: DVec3, _dir: DVec3) -> f64 {
        f64::INFINITY
    }
}

/// A layered medium: n tabulated against the height h = (x − origin)·up (unit `up`), joined by
/// monotone cubic pieces (see [`MonotoneCubic`]); below the first node and above the last the
/// index is the end value (∇n = 0). An atmosphere over a hot road or a sea, from a sounding.
#[derive(Clone, Debug)]
pub struct HeightTable {
    /// n(h).
    table: MonotoneCubic,
    /// h = 0.
    pub origin: DVec3,
    /// Unit direction of increasing h.
    pub up: DVec3,
}

impl HeightTable {
    /// The profile through the nodes (h, n), or why not, as (the offending key, message): at
    /// least two nodes, h strictly increasing, every n finite and > 0.
    pub fn new(
        h: Vec<f64>,
        n: Vec<f64>,
        origin: DVec3,
        up: DVec3,
    ) -> Result<Self, (&'static str, String)> {
        Ok(Self {
            table: MonotoneCubic::indices(h, n, false, ("h", "n"))?,
            origin,
            up,
        })
    }

    fn height(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.up)
    }
}

impl Medium for HeightTable {
    /// Transparent.
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let (n, dn) = self.table.at(self.height(p));
        Some(IndexSample {
            n,
            grad: self.up * dn,
        })
    }
    /// Four node spacings where `p` lies; above and below the table, the distance to it plus
    /// four end spacings (see [`MonotoneCubic::reach`]) — heights, so along `dir` the step
    /// may be 1/|dir·up| times longer (at most 10⁴ times: a ray along the layers).
    fn step_hint(&self, p: DVec3, dir: DVec3) -> f64 {
        self.table.reach(self.height(p)) / dir.dot(self.up).abs().max(1e-4)
    }
}
