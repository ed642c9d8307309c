//! What every integrator estimates the same way: a camera path to its visible point (the first
//! diffuse surface after the specular and curved chain), the emission seen along a chain, and
//! direct light at a diffuse point. Radiance per RGB channel, W/(m²·sr), scaled across indices
//! as [`crate::transport::chain`] says; Lambertian BRDF = albedo/π. In a dispersive scene each
//! camera sample draws a hero wavelength ([`hero`]) that its paths take on where they meet
//! dispersion ([`Carried`]); colours are then read at it ([`Tracer::reflectance`],
//! [`Tracer::radiance`]).

use crate::bsdf::Bsdf;
use crate::color::Rgb;
use crate::lights::Light;
use crate::spectrum::Hero;
use crate::transport::chain::{Carried, Chain, End, Policy, Ray, Walker};
use crate::transport::connect::connect;
use crate::transport::{offset, visibility, HeroTracer, Stats, Tracer};
use glam::DVec3;
use rand::Rng;
use std::f64::consts::FRAC_1_PI;

/// A diffuse point a path has reached (the camera's first: its visible point).
#[derive(Clone, Copy, Debug)]
pub struct VisiblePoint {
    /// Where.
    pub position: DVec3,
    /// Unit normal of the side the path arrived on.
    pub normal: DVec3,
    /// Albedo of the surface.
    pub albedo: Rgb,
    /// What radiance leaving the point becomes at the camera: the path's throughput (mirror
    /// reflectances, albedos, absorption) times (n_camera/n_here)².
    pub throughput: Rgb,
    /// The medium the path arrived in (None: vacuum).
    pub medium: Option<usize>,
}

/// What one camera path found.
#[derive(Clone, Copy)]
pub struct Components<'w> {
    /// Emission and environment radiance met along the specular chain.
    pub emitted: Rgb,
    /// The visible point, if the path reached a diffuse surface.
    pub visible: Option<VisiblePoint>,
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

/// Follows a camera ray through mirrors, dielectrics and curved media to its visible point.
pub fn camera_path<'w>(
    carried: Carried<'w>,
    origin: DVec3,
    dir: DVec3,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Components<'w> {
    let ray = Ray {
        origin,
        direction: dir,
        medium: carried.tracer.camera_medium,
    };
    let mut walker = Walker::carrying(carried, Policy::Weighted);
    let chain = walker.follow(ray, rng, stats, &mut ());
    let mut out = Components {
        emitted: emission_seen(walker.tracer, &chain),
        visible: None,
        carried: walker.carried(),
    };
    if let End::Diffuse {
        position,
        normal,
        albedo,
        ..
    } = chain.end
    {
        out.visible = Some(VisiblePoint {
            position,
            normal,
            albedo,
            throughput: chain.weight * chain.radiance_scale(),
            medium: chain.medium,
        });
    }
    out
}

/// One light sample of `light` at a visible point in a uniform medium, through a straight
/// shadow ray (multiple importance weighted against the BSDF sample for area lights).
fn straight_light(
    tracer: &Tracer,
    vp: &VisiblePoint,
    origin: DVec3,
    light: &Light,
    uv: (f64, f64),
) -> Rgb {
    let Some(inc) = light.sample_incident(origin, uv) else {
        return Rgb::ZERO;
    };
    let cos = inc.wi.dot(vp.normal);
    if cos <= 0.0 {
        return Rgb::ZERO;
    }
    let reach = if inc.distance.is_finite() {
        inc.distance * (1.0 - 1e-7)
    } else {
        f64::INFINITY
    };
    let kept = visibility::transmittance(tracer, origin, vp.medium, inc.wi, reach);
    let weight = power_heuristic(inc.pdf, cos * FRAC_1_PI);
    vp.albedo * FRAC_1_PI * tracer.radiance(inc.irradiance) * (cos * weight * kept)
}

/// A point, spot, LED or parallel light at a visible point in gradient medium `m`, through
/// the curved connection to it (`uv` samples an LED's disk).
fn curved_light(
    tracer: &Tracer,
    vp: &VisiblePoint,
    m: usize,
    light: &Light,
    uv: (f64, f64),
    stats: &mut Stats,
) -> Rgb {
    let origin = offset(vp.position, vp.normal);
    let Some(anchor) = light.anchor(uv) else {
        return Rgb::ZERO;
    };
    let Some(link) = connect(tracer, origin, m, &anchor, stats) else {
        return Rgb::ZERO;
    };
    let cos = link.direction.dot(vp.normal);
    if cos <= 0.0 {
        return Rgb::ZERO;
    }
    let e = link.irradiance(&anchor, tracer.radiance(light.intensity(-link.arrival)));
    vp.albedo * FRAC_1_PI * e * cos
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

/// Direct light at a visible point: light that reaches it from an emitter or the environment
/// with no specular interaction on the way.
/// - In a uniform medium, one light sample of every light through a straight shadow ray
///   (the visibility query: detectors are transparent, absorption applied), and one
///   cosine-sampled (BSDF) ray, combined by multiple importance sampling with the power
///   heuristic for area lights (the only lights both strategies can find).
/// - In a gradient medium a straight connection is not a light path: point, spot, LED and
///   parallel light are connected to along the curved path ([`connect`]), and the BSDF ray,
///   followed along its curved path, finds area lights and the environment (weight 1: there
///   are no area-light samples to weigh it against).
///
/// A BSDF ray that meets a mirror or dielectric first carries nothing: that light is the
/// caustic map's. A BSDF ray into a dispersive medium takes on the hero wavelength there;
/// connections are traced at the wavelength(s) the path carries.
pub fn direct(carried: Carried, vp: &VisiblePoint, rng: &mut impl Rng, stats: &mut Stats) -> Rgb {
    let tracer = carried.tracer;
    let scene = tracer.scene;
    let graded = vp.medium.filter(|&m| !tracer.medium(m).is_uniform());
    let origin = offset(vp.position, vp.normal);
    let mut radiance = Rgb::ZERO;
    for light in &scene.lights {
        let lit = match graded {
            None => straight_light(tracer, vp, origin, light, (rng.gen(), rng.gen())),
            Some(m) if !light.is_hittable() => {
                curved_light(tracer, vp, m, light, (rng.gen(), rng.gen()), stats)
            }
            Some(_) => Rgb::ZERO,
        };
        radiance += lit;
    }
    let uniform = graded.is_none();
    // The BSDF sample: f cos θ / pdf = albedo for cosine sampling.
    let lambert = Bsdf::Lambert { albedo: vp.albedo };
    let s = lambert
        .sample(vp.normal, vp.normal, (rng.gen(), rng.gen(), 0.0))
        .expect("a Lambertian surface always scatters");
    let ray = Ray {
        origin,
        direction: s.wi,
        medium: vp.medium,
    };
    let mut walker = Walker::carrying(carried, Policy::Unscattered);
    let chain = walker.follow(ray, rng, stats, &mut ());
    let mis = match chain.end {
        End::Emitter {
            prim,
            position,
            direction,
            ..
        } if uniform => scene.surfaces[prim]
            .light
            .map_or(1.0, |l| match &scene.lights[l] {
                Light::Area { emitter, .. } => {
                    let cos_l = -direction.dot(emitter.normal());
                    let t2 = (position - origin).length_squared();
                    power_heuristic(s.pdf, t2 / (cos_l * emitter.area()))
                }
                _ => 1.0,
            }),
        _ => 1.0,
    };
    radiance += s.weight * emission_seen(walker.tracer, &chain) * mis;
    vp.throughput * radiance
}
