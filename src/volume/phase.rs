//! Phase functions: how a scattering medium redirects light at a scattering event.
//!
//! Convention: p(cos θ) per steradian, normalised over the sphere (∫ p dω = 1), with θ the
//! angle between the direction of travel before the event and after it (cos θ = 1: straight
//! on). Symmetric in the two directions, so light and importance use the same function.

use crate::polarization::{mueller, Element};
use crate::sampling::Frame;
use glam::DVec3;
use std::f64::consts::PI;

/// A phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Phase {
    /// The same in every direction: 1/(4π).
    Isotropic,
    /// Henyey and Greenstein's (1941), of mean cosine `g` ∈ (−1, 1):
    /// p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}); g > 0 scatters forward.
    HenyeyGreenstein {
        /// The mean cosine of the scattering angle.
        g: f64,
    },
    /// Rayleigh's, of light scattered by particles much smaller than its wavelength (molecules
    /// of air), for unpolarized light: p(cos θ) = 3 (1 + cos² θ) / (16π). Where the transport
    /// is polarized its Mueller matrix [`crate::polarization::mueller::rayleigh`] goes with it.
    Rayleigh,
}

impl Phase {
    /// p at the scattering angle of cosine `cos` (1/sr).
    pub fn eval(&self, cos: f64) -> f64 {
        match *self {
            Phase::Isotropic => 0.25 / PI,
            Phase::HenyeyGreenstein { g } => {
                let denom = (1.0 + g * g - 2.0 * g * cos.clamp(-1.0, 1.0)).max(f64::MIN_POSITIVE);
                (1.0 - g * g) / (4.0 * PI * denom * denom.sqrt())
            }
            Phase::Rayleigh => {
                let cos = cos.clamp(-1.0, 1.0);
                3.0 * (1.0 + cos * cos) / (16.0 * PI)
            }
        }
    }

    /// The density of a scattering from travel direction `before` into `after` (both unit).
    pub fn between(&self, before: DVec3, after: DVec3) -> f64 {
        self.eval(before.dot(after))
    }

    /// Whether scattering polarizes light ([`Phase::mueller`] is Some).
    pub fn polarizes(&self) -> bool {
        match self {
            Phase::Rayleigh => true,
            Phase::Isotropic | Phase::HenyeyGreenstein { .. } => false,
        }
    }

    /// The Mueller matrix of a scattering from travel direction `before` into `after` (both
    /// unit), in the basis of the scattering plane ([`mueller::rayleigh`]: x across both
    /// directions, any across them where they are parallel); None where it depolarizes —
    /// isotropic and Henyey–Greenstein scattering as grinlight defines them, for which polarized
    /// transport sends unpolarized light on.
    pub fn mueller(&self, before: DVec3, after: DVec3) -> Option<Element> {
        match self {
            Phase::Rayleigh => Some(Element::grey(
                mueller::rayleigh(before.dot(after)),
                before
                    .cross(after)
                    .try_normalize()
                    .unwrap_or_else(|| before.any_orthonormal_vector()),
            )),
            Phase::Isotropic | Phase::HenyeyGreenstein { .. } => None,
        }
    }

    /// A direction of travel after scattering, for light travelling along unit `before`,
    /// from uniform numbers `u`; drawn with density exactly [`Phase::between`], so a sample's
    /// weight p/pdf is 1.
    pub fn sample(&self, before: DVec3, u: (f64, f64)) -> DVec3 {
        let v = 2.0 * u.0 - 1.0;
        let cos = match *self {
            // The inverse of the CDF in cos θ, (1 + g² − ((1 − g²)/(1 + g v))²)/(2g) with
            // v = 2u − 1, expanded so that nothing cancels as g → 0 (where it tends to v).
            Phase::HenyeyGreenstein { g } => {
                let d = 1.0 + g * v;
                let num = v + g * (0.5 * (v * v + 3.0) + g * (v + 0.5 * g * (v * v - 1.0)));
                (num / (d * d)).clamp(-1.0, 1.0)
            }
            // The CDF in cos θ is (μ³ + 3μ + 4)/8 = u: the root of μ³ + 3μ = 4v by Cardano's
            // formula, μ = A − 1/A with A³ = 2v + √(4v² + 1); odd in v, and taken from |v|
            // so that nothing cancels for v < 0.
            Phase::Rayleigh => {
                let a = (2.0 * v.abs() + (4.0 * v * v + 1.0).sqrt()).cbrt();
                ((a - 1.0 / a) * v.signum()).clamp(-1.0, 1.0)
            }
            Phase::Isotropic => v,
        };
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u.1;
        Frame::new(before)
            .to_world(DVec3::new(sin * phi.cos(), sin * phi.sin(), cos))
            .normalize()
    }
}
