//! Direct light at a scattering vertex: light that reaches it from the lights and the
//! environment with no specular interaction on the way (light samples through the one shadow
//! ray or curved connections, and a BSDF or phase sample, weighed against each other), and the
//! emission a chain sees at its end. Radiance per RGB channel, W/(m²·sr), scaled across
//! indices as [`super::chain`] says. Camera paths, the path tracer and the photons the
//! medium around the scene scatters toward it all estimate direct light here.

use super::chain::{Carried, Chain, End, Policy, Ray, Walker};
use super::connect::connect;
use super::{offset, visibility, Scattered, Stats, SurfaceVertex, Tracer, Vertex};
use crate::color::Rgb;
use crate::ids::MediumId;
use crate::lights::{Light, LightSamples};
use crate::polarization::{Polarization, Recorded, StoredStokes};
use crate::sampling::{Given, Pick};
use crate::scene::Role;
use glam::DVec3;
use rand::Rng;
use std::ops::{Add, AddAssign, Div, Mul};

/// What a camera path carries of the camera's measurement past its first chain, and what the
/// light it estimates is tallied as: radiance where the transport is not polarized
/// ([`Radiance`]), or what the camera records through the rows of its polarized measurement
/// ([`Polarization`], carried against the light, per unit of the path's weight:
/// [`Polarization::close`]). Estimates are generic over it, so that unpolarized transport
/// adds up radiance alone.
pub trait Measure {
    /// The tallied light.
    type Light: Copy
        + Default
        + Add<Output = Self::Light>
        + AddAssign
        + Mul<Rgb, Output = Self::Light>
        + Mul<f64, Output = Self::Light>
        + Div<f64, Output = Self::Light>;
    /// What is tallied per unit of radiance of the light arriving at `vertex` from unit `wi`
    /// that leaves toward ωo, the scattering function aside ([`Vertex::measure_toward`]): of
    /// unpolarized light, or of the Stokes vector a photon map kept (`kept`).
    fn through(&self, vertex: &Vertex, wi: DVec3, kept: Option<&StoredStokes>) -> Self::Light;
    /// Depolarized light of radiance `value` (as the path's weight sees it) where the path is.
    fn of(&self, value: Rgb) -> Self::Light;
    /// Light as the camera records it, as tallied.
    fn tallied(recorded: Recorded) -> Self::Light;
    /// Tallied light as the camera records it.
    fn recorded(light: Self::Light) -> Recorded;
    /// The measurement past `vertex`, the path going on toward unit `wi`.
    fn toward(&mut self, vertex: &Vertex, wi: DVec3);
    /// The rows a chain carries along ([`Walker::follow_measured`]; None: radiance alone).
    fn rows(&mut self) -> Option<&mut Polarization>;
}

/// Light tallied as radiance (per RGB channel): unpolarized transport.
#[derive(Clone, Copy, Debug)]
pub struct Radiance;

impl Measure for Radiance {
    type Light = Rgb;
    fn through(&self, _: &Vertex, _: DVec3, _: Option<&StoredStokes>) -> Rgb {
        Rgb::ONE
    }
    fn of(&self, value: Rgb) -> Rgb {
        value
    }
    fn tallied(recorded: Recorded) -> Rgb {
        recorded.s0
    }
    fn recorded(light: Rgb) -> Recorded {
        Recorded::radiance(light)
    }
    fn toward(&mut self, _: &Vertex, _: DVec3) {}
    fn rows(&mut self) -> Option<&mut Polarization> {
        None
    }
}

impl Measure for Polarization {
    type Light = Recorded;
    fn through(&self, vertex: &Vertex, wi: DVec3, kept: Option<&StoredStokes>) -> Recorded {
        let element = vertex.mueller(wi);
        self.recorded_through(element.as_ref(), -vertex.wo(), kept, -wi)
    }
    fn of(&self, value: Rgb) -> Recorded {
        Recorded::of(Some(self), value)
    }
    fn tallied(recorded: Recorded) -> Recorded {
        recorded
    }
    fn recorded(light: Recorded) -> Recorded {
        light
    }
    fn toward(&mut self, vertex: &Vertex, wi: DVec3) {
        vertex.measure_toward(self, wi);
    }
    fn rows(&mut self) -> Option<&mut Polarization> {
        Some(self)
    }
}

/// Radiance the end of `chain` sends back along it, as seen at its start: an emitter's (in
/// its medium), or the environment's where it escaped into the ambient medium; zero for
/// every other end. `tracer` is the one the chain ended on (it reads the environment).
pub fn emission_seen(tracer: &Tracer, chain: &Chain) -> Rgb {
    let scene = tracer.scene;
    match chain.end {
        End::Emitter { radiance, .. } => chain.weight * radiance * chain.radiance_scale(),
        End::Escaped { direction } if chain.medium == scene.ambient() => {
            scene.environment.as_ref().map_or(Rgb::ZERO, |env| {
                chain.weight * tracer.radiance(env.radiance(direction)) * chain.environment_scale()
            })
        }
        End::Escaped { .. }
        | End::Scatter(_)
        | End::Absorbed { .. }
        | End::Lost
        | End::DepthLimit
        | End::Stopped => Rgb::ZERO,
    }
}

/// Whether light samples reach the surface vertex `v` through it, from its far side: its BSDF
/// transmits, into a medium of uniform index (a straight shadow ray there is a light path).
pub fn samples_through(tracer: &Tracer, v: &SurfaceVertex) -> bool {
    v.lobes().transmits() && v.beyond.is_none_or(|m| tracer.medium(m).is_uniform())
}

/// A face of a scattering vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Face {
    /// The side the path arrived on (the point itself in a medium).
    Arrival,
    /// The other side of a surface, where a transmitted path goes.
    Far,
}

/// The side of a scattering vertex light arriving from a direction comes from, as a light
/// sample's shadow ray leaves it.
struct LitSide {
    /// Which face it is.
    face: Face,
    /// Where the shadow ray starts: off the surface on that side (the point itself in a
    /// medium).
    origin: DVec3,
    /// The medium it crosses.
    medium: Option<MediumId>,
    /// |cos| at the surface's normal (1 in a medium).
    cos: f64,
    /// What radiance from there becomes toward ωo besides f: (n_ωo/n_far)² from a rough
    /// interface's far side ([`SurfaceVertex::radiance_scale`]), else 1.
    radiance_scale: f64,
}

/// The side light arriving from unit `wi` reaches `vertex` from — its arrival side, or the far
/// side of a surface light samples reach through ([`samples_through`]) — or None where no
/// light sample reaches it from there.
fn lit_side(tracer: &Tracer, vertex: &Vertex, wi: DVec3) -> Option<LitSide> {
    let cos = vertex.cos(wi);
    if cos > 0.0 {
        return Some(LitSide {
            face: Face::Arrival,
            origin: vertex.origin(),
            medium: vertex.medium(),
            cos,
            radiance_scale: 1.0,
        });
    }
    let v = vertex
        .surface()
        .filter(|v| cos < 0.0 && samples_through(tracer, v))?;
    Some(LitSide {
        face: Face::Far,
        origin: offset(v.position, -v.normal),
        medium: v.beyond,
        cos: -cos,
        radiance_scale: v.radiance_scale(wi),
    })
}

/// The sides of a vertex a light sample may light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Sides {
    /// Whichever side the light lies on (the vertex is in a uniform medium).
    Either,
    /// Only the far side of a surface (its arrival side is in a gradient medium, where light
    /// samples connect by curved paths).
    Far,
}

/// One light sample of light `index` at a scattering vertex, through a straight shadow ray from the
/// side the light lies on, among `sides` (the far side only through a surface that transmits
/// into a uniform medium); multiple importance weighted against the BSDF or phase sample for
/// area lights.
fn straight_light<M: Measure>(
    tracer: &Tracer,
    vertex: &Vertex,
    sides: Sides,
    index: usize,
    chosen: f64,
    uv: (f64, f64),
    measure: &M,
) -> M::Light {
    let light = &tracer.scene.lights[index];
    let Some(inc) = light.sample_incident(vertex.origin(), uv) else {
        return M::Light::default();
    };
    let Some(side) = lit_side(tracer, vertex, inc.wi) else {
        return M::Light::default();
    };
    if sides == Sides::Far && side.face == Face::Arrival {
        return M::Light::default();
    }
    let reach = if inc.distance.is_finite() {
        inc.distance * (1.0 - 1e-7)
    } else {
        f64::INFINITY
    };
    let f = vertex.eval(inc.wi);
    if f == Rgb::ZERO {
        return M::Light::default();
    }
    let kept = visibility::transmittance(tracer, side.origin, side.medium, inc.wi, reach);
    let weight = power_heuristic(inc.pdf * chosen, vertex.pdf(inc.wi));
    measure.through(vertex, inc.wi, None)
        * (f * tracer.emitted_by(index, inc.irradiance)
            * (side.cos * weight * side.radiance_scale)
            * kept)
}

/// A point, spot, LED or parallel light (light `index`) at a scattering vertex, through the curved connection
/// to it from its `face` in the gradient medium there: its arrival side, or the far side of a
/// surface that transmits into one (`uv` samples an LED's disk). Zero where that side's
/// medium is uniform (a straight shadow ray serves it) or no connection reaches the light.
fn curved_light<M: Measure>(
    tracer: &Tracer,
    vertex: &Vertex,
    face: Face,
    index: usize,
    uv: (f64, f64),
    measure: &M,
    stats: &mut Stats,
) -> M::Light {
    let light = &tracer.scene.lights[index];
    let (origin, medium) = match (face, vertex.surface()) {
        (Face::Arrival, _) => (vertex.origin(), vertex.medium()),
        (Face::Far, Some(v)) if v.lobes().transmits() => (offset(v.position, -v.normal), v.beyond),
        (Face::Far, _) => return M::Light::default(),
    };
    let Some(m) = medium.filter(|&m| !tracer.medium(m).is_uniform()) else {
        return M::Light::default();
    };
    let Some(anchor) = light.anchor(uv) else {
        return M::Light::default();
    };
    let Some(link) = connect(tracer, origin, m, &anchor, stats) else {
        return M::Light::default();
    };
    let (cos, radiance_scale) = match (face, vertex.surface()) {
        (Face::Far, Some(v)) => (
            -vertex.cos(link.direction),
            v.radiance_scale(link.direction),
        ),
        (Face::Arrival, _) | (Face::Far, None) => (vertex.cos(link.direction), 1.0),
    };
    if cos <= 0.0 {
        return M::Light::default();
    }
    let e = link.irradiance(
        &anchor,
        tracer.emitted_by(index, light.intensity(-link.arrival)),
    );
    let unscattered = tracer
        .scattering(m)
        .map_or(Rgb::ONE, |sc| sc.transmittance(link.column));
    measure.through(vertex, link.direction, None)
        * (vertex.eval(link.direction) * e * unscattered * (cos * radiance_scale))
}

fn power_heuristic(a: f64, b: f64) -> f64 {
    if a.is_infinite() {
        1.0
    } else {
        a * a / (a * a + b * b)
    }
}

/// Direct light at a scattering vertex: light that reaches it from an emitter or the
/// environment with no specular interaction on the way, reflected toward ωo by its BSDF
/// (radiance leaving the vertex, W/(m²·sr), per unit of the scattering coefficient at a point
/// in a medium).
/// - In a uniform medium, one light sample of every light or of one drawn by a bound on the
///   irradiance it can send to the vertex, as the integrator chose ([`crate::lights::LightSamples`]) through a straight shadow ray (the visibility query:
///   detectors are transparent, absorption applied), and one BSDF ray, combined by multiple
///   importance sampling with the power heuristic for area lights (the only lights both
///   strategies can find; a light sample's density is the light's times the chance it was
///   drawn). Light samples reach the arrival side, and the far side of a surface that
///   transmits into a uniform medium (a rough glass lit from behind, by a point light as by
///   any); a BSDF ray transmitted into a gradient medium is the only strategy there (weight 1).
/// - In a gradient medium a straight connection is not a light path: point, spot, LED and
///   parallel light (the light drawn, if it is one of them) are connected to along the
///   curved path ([`connect`]), and the BSDF ray,
///   followed along its curved path, finds area lights and the environment (weight 1: there
///   are no area-light samples to weigh it against).
///
/// A BSDF ray that meets a purely specular surface first carries nothing: that light is the
/// caustic map's. A BSDF ray that can find no emission is not traced ([`may_find_emission`]). A BSDF ray into a dispersive medium takes on the hero wavelength there;
/// connections are traced at the wavelength(s) the path carries.
pub fn direct_light<M: Measure>(
    carried: Carried,
    vertex: &Vertex,
    measure: &M,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> M::Light {
    let mut radiance = light_samples(
        carried,
        vertex,
        LightNumbers::default(),
        measure,
        rng,
        stats,
    );
    let Some(s) = vertex.scatter_with(rng) else {
        return radiance;
    };
    if !may_find_emission(carried.tracer, &s.ray) {
        return radiance;
    }
    // A chain that stops at its first specular surface meets no polarizing element.
    let mut walker = Walker::carrying(carried, Policy::Unscattered);
    let chain = walker.follow(s.ray, rng, stats, &mut ());
    let mis = bsdf_sample_weight(carried.tracer, vertex, &s, &chain);
    radiance += measure.through(vertex, s.sample.wi, None)
        * (s.sample.weight * emission_seen(walker.tracer, &chain) * (mis * s.radiance_scale));
    radiance
}

/// Whether the BSDF ray `ray` of [`direct_light`] may find emission ([`emission_seen`] not
/// zero): yes, unless the tracer finds emission along straight lines only
/// ([`Tracer::emission_on_lines`]) and the ray's line meets no area light. Its chain then
/// cannot: it follows that line (every medium of uniform index; through sheets, detectors and
/// surfaces joining equal indices) to its end — a scattering vertex, a specular surface where
/// it stops, an emitter, or the world's edge, where no environment shines — drawing no random
/// number on the way ([`Policy::Unscattered`]), so leaving it untraced changes no estimate.
pub fn may_find_emission(tracer: &Tracer, ray: &Ray) -> bool {
    !tracer.emission_on_lines
        || tracer.scene.lights.iter().any(|light| match light {
            Light::Area { emitter, .. } => emitter.meets_ray(ray.origin, ray.direction),
            Light::Point { .. }
            | Light::Spot { .. }
            | Light::Led { .. }
            | Light::Goniometric { .. }
            | Light::Directional { .. } => false,
        })
}

/// The light samples of [`direct_light`] alone (its first strategy): for a path that goes on
/// along its own BSDF or phase sample and weighs the emission that finds by
/// [`bsdf_sample_weight`], so that one ray serves as the second strategy and as the way on.
pub fn light_samples<M: Measure>(
    carried: Carried,
    vertex: &Vertex,
    numbers: LightNumbers,
    measure: &M,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> M::Light {
    let tracer = carried.tracer;
    let scene = tracer.scene;
    let graded = vertex
        .medium()
        .is_some_and(|m| !tracer.medium(m).is_uniform());
    // Light `index`'s sample at `uv`, drawn with chance `chosen`, divided by it.
    let sample = |Pick { index, probability }: Pick, [u, v]: [f64; 2], stats: &mut Stats| {
        let light = &scene.lights[index];
        let uv = (u, v);
        let lit = match (graded, light.is_hittable()) {
            (false, _) => straight_light(
                tracer,
                vertex,
                Sides::Either,
                index,
                probability,
                uv,
                measure,
            ),
            (true, false) => {
                curved_light(tracer, vertex, Face::Arrival, index, uv, measure, stats)
                    + straight_light(tracer, vertex, Sides::Far, index, probability, uv, measure)
            }
            // An area light's light reaches a vertex in a gradient medium by the BSDF ray.
            (true, true) => M::Light::default(),
        };
        // A delta light in a gradient medium beyond a surface that transmits into it is
        // reached by no direction sample and no straight shadow ray: by the curved connection
        // from the far side only (an area light there by the BSDF ray).
        let beyond = match light.is_hittable() {
            false => curved_light(tracer, vertex, Face::Far, index, uv, measure, stats),
            true => M::Light::default(),
        };
        (lit + beyond) / probability
    };
    match tracer.light_samples {
        LightSamples::Each => {
            let mut radiance = M::Light::default();
            for index in 0..scene.lights.len() {
                let uv = [rng.gen(), rng.gen()];
                let each = Pick {
                    index,
                    probability: 1.0,
                };
                radiance += sample(each, uv, stats);
            }
            radiance
        }
        LightSamples::One => {
            let uv = numbers.uv.or_draw(rng);
            let choice = tracer.light_sampler.at(vertex.origin());
            match choice.pick(numbers.pick, rng) {
                Some(pick) => sample(pick, uv, stats),
                None => M::Light::default(),
            }
        }
    }
}

/// The numbers a vertex's light sample takes in place of its stream's, where given: the
/// point on the light and the number that picks it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightNumbers {
    /// Where on the light (an area light's or LED's surface).
    pub uv: Given<2>,
    /// Which light ([`crate::lights::LightChoice::pick`]).
    pub pick: Given<1>,
}

/// The multiple-importance weight of the emission that a BSDF or phase sample `s` of `vertex`
/// found at the end of `chain`, a chain that met no specular surface: the power heuristic
/// against the light samples where they could have found it (an area light, seen from a
/// vertex in a uniform medium on its arrival side, or through it where [`samples_through`]),
/// 1 where they could not (the environment, a sample transmitted into a gradient medium, a
/// vertex in a gradient medium).
pub fn bsdf_sample_weight(tracer: &Tracer, vertex: &Vertex, s: &Scattered, chain: &Chain) -> f64 {
    let graded = vertex
        .medium()
        .is_some_and(|m| !tracer.medium(m).is_uniform());
    // Light samples reach the arrival side of a vertex in a uniform medium, and its far side
    // through a surface that transmits into a uniform medium.
    let through = || vertex.surface().is_some_and(|v| samples_through(tracer, v));
    let weighed = !graded && (!s.sample.transmitted() || through());
    match chain.end {
        End::Emitter {
            prim,
            position,
            normal,
            direction,
            ..
        } if weighed => match tracer.scene.surface(prim).role {
            Role::Emitter(l) => {
                let choice = tracer.light_sampler.at(vertex.origin());
                power_heuristic(
                    s.sample.pdf,
                    tracer.scene.light(l).pdf_incident(
                        vertex.origin(),
                        direction,
                        (position - vertex.origin()).length(),
                        normal,
                    ) * choice.chance(tracer.light_samples, l),
                )
            }
            // A path ends at an emitter only on an emitter's surface.
            Role::Scatter(_) | Role::Detector(_) => 1.0,
        },
        // Light the sample did not reach by hitting a surface has no second strategy.
        End::Emitter { .. }
        | End::Scatter(_)
        | End::Escaped { .. }
        | End::Absorbed { .. }
        | End::Lost
        | End::DepthLimit
        | End::Stopped => 1.0,
    }
}
