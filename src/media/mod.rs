//! Gradient-index media: the [`Medium`] interface and its index profiles. A medium here only
//! bends light; what it absorbs, scatters and emits is `volume::Participating`, a floor above.
//!
//! Conventions: positions and lengths are in scene units; the index `n` is dimensionless and
//! its gradient has units of 1/length. A medium answers `n` and `∇n` together, because every
//! stepper needs both at the same point.

mod air;
mod density;
mod grid;
mod lattice;
mod parametric;
mod planar;
mod radial;
mod spherical;
mod table;

pub use air::{GridQuantity, GAS_CONSTANT, GLADSTONE_DALE_AIR, MOLAR_MASS_AIR, STANDARD_PRESSURE};
pub use density::{Density, LocalMajorant};
pub use grid::{GridMedium, Interpolation};
pub use lattice::{GridError, Lattice};
pub use parametric::{Parametric, WithMedium};
pub use planar::{ExponentialMedium, HeightTable, LinearMedium, UniformMedium};
pub use radial::{Axis, ParabolicFiber, RadialTable, SechFiber};
pub use spherical::{
    black_hole_deflection, schwarzschild_deflection_series, BlackHole, ExactBlackHole, FishEye,
    HyperbolicMedium, Luneburg,
};
pub use table::MonotoneCubic;

use glam::DVec3;

/// An index field of constant curvature, whose rays are circles found in closed form
/// ([`crate::curve::GeodesicRay::of`]): the transformation method where it is exact.
#[derive(Clone, Copy, Debug)]
pub enum ConstantCurvature<'m> {
    /// Positive curvature: Maxwell's fish-eye.
    FishEye(&'m FishEye),
    /// Negative curvature: the Poincaré ball.
    Hyperbolic(&'m HyperbolicMedium),
}

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
/// A `Medium` is the field at one wavelength. A dispersive medium is a family of them, one per
/// vacuum wavelength (`scene::Media::at_wavelength`); Zhdanov et al.'s (2020) question "which wavelengths
/// can share a path" is answered per medium by `scene::Media::is_dispersive` — all of them
/// through a medium that is not, one through a medium that is — and asked by the transport
/// where a path enters one (`transport::Tracer::disperses_in`, `disperses_at`).
pub trait Medium: Send + Sync {
    /// n and ∇n at `p`, or `None` where a ray is captured: the index is singular there or
    /// would not be positive (a black hole's horizon). Never returns a non-finite sample.
    fn sample(&self, p: DVec3) -> Option<IndexSample>;

    /// The length over which ∇ln n changes appreciably near `p` along unit `dir` (scene
    /// units): adaptive step control never takes a step longer than this, so no feature of
    /// the profile is stepped over. `f64::INFINITY` where ∇ln n is constant. Most profiles
    /// vary alike in every direction and ignore `dir`; a layered one allows long steps along
    /// its layers.
    fn step_hint(&self, p: DVec3, dir: DVec3) -> f64;

    /// True when n is constant everywhere: rays are straight and need no marching.
    fn is_uniform(&self) -> bool {
        false
    }

    /// The index field when it has constant curvature (the fish-eye, the hyperbolic medium) —
    /// its rays are then circles in closed form and `stepper = "linearize"` follows them
    /// without error. Default: None, no closed form.
    fn constant_curvature(&self) -> Option<ConstantCurvature<'_>> {
        None
    }

    /// Where the medium has a closed form ([`Medium::constant_curvature`]): an arclength a ray may go in
    /// one step of `stepper = "linearize"` whose optical path the closed form finds without
    /// ambiguity (scene units). Default: None.
    fn exact_reach(&self) -> Option<f64> {
        None
    }

    /// The centre when n depends only on the distance from it (every ray then stays in the
    /// plane of its direction and the centre: the deflection table applies). Default:
    /// None, not spherically symmetric.
    fn symmetry_center(&self) -> Option<DVec3> {
        None
    }
}
