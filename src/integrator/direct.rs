//! What every integrator estimates the same way: a camera path to its first scattering vertex
//! (the first surface after the specular and curved chain that is not purely specular), and
//! direct light at its vertices as the camera sees it (the estimate itself, and the emission
//! seen along a chain, are [`crate::transport::lighting`]'s). Radiance
//! per RGB channel, W/(m²·sr), scaled across indices as [`crate::transport::chain`] says. In a
//! dispersive scene each
//! camera sample draws a hero wavelength ([`hero`]) that its paths take on where they meet
//! dispersion ([`Carried`]); colours are then read at it ([`Tracer::reflectance`],
//! [`Tracer::radiance`]).

use super::beam::Beams;
use super::single::single_scattering;
use super::CameraRay;
use crate::color::Rgb;
use crate::spectrum::Hero;
use crate::transport::chain::{Carried, Chain, End, Policy, Ray, Walker};
use crate::transport::lighting::direct_light;
pub use crate::transport::lighting::emission_seen;
use crate::transport::{HeroTracer, Stats, Tracer, Vertex};
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
    /// Emission and environment radiance met along the specular chain, and the light its
    /// media emitted on the way.
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
    record_cut(&chain, Rgb::ONE, stats);
    let mut out = Components {
        emitted: emission_seen(walker.tracer, &chain) + chain.emitted,
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

/// Direct light at the visible point `vp` ([`direct_light`]) as seen at the camera (times the
/// path's throughput there) — but none at a point in a scattering
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
        Vertex::Medium(_) | Vertex::Surface(_) => {
            vp.throughput * direct_light(carried, &vp.vertex, rng, stats)
        }
    }
}

/// Counts in `stats` what a camera path whose chain ended at the depth limit carried there:
/// `throughput` before the chain times the chain's weight.
pub fn record_cut(chain: &Chain, throughput: Rgb, stats: &mut Stats) {
    if chain.end == End::DepthLimit {
        stats.camera_weight_cut += (throughput * chain.weight).mean();
    }
}
