//! Unidirectional path tracing through the curved transport: the camera's specular chain to
//! its first scattering vertex, then BSDF-sampled bounces from vertex to vertex (diffuse or
//! glossy), each followed through purely specular surfaces and gradient media. At every
//! vertex the light arriving with no specular interaction is estimated by two strategies
//! weighed against each other: light samples ([`super::direct::lit`]: straight shadow rays
//! where they are valid, curved connections where they are not) and the bounce's own BSDF or
//! phase sample, whose chain is the path's way on as well ([`super::direct::continued_emission`]:
//! one ray for both, where a separate BSDF ray would trace a third). A bounce whose chain
//! reaches an emitter or the sky after a specular interaction adds that light in full
//! (caustics). Russian roulette after three bounces.
//!
//! Light from point, spot, LED and parallel sources that reaches a diffuse point only through
//! a specular chain (their caustics) cannot be found by any direction sample: the path tracer
//! misses it, the photon mapper does not. An index-matched boundary between uniform media is
//! no specular surface ([`crate::transport::Tracer::crosses_unchanged`]): light samples reach
//! through it into the fog it holds.

use super::beam::Beams;
use super::direct::{
    camera_path, continued_emission, hero, lit, measuring_radiance, record_cut, takes_direct,
    VisiblePoint,
};
use super::dye::dye_sources;
use super::relight::{fluoresces, relight, Relighting};
use super::single::single_scattering;
use super::{CameraRay, FirstVertex, Integrator, Sample};
use crate::color::Rgb;
use crate::lights::LightSamples;
use crate::polarization::Recorded;
use crate::report::Report;
use crate::transport::chain::{Carried, End, Policy, Walker};
use crate::transport::lighting::{direct_light, LightNumbers, Measure, Radiance};
use crate::transport::{BsdfNumbers, Stats, Tracer, Vertex};
use rand::Rng;

super::layers!(
    /// The layers, in order; `beauty` is their radiance sum.
    PathLayer {
        /// Light from the lights at the visible point and every later vertex.
        Direct: radiance "direct",
        /// Light the bounces' chains found.
        Indirect: radiance "indirect",
        /// Emission seen directly.
        Emitted: radiance "emitted",
        /// The first scattering surface's albedo.
        Albedo: aux "albedo",
        /// Its normal.
        Normal: aux "normal",
    }
);

/// Bounces before Russian roulette starts.
const SURE_BOUNCES: u32 = 3;

/// The path tracer of a scene.
pub struct PathTracer<'a> {
    tracer: &'a Tracer<'a>,
}

impl PathTracer<'_> {
    /// The film's layers.
    pub const LAYERS: &'static [crate::film::Layer] = <PathLayer as super::Layers>::FILM;
}

impl<'a> PathTracer<'a> {
    /// The path tracer of the tracer's scene.
    pub fn new(tracer: &'a Tracer<'a>) -> Self {
        Self { tracer }
    }
}

/// The light reaching the camera from the scattering vertex `vp` a camera path carrying
/// `carried` has reached, estimated by path tracing: its light samples (taking `first`'s light
/// numbers where given), and the bounces on from it ([`bounces`]), tallied through the
/// measurement its path carries there (`measure`, changed by the bounces). At a fluorescent
/// layer the path goes on at the wavelength the layer absorbs ([`relight`]).
pub fn onward<'w, M: Measure, R: Rng>(
    mut vp: VisiblePoint<'w>,
    carried: Carried<'w>,
    first: FirstVertex,
    measure: &mut M,
    rng: &mut R,
    stats: &mut Stats,
) -> Onward<M::Light> {
    match relight(carried.tracer, &mut vp, rng) {
        Relighting::Unchanged => lit_and_bounces(vp, carried, first, measure, rng, stats),
        Relighting::Dark => Onward::default(),
        Relighting::Relit { nm } => {
            let tracer = past_fluorophore(carried.tracer, nm);
            let carried = Carried {
                tracer: &tracer,
                hero: None,
                ..carried
            };
            lit_and_bounces(vp, carried, first, measure, rng, stats)
        }
    }
}

/// [`onward`] from a vertex whose light leaves it unpolarized (a dye's point, a diffuse
/// vertex a gather reaches), as the camera records its radiance alone: carrying a measurement
/// of it where the transport is polarized ([`measuring_radiance`]).
pub fn onward_from_unpolarized<'w, R: Rng>(
    vp: VisiblePoint<'w>,
    carried: Carried<'w>,
    rng: &mut R,
    stats: &mut Stats,
) -> Rgb {
    let first = FirstVertex::default();
    match measuring_radiance(carried.tracer, -vp.vertex.wo()) {
        Some(mut m) => onward(vp, carried, first, &mut m, rng, stats).total().s0,
        None => onward(vp, carried, first, &mut Radiance, rng, stats).total(),
    }
}

/// The tracer a path goes on with past a fluorophore, at the vacuum wavelength `nm` it absorbs:
/// its light samples go to every light, since the light sampler weighs lights by their RGB
/// power, and at one wavelength a light of little colour (a violet lamp) may be the brightest.
fn past_fluorophore<'a>(tracer: &'a Tracer<'a>, nm: f64) -> Tracer<'a> {
    let mut tracer = tracer.at_wavelength(nm);
    tracer.light_samples = LightSamples::Each;
    tracer
}

/// The light dyes emit toward the chain recorded in `beams` on its way through their media
/// ([`super::dye`]), per unit of the path's throughput before it, estimated by path tracing on
/// from a point on each stretch at a wavelength the dye absorbs; `carried`: what the chain
/// carried at its end. A dye's light leaves it unpolarized: its radiance alone is estimated
/// (carrying a measurement of it where the transport is polarized: [`measuring_radiance`]),
/// and recorded through the camera's measurement on the stretch where the chain carries one.
pub fn dye_light<R: Rng>(
    beams: &Beams,
    carried: Carried,
    rng: &mut R,
    stats: &mut Stats,
) -> Recorded {
    let mut sum = Recorded::default();
    for source in dye_sources(beams, carried.tracer, rng, stats) {
        let tracer = past_fluorophore(carried.tracer, source.nm);
        let carried = Carried {
            tracer: &tracer,
            hero: None,
            flights: source.flights,
            depth: source.depth,
        };
        let vp = VisiblePoint {
            vertex: Vertex::Medium(source.vertex),
            throughput: source.weight,
        };
        let light = match measuring_radiance(&tracer, -source.vertex.wo) {
            Some(mut m) => from_point(vp, carried, &mut m, rng, stats).s0,
            None => from_point(vp, carried, &mut Radiance, rng, stats),
        };
        sum += Recorded::of(source.measure, light);
    }
    sum
}

/// The light reaching the camera from the point `vp` in a medium where no free flight ended
/// (a dye's point): its direct light in full — at a point in a medium of uniform index too,
/// where a flight's end leaves it to the stretch's single scattering — and the bounces on.
fn from_point<'w, M: Measure, R: Rng>(
    vp: VisiblePoint<'w>,
    carried: Carried<'w>,
    measure: &mut M,
    rng: &mut R,
    stats: &mut Stats,
) -> M::Light {
    let direct = match takes_direct(carried.tracer, &vp.vertex) {
        true => lit(carried, &vp, LightNumbers::default(), measure, rng, stats),
        false => direct_light(carried, &vp.vertex, measure, rng, stats) * vp.throughput,
    };
    let found = bounces(vp, carried, BsdfNumbers::default(), measure, rng, stats);
    direct + found.direct + found.indirect
}

/// [`onward`] from a vertex the path goes on from as it is.
fn lit_and_bounces<'w, M: Measure, R: Rng>(
    vp: VisiblePoint<'w>,
    carried: Carried<'w>,
    first: FirstVertex,
    measure: &mut M,
    rng: &mut R,
    stats: &mut Stats,
) -> Onward<M::Light> {
    let lit = lit(carried, &vp, first.light, measure, rng, stats);
    let Bounces { direct, indirect } = bounces(vp, carried, first.bsdf, measure, rng, stats);
    Onward {
        lit,
        direct,
        indirect,
    }
}

/// The light reaching the camera along the bounces from the vertex `vp`: direct light at every
/// later scattering vertex (light samples), and the emission each bounce's chain finds
/// (weighed against the light samples where it met no specular surface); the first bounce's,
/// where it met none, is `vp`'s direct light. The first bounce's BSDF or phase sample takes
/// `first` where given. A bounce that reaches a fluorescent layer goes on from it by
/// [`onward`]. The camera's measurement `measure` meets each vertex's Mueller matrix on the
/// way ([`Measure::toward`]) and each chain's elements.
fn bounces<'w, M: Measure, R: Rng>(
    mut vp: VisiblePoint<'w>,
    carried: Carried<'w>,
    first: BsdfNumbers,
    measure: &mut M,
    rng: &mut R,
    stats: &mut Stats,
) -> Bounces<M::Light> {
    let mut walker = Walker::carrying(carried, Policy::Weighted);
    let mut direct = M::Light::default();
    let mut sum = M::Light::default();
    for bounce in 0.. {
        if bounce >= SURE_BOUNCES {
            let survive = vp.throughput.max_element().min(0.95);
            if survive <= 0.0 || rng.gen::<f64>() >= survive {
                break;
            }
            vp.throughput /= survive;
        }
        let numbers = match bounce {
            0 => first,
            _ => BsdfNumbers::default(),
        };
        let Some(b) = vp.vertex.scatter_given(numbers, rng) else {
            break;
        };
        measure.toward(&vp.vertex, b.sample.wi);
        let mut beams = Beams::default();
        let recording = &mut beams.record(walker.tracer);
        let chain = walker.follow_measured(b.ray, measure.rows(), rng, stats, recording);
        let weight = b.sample.weight * b.radiance_scale;
        record_cut(&chain, vp.throughput * weight, stats);
        if beams.recorded_any() {
            let single = single_scattering(&beams, walker.carried(), rng, stats);
            sum += M::tallied(single * (vp.throughput * weight));
            let dyed = dye_light(&beams, walker.carried(), rng, stats);
            sum += M::tallied(dyed * (vp.throughput * weight));
        }
        let throughput = vp.throughput * weight * chain.weight;
        // Light emitted by media on the way is sampled by no light sample: it counts here.
        sum += M::tallied(beams.emission(chain.emitted) * (vp.throughput * weight));
        // The sample is also direct light's second strategy, weighed against `lit`'s.
        let found =
            measure.of(vp.throughput * continued_emission(walker.tracer, &vp.vertex, &b, &chain));
        match bounce == 0 && chain.specular == 0 {
            true => direct += found,
            false => sum += found,
        }
        let End::Scatter(vertex) = chain.end else {
            break;
        };
        vp = VisiblePoint {
            vertex,
            throughput: throughput * chain.radiance_scale(),
        };
        if fluoresces(walker.tracer, &vp.vertex) {
            let onward = onward(
                vp,
                walker.carried(),
                FirstVertex::default(),
                measure,
                rng,
                stats,
            );
            sum += onward.total();
            break;
        }
        sum += lit(
            walker.carried(),
            &vp,
            LightNumbers::default(),
            measure,
            rng,
            stats,
        );
    }
    Bounces {
        direct,
        indirect: sum,
    }
}

/// The light a camera path's bounces from a vertex bring, tallied: the vertex's direct light
/// its first bounce found (the second strategy of direct light there), and the rest.
struct Bounces<L> {
    direct: L,
    indirect: L,
}

/// The light reaching the camera from a vertex ([`onward`]), tallied.
#[derive(Clone, Copy, Debug, Default)]
pub struct Onward<L> {
    /// The vertex's light samples.
    pub lit: L,
    /// Its direct light the first bounce found.
    pub direct: L,
    /// The rest.
    pub indirect: L,
}

impl<L: Copy + std::ops::Add<Output = L>> Onward<L> {
    /// All of it.
    pub fn total(&self) -> L {
        self.lit + self.direct + self.indirect
    }

    /// Each part as `f` makes it.
    pub fn map<K>(self, f: impl Fn(L) -> K) -> Onward<K> {
        Onward {
            lit: f(self.lit),
            direct: f(self.direct),
            indirect: f(self.indirect),
        }
    }
}

impl Integrator for PathTracer<'_> {
    type Pass = ();
    type Pixel = ();
    type Layer = PathLayer;

    fn begin_pass(&self, _: u32, _: &mut Report, _: &(dyn Fn() -> bool + Sync)) -> Option<()> {
        Some(())
    }

    fn sample(&self, _: &(), _: &mut (), ray: CameraRay, s: &mut Sample<PathLayer>) {
        let hero = hero(self.tracer, s.rng);
        let carried = Carried::starting(self.tracer, hero.as_ref());
        let mut beams = Beams::default();
        let mut measure = None;
        let c = camera_path(carried, ray, &mut beams, &mut measure, s.rng, s.stats);
        s.record(PathLayer::Emitted, c.emitted);
        s.record(PathLayer::Direct, c.single);
        let dyed = dye_light(&beams, c.carried, s.rng, s.stats);
        s.record(PathLayer::Indirect, dyed);
        let Some(vp) = c.visible else { return };
        s.add(PathLayer::Albedo, vp.vertex.albedo());
        s.add(PathLayer::Normal, vp.vertex.normal());
        match measure.as_mut() {
            Some(p) => self.record_onward(vp, c.carried, ray, p, s),
            None => self.record_onward(vp, c.carried, ray, &mut Radiance, s),
        }
    }
}

impl PathTracer<'_> {
    /// Records the light reaching the camera from its path's first scattering vertex `vp`
    /// ([`onward`]), tallied through the measurement `measure` its path carries there.
    fn record_onward<'w, M: Measure>(
        &self,
        vp: VisiblePoint<'w>,
        carried: Carried<'w>,
        ray: CameraRay,
        measure: &mut M,
        s: &mut Sample<PathLayer>,
    ) {
        let onward = onward(vp, carried, ray.first, measure, s.rng, s.stats);
        s.record(PathLayer::Direct, M::recorded(onward.lit));
        s.record(PathLayer::Direct, M::recorded(onward.direct));
        s.record(PathLayer::Indirect, M::recorded(onward.indirect));
    }
}
