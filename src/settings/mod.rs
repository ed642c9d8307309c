//! How to render a scene, kept apart from what the scene is: plain data read from the scene
//! file's `[render]` and `[output]` tables, changed by the command line and Python in one
//! place ([`crate::commands::Overrides`]) and handed to the passes. The settings a user gives
//! are declared once, in [`keys`]; every key's unit and default is listed in
//! `docs/scene-format.md`.

pub mod keys;

pub use keys::{
    apply_all, unknown, Assignment, Given, Key, Table, Target, CAUSTIC_PHOTONS, DEFLECTION_TABLE,
    GATHER, HEIGHT, INTEGRATOR, KEYS, KNN, MAX_DEPTH, MAX_GATHER_OR_KNN, MAX_IMAGE_SIDE, MAX_STEPS,
    PASSES, PHOTONS, RADIUS, RECEIVER_PHOTONS, SEED, SPP, TARGET_ERROR, THREADS, TIME_BUDGET,
    WIDTH, WORLD_RADIUS,
};

use crate::curve::{StepControl, StepperKind};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// Everything a render, a measurement or a trace is asked to do with a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Seed of every random stream.
    pub seed: u64,
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// Camera samples per pixel per pass.
    pub spp: u32,
    /// Progressive passes: photon pass + camera pass each, the caustic radius shrinking
    /// (`u32::MAX` with a time budget: as many as fit).
    pub passes: u32,
    /// Stop starting new passes after this many seconds (None: run all `passes`).
    pub time_budget: Option<f64>,
    /// Stop starting new passes once the film's estimate of its relative RMSE
    /// ([`crate::film::FilmError`]) is at most this, after at least
    /// [`crate::render::MIN_PASSES_FOR_ERROR`] passes (None: run all `passes`).
    pub target_error: Option<f64>,
    /// How the camera's view is estimated.
    pub integrator: IntegratorKind,
    /// Where camera samples' random numbers come from.
    pub sampler: SamplerKind,
    /// Let the photon mapper's place be taken by a deflection table where one applies
    /// ([`crate::integrator::DeflectionTable`]); false traces every camera ray.
    pub deflection_table: bool,
    /// How rays travel.
    pub trace: TraceSettings,
    /// The photon maps and how they are read.
    pub photons: PhotonSettings,
    /// Photons traced for the receivers.
    pub receiver_photons: u64,
    /// What is written.
    pub output: OutputSettings,
}

/// How rays travel through the scene: the curved-ray engine and the path's length.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TraceSettings {
    /// Maximum number of surface interactions and scattering events in media along a path: a
    /// bound (camera paths and map photons are ended by Russian roulette past
    /// [`crate::transport::chain::ROULETTE_AFTER`] events; receiver photons only by it).
    pub max_depth: u32,
    /// Stepper in gradient media.
    pub stepper: StepperKind,
    /// Step control in gradient media.
    pub control: StepControl,
    /// Step limit (N_max) per curved march.
    pub max_steps: u64,
    /// Radius around the scene centre beyond which a ray in a gradient ambient medium counts
    /// as escaped (None: 10× the scene's extent including the camera).
    pub world_radius: Option<f64>,
    /// Whether specular chains carry polarization ([`crate::polarization::carried`]); a scene
    /// with a polarizer or retarder is rendered with it whatever this says.
    pub polarized: bool,
    /// Whether the camera's Stokes vector is written (layers S0–S3); implies `polarized`.
    pub stokes: bool,
}

/// The photon maps: how many photons per pass, and how the estimates read them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PhotonSettings {
    /// Photons per pass for the global map.
    pub global: u64,
    /// Photons per pass for the caustic map.
    pub caustic: u64,
    /// Final-gather rays per camera sample at its first diffuse hit (0: no secondary light).
    pub gather: u32,
    /// Photon gather radius (scene units): the caustic estimate's initial radius and the
    /// global estimate's largest (None: the k-nearest radius, at most 5 % of the scene's size).
    pub radius: Option<f64>,
    /// k of the k-nearest-photon radius.
    pub knn: u32,
}

/// Output settings (`[output]`).
#[derive(Clone, Debug, PartialEq)]
pub struct OutputSettings {
    /// The EXR path (None: `<scene stem>.exr` in the working directory).
    pub path: Option<PathBuf>,
    /// Whether to write the PNG preview next to it.
    pub png: bool,
    /// Exposure multiplier of the preview.
    pub exposure: f32,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            seed: 0,
            threads: 0,
            spp: 16,
            passes: 1,
            time_budget: None,
            target_error: None,
            integrator: IntegratorKind::PhotonMap,
            sampler: SamplerKind::default(),
            deflection_table: true,
            trace: TraceSettings::default(),
            photons: PhotonSettings::default(),
            receiver_photons: 1_000_000,
            output: OutputSettings::default(),
        }
    }
}

impl Default for TraceSettings {
    fn default() -> Self {
        Self {
            max_depth: 65_536,
            stepper: StepperKind::DEFAULT,
            control: StepControl::default_for(StepperKind::DEFAULT),
            max_steps: 1_000_000,
            world_radius: None,
            polarized: false,
            stokes: false,
        }
    }
}

impl Default for PhotonSettings {
    fn default() -> Self {
        Self {
            global: 100_000,
            caustic: 100_000,
            gather: 16,
            radius: None,
            knn: 16,
        }
    }
}

impl Default for OutputSettings {
    fn default() -> Self {
        Self {
            path: None,
            png: true,
            exposure: 1.0,
        }
    }
}

/// Where a camera sample's random numbers come from (`[render] sampler`; see
/// [`crate::render::sampler`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum SamplerKind {
    /// Independent numbers, with the film point and the first vertex's numbers stratified
    /// over the pixel's samples of a pass.
    Stratified,
    /// Owen-scrambled Sobol points, padded in sets of four dimensions, over a pixel's samples
    /// of a pass (each pass scrambled anew).
    #[default]
    Sobol,
}

impl SamplerKind {
    /// Every sampler, in the order its names are listed.
    pub const ALL: [SamplerKind; 2] = [SamplerKind::Sobol, SamplerKind::Stratified];

    /// Every sampler's name, in the order of [`SamplerKind::ALL`].
    pub const NAMES: [&'static str; 2] = [Self::ALL[0].name(), Self::ALL[1].name()];

    /// Its name in a scene file, on the command line and in Python.
    pub const fn name(self) -> &'static str {
        match self {
            SamplerKind::Stratified => "stratified",
            SamplerKind::Sobol => "sobol",
        }
    }
}

/// The integrators a scene may ask for (`[render] integrator`; see [`crate::integrator`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum IntegratorKind {
    /// The photon mapper (default).
    #[default]
    PhotonMap,
    /// The path tracer.
    Path,
}

impl IntegratorKind {
    /// Every integrator, in the order its names are listed.
    pub const ALL: [IntegratorKind; 2] = [IntegratorKind::PhotonMap, IntegratorKind::Path];

    /// Every integrator's name, in the order of [`IntegratorKind::ALL`].
    pub const NAMES: [&'static str; 2] = [Self::ALL[0].name(), Self::ALL[1].name()];

    /// Its name in a scene file, on the command line and in Python.
    pub const fn name(self) -> &'static str {
        match self {
            IntegratorKind::PhotonMap => "photon_map",
            IntegratorKind::Path => "path",
        }
    }
}
