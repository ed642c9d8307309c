//! What every integrator estimates the same way: a camera path to its first scattering vertex
//! (the first surface after the specular and curved chain that is not purely specular), the
//! emission seen along a chain, and direct light at a scattering vertex for any BSDF. Radiance
//! per RGB channel, W/(m²·sr), scaled across indices as [`crate::transport::chain`] says. In a
//! dispersive scene each
//! camera sample draws a hero wavelength ([`hero`]) that its paths take on where they meet
//! dispersion ([`Carried`]); colours are then read at it ([`Tracer::reflectance`],
//! [`Tracer::radiance`]).

use super::beam::Beams;
use super::single::single_scattering;
use super::CameraRay;
use crate::color::Rgb;
use crate::lights::Light;
use crate::spectrum::Hero;
use crate::transport::chain::{Carried, Chain, End, Policy, Ray, Walker};
use crate::transport::connect::connect;
use crate::transport::{visibility, HeroTracer, Stats, Tracer, Vertex};
use rand::Rng;

/// A scattering vertex a camera path has reached, with what radiance leaving it becomes at
/// the camera.
#[derive(Clone, Copy, Debug)]
pub struct VisiblePoint<'w> {
    /// The vertex: where, its BSDF or phase function, ωo.
    pub vertex: Vertex<'w>,
    /// The path's throughput (reflectances, BSDF weights, absorption) times
    /// (n_camera/n_here)².
    pub throughput: Rgb,
}

/// What one camera path found.
#[derive(Clone, Copy)]
pub struct Components<'w> {
    /// Emission and environment radiance met along the specular chain.
    pub emitted: Rgb,
    /// Direct light scattered toward the camera along the chain's straight stretches through
    /// scattering media ([`super::single::single_scattering`]).
    pub single: Rgb,
    /// Its first scattering vertex, if it reached one.
    pub visible: Option<VisiblePoint<'w>>,
    /// The specular bounces on its way there.
    pub bounces: u32,
    /// Whether it crossed a gradient medium (a curved stretch) on its way there.
    pub curved: bool,
    /// The wavelengths the path carries there.
    pub carried: Carried<'w>,
}

/// A camera sample's hero wavelength, drawn from `rng` in a dispersive scene (None — and no
/// random number drawn — in any other).
pub fn hero<'a>(tracer: &'a Tracer<'a>, rng: &mut impl Rng) -> Option<HeroTracer<'a>> {
    tracer
        .scene
        .is_dispersive()
        .then(|| HeroTracer::new(tracer, Hero::visible(rng.gen())))
}

/// Radiance the end of `chain` sends back along it, as seen at its start: an emitter's (in
/// its medium), or the environment's where it escaped into the ambient medium; zero for
/// every other end. `tracer` is the one the chain ended on (it reads the environment).
pub fn emission_seen(tracer: &Tracer, chain: &Chain) -> Rgb {
    let scene = tracer.scene;
    match chain.end {
        End::Emitter { radiance, .. } => chain.weight * radiance * chain.radiance_scale(),
        End::Escaped { direction } if chain.medium == scene.ambient => {
            scene.environment.as_ref().map_or(Rgb::ZERO, |env| {
                chain.weight * tracer.radiance(env.radiance(direction)) * chain.environment_scale()
            })
        }
        _ => Rgb::ZERO,
    }
}

/// Follows a camera ray through mirrors, dielectrics and curved media to its visible point,
/// recording its stretches through scattering media in `beams`.
pub fn camera_path<'w>(
    carried: Carried<'w>,
    camera: CameraRay,
    beams: &mut Beams,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Components<'w> {
    let ray = Ray {
        origin: camera.origin,
        direction: camera.direction,
        medium: carried.tracer.camera_medium,
    };
    let mut walker = Walker::carrying(carried, Policy::Weighted).choosing(camera.choices);
    let chain = walker.follow(ray, rng, stats, &mut beams.record(carried.tracer));
    let mut out = Components {
        emitted: emission_seen(walker.tracer, &chain),
        single: single_scattering(beams, walker.carried(), rng, stats),
        visible: None,
        bounces: chain.specular,
        curved: chain.curved,
        carried: walker.carried(),
    };
    if let End::Scatter(vertex) = chain.end {
        out.visible = Some(VisiblePoint {
            vertex,
            throughput: chain.weight * chain.radiance_scale(),
        });
    }
    out
}

/// One light sample of `light` at a scattering vertex in a uniform medium, through a straight
/// shadow ray from its arrival side (multiple importance weighted against the BSDF or phase
/// sample for area lights).
fn straight_light(tracer: &Tracer, vertex: &Vertex, light: &Light, uv: (f64, f64)) -> Rgb {
    let origin = vertex.origin();
    let Some(inc) = light.sample_incident(origin, uv) else {
        return Rgb::ZERO;
    };
    let cos = vertex.cos(inc.wi);
    if cos <= 0.0 {
        return Rgb::ZERO;
    }
    let reach = if inc.distance.is_finite() {
        inc.distance * (1.0 - 1e-7)
    } else {
        f64::INFINITY
    };
    let f = vertex.eval(inc.wi);
    if f == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let medium = vertex.medium();
    let kept = visibility::transmittance(tracer, origin, medium, inc.wi, reach);
    let unscattered = visibility::unscattered(tracer, origin, medium, inc.wi, reach);
    let weight = power_heuristic(inc.pdf, vertex.pdf(inc.wi));
    f * tracer.radiance(inc.irradiance) * (cos * weight * kept) * unscattered
}

/// A point, spot, LED or parallel light at a scattering vertex in gradient medium `m`,
/// through the curved connection to it (`uv` samples an LED's disk).
fn curved_light(
    tracer: &Tracer,
    vertex: &Vertex,
    m: usize,
    light: &Light,
    uv: (f64, f64),
    stats: &mut Stats,
) -> Rgb {
    let Some(anchor) = light.anchor(uv) else {
        return Rgb::ZERO;
    };
    let Some(link) = connect(tracer, vertex.origin(), m, &anchor, stats) else {
        return Rgb::ZERO;
    };
    let cos = vertex.cos(link.direction);
    if cos <= 0.0 {
        return Rgb::ZERO;
    }
    let e = link.irradiance(&anchor, tracer.radiance(light.intensity(-link.arrival)));
    let unscattered = tracer
        .scattering(m)
        .map_or(Rgb::ONE, |sc| sc.transmittance(link.column));
    vertex.eval(link.direction) * e * unscattered * cos
}

/// The power heuristic's weight of a strategy of pdf `a` against one of pdf `b` (1 when `a`
/// is a delta).
fn power_heuristic(a: f64, b: f64) -> f64 {
    if a.is_infinite() {
        1.0
    } else {
        a * a / (a * a + b * b)
    }
}

/// Direct light at the visible point `vp` ([`direct_at`]) — but none at a point in a scattering
/// medium of uniform index: the direct light scattered along the whole straight stretch that
/// ended there is [`super::single::single_scattering`]'s, which samples it where the lights are.
pub fn direct(carried: Carried, vp: &VisiblePoint, rng: &mut impl Rng, stats: &mut Stats) -> Rgb {
    match vp.vertex {
        Vertex::Medium(v)
            if v.medium
                .is_some_and(|m| carried.tracer.medium(m).is_uniform()) =>
        {
            Rgb::ZERO
        }
        _ => direct_at(carried, vp, rng, stats),
    }
}

/// Direct light at a scattering vertex: light that reaches it from an emitter or the
/// environment with no specular interaction on the way, reflected toward ωo by its BSDF.
/// - In a uniform medium, one light sample of every light through a straight shadow ray
///   (the visibility query: detectors are transparent, absorption applied), and one BSDF
///   ray, combined by multiple importance sampling with the power heuristic for area lights
///   (the only lights both strategies can find). Light samples reach the arrival side; a
///   transmitted BSDF ray is the only strategy for the other side (weight 1).
/// - In a gradient medium a straight connection is not a light path: point, spot, LED and
///   parallel light are connected to along the curved path ([`connect`]), and the BSDF ray,
///   followed along its curved path, finds area lights and the environment (weight 1: there
///   are no area-light samples to weigh it against).
///
/// A BSDF ray that meets a purely specular surface first carries nothing: that light is the
/// caustic map's. A BSDF ray into a dispersive medium takes on the hero wavelength there;
/// connections are traced at the wavelength(s) the path carries.
pub fn direct_at(
    carried: Carried,
    vp: &VisiblePoint,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Rgb {
    let tracer = carried.tracer;
    let scene = tracer.scene;
    let vertex = &vp.vertex;
    let graded = vertex.medium().filter(|&m| !tracer.medium(m).is_uniform());
    let origin = vertex.origin();
    let mut radiance = Rgb::ZERO;
    for light in &scene.lights {
        let lit = match graded {
            None => straight_light(tracer, vertex, light, (rng.gen(), rng.gen())),
            Some(m) if !light.is_hittable() => {
                curved_light(tracer, vertex, m, light, (rng.gen(), rng.gen()), stats)
            }
            Some(_) => Rgb::ZERO,
        };
        radiance += lit;
    }
    let Some(s) = vertex.scatter_with(rng) else {
        return vp.throughput * radiance;
    };
    let mut walker = Walker::carrying(carried, Policy::Unscattered);
    let chain = walker.follow(s.ray, rng, stats, &mut ());
    // Light samples reach only the arrival side of a vertex in a uniform medium.
    let weighed = graded.is_none() && !s.sample.transmitted();
    let mis = match chain.end {
        End::Emitter {
            prim,
            position,
            direction,
            ..
        } if weighed => scene.surfaces[prim]
            .light
            .map_or(1.0, |l| match &scene.lights[l] {
                Light::Area { emitter, .. } => {
                    let cos_l = -direction.dot(emitter.normal());
                    let t2 = (position - origin).length_squared();
                    power_heuristic(s.sample.pdf, t2 / (cos_l * emitter.area()))
                }
                _ => 1.0,
            }),
        _ => 1.0,
    };
    radiance += s.sample.weight * emission_seen(walker.tracer, &chain) * (mis * s.radiance_scale);
    vp.throughput * radiance
}
