//! Gradient-index media: the [`Medium`] interface and its index profiles.
//!
//! Conventions: positions and lengths are in scene units; the index `n` is dimensionless and
//! its gradient has units of 1/length. A medium answers `n` and `∇n` together, because every
//! stepper needs both at the same point.

mod absorbing;
mod air;
mod density;
mod grid;
mod lattice;
mod planar;
mod radial;
mod spherical;
mod table;

pub use absorbing::Absorbing;
pub use air::{GridQuantity, GAS_CONSTANT, GLADSTONE_DALE_AIR, MOLAR_MASS_AIR, STANDARD_PRESSURE};
pub use density::{Density, LocalMajorant};
pub use grid::{GridMedium, Interpolation};
pub use lattice::{GridError, Lattice};
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

    /// Absorption coefficient σa at `p` (1/length). Default: transparent.
    fn absorption(&self, _p: DVec3) -> f64 {
        0.0
    }

    /// Whether σa may be non-zero anywhere. False lets every path skip its optical depth;
    /// the default is true, so a medium that overrides [`Medium::absorption`] cannot be
    /// taken for transparent by mistake (every transparent profile here says false).
    fn absorbs(&self) -> bool {
        true
    }

    /// Optical depth ∫ σa ds of absorption along the straight segment from `from` along unit
    /// `dir` over `length` (exp(−depth) of the light is kept). Default: 8-point Gauss–Legendre
    /// quadrature of [`Medium::absorption`] (exact for σa polynomial of degree ≤ 15 along the
    /// segment); 0 for a medium that does not absorb.
    fn optical_depth(&self, from: DVec3, dir: DVec3, length: f64) -> f64 {
        if !self.absorbs() || length <= 0.0 {
            return 0.0;
        }
        gauss_legendre_8(|s| self.absorption(from + dir * s), length)
    }

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

/// ∫₀ᴸ f(s) ds by 8-point Gauss–Legendre quadrature.
fn gauss_legendre_8(f: impl Fn(f64) -> f64, length: f64) -> f64 {
    // Nodes on [−1, 1] (positive half) and weights, Abramowitz & Stegun table 25.4.
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let half = 0.5 * length;
    X.iter()
        .zip(W)
        .map(|(x, w)| w * (f(half * (1.0 - x)) + f(half * (1.0 + x))))
        .sum::<f64>()
        * half
}
