//! A fluorophore dissolved in a medium: a dye that absorbs light and emits some of it again
//! at longer wavelengths, isotropically.
//!
//! **Absorption.** The dye absorbs light of vacuum wavelength λ at the rate σf(λ) (1/length),
//! uniformly through the medium: a path at λ meets the dye after an arclength drawn at that
//! rate, as it meets a scattering particle at σs (the two rates add; which one it met is
//! drawn in proportion to them, [`Fluorescence::share`]).
//!
//! **Emission.** Of the photons the dye absorbs, the quantum yield q (∈ [0, 1]) are emitted
//! again, the rest turn into heat. An emitted photon's wavelength λ′ is drawn from the
//! emission spectrum — the distribution of the emitted photons' *number* over wavelength, as a
//! fluorimeter records it — whatever λ it was absorbed at (Kasha's rule), and its direction
//! uniformly over the sphere. A photon's energy is hc/λ, so light of power P absorbed at λ
//! comes out as power P·λ/λ′ per photon emitted: the difference, the Stokes shift's energy, is
//! heat too (negative for an anti-Stokes photon, λ′ < λ, which takes its excess from the
//! medium's heat). The fluorescence lifetime (nanoseconds) does not enter a steady state and
//! is not modelled.
//!
//! **Re-absorption.** Emitted light travels on at λ′ and meets the dye at σf(λ′) like any
//! other light: where the emission spectrum overlaps the absorption, the dye absorbs its own
//! light again (what limits a luminescent solar concentrator).

use crate::spectrum::{Dispersion, Spectrum};

/// A dye in a medium (see the module's notes).
#[derive(Clone, Debug)]
pub struct Fluorescence {
    /// σf over vacuum wavelength (1/length, ≥ 0).
    pub absorption: Dispersion,
    /// The emitted photons' distribution over vacuum wavelength (by number).
    pub emission: Spectrum,
    /// Photons emitted per photon absorbed, in [0, 1].
    pub quantum_yield: f64,
}

/// A photon the dye emitted: its wavelength, and its power per unit of the power absorbed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reemitted {
    /// Vacuum wavelength, nm.
    pub nm: f64,
    /// λ/λ′: the emitted photon's energy over the absorbed one's.
    pub energy: f64,
}

impl Fluorescence {
    /// σf at vacuum wavelength `nm` (1/length).
    pub fn sigma(&self, nm: f64) -> f64 {
        self.absorption.at(nm).max(0.0)
    }

    /// The share of the collisions at `nm` that are the dye's, where the medium also scatters
    /// with `sigma_s` there: σf/(σs + σf) (0 where neither acts).
    pub fn share(&self, nm: f64, sigma_s: f64) -> f64 {
        let f = self.sigma(nm);
        match f + sigma_s > 0.0 {
            true => f / (f + sigma_s),
            false => 0.0,
        }
    }

    /// What becomes of a photon of wavelength `nm` the dye absorbed, for uniform `yield_u` and
    /// `nm_u`: emitted again (with probability q) at a wavelength drawn from the emission
    /// spectrum, or None: turned into heat.
    pub fn reemit(&self, nm: f64, yield_u: f64, nm_u: f64) -> Option<Reemitted> {
        (yield_u < self.quantum_yield).then(|| {
            let out = self.emission.sample(nm_u);
            Reemitted {
                nm: out,
                energy: nm / out,
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::emission::Shape;
    use rand::{Rng, SeedableRng};

    /// Photons absorbed at 420 nm by a dye of yield 0.7 emitting a Gaussian line at 600 nm
    /// (FWHM 40): the share emitted is q, within 4 standard errors of 200 000 draws, and the
    /// power emitted per power absorbed is q·420·E[1/λ′], E by a 0.01 nm midpoint sum of the
    /// line's density (4 standard errors).
    #[test]
    fn a_dye_emits_its_quantum_yield_and_pays_the_stokes_shift() {
        let dye = Fluorescence {
            absorption: Dispersion::Constant(1.0),
            emission: Spectrum::new(Shape::Gaussian {
                peak: 600.0,
                fwhm: 40.0,
            })
            .unwrap(),
            quantum_yield: 0.7,
        };
        let n = 200_000;
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(5);
        let (mut emitted, mut power, mut squares) = (0u32, 0.0, 0.0);
        for _ in 0..n {
            if let Some(r) = dye.reemit(420.0, rng.gen(), rng.gen()) {
                emitted += 1;
                power += r.energy;
                squares += r.energy * r.energy;
            }
        }
        let share = emitted as f64 / n as f64;
        let sigma = (0.7 * 0.3 / n as f64).sqrt();
        assert!((share - 0.7).abs() < 4.0 * sigma, "{share}");
        let shape = dye.emission.shape;
        let (mut mass, mut inverse) = (0.0, 0.0);
        for k in 0..47_000 {
            let nm = 360.0 + 0.01 * (k as f64 + 0.5);
            mass += shape.power(nm);
            inverse += shape.power(nm) / nm;
        }
        let expected = 0.7 * 420.0 * inverse / mass;
        let mean = power / n as f64;
        let sigma = ((squares / n as f64 - mean * mean) / n as f64).sqrt();
        assert!(
            (mean - expected).abs() < 4.0 * sigma,
            "{mean} vs {expected}"
        );
    }
}
