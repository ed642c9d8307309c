//! Wavelength as a physical quantity. Wavelengths are in nanometres (vacuum)
//! throughout, over the visible range [`LAMBDA_MIN`, `LAMBDA_MAX`] = 360–830 nm of the CIE
//! 1931 observer. Here: [`dispersion`] (a refractive index as a function of wavelength — seed
//! 004's media answer "which wavelengths share a path" with it: media whose index does not
//! depend on λ keep them all on one), [`emission`] (the shape of a light's spectrum, and
//! sampling a photon's wavelength from it), [`fluorophore`] (what emits light again at another
//! wavelength), [`binned`] (a density over wavelength drawn from where no closed form serves), [`colour`] (spectra to and from the linear sRGB of the images) and [`Hero`] (the wavelength a camera path takes where it meets dispersion).

pub mod binned;
pub mod colour;
pub mod dispersion;
pub mod emission;
pub mod excitation;
pub mod fluorophore;

pub use binned::Binned;
pub use dispersion::Dispersion;
pub use emission::Spectrum;
pub use excitation::Excitation;
pub use fluorophore::{Fluorophore, Reemitted};

use crate::color::Rgb;

/// Shortest wavelength transported, nm.
pub const LAMBDA_MIN: f64 = 360.0;
/// Longest wavelength transported, nm.
pub const LAMBDA_MAX: f64 = 830.0;

/// The wavelength at which an index is quoted when one number is wanted: the helium d line,
/// 587.5618 nm, where glass catalogues give n_d and the Abbe number is anchored. Camera paths
/// see every medium at this wavelength until they meet dispersion ([`Hero`]).
pub const LAMBDA_D: f64 = 587.5618;
/// Hydrogen F line (blue), nm: with C, the lines of the Abbe number V_d = (n_d − 1)/(n_F − n_C).
pub const LAMBDA_F: f64 = 486.1327;
/// Hydrogen C line (red), nm.
pub const LAMBDA_C: f64 = 656.2725;

/// A probability density over vacuum wavelength that a path may draw its wavelength from.
pub trait Density {
    /// The wavelength (nm) for uniform `u` in [0, 1).
    fn sample(&self, u: f64) -> f64;
    /// The density (1/nm) at `nm`.
    fn pdf(&self, nm: f64) -> f64;
}

impl Density for Spectrum {
    fn sample(&self, u: f64) -> f64 {
        Spectrum::sample(self, u)
    }
    fn pdf(&self, nm: f64) -> f64 {
        Spectrum::pdf(self, nm)
    }
}

impl Density for Binned {
    fn sample(&self, u: f64) -> f64 {
        Binned::sample(self, u)
    }
    fn pdf(&self, nm: f64) -> f64 {
        Binned::pdf(self, nm)
    }
}

/// A wavelength drawn for a path, with its probability density: the one wavelength the path
/// carries on from where it meets dispersion (Zhdanov et al.'s (2020) "subset of wavelengths that share a
/// path": all of them until then, one after). Drawn from the visible-importance density
/// p(λ) ∝ 1/cosh²(0.0072 (λ − 538 nm)) over [`LAMBDA_MIN`, `LAMBDA_MAX`] (Radziszewski et al.
/// 2009, as in pbrt-v4), which follows the eye's response and so keeps the colour noise of
/// the estimate [`Hero::sensor_weight`] low.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hero {
    /// Vacuum wavelength, nm.
    pub nm: f64,
    /// Its probability density, 1/nm.
    pub pdf: f64,
}

/// The rate of the visible-importance density, 1/nm.
const VISIBLE_RATE: f64 = 0.0072;
/// The centre of the visible-importance density, nm.
const VISIBLE_CENTRE: f64 = 538.0;

impl Hero {
    /// The wavelength for uniform `u` in [0, 1), by inverting the density's cumulative
    /// distribution (tanh(a(λ − c)) − tanh(a(λ_min − c))) / A.
    pub fn visible(u: f64) -> Hero {
        let lo = (VISIBLE_RATE * (LAMBDA_MIN - VISIBLE_CENTRE)).tanh();
        let hi = (VISIBLE_RATE * (LAMBDA_MAX - VISIBLE_CENTRE)).tanh();
        let t = (lo + u.clamp(0.0, 1.0) * (hi - lo)).clamp(lo, hi);
        let nm = (VISIBLE_CENTRE + t.atanh() / VISIBLE_RATE).clamp(LAMBDA_MIN, LAMBDA_MAX);
        Hero {
            nm,
            pdf: Self::visible_pdf(nm),
        }
    }

    /// The visible-importance density at `nm`, 1/nm (zero outside the range).
    pub fn visible_pdf(nm: f64) -> f64 {
        if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&nm) {
            return 0.0;
        }
        let lo = (VISIBLE_RATE * (LAMBDA_MIN - VISIBLE_CENTRE)).tanh();
        let hi = (VISIBLE_RATE * (LAMBDA_MAX - VISIBLE_CENTRE)).tanh();
        let c = (VISIBLE_RATE * (nm - VISIBLE_CENTRE)).cosh();
        VISIBLE_RATE / (hi - lo) / (c * c)
    }

    /// The wavelength for uniform `u` from the visible-importance density and `lines` in
    /// equal shares — a narrow line (a fluorophore's emission, a light's) is found by a share
    /// of the paths where the visible density alone would find it by a few — with the
    /// mixture's density; [`Hero::visible`] without lines.
    pub fn visible_or(lines: &[&dyn Density], u: f64) -> Hero {
        if lines.is_empty() {
            return Hero::visible(u);
        }
        let parts = (lines.len() + 1) as f64;
        let (part, v) = ((u * parts).floor().min(parts - 1.0), (u * parts).fract());
        let nm = match part as usize {
            0 => Hero::visible(v).nm,
            k => lines[k - 1].sample(v),
        };
        let pdf = lines
            .iter()
            .fold(Hero::visible_pdf(nm), |sum, line| sum + line.pdf(nm));
        Hero {
            nm,
            pdf: pdf / parts,
        }
    }

    /// r̄(λ)/p(λ) ([`colour::sensor`]): the linear sRGB a path's spectral radiance at this
    /// wavelength stands for — its expectation over the density is ∫ r̄ L dλ, the colour of
    /// the radiance L.
    pub fn sensor_weight(&self) -> Rgb {
        colour::sensor(self.nm) / self.pdf
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// χ² of 200 000 hero wavelengths in 47 bins of 10 nm against the density's bin masses
    /// (trapezoid of 1 nm sub-steps, 1e-6 accurate); the pdf integrates to 1. 46 degrees of
    /// freedom: the 0.1 % critical value is 81.4 (the seed is fixed).
    #[test]
    fn hero_wavelengths_follow_their_density() {
        let mass = |lo: f64| -> f64 {
            (0..100)
                .map(|k| Hero::visible_pdf(lo + 0.1 * (k as f64 + 0.5)) * 0.1)
                .sum()
        };
        let total: f64 = (0..47).map(|k| mass(LAMBDA_MIN + 10.0 * k as f64)).sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        let n = 200_000;
        let mut counts = [0u32; 47];
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(11);
        for _ in 0..n {
            let h = Hero::visible(rng.gen());
            assert!((h.pdf - Hero::visible_pdf(h.nm)).abs() < 1e-15);
            counts[(((h.nm - LAMBDA_MIN) / 10.0) as usize).min(46)] += 1;
        }
        let chi2: f64 = counts
            .iter()
            .enumerate()
            .map(|(k, &c)| {
                let e = n as f64 * mass(LAMBDA_MIN + 10.0 * k as f64);
                (c as f64 - e).powi(2) / e
            })
            .sum();
        assert!(chi2 < 81.4, "χ² {chi2}");
    }

    /// The hero's estimate of a colour is unbiased: the mean of r̄(λ)/p(λ)·S(λ) over hero
    /// wavelengths is ∫ r̄ S dλ — unit-power D65 gives white — within 4 standard errors.
    #[test]
    fn hero_estimates_are_unbiased() {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let n = 400_000;
        let (mut sum, mut sum2) = (glam::DVec3::ZERO, glam::DVec3::ZERO);
        for _ in 0..n {
            let h = Hero::visible(rng.gen());
            let x = (h.sensor_weight() * colour::d65(h.nm)).0;
            sum += x;
            sum2 += x * x;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).powf(0.5);
        let err = (mean - glam::DVec3::ONE).abs();
        assert!(err.cmple(4.0 * se).all(), "{mean} ± {se}");
    }
}
