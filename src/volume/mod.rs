//! Scattering in media: a medium's radiometry beside its index field ([`crate::media`]).
//! A medium may scatter light with coefficient σs (1/length, per RGB channel) and a
//! [`Phase`] function; it may absorb with σa (the index profile's `absorption`).
//!
//! **Free flights.** Light travelling a path of arclength s in the medium keeps exp(−σs s)
//! unscattered — along a curved path exactly as along a straight one, since σs is constant
//! in the medium and only the arclength counts. A path draws the arclength at which it
//! scatters ([`Flights::draw`]); absorption is carried apart, as a weight exp(−σa s) (or
//! Russian roulette on it for photons), as it always was. With σs the same in every channel
//! the draw is exact and every weight is 1; with a coloured σs see [`Flights`].
//!
//! **Radiance.** Basic radiance L/n² is conserved between events (the refractive radiative
//! transfer equation; Ament et al. 2014), so radiance in-scattered at a point of index n is
//! seen at a path's start scaled by (n_start/n)², as radiance leaving a surface is: the chain
//! does it ([`crate::transport::chain::Chain::radiance_scale`]). A phase function is
//! normalised over solid angle at the point, whatever n is there.

mod phase;

pub use phase::Phase;

use crate::color::Rgb;

/// How a medium scatters: σs per channel (1/length, ≥ 0) and the phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattering {
    /// The scattering coefficient σs per RGB channel (1/length).
    pub sigma_s: Rgb,
    /// How a scattering event redirects light.
    pub phase: Phase,
}

impl Scattering {
    /// Whether σs is the same in every channel (then a free flight's weights are 1).
    fn is_grey(&self) -> bool {
        let s = self.sigma_s;
        s.0.x == s.0.y && s.0.y == s.0.z
    }

    /// ln of each channel's density of a free flight's outcome after arclength `s`: scattered
    /// there (σs exp(−σs s)) or gone on past it (exp(−σs s)); −∞ for a channel that cannot.
    fn log_densities(&self, s: f64, scattered: bool) -> [f64; 3] {
        self.sigma_s
            .0
            .to_array()
            .map(|sigma| match (scattered, sigma > 0.0) {
                (true, true) => sigma.ln() - sigma * s,
                (true, false) => f64::NEG_INFINITY,
                (false, _) => -sigma * s,
            })
    }

    /// The fraction exp(−σs s) of light that goes arclength `s` unscattered, per channel.
    pub fn transmittance(&self, s: f64) -> Rgb {
        Rgb((-self.sigma_s.0 * s).exp())
    }
}

/// A path's free flights, for a coloured σs (a grey one needs none of this: every weight is
/// 1). Every flight of a path is drawn with one channel's σs, its hero, picked at random at
/// the path's first coloured flight; so the path's density is the mean over channels of each
/// channel's product of flight densities, and a channel's weight is its own product over that
/// mean (one-sample multiple importance sampling over the channels, per path as in
/// pbrt-v4's spectral MIS: a weight is at most 3, where a product of per-flight ratios grows
/// without bound and, in a box of σs = (0.3, 1, 3), read the blue channel 27 % dark at 16 000
/// samples). The weight so far is kept (mean 1 by construction); each flight multiplies it
/// by its densities over their mean under it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flights {
    /// The channel whose σs draws every flight (None until the first coloured flight).
    hero: Option<usize>,
    /// The path's flight weight so far, per channel.
    weight: Rgb,
}

impl Default for Flights {
    fn default() -> Self {
        Self {
            hero: None,
            weight: Rgb::ONE,
        }
    }
}

impl Flights {
    /// The arclength a path travels in `medium` before it scatters, drawn from `rng` (one
    /// number; a second, once per path, picks the hero channel); ∞ where the hero does not
    /// scatter.
    pub fn draw(&mut self, medium: &Scattering, rng: &mut impl rand::Rng) -> f64 {
        let s = medium.sigma_s.0;
        let sigma = match medium.is_grey() {
            true => s.x,
            false => s[*self.hero.get_or_insert_with(|| rng.gen_range(0..3))],
        };
        let u: f64 = rng.gen();
        match sigma > 0.0 {
            // 1 − u ∈ (0, 1]: the distance is finite and ≥ 0.
            true => -(1.0 - u).ln() / sigma,
            false => f64::INFINITY,
        }
    }

    /// The weight a flight of arclength `s` in `medium` multiplies the path's throughput by:
    /// it `scattered` there, or went on past it (to a surface or out of the world).
    pub fn weigh(&mut self, medium: &Scattering, s: f64, scattered: bool) -> Rgb {
        if medium.is_grey() {
            return Rgb::ONE;
        }
        // Relative to the largest, so that nothing underflows to 0/0.
        let log = medium.log_densities(s, scattered);
        let top = log.into_iter().fold(f64::NEG_INFINITY, f64::max);
        let density = Rgb(glam::DVec3::from_array(log.map(|l| (l - top).exp())));
        let mean = (self.weight * density).mean();
        let factor = match mean > 0.0 {
            true => density / mean,
            false => Rgb::ZERO,
        };
        self.weight *= factor;
        factor
    }
}
