//! Gradient-index media: the [`Medium`] interface and its index profiles (DESIGN §3).
//!
//! Conventions: positions and lengths are in scene units; the index `n` is dimensionless and
//! its gradient has units of 1/length. A medium answers `n` and `∇n` together, because every
//! stepper needs both at the same point.

mod absorbing;
mod grid;
mod planar;
mod radial;
mod spherical;

pub use absorbing::Absorbing;
pub use grid::{GridError, GridMedium};
pub use planar::{ExponentialMedium, LinearMedium, UniformMedium};
pub use radial::{Axis, ParabolicFiber, RadialTable, SechFiber};
pub use spherical::{black_hole_deflection, BlackHole, FishEye, Luneburg};

use glam::DVec3;

/// The refractive index and its gradient at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IndexSample {
    /// Refractive index n (> 0).
    pub n: f64,
    /// Gradient ∇n (1/length).
    pub grad: DVec3,
}

impl IndexSample {
    /// A sample of a constant index.
    pub fn constant(n: f64) -> Self {
        Self {
            n,
            grad: DVec3::ZERO,
        }
    }

    /// F = ∇ln n = ∇n / n, the "force" of the ray equation dt̂/ds = F − t̂ (t̂·F) (1/length).
    pub fn log_gradient(&self) -> DVec3 {
        self.grad / self.n
    }
}

/// A refractive-index field: the question every curved-ray stepper asks.
///
/// Media do not disperse: all wavelengths share one path (grinlight's transport is not spectral).
pub trait Medium: Send + Sync {
    /// n and ∇n at `p`, or `None` where a ray is captured: the index is singular there or
    /// would not be positive (a black hole's horizon). Never returns a non-finite sample.
    fn sample(&self, p: DVec3) -> Option<IndexSample>;

    /// Absorption coefficient σa at `p` (1/length). Default: transparent.
    fn absorption(&self, _p: DVec3) -> f64 {
        0.0
    }

    /// The length over which ∇ln n changes appreciably near `p` (scene units): adaptive step
    /// control never takes a step longer than this, so no feature of the profile is stepped over.
    /// `f64::INFINITY` where ∇ln n is constant.
    fn step_hint(&self, p: DVec3) -> f64;

    /// True when n is constant everywhere: rays are straight and need no marching.
    fn is_uniform(&self) -> bool {
        false
    }
}

/// Optical path length ∫ n ds of a step between two samples `ds` apart (trapezoid rule,
/// second order in `ds`; exact for the constant and linear-along-the-path cases).
pub fn optical_path_length(a: &IndexSample, b: &IndexSample, ds: f64) -> f64 {
    0.5 * (a.n + b.n) * ds
}
