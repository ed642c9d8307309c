//! Absorption: a coefficient σa around any index profile, constant or scaled by a density.

use super::{ConstantCurvature, Density, IndexSample, Medium};
use glam::DVec3;
use std::sync::Arc;

/// `inner`'s index with absorption coefficient `sigma_a` (1/length) everywhere, times the
/// `density` where there is one: light crossing a path of length s keeps exp(−σa s) of its
/// power (exp(−σa ∫d ds) in a dense medium).
pub struct Absorbing {
    /// The index profile.
    pub inner: Box<dyn Medium>,
    /// σa (1/length), ≥ 0.
    pub sigma_a: f64,
    /// The density scaling σa (None: 1 everywhere).
    pub density: Option<Arc<Density>>,
}

impl Medium for Absorbing {
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        self.inner.sample(p)
    }
    fn absorption(&self, p: DVec3) -> f64 {
        self.sigma_a * self.density.as_ref().map_or(1.0, |d| d.at(p))
    }
    fn absorbs(&self) -> bool {
        self.sigma_a > 0.0
    }
    /// σa·length (σa times the density's column), exactly.
    fn optical_depth(&self, from: DVec3, dir: DVec3, length: f64) -> f64 {
        match &self.density {
            None => self.sigma_a * length,
            Some(d) => self.sigma_a * d.column(from, dir, length),
        }
    }
    fn step_hint(&self, p: DVec3, dir: DVec3) -> f64 {
        self.inner.step_hint(p, dir)
    }
    fn is_uniform(&self) -> bool {
        self.inner.is_uniform()
    }
    fn constant_curvature(&self) -> Option<ConstantCurvature<'_>> {
        self.inner.constant_curvature()
    }
    fn exact_reach(&self) -> Option<f64> {
        self.inner.exact_reach()
    }
}
