//! Where a dye in a medium emits light toward a camera chain on its way: a point drawn on each
//! of the chain's stretches through the dye, from which the light the dye absorbs there is
//! estimated at a wavelength it absorbs ([`super::path::dye_light`] goes on from it).
//!
//! **The estimator.** A dye of absorption σf(λ) and quantum yield q, emitting photons on the
//! line ε(λ′) (by number), emits isotropically at λ′ the radiance per unit length
//!
//! S(x, λ′) = q·ε(λ′)/λ′ · ∫ σf(λ)·λ · L̄(x, λ) dλ,
//!
//! L̄ the radiance at x averaged over the sphere (what an isotropic phase function scatters):
//! q of the photons absorbed, each with λ/λ′ of the absorbed energy. A camera chain at λ′ (a
//! path through a dye always carries one wavelength: the medium is dispersive) sees along a
//! stretch of length ℓ the light ∫₀^ℓ P(t)·T_a(t)·(n_start/n)²·S(x(t), λ′) dt, P(t) the chance
//! its free flight reaches t — the transmittance of the collisions σs + σf(λ′), which the
//! flight draws (the dye's share of a collision ends a camera path, [`crate::transport::chain`])
//! — and T_a the medium's own absorption. So one point drawn uniformly on the stretch as the
//! chain walked it estimates it without bias over where the flight ends, as the light a medium
//! emits is gathered ([`crate::volume::Emission`]); there λ is drawn by [`Excitation::draw`]
//! and L̄ estimated by path tracing on from the point at λ as from an isotropic scatterer.
//!
//! **Russian roulette.** K(λ′)·ℓ, K = q·ε(λ′)/λ′·∫σf(λ)λ dλ, is the light the dye emits along
//! the stretch per unit of L̄: a point is drawn with probability min(1, K·ℓ) and weighed by its
//! reciprocal, so that a stretch where the dye emits little at the chain's wavelength (its
//! excitation band, for a path that is itself a dye's estimate) rarely branches.
//!
//! **The point.** It is found by following the stretch again from its start, exactly, to the
//! drawn arclength (a curved stretch's is summed over the chords between its points, short of
//! its arclength by O((κh)²) of it for steps h on a path of curvature κ).
//!
//! [`Excitation::draw`]: crate::spectrum::Excitation::draw

use super::beam::{Beams, Walked};
use crate::color::Rgb;
use crate::polarization::Polarization;
use crate::transport::{Event, MediumVertex, Stats, Tracer};
use crate::volume::{Flights, Phase};
use rand::Rng;

/// A point where a dye emits toward a camera chain, and how the chain goes on from it.
pub struct DyeSource<'b> {
    /// The point, scattering isotropically.
    pub vertex: MediumVertex,
    /// The vacuum wavelength (nm) the light is estimated at there.
    pub nm: f64,
    /// What the light arriving there (averaged over the sphere) is multiplied by, as seen at
    /// the chain's start per unit of the path's throughput before it.
    pub weight: Rgb,
    /// The path's free flights up to the point.
    pub flights: Flights,
    /// The events the path may still meet past the point.
    pub depth: u32,
    /// Where the transport is polarized, the camera's measurement on the stretch, per unit of
    /// the chain's weight at its start (the dye's light leaves it unpolarized).
    pub measure: Option<&'b Polarization>,
}

/// The points where dyes emit toward the chain recorded in `beams` (see the module's notes),
/// `tracer` the one it ended on; numbers from `rng`.
pub fn dye_sources<'b>(
    beams: &'b Beams,
    tracer: &Tracer,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Vec<DyeSource<'b>> {
    beams
        .walked()
        .filter_map(|w| source(&w, tracer, rng, stats))
        .collect()
}

/// The point drawn on the walked stretch `w`, if its medium holds a dye and one is drawn (no
/// number is drawn for a stretch through a medium without one).
fn source<'b>(
    w: &Walked<'b>,
    tracer: &Tracer,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Option<DyeSource<'b>> {
    let dye = tracer.scene.media().fluorescence(w.medium)?;
    // A chain in a dye carries one wavelength (the medium is dispersive).
    let seen = tracer.single_wavelength()?;
    let line = dye.fluorophore.emitted(seen);
    let rate = line * dye.absorption.integral();
    let mut from = w.stretch.origin;
    let length: f64 = w
        .points
        .iter()
        .map(|&p| {
            let chord = (p - from).length();
            from = p;
            chord
        })
        .sum();
    let expected = rate * length;
    if expected.is_nan() || expected <= 0.0 {
        return None;
    }
    let chance = expected.min(1.0);
    if rng.gen::<f64>() >= chance {
        return None;
    }
    let t = rng.gen::<f64>() * length;
    let medium = Some(w.medium);
    let Event::Reached {
        position,
        direction,
        optical_depth,
        ..
    } = tracer.next_event_within(
        w.stretch.origin,
        w.stretch.direction,
        medium,
        t,
        stats,
        None,
    )
    else {
        return None;
    };
    let n = tracer.index(medium, position)?;
    let excited = tracer.scene.dye_excitation(w.medium);
    let (nm, ratio) = dye.absorption.draw(excited, rng.gen());
    let scale = (w.n_start / n) * (w.n_start / n);
    Some(DyeSource {
        vertex: MediumVertex {
            position,
            wo: -direction,
            medium,
            phase: Phase::Isotropic,
        },
        nm,
        weight: w.stretch.weight
            * (-optical_depth).exp()
            * (scale * length / chance * line * ratio),
        flights: w.stretch.flights,
        depth: w.stretch.depth,
        measure: w.measure,
    })
}
