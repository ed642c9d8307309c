//! The forward photon pass (seed 004 §4, Jensen's photon mapping): photons leave the lights in
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

pub use budget::{Budget, Fate};
pub use map::{Photon, PhotonMap};

use crate::environment::Environment;
use crate::lights::{Emission, Light};
use crate::material::Material;
use crate::receiver::Detection;
use crate::sampling::{cosine_hemisphere, stream, Frame, Purpose};
use crate::transport::{facing, offset, Event, Stats, Tracer};
use glam::DVec3;
use rand::Rng;
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

/// Photons per chunk of parallel work.
const CHUNK: u64 = 4096;

/// Something that emits photons.
#[derive(Clone, Copy)]
enum Source<'a> {
    Light(&'a Light),
    Environment(&'a Environment),
}

/// The scene's photon sources with a discrete distribution proportional to their power.
pub struct Sources<'a> {
    sources: Vec<Source<'a>>,
    /// Cumulative selection probabilities, the last one 1.
    cdf: Vec<f64>,
}

impl<'a> Sources<'a> {
    /// The lights and the environment of the tracer's scene; sources of zero power are left
    /// out.
    pub fn new(tracer: &Tracer<'a>) -> Self {
        let scene = tracer.scene;
        let mut sources = Vec::new();
        let mut weights = Vec::new();
        for light in &scene.lights {
            sources.push(Source::Light(light));
            weights.push(light.selection_power(tracer.ball));
        }
        if let Some(env) = &scene.environment {
            sources.push(Source::Environment(env));
            weights.push(env.selection_power(tracer.ball));
        }
        let total: f64 = weights.iter().filter(|w| w.is_finite() && **w > 0.0).sum();
        let mut kept = Vec::new();
        let mut cdf = Vec::new();
        let mut acc = 0.0;
        for (s, w) in sources.into_iter().zip(weights) {
            if w.is_finite() && w > 0.0 {
                acc += w / total;
                kept.push(s);
                cdf.push(acc);
            }
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        Self { sources: kept, cdf }
    }

    /// True when nothing emits.
    pub fn is_empty(&self) -> bool {
        self.sources.is_empty()
    }

    /// Emission for uniform numbers `u` (u[0] picks the source), with the power divided by
    /// the selection probability.
    fn emit(&self, tracer: &Tracer, u: [f64; 5]) -> Option<Emission> {
        let i = self
            .cdf
            .partition_point(|c| *c <= u[0])
            .min(self.cdf.len() - 1);
        let p = self.cdf[i] - if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let rest = [u[1], u[2], u[3], u[4]];
        let e = match self.sources[i] {
            Source::Light(l) => l.emit(rest, tracer.ball)?,
            Source::Environment(env) => env.emit(rest, tracer.ball),
        };
        Some(Emission {
            power: e.power / p,
            ..e
        })
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
    pub photons: Vec<Photon>,
    /// Receiver crossings.
    pub detections: Vec<Detection>,
    /// Where the photons' power went.
    pub budget: Budget,
}

/// Traces `count` photons of pass `pass` (random streams keyed by `seed`) and returns what they left, in photon order, with
/// the transport statistics. Runs on the current rayon pool. Once `stop` answers true, chunks
/// not yet started are skipped: the photons traced are then a subset of whole chunks,
/// counted in the statistics' `photons_emitted` (their powers stay those of a batch of
/// `count`).
pub fn shoot(
    tracer: &Tracer,
    sources: &Sources,
    batch: Batch,
    seed: u64,
    pass: u64,
    count: u64,
    stop: &(dyn Fn() -> bool + Sync),
) -> (Sink, Stats) {
    if sources.is_empty() || count == 0 {
        return (Sink::default(), Stats::default());
    }
    let purpose = match batch {
        Batch::Caustic => Purpose::CausticPhotons,
        Batch::Global => Purpose::GlobalPhotons,
        Batch::Receivers => Purpose::ReceiverPhotons,
    };
    let chunks: Vec<(Sink, Stats)> = (0..count.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut stored = Sink::default();
            let mut stats = Stats::default();
            if stop() {
                return (stored, stats);
            }
            for i in c * CHUNK..((c + 1) * CHUNK).min(count) {
                let (mut rng, emission) = launch(tracer, sources, purpose, seed, pass, i);
                stats.photons_emitted += 1;
                if let Some(e) = emission {
                    let photon = Tagged {
                        index: i,
                        count,
                        batch,
                    };
                    trace_photon(
                        tracer,
                        e,
                        photon,
                        &mut rng,
                        &mut stored,
                        &mut stats,
                        &mut |_| {},
                    );
                }
            }
            (stored, stats)
        })
        .collect();
    let mut sink = Sink::default();
    let mut stats = Stats::default();
    for (p, s) in chunks {
        sink.photons.extend(p.photons);
        sink.detections.extend(p.detections);
        sink.budget.add(&p.budget);
        stats.add(&s);
    }
    (sink, stats)
}

/// Photon `i` of pass `pass` of a batch: its random stream, advanced past its emission, and
/// the emission (None where the chosen source emits nothing for these numbers).
fn launch(
    tracer: &Tracer,
    sources: &Sources,
    purpose: Purpose,
    seed: u64,
    pass: u64,
    i: u64,
) -> (Pcg64Mcg, Option<Emission>) {
    let mut rng = stream(seed, purpose, pass, i);
    let u = [rng.gen(), rng.gen(), rng.gen(), rng.gen(), rng.gen()];
    let emission = sources.emit(tracer, u);
    (rng, emission)
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
    for i in 0..count {
        let (mut rng, emission) = launch(tracer, sources, Purpose::ReceiverPhotons, seed, pass, i);
        if let Some(e) = emission {
            let tag = Tagged {
                index: i,
                count,
                batch: Batch::Receivers,
            };
            let mut path = Vec::new();
            let (mut sink, mut stats) = (Sink::default(), Stats::default());
            trace_photon(tracer, e, tag, &mut rng, &mut sink, &mut stats, &mut |p| {
                path.push(p)
            });
            paths.push(path);
        }
    }
    paths
}

/// Follows one photon from its emission, storing it into `stored` as `batch` says and
/// booking its power in `stored.budget` when it ends; `path` is shown every point it passes.
fn trace_photon(
    tracer: &Tracer,
    e: Emission,
    tag: Tagged,
    rng: &mut impl Rng,
    stored: &mut Sink,
    stats: &mut Stats,
    path: &mut dyn FnMut(DVec3),
) {
    let scene = tracer.scene;
    let batch = tag.batch;
    let mut power = e.power / tag.count as f64;
    stored.budget.emitted += power.element_sum() / 3.0;
    let (mut origin, mut dir, mut medium) = (e.origin, e.direction, scene.ambient);
    // Whether the path so far holds a specular bounce or a gradient-medium traversal.
    let mut bent = false;
    // Whether it has met a specular reflection, and where it last left a dielectric into the
    // ambient medium.
    let (mut reflected, mut left_through) = (false, None);
    path(origin);
    let fate = 'path: {
        for _ in 0..tracer.settings.max_depth {
            bent |= medium.is_some_and(|m| !scene.medium_at(m).is_uniform());
            let event = tracer.next_event_along(origin, dir, medium, stats, path);
            // Absorption on the way, by Russian roulette (photon powers stay equal in size).
            if let Event::Surface { distance, .. } | Event::Escaped { distance, .. } = event {
                let kept = tracer.transmittance(medium, origin, distance);
                if kept < 1.0 && rng.gen::<f64>() >= kept {
                    break 'path Fate::Absorbed;
                }
            }
            let (prim, position, normal, direction) = match event {
                Event::Surface {
                    prim,
                    position,
                    normal,
                    direction,
                    ..
                } => (prim, position, normal, direction),
                Event::Escaped {
                    direction: d,
                    distance,
                } => {
                    if medium.is_none_or(|m| scene.medium_at(m).is_uniform()) {
                        path(origin + d * distance.min(tracer.ball.1));
                    }
                    // Escaping from inside a dielectric (the world sphere cuts it) is lost.
                    break 'path match left_through {
                        _ if medium != scene.ambient => Fate::Lost,
                        Some(p) => Fate::OutThrough(p),
                        None if reflected => Fate::Reflected,
                        None => Fate::Missed,
                    };
                }
                Event::Lost => break 'path Fate::Lost,
            };
            path(position);
            let surface = scene.surfaces[prim];
            let facing = facing(normal, direction);
            match &scene.materials[surface.material] {
                Material::Emissive { .. } => break 'path Fate::Absorbed,
                Material::Diffuse { albedo } => {
                    let photon = Photon {
                        position,
                        normal: facing,
                        power: power.as_vec3().to_array(),
                    };
                    match batch {
                        Batch::Caustic => {
                            if bent {
                                stored.photons.push(photon);
                            }
                            break 'path Fate::Absorbed;
                        }
                        Batch::Global => stored.photons.push(photon),
                        Batch::Receivers => {}
                    }
                    let survive = albedo.max_element();
                    if rng.gen::<f64>() >= survive {
                        break 'path Fate::Absorbed;
                    }
                    power *= *albedo / survive;
                    dir = Frame::new(facing).to_world(cosine_hemisphere((rng.gen(), rng.gen())));
                    origin = offset(position, facing);
                }
                Material::Detector { receiver } => {
                    if batch == Batch::Receivers {
                        if let Some(bin) = scene.receivers[*receiver].bin(position) {
                            stored.detections.push(Detection {
                                receiver: *receiver as u32,
                                bin: bin as u32,
                                photon: tag.index,
                                flux: power.element_sum() / 3.0,
                            });
                        }
                    }
                    (origin, dir) = (offset(position, direction), direction);
                }
                Material::Mirror { .. } | Material::Dielectric => {
                    let Some(b) = tracer.specular_bounce(
                        surface,
                        medium,
                        position,
                        direction,
                        normal,
                        rng.gen(),
                    ) else {
                        break 'path Fate::Lost;
                    };
                    // Russian roulette on a lossy mirror keeps photon powers equal in size.
                    let survive = b.weight.max_element();
                    if survive < 1.0 && rng.gen::<f64>() >= survive {
                        break 'path Fate::Absorbed;
                    }
                    power *= b.weight / survive.clamp(f64::MIN_POSITIVE, 1.0);
                    if b.medium == medium {
                        reflected = true;
                    } else if b.medium == scene.ambient {
                        left_through = Some(prim);
                    }
                    (origin, dir, medium) = (b.origin, b.direction, b.medium);
                    bent = true;
                }
            }
        }
        stats.depth_limited += 1;
        Fate::Lost
    };
    stored.budget.book(fate, power.element_sum() / 3.0);
}
