//! A fluorophore: what emits light again after absorbing it — its emission line and its
//! quantum yield. Where it sits (dissolved in a medium, [`crate::volume::Fluorescence`], or a
//! layer on a surface, [`crate::material::FluorescentLayer`]) says how much light it absorbs.
//!
//! Of the photons it absorbs, the quantum yield q (∈ [0, 1]) are emitted again, the rest turn
//! into heat. An emitted photon's wavelength λ′ is drawn from the emission spectrum — the
//! distribution of the emitted photons' *number* over wavelength, as a fluorimeter records it —
//! whatever λ it was absorbed at (Kasha's rule). A photon's energy is hc/λ, so light of power P
//! absorbed at λ comes out as power P·λ/λ′ per photon emitted: the difference, the Stokes
//! shift's energy, is heat too (negative for an anti-Stokes photon, λ′ < λ, which takes its
//! excess from the material's heat). The fluorescence lifetime (nanoseconds) does not enter a
//! steady state and is not modelled.

use super::Spectrum;

/// What emits light again (see the module's notes).
#[derive(Clone, Debug)]
pub struct Fluorophore {
    /// The emitted photons' distribution over vacuum wavelength (by number).
    pub emission: Spectrum,
    /// Photons emitted per photon absorbed, in [0, 1].
    pub quantum_yield: f64,
}

/// A photon a fluorophore emitted: its wavelength, and its energy per unit of the absorbed
/// photon's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reemitted {
    /// Vacuum wavelength, nm.
    pub nm: f64,
    /// λ/λ′: the emitted photon's energy over the absorbed one's.
    pub energy: f64,
}

impl Fluorophore {
    /// q·ε(λ′)/λ′ at vacuum wavelength `nm` = λ′ (1/nm²): the light it emits at λ′, per nm,
    /// per unit of λ times the light of wavelength λ it absorbs — q of the absorbed photons,
    /// each with λ/λ′ of the absorbed energy.
    pub fn emitted(&self, nm: f64) -> f64 {
        self.quantum_yield * self.emission.pdf(nm) / nm
    }

    /// What becomes of a photon of wavelength `nm` it absorbed, for uniform `yield_u` and
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

    /// Photons absorbed at 420 nm by a fluorophore of yield 0.7 emitting a Gaussian line at
    /// 600 nm (FWHM 40): the share emitted is q, within 4 standard errors of 200 000 draws,
    /// and the power emitted per power absorbed is q·420·E[1/λ′], E by a 0.01 nm midpoint sum
    /// of the line's density (4 standard errors).
    #[test]
    fn a_fluorophore_emits_its_quantum_yield_and_pays_the_stokes_shift() {
        let dye = Fluorophore {
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
        let shape = &dye.emission.shape;
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
