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
    /// Stop starting new passes once the film's estimate of its relative RMSE
    /// ([`crate::film::FilmError`]) is at most this, after at least
    /// [`crate::render::MIN_PASSES_FOR_ERROR`] passes (None: run all `passes`).
    pub target_error: Option<f64>,
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
}

/// The range an integer setting may take: one definition per key, read by the scene file
/// (`[render]` and `[camera]`), by the command line's overrides (`--key`, `_` written `-`) and
/// by the partial header's settings, so the three cannot disagree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count {
    /// The scene file's key.
    pub key: &'static str,
    /// The smallest value allowed.
    pub min: u64,
    /// The largest value allowed.
    pub max: u64,
}

impl Count {
    /// `value`, or why it is refused (outside `min..=max`).
    pub fn check(&self, value: u64) -> Result<u64, String> {
        if (self.min..=self.max).contains(&value) {
            Ok(value)
        } else if value < self.min {
            Err(format!("expected an integer ≥ {}, got {value}", self.min))
        } else {
            Err(format!("must be at most {}, got {value}", self.max))
        }
    }

    /// The range in words, as `docs/scene-format.md` gives it: `1…65536`, or `≥ 1` where the
    /// type's own limit is the only one.
    pub fn range(&self) -> String {
        if self.max == u64::MAX {
            format!("≥ {}", self.min)
        } else {
            format!("{}…{}", self.min, self.max)
        }
    }

    /// The command-line flag of the key (`--receiver-photons` for `receiver_photons`).
    pub fn flag(&self) -> String {
        format!("--{}", self.key.replace('_', "-"))
    }
}

/// The most final-gather rays a camera sample may ask for, and the largest k of the
/// k-nearest radius.
pub const MAX_GATHER_OR_KNN: u64 = 1 << 16;

/// The largest image side in pixels.
pub const MAX_IMAGE_SIDE: u64 = 1 << 16;

/// Camera samples per pixel per pass.
pub const SPP: Count = Count {
    key: "spp",
    min: 1,
    max: u32::MAX as u64,
};
/// Progressive passes.
pub const PASSES: Count = Count {
    key: "passes",
    min: 1,
    max: u32::MAX as u64,
};
/// Surface interactions and scattering events in media along a path.
pub const MAX_DEPTH: Count = Count {
    key: "max_depth",
    min: 1,
    max: u32::MAX as u64,
};
/// Steps per curved march.
pub const MAX_STEPS: Count = Count {
    key: "max_steps",
    min: 1,
    max: u64::MAX,
};
/// Final-gather rays per camera sample (0: no secondary light).
pub const GATHER: Count = Count {
    key: "gather",
    min: 0,
    max: MAX_GATHER_OR_KNN,
};
/// k of the k-nearest-photon radius.
pub const KNN: Count = Count {
    key: "knn",
    min: 1,
    max: MAX_GATHER_OR_KNN,
};
/// Global-map photons per pass.
pub const PHOTONS: Count = Count {
    key: "photons",
    min: 0,
    max: u64::MAX,
};
/// Caustic-map photons per pass.
pub const CAUSTIC_PHOTONS: Count = Count {
    key: "caustic_photons",
    min: 0,
    max: u64::MAX,
};
/// Photons traced for the receivers.
pub const RECEIVER_PHOTONS: Count = Count {
    key: "receiver_photons",
    min: 1,
    max: u64::MAX,
};
/// Every integer setting, for the documentation's check.
pub const COUNTS: [Count; 11] = [
    SPP,
    PASSES,
    MAX_DEPTH,
    MAX_STEPS,
    GATHER,
    KNN,
    PHOTONS,
    CAUSTIC_PHOTONS,
    RECEIVER_PHOTONS,
    WIDTH,
    HEIGHT,
];

/// Image width in pixels.
pub const WIDTH: Count = Count {
    key: "width",
    min: 1,
    max: MAX_IMAGE_SIDE,
};
/// Image height in pixels.
pub const HEIGHT: Count = Count {
    key: "height",
    min: 1,
    max: MAX_IMAGE_SIDE,
};

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
            target_error: None,
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
            max_depth: 65_536,
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

impl IntegratorKind {
    /// Every integrator, in the order its names are listed.
    pub const ALL: [IntegratorKind; 2] = [IntegratorKind::PhotonMap, IntegratorKind::Path];

    /// Its name in a scene file, on the command line and in Python.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::PhotonMap => "photon_map",
            IntegratorKind::Path => "path",
        }
    }

    /// Every integrator's name, quoted, as errors list them: `'photon_map' or 'path'`.
    pub fn names() -> String {
        let quoted: Vec<String> = Self::ALL
            .iter()
            .map(|k| format!("'{}'", k.name()))
            .collect();
        quoted.join(" or ")
    }
}

impl std::str::FromStr for IntegratorKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| format!("unknown integrator '{s}' (expected {})", Self::names()))
    }
}
