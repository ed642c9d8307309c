//! Microfacet distributions — GGX (Trowbridge–Reitz) and Beckmann — with Smith's
//! height-correlated masking–shadowing, in a local shading frame where the macro-surface
//! normal is +z.
//!
//! - GGX: D(m) = 1 / (π αx αy (mx²/αx² + my²/αy² + mz²)²),
//!   Λ(ω) = (−1 + √(1 + (αx² ωx² + αy² ωy²)/ωz²)) / 2;
//! - Beckmann: D(m) = exp(−(mx²/αx² + my²/αy²)/mz²) / (π αx αy mz⁴) (Gaussian slopes),
//!   Λ(ω) = (e^(−a²)/(a√π) − erfc(a)) / 2 with a = |ωz| / √(αx² ωx² + αy² ωy²)
//!   (Walter et al. 2007);
//! - both normalised so ∫ D(m) mz dm = 1; G₁(ω) = 1/(1 + Λ(ω)),
//!   G₂(ωi, ωo) = 1/(1 + Λ(ωi) + Λ(ωo)) (Heitz 2014, the height-correlated form);
//! - visible normals D_ωo(m) = G₁(ωo) max(0, ωo·m) D(m) / ωo,z, sampled exactly for any ωo:
//!   ωo is stretched to the unit-roughness configuration, a visible normal drawn there, and the
//!   result unstretched — GGX's by Heitz's (2018) projected hemisphere, Beckmann's by its
//!   slopes (Heitz and d'Eon 2014): one Gaussian slope across ωo's plane and one along it,
//!   whose density (cos θo − x sin θo)⁺ e^(−x²)/√π is inverted by safeguarded Newton steps on
//!   its closed-form cumulative distribution ([`slope_quantile`]).
//!
//! Directions are unit vectors; α is dimensionless (the RMS slope / √2 of the microsurface for
//! Beckmann; GGX's α has the same meaning for its peak).

use glam::DVec3;
use std::f64::consts::PI;

/// Below this α a surface is treated as smooth (a delta lobe): D's peak, 1/(πα²), passes
/// 3·10⁵ and its samples could no longer be told from the mirror direction in f64 work.
pub const SMOOTH_ALPHA: f64 = 1e-3;

/// How a microsurface's normals are distributed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// GGX (Trowbridge–Reitz): long tails.
    Ggx,
    /// Beckmann: Gaussian slopes.
    Beckmann,
}

impl Distribution {
    /// Every distribution.
    pub const ALL: [Distribution; 2] = [Distribution::Ggx, Distribution::Beckmann];

    /// Its name in a scene's `distribution` key.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Ggx => "ggx",
            Distribution::Beckmann => "beckmann",
        }
    }

    /// The distribution called `name`.
    pub fn named(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|d| d.name() == name)
    }
}

/// A microsurface: its distribution of normals, of roughness (αx, αy) along the frame's x and
/// y axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microsurface {
    /// How its normals are distributed.
    pub distribution: Distribution,
    /// Roughness along x.
    pub alpha_x: f64,
    /// Roughness along y.
    pub alpha_y: f64,
}

impl Microsurface {
    /// An isotropic GGX microsurface of roughness `alpha`.
    pub fn ggx(alpha: f64) -> Self {
        Self::isotropic(Distribution::Ggx, alpha)
    }

    /// An isotropic Beckmann microsurface of roughness `alpha`.
    pub fn beckmann(alpha: f64) -> Self {
        Self::isotropic(Distribution::Beckmann, alpha)
    }

    /// An isotropic microsurface of `distribution` and roughness `alpha`.
    pub fn isotropic(distribution: Distribution, alpha: f64) -> Self {
        Self {
            distribution,
            alpha_x: alpha,
            alpha_y: alpha,
        }
    }

    /// The microsurface of `distribution` and roughness `alpha` = [αx, αy], or None where both
    /// are below [`SMOOTH_ALPHA`] (the surface is smooth). Each α is at least [`SMOOTH_ALPHA`].
    pub fn rough(distribution: Distribution, alpha: [f64; 2]) -> Option<Self> {
        (alpha[0].max(alpha[1]) >= SMOOTH_ALPHA).then(|| Self {
            distribution,
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
        let slopes2 = (m.x / ax).powi(2) + (m.y / ay).powi(2);
        let z2 = m.z * m.z;
        match self.distribution {
            Distribution::Ggx => {
                let e = slopes2 + z2;
                1.0 / (PI * ax * ay * e * e)
            }
            Distribution::Beckmann => (-slopes2 / z2).exp() / (PI * ax * ay * z2 * z2),
        }
    }

    /// Smith's Λ(ω) (of |ωz|: the same seen from below).
    pub fn lambda(&self, w: DVec3) -> f64 {
        let z2 = w.z * w.z;
        if z2 == 0.0 {
            return f64::INFINITY;
        }
        let across2 = (self.alpha_x * w.x).powi(2) + (self.alpha_y * w.y).powi(2);
        match self.distribution {
            Distribution::Ggx => 0.5 * ((1.0 + across2 / z2).sqrt() - 1.0),
            Distribution::Beckmann => {
                if across2 == 0.0 {
                    return 0.0;
                }
                let a = (z2 / across2).sqrt();
                0.5 * ((-a * a).exp() / (a * PI.sqrt()) - libm::erfc(a))
            }
        }
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
    /// D(m), for uniform `u` in [0, 1)². Any unit `wo` — also below the horizon, where a ray
    /// going up meets the microsurface ([`super::walk`]; χ² against the density in
    /// `tests/bsdf.rs`).
    pub fn sample_visible(&self, wo: DVec3, u: (f64, f64)) -> DVec3 {
        let v = DVec3::new(self.alpha_x * wo.x, self.alpha_y * wo.y, wo.z).normalize();
        match self.distribution {
            Distribution::Ggx => self.ggx_visible(v, u),
            Distribution::Beckmann => self.beckmann_visible(v, u),
        }
    }

    /// GGX's visible normal from the stretched direction `v` (Heitz 2018).
    fn ggx_visible(&self, v: DVec3, u: (f64, f64)) -> DVec3 {
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

    /// Beckmann's visible normal from the stretched direction `v`: in the frame turned to v's
    /// azimuth, the slope along v's plane from (cos θ − x sin θ)⁺ e^(−x²)/√π, the slope across
    /// it Gaussian (e^(−y²)/√π); turned back and unstretched, the normal (−x, −y, 1) normalised.
    fn beckmann_visible(&self, v: DVec3, u: (f64, f64)) -> DVec3 {
        let sin = (v.x * v.x + v.y * v.y).sqrt();
        let (cos_phi, sin_phi) = match sin > 0.0 {
            true => (v.x / sin, v.y / sin),
            false => (1.0, 0.0),
        };
        let along = slope_quantile(v.z, sin, u.0);
        let across = slope_quantile(1.0, 0.0, u.1);
        let sx = (cos_phi * along - sin_phi * across) * self.alpha_x;
        let sy = (sin_phi * along + cos_phi * across) * self.alpha_y;
        DVec3::new(-sx, -sy, 1.0).normalize()
    }
}

/// The slope x whose share of the density (c − s x)⁺ e^(−x²)/√π (s ≥ 0, c² + s² = 1: a
/// direction at cos θ = c seen over Gaussian slopes; c = 1, s = 0 is the Gaussian itself) below
/// it is `u` ∈ [0, 1). Its cumulative distribution is G(x) = c·erfc(−x)/2 + s·e^(−x²)/(2√π) up
/// to x = c/s, where the density ends; G is read in logarithms (e^(−x²) times the scaled
/// erfcx, which neither underflows nor cancels where the visible slopes lie far out, a
/// direction from just below the horizon), and ln G(x) = ln u + ln G(end) solved by Newton
/// steps kept inside a shrinking bracket (bisection where a step would leave it), to 1e-13.
/// The bracket's ends, min(c/s, 8) and min(c/s, 0) − 8, leave out less than e^(−64) of it.
pub fn slope_quantile(c: f64, s: f64, u: f64) -> f64 {
    let end = if s > 0.0 { c / s } else { f64::INFINITY };
    let (mut lo, mut hi) = (end.min(0.0) - 8.0, end.min(8.0));
    // ln(2√π G(x)) + x² and d ln G/dx.
    let scaled = |x: f64| c * PI.sqrt() * erfcx(-x) + s;
    let ln_g = |x: f64| scaled(x).max(f64::MIN_POSITIVE).ln() - x * x;
    let target = u.ln() + ln_g(hi);
    if target <= ln_g(lo) {
        return lo;
    }
    let mut x = 0.5 * (lo + hi);
    for _ in 0..200 {
        let f = ln_g(x) - target;
        match f > 0.0 {
            true => hi = x,
            false => lo = x,
        }
        let slope = 2.0 * (c - s * x) / scaled(x);
        let newton = x - f / slope;
        let next = match newton > lo && newton < hi && slope > 0.0 {
            true => newton,
            false => 0.5 * (lo + hi),
        };
        if (next - x).abs() <= 1e-13 * (1.0 + x.abs()) || hi - lo <= 1e-13 * (1.0 + x.abs()) {
            return next;
        }
        x = next;
    }
    x
}

/// The scaled complementary error function erfcx(z) = e^(z²) erfc(z), for z ≥ −8 (as
/// [`slope_quantile`] needs): directly up to z = 20, then its asymptotic series
/// 1/(z√π) Σ (−1)^k (2k − 1)!!/(2z²)^k, whose terms fall below 1e-16 of the sum by the tenth.
fn erfcx(z: f64) -> f64 {
    if z < 0.0 {
        return 2.0 * (z * z).exp() - erfcx(-z);
    }
    if z < 20.0 {
        return (z * z).exp() * libm::erfc(z);
    }
    let (mut term, mut sum) = (1.0, 1.0);
    for k in 1..12 {
        term *= -((2 * k - 1) as f64) / (2.0 * z * z);
        sum += term;
    }
    sum / (z * PI.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// erfcx's series takes over from e^(z²) erfc(z) at 20 without a seam (1e-13), and matches
    /// it where both hold (z = 15: 1e-13); erfcx(0) = 1 and erfcx(−z) = 2e^(z²) − erfcx(z).
    #[test]
    fn the_scaled_complementary_error_function() {
        let direct = |z: f64| (z * z).exp() * libm::erfc(z);
        assert!((erfcx(0.0) - 1.0).abs() < 1e-15);
        for z in [15.0, 19.999, 20.0, 20.001] {
            let (a, b) = (erfcx(z), direct(z));
            assert!((a - b).abs() <= 1e-13 * b, "z {z}: {a} vs {b}");
        }
        for z in [0.5f64, 3.0, 7.5] {
            let (a, b) = (erfcx(-z), 2.0 * (z * z).exp() - direct(z));
            assert!((a - b).abs() <= 1e-13 * b, "−{z}: {a} vs {b}");
        }
    }

    /// The slope quantile inverts its closed-form distribution, G(x)/G(end) = u to 1e-10, for
    /// directions from overhead to just below the horizon and from below it (c = −0.99,
    /// where the visible slopes lie beyond 7); the Gaussian's is erf⁻¹(2u − 1)
    /// (erf⁻¹(0.95) = 1.3859038243496777, Abramowitz and Stegun's table).
    #[test]
    fn slope_quantiles_invert_their_distribution() {
        let g = |c: f64, s: f64, x: f64| {
            c * libm::erfc(-x) / 2.0 + s * (-x * x).exp() / (2.0 * PI.sqrt())
        };
        assert!((slope_quantile(1.0, 0.0, 0.975) - 1.385_903_824_349_677_7).abs() < 1e-12);
        for c in [1.0f64, 0.9, 0.5, 0.1, 0.0, -0.3, -0.9, -0.99] {
            let s = (1.0 - c * c).sqrt();
            let end = if s > 0.0 { (c / s).min(8.0) } else { 8.0 };
            for u in [1e-9, 0.01, 0.3, 0.5, 0.77, 0.999, 1.0 - 1e-9] {
                let x = slope_quantile(c, s, u);
                assert!(x <= end, "c {c} u {u}: {x} beyond {end}");
                let share = g(c, s, x) / g(c, s, end);
                assert!(
                    (share - u).abs() <= 1e-10 * u.max(1e-3),
                    "c {c} u {u}: {share}"
                );
            }
        }
    }
}
