//! Plastic: a Lambertian base under a rough dielectric coat, as Mitsuba's `roughplastic`
//! models it (Jakob et al.; after Kelemen and Szirmay-Kalos 2001 and Weidlich and Wilkie
//! 2007). Light either reflects off the coat (its microsurface, the dielectric Fresnel term) or enters,
//! scatters in the base (albedo ρ) and among the coat's inner side, and leaves:
//!
//! f(ωo, ωi) = F(ωo·m) D(m) G₂ / (4 cos θi cos θo)
//!           + ρ (1 − E(μi)) (1 − E(μo)) / (π η² (1 − ρ F̄ᵢ)),
//!
//! where E(μ) is the coat's directional albedo (the specular lobe's reflected fraction at
//! cos θ = μ, tabulated once by quadrature over visible normals), 1 − E what enters, η the
//! coat's index relative to the outside, and F̄ᵢ = 1 − T̄/η² the inner side's mean reflectance
//! of diffuse light, T̄ = 2∫(1 − E(μ)) μ dμ (reciprocity: the inner mean transmittance is the
//! outer one over η²). Its albedo is E(μo) + (1 − E(μo)) ρx/(1 − ρ + ρx), x = T̄/η² — at most
//! 1, and 1 for ρ = 1: no energy is made, and a white plastic loses none.
//!
//! **Polarization** ([`Coat::element`]). The coat's reflection is its microfacet's Fresnel
//! reflection matrix. The diffuse part is light refracted into the coat, depolarized by the
//! base and refracted out, as Baek et al. (2018) and Mitsuba 3's `pplastic` model it: the
//! smooth coat's transmission matrices at the arriving and the leaving angle about the
//! surface's normal, a depolarizer between them. Its entry passes s and p light in the ratio
//! T_s/T_p of the angle the light arrives at, and its light leaves partly p-polarized, in the
//! plane of the normal and the light, by (T_p − T_s)/(T_p + T_s) of the angle it leaves at
//! (Atkinson and Hancock 2006). The part's scale stays the coat's 1 − E of the rough
//! microsurface above; only the matrices' shape is the smooth coat's.

use super::fresnel::dielectric;
use super::microfacet::Microsurface;
use super::{reflect, BsdfSample, Lobes};
use crate::color::Rgb;
use crate::polarization::{mueller, Element};
use crate::sampling::Frame;
use glam::{DMat4, DVec3, DVec4};
use std::f64::consts::FRAC_1_PI;

/// Nodes of the tabulated coat albedo E(μ), uniform in μ = cos θ over [0, 1].
const NODES: usize = 65;

/// A rough dielectric coat: its relative index, microsurface and tabulated albedo.
#[derive(Clone, Debug, PartialEq)]
pub struct Coat {
    /// The coat's index relative to the medium outside.
    pub eta: f64,
    /// Its microsurface.
    pub microsurface: Microsurface,
    /// E(μ) at μ = j/(NODES − 1).
    albedo: Vec<f64>,
    /// The inner side's mean reflectance F̄ᵢ of diffuse light.
    inner_reflectance: f64,
}

impl Coat {
    /// The coat of relative index `eta` (> 1) and roughness `microsurface`: tabulates E(μ) by a
    /// 64 × 64 midpoint rule over the visible normals' sampling square (smooth there) at each
    /// of 65 angles.
    pub fn new(eta: f64, microsurface: Microsurface) -> Self {
        let n = 64;
        let albedo: Vec<f64> = (0..NODES)
            .map(|j| {
                let mu = (j as f64 / (NODES - 1) as f64).max(1e-4);
                let o = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                let mut sum = 0.0;
                for a in 0..n {
                    for b in 0..n {
                        let u = ((a as f64 + 0.5) / n as f64, (b as f64 + 0.5) / n as f64);
                        let m = microsurface.sample_visible(o, u);
                        let i = reflect(-o, m);
                        if i.z > 0.0 {
                            sum += dielectric(o.dot(m), 1.0, eta).0 * microsurface.g2(i, o)
                                / microsurface.g1(o);
                        }
                    }
                }
                sum / (n * n) as f64
            })
            .collect();
        // T̄ = 2∫(1 − E) μ dμ by the trapezoid rule on the nodes.
        let h = 1.0 / (NODES - 1) as f64;
        let t_mean = 2.0
            * h
            * (0..NODES)
                .map(|j| {
                    let w = if j == 0 || j == NODES - 1 { 0.5 } else { 1.0 };
                    w * (1.0 - albedo[j]) * j as f64 * h
                })
                .sum::<f64>();
        Self {
            eta,
            microsurface,
            albedo,
            inner_reflectance: 1.0 - t_mean / (eta * eta),
        }
    }

    /// E(μ): the fraction the coat's specular lobe reflects at cos θ = `mu`.
    pub fn coat_albedo(&self, mu: f64) -> f64 {
        let x = mu.clamp(0.0, 1.0) * (NODES - 1) as f64;
        let j = (x as usize).min(NODES - 2);
        let t = x - j as f64;
        self.albedo[j] * (1.0 - t) + self.albedo[j + 1] * t
    }

    /// f(o, i) in the local frame (both above the surface).
    pub(super) fn f(&self, o: DVec3, i: DVec3, albedo: Rgb) -> Rgb {
        let m = (o + i).normalize();
        let specular = dielectric(o.dot(m), 1.0, self.eta).0
            * self.microsurface.d(m)
            * self.microsurface.g2(i, o)
            / (4.0 * i.z * o.z);
        self.leaving(o.z, albedo) * self.entering(i.z) + Rgb::splat(specular)
    }

    /// The Mueller matrices per channel of the plastic of base albedo `albedo` about unit
    /// normal `n` for light arriving from unit `from` and leaving toward unit `to` (both
    /// pointing away from the surface), whose first element is f — the same both ways, as f
    /// is — in the basis across the plane of the two directions on both sides (see the
    /// module's notes); None unless both lie above the surface.
    pub fn element(&self, albedo: Rgb, n: DVec3, from: DVec3, to: DVec3) -> Option<Element> {
        let frame = Frame::new(n);
        let (a, l) = (frame.to_local(from), frame.to_local(to));
        if a.z <= 0.0 || l.z <= 0.0 {
            return None;
        }
        let across = from
            .cross(to)
            .try_normalize()
            .unwrap_or_else(|| to.any_orthonormal_vector());
        let m = (a + l).normalize();
        let specular = mueller::dielectric_reflection(a.dot(m), 1.0, self.eta)
            * (self.microsurface.d(m) * self.microsurface.g2(a, l) / (4.0 * a.z * l.z));
        // The diffuse part's entry (a row: what it takes of the light arriving along −from)
        // and exit (a column: the light leaving along `to`), each (1, b, 0, 0) in the basis of
        // its own plane of incidence, turned into the basis across both directions.
        let transmitted = |w: DVec3| -> (DVec4, Option<DVec3>) {
            let t = mueller::dielectric_transmission(w.dot(n).min(1.0), 1.0, self.eta).col(0);
            // Grazing, where the coat lets nothing through, s and p alike.
            let b = if t.x > 0.0 { t.y / t.x } else { 0.0 };
            let shape = DVec4::new(1.0, b, 0.0, 0.0);
            (shape, w.cross(n).try_normalize())
        };
        let exit = match transmitted(to) {
            (shape, Some(s)) => mueller::basis_change(to, s, across).map_or(shape, |t| t.0 * shape),
            // Square to the surface s and p are alike: b = 0, any basis.
            (shape, None) => shape,
        };
        let entry = match transmitted(from) {
            (shape, Some(s)) => {
                mueller::basis_change(-from, across, s).map_or(shape, |t| t.0.transpose() * shape)
            }
            (shape, None) => shape,
        };
        let diffuse = DMat4::from_cols(
            entry.x * exit,
            entry.y * exit,
            entry.z * exit,
            entry.w * exit,
        );
        let f = self.leaving(l.z, albedo) * self.entering(a.z);
        Some(Element {
            mueller: [f.0.x, f.0.y, f.0.z].map(|f| specular + diffuse * f),
            x: across,
            x_leaving: across,
        })
    }

    /// The diffuse part's factor of the light arriving at cos θi = `mu`: the share 1 − E(μ)
    /// the coat lets in to the base.
    pub fn entering(&self, mu: f64) -> f64 {
        1.0 - self.coat_albedo(mu)
    }

    /// The diffuse part's factor toward cos θo = `mu` (1/sr): ρ (1 − E(μo)) / (π η² (1 − ρ
    /// F̄ᵢ)), so that the diffuse part of f is `leaving(μo)·entering(μi)`.
    pub fn leaving(&self, mu: f64, albedo: Rgb) -> Rgb {
        albedo * (self.entering(mu) * FRAC_1_PI / (self.eta * self.eta))
            / (Rgb::ONE - albedo * self.inner_reflectance)
    }

    /// The coat's lobe alone sampled at `o` (local) for uniform numbers `u`, played for with
    /// the probability E(μo) it reflects (u.2 decides): a direction (local) with weight
    /// F·G₂/(G₁·E(μo)), whose mean over the lobe is 1, and pdf E(μo)·D_ωo(m)/(4 o·m) — an
    /// unbiased estimate of the light the coat's lobe reflects that spends a ray only as
    /// often as the coat reflects. None when the play is lost or the direction goes below
    /// the surface.
    pub(super) fn sample_lobe(&self, o: DVec3, u: (f64, f64, f64)) -> Option<BsdfSample> {
        let e = self.coat_albedo(o.z);
        if u.2 >= e {
            return None;
        }
        let m = self.microsurface.sample_visible(o, (u.0, u.1));
        let i = reflect(-o, m);
        if i.z <= 0.0 {
            return None;
        }
        let weight = dielectric(o.dot(m), 1.0, self.eta).0 * self.microsurface.g2(i, o)
            / self.microsurface.g1(o);
        let pdf = e * self.microsurface.visible_d(o, m) / (4.0 * o.dot(m));
        Some(BsdfSample {
            wi: i,
            weight: Rgb::splat(weight / e),
            pdf,
            lobe: Lobes::GLOSSY_REFLECTION,
        })
    }

    /// The probability of sampling the coat's lobe at cos θo = `mu`: its share of the
    /// reflected light for a grey base of the albedo's mean.
    pub(super) fn specular_probability(&self, mu: f64, albedo: Rgb) -> f64 {
        let e = self.coat_albedo(mu);
        let d = (1.0 - e) * albedo.mean().clamp(0.0, 1.0);
        if e + d > 0.0 {
            (e / (e + d)).clamp(0.05, 0.95)
        } else {
            1.0
        }
    }

    /// The mixture's pdf for `i` given `o` and the coat's probability `p`.
    pub(super) fn pdf(&self, o: DVec3, i: DVec3, p: f64) -> f64 {
        let m = (o + i).normalize();
        let specular = self.microsurface.visible_d(o, m) / (4.0 * o.dot(m));
        p * specular + (1.0 - p) * i.z.max(0.0) * FRAC_1_PI
    }
}
