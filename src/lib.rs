//! grinlight: a photon-mapping renderer for gradient-index (GRIN) media.
//!
//! Light in a medium of varying index n follows the ray equation d/ds(n dx/ds) = ∇n. This crate
//! holds the media ([`media`]), the curved-ray engine ([`curve`]) and the scene description
//! ([`scene`]).
//!
//! ```
//! use grinlight::curve::{march, Bounds, ArcChain, MarchLimits, RayState, StepControl, StepperKind, Termination};
//! use grinlight::media::SechFiber;
//! use glam::DVec3;
//!
//! // A meridional ray in a sech fiber returns to its start height after one period 2π/g.
//! let fiber = SechFiber { n0: 1.5, g: 1.0, axis: grinlight::media::Axis { center: DVec3::ZERO, axis: DVec3::Z } };
//! let start = RayState::new(&fiber, DVec3::new(0.1, 0.0, 0.0), DVec3::Z).unwrap();
//! let limits = MarchLimits { length: 20.0, max_steps: 100_000, bounds: Bounds::Unbounded };
//! let out = march(&ArcChain, &fiber, StepControl::default_for(StepperKind::Arc), start, &limits, |_, _| std::ops::ControlFlow::Continue(()));
//! assert_eq!(out.reason, Termination::LengthReached);
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod accel;
pub mod bsdf;
pub(crate) mod bvh;
pub mod camera;
pub mod color;
pub mod commands;
pub mod compare;
pub mod curve;
pub(crate) mod environment;
pub mod equal_area;
pub mod error;
pub(crate) mod exact;
pub mod fiber;
pub mod film;
pub(crate) mod fluorescent_layer;
pub mod ids;
pub mod import;
pub mod input;
pub mod integrator;
pub mod interrupt;
pub mod lights;
pub(crate) mod material;
pub mod math;
pub mod media;
pub mod output;
pub mod photometry;
pub mod photon;
pub mod pixel_filter;
pub mod plot;
pub mod polarization;
pub mod receiver;
pub mod render;
pub(crate) mod report;
pub(crate) mod resources;
pub mod sample_stream;
pub mod sampling;
pub mod scene;
pub mod settings;
pub mod shapes;
pub mod shard;
pub mod spectrum;
pub mod texture;
pub mod transport;
pub mod volume;
