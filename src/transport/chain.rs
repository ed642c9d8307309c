//! The specular chain: a path followed through purely specular surfaces (smooth mirrors,
//! conductors and dielectrics) and receivers' detectors (straight or curved between them) to
//! its next scattering vertex (any other surface: diffuse, glossy), emitter or escape. It is
//! the one such loop: camera paths, final-gather rays, the direct estimate's BSDF rays,
//! photons and principal rays all walk it.
//!
//! **Radiance across indices.** Basic radiance L/n² is conserved along a path — across a
//! dielectric interface (with the Fresnel factor, which the chain samples) and along a curved
//! path in a gradient medium alike. So radiance L formed at the chain's end, in a medium of
//! index n_end there, arrives at its start as (n_start/n_end)² L: [`Chain::radiance_scale`].
//! The factors of the single refractions telescope into this one ratio, which is why no
//! BSDF carries them. Power (a photon's flux) never scales.

use super::{Event, HeroTracer, MediumVertex, Stats, SurfaceVertex, Tracer, Vertex};
use crate::color::Rgb;
use crate::curve::ArcPoint;
use crate::ids::{MediumId, PrimId, ReceiverId};
use crate::material::Material;
use crate::polarization::crystal::{Beam, Interface};
use crate::polarization::{Element, Polarization, Recorded, Sense};
use crate::scene::Role;
use crate::volume::{Flights, Scattering};
use glam::DVec3;
use rand::Rng;
use std::ops::ControlFlow;

/// A ray: where it starts, which way, and in which medium; also where a chain stands
/// between two events.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Start.
    pub origin: DVec3,
    /// Unit direction.
    pub direction: DVec3,
    /// The medium it starts in (None: vacuum).
    pub medium: Option<MediumId>,
}

/// How a chain carries its losses (absorption along the way, a mirror's reflectance).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Policy {
    /// Multiply the weight by each (paths from the camera).
    Weighted,
    /// Russian roulette: go on with the loss's probability and divide the weight by it, so
    /// a photon's power keeps its size; end as [`End::Absorbed`] otherwise.
    Roulette,
    /// The principal ray: at a dielectric the likelier branch (reflected where the Fresnel
    /// reflectance exceeds 1/2, as under total internal reflection), losses ignored.
    Principal,
    /// Weighted, and stopped ([`End::Stopped`]) at the first mirror or dielectric: light
    /// that reaches the start with no specular interaction (the direct estimate's BSDF rays).
    Unscattered,
}

/// Where a chain ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End<'s> {
    /// A scattering vertex: a surface whose BSDF is not purely specular, or a point inside
    /// a scattering medium where a free flight ended.
    Scatter(Vertex<'s>),
    /// An emitter: its radiance toward the path (zero from its back).
    Emitter {
        /// Primitive index.
        prim: PrimId,
        /// Radiance, W/(m²·sr), in the medium at its surface.
        radiance: Rgb,
        /// Hit point.
        position: DVec3,
        /// The surface's unit geometric normal there (its emitting side's for a front hit).
        normal: DVec3,
        /// Unit direction of arrival.
        direction: DVec3,
    },
    /// The path left the world.
    Escaped {
        /// Unit direction when leaving.
        direction: DVec3,
    },
    /// Russian roulette ended it: absorbed on the way in a medium, or by a lossy mirror.
    Absorbed {
        /// The medium that absorbed it (None: a mirror, or on the way through vacuum).
        medium: Option<MediumId>,
    },
    /// Captured, out of steps, trapped, or at an index that cannot be evaluated.
    Lost,
    /// It met `max_depth` surfaces.
    DepthLimit,
    /// The observer ended it.
    Stopped,
}

/// A followed chain: how it ended and what it gathered on the way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chain<'s> {
    /// How it ended.
    pub end: End<'s>,
    /// Throughput (Weighted) or the photon's power factor (Roulette).
    pub weight: Rgb,
    /// The medium at the end.
    pub medium: Option<MediumId>,
    /// n at the start, in the start medium.
    pub n_start: f64,
    /// n at the end, in the end medium (at the escape point for an escape).
    pub n_end: f64,
    /// Specular bounces (smooth mirrors, conductors and dielectrics; not detectors) on the way.
    pub specular: u32,
    /// Whether a stretch of it crossed a non-uniform medium (a curved path).
    pub curved: bool,
    /// Radiance the media on the way emitted toward the start and did not absorb again, as
    /// seen at the start (basic radiance times n_start²; [`crate::volume::Emission`]) and
    /// weighted as the chain was there: a camera path's ([`Policy::Weighted`]; zero for
    /// every other policy).
    pub emitted: Rgb,
    /// A photon's chain ([`Policy::Roulette`]) that met dispersion: its weight up to there
    /// (then `weight` counts from there, at the hero wavelength). The photon's power changes
    /// there in a way only it knows (its source's spectrum at the wavelength).
    pub dispersed: Option<Rgb>,
}

impl Chain<'_> {
    /// (n_start/n_end)²: radiance formed at the end in its medium, as seen at the start.
    pub fn radiance_scale(&self) -> f64 {
        let r = self.n_start / self.n_end;
        r * r
    }

    /// n_start²: environment radiance, as seen at the start of a chain that escaped.
    /// Environment radiance is given as in vacuum (n = 1) — the basic radiance L/n² of the
    /// light arriving from beyond the world — so in a medium of index n it is n² L, and
    /// (n_start/n_end)² of that is seen at the start, whatever the index where it escaped.
    pub fn environment_scale(&self) -> f64 {
        self.n_start * self.n_start
    }
}

/// Where a chain sets off on a stretch: from one event (its start, a specular surface, a
/// detector) through one medium to the next. The stretch's points follow as
/// [`ChainEvents::point`]s, up to and including its end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    /// Where it starts.
    pub origin: DVec3,
    /// Its unit direction there.
    pub direction: DVec3,
    /// The medium it travels in.
    pub medium: Option<MediumId>,
    /// The chain's weight at its start (its own absorption and free flight not yet in it).
    pub weight: Rgb,
    /// The path's free flights with this stretch's drawn (what [`Flights::weigh`] needs to
    /// weigh a point on it).
    pub flights: Flights,
    /// Whether the path may still scatter on it: false where it has met `max_depth` events
    /// (light scattered toward it on the way would be one event too many).
    pub may_scatter: bool,
    /// The events the path may still meet past one on it.
    pub depth: u32,
}

/// A chain crossing a receiver's detector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DetectorCrossing<'p> {
    /// The receiver.
    pub receiver: ReceiverId,
    /// Where it crosses.
    pub position: DVec3,
    /// The chain's unit direction there.
    pub direction: DVec3,
    /// The chain's weight there.
    pub weight: Rgb,
    /// What the chain carries of the light's polarization there (None: unpolarized transport).
    pub polarization: Option<&'p Polarization>,
}

/// Told of what a chain passes (all optional).
pub trait ChainEvents {
    /// It sets off on a stretch, carrying `polarization` (None: unpolarized transport).
    fn stretch(&mut self, _stretch: &Stretch, _polarization: Option<&Polarization>) {}
    /// It gathered light a medium emitted along its stretch, `light` as the camera records it
    /// through the measurement the chain carries (only where it carries one).
    fn emitted(&mut self, _light: Recorded) {}
    /// A point the path passes: each accepted point of a curved stretch, each surface met,
    /// where a free flight ends, and where it leaves the world.
    fn point(&mut self, _p: DVec3) {}
    /// Whether [`ChainEvents::point`] reads the points of curved stretches (false: it ignores
    /// them, and they are not computed).
    fn wants_points(&self) -> bool {
        true
    }
    /// It crosses a receiver's detector; `Break` ends the chain ([`End::Stopped`]).
    fn detector(&mut self, _crossing: &DetectorCrossing) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// It was reflected or refracted at primitive `prim`, from medium `from` into `to`;
    /// `Break` ends the chain ([`End::Stopped`]).
    fn specular(
        &mut self,
        _prim: PrimId,
        _from: Option<MediumId>,
        _to: Option<MediumId>,
    ) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

impl ChainEvents for () {
    fn wants_points(&self) -> bool {
        false
    }
}

/// The wavelengths a path carries (Zhdanov et al.'s (2020) "subset of wavelengths that share a path"):
/// every one, seeing each medium at [`crate::spectrum::LAMBDA_D`] and every colour as RGB,
/// until it meets dispersion, where it takes on `hero`'s one wavelength; or one, when `tracer`
/// is at a wavelength (then `hero` is None). In a scene without dispersion `hero` is None and
/// every path carries every wavelength to its end.
#[derive(Clone, Copy)]
pub struct Carried<'w> {
    /// Where it travels now.
    pub tracer: &'w Tracer<'w>,
    /// The wavelength it takes on where it meets dispersion.
    pub hero: Option<&'w HeroTracer<'w>>,
    /// Its free flights in scattering media so far.
    pub flights: Flights,
    /// Surfaces (detectors included) and scattering events in media it may still meet: the
    /// tracer's `max_depth` at its start, spent by every chain it follows, so that a camera
    /// path's bounces after its visible point count on from the events before it.
    pub depth: u32,
}

impl<'w> Carried<'w> {
    /// Paths on `tracer` that never change their wavelengths.
    pub fn on(tracer: &'w Tracer<'w>) -> Self {
        Self::starting(tracer, None)
    }

    /// A path starting on `tracer` that takes on `hero`'s wavelength where it meets dispersion.
    pub fn starting(tracer: &'w Tracer<'w>, hero: Option<&'w HeroTracer<'w>>) -> Self {
        Self {
            tracer,
            hero,
            flights: Flights::default(),
            depth: tracer.settings.max_depth,
        }
    }
}

/// A path being walked: the wavelengths it carries and where it travels, how its losses are
/// carried, and how many surfaces it may still meet (shared by a photon's successive chains).
/// Its random numbers (the Fresnel choices and Russian roulette) and statistics are lent to
/// each [`Walker::follow`].
#[derive(Clone, Copy)]
pub struct Walker<'w> {
    /// Where it travels (at its hero wavelength once it has met dispersion).
    pub tracer: &'w Tracer<'w>,
    /// The wavelength it takes on where it meets dispersion ([`Carried`]).
    hero: Option<&'w HeroTracer<'w>>,
    /// How losses are carried.
    pub policy: Policy,
    /// Surfaces (detectors included) and scattering events in media it may still meet.
    pub depth: u32,
    /// Its free flights in scattering media so far.
    flights: Flights,
    /// Numbers its first choices between reflection and refraction take instead of numbers
    /// from the stream ([`Walker::choosing`]).
    choices: Choices,
}

/// Numbers in [0, 1) that a path's first choices between reflection and refraction take, in
/// order, in place of numbers from its stream: a camera sample's, each stratified over the
/// pixel's samples, so that a pixel's samples split between the branches of the first
/// dielectrics they meet nearly in proportion to the Fresnel reflectances.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Choices {
    numbers: [f64; Choices::COUNT],
    /// How many are left (the last ones of `numbers`).
    left: usize,
}

impl Choices {
    /// How many choices a camera sample makes with given numbers.
    pub const COUNT: usize = 3;

    /// The choices `numbers` (each uniform in [0, 1)).
    pub fn new(numbers: [f64; Choices::COUNT]) -> Self {
        Self {
            numbers,
            left: Self::COUNT,
        }
    }

    /// The next number, if one is left.
    fn next(&mut self) -> Option<f64> {
        let u = self.numbers.get(Self::COUNT - self.left).copied();
        self.left = self.left.saturating_sub(1);
        u
    }
}

/// What one [`Walker::follow`] works with: the random stream and the statistics lent to it,
/// and what the chain carries of the light's polarization where the transport is polarized
/// ([`crate::polarization::carried`]: a photon's Stokes vector, or a camera path's measurement
/// row, folded into the chain's weight where it ends). Kept beside the chain rather than in
/// it: a [`Chain`] is returned by value at every bounce, and an unpolarized one should not
/// carry the 4 × 4 numbers a channel.
struct Lent<'a, R> {
    rng: &'a mut R,
    stats: &'a mut Stats,
    polarization: Option<&'a mut Polarization>,
    /// Index-matched boundaries crossed so far ([`MAX_CROSSINGS`]).
    crossings: usize,
}

/// The polarization a chain starts from, where the transport is polarized.
enum Start<'a> {
    /// Unpolarized light, or an unpolarized measurement of it.
    Unpolarized,
    /// A camera's measurement of the light, through its analyzer if any, of the whole Stokes
    /// vector in the basis of `stokes_axis` where that is given, left in `measure` at the
    /// chain's end (a chain is returned by value at every bounce: what a camera path carries
    /// past its first chain is not returned with it).
    Camera {
        analyzer: Option<&'a Element>,
        stokes_axis: Option<DVec3>,
        measure: &'a mut Option<Polarization>,
    },
    /// What the place holds (unpolarized where it holds none), left there at the chain's end.
    Carrying(&'a mut Option<Polarization>),
}

/// The chain's weight as its start sees light that is unpolarized where the chain is now: with
/// a camera's measurement row's share of it where the transport is polarized (light a medium
/// scatters or emits toward the path, as any light at a chain's end, is unpolarized).
fn seen<R>(chain: &Chain, lent: &Lent<R>) -> Rgb {
    match lent.polarization.as_deref() {
        Some(p) => chain.weight * p.closing(),
        None => chain.weight,
    }
}

/// Events (surfaces and scattering in media) a camera path or a map photon meets before
/// Russian roulette may end it: past them each further event is survived with probability
/// [`ROULETTE_SURVIVAL`], the survivors weighed by its reciprocal — unbiased, and a path
/// trapped between mirrors or in a conservative fog ends all the same (`max_depth` is only
/// a bound, 65 536 unless the scene sets it).
pub const ROULETTE_AFTER: u32 = 64;

/// The chance a path goes on at each event past [`ROULETTE_AFTER`].
pub const ROULETTE_SURVIVAL: f64 = 0.95;

/// The most null collisions (and redraws at a local majorant's reach) one stretch may meet in
/// a heterogeneous medium (a path in a near empty corner of a dense grid, or one orbiting in a
/// void): bounded time, never a loop.
pub const MAX_NULL_COLLISIONS: usize = 100_000;

/// The most index-matched boundaries one chain (or one shadow ray) crosses: they cost no
/// depth, so this bounds a chain that numbers trap among coincident ones; past it the chain
/// ends lost, counted in the statistics as out of steps (a shadow ray: blocked).
pub const MAX_CROSSINGS: usize = 1 << 16;

/// The scattering column ∫d ds summed along a stretch's chords, where it is wanted.
struct Column<'s> {
    /// The medium's scattering, when the column is summed.
    scattering: Option<&'s Scattering>,
    /// The last point reached.
    last: DVec3,
    total: f64,
}

impl Column<'_> {
    /// Adds the chord from the last point to `p`.
    fn to(&mut self, p: DVec3) {
        if let Some(sc) = self.scattering {
            let length = (p - self.last).length();
            if length > 0.0 {
                self.total += sc.column(self.last, (p - self.last) / length, length);
            }
        }
        self.last = p;
    }
}

/// One free flight of a path in a scattering medium: how far it goes before it stops to look.
#[derive(Clone, Copy)]
struct Flight {
    /// The arclength it goes.
    reach: f64,
    /// The density bound it was drawn under.
    majorant: f64,
    /// Whether it ends at a tentative collision (else at the bound's reach, where the path
    /// draws anew).
    tentative: bool,
}

impl Flight {
    /// The path's next flight from `p` in `medium`.
    fn from(p: DVec3, medium: &Scattering, flights: &mut Flights, rng: &mut impl Rng) -> Self {
        let bound = medium.majorant_near(p);
        let drawn = flights.draw(medium, bound.density, rng);
        Self {
            reach: drawn.min(bound.reach),
            majorant: bound.density,
            tentative: drawn <= bound.reach,
        }
    }
}

impl<'w> Walker<'w> {
    /// A walker allowed the tracer's `max_depth` surfaces.
    pub fn new(tracer: &'w Tracer<'w>, policy: Policy) -> Self {
        Self::carrying(Carried::on(tracer), policy)
    }

    /// A walker for a path carrying `carried`, allowed the surfaces it has left.
    pub fn carrying(carried: Carried<'w>, policy: Policy) -> Self {
        Self {
            tracer: carried.tracer,
            hero: carried.hero,
            policy,
            depth: carried.depth,
            flights: carried.flights,
            choices: Choices::default(),
        }
    }

    /// The walker that makes its first choices between reflection and refraction with
    /// `choices`.
    pub fn choosing(self, choices: Choices) -> Self {
        Self { choices, ..self }
    }

    /// What the path carries now (after the chains it followed).
    pub fn carried(&self) -> Carried<'w> {
        Carried {
            tracer: self.tracer,
            hero: self.hero,
            flights: self.flights,
            depth: self.depth,
        }
    }

    /// Which way its chains carry polarization, where the transport is polarized: a camera
    /// path's against the light, a photon's with it; None for unpolarized transport and for
    /// the chains that stop at the first specular surface or ignore losses.
    fn polarizes(&self) -> Option<Sense> {
        match (self.tracer.settings.polarized, self.policy) {
            (false, _) | (true, Policy::Principal | Policy::Unscattered) => None,
            (true, Policy::Weighted) => Some(Sense::AgainstLight),
            (true, Policy::Roulette) => Some(Sense::WithLight),
        }
    }

    /// Where the path meets dispersion (`disperses`) while it carries every wavelength, it
    /// takes on its hero's: the tracer at that wavelength from here on, and for a path from
    /// the camera the hero's sRGB weight r̄(λ)/p(λ) in its throughput — in expectation over
    /// hero wavelengths the colour the RGB path would have had where the rest of its way does
    /// not depend on λ. A photon's chain records its weight there ([`Chain::dispersed`]).
    fn meet_dispersion(&mut self, disperses: bool, chain: &mut Chain) {
        if let (true, Some(hero)) = (disperses, self.hero) {
            self.tracer = hero.tracer();
            self.hero = None;
            match self.policy {
                Policy::Roulette => {
                    chain.dispersed = Some(chain.weight);
                    chain.weight = Rgb::ONE;
                }
                Policy::Weighted | Policy::Principal | Policy::Unscattered => {
                    chain.weight *= hero.weight
                }
            }
        }
    }

    /// Takes on the hero's wavelength now, where the path still carries every wavelength and
    /// has a hero (a photon meeting a fluorescent layer, which absorbs and emits at
    /// wavelengths); true where it did. Its weight there is the caller's to change.
    pub fn take_on_hero(&mut self) -> bool {
        match self.hero.take() {
            Some(hero) => {
                self.tracer = hero.tracer();
                true
            }
            None => false,
        }
    }

    /// Follows `ray` to the end of its specular chain, drawing from `rng`, adding to `stats`
    /// and telling `observer` what it passes. Counts a depth-limited chain in the statistics.
    pub fn follow<R: Rng>(
        &mut self,
        ray: Ray,
        rng: &mut R,
        stats: &mut Stats,
        observer: &mut dyn ChainEvents,
    ) -> Chain<'w> {
        self.walk(ray, Start::Unpolarized, rng, stats, observer)
    }

    /// [`Walker::follow`] for a camera's first chain, which starts behind `analyzer` (its
    /// polarizer, if any): where the transport is polarized, it measures the light through it
    /// ([`Polarization::measured_through`]) — the whole Stokes vector, in the basis whose first
    /// axis is the unit `stokes_axis` across the ray, where that is given
    /// ([`Polarization::measuring_stokes`]) — and leaves the measurement at the chain's end in
    /// `measure` (None where the transport is not polarized), per unit of what the chain's
    /// weight holds ([`Polarization::close`]): what a camera path carries on past its first
    /// scattering vertex.
    #[allow(clippy::too_many_arguments)]
    pub fn follow_from_camera<R: Rng>(
        &mut self,
        ray: Ray,
        analyzer: Option<&Element>,
        stokes_axis: Option<DVec3>,
        measure: &mut Option<Polarization>,
        rng: &mut R,
        stats: &mut Stats,
        observer: &mut dyn ChainEvents,
    ) -> Chain<'w> {
        let start = Start::Camera {
            analyzer,
            stokes_axis,
            measure,
        };
        self.walk(ray, start, rng, stats, observer)
    }

    /// [`Walker::follow`] for a camera path that carries the measurement `measure` past a
    /// scattering vertex (None: radiance alone, unpolarized transport): it meets what the chain
    /// meets, and is closed where the chain ends ([`Polarization::close`]; the chain's weight
    /// takes on what it records there).
    pub fn follow_measured<R: Rng>(
        &mut self,
        ray: Ray,
        measure: Option<&mut Polarization>,
        rng: &mut R,
        stats: &mut Stats,
        observer: &mut dyn ChainEvents,
    ) -> Chain<'w> {
        match measure {
            Some(rows) => {
                let polarization = self.polarizes().map(|_| rows);
                self.walk_from(ray, polarization, rng, stats, observer)
            }
            None => self.walk(ray, Start::Unpolarized, rng, stats, observer),
        }
    }

    /// [`Walker::follow`] for a chain that starts carrying the polarization `carried` holds
    /// (unpolarized light where it holds none: a photon leaving a source or a depolarizing
    /// vertex) and leaves in it what it carries at its end — what a photon takes on through a
    /// scattering that polarizes ([`crate::volume::Phase::Rayleigh`]). Where the transport is
    /// not polarized, `carried` stays None.
    pub fn follow_carrying<R: Rng>(
        &mut self,
        ray: Ray,
        carried: &mut Option<Polarization>,
        rng: &mut R,
        stats: &mut Stats,
        observer: &mut dyn ChainEvents,
    ) -> Chain<'w> {
        self.walk(ray, Start::Carrying(carried), rng, stats, observer)
    }

    /// Follows `ray` (see [`Walker::follow`]) from the polarization `start` gives.
    fn walk<R: Rng>(
        &mut self,
        ray: Ray,
        start: Start,
        rng: &mut R,
        stats: &mut Stats,
        observer: &mut dyn ChainEvents,
    ) -> Chain<'w> {
        // The polarization lives here (or in the caller's place) and the walk holds a
        // reference to it: an unpolarized walk moves no polarization state around.
        let mut own = None;
        let (place, analyzer, stokes_axis) = match start {
            Start::Unpolarized => (&mut own, None, None),
            Start::Camera {
                analyzer,
                stokes_axis,
                measure,
            } => {
                *measure = None;
                (measure, analyzer, stokes_axis)
            }
            Start::Carrying(carried) => (carried, None, None),
        };
        let polarization = match self.polarizes() {
            None => {
                *place = None;
                None
            }
            Some(sense) => Some(match place {
                Some(carried) => carried,
                None => place.insert(match (sense, analyzer, stokes_axis) {
                    (Sense::AgainstLight, analyzer, Some(axis)) => {
                        Polarization::measuring_stokes(analyzer, ray.direction, axis)
                    }
                    (Sense::AgainstLight, Some(element), None) => {
                        Polarization::measured_through(element, ray.direction)
                    }
                    (Sense::AgainstLight | Sense::WithLight, _, _) => {
                        Polarization::unpolarized(sense, ray.direction)
                    }
                }),
            }),
        };
        self.walk_from(ray, polarization, rng, stats, observer)
    }

    /// Follows `ray` (see [`Walker::follow`]) carrying `polarization` (None: unpolarized).
    fn walk_from<R: Rng>(
        &mut self,
        ray: Ray,
        polarization: Option<&mut Polarization>,
        rng: &mut R,
        stats: &mut Stats,
        observer: &mut dyn ChainEvents,
    ) -> Chain<'w> {
        let mut lent = Lent {
            rng,
            stats,
            polarization,
            crossings: 0,
        };
        let mut chain = Chain {
            end: End::Lost,
            weight: Rgb::ONE,
            medium: ray.medium,
            n_start: 1.0,
            n_end: 1.0,
            specular: 0,
            curved: false,
            emitted: Rgb::ZERO,
            dispersed: None,
        };
        self.meet_dispersion(self.tracer.disperses_in(ray.medium), &mut chain);
        if self.tracer.wave(ray.medium).is_some() {
            lent.stats.lost_in_crystal += 1;
            return chain;
        }
        let Some(n_start) = self.tracer.index(ray.medium, ray.origin) else {
            return chain;
        };
        chain.n_start = n_start;
        let mut at = ray;
        let end = loop {
            if let ControlFlow::Break(end) = self.step(&mut chain, &mut at, &mut lent, observer) {
                break end;
            }
        };
        chain.medium = at.medium;
        if let Some(p) = lent.polarization.as_deref_mut() {
            chain.weight *= p.close();
        }
        if !matches!(end, End::Escaped { .. }) {
            let p = match end {
                End::Scatter(v) => v.position(),
                End::Emitter { position, .. } => position,
                End::Escaped { .. }
                | End::Absorbed { .. }
                | End::Lost
                | End::DepthLimit
                | End::Stopped => at.origin,
            };
            chain.n_end = self.tracer.index(at.medium, p).unwrap_or(1.0);
        }
        chain.end = end;
        chain
    }

    /// Follows the chain from `at` to the end of its stretch: the next surface, the world's
    /// edge, or — where a chain that scatters (weighted or roulette) crosses a scattering
    /// medium — the free flight's collision. In a heterogeneous medium tentative collisions
    /// are drawn at the majorant and the chain goes on past each null one, straight on along
    /// its (curved) way ([`crate::volume`]); a stretch that meets more than
    /// [`MAX_NULL_COLLISIONS`] ends lost, as a march out of steps does. Returns the event
    /// (distance and absorption from `at`) and the stretch's scattering column: the density
    /// integrated along its chords where the weights need it (a coloured σs, or a chain that
    /// does not scatter), else its arclength. `exhausted`: the chain has met `max_depth` events.
    fn fly<R: Rng>(
        &mut self,
        exhausted: bool,
        scattering: Option<&Scattering>,
        chain: &Chain<'w>,
        at: &Ray,
        lent: &mut Lent<R>,
        observer: &mut dyn ChainEvents,
    ) -> (Event, f64) {
        let tracks =
            scattering.filter(|_| matches!(self.policy, Policy::Weighted | Policy::Roulette));
        let mut flight = tracks.map(|sc| Flight::from(at.origin, sc, &mut self.flights, lent.rng));
        observer.stretch(
            &Stretch {
                origin: at.origin,
                direction: at.direction,
                medium: at.medium,
                weight: seen(chain, lent),
                flights: self.flights,
                may_scatter: !exhausted,
                depth: self.depth,
            },
            lent.polarization.as_deref(),
        );
        let integrates = scattering.filter(|sc| {
            sc.is_heterogeneous() && (!sc.is_grey() || self.policy == Policy::Unscattered)
        });
        let mut column = Column {
            scattering: integrates,
            last: at.origin,
            total: 0.0,
        };
        let (mut origin, mut dir) = (at.origin, at.direction);
        let (mut travelled, mut depth) = (0.0, Rgb::ZERO);
        // The polarization's basis, parallel-transported along a curved stretch.
        let carried = (lent.polarization.as_deref_mut()).filter(|_| {
            at.medium
                .is_some_and(|m| !self.tracer.medium(m).is_uniform())
        });
        let follows_basis = carried.is_some();
        if let Some(p) = carried {
            p.begin_curve(at.direction);
        }
        // Points between a step's ends cost a circle's worth of evaluations: computed only
        // for a column, a polarization or an observer that reads them.
        let shown = column.scattering.is_some() || follows_basis || observer.wants_points();
        for _ in 0..=MAX_NULL_COLLISIONS {
            let polarization = &mut lent.polarization;
            let mut show = |p: ArcPoint| {
                column.to(p.position);
                if let Some(carried) = polarization.as_deref_mut() {
                    carried.turn(p.direction);
                }
                observer.point(p.position)
            };
            let event = self.tracer.next_event_within(
                origin,
                dir,
                at.medium,
                flight.map_or(f64::INFINITY, |f| f.reach),
                lent.stats,
                shown.then_some(&mut show as &mut dyn FnMut(ArcPoint)),
            );
            match (event, tracks) {
                (
                    Event::Reached {
                        position,
                        direction,
                        distance,
                        optical_depth,
                    },
                    Some(sc),
                ) if flight.is_some_and(|f| {
                    !f.tentative || !sc.collides(position, f.majorant, lent.rng)
                }) =>
                {
                    column.to(position);
                    if let Some(carried) = lent.polarization.as_deref_mut() {
                        carried.turn(direction);
                    }
                    observer.point(position);
                    (origin, dir) = (position, direction);
                    travelled += distance;
                    depth += optical_depth;
                    flight = Some(Flight::from(position, sc, &mut self.flights, lent.rng));
                }
                _ => {
                    if let Some(end) = event.position() {
                        column.to(end);
                    }
                    if let Some(carried) = lent.polarization.as_deref_mut() {
                        if let Some(d) = event.direction() {
                            carried.end_curve(d);
                        }
                    }
                    let event = event.continuing(travelled, depth);
                    let column = match column.scattering {
                        Some(_) => column.total,
                        None => event.distance(),
                    };
                    return (event, column);
                }
            }
        }
        lent.stats.record_end(crate::curve::Termination::MaxSteps);
        (Event::Lost, 0.0)
    }

    /// Moves the chain to its next event: `Break` with how it ends, or `Continue` past a
    /// detector or a specular surface. Inlined into the walk's loop, so that how it ends (an
    /// [`End`] of 216 bytes) is not copied through memory at every event (3 % of a Cornell
    /// box's path-traced time where it was not).
    #[inline(always)]
    fn step<R: Rng>(
        &mut self,
        chain: &mut Chain<'w>,
        at: &mut Ray,
        lent: &mut Lent<R>,
        observer: &mut dyn ChainEvents,
    ) -> ControlFlow<End<'w>> {
        let scene = self.tracer.scene;
        // A chain that may meet nothing more still goes as far as its next event: light it
        // reaches there (an emitter, the sky) counts, as a path of max_depth interactions
        // and one more segment to the light; an interaction there is cut.
        let exhausted = self.depth == 0;
        let cut = |lent: &mut Lent<R>| {
            lent.stats.depth_limited += 1;
            ControlFlow::Break(End::DepthLimit)
        };
        self.depth = self.depth.saturating_sub(1);
        let met = self.tracer.settings.max_depth.saturating_sub(self.depth);
        if self.policy == Policy::Weighted && !exhausted && met > ROULETTE_AFTER {
            if lent.rng.gen::<f64>() >= ROULETTE_SURVIVAL {
                return ControlFlow::Break(End::Absorbed { medium: None });
            }
            chain.weight /= ROULETTE_SURVIVAL;
        }
        self.meet_dispersion(self.tracer.disperses_in(at.medium), chain);
        chain.curved |= at
            .medium
            .is_some_and(|m| !self.tracer.medium(m).is_uniform());
        let scattering = at.medium.and_then(|m| self.tracer.scattering(m));
        let (event, column) = self.fly(exhausted, scattering.as_deref(), chain, at, lent, observer);
        if let Some(sc) = scattering.as_deref() {
            chain.weight *= match (self.policy, event) {
                (Policy::Weighted | Policy::Roulette, Event::Reached { .. }) => {
                    self.flights.weigh(sc, column, true)
                }
                (Policy::Weighted | Policy::Roulette, _) => self.flights.weigh(sc, column, false),
                // Light scattered out of a shadow-like ray is not followed: it is lost to it.
                (Policy::Unscattered, _) => sc.transmittance(column),
                // The principal ray is geometry: scattering does not change its way.
                (Policy::Principal, _) => Rgb::ONE,
            };
        }
        self.gather_emission(chain, lent, at.medium, &event, observer);
        let hit = match event {
            Event::Lost => return ControlFlow::Break(End::Lost),
            _ if self.absorbed(chain, event.transmittance(), lent.rng) => {
                return ControlFlow::Break(End::Absorbed { medium: at.medium })
            }
            Event::Surface { hit, .. } => hit,
            Event::Escaped {
                position,
                direction,
                ..
            } => {
                observer.point(position);
                chain.n_end = self.tracer.index(at.medium, position).unwrap_or(1.0);
                return ControlFlow::Break(End::Escaped { direction });
            }
            Event::Reached { .. } if exhausted => return cut(lent),
            Event::Reached {
                position,
                direction,
                ..
            } => {
                observer.point(position);
                if self.dye_absorbs(chain, at.medium) {
                    return ControlFlow::Break(End::Absorbed { medium: at.medium });
                }
                let phase = scattering
                    .expect("a free flight in a scattering medium")
                    .phase;
                return ControlFlow::Break(End::Scatter(Vertex::Medium(MediumVertex {
                    position,
                    wo: -direction,
                    medium: at.medium,
                    phase,
                })));
            }
        };
        observer.point(hit.position);
        let surface = scene.surface(hit.prim);
        match surface.role {
            Role::Emitter(_) if self.tracer.wave(at.medium).is_some() => {
                lent.stats.lost_in_crystal += 1;
                ControlFlow::Break(End::Lost)
            }
            Role::Emitter(light) => {
                let front = hit.incoming.dot(hit.normals.geometric) < 0.0;
                ControlFlow::Break(End::Emitter {
                    prim: hit.prim,
                    radiance: match front {
                        true => self
                            .tracer
                            .emitted_by(light.index(), scene.light(light).surface_radiance()),
                        false => Rgb::ZERO,
                    },
                    position: hit.position,
                    normal: hit.normals.geometric,
                    direction: hit.incoming,
                })
            }
            Role::Detector(_) if exhausted => cut(lent),
            Role::Detector(receiver) => {
                let crossing = DetectorCrossing {
                    receiver,
                    position: hit.position,
                    direction: hit.incoming,
                    weight: chain.weight,
                    polarization: lent.polarization.as_deref(),
                };
                if observer.detector(&crossing).is_break() {
                    return ControlFlow::Break(End::Stopped);
                }
                // On from the crossing as it arrived there: along a curved stretch its
                // direction is no longer the stretch's first.
                at.origin = super::offset(hit.position, hit.incoming);
                at.direction = hit.incoming;
                ControlFlow::Continue(())
            }
            Role::Scatter(material) => {
                let dielectric = matches!(
                    scene.materials[material.index()],
                    Material::Dielectric { .. }
                );
                // Only a dielectric may be no surface at all (an index-matched one).
                if exhausted && !dielectric {
                    return cut(lent);
                }
                if dielectric {
                    self.meet_dispersion(self.tracer.disperses_at(surface), chain);
                }
                let Some(vertex) = self.tracer.vertex(hit, surface, at.medium) else {
                    lent.stats.undefined_index += 1;
                    return ControlFlow::Break(End::Lost);
                };
                if self.tracer.has_crystals {
                    if let Some(flow) =
                        self.at_crystal(chain, at, &vertex, exhausted, lent, observer)
                    {
                        return flow;
                    }
                }
                if self.tracer.crosses_unchanged(&vertex) {
                    lent.crossings += 1;
                    if lent.crossings > MAX_CROSSINGS {
                        lent.stats.record_end(crate::curve::Termination::MaxSteps);
                        return ControlFlow::Break(End::Lost);
                    }
                    // No event: the depth it was charged is given back.
                    self.depth = match exhausted {
                        true => 0,
                        false => self.depth + 1,
                    };
                    return self.cross(at, &vertex, observer);
                }
                if exhausted {
                    return cut(lent);
                }
                match vertex.lobes().is_specular() {
                    true => self.bounce(chain, at, &vertex, lent, observer),
                    false => ControlFlow::Break(End::Scatter(Vertex::Surface(vertex))),
                }
            }
        }
    }

    /// Adds to a camera path's chain the light `medium` emitted along the stretch to `event`
    /// and did not absorb again: Le·(1 − e^(−τa)) as basic radiance, exact for any density and
    /// any curved path ([`crate::volume::Emission`]), times the chain's weight at the
    /// stretch's start as the camera sees it there ([`seen`]; its free flight weighed in: the
    /// flight's survival stands for the scattering along the way, as for anything met at its
    /// end). The light leaves the medium unpolarized; where the chain carries the camera's
    /// measurement, `observer` is given it as the camera records it through the measurement
    /// ([`ChainEvents::emitted`]).
    fn gather_emission<R>(
        &self,
        chain: &mut Chain,
        lent: &Lent<R>,
        medium: Option<MediumId>,
        event: &Event,
        observer: &mut dyn ChainEvents,
    ) {
        let emission = medium.and_then(|m| self.tracer.participating(m).emission);
        if let (Policy::Weighted, Some(emission), false) =
            (self.policy, emission, *event == Event::Lost)
        {
            let basic = self.tracer.radiance(emission.along(event.optical_depth()));
            let scale = chain.n_start * chain.n_start;
            chain.emitted += seen(chain, lent) * basic * scale;
            if let Some(p) = lent.polarization.as_deref() {
                observer.emitted(p.recorded() * (chain.weight * basic * scale));
            }
        }
    }

    /// Whether a dye in `medium` absorbs the path at a collision there: a collision at the
    /// tracer's wavelength is the dye's absorption in the share [`Tracer::dye_share`] gives.
    /// A camera path goes on weighed by the share that scatters (ending where none does); a
    /// photon's [`crate::photon`] tracing plays for it where it meets the vertex, and every
    /// other chain makes no collision.
    fn dye_absorbs(&self, chain: &mut Chain, medium: Option<MediumId>) -> bool {
        let Some((_, share)) = medium.and_then(|m| self.tracer.dye_share(m)) else {
            return false;
        };
        match self.policy {
            Policy::Weighted if share >= 1.0 => true,
            Policy::Weighted => {
                chain.weight *= 1.0 - share;
                false
            }
            Policy::Roulette | Policy::Principal | Policy::Unscattered => false,
        }
    }

    /// Carries a stretch's transmittance `kept` (per channel) by the policy; true when Russian
    /// roulette absorbs the path there. A photon goes on with the probability of its largest
    /// channel's, its power weighed by each channel's over that (1 in every channel where
    /// absorption is grey), as at a coloured surface.
    fn absorbed(&self, chain: &mut Chain, kept: Rgb, rng: &mut impl Rng) -> bool {
        match self.policy {
            Policy::Weighted | Policy::Unscattered => {
                chain.weight *= kept;
                false
            }
            Policy::Roulette => {
                let survive = kept.max_element();
                if survive < 1.0 && rng.gen::<f64>() >= survive {
                    return true;
                }
                if !kept.is_grey() {
                    chain.weight *= kept / survive;
                }
                false
            }
            Policy::Principal => false,
        }
    }

    /// Takes the chain straight on through the index-matched `vertex`
    /// ([`Tracer::crosses_unchanged`]) into the medium beyond: no specular bounce, no event
    /// of its depth, no choice drawn, its weight and polarization unchanged (the interface's Mueller matrix is the
    /// identity); the observer is told of a crossing into another medium as of a refraction
    /// (one between the same medium on both sides is no event to it: it would read as a
    /// reflection).
    fn cross(
        &mut self,
        at: &mut Ray,
        vertex: &SurfaceVertex,
        observer: &mut dyn ChainEvents,
    ) -> ControlFlow<End<'w>> {
        let into_another = vertex.beyond != at.medium;
        if into_another
            && observer
                .specular(vertex.prim, at.medium, vertex.beyond)
                .is_break()
        {
            return ControlFlow::Break(End::Stopped);
        }
        *at = Ray {
            origin: super::offset(vertex.position, -vertex.normal),
            direction: -vertex.wo,
            medium: vertex.beyond,
        };
        ControlFlow::Continue(())
    }

    /// Carries a specular event's `weight` (per channel) by the policy: a camera path's weight
    /// takes it, a photon goes on with its largest channel's probability (its power weighed by
    /// each channel's over that); true where Russian roulette absorbs the photon there.
    fn absorbed_at_specular(&self, chain: &mut Chain, weight: Rgb, rng: &mut impl Rng) -> bool {
        match self.policy {
            Policy::Weighted => chain.weight *= weight,
            Policy::Roulette => {
                let survive = weight.max_element();
                if survive < 1.0 && rng.gen::<f64>() >= survive {
                    return true;
                }
                chain.weight *= weight / survive.clamp(f64::MIN_POSITIVE, 1.0);
            }
            Policy::Principal | Policy::Unscattered => {}
        }
        false
    }

    /// Reflects or refracts the chain at the purely specular `vertex`.
    fn bounce(
        &mut self,
        chain: &mut Chain,
        at: &mut Ray,
        vertex: &SurfaceVertex,
        lent: &mut Lent<impl Rng>,
        observer: &mut dyn ChainEvents,
    ) -> ControlFlow<End<'w>> {
        let u = match self.policy {
            Policy::Unscattered => return ControlFlow::Break(End::Stopped),
            // A mirror makes no choice and draws no number.
            _ if !vertex.bsdf.draws_choice() => 0.0,
            Policy::Principal => 0.5,
            _ => self.choices.next().unwrap_or_else(|| lent.rng.gen()),
        };
        let Some(b) = vertex.scatter((0.0, 0.0, u)) else {
            return ControlFlow::Break(End::Lost);
        };
        let mut weight = b.sample.weight;
        if let Some(p) = lent.polarization.as_deref_mut() {
            match vertex
                .bsdf
                .mueller(vertex.wo, b.sample.wi, vertex.normal, p.sense())
            {
                Some(element) => weight *= p.meet(&element, -vertex.wo),
                None => p.depolarize(),
            }
        }
        if self.absorbed_at_specular(chain, weight, lent.rng) {
            return ControlFlow::Break(End::Absorbed { medium: None });
        }
        chain.specular += 1;
        if observer
            .specular(vertex.prim, at.medium, b.ray.medium)
            .is_break()
        {
            return ControlFlow::Break(End::Stopped);
        }
        *at = b.ray;
        ControlFlow::Continue(())
    }
}

impl<'w> Walker<'w> {
    /// Where the scene holds a crystal: the chain's way on from the surface `vertex` where it
    /// is a crystal's face ([`Walker::split`]; cut where the chain may meet nothing more), or
    /// lost where the chain is inside a crystal and the surface is none of its faces; None
    /// where neither side is a crystal. Kept out of the walk's loop, which scenes without a
    /// crystal never bring here.
    #[cold]
    #[inline(never)]
    fn at_crystal(
        &mut self,
        chain: &mut Chain,
        at: &mut Ray,
        vertex: &SurfaceVertex,
        exhausted: bool,
        lent: &mut Lent<impl Rng>,
        observer: &mut dyn ChainEvents,
    ) -> Option<ControlFlow<End<'w>>> {
        match self.tracer.crystal_interface(vertex) {
            Some(_) if exhausted => {
                lent.stats.depth_limited += 1;
                Some(ControlFlow::Break(End::DepthLimit))
            }
            Some(interface) => Some(self.split(chain, at, vertex, &interface, lent, observer)),
            None if self.tracer.wave(at.medium).is_some() => {
                lent.stats.lost_in_crystal += 1;
                Some(ControlFlow::Break(End::Lost))
            }
            None => None,
        }
    }

    /// Splits the chain at `vertex`, a face of a crystal ([`Interface`]): a photon (with the
    /// light) goes on as one of the beams the light arriving leaves as, a camera path (against
    /// it) as one of the beams feeding the light it carries back, each drawn in proportion to
    /// its power (of unpolarized light on an isotropic side, of its own wave's in a crystal)
    /// and weighed by the branches' summed power — 1 for a photon, the power kept — and the
    /// factor its Mueller matrix gives the polarization carried. The principal ray takes the
    /// strongest; a chain that stops at the first specular surface stops.
    fn split(
        &mut self,
        chain: &mut Chain,
        at: &mut Ray,
        vertex: &SurfaceVertex,
        interface: &Interface,
        lent: &mut Lent<impl Rng>,
        observer: &mut dyn ChainEvents,
    ) -> ControlFlow<End<'w>> {
        let wave = self.tracer.wave(at.medium);
        let with_light = match self.policy {
            Policy::Unscattered => return ControlFlow::Break(End::Stopped),
            Policy::Roulette | Policy::Principal => true,
            Policy::Weighted => false,
        };
        let branches = match with_light {
            true => interface.scatter(Beam {
                direction: -vertex.wo,
                wave,
            }),
            false => interface.gather(Beam {
                direction: vertex.wo,
                wave,
            }),
        };
        let total = branches.power();
        let chosen = match self.policy {
            Policy::Principal => (branches.iter()).max_by(|a, b| a.power().total_cmp(&b.power())),
            Policy::Weighted | Policy::Roulette | Policy::Unscattered => {
                let u = self.choices.next().unwrap_or_else(|| lent.rng.gen()) * total;
                let mut sum = 0.0;
                let mut last = None;
                (branches.iter())
                    .find(|b| {
                        sum += b.power();
                        last = Some(*b);
                        u < sum
                    })
                    .or(last)
            }
        };
        let Some(branch) = chosen.copied().filter(|_| total > 0.0) else {
            return ControlFlow::Break(End::Absorbed { medium: None });
        };
        let mut weight = Rgb::splat(total);
        if let Some(p) = lent.polarization.as_deref_mut() {
            weight *= p.meet(&branch.element, -vertex.wo);
        }
        if self.absorbed_at_specular(chain, weight, lent.rng) {
            return ControlFlow::Break(End::Absorbed { medium: None });
        }
        let (side, normal) = match branch.beyond {
            true => (vertex.beyond, -vertex.normal),
            false => (vertex.medium, vertex.normal),
        };
        let medium = match (side, branch.beam.wave) {
            (Some(m), Some(w)) => Some(self.tracer.scene.media().of_wave(m, w)),
            (side, None) => side,
            // A wave is a crystal's, and a crystal is a medium: no beam has one in vacuum.
            (None, Some(_)) => None,
        };
        let direction = match with_light {
            true => branch.beam.direction,
            false => -branch.beam.direction,
        };
        chain.specular += 1;
        if observer.specular(vertex.prim, at.medium, medium).is_break() {
            return ControlFlow::Break(End::Stopped);
        }
        *at = Ray {
            origin: super::offset(vertex.position, normal),
            direction,
            medium,
        };
        ControlFlow::Continue(())
    }
}

/// The principal ray from `origin` along unit `dir` in `medium` (see [`Policy::Principal`]),
/// followed to the first receiver detector it crosses: the crossing point and the number of
/// surfaces met before it; None when it escapes, is lost, reaches a diffuse or emissive
/// surface, or has met `max_events` surfaces.
pub fn principal_ray(
    tracer: &Tracer,
    origin: DVec3,
    dir: DVec3,
    medium: Option<MediumId>,
    max_events: u32,
) -> Option<(DVec3, u32)> {
    struct FirstDetector(Option<DVec3>);
    impl ChainEvents for FirstDetector {
        fn detector(&mut self, crossing: &DetectorCrossing) -> ControlFlow<()> {
            self.0 = Some(crossing.position);
            ControlFlow::Break(())
        }
    }
    let mut found = FirstDetector(None);
    let mut walker = Walker::new(tracer, Policy::Principal);
    walker.depth = max_events;
    let ray = Ray {
        origin,
        direction: dir,
        medium,
    };
    let (mut unused, mut stats) = (rand_pcg::Pcg64Mcg::new(1), Stats::default());
    let chain = walker.follow(ray, &mut unused, &mut stats, &mut found);
    (chain.end == End::Stopped).then_some(())?;
    found.0.map(|p| (p, chain.specular))
}
