//! A fluorescent layer on a diffuse surface (a highlighter's ink, a brightened paper): of the
//! light of vacuum wavelength λ falling on it, the share a(λ) is absorbed by the layer's
//! fluorophore, which emits q of those photons again, Lambertian, on its line
//! ([`Fluorophore`]: ε(λ′) their number per nm, each with λ/λ′ of the absorbed energy); the
//! rest meets the surface's own reflectance ρ. Its reflectance from λ to λ′ is so the simplest
//! exact bispectral one (a Donaldson matrix of a diagonal and one rank-1 part): (1 − a(λ))·ρ(λ)
//! for λ′ = λ, a(λ)·q·ε(λ′)·λ/λ′ per nm otherwise.
//!
//! **Seen from a camera** ([`FluorescentLayer::relight`]). Under spectral irradiance E(λ) the
//! layer's radiance at λ′ is
//!
//! L(λ′) = ρ(λ′)(1 − a(λ′))·E(λ′)/π + q·ε(λ′)/λ′ · ∫ a(λ)·λ·E(λ) dλ / π.
//!
//! A camera path that carries every wavelength takes on one λ′ there, drawn from the
//! visible-importance density, the emission line and the light the scene's sources emit in
//! equal shares ([`FluorescentLayer::hero`]),
//! its throughput weighed r̄(λ′)/p(λ′) as where a path meets dispersion. A camera path
//! carrying one wavelength λ′ estimates either part by going on from the layer as
//! from a white Lambertian surface at one wavelength λ — whose estimate is E(λ)/π — with a
//! weight: the reflected part at λ = λ′, weighed ρ(λ′)(1 − a(λ′)); the fluorescent part at an
//! excitation wavelength drawn in equal shares from a(λ)·λ and from a(λ)·λ·s(λ), s the light
//! the scene's sources emit (a narrow line of a light found where it excites, and light the
//! scene's surfaces colour on its way still found), weighed
//! q·ε(λ′)/λ′·a(λ)·λ/p(λ). Which part a path takes is drawn in proportion to their sizes under
//! equal-energy light, and the weight divided by its chance.

use crate::spectrum::{Binned, Dispersion, Excitation, Fluorophore, Hero};

/// A fluorescent layer (see the module's notes).
#[derive(Clone, Debug)]
pub struct FluorescentLayer {
    /// a(λ): the share of the light the layer absorbs, in [0, 1].
    pub excitation: Excitation,
    /// What it emits again.
    pub fluorophore: Fluorophore,
}

/// The very same layer (a material's, read once from its file): its forms over wavelength have
/// no equality of their own.
impl PartialEq for FluorescentLayer {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

/// Where a camera path goes on from a fluorescent layer: as from a white Lambertian surface at
/// one wavelength, its throughput times a weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Relit {
    /// The vacuum wavelength (nm) the path carries on at.
    pub nm: f64,
    /// What its throughput is multiplied by (see the module's notes).
    pub weight: f64,
}

impl FluorescentLayer {
    /// The layer absorbing a(λ) = `excitation` and emitting as `fluorophore` (None where it
    /// absorbs nothing from 360 to 830 nm).
    pub fn new(excitation: Dispersion, fluorophore: Fluorophore) -> Option<Self> {
        Some(Self {
            excitation: Excitation::new(excitation, 1.0)?,
            fluorophore,
        })
    }

    /// a at vacuum wavelength `nm`, within [0, 1].
    pub fn absorbed(&self, nm: f64) -> f64 {
        self.excitation.at(nm)
    }

    /// Where a camera path at vacuum wavelength `nm` that meets the layer on a surface of
    /// reflectance `albedo` there goes on (see the module's notes), drawing the excitation
    /// wavelength from a(λ)·λ and `excited`, the density of the light the layer absorbs from
    /// the scene's sources (None: from a(λ)·λ alone), for uniform `u`; None where the layer
    /// sends no light its way.
    pub fn relight(
        &self,
        nm: f64,
        albedo: f64,
        excited: Option<&Binned>,
        u: [f64; 2],
    ) -> Option<Relit> {
        let [choice, draw] = u;
        let reflected = albedo * (1.0 - self.absorbed(nm));
        let line = self.fluorophore.emitted(nm);
        let fluorescent = line * self.excitation.integral();
        let total = reflected + fluorescent;
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let relit = match choice * total < fluorescent {
            true => {
                let (at, ratio) = self.excitation.draw(excited, draw);
                Relit {
                    nm: at,
                    weight: total * ratio / self.excitation.integral(),
                }
            }
            false => Relit { nm, weight: total },
        };
        (relit.weight > 0.0).then_some(relit)
    }

    /// The wavelength a camera path carrying every wavelength takes on where it meets the
    /// layer, for uniform `u`: from the visible-importance density, the layer's emission line
    /// and `sources` (the light the scene's sources emit, which the layer reflects; None: the
    /// first two alone) in equal shares — a narrow line, emitted or reflected, is found by a
    /// share of the paths where the visible density alone would find it by a few — with the
    /// mixture's density.
    pub fn hero(&self, sources: Option<&Binned>, u: f64) -> Hero {
        let emission = &self.fluorophore.emission;
        match sources {
            Some(s) => Hero::visible_or(&[emission, s], u),
            None => Hero::visible_or(&[emission], u),
        }
    }
}
