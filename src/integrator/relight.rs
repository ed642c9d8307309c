//! What a camera path does where it reaches a fluorescent layer: light arrives there at other
//! wavelengths than it leaves at, so the path goes on at the wavelength the layer absorbs
//! ([`crate::material::FluorescentLayer::relight`]), from the layer as from a white Lambertian
//! surface on the tracer at that wavelength, its throughput weighed. Both integrators go on
//! from such a vertex by path tracing ([`super::path::onward`]): the photons the maps hold there
//! carry no wavelength to read the layer's response at.

use super::direct::VisiblePoint;
use crate::bsdf::Bsdf;
use crate::color::Rgb;
use crate::transport::{Tracer, Vertex};
use rand::Rng;

/// What becomes of a camera path at a vertex.
pub enum Relighting {
    /// The vertex does not fluoresce: the path goes on as it is.
    Unchanged,
    /// A fluorescent layer that sends the path no light: it ends.
    Dark,
    /// A fluorescent layer: the path goes on from its vertex, made white and Lambertian, its
    /// throughput weighed, at the wavelength `nm` (vacuum, nm) the layer absorbs, on the tracer
    /// at that wavelength ([`Tracer::at_wavelength`]).
    Relit {
        /// That wavelength.
        nm: f64,
    },
}

/// Whether `vertex` lies on a fluorescent layer.
pub fn fluoresces(tracer: &Tracer, vertex: &Vertex) -> bool {
    tracer.scene.fluoresces()
        && vertex
            .surface()
            .is_some_and(|v| tracer.scene.fluorescent_layer(v.prim).is_some())
}

/// What becomes of the camera path at `vp` on `tracer` (numbers from `rng` at a fluorescent
/// layer, none elsewhere); where it is relit, `vp` becomes the point it goes on from.
pub fn relight(tracer: &Tracer, vp: &mut VisiblePoint, rng: &mut impl Rng) -> Relighting {
    let Vertex::Surface(v) = vp.vertex else {
        return Relighting::Unchanged;
    };
    if !tracer.scene.fluoresces() {
        return Relighting::Unchanged;
    }
    let Some(layer) = tracer.scene.fluorescent_layer(v.prim) else {
        return Relighting::Unchanged;
    };
    let Some(albedo) = v.bsdf.lambert_albedo() else {
        return Relighting::Unchanged;
    };
    // A path that still carries every wavelength (RGB) takes on one here, as where it meets
    // dispersion; one past dispersion keeps its own.
    let (nm, sensor) = match tracer.single_wavelength() {
        Some(nm) => (nm, Rgb::ONE),
        None => {
            let hero = layer.hero(tracer.scene.sources(), rng.gen());
            (hero.nm, hero.sensor_weight())
        }
    };
    let reflectance = crate::material::reflectance(albedo, Some(nm)).mean();
    let u = [rng.gen(), rng.gen()];
    let Some(relit) = layer.relight(nm, reflectance, tracer.scene.excitation(v.prim), u) else {
        return Relighting::Dark;
    };
    let mut white = v;
    white.bsdf = Bsdf::Lambert { albedo: Rgb::ONE };
    vp.vertex = Vertex::Surface(white);
    vp.throughput *= sensor * relit.weight;
    Relighting::Relit { nm: relit.nm }
}
