//! The forward photon pass (Zhdanov et al. (2020) §4, Jensen's photon mapping): photons leave the lights in
//! proportion to their power, travel with the same transport as camera rays (curved in
//! gradient media, Fresnel at dielectrics, mirrors), and are stored at diffuse hits.
//!
//! Two maps, each from its own batch of photons:
//! - **caustic**: photons whose path is L (S|G)+ D — at least one specular bounce or one
//!   traversal of a non-uniform medium before the first diffuse hit — stored at that hit;
//! - **global**: every diffuse hit of every photon, followed by Lambertian bounces with
//!   Russian roulette on the albedo.
//!
//! A third batch feeds the receivers: nothing is stored, every receiver crossing is recorded.
//! Every batch books each photon's power in an energy [`Budget`] when its path ends, and
//! [`photon_paths`] replays photons of the receiver batch keeping their paths, for figures.
//!
//! Photon `i` of pass `p` draws from the stream (seed, batch, p, i), and photons are traced in
//! fixed chunks whose results are concatenated in order, so a map does not depend on the
//! thread count.

mod budget;
mod map;
mod shell;
mod volume;

pub use budget::{Budget, Dye, DyeEvent, DyeSite, Ended, Fate, Ledger};
pub use map::{Photon, PhotonMap, Summand, TracedPhotons};
pub use shell::Shell;
pub use volume::VolumeMap;

use crate::bsdf::{Bsdf, Lobes};
use crate::color::Rgb;
use crate::curve::Bounds;
use crate::environment::Environment;
use crate::ids::{MediumId, PrimId};
use crate::lights::{Aim, Cone, Emission, Entry, Light};
use crate::math::Ball;
use crate::polarization::{Polarization, Sense, StoredStokes};
use crate::receiver::Detection;
use crate::sampling::{cosine_hemisphere, stream, uniform_sphere, Discrete, Frame, Pick, Purpose};
use crate::spectrum::{colour, Fluorophore, Spectrum};
use crate::transport::chain::{self, End, Policy, Ray};
use crate::transport::{HeroTracer, MediumVertex, Scattered, Stats, Tracer, Vertex};
use glam::DVec3;
use rand::Rng;
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use std::ops::ControlFlow;

/// Photons per chunk of parallel work.
const CHUNK: u64 = 4096;

/// Something that emits photons.
#[derive(Clone, Copy)]
enum Source<'a> {
    Light(&'a Light),
    Environment(&'a Environment),
    /// The light the ambient medium scatters outside the scene ball (map photons).
    Shell(Shell),
}

/// A photon source with what its photons start in.
#[derive(Clone, Copy)]
struct Placed<'a> {
    source: Source<'a>,
    /// The medium its photons start in.
    medium: Option<MediumId>,
    /// The spectrum it was given (None: its colour is its RGB, and its spectrum D65).
    spectrum: Option<&'a Spectrum>,
}

/// A photon leaving a source: where, which way, with what power, in which medium, at which
/// wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Launch {
    /// Where, which way and with what power (already divided by the selection probability).
    pub emission: Emission,
    /// The medium it starts in.
    pub medium: Option<MediumId>,
    /// Its vacuum wavelength (nm), drawn from its source's spectrum when the photon feeds
    /// receivers in a spectral scene ([`crate::scene::Scene::is_spectral`]); its power is then
    /// that one wavelength's (`Launch::draw_wavelength`). None: it carries every wavelength
    /// (RGB) and sees each medium at [`crate::spectrum::LAMBDA_D`] — until it meets
    /// dispersion, if it has a `hero`.
    pub wavelength: Option<f64>,
    /// For a photon of a photon map in a dispersive scene: the wavelength it takes on where
    /// it meets dispersion, and its power there.
    pub hero: Option<PhotonHero>,
    /// For a map photon from a light or the environment in a scene whose ambient medium
    /// scatters outside the scene ball: that ball. Where such a photon first scatters outside
    /// it, it ends: light scattered there first is the shell's ([`Shell`]).
    pub shell: Option<Ball>,
    /// Whether it has scattered in a medium already: a photon of the shell.
    pub scattered: bool,
}

/// The wavelength a photon carrying every wavelength takes on where it meets dispersion —
/// drawn at its launch from its source's spectrum — and its power there per unit of the
/// throughput it has gathered on the way (W, the same in every channel from there on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhotonHero {
    /// Vacuum wavelength, nm.
    pub nm: f64,
    /// Power at launch at this wavelength (`Launch::draw_wavelength`).
    pub power: f64,
}

impl Launch {
    /// A vacuum wavelength drawn (uniform `u`) from the photon's source's spectrum — `given`,
    /// or D65 for a source whose colour is its RGB — and the power the photon carries there,
    /// the same in every channel (W, as an estimate over wavelengths): for a given spectrum,
    /// the light's power key ([`Launch::radiometric`]); for an RGB source of colour P, whose
    /// spectral power is the reflectance spectrum of P times D65 ([`colour::illuminant`]) and
    /// whose wavelengths are drawn from D65, the reflectance spectrum of P at the wavelength.
    /// Where such a photon is stored it is read in sRGB through [`colour::sensor`].
    fn draw_wavelength(&self, given: Option<&Spectrum>, u: f64) -> PhotonHero {
        match given {
            Some(spectrum) => PhotonHero {
                nm: spectrum.sample(u),
                power: self.radiometric(given).emission.power.x,
            },
            None => {
                let nm = Spectrum::white().sample(u);
                PhotonHero {
                    nm,
                    power: colour::reflectance(self.emission.power, nm),
                }
            }
        }
    }

    /// The same photon at one wavelength from the launch on ([`Launch::draw_wavelength`]).
    fn at_wavelength(self, given: Option<&Spectrum>, u: f64) -> Launch {
        let drawn = self.draw_wavelength(given, u);
        Launch {
            emission: Emission {
                power: Rgb::splat(drawn.power),
                ..self.emission
            },
            wavelength: Some(drawn.nm),
            ..self
        }
    }

    /// The same photon with its power in W, as receivers count it: a light with a `given`
    /// spectrum was tinted by the spectrum's colour for the images (its channels' mean is
    /// taken off again, leaving the power key's value in every channel); any other is as it is
    /// (receivers count the mean of its channels).
    fn radiometric(self, given: Option<&Spectrum>) -> Launch {
        let Some(spectrum) = given else { return self };
        let tint = spectrum.colour().0.max(DVec3::ZERO).element_sum() / 3.0;
        Launch {
            emission: Emission {
                power: Rgb::splat(self.emission.power.mean() / tint),
                ..self.emission
            },
            ..self
        }
    }
}

/// The scene's photon sources with a discrete distribution proportional to their power.
pub struct Sources<'a> {
    sources: Vec<Placed<'a>>,
    /// Where parallel and environment light is sent.
    aim: Aim,
    /// For map photons where the ambient medium absorbs or scatters: that medium. Parallel
    /// and environment light set off upstream of the scene carrying what it lets through
    /// unscattered from the world sphere to there.
    crossed: Option<MediumId>,
    /// For map photons where the ambient medium scatters outside the scene ball: that part
    /// of it, a source of its own.
    shell: Option<Shell>,
    /// Whether receiver photons carry a wavelength ([`crate::scene::Scene::is_spectral`]).
    spectral: bool,
    /// Whether map photons take a hero wavelength ([`crate::scene::Scene::is_dispersive`]).
    dispersive: bool,
    /// Whether a surface has a fluorescent layer: map photons then take a hero wavelength,
    /// which they take on where they meet a layer ([`crate::scene::Scene::fluoresces`]).
    layers: bool,
    /// How a photon picks its source (None: nothing emits).
    choice: Option<Discrete>,
}

impl<'a> Sources<'a> {
    /// The sources of the global map's photons: the lights and the environment of the
    /// tracer's scene, each with the medium it emits into (a light inside a dielectric shape
    /// emits into its interior; parallel and environment light into the ambient medium) —
    /// and, in open scattering fog, the fog outside the scene ([`Shell`]); sources of zero
    /// power are left out.
    pub fn new(tracer: &Tracer<'a>) -> Self {
        Self::aimed(tracer, Aim::whole(tracer.ball, Entry::Upstream), true)
    }

    /// The sources of receiver photons: the lights and the environment as [`Sources::new`],
    /// traced as light travels — parallel and environment light from the world sphere where
    /// the ambient medium absorbs or scatters —, so that each photon's power is booked where
    /// it really goes.
    pub fn for_receivers(tracer: &Tracer<'a>) -> Self {
        Self::aimed(tracer, Aim::whole(tracer.ball, world_entry(tracer)), false)
    }

    /// The sources of caustic photons: as [`Sources::new`], but sent only through a ball
    /// holding the scene's specular surfaces (mirrors, dielectrics), as Jensen's projection
    /// maps do — a caustic photon must meet one before its first diffuse surface: parallel and
    /// environment light from upstream of the scene, light from points and surfaces within
    /// the ball's cone ([`Light::emit`]). The ball holds each such surface's own bounding ball
    /// (a sphere's is itself) and is grown by 10 % for photons that curve into them in a
    /// gradient medium (those bent in from farther are missed). A small glass object in a
    /// large sunlit scene then catches (R/r)² times more of them; the Cornell box's glass
    /// ball under its ceiling light, 21 times more.
    pub fn for_caustics(tracer: &Tracer<'a>) -> Self {
        let scene = tracer.scene;
        let balls: Vec<Ball> = scene
            .accel
            .primitives()
            .iter()
            .zip(&scene.surfaces)
            .filter(|(_, s)| {
                scene
                    .material(**s)
                    .is_some_and(|m| m.lobes() != Lobes::DIFFUSE_REFLECTION)
            })
            .map(|(p, _)| p.bounding_ball())
            .collect();
        let (lo, hi) = balls
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.center - b.radius), hi.max(b.center + b.radius))
            });
        let center = 0.5 * (lo + hi);
        let radius = balls
            .iter()
            .map(|b| (b.center - center).length() + b.radius)
            .fold(0.0, f64::max);
        let target = Ball {
            center,
            radius: 1.1 * radius,
        };
        // A scattering medium may fill the scene: caustic photons are wanted everywhere.
        let fog = scene.media().any_scatters();
        let aim = Aim {
            scene: tracer.ball,
            target: if !fog && !balls.is_empty() && target.radius < tracer.ball.radius {
                target
            } else {
                tracer.ball
            },
            entry: Entry::Upstream,
        };
        Self::aimed(tracer, aim, true)
    }

    /// The sources sent as `aim` says, for the maps (`maps`: with the ambient medium's
    /// transmittance and its shell) or for receivers.
    fn aimed(tracer: &Tracer<'a>, aim: Aim, maps: bool) -> Self {
        let scene = tracer.scene;
        let crossed = match (maps, world_entry(tracer)) {
            (true, Entry::World { .. }) => scene.ambient(),
            (false, Entry::World { .. }) | (_, Entry::Upstream) => None,
        };
        // About what parallel and environment light keeps of its power on its way in: the
        // transmittance from the world sphere to the upstream start along a line through the
        // scene's centre, for weighing it against the other sources.
        let crossed_share = crossed.map_or(1.0, |m| {
            let Ball { center, radius } = tracer.ball;
            let length = (tracer.world.scale() - 2.0 * radius).max(0.0);
            let sigma_s = tracer.scattering(m).map_or(0.0, |sc| {
                sc.sigma_s.mean() * sc.majorant_near(center).density
            });
            (-(tracer.participating(m).sigma_a(center).max_element() + sigma_s) * length).exp()
        });
        let mut sources = Vec::new();
        let mut weights = Vec::new();
        for (i, light) in scene.lights.iter().enumerate() {
            let medium = match light.origin() {
                Some(p) => tracer.medium_containing(p),
                None => scene.ambient(),
            };
            sources.push(Placed {
                source: Source::Light(light),
                medium,
                spectrum: scene.light_spectrum(i),
            });
            let crossing = match light.origin() {
                None => crossed_share,
                Some(_) => 1.0,
            };
            weights.push(light.selection_power(aim) * crossing);
        }
        if let Some(env) = &scene.environment {
            sources.push(Placed {
                source: Source::Environment(env),
                medium: scene.ambient(),
                spectrum: None,
            });
            weights.push(env.selection_power(aim) * crossed_share);
        }
        // The shell, where its pilot photons found light to send (a closed room's walls hide
        // every light from the fog outside it): then photons that first scatter there end.
        let others: f64 = weights.iter().filter(|w| w.is_finite() && **w > 0.0).sum();
        let shell = maps
            .then(|| Shell::of(tracer))
            .flatten()
            .map(|shell| {
                let dispersive = tracer.disperses_in(Some(shell.medium));
                (shell, shell.selection_power(tracer, dispersive))
            })
            .filter(|(_, pilot)| *pilot > 0.0);
        if let Some((shell, pilot)) = shell {
            sources.push(Placed {
                source: Source::Shell(shell),
                medium: Some(shell.medium),
                spectrum: None,
            });
            // At least a tenth of the photons: a pilot that barely found the shell's light (a
            // small lamp seen from far out in the fog) must not leave it to rare heavy photons.
            weights.push(pilot.max(others / 9.0));
        }
        let shell = shell.map(|(shell, _)| shell);
        let (kept, weights): (Vec<Placed>, Vec<f64>) = sources
            .into_iter()
            .zip(weights)
            .filter(|(_, w)| w.is_finite() && *w > 0.0)
            .unzip();
        Self {
            choice: Discrete::new(&weights),
            sources: kept,
            aim,
            crossed,
            shell,
            spectral: scene.is_spectral(),
            dispersive: scene.is_dispersive(),
            layers: scene.fluoresces(),
        }
    }

    /// True when nothing emits.
    pub fn is_empty(&self) -> bool {
        self.sources.is_empty()
    }

    /// A photon for uniform numbers `u` (u[0] picks the source) and, for the shell, more from
    /// `rng`, with the power divided by the selection probability, and the source's spectrum.
    /// Environment radiance is given as in vacuum (see
    /// [`crate::transport::chain::Chain::environment_scale`]): in an ambient medium of index
    /// n at the photon's start, its power is n² times the vacuum estimate.
    fn emit(
        &self,
        tracer: &Tracer,
        u: [f64; 5],
        rng: &mut impl Rng,
        stats: &mut Stats,
    ) -> Option<(Launch, Option<&Spectrum>)> {
        let Pick {
            index: i,
            probability: p,
        } = self.choice.as_ref()?.pick(u[0]);
        let rest = [u[1], u[2], u[3], u[4]];
        let Placed {
            source,
            medium,
            spectrum,
        } = self.sources[i];
        let mut hero = None;
        let e = match source {
            Source::Light(l) => self.crossing(tracer, l.emit(rest, self.aim)?, l.origin()),
            Source::Environment(env) => {
                let e = self.crossing(tracer, env.emit(rest, self.aim)?, None);
                let n = tracer.index(medium, e.origin).unwrap_or(1.0);
                Emission {
                    power: e.power * (n * n),
                    ..e
                }
            }
            Source::Shell(shell) => {
                let dispersive = tracer.disperses_in(Some(shell.medium));
                let photon = shell.emit(tracer, rest, dispersive, rng, stats)?;
                hero = photon.hero.map(|(nm, power)| PhotonHero {
                    nm,
                    power: power / p,
                });
                photon.emission
            }
        };
        let launch = Launch {
            emission: Emission {
                power: e.power / p,
                ..e
            },
            medium,
            wavelength: None,
            hero,
            shell: match source {
                Source::Shell(_) => None,
                Source::Light(_) | Source::Environment(_) => self.shell.map(|s| s.ball),
            },
            scattered: matches!(source, Source::Shell(_)),
        };
        Some((launch, spectrum))
    }

    /// Light from beyond the world (`origin` None: parallel or environment light), as a map
    /// photon `e` sets off upstream of the scene: with what the ambient medium it crossed from
    /// the world sphere lets through unscattered (absorption and scattering along the line).
    fn crossing(&self, tracer: &Tracer, e: Emission, origin: Option<DVec3>) -> Emission {
        let Some(m) = self.crossed.filter(|_| origin.is_none()) else {
            return e;
        };
        let back = tracer.world.exit_distance(e.origin, -e.direction);
        if !back.is_finite() {
            return e;
        }
        let from = e.origin - e.direction * back;
        Emission {
            power: e.power * tracer.transmittance(Some(m), from, e.direction, back),
            ..e
        }
    }
}

/// Where parallel and environment light enters the tracer's scene as it travels: at the world
/// sphere where the ambient medium absorbs or scatters (light crosses all of it from beyond
/// the world, as the camera's paths see), else upstream of the scene.
fn world_entry(tracer: &Tracer) -> Entry {
    let scene = tracer.scene;
    let Some(ambient) = scene.ambient() else {
        return Entry::Upstream;
    };
    let scatters = scene.media().scattering(ambient).is_some();
    let absorbs = scene.media().participating(ambient).absorption.is_some();
    match (tracer.world, scatters || absorbs) {
        (Bounds::Ball { center, radius }, true) => Entry::World {
            ball: Ball { center, radius },
            scatters,
        },
        (
            Bounds::Ball { .. } | Bounds::Box { .. } | Bounds::HalfSpace { .. } | Bounds::Unbounded,
            _,
        ) => Entry::Upstream,
    }
}

/// What a batch of photons is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Batch {
    /// The caustic map: stored at the first diffuse hit after a specular bounce or a gradient
    /// medium; the photon ends there.
    Caustic,
    /// The global map: stored at every diffuse hit.
    Global,
    /// Receivers: nothing is stored; every crossing of a receiver is recorded.
    Receivers,
}

/// What a batch leaves behind, in photon order.
#[derive(Clone, Debug, Default)]
pub struct Sink {
    /// Photons stored at diffuse hits.
    pub photons: TracedPhotons,
    /// Caustic photons stored where they first scattered in a medium.
    pub volume: TracedPhotons,
    /// Receiver crossings.
    pub detections: Vec<Detection>,
    /// Where the photons' power went.
    pub budget: Ledger,
}

/// Which photons a batch traces: photons `traced` of the `count` of pass `pass` (each
/// carrying 1/`count` of the power), their random streams keyed by `seed` and by what the
/// batch is for. Photon `i` is the same photon whatever range it is traced in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Photons {
    /// What the batch is for.
    pub batch: Batch,
    /// Seed of the random streams.
    pub seed: u64,
    /// The pass.
    pub pass: u64,
    /// How many photons the batch has.
    pub count: u64,
    /// Which of them are traced (a sub-range of `0..count`).
    pub traced: std::ops::Range<u64>,
}

impl Photons {
    /// All `count` photons of pass `pass` of `batch`.
    pub fn all(batch: Batch, seed: u64, pass: u64, count: u64) -> Photons {
        Photons {
            batch,
            seed,
            pass,
            count,
            traced: 0..count,
        }
    }

    /// The random stream of photon `i`, advanced past its launch from `sources`, and the
    /// launch (None where the chosen source emits nothing for these numbers).
    fn launch(
        &self,
        tracer: &Tracer,
        sources: &Sources,
        i: u64,
        stats: &mut Stats,
    ) -> (Pcg64Mcg, Option<Launch>) {
        let purpose = match self.batch {
            Batch::Caustic => Purpose::CausticPhotons,
            Batch::Global => Purpose::GlobalPhotons,
            Batch::Receivers => Purpose::ReceiverPhotons,
        };
        let mut rng = stream(self.seed, purpose, self.pass, i);
        let u = [rng.gen(), rng.gen(), rng.gen(), rng.gen(), rng.gen()];
        let launch = sources
            .emit(tracer, u, &mut rng, stats)
            .map(|(launch, spectrum)| match self.batch {
                Batch::Receivers if sources.spectral => launch.at_wavelength(spectrum, rng.gen()),
                Batch::Receivers => launch.radiometric(spectrum),
                // A shell photon in a medium whose σs depends on wavelength has its own.
                Batch::Caustic | Batch::Global if launch.hero.is_some() => launch,
                Batch::Caustic | Batch::Global if sources.dispersive || sources.layers => Launch {
                    hero: Some(launch.draw_wavelength(spectrum, rng.gen())),
                    ..launch
                },
                Batch::Caustic | Batch::Global => launch,
            });
        (rng, launch)
    }
}

/// Traces `photons` and returns what they left, in photon order, with
/// the transport statistics. Runs on the current rayon pool, in chunks of [`CHUNK`] photon
/// indices. Once `stop` answers true, chunks not yet started are skipped: the photons traced
/// are then a subset of whole chunks, counted in the statistics' `photons_emitted` (their
/// powers stay those of a batch of `count`).
pub fn shoot(
    tracer: &Tracer,
    sources: &Sources,
    photons: Photons,
    stop: &(dyn Fn() -> bool + Sync),
) -> (Sink, Stats) {
    let Photons {
        batch,
        count,
        ref traced,
        ..
    } = photons;
    let traced = traced.start..traced.end.min(count);
    if sources.is_empty() || traced.is_empty() {
        return (Sink::default(), Stats::default());
    }
    let bands = crate::receiver::distinct_bands(&tracer.scene.receivers);
    let chunks: Vec<(Sink, Stats)> = (traced.start / CHUNK..traced.end.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut stored = Sink {
                budget: Ledger::with_bands(&bands),
                ..Sink::default()
            };
            let mut stats = Stats::default();
            if stop() {
                return (stored, stats);
            }
            for i in (c * CHUNK).max(traced.start)..((c + 1) * CHUNK).min(traced.end) {
                let (mut rng, emission) = photons.launch(tracer, sources, i, &mut stats);
                stats.photons_emitted += 1;
                if let Some(e) = emission {
                    let photon = Tagged {
                        index: i,
                        count,
                        batch,
                    };
                    trace_photon(tracer, e, photon, &mut rng, &mut stats, &mut stored, None);
                }
            }
            (stored, stats)
        })
        .collect();
    let mut sink = Sink::default();
    let mut stats = Stats::default();
    for (p, s) in chunks {
        sink.photons.extend(p.photons);
        sink.volume.extend(p.volume);
        sink.detections.extend(p.detections);
        sink.budget.add(&p.budget);
        stats.add(&s);
    }
    (sink, stats)
}

/// A photon's place in its batch.
#[derive(Clone, Copy)]
struct Tagged {
    /// Index in the batch.
    index: u64,
    /// Photons in the batch.
    count: u64,
    /// What the batch is for.
    batch: Batch,
}

/// The paths of photons `0..count` of the receiver batch's pass `pass` under `seed` (the same
/// photons a receiver measurement with that pass traces): each path's emission point, every accepted
/// point of its curved stretches and every surface it met, in order. Single-threaded.
pub fn photon_paths(
    tracer: &Tracer,
    sources: &Sources,
    seed: u64,
    pass: u64,
    count: u64,
) -> Vec<Vec<DVec3>> {
    let mut paths = Vec::new();
    if sources.is_empty() {
        return paths;
    }
    let photons = Photons::all(Batch::Receivers, seed, pass, count);
    for i in 0..count {
        let (mut rng, emission) = photons.launch(tracer, sources, i, &mut Stats::default());
        if let Some(e) = emission {
            let tag = Tagged {
                index: i,
                count,
                batch: Batch::Receivers,
            };
            let mut path = Vec::new();
            let (mut sink, mut stats) = (Sink::default(), Stats::default());
            let mut show = |p| path.push(p);
            trace_photon(
                tracer,
                e,
                tag,
                &mut rng,
                &mut stats,
                &mut sink,
                Some(&mut show),
            );
            paths.push(path);
        }
    }
    paths
}

/// What a photon's chains tell it on the way: detector crossings, whether it was reflected
/// and where it last left a dielectric, and the points it passes.
struct PhotonWalk<'a, 'p> {
    tag: Tagged,
    /// Vacuum wavelength, nm.
    wavelength: f64,
    ambient: Option<MediumId>,
    /// The photon's power at the start of the current chain.
    power: Rgb,
    detections: &'a mut Vec<Detection>,
    receivers: &'a [crate::receiver::Receiver],
    reflected: bool,
    left_through: Option<PrimId>,
    path: Option<&'p mut dyn FnMut(DVec3)>,
    /// The last point shown, and how far a point may lie from it (escapes are drawn only
    /// that far, so a figure's lines stay short).
    last: DVec3,
    reach: f64,
    /// Power its bounces absorbed on the way and its branch has not booked yet (W, the mean
    /// over the channels): where a bounce's weight differs by channel, Russian roulette keeps
    /// the photon's largest channel's chance and the others lose power without ending it.
    absorbed: f64,
}

impl PhotonWalk<'_, '_> {
    /// How a photon that left the world in `medium` ended: out through the face it last left
    /// a dielectric by, reflected, or missed; lost when it escaped from inside a dielectric
    /// (the world sphere cuts the object).
    fn escaped(&self, medium: Option<MediumId>) -> Fate {
        match self.left_through {
            _ if medium != self.ambient => Fate::Lost,
            Some(p) => Fate::OutThrough(p),
            None if self.reflected => Fate::Reflected,
            None => Fate::Missed,
        }
    }
}

impl chain::ChainEvents for PhotonWalk<'_, '_> {
    fn point(&mut self, p: DVec3) {
        let d = p - self.last;
        let p = if d.length() > self.reach {
            self.last + d.normalize() * self.reach
        } else {
            p
        };
        if let Some(path) = self.path.as_mut() {
            path(p);
        }
        self.last = p;
    }

    fn wants_points(&self) -> bool {
        self.path.is_some()
    }

    fn detector(&mut self, crossing: &chain::DetectorCrossing) -> ControlFlow<()> {
        let receiver = &self.receivers[crossing.receiver.index()];
        if self.tag.batch == Batch::Receivers {
            if let Some(bin) = receiver.bin(crossing.position) {
                let power = self.power * crossing.weight;
                let stokes = crossing.polarization.and_then(|p| {
                    let per_channel = p.stokes(crossing.direction, receiver.stokes_basis())?;
                    let total = power.element_sum();
                    Some(std::array::from_fn(|i| {
                        let s: f64 = (0..3).map(|c| power.0[c] * per_channel[c][i + 1]).sum();
                        match total > 0.0 {
                            true => (s / total) as f32,
                            false => 0.0,
                        }
                    }))
                });
                self.detections.push(Detection {
                    receiver: crossing.receiver.index() as u32,
                    bin: bin as u32,
                    photon: self.tag.index,
                    flux: power.element_sum() / 3.0,
                    wavelength: self.wavelength,
                    stokes,
                });
            }
        }
        ControlFlow::Continue(())
    }

    fn specular(
        &mut self,
        prim: PrimId,
        from: Option<MediumId>,
        to: Option<MediumId>,
    ) -> ControlFlow<()> {
        if to == from {
            self.reflected = true;
        } else if to == self.ambient {
            self.left_through = Some(prim);
        }
        ControlFlow::Continue(())
    }
}

/// Whether a fluorophore absorbs the photon at `vertex` (one number from `rng` where there is
/// one): a collision in a medium holding a dye is the dye's absorption in proportion to its
/// rate ([`Tracer::scattering`] counts the dye in); a surface with a fluorescent layer
/// absorbs the share a(λ) of the light it meets.
fn absorbed_by_fluorophore<'s>(
    vertex: &Vertex,
    walker: &chain::Walker<'s>,
    rng: &mut impl Rng,
) -> Option<DyeAbsorption<'s>> {
    let carried = walker.carried();
    let tracer = carried.tracer;
    let absorption = |site, fluorophore, facing, medium| DyeAbsorption {
        site,
        fluorophore,
        nm: tracer.wavelength(),
        position: vertex.origin(),
        facing,
        medium,
        depth: carried.depth,
    };
    let (share, absorbed) = match vertex {
        Vertex::Medium(MediumVertex {
            medium: Some(m), ..
        }) => {
            let (dye, share) = tracer.dye_share(*m)?;
            let at = absorption(DyeSite::Medium(*m), &dye.fluorophore, None, Some(*m));
            (share, at)
        }
        Vertex::Medium(MediumVertex { medium: None, .. }) => return None,
        Vertex::Surface(v) => {
            let layer = tracer.scene.fluorescent_layer(v.prim)?;
            let at = absorption(
                DyeSite::Surface(v.prim),
                &layer.fluorophore,
                Some(v.normal),
                v.medium,
            );
            (layer.absorbed(tracer.wavelength()), at)
        }
    };
    (rng.gen::<f64>() < share).then_some(absorbed)
}

/// A photon's scattering at `vertex`: a direction from its BSDF or phase function and
/// Russian roulette on the sample's weight ([`roulette`]; a phase sample's is 1: what a
/// medium absorbs was played for on the way); None when it is absorbed. A Lambertian vertex,
/// whose weight (its albedo) is known before sampling, plays the roulette first (as photons
/// always have: the same numbers, the same photons). Where the photon carries a Stokes vector
/// (`polarization`, polarized transport) a phase function that polarizes draws its direction
/// with the polarization's factor ([`polarized_direction`]), and a rough conductor's or
/// dielectric's microfacet or a plastic applies its Mueller matrix
/// ([`crate::bsdf::Bsdf::mueller`]); every other vertex leaves the light unpolarized.
fn scatter_photon(
    vertex: &Vertex,
    polarization: &mut Option<Polarization>,
    rng: &mut impl Rng,
) -> Option<PhotonBounce> {
    if let (Vertex::Medium(v), Some(state)) = (vertex, polarization.as_mut()) {
        if v.phase.polarizes() {
            let (wi, weight) = polarized_direction(v, state, rng)?;
            let scattered = v.toward(wi);
            return Some(PhotonBounce { weight, scattered });
        }
    }
    let (bounce, polarizes) = match vertex.surface().and_then(|v| v.bsdf.lambert_albedo()) {
        Some(albedo) => {
            let weight = roulette(albedo, rng)?;
            let scattered = vertex.scatter_with(rng)?;
            (PhotonBounce { weight, scattered }, false)
        }
        None => {
            let scattered = vertex.scatter_with(rng)?;
            // A surface whose scattering has a Mueller matrix (a rough conductor's or
            // dielectric's microfacet, a plastic) carries the photon's Stokes vector on, its
            // power weighed by what it does to it.
            let carried = polarization.as_mut().and_then(|state| {
                let v = vertex.surface()?;
                let element =
                    v.bsdf
                        .mueller(v.wo, scattered.sample.wi, v.normal, Sense::WithLight)?;
                Some(state.meet(&element, -v.wo))
            });
            let weight = roulette(scattered.sample.weight * carried.unwrap_or(Rgb::ONE), rng)?;
            (PhotonBounce { weight, scattered }, carried.is_some())
        }
    };
    if let (Some(state), false) = (polarization.as_mut(), polarizes) {
        *state = Polarization::unpolarized(Sense::WithLight, bounce.scattered.ray.direction);
    }
    Some(bounce)
}

/// What a map keeps of a photon's polarization `state` where it arrives from unit `wo`
/// (pointing back along its way) — its Stokes vector where the transport is polarized, on
/// which the light a polarizing phase function or a plastic sends toward a camera depends;
/// nothing where it is not.
fn stokes_kept(tracer: &Tracer, state: &Option<Polarization>, wo: DVec3) -> Option<StoredStokes> {
    (tracer.settings.polarized).then(|| match state {
        Some(state) => state.stored(),
        None => Polarization::unpolarized(Sense::WithLight, -wo).stored(),
    })
}

/// The most directions [`polarized_direction`] draws before it gives up: each is taken with
/// probability at least 1/2 on average, so giving up has a chance below 2⁻¹⁰⁰⁰.
const MAX_REDRAWS: usize = 1000;

/// The light of Stokes vector `state` scattered at `v` into unit `after`: the phase
/// function's Mueller matrix applied where it polarizes, unpolarized light where it does not.
/// Returns the factor per channel by which the light's polarization changes the power going
/// that way, against unpolarized light's ([`Polarization::meet`]).
fn scatter_state(state: &mut Polarization, v: &MediumVertex, after: DVec3) -> Rgb {
    let before = -v.wo;
    match v.phase.mueller(before, after) {
        Some(element) => state.meet(&element, before),
        None => {
            *state = Polarization::unpolarized(Sense::WithLight, after);
            Rgb::ONE
        }
    }
}

/// A direction for a photon of Stokes vector `state` scattered at `v` by a phase function
/// that polarizes, drawn with density p·f̄ — p the phase function for unpolarized light, f the
/// factor per channel by which the light's polarization changes what goes that way
/// ([`scatter_state`]), f̄ its channels' mean — by rejection from p under f̄'s bound 1 + the
/// largest degree of linear polarization. f averages 1 over the azimuth (the matrix's first
/// row is (M00, M01, 0, 0) in the scattering plane's basis, which turns with the azimuth), so
/// p·f̄ is normalised; unpolarized light is never rejected. `state` becomes the scattered
/// light's. Returns the direction and the channels' weights f/f̄ (1 where they share one
/// state); None after [`MAX_REDRAWS`] rejections.
fn polarized_direction(
    v: &MediumVertex,
    state: &mut Polarization,
    rng: &mut impl Rng,
) -> Option<(DVec3, Rgb)> {
    let bound = 1.0 + state.linear_degree();
    for _ in 0..MAX_REDRAWS {
        let after = v.phase.sample(-v.wo, (rng.gen(), rng.gen()));
        let mut scattered = *state;
        let f = scatter_state(&mut scattered, v, after);
        let mean = f.mean();
        if rng.gen::<f64>() * bound < mean {
            *state = scattered;
            let weight = match f.is_grey() {
                true => Rgb::ONE,
                false => f / mean,
            };
            return Some((after, weight));
        }
    }
    None
}

/// A map photon scattering at a point `v` of a medium outside the scene ball, of which it sees
/// `cone`, splits in two: a branch sent uniformly over the cone, weighed p·Ω (the phase
/// function times the cone's solid angle), and the photon itself, going on along a direction
/// from the phase function — ending where that direction lies in the cone, whose light is the
/// branch's. In open fog most of the light scattered outside the scene never comes back: drawn
/// from the phase function alone, a photon scattered at distance ρ reaches the ball about
/// (radius / 2ρ)² of the time, carrying a weight none of the others do. Where the photon
/// carries a Stokes vector (`polarization`), both are scattered light's, the branch weighed by
/// the polarization's factor and the photon's direction drawn with it ([`polarized_direction`]).
fn split_toward(
    v: &MediumVertex,
    cone: Cone,
    polarization: &mut Option<Polarization>,
    rng: &mut impl Rng,
) -> Option<Split> {
    let before = -v.wo;
    let toward = cone.sample((rng.gen(), rng.gen()));
    let mut branch_polarization = *polarization;
    let polarized =
        (branch_polarization.as_mut()).map_or(Rgb::ONE, |s| scatter_state(s, v, toward));
    let branch_weight = polarized * (v.phase.between(before, toward) * cone.solid_angle());
    let (on, on_weight) = match polarization.as_mut() {
        Some(state) if v.phase.polarizes() => polarized_direction(v, state, rng)?,
        _ => {
            let after = v.phase.sample(before, (rng.gen(), rng.gen()));
            if let Some(state) = polarization.as_mut() {
                *state = Polarization::unpolarized(Sense::WithLight, after);
            }
            (after, Rgb::ONE)
        }
    };
    Some(Split {
        branch: Ray {
            origin: v.position,
            direction: toward,
            medium: v.medium,
        },
        branch_weight,
        branch_polarization,
        on: (cone.density(on) == 0.0).then_some(Ray {
            origin: v.position,
            direction: on,
            medium: v.medium,
        }),
        on_weight,
    })
}

/// What a photon splits into outside the scene ball ([`split_toward`]).
struct Split {
    /// The branch sent toward the ball.
    branch: Ray,
    /// The branch's weight: p·Ω, times the polarization's factor.
    branch_weight: Rgb,
    /// The branch's Stokes vector, where the photon carries one.
    branch_polarization: Option<Polarization>,
    /// The photon's own way on (None where it ends: its direction lies in the cone).
    on: Option<Ray>,
    /// What the photon's power is multiplied by on its way on.
    on_weight: Rgb,
}

/// Russian roulette on a bounce of `weight`: the photon goes on with probability equal to its
/// largest channel (at most 1) and its power is divided by that, so it keeps its size; None
/// when it is absorbed (always for a weight of 0 or NaN).
fn roulette(weight: Rgb, rng: &mut impl Rng) -> Option<Rgb> {
    let survive = weight.max_element().min(1.0);
    (survive > 0.0 && rng.gen::<f64>() < survive).then(|| weight / survive)
}

/// A photon's way on from a scattering vertex.
struct PhotonBounce {
    /// What its power is multiplied by.
    weight: Rgb,
    /// Where it goes.
    scattered: Scattered,
}

/// Follows one photon from its launch, drawing from `rng` and adding to `stats`, storing it
/// into `stored` as its batch says and booking its power in `stored.budget` when it ends;
/// `path`, if any, is shown every point it passes. Where a dye absorbs it and emits it again,
/// it goes on from there as a photon of the new wavelength (a leg of its own, on the tracer
/// at that wavelength).
fn trace_photon(
    tracer: &Tracer,
    launch: Launch,
    tag: Tagged,
    rng: &mut impl Rng,
    stats: &mut Stats,
    stored: &mut Sink,
    mut path: Option<&mut dyn FnMut(DVec3)>,
) {
    let scene = tracer.scene;
    let e = launch.emission;
    // The wavelength it left its light at: its budget's band.
    let nm = launch.wavelength;
    if let Some(path) = path.as_mut() {
        path(e.origin);
    }
    let Sink {
        photons,
        volume,
        detections,
        budget,
    } = stored;
    let mut walk = PhotonWalk {
        tag,
        wavelength: tracer.wavelength(),
        ambient: scene.ambient(),
        power: e.power / tag.count as f64,
        detections,
        receivers: &scene.receivers,
        reflected: false,
        left_through: None,
        path,
        last: e.origin,
        reach: tracer.ball.radius,
        absorbed: 0.0,
    };
    let mut emitted = (e.power / tag.count as f64).mean();
    if tag.batch != Batch::Receivers {
        stats.photon_power_emitted += emitted;
    }
    // The photon's first leg, and the legs dyes send off (none in most scenes: an empty Vec
    // allocates nothing).
    let mut first = Some(Leg {
        launch,
        ray: Ray {
            origin: e.origin,
            direction: e.direction,
            medium: launch.medium,
        },
        power: walk.power,
        depth: tracer.settings.max_depth,
        fluoresced: None,
    });
    let mut legs: Vec<Leg> = Vec::new();
    while let Some(leg) = first.take().or_else(|| legs.pop()) {
        // A photon with a wavelength of its own sees the dispersive media at it; one with a
        // hero takes it on where it meets dispersion.
        let dispersed = leg.launch.wavelength.map(|nm| tracer.at_wavelength(nm));
        let tracer = dispersed.as_ref().unwrap_or(tracer);
        let hero = leg
            .launch
            .hero
            .map(|h| HeroTracer::for_photon(tracer, h.nm));
        walk.wavelength = tracer.wavelength();
        let carried = chain::Carried {
            depth: leg.depth,
            ..chain::Carried::starting(tracer, hero.as_ref())
        };
        let walker = chain::Walker::carrying(carried, Policy::Roulette);
        // The photon's path, and the branches split off it outside the scene ball (map
        // photons in open fog: [`split_toward`]), each followed in turn.
        let mut branches = vec![Branch {
            ray: leg.ray,
            walker,
            power: leg.power,
            throughput: Rgb::ONE,
            seen_as: match leg.launch.wavelength {
                Some(nm) => colour::sensor(nm),
                None => Rgb::ONE,
            },
            bent: leg.launch.scattered || leg.fluoresced.is_some(),
            fogged: leg.launch.scattered,
            first: leg.fluoresced.is_none(),
            splits: tag.batch != Batch::Receivers,
            polarization: None,
        }];
        // The power a dye first emitted it with, booked in the fluorescence part once.
        let mut first_emission = leg.fluoresced;
        while let Some(branch) = branches.pop() {
            walk.power = branch.power;
            let lent = Lent {
                rng: &mut *rng,
                stats: &mut *stats,
            };
            let stores = Stores {
                photons: &mut *photons,
                volume: &mut *volume,
            };
            let (ending, fogged) =
                follow_branch(branch, &leg.launch, &mut walk, &mut branches, lent, stores);
            let mut book = |power: f64, fate: Fate| {
                budget.book(&Ended {
                    emitted,
                    power,
                    fate,
                    nm,
                    scattered: fogged,
                    fluoresced: leg.fluoresced.map(|_| first_emission.take().unwrap_or(0.0)),
                });
                emitted = 0.0;
            };
            if walk.absorbed != 0.0 {
                book(std::mem::take(&mut walk.absorbed), Fate::Absorbed);
            }
            let absorbed = walk.power.mean();
            let at = match ending {
                Ending::Fate(fate) => {
                    book(absorbed, fate);
                    continue;
                }
                Ending::Dye(at) => at,
            };
            let reemitted = at.fluorophore.reemit(at.nm, rng.gen(), rng.gen());
            let out = reemitted.map_or(0.0, |r| absorbed * r.energy);
            // All of it heat, or the Stokes shift's share.
            let heat = match at.site {
                DyeSite::Medium(m) => Fate::AbsorbedIn(m),
                DyeSite::Surface(_) => Fate::Absorbed,
            };
            book(absorbed - out, heat);
            budget.book_dye(&DyeEvent {
                site: at.site,
                absorbed,
                emitted: out,
                again: leg.fluoresced.is_some(),
                nm,
            });
            // A fluorophore's light reaches the caustic map by no specular way from a light:
            // camera paths find it through the final gather ([`crate::integrator`]'s
            // relighting), which the caustic map would count again.
            if let (Some(r), false) = (reemitted, tag.batch == Batch::Caustic) {
                legs.push(Leg {
                    launch: Launch {
                        wavelength: Some(r.nm),
                        hero: None,
                        shell: None,
                        scattered: false,
                        ..leg.launch
                    },
                    ray: Ray {
                        origin: at.position,
                        // Isotropic from a dye; Lambertian from a layer, back on the side
                        // the light came from.
                        direction: match at.facing {
                            None => uniform_sphere((rng.gen(), rng.gen())),
                            Some(n) => {
                                Frame::new(n).to_world(cosine_hemisphere((rng.gen(), rng.gen())))
                            }
                        },
                        medium: at.medium,
                    },
                    power: walk.power * r.energy,
                    depth: at.depth,
                    fluoresced: Some(leg.fluoresced.map_or(out, |_| 0.0)),
                });
            }
        }
    }
}

/// A photon's way from its light, or from where a dye emitted it: one leg of its path.
struct Leg {
    /// How it set off (a dye's photon: at its wavelength, with no hero, shell or scattering).
    launch: Launch,
    /// Where it goes.
    ray: Ray,
    /// Its power (W per channel, of the batch's count).
    power: Rgb,
    /// Surfaces and events in media it may still meet.
    depth: u32,
    /// For a dye's photon: the power a dye first emitted it with, to book in the budget's
    /// part of fluorescence once (0 after a second emission); None for the light's photon.
    fluoresced: Option<f64>,
}

/// How a branch of a photon ends: a fate, or absorbed by a fluorophore (which may emit it
/// again).
enum Ending<'s> {
    Fate(Fate),
    Dye(DyeAbsorption<'s>),
}

/// Where a fluorophore absorbed a photon.
struct DyeAbsorption<'s> {
    /// Where it sits.
    site: DyeSite,
    /// What it emits.
    fluorophore: &'s Fluorophore,
    /// The vacuum wavelength it absorbed, nm.
    nm: f64,
    /// Where its light sets off: the point in a medium, just off a surface on the side the
    /// light came from.
    position: DVec3,
    /// A layer's normal on the side the light came from (None: a dye, emitting every way).
    facing: Option<DVec3>,
    /// The medium its light sets off in.
    medium: Option<MediumId>,
    /// The surfaces and events in media the photon may still meet.
    depth: u32,
}

/// One path of a photon (the photon's own, or a branch split off it): where it goes on from,
/// what it carries, and what it has met.
struct Branch<'w> {
    ray: Ray,
    walker: chain::Walker<'w>,
    /// Its power (W per channel, of the batch's count).
    power: Rgb,
    /// What it has kept of its launch power while it carries every wavelength: every factor
    /// its power has taken on (Russian roulette's and a split's too), for the power it takes on
    /// with its hero wavelength ([`Branch::take_on`]).
    throughput: Rgb,
    /// The sRGB its power stands for: a photon of one wavelength is stored in that
    /// wavelength's (once it has met dispersion).
    seen_as: Rgb,
    /// Whether a specular or glossy lobe or a medium has scattered it since the light.
    bent: bool,
    /// Whether a medium has scattered it.
    fogged: bool,
    /// Whether it has met nothing yet.
    first: bool,
    /// Whether it splits where a medium scatters it outside the scene ball (a map photon's
    /// own path; branches do not split again).
    splits: bool,
    /// Its Stokes vector where the transport is polarized and a scattering that polarizes
    /// sent it on polarized (None: unpolarized, as from a source or a depolarizing vertex).
    polarization: Option<Polarization>,
}

impl Branch<'_> {
    /// Takes on the photon's hero wavelength `h` (its walker already on the tracer there): its
    /// power becomes its source's spectrum at `h` times the reflectance spectrum of `kept`, what
    /// it kept of its launch power while it carried every wavelength; it is stored in that
    /// wavelength's sRGB from here on.
    fn take_on(&mut self, walk: &mut PhotonWalk, h: PhotonHero, kept: Rgb) {
        let kept = colour::reflectance(kept, h.nm);
        walk.power = Rgb::splat(h.power * kept / walk.tag.count as f64);
        walk.wavelength = h.nm;
        self.seen_as = colour::sensor(h.nm);
    }
}

/// The random stream and statistics a photon's branches share.
struct Lent<'a, R> {
    rng: &'a mut R,
    stats: &'a mut Stats,
}

/// Where a photon's branches are stored: the photons on surfaces and in media.
struct Stores<'a> {
    photons: &'a mut TracedPhotons,
    volume: &'a mut TracedPhotons,
}

/// Follows `branch` of a photon launched as `launch` to its end, storing it as its batch says
/// and pushing the branches it splits off onto `branches`; returns how it ended (a fate, or
/// absorbed by a dye) and whether a medium scattered it.
fn follow_branch<'w, R: Rng>(
    mut b: Branch<'w>,
    launch: &Launch,
    walk: &mut PhotonWalk,
    branches: &mut Vec<Branch<'w>>,
    lent: Lent<R>,
    stored: Stores,
) -> (Ending<'w>, bool) {
    let Lent { rng, stats } = lent;
    let tracer = b.walker.tracer;
    let tag = walk.tag;
    let fate = loop {
        let chain = b
            .walker
            .follow_carrying(b.ray, &mut b.polarization, rng, stats, walk);
        match (chain.dispersed, launch.hero) {
            (Some(before), Some(h)) => {
                b.take_on(walk, h, b.throughput * before);
                walk.power *= chain.weight;
            }
            _ => {
                walk.power *= chain.weight;
                b.throughput *= chain.weight;
            }
        }
        let mut vertex = match chain.end {
            End::Scatter(vertex) => vertex,
            End::Escaped { .. } => break walk.escaped(chain.medium),
            End::Emitter { .. } | End::Absorbed { medium: None } => break Fate::Absorbed,
            End::Absorbed { medium: Some(m) } => break Fate::AbsorbedIn(m),
            End::DepthLimit => {
                if tag.batch != Batch::Receivers {
                    stats.photon_power_cut += walk.power.mean();
                }
                break Fate::Lost;
            }
            End::Lost | End::Stopped => break Fate::Lost,
        };
        if let (Vertex::Surface(v), Some(h)) = (&mut vertex, launch.hero) {
            let layer =
                tracer.scene.fluoresces() && tracer.scene.fluorescent_layer(v.prim).is_some();
            if layer && b.walker.take_on_hero() {
                // A layer absorbs and emits at wavelengths: the photon takes on its hero's
                // here, as where it meets dispersion, and so does the surface's reflectance.
                b.take_on(walk, h, b.throughput);
                if let Some(albedo) = v.bsdf.lambert_albedo() {
                    v.bsdf = Bsdf::Lambert {
                        albedo: Rgb::splat(colour::reflectance(albedo, h.nm)),
                    };
                }
            }
        }
        if let Some(at) = absorbed_by_fluorophore(&vertex, &b.walker, rng) {
            return (Ending::Dye(at), b.fogged);
        }
        let outside = match &vertex {
            Vertex::Medium(v) => Cone::toward(tracer.ball, v.position).map(|c| (v, c)),
            Vertex::Surface(_) => None,
        };
        if b.first && chain.specular == 0 && outside.is_some() && launch.shell.is_some() {
            // Scattered outside the scene ball before anything else: the shell's light.
            break Fate::Lost;
        }
        b.first = false;
        b.bent |= chain.specular > 0;
        // Photons are stored only at surfaces with a diffuse lobe: camera paths and final
        // gathers pass glossy-only vertices and points in media by sampling them and read no
        // photons there (and photons on the inside of a rough glass ball would be read by the
        // floor it stands on, whose normal they share).
        if let Vertex::Surface(v) = &vertex {
            let photon = Photon {
                position: v.position,
                normal: v.normal,
                power: (walk.power * b.seen_as).as_vec3().to_array(),
                from: v.wo.as_vec3().to_array(),
                base: v.diffuse_entry() as f32,
            };
            let stores = match tag.batch {
                // L (S|G|V)+ D: at least one specular or glossy lobe or scattering in a medium,
                // and no diffuse lobe, since the light. Light through gradient media alone
                // (L G+ D) is the direct estimate's, which follows it along the curved path.
                Batch::Caustic => b.bent,
                Batch::Global => true,
                Batch::Receivers => false,
            };
            if stores && v.lobes().has_diffuse() {
                // The caustic map's photons keep their Stokes vectors (the caustic estimate
                // reads them through the surface's matrix); the global map's irradiance reads
                // none.
                let stokes = match tag.batch {
                    Batch::Caustic => stokes_kept(tracer, &b.polarization, v.wo),
                    Batch::Global | Batch::Receivers => None,
                };
                stored.photons.push(photon, stokes);
            }
        } else if tag.batch == Batch::Caustic && b.bent && !b.fogged {
            // L (S|G)+ V: a volume caustic, where it first scatters in a medium.
            let stokes = stokes_kept(tracer, &b.polarization, vertex.wo());
            let photon = Photon {
                position: vertex.position(),
                normal: DVec3::ZERO,
                power: (walk.power * b.seen_as).as_vec3().to_array(),
                from: vertex.wo().as_vec3().to_array(),
                base: 1.0,
            };
            stored.volume.push(photon, stokes);
        }
        if tag.batch == Batch::Caustic && vertex.lobes() == Lobes::DIFFUSE_REFLECTION {
            break Fate::Absorbed;
        }
        // Map photons go on from here past a depth only by Russian roulette ([`chain::ROULETTE_AFTER`]); a
        // receiver photon goes on to `max_depth`, so that the budget books every photon's own
        // power.
        let met = tracer.settings.max_depth.saturating_sub(b.walker.depth);
        if tag.batch != Batch::Receivers && met > chain::ROULETTE_AFTER {
            if rng.gen::<f64>() >= chain::ROULETTE_SURVIVAL {
                break Fate::Lost;
            }
            walk.power /= chain::ROULETTE_SURVIVAL;
            b.throughput /= chain::ROULETTE_SURVIVAL;
        }
        if let (Some((v, cone)), true) = (outside, b.splits) {
            let Some(split) = split_toward(v, cone, &mut b.polarization, rng) else {
                break Fate::Lost;
            };
            // A branch from far out, whose weight is small, is kept by Russian roulette in
            // proportion to it: in a thick fog a photon scatters outside the ball dozens of
            // times, and each branch is a photon to trace.
            let kept = (2.0 * split.branch_weight.max_element()).min(1.0);
            if rng.gen::<f64>() < kept {
                branches.push(Branch {
                    ray: split.branch,
                    power: walk.power * (split.branch_weight / kept),
                    throughput: b.throughput * (split.branch_weight / kept),
                    polarization: split.branch_polarization,
                    bent: true,
                    fogged: true,
                    splits: false,
                    ..b
                });
            }
            b.bent = true;
            b.fogged = true;
            match split.on {
                Some(ray) => {
                    walk.power *= split.on_weight;
                    b.throughput *= split.on_weight;
                    b.ray = ray;
                }
                None => break Fate::Lost,
            }
            continue;
        }
        let Some(bounce) = scatter_photon(&vertex, &mut b.polarization, rng) else {
            break match vertex {
                Vertex::Medium(MediumVertex {
                    medium: Some(m), ..
                }) => Fate::AbsorbedIn(m),
                Vertex::Medium(_) | Vertex::Surface(_) => Fate::Absorbed,
            };
        };
        let before = walk.power.mean();
        walk.power *= bounce.weight;
        // What the surviving photon's channels lost (a coloured surface's), signed: a
        // glossy sample's weight may exceed 1 where its pdf falls short of f·cos, and the
        // bookings add up to what the bounces absorb in expectation either way.
        walk.absorbed += before - walk.power.mean();
        b.throughput *= bounce.weight;
        if bounce.scattered.sample.lobe.has_diffuse() {
            if tag.batch == Batch::Caustic {
                break Fate::Absorbed;
            }
        } else {
            b.bent = true;
            b.fogged |= matches!(vertex, Vertex::Medium(_));
            if let Vertex::Surface(v) = &vertex {
                let to = bounce.scattered.ray.medium;
                // What the budget tells of a glossy reflection or transmission, as of a smooth
                // one.
                let _ = chain::ChainEvents::specular(walk, v.prim, v.medium, to);
            }
        }
        b.ray = bounce.scattered.ray;
    };
    (Ending::Fate(fate), b.fogged)
}
