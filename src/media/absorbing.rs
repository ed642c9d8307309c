//! Absorption: a constant coefficient σa around any index profile.

use super::{IndexSample, Medium};
use glam::DVec3;

/// `inner`'s index with absorption coefficient `sigma_a` (1/length) everywhere: light crossing
/// a path of length s keeps exp(−σa s) of its power.
pub struct Absorbing {
    /// The index profile.
    pub inner: Box<dyn Medium>,
    /// σa (1/length), ≥ 0.
    pub sigma_a: f64,
}

impl Medium for Absorbing {
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        self.inner.sample(p)
    }
    fn absorption(&self, _p: DVec3) -> f64 {
        self.sigma_a
    }
    fn absorbs(&self) -> bool {
        self.sigma_a > 0.0
    }
    /// σa·length, exactly.
    fn optical_depth(&self, _from: DVec3, _dir: DVec3, length: f64) -> f64 {
        self.sigma_a * length
    }
    fn step_hint(&self, p: DVec3, dir: DVec3) -> f64 {
        self.inner.step_hint(p, dir)
    }
    fn is_uniform(&self) -> bool {
        self.inner.is_uniform()
    }
}
