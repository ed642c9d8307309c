//! What a fluorophore absorbs over vacuum wavelength, as a camera path draws the wavelength it
//! absorbs at: f(λ) — a fluorescent layer's absorbed share a(λ), a dye's absorption coefficient
//! σf(λ) — and the density in proportion to f(λ)·λ, the number of photons it absorbs over
//! wavelength under equal-energy light (a photon's energy is hc/λ).
//!
//! A camera path that meets a fluorophore's light at λ′ goes on at an excitation wavelength λ
//! weighed q·ε(λ′)/λ′ · f(λ)·λ/p(λ) ([`super::Fluorophore::emitted`] times
//! [`Excitation::draw`]'s ratio): p draws λ in equal shares from f(λ)·λ and from f(λ)·λ·s(λ),
//! s the light the scene's sources emit, so that a narrow line of a light is found where it
//! excites and light the scene colours on its way is still found.

use super::{Binned, Dispersion, LAMBDA_MAX, LAMBDA_MIN};

/// A fluorophore's absorption over wavelength (see the module's notes).
#[derive(Clone, Debug)]
pub struct Excitation {
    /// f(λ), read within [0, `most`].
    form: Dispersion,
    /// The largest value f is read at (1 for a share; ∞ for a coefficient).
    most: f64,
    /// The density ∝ f(λ)·λ.
    absorbing: Binned,
    /// ∫ f(λ)·λ dλ over the transported range (1 nm midpoint sums), nm² times f's unit.
    integral: f64,
}

impl Excitation {
    /// The absorption `form`, read within [0, `most`]; None where it absorbs nothing from 360
    /// to 830 nm.
    pub fn new(form: Dispersion, most: f64) -> Option<Self> {
        let f = |nm: f64| form.at(nm).clamp(0.0, most);
        let absorbing = Binned::new(|nm| f(nm) * nm)?;
        let bins = (LAMBDA_MAX - LAMBDA_MIN) as usize;
        let integral = (0..bins)
            .map(|i| {
                let nm = LAMBDA_MIN + i as f64 + 0.5;
                f(nm) * nm
            })
            .sum();
        Some(Self {
            form,
            most,
            absorbing,
            integral,
        })
    }

    /// f at vacuum wavelength `nm`, within [0, most].
    pub fn at(&self, nm: f64) -> f64 {
        self.form.at(nm).clamp(0.0, self.most)
    }

    /// ∫ f(λ)·λ dλ (nm² times f's unit).
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// An excitation wavelength for uniform `u`, from f(λ)·λ and `excited` (the density of the
    /// light it absorbs from the scene's sources; None: f(λ)·λ alone) in equal shares, and
    /// f(λ)·λ/p(λ) there (0 where p is).
    pub fn draw(&self, excited: Option<&Binned>, u: f64) -> (f64, f64) {
        let nm = match excited {
            Some(s) if u >= 0.5 => s.sample(2.0 * u - 1.0),
            Some(_) => self.absorbing.sample(2.0 * u),
            None => self.absorbing.sample(u),
        };
        let pdf = match excited {
            Some(s) => 0.5 * (self.absorbing.pdf(nm) + s.pdf(nm)),
            None => self.absorbing.pdf(nm),
        };
        match pdf > 0.0 {
            true => (nm, self.at(nm) * nm / pdf),
            false => (nm, 0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The draw's ratio is an unbiased estimate of ∫ f(λ)·λ·g(λ) dλ for any g, with and
    /// without the sources' share: for σf = 3·(450/λ)⁴ and g(λ) = λ/500, E[ratio·g] against a
    /// 0.01 nm midpoint sum, within 4 standard errors of 10⁶ draws.
    #[test]
    fn the_excitation_draw_weighs_what_it_draws_by_its_density() {
        let form = Dispersion::PowerLaw {
            value: 3.0,
            nm: 450.0,
            exponent: 4.0,
        };
        let e = Excitation::new(form, f64::INFINITY).expect("it absorbs");
        let g = |nm: f64| nm / 500.0;
        let expected: f64 = (0..47_000)
            .map(|i| LAMBDA_MIN + (i as f64 + 0.5) * 0.01)
            .map(|nm| e.at(nm) * nm * g(nm) * 0.01)
            .sum();
        let sources = Binned::new(|nm| (nm - 360.0).max(0.0)).expect("a density");
        for excited in [None, Some(&sources)] {
            let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
            let n = 1_000_000;
            let (mut sum, mut sq) = (0.0, 0.0);
            for _ in 0..n {
                let (nm, ratio) = e.draw(excited, rng.gen());
                let v = ratio * g(nm);
                sum += v;
                sq += v * v;
            }
            let mean = sum / n as f64;
            let error = ((sq / n as f64 - mean * mean) / n as f64).sqrt();
            assert!(
                (mean - expected).abs() < 4.0 * error,
                "{mean} ± {error} against {expected}"
            );
        }
    }
}
