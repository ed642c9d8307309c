//! A participating medium: what a medium does to light's power beside bending it — it absorbs
//! (σa), scatters (σs and a phase function: [`Scattering`]) and emits (Le), each scaled by the
//! medium's density where it is heterogeneous, and it may hold a dye ([`Fluorescence`]). The
//! index field ([`crate::media::Medium`]) only bends rays; the curved-segment engine returns geometry, and the transport asks this type
//! what the light loses and gains along it.
//!
//! **Emission.** A medium that absorbs with σa(x) emits σa(x)·Le per unit length (the
//! emission coefficient of Kirchhoff's law, as pbrt-v4's and Mitsuba 3's media state it), Le
//! given as *basic radiance* L/n²: a thermal emitter of index n shows n²·Le (Kirchhoff's law
//! in a medium), so Le is the radiance an optically thick body of the medium shows in vacuum,
//! Fresnel apart. Along a stretch of optical depth τa (absorption only) the light emitted
//! and not absorbed again on the way is then Le·(1 − e^(−τa)) as basic radiance — exactly, for
//! any density and along any curved path, since d/ds e^(−τa(s)) = −σa(s)·e^(−τa(s)) — and a
//! path starting at index n sees n² times it ([`Emission::along`]).

use super::{Fluorescence, Scattering};
use crate::color::Rgb;
use crate::media::Density;
use glam::DVec3;
use std::sync::Arc;

/// Absorption: a coefficient σa per RGB channel (1/length, ≥ 0, above 0 in some channel) where
/// the density is 1, scaled by the density. Optical depths are per channel: a channel keeps
/// exp(−τ) of its light over an optical depth τ.
#[derive(Clone, Debug)]
pub struct Absorption {
    /// σa (1/length) per channel where the density is 1.
    pub sigma_a: Rgb,
    /// The density scaling σa (None: 1 everywhere).
    pub density: Option<Arc<Density>>,
}

impl Absorption {
    /// σa at `p` (1/length, per channel).
    pub fn at(&self, p: DVec3) -> Rgb {
        self.sigma_a * self.density.as_ref().map_or(1.0, |d| d.at(p))
    }

    /// The optical depth ∫ σa ds along the straight piece from `from` along unit `dir` over
    /// `length`: σa times the density's column, exactly.
    pub fn optical_depth(&self, from: DVec3, dir: DVec3, length: f64) -> Rgb {
        match &self.density {
            None => self.sigma_a * length,
            Some(d) => self.sigma_a * d.column(from, dir, length),
        }
    }

    /// The optical depth of one step of a curved path between `a` and `b`, `length` apart
    /// along the path: the depth along the chord, scaled by the arclength over the chord's
    /// length (so a constant σa gives σa·length exactly).
    pub fn step_depth(&self, a: DVec3, b: DVec3, length: f64) -> Rgb {
        let chord = (b - a).length();
        match chord > 0.0 {
            true => self.optical_depth(a, (b - a) / chord, chord) * (length / chord),
            false => self.at(a) * length,
        }
    }
}

/// Emission: basic radiance Le (W/(m²·sr) per RGB channel, ≥ 0) emitted at the rate σa
/// (see the module's notes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Le, as basic radiance L/n².
    pub radiance: Rgb,
}

impl Emission {
    /// The basic radiance emitted along a stretch of absorption optical depth `depth` (per
    /// channel) and not absorbed on it: Le·(1 − e^(−depth)).
    pub fn along(&self, depth: Rgb) -> Rgb {
        self.radiance * Rgb(depth.0.map(|tau| -(-tau).exp_m1()))
    }
}

/// What a medium does to light's power: it may absorb, scatter and emit (each None where it
/// does not).
#[derive(Clone, Debug, Default)]
pub struct Participating {
    /// Absorption (None: it does not absorb).
    pub absorption: Option<Absorption>,
    /// Scattering (None: it does not scatter).
    pub scattering: Option<Scattering>,
    /// Emission (only a medium that absorbs emits).
    pub emission: Option<Emission>,
    /// A dye that fluoresces (None: none).
    pub fluorescence: Option<Fluorescence>,
}

impl Participating {
    /// The optical depth of absorption per channel along the straight piece from `from` along
    /// unit `dir` over `length` (0 where it does not absorb).
    pub fn optical_depth(&self, from: DVec3, dir: DVec3, length: f64) -> Rgb {
        match &self.absorption {
            Some(a) if length > 0.0 => a.optical_depth(from, dir, length),
            _ => Rgb::ZERO,
        }
    }

    /// The optical depth of absorption along one step of a curved path ([`Absorption::step_depth`];
    /// 0 where it does not absorb).
    pub fn step_depth(&self, a: DVec3, b: DVec3, length: f64) -> Rgb {
        self.absorption
            .as_ref()
            .map_or(Rgb::ZERO, |ab| ab.step_depth(a, b, length))
    }

    /// σa at `p` (1/length per channel; 0 where it does not absorb).
    pub fn sigma_a(&self, p: DVec3) -> Rgb {
        self.absorption.as_ref().map_or(Rgb::ZERO, |a| a.at(p))
    }
}
