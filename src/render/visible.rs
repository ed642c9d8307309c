//! A camera path to its visible point (the first diffuse surface after the specular and
//! curved chain), and the direct and secondary estimates there. Radiance per RGB channel,
//! W/(m²·sr); Lambertian BRDF = albedo/π.

use crate::color::Rgb;
use crate::lights::Light;
use crate::material::Material;
use crate::photon::PhotonMap;
use crate::sampling::{cosine_hemisphere, Frame};
use crate::transport::{facing, offset, Event, Stats, Tracer};
use glam::DVec3;
use rand::Rng;
use std::f64::consts::FRAC_1_PI;

/// The first diffuse surface a camera path meets.
#[derive(Clone, Copy, Debug)]
pub struct VisiblePoint {
    /// Where.
    pub position: DVec3,
    /// Unit normal of the side the path arrived on.
    pub normal: DVec3,
    /// Albedo of the surface.
    pub albedo: Rgb,
    /// Throughput of the camera path up to here (mirror reflectances).
    pub throughput: Rgb,
    /// The medium the path arrived in (None: vacuum).
    pub medium: Option<usize>,
}

/// What one camera path found.
#[derive(Clone, Copy, Debug, Default)]
pub struct Components {
    /// Emission and environment radiance met along the specular chain.
    pub emitted: Rgb,
    /// The visible point, if the path reached a diffuse surface.
    pub visible: Option<VisiblePoint>,
}

/// Follows a camera ray through mirrors, dielectrics and curved media to its visible point.
pub fn camera_path(
    tracer: &Tracer,
    mut origin: DVec3,
    mut dir: DVec3,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Components {
    let scene = tracer.scene;
    let mut medium = scene.ambient;
    let mut throughput = Rgb::ONE;
    let mut out = Components::default();
    for _ in 0..tracer.settings.max_depth {
        let event = tracer.next_event(origin, dir, medium, stats);
        if let Event::Surface { distance, .. } | Event::Escaped { distance, .. } = event {
            throughput *= tracer.transmittance(medium, origin, distance);
        }
        let (prim, position, normal, incoming) = match event {
            Event::Surface {
                prim,
                position,
                normal,
                direction,
                ..
            } => (prim, position, normal, direction),
            Event::Escaped { direction, .. } => {
                if let (true, Some(env)) = (medium == scene.ambient, &scene.environment) {
                    out.emitted += throughput * env.radiance(direction);
                }
                return out;
            }
            Event::Lost => return out,
        };
        let surface = scene.surfaces[prim];
        let side = facing(normal, incoming);
        match &scene.materials[surface.material] {
            Material::Emissive { radiance } => {
                if side == normal {
                    out.emitted += throughput * *radiance;
                }
                return out;
            }
            Material::Diffuse { albedo } => {
                out.visible = Some(VisiblePoint {
                    position,
                    normal: side,
                    albedo: *albedo,
                    throughput,
                    medium,
                });
                return out;
            }
            Material::Mirror { .. } | Material::Dielectric | Material::Detector { .. } => {
                let Some(b) =
                    tracer.specular_bounce(surface, medium, position, incoming, normal, rng.gen())
                else {
                    return out;
                };
                throughput *= b.weight;
                (origin, dir, medium) = (b.origin, b.direction, b.medium);
            }
        }
    }
    stats.depth_limited += 1;
    out
}

/// Direct light at a visible point, where a straight connection is valid (the point lies in
/// a uniform medium): one light sample of every light through a straight shadow ray, and one
/// cosine-sampled (BSDF) ray, combined by multiple importance sampling with the power
/// heuristic for area lights (the only lights both strategies can find); the same ray
/// collects environment light when it escapes. A shadow ray or BSDF ray that meets another
/// surface first (glass or a GRIN object included) carries nothing: that light is the
/// caustic map's. Zero in a non-uniform medium.
pub fn direct(tracer: &Tracer, vp: &VisiblePoint, rng: &mut impl Rng) -> Rgb {
    let scene = tracer.scene;
    if !vp.medium.is_none_or(|m| scene.medium_at(m).is_uniform()) {
        return Rgb::ZERO;
    }
    let power = |a: f64, b: f64| {
        if a.is_infinite() {
            1.0
        } else {
            a * a / (a * a + b * b)
        }
    };
    let origin = offset(vp.position, vp.normal);
    let mut radiance = Rgb::ZERO;
    for light in &scene.lights {
        let Some(inc) = light.sample_incident(origin, (rng.gen(), rng.gen())) else {
            continue;
        };
        let cos = inc.wi.dot(vp.normal);
        if cos <= 0.0 {
            continue;
        }
        let reach = if inc.distance.is_finite() {
            inc.distance * (1.0 - 1e-7)
        } else {
            f64::INFINITY
        };
        if scene
            .accel
            .intersect_ray(origin, inc.wi, 0.0, reach)
            .is_none()
        {
            let weight = power(inc.pdf, cos * FRAC_1_PI);
            // Absorption along the connection, up to the world sphere for lights beyond it.
            let length = inc.distance.min(tracer.world.exit_distance(origin, inc.wi));
            let kept = tracer.transmittance(vp.medium, origin, length);
            radiance += vp.albedo * FRAC_1_PI * inc.irradiance * (cos * weight * kept);
        }
    }
    // The BSDF sample: f cos θ / pdf = albedo for cosine sampling.
    let d = Frame::new(vp.normal).to_world(cosine_hemisphere((rng.gen(), rng.gen())));
    match scene.accel.intersect_ray(origin, d, 0.0, f64::INFINITY) {
        None => {
            if let (true, Some(env)) = (vp.medium == scene.ambient, &scene.environment) {
                let kept =
                    tracer.transmittance(vp.medium, origin, tracer.world.exit_distance(origin, d));
                radiance += vp.albedo * env.radiance(d) * kept;
            }
        }
        Some((prim, hit)) => {
            let surface = scene.surfaces[prim];
            let cos_l = -d.dot(hit.normal);
            if let (Some(l), true) = (surface.light, cos_l > 0.0) {
                if let Light::Area {
                    emitter,
                    radiance: le,
                } = &scene.lights[l]
                {
                    let pdf_light = hit.t * hit.t / (cos_l * emitter.area());
                    let pdf_bsdf = d.dot(vp.normal) * FRAC_1_PI;
                    let kept = tracer.transmittance(vp.medium, origin, hit.t);
                    radiance += vp.albedo * *le * (power(pdf_bsdf, pdf_light) * kept);
                }
            }
        }
    }
    vp.throughput * radiance
}

/// Secondary light at a visible point: `gather` cosine rays, each
/// followed through specular surfaces to a diffuse one, where the global map's precomputed
/// k-nearest irradiance of the nearest photon gives the radiance leaving it. Emission and environment met by gather rays are
/// not counted: that light is the direct or caustic part.
pub fn secondary(
    tracer: &Tracer,
    global: &PhotonMap,
    gather: u32,
    max_r2: f64,
    vp: &VisiblePoint,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Rgb {
    let scene = tracer.scene;
    let frame = Frame::new(vp.normal);
    let mut sum = Rgb::ZERO;
    for _ in 0..gather {
        stats.gather_rays += 1;
        let mut dir = frame.to_world(cosine_hemisphere((rng.gen(), rng.gen())));
        let mut origin = offset(vp.position, vp.normal);
        let mut medium = vp.medium;
        let mut weight = Rgb::ONE;
        for _ in 0..tracer.settings.max_depth {
            let Event::Surface {
                prim,
                position,
                normal,
                direction,
                distance,
            } = tracer.next_event(origin, dir, medium, stats)
            else {
                break;
            };
            weight *= tracer.transmittance(medium, origin, distance);
            let surface = scene.surfaces[prim];
            match &scene.materials[surface.material] {
                Material::Diffuse { albedo } => {
                    let facing = facing(normal, direction);
                    let e =
                        stats.time_query(|| global.nearest_irradiance(position, facing, max_r2));
                    sum += weight * *albedo * FRAC_1_PI * e;
                    break;
                }
                Material::Emissive { .. } => break,
                Material::Mirror { .. } | Material::Dielectric | Material::Detector { .. } => {
                    let Some(b) = tracer.specular_bounce(
                        surface,
                        medium,
                        position,
                        direction,
                        normal,
                        rng.gen(),
                    ) else {
                        break;
                    };
                    weight *= b.weight;
                    (origin, dir, medium) = (b.origin, b.direction, b.medium);
                }
            }
        }
    }
    // Cosine sampling: (albedo/π) L cos θ / pdf = albedo · L per ray.
    vp.throughput * vp.albedo * sum / gather.max(1) as f64
}
