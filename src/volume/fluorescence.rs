//! A fluorophore dissolved in a medium: a dye that absorbs light and emits some of it again
//! at longer wavelengths, isotropically ([`Fluorophore`]: its line and quantum yield).
//!
//! **Absorption.** The dye absorbs light of vacuum wavelength λ at the rate σf(λ) (1/length),
//! uniformly through the medium: a path at λ meets the dye after an arclength drawn at that
//! rate, as it meets a scattering particle at σs (the two rates add; which one it met is
//! drawn in proportion to them, [`Fluorescence::share`]).
//!
//! **Emission.** What the dye emits again leaves the point of absorption in a direction
//! drawn uniformly over the sphere.
//!
//! **Re-absorption.** Emitted light travels on at λ′ and meets the dye at σf(λ′) like any
//! other light: where the emission spectrum overlaps the absorption, the dye absorbs its own
//! light again (what limits a luminescent solar concentrator).

use crate::spectrum::{Excitation, Fluorophore};

/// A dye in a medium (see the module's notes).
#[derive(Clone, Debug)]
pub struct Fluorescence {
    /// σf over vacuum wavelength (1/length, ≥ 0).
    pub absorption: Excitation,
    /// What it emits again.
    pub fluorophore: Fluorophore,
}

impl Fluorescence {
    /// σf at vacuum wavelength `nm` (1/length).
    pub fn sigma(&self, nm: f64) -> f64 {
        self.absorption.at(nm)
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
}
