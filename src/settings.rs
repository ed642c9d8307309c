//! How to render a scene, kept apart from what the scene is: plain data read from the scene
//! file's `[render]` and `[output]` tables, changed by the command line in one place
//! ([`crate::commands::Overrides`]) and handed to the passes. Every key's unit and default is
//! listed in `docs/scene-format.md`.

use crate::curve::{StepControl, StepperKind};
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
    /// How the camera's view is estimated.
    pub integrator: IntegratorKind,
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceSettings {
    /// Maximum number of surface interactions along a path.
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
}

/// The most final-gather rays a camera sample may ask for, and the largest k of the
/// k-nearest radius: the one limit the scene file and the command line both enforce.
pub const MAX_GATHER_OR_KNN: u32 = 1 << 16;

/// Why a `gather` or `knn` of `value` is refused, if it is: above [`MAX_GATHER_OR_KNN`].
pub fn beyond_gather_or_knn_limit(value: u64) -> Option<String> {
    (value > MAX_GATHER_OR_KNN as u64)
        .then(|| format!("must be at most {MAX_GATHER_OR_KNN}, got {value}"))
}

/// The photon maps: how many photons per pass, and how the estimates read them.
#[derive(Clone, Copy, Debug, PartialEq)]
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
            integrator: IntegratorKind::PhotonMap,
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
            max_depth: 64,
            stepper: StepperKind::DEFAULT,
            control: StepControl::default_for(StepperKind::DEFAULT),
            max_steps: 1_000_000,
            world_radius: None,
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

/// The integrators a scene may ask for (`[render] integrator`; see [`crate::integrator`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IntegratorKind {
    /// The photon mapper (default).
    #[default]
    PhotonMap,
    /// The path tracer.
    Path,
}

impl std::str::FromStr for IntegratorKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "photon_map" => Ok(IntegratorKind::PhotonMap),
            "path" => Ok(IntegratorKind::Path),
            other => Err(format!("unknown integrator '{other}' (photon_map, path)")),
        }
    }
}
