//! The render settings a user may give, declared once: each [`Key`] is its name (the scene
//! file's key, Python's keyword, the command line's flag with `_` written `-`), the values it
//! takes, its default in words, what it means, and where it goes in [`Settings`] or the
//! camera. The scene file's reader, the command line's options (built from [`KEYS`]), the
//! Python keywords and the scene-format reference all read this table, so a value is refused
//! with the same words wherever it is given: only the place named before them differs
//! (`file:line:col: [render]: key `spp``, `--spp`, `spp`).

use super::{IntegratorKind, SamplerKind, Settings};
use crate::camera::Camera;
use crate::error::{number, MAX_MAGNITUDE};

/// What a setting is applied to: the render's settings and, for the image's size, the camera
/// (None: the scene has none, and the size is not used).
pub struct Target<'a> {
    /// The render's settings.
    pub settings: &'a mut Settings,
    /// The scene's camera.
    pub camera: Option<&'a mut Camera>,
}

/// The values a setting takes, and where a value goes.
#[derive(Clone, Copy, Debug)]
enum Kind {
    /// An integer in `min..=max`.
    Count {
        min: u64,
        max: u64,
        set: fn(&mut Target, u64),
    },
    /// A finite number in (0, [`MAX_MAGNITUDE`]].
    Positive { set: fn(&mut Target, f64) },
    /// One of `names`; `set` is given its position.
    Choice {
        names: &'static [&'static str],
        set: fn(&mut Target, usize),
    },
    /// true or false.
    Flag { set: fn(&mut Target, bool) },
}

/// Which table of the scene file holds a setting.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Table {
    /// `[render]`.
    Render,
    /// `[camera]` (the image's size).
    Camera,
}

/// One render setting, as every front end names it.
#[derive(Clone, Copy, Debug)]
pub struct Key {
    /// The scene file's key and Python's keyword; the flag is `--` and this with `-` for `_`.
    pub name: &'static str,
    /// The table of the scene file that holds it.
    pub table: Table,
    /// Its default, in words.
    pub default: &'static str,
    /// What it means, in one line (the command line's help).
    pub doc: &'static str,
    kind: Kind,
}

/// A value as a front end was given it, before it is read as a setting: what a TOML value,
/// a command-line word or a Python object is.
#[derive(Clone, Debug, PartialEq)]
pub enum Given {
    /// A whole number.
    Integer(i128),
    /// A number with a fraction or an exponent.
    Number(f64),
    /// A word.
    Text(String),
    /// true or false.
    Bool(bool),
    /// Anything else, described (`an array`, `a list`).
    Other(String),
}

impl Given {
    /// A command-line word as the value it spells: an integer, else a number, else `true` or
    /// `false`, else the word.
    pub fn from_text(text: &str) -> Self {
        if let Ok(i) = text.parse::<i128>() {
            Given::Integer(i)
        } else if let Ok(x) = text.parse::<f64>() {
            Given::Number(x)
        } else {
            match text {
                "true" => Given::Bool(true),
                "false" => Given::Bool(false),
                _ => Given::Text(text.to_string()),
            }
        }
    }

    /// A scene file's value.
    pub fn from_toml(value: &toml::Value) -> Self {
        match value {
            toml::Value::Integer(i) => Given::Integer(i128::from(*i)),
            toml::Value::Float(x) => Given::Number(*x),
            toml::Value::String(s) => Given::Text(s.clone()),
            toml::Value::Boolean(b) => Given::Bool(*b),
            toml::Value::Datetime(_) | toml::Value::Array(_) | toml::Value::Table(_) => {
                Given::Other(format!("a {}", value.type_str()))
            }
        }
    }
}

impl From<u64> for Given {
    fn from(n: u64) -> Self {
        Given::Integer(i128::from(n))
    }
}

impl From<u32> for Given {
    fn from(n: u32) -> Self {
        Given::Integer(i128::from(n))
    }
}

impl From<i32> for Given {
    fn from(n: i32) -> Self {
        Given::Integer(i128::from(n))
    }
}

impl From<f64> for Given {
    fn from(x: f64) -> Self {
        Given::Number(x)
    }
}

impl From<bool> for Given {
    fn from(b: bool) -> Self {
        Given::Bool(b)
    }
}

impl From<&str> for Given {
    fn from(s: &str) -> Self {
        Given::Text(s.to_string())
    }
}

impl std::fmt::Display for Given {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Given::Integer(i) => write!(f, "{i}"),
            // A whole number given as one with a fraction reads as such (`4.0`, not `4`).
            Given::Number(x) if x.fract() == 0.0 && x.abs() < 1e6 => write!(f, "{x:?}"),
            Given::Number(x) => write!(f, "{}", number(*x)),
            Given::Text(s) => write!(f, "\"{s}\""),
            Given::Bool(b) => write!(f, "{b}"),
            Given::Other(what) => write!(f, "{what}"),
        }
    }
}

/// A setting read and ready to apply: the key and its value, typed as the key takes it.
#[derive(Clone, Copy, Debug)]
pub struct Assignment {
    /// The setting.
    pub key: &'static Key,
    value: Typed,
}

/// A value with the setter of its type.
#[derive(Clone, Copy, Debug)]
enum Typed {
    Count(fn(&mut Target, u64), u64),
    Positive(fn(&mut Target, f64), f64),
    Choice(fn(&mut Target, usize), usize),
    Flag(fn(&mut Target, bool), bool),
}

impl Key {
    /// `given` read as this setting's value, or why it is refused (the same words for every
    /// front end).
    pub fn read(&'static self, given: &Given) -> Result<Assignment, String> {
        let value = match self.kind {
            Kind::Count { min, max, set } => match *given {
                Given::Integer(i) if i < i128::from(min) => {
                    return Err(format!("expected an integer ≥ {min}, got {i}"))
                }
                Given::Integer(i) if i > i128::from(max) => {
                    return Err(format!("must be at most {max}, got {i}"))
                }
                Given::Integer(i) => Typed::Count(set, i as u64),
                _ => return Err(format!("expected an integer ≥ {min}, got {given}")),
            },
            Kind::Positive { set } => {
                let x = match *given {
                    Given::Integer(i) => i as f64,
                    Given::Number(x) => x,
                    _ => return Err(format!("expected a number, got {given}")),
                };
                if !(x.is_finite() && x > 0.0 && x <= MAX_MAGNITUDE) {
                    return Err(format!(
                        "must be a number in (0, {MAX_MAGNITUDE:e}], got {}",
                        number(x)
                    ));
                }
                Typed::Positive(set, x)
            }
            Kind::Choice { names, set } => match given {
                Given::Text(name) if names.contains(&name.as_str()) => {
                    let at = names.iter().position(|n| n == name).unwrap_or(0);
                    Typed::Choice(set, at)
                }
                _ => {
                    let quoted: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
                    return Err(format!("expected {}, got {given}", quoted.join(" or ")));
                }
            },
            Kind::Flag { set } => match *given {
                Given::Bool(b) => Typed::Flag(set, b),
                _ => return Err(format!("expected true or false, got {given}")),
            },
        };
        Ok(Assignment { key: self, value })
    }

    /// `n` as this count's value, or why it is refused.
    pub fn count(&'static self, n: u64) -> Result<u64, String> {
        let a = self.read(&Given::Integer(i128::from(n)))?;
        a.count()
            .ok_or_else(|| format!("{} is not a count", self.name))
    }

    /// The command-line flag (`--receiver-photons` for `receiver_photons`).
    pub fn flag(&self) -> String {
        format!("--{}", self.name.replace('_', "-"))
    }

    /// The values it takes, in words, as `docs/scene-format.md` gives them: `1…65536`, `≥ 1`
    /// where the type's own limit is the only one, `> 0`, the names of a choice, `true` or
    /// `false`.
    pub fn range(&self) -> String {
        match self.kind {
            Kind::Count { min, max, .. } if max == u64::MAX => format!("≥ {min}"),
            Kind::Count { min, max, .. } => format!("{min}…{max}"),
            Kind::Positive { .. } => "> 0".into(),
            Kind::Choice { names, .. } => names.join(", "),
            Kind::Flag { .. } => "true, false".into(),
        }
    }

    /// The value a command-line flag takes, for its help (`N`, `X`, `NAME`, `BOOL`).
    pub fn value_name(&self) -> &'static str {
        match self.kind {
            Kind::Count { .. } => "N",
            Kind::Positive { .. } => "X",
            Kind::Choice { .. } => "NAME",
            Kind::Flag { .. } => "BOOL",
        }
    }

    /// The setting called `name`.
    pub fn named(name: &str) -> Option<&'static Key> {
        KEYS.iter().copied().find(|k| k.name == name)
    }
}

impl Assignment {
    /// The value of a count (None: the setting is not one).
    pub fn count(&self) -> Option<u64> {
        match self.value {
            Typed::Count(_, n) => Some(n),
            Typed::Positive(..) | Typed::Choice(..) | Typed::Flag(..) => None,
        }
    }

    /// Sets the value.
    pub fn apply(&self, target: &mut Target) {
        match self.value {
            Typed::Count(set, n) => set(target, n),
            Typed::Positive(set, x) => set(target, x),
            Typed::Choice(set, i) => set(target, i),
            Typed::Flag(set, b) => set(target, b),
        }
    }
}

/// Why `name` is refused as a setting's name: the scene file's words for a key its table
/// does not have (`unknown key `sppp` (expected one of: …)`), listing the table's keys and
/// any `more` a front end also takes.
pub fn unknown(name: &str, more: &[&str]) -> String {
    let names: Vec<&str> = KEYS
        .iter()
        .map(|k| k.name)
        .chain(more.iter().copied())
        .collect();
    format!(
        "unknown key `{name}` (expected one of: {})",
        names.join(", ")
    )
}

/// Applies `assignments` in order. A time budget or a target error given without a count of
/// passes renders as many passes as it takes (the scene file's `[render]` and the command line
/// alike).
pub fn apply_all(assignments: &[Assignment], target: &mut Target) {
    for a in assignments {
        a.apply(target);
    }
    let given = |key: &Key| assignments.iter().any(|a| a.key.name == key.name);
    if (given(&TIME_BUDGET) || given(&TARGET_ERROR)) && !given(&PASSES) {
        target.settings.passes = u32::MAX;
    }
}

/// A count of type u32 taken from a u64 in its range (the range keeps it within u32).
fn u32_of(n: u64) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// The most final-gather rays a camera sample may ask for, and the largest k of the
/// k-nearest radius.
pub const MAX_GATHER_OR_KNN: u64 = 1 << 16;

/// The largest image side in pixels.
pub const MAX_IMAGE_SIDE: u64 = 1 << 16;

/// How the view is estimated.
pub const INTEGRATOR: Key = Key {
    name: "integrator",
    table: Table::Render,
    default: "photon_map",
    doc: "How the view is estimated: photon_map (direct, caustic map, final gather over the global map) or path (unidirectional path tracing, a reference)",
    kind: Kind::Choice {
        names: &IntegratorKind::NAMES,
        set: |t, i| t.settings.integrator = IntegratorKind::ALL[i],
    },
};
/// Where camera samples' numbers come from.
pub const SAMPLER: Key = Key {
    name: "sampler",
    table: Table::Render,
    default: "sobol",
    doc: "Where camera samples' random numbers come from: sobol (Owen-scrambled Sobol points: every dimension stratified over a pixel's samples of a pass) or stratified (independent numbers; the film point and the first vertex's numbers stratified over a pass's samples)",
    kind: Kind::Choice {
        names: &SamplerKind::NAMES,
        set: |t, i| t.settings.sampler = SamplerKind::ALL[i],
    },
};
/// Whether a deflection table may stand in for traced camera rays.
pub const DEFLECTION_TABLE: Key = Key {
    name: "deflection_table",
    table: Table::Render,
    default: "true",
    doc: "Let a deflection table stand in for traced camera rays where one applies (a camera before one spherically symmetric ambient medium and nothing else, e.g. a black hole); false traces every ray",
    kind: Kind::Flag {
        set: |t, b| t.settings.deflection_table = b,
    },
};
/// Camera samples per pixel per pass.
pub const SPP: Key = Key {
    name: "spp",
    table: Table::Render,
    default: "16",
    doc: "Camera samples per pixel per pass",
    kind: Kind::Count {
        min: 1,
        max: u32::MAX as u64,
        set: |t, n| t.settings.spp = u32_of(n),
    },
};
/// Seed of every random stream.
pub const SEED: Key = Key {
    name: "seed",
    table: Table::Render,
    default: "0",
    doc: "Seed of every random stream",
    kind: Kind::Count {
        min: 0,
        max: u64::MAX,
        set: |t, n| t.settings.seed = n,
    },
};
/// Surface interactions and scattering events in media along a path.
pub const MAX_DEPTH: Key = Key {
    name: "max_depth",
    table: Table::Render,
    default: "65536",
    doc: "Most surface interactions and scattering events in media along a path",
    kind: Kind::Count {
        min: 1,
        max: u32::MAX as u64,
        set: |t, n| t.settings.trace.max_depth = u32_of(n),
    },
};
/// Worker threads.
pub const THREADS: Key = Key {
    name: "threads",
    table: Table::Render,
    default: "0",
    doc: "Worker threads (0 = all cores; at most 16 per core)",
    kind: Kind::Count {
        min: 0,
        max: u32::MAX as u64,
        set: |t, n| t.settings.threads = usize::try_from(n).unwrap_or(usize::MAX),
    },
};
/// Steps per curved march.
pub const MAX_STEPS: Key = Key {
    name: "max_steps",
    table: Table::Render,
    default: "1000000",
    doc: "Step attempts per curved march (N_max)",
    kind: Kind::Count {
        min: 1,
        max: u64::MAX,
        set: |t, n| t.settings.trace.max_steps = n,
    },
};
/// Whether specular chains carry polarization.
pub const POLARIZED: Key = Key {
    name: "polarized",
    table: Table::Render,
    default: "false",
    doc: "Carry polarization (Stokes vectors through Fresnel reflection and refraction, smooth and rough conductors and dielectrics, plastics, polarizer and retarder sheets, crystal faces, Rayleigh scattering, and the geometric phase along curved stretches; other scattering vertices depolarize); a polarizer or retarder in the scene turns it on",
    kind: Kind::Flag {
        set: |t, b| t.settings.trace.polarized = b,
    },
};
/// Whether the camera's Stokes vector is written.
pub const STOKES: Key = Key {
    name: "stokes",
    table: Table::Render,
    default: "false",
    doc: "Write the Stokes vector of the light the camera sees as EXR layers S0–S3, in the frame of each pixel's ray (first axis d × up, d the ray, up the camera's; S0 is the beauty); implies polarized",
    kind: Kind::Flag {
        set: |t, b| t.settings.trace.stokes = b,
    },
};
/// Where a ray in a gradient ambient medium has escaped.
pub const WORLD_RADIUS: Key = Key {
    name: "world_radius",
    table: Table::Render,
    default: "10 × the scene's size",
    doc: "Radius around the scene's centre beyond which a ray in a gradient ambient medium has escaped (scene units)",
    kind: Kind::Positive {
        set: |t, x| t.settings.trace.world_radius = Some(x),
    },
};
/// Global-map photons per pass.
pub const PHOTONS: Key = Key {
    name: "photons",
    table: Table::Render,
    default: "100000",
    doc: "Global-map photons per pass",
    kind: Kind::Count {
        min: 0,
        max: u64::MAX,
        set: |t, n| t.settings.photons.global = n,
    },
};
/// Caustic-map photons per pass.
pub const CAUSTIC_PHOTONS: Key = Key {
    name: "caustic_photons",
    table: Table::Render,
    default: "100000",
    doc: "Caustic-map photons per pass",
    kind: Kind::Count {
        min: 0,
        max: u64::MAX,
        set: |t, n| t.settings.photons.caustic = n,
    },
};
/// Final-gather rays per camera sample (0: no secondary light).
pub const GATHER: Key = Key {
    name: "gather",
    table: Table::Render,
    default: "16",
    doc: "Final-gather rays per camera sample (0: no secondary light)",
    kind: Kind::Count {
        min: 0,
        max: MAX_GATHER_OR_KNN,
        set: |t, n| t.settings.photons.gather = u32_of(n),
    },
};
/// k of the k-nearest-photon radius.
pub const KNN: Key = Key {
    name: "knn",
    table: Table::Render,
    default: "16",
    doc: "k of the k-nearest-photon radius",
    kind: Kind::Count {
        min: 1,
        max: MAX_GATHER_OR_KNN,
        set: |t, n| t.settings.photons.knn = u32_of(n),
    },
};
/// The photon gather radius.
pub const RADIUS: Key = Key {
    name: "radius",
    table: Table::Render,
    default: "the k-nearest radius, at most 5 % of the scene's size",
    doc: "Photon gather radius (scene units): initial caustic radius, largest global radius",
    kind: Kind::Positive {
        set: |t, x| t.settings.photons.radius = Some(x),
    },
};
/// Progressive passes.
pub const PASSES: Key = Key {
    name: "passes",
    table: Table::Render,
    default: "1",
    doc: "Progressive passes (photon pass + camera pass; the caustic radius shrinks)",
    kind: Kind::Count {
        min: 1,
        max: u32::MAX as u64,
        set: |t, n| t.settings.passes = u32_of(n),
    },
};
/// Seconds after which no new pass starts.
pub const TIME_BUDGET: Key = Key {
    name: "time_budget",
    table: Table::Render,
    default: "none",
    doc: "Start no new pass after this many seconds (with no passes: as many as fit)",
    kind: Kind::Positive {
        set: |t, x| t.settings.time_budget = Some(x),
    },
};
/// The relative RMSE at which no new pass starts.
pub const TARGET_ERROR: Key = Key {
    name: "target_error",
    table: Table::Render,
    default: "none",
    doc: "Start no new pass once the image's estimated relative RMSE (from the spread of its passes) is at most this, after at least 4 passes (with no passes: as many as it takes)",
    kind: Kind::Positive {
        set: |t, x| t.settings.target_error = Some(x),
    },
};
/// Photons traced for the receivers.
pub const RECEIVER_PHOTONS: Key = Key {
    name: "receiver_photons",
    table: Table::Render,
    default: "1000000",
    doc: "Photons traced for the scene's receivers",
    kind: Kind::Count {
        min: 1,
        max: u64::MAX,
        set: |t, n| t.settings.receiver_photons = n,
    },
};
/// Image width in pixels.
pub const WIDTH: Key = Key {
    name: "width",
    table: Table::Camera,
    default: "640",
    doc: "Image width in pixels (the vertical field of view is kept)",
    kind: Kind::Count {
        min: 1,
        max: MAX_IMAGE_SIDE,
        set: |t, n| {
            if let Some(c) = t.camera.as_deref_mut() {
                c.width = u32_of(n);
            }
        },
    },
};
/// Image height in pixels.
pub const HEIGHT: Key = Key {
    name: "height",
    table: Table::Camera,
    default: "480",
    doc: "Image height in pixels",
    kind: Kind::Count {
        min: 1,
        max: MAX_IMAGE_SIDE,
        set: |t, n| {
            if let Some(c) = t.camera.as_deref_mut() {
                c.height = u32_of(n);
            }
        },
    },
};

/// Every setting of the table, in the order help and documentation list them.
pub const KEYS: [&Key; 22] = [
    &INTEGRATOR,
    &SAMPLER,
    &DEFLECTION_TABLE,
    &SPP,
    &SEED,
    &MAX_DEPTH,
    &THREADS,
    &MAX_STEPS,
    &WORLD_RADIUS,
    &POLARIZED,
    &STOKES,
    &PHOTONS,
    &CAUSTIC_PHOTONS,
    &GATHER,
    &KNN,
    &RADIUS,
    &PASSES,
    &TIME_BUDGET,
    &TARGET_ERROR,
    &RECEIVER_PHOTONS,
    &WIDTH,
    &HEIGHT,
];
