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
use crate::camera::Camera;
use crate::color::Rgb;
use crate::polarization::{Element, Polarization, Recorded, Sense, Sheet};
use crate::transport::chain::{Carried, Chain, End, Policy, Ray, Walker};
pub use crate::transport::lighting::emission_seen;
use crate::transport::lighting::{
    bsdf_sample_weight, direct_light, light_samples, LightNumbers, Measure,
};
use crate::transport::{HeroTracer, Scattered, Stats, Tracer, Vertex};
use glam::DVec3;
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
    /// Emission and environment radiance met along the specular chain (none where the camera
    /// hides emitters and the chain met no specular surface), and the light its media emitted
    /// on the way, as the camera records them.
    pub emitted: Recorded,
    /// Direct light scattered toward the camera along the chain's straight stretches through
    /// scattering media ([`super::single::single_scattering`]), as the camera records it.
    pub single: Recorded,
    /// Its first scattering vertex, if it reached one.
    pub visible: Option<VisiblePoint<'w>>,
    /// The specular bounces on its way there.
    pub bounces: u32,
    /// Whether it crossed a gradient medium (a curved stretch) on its way there.
    pub curved: bool,
    /// The wavelengths the path carries there.
    pub carried: Carried<'w>,
}

/// A camera sample's hero wavelength ([`crate::scene::Scene::hero`]), drawn from `rng` in a
/// dispersive scene (None — and no
/// random number drawn — in any other).
pub fn hero<'a>(tracer: &'a Tracer<'a>, rng: &mut impl Rng) -> Option<HeroTracer<'a>> {
    tracer
        .scene
        .is_dispersive()
        .then(|| HeroTracer::new(tracer, tracer.scene.hero(rng.gen())))
}

/// Follows a camera ray through mirrors, dielectrics and curved media to its visible point,
/// recording its stretches through scattering media in `beams`. Where the transport is
/// polarized, `measure` is left holding the camera's measurement of the light at the chain's
/// end, per unit of the throughput there ([`Walker::follow_from_camera`]); None otherwise.
pub fn camera_path<'w>(
    carried: Carried<'w>,
    camera: CameraRay,
    beams: &mut Beams,
    measure: &mut Option<Polarization>,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Components<'w> {
    let ray = Ray {
        origin: camera.origin,
        direction: camera.direction,
        medium: carried.tracer.camera_medium,
    };
    let analyzer = (carried.tracer.scene.camera.as_ref()).and_then(|c| analyzer(c, ray.direction));
    let mut walker = Walker::carrying(carried, Policy::Weighted).choosing(camera.choices);
    let recording = &mut beams.record(carried.tracer);
    let analyzer = analyzer.as_ref();
    let stokes_axis = match (carried.tracer.settings.stokes, &carried.tracer.scene.camera) {
        (true, Some(c)) => Some(c.stokes_axis(ray.direction)),
        (true, None) | (false, _) => None,
    };
    let chain =
        walker.follow_from_camera(ray, analyzer, stokes_axis, measure, rng, stats, recording);
    record_cut(&chain, Rgb::ONE, stats);
    let hidden = chain.specular == 0
        && (carried.tracer.scene.camera.as_ref()).is_some_and(|c| c.hide_emitters);
    let seen = match hidden {
        true => Rgb::ZERO,
        false => emission_seen(walker.tracer, &chain),
    };
    let mut out = Components {
        emitted: Recorded::of(measure.as_ref(), seen) + beams.emission(chain.emitted),
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

/// Direct light at the visible point `vp` ([`direct_light`]) as seen at the camera, tallied
/// through the measurement its path carries there — but none at a point in a scattering
/// medium of uniform index: the direct light scattered along the whole straight stretch that
/// ended there is [`super::single::single_scattering`]'s, which samples it where the lights are.
pub fn direct<M: Measure>(
    carried: Carried,
    vp: &VisiblePoint,
    measure: &M,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> M::Light {
    match takes_direct(carried.tracer, &vp.vertex) {
        true => direct_light(carried, &vp.vertex, measure, rng, stats) * vp.throughput,
        false => M::Light::default(),
    }
}

/// [`direct`]'s light samples alone, for a path that goes on along its own BSDF or phase
/// sample and weighs the emission it finds ([`continued_emission`]).
pub fn lit<M: Measure>(
    carried: Carried,
    vp: &VisiblePoint,
    numbers: LightNumbers,
    measure: &M,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> M::Light {
    match takes_direct(carried.tracer, &vp.vertex) {
        true => light_samples(carried, &vp.vertex, numbers, measure, rng, stats) * vp.throughput,
        false => M::Light::default(),
    }
}

/// The measurement of radiance alone, for a path that sets off along unit `direction` from
/// light that is unpolarized (from a point where it is depolarized: a dye's, a diffuse
/// vertex's), where the transport is polarized; None where it is not.
pub fn measuring_radiance(tracer: &Tracer, direction: DVec3) -> Option<Polarization> {
    (tracer.settings.polarized).then(|| Polarization::unpolarized(Sense::AgainstLight, direction))
}

/// The emission the chain of a path's BSDF or phase sample `s` from `vertex` found, as seen
/// at the vertex (times the sample's weight and radiance scale): after a specular surface in
/// full (caustics: no light sample finds them), else weighed against [`lit`]'s light samples
/// where the vertex takes direct light at all.
pub fn continued_emission(tracer: &Tracer, vertex: &Vertex, s: &Scattered, chain: &Chain) -> Rgb {
    let mis = match (chain.specular > 0, takes_direct(tracer, vertex)) {
        (true, _) => 1.0,
        (false, true) => bsdf_sample_weight(tracer, vertex, s, chain),
        (false, false) => return Rgb::ZERO,
    };
    s.sample.weight * emission_seen(tracer, chain) * (mis * s.radiance_scale)
}

/// Whether direct light is estimated at `vertex`: everywhere but at a point in a scattering
/// medium of uniform index, whose direct light is the stretch's single scattering.
pub fn takes_direct(tracer: &Tracer, vertex: &Vertex) -> bool {
    match vertex {
        Vertex::Medium(v) => !v.medium.is_some_and(|m| tracer.medium(m).is_uniform()),
        Vertex::Surface(_) => true,
    }
}

/// Counts in `stats` what a camera path whose chain ended at the depth limit carried there:
/// `throughput` before the chain times the chain's weight.
pub fn record_cut(chain: &Chain, throughput: Rgb, stats: &mut Stats) {
    if chain.end == End::DepthLimit {
        stats.camera_weight_cut += (throughput * chain.weight).mean();
    }
}

/// What `camera`'s polarizer does to light arriving against its ray of unit direction `d`: a
/// sheet across the view, normal to its forward axis, its transmission axis
/// [`Camera::polarizer_axis`] ([`Sheet::element`]: off the image's centre the light crosses it
/// obliquely). None without a polarizer.
fn analyzer(camera: &Camera, d: DVec3) -> Option<Element> {
    let axis = camera.polarizer_axis()?;
    Some(Sheet::Polarizer { axis }.element(camera.forward(), d))
}
