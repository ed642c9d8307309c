//! Scattering in media: a medium's radiometry beside its index field ([`crate::media`]).
//! A medium may scatter light with coefficient σs (1/length, per RGB channel) and a
//! [`Phase`] function; it may absorb with σa (the index profile's `absorption`).
//!
//! **Free flights.** Light travelling a path of arclength s in the medium keeps exp(−σs s)
//! unscattered — along a curved path exactly as along a straight one, since σs is constant
//! in the medium and only the arclength counts. A path draws the arclength at which it
//! scatters ([`Scattering::free_flight`]); absorption is carried apart, as a weight
//! exp(−σa s) (or Russian roulette on it for photons), as it always was. With σs the same in
//! every channel the draw is exact and every weight is 1; with a coloured σs a channel is
//! picked at random and the density is the mean of the channels' (one-sample multiple
//! importance sampling over channels), which the weights divide by.
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

    /// The arclength a path travels before it scatters, from uniform numbers `u` (`u.0`
    /// picks the channel whose σs draws it when σs is coloured); ∞ where that channel does not
    /// scatter.
    pub fn free_flight(&self, u: (f64, f64)) -> f64 {
        let s = self.sigma_s.0;
        let sigma = match self.is_grey() {
            true => s.x,
            false => s[((u.0 * 3.0) as usize).min(2)],
        };
        match sigma > 0.0 {
            // 1 − u.1 ∈ (0, 1]: the distance is finite and ≥ 0.
            true => -(1.0 - u.1).ln() / sigma,
            false => f64::INFINITY,
        }
    }

    /// Whether drawing a free flight uses `u.0` (a coloured σs) — grey media draw one number.
    pub fn picks_channel(&self) -> bool {
        !self.is_grey()
    }

    /// The weight of a path that scattered after arclength `s`: σs exp(−σs s) per channel over
    /// the density the draw had there (1 for a grey medium).
    pub fn scattered_weight(&self, s: f64) -> Rgb {
        if self.is_grey() {
            return Rgb::ONE;
        }
        // In logarithms, relative to the largest channel's, so that nothing underflows to 0/0.
        let log = self.sigma_s.0.to_array().map(|sigma| match sigma > 0.0 {
            true => sigma.ln() - sigma * s,
            false => f64::NEG_INFINITY,
        });
        let top = log.into_iter().fold(f64::NEG_INFINITY, f64::max);
        let f = Rgb(glam::DVec3::from_array(log.map(|l| (l - top).exp())));
        f / f.mean()
    }

    /// The weight of a path that went `s` without scattering: exp(−σs s) per channel over the
    /// probability the draw gave that (1 for a grey medium).
    pub fn passed_weight(&self, s: f64) -> Rgb {
        if self.is_grey() {
            return Rgb::ONE;
        }
        // Relative to the least σs's, which keeps 1: the mean is at least 1/3.
        let least = self.sigma_s.min_element();
        let kept = Rgb((-(self.sigma_s.0 - least) * s).exp());
        kept / kept.mean()
    }

    /// The fraction exp(−σs s) of light that goes arclength `s` unscattered, per channel.
    pub fn transmittance(&self, s: f64) -> Rgb {
        Rgb((-self.sigma_s.0 * s).exp())
    }
}
