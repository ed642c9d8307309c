//! The GGX (Trowbridge–Reitz) microfacet distribution with Smith's height-correlated
//! masking–shadowing, in a local shading frame where the macro-surface normal is +z.
//!
//! - D(m) = 1 / (π αx αy (mx²/αx² + my²/αy² + mz²)²), normalised so ∫ D(m) mz dm = 1;
//! - Λ(ω) = (−1 + √(1 + (αx² ωx² + αy² ωy²)/ωz²)) / 2, G₁(ω) = 1/(1 + Λ(ω)),
//!   G₂(ωi, ωo) = 1/(1 + Λ(ωi) + Λ(ωo)) (Heitz 2014, the height-correlated form);
//! - visible normals D_ωo(m) = G₁(ωo) max(0, ωo·m) D(m) / ωo,z, sampled exactly by Heitz's
//!   (2018) method: stretch ωo to the unit-roughness configuration, sample the projected
//!   hemisphere, unstretch.
//!
//! Directions are unit vectors; α is dimensionless (the RMS slope / √2 of the microsurface).

use glam::DVec3;
use std::f64::consts::PI;

/// Below this α a surface is treated as smooth (a delta lobe): D's peak, 1/(πα²), passes
/// 3·10⁵ and its samples could no longer be told from the mirror direction in f64 work.
pub const SMOOTH_ALPHA: f64 = 1e-3;

/// A GGX distribution of roughness (αx, αy) along the frame's x and y axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    /// Roughness along x.
    pub alpha_x: f64,
    /// Roughness along y.
    pub alpha_y: f64,
}

impl Ggx {
    /// An isotropic distribution of roughness `alpha`.
    pub fn isotropic(alpha: f64) -> Self {
        Self {
            alpha_x: alpha,
            alpha_y: alpha,
        }
    }

    /// The distribution of roughness `alpha` = [αx, αy], or None where both are below
    /// [`SMOOTH_ALPHA`] (the surface is smooth). Each α is at least [`SMOOTH_ALPHA`].
    pub fn rough(alpha: [f64; 2]) -> Option<Self> {
        (alpha[0].max(alpha[1]) >= SMOOTH_ALPHA).then(|| Self {
            alpha_x: alpha[0].max(SMOOTH_ALPHA),
            alpha_y: alpha[1].max(SMOOTH_ALPHA),
        })
    }

    /// D(m) for a unit microfacet normal `m` (1/sr); 0 below the surface.
    pub fn d(&self, m: DVec3) -> f64 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let (ax, ay) = (self.alpha_x, self.alpha_y);
        let e = (m.x / ax).powi(2) + (m.y / ay).powi(2) + m.z * m.z;
        1.0 / (PI * ax * ay * e * e)
    }

    /// Smith's Λ(ω).
    pub fn lambda(&self, w: DVec3) -> f64 {
        let z2 = w.z * w.z;
        if z2 == 0.0 {
            return f64::INFINITY;
        }
        let t2 = ((self.alpha_x * w.x).powi(2) + (self.alpha_y * w.y).powi(2)) / z2;
        0.5 * ((1.0 + t2).sqrt() - 1.0)
    }

    /// G₁(ω) = 1/(1 + Λ(ω)): the fraction of the microsurface visible from ω.
    pub fn g1(&self, w: DVec3) -> f64 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// G₂(ωi, ωo) = 1/(1 + Λ(ωi) + Λ(ωo)), height-correlated.
    pub fn g2(&self, wi: DVec3, wo: DVec3) -> f64 {
        1.0 / (1.0 + self.lambda(wi) + self.lambda(wo))
    }

    /// G₂ of a transmission, light arriving from `wo` above the surface and leaving along
    /// `wi` below it: with correlated heights (uniform in [−1, 1]), the ray refracted at
    /// height h leaves downward unstopped with probability (1 − C₁(h))^Λ(ωi) while ωo saw h
    /// with C₁(h)^Λ(ωo), so G₂ = ∫₀¹ c^Λo (1 − c)^Λi dc = B(1 + Λo, 1 + Λi) (Euler's beta
    /// function; Heitz 2014 §6). At most 1/(1 + Λo + Λi), the reflection's.
    pub fn g2_transmission(&self, wi: DVec3, wo: DVec3) -> f64 {
        let (a, b) = (self.lambda(wo), self.lambda(wi));
        if !(a.is_finite() && b.is_finite()) {
            return 0.0;
        }
        (libm::lgamma(1.0 + a) + libm::lgamma(1.0 + b) - libm::lgamma(2.0 + a + b)).exp()
    }

    /// The density of visible normals D_ωo(m) seen from `wo` (wo.z > 0), 1/sr.
    pub fn visible_d(&self, wo: DVec3, m: DVec3) -> f64 {
        let cos = wo.dot(m);
        if wo.z <= 0.0 || cos <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * cos * self.d(m) / wo.z
    }

    /// A microfacet normal drawn from the normals visible from `wo`, density ∝ max(0, wo·m)
    /// D(m), for uniform `u` in [0, 1)² (Heitz 2018). Any unit `wo` — also below the
    /// horizon, where a ray going up meets the microsurface ([`super::walk`]; χ² against the
    /// density in `tests/bsdf.rs`).
    pub fn sample_visible(&self, wo: DVec3, u: (f64, f64)) -> DVec3 {
        let v = DVec3::new(self.alpha_x * wo.x, self.alpha_y * wo.y, wo.z).normalize();
        let len2 = v.x * v.x + v.y * v.y;
        let t1 = if len2 > 0.0 {
            DVec3::new(-v.y, v.x, 0.0) / len2.sqrt()
        } else {
            DVec3::X
        };
        let t2 = v.cross(t1);
        let r = u.0.sqrt();
        let phi = 2.0 * PI * u.1;
        let p1 = r * phi.cos();
        let s = 0.5 * (1.0 + v.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
        let h = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * v;
        DVec3::new(self.alpha_x * h.x, self.alpha_y * h.y, h.z.max(1e-12)).normalize()
    }
}
