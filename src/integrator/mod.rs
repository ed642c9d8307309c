//! Integrators: ways of estimating the radiance a camera sample sees, pass by pass. The render
//! ([`crate::render`]) drives one over tiles and passes; each declares the film layers it
//! writes and estimates one camera ray at a time from what its pass prepared.
//!
//! - [`PhotonMapper`]: Zhdanov et al.'s (2020) luminance components — direct light, the caustic map, and
//!   secondary light by final gathering over the global map.
//! - [`PathTracer`]: unidirectional path tracing through the same curved transport, an
//!   independent reference for the photon mapper.
//! - [`DeflectionTable`]: for a camera before one spherically symmetric ambient medium and
//!   nothing else (a black hole), the Black Hole Simulator's (ebvalaim 2015) table of where each ray leaves; chosen by
//!   [`crate::render::render`] in place of the photon mapper whenever it applies.
//!
//! Passes are independent: pass `i` draws from streams keyed by `i` and its caustic radius
//! follows a schedule of `i` alone, so any set of passes can be rendered apart and their
//! films merged. To add an integrator: implement [`Integrator`], name it in
//! [`crate::settings::IntegratorKind`] and in [`crate::render::render`].

mod beam;
mod deflection;
pub mod direct;
mod dye;
pub mod footprint;
mod neighbourhood;
mod path;
mod photon_map;
mod relight;
mod single;

pub use deflection::{DeflectionTable, TableCheck};
pub use path::PathTracer;
pub use photon_map::{PhotonMapper, Plan};

use crate::camera::FilmPoint;
use crate::color::Rgb;
use crate::film::Layer;
use crate::polarization::Recorded;
use crate::report::Report;
use crate::sample_stream::SampleStream;
use crate::transport::chain::Choices;
use crate::transport::Stats;
use glam::DVec3;

/// One camera sample being estimated: its random stream, the statistics it adds to, and its
/// value for each of the integrator's layers `L` (zero on entry; in [`Layers::FILM`] order),
/// then, where the render measures the camera's Stokes vector, for each of
/// [`crate::film::STOKES_LAYERS`].
pub struct Sample<'a, L> {
    /// The sample's random stream.
    pub rng: &'a mut SampleStream,
    /// Transport statistics.
    pub stats: &'a mut Stats,
    /// Values per layer.
    pub values: &'a mut [Rgb],
    layers: std::marker::PhantomData<L>,
}

impl<'a, L: Layers> Sample<'a, L> {
    /// A sample writing into `values` (one per layer of `L`, then the Stokes layers where the
    /// render measures them).
    pub fn new(rng: &'a mut SampleStream, stats: &'a mut Stats, values: &'a mut [Rgb]) -> Self {
        Self {
            rng,
            stats,
            values,
            layers: std::marker::PhantomData,
        }
    }

    /// Adds `value` to the auxiliary layer `layer` (a denoiser's albedo or normal).
    pub fn add(&mut self, layer: L, value: Rgb) {
        debug_assert!(L::FILM[layer.index()].kind != crate::film::LayerKind::Radiance);
        self.values[layer.index()] += value;
    }

    /// Adds the light `value` as the camera records it to the radiance layer `layer` (its S0),
    /// and to the Stokes layers where the render measures them.
    pub fn record(&mut self, layer: L, value: Recorded) {
        self.values[layer.index()] += value.s0;
        if let Some([s0, rest @ ..]) = self.values.get_mut(L::FILM.len()..) {
            *s0 += value.s0;
            if let Some(stokes) = value.stokes {
                for (s, v) in rest.iter_mut().zip(stokes) {
                    *s += v;
                }
            }
        }
    }
}

/// An integrator's output layers: an enum whose variants are its film's layers, declared by
/// `layers!` so that a variant's place, its name and its kind cannot drift
/// apart.
pub trait Layers: Copy + 'static {
    /// The film's layers, in the variants' order.
    const FILM: &'static [Layer];
    /// Its place in [`Layers::FILM`].
    fn index(self) -> usize;
}

/// Declares an integrator's layers: `layers!(Out { Direct: radiance "direct", Albedo: aux
/// "albedo" })` is an enum `Out` with one variant per layer and its [`Layers`], the film's
/// layers in the variants' order.
macro_rules! layers {
    ($(#[$meta:meta])* $name:ident { $($(#[$vmeta:meta])* $variant:ident: $kind:ident $label:literal),+ $(,)? }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum $name {
            $($(#[$vmeta])* $variant),+
        }

        impl crate::integrator::Layers for $name {
            const FILM: &'static [crate::film::Layer] =
                &[$(crate::film::Layer::$kind($label)),+];
            fn index(self) -> usize {
                self as usize
            }
        }
    };
}
pub(crate) use layers;

/// A camera ray: origin and unit direction, the numbers its path's first choices between
/// reflection and refraction take, and the film point it was drawn through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRay {
    /// Origin (on the camera's lens).
    pub origin: DVec3,
    /// Unit direction.
    pub direction: DVec3,
    /// Each stratified over the pixel's samples ([`crate::sampling::Strata`]).
    pub choices: Choices,
    /// The numbers its first scattering vertex's samples take, stratified over the pixel's
    /// samples where given (the path tracer reads them).
    pub first: FirstVertex,
    /// Where on the film and the lens it was drawn (its neighbours' rays are drawn beside it:
    /// [`footprint`]).
    pub film: FilmPoint,
}

/// The numbers a camera sample's first scattering vertex takes in place of its stream's,
/// stratified over the pixel's samples ([`crate::sampling::Strata2`], [`crate::sampling::Strata`]):
/// the direct estimate's light sample and the BSDF or phase sample of the path's way on —
/// the dimensions whose noise the first vertex's direct light shows.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FirstVertex {
    /// The light sample's.
    pub light: crate::transport::lighting::LightNumbers,
    /// The BSDF or phase sample's.
    pub bsdf: crate::transport::BsdfNumbers,
}

/// A way of estimating what the camera sees.
pub trait Integrator: Sync {
    /// What a pass shares among its camera samples (e.g. its photon maps).
    type Pass: Send + Sync;
    /// What a pass keeps per pixel across that pixel's samples.
    type Pixel: Default;
    /// The layers it writes; `beauty` is developed as the sum of the radiance layers.
    type Layer: Layers;
    /// The film's layers.
    fn layers(&self) -> &'static [Layer] {
        <Self::Layer as Layers>::FILM
    }
    /// Prepares pass `index` (global: passes are independent), adding its work to `report`;
    /// None if `stop` answered true before the pass was ready.
    fn begin_pass(
        &self,
        index: u32,
        report: &mut Report,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Self::Pass>;
    /// Estimates one camera ray of `pass` at a pixel, writing its values into `sample`.
    fn sample(
        &self,
        pass: &Self::Pass,
        pixel: &mut Self::Pixel,
        ray: CameraRay,
        sample: &mut Sample<Self::Layer>,
    );
}
