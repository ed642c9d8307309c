//! The scene file's tables as serde structs. Unknown keys are errors; every key's units and
//! default are documented here and in `docs/scene-format.md`.

use serde::Deserialize;
use toml::Spanned;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// `[[medium]]` tables.
    #[serde(default)]
    pub medium: Vec<Spanned<MediumDesc>>,
}

fn origin() -> [f64; 3] {
    [0.0; 3]
}

fn z_axis() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

/// One `[[medium]]` table: `name`, `profile` and the profile's parameters. Vectors are
/// 3-element arrays; lengths are in scene units.
#[derive(Debug, Deserialize)]
#[serde(tag = "profile", rename_all = "snake_case", deny_unknown_fields)]
pub enum MediumDesc {
    /// n constant.
    Uniform {
        /// Name other tables and the CLI refer to.
        name: String,
        /// Index.
        n: f64,
    },
    /// n = n0 + gradient·(x − origin).
    Linear {
        /// Name.
        name: String,
        /// Index at `origin`.
        n0: f64,
        /// ∇n (1/length).
        gradient: [f64; 3],
        /// Default [0, 0, 0].
        #[serde(default = "origin")]
        origin: [f64; 3],
    },
    /// n = n0·exp(gradient·(x − origin)).
    Exponential {
        /// Name.
        name: String,
        /// Index at `origin`.
        n0: f64,
        /// ∇ln n (1/length).
        gradient: [f64; 3],
        /// Default [0, 0, 0].
        #[serde(default = "origin")]
        origin: [f64; 3],
    },
    /// n = n0 (1 − a r²/2), r from the axis line.
    Parabolic {
        /// Name.
        name: String,
        /// Index on the axis.
        n0: f64,
        /// 1/length².
        a: f64,
        /// A point on the axis, default [0, 0, 0].
        #[serde(default = "origin")]
        center: [f64; 3],
        /// Axis direction (any length), default [0, 0, 1].
        #[serde(default = "z_axis")]
        axis: [f64; 3],
    },
    /// n = n0 sech(g r), r from the axis line.
    Sech {
        /// Name.
        name: String,
        /// Index on the axis.
        n0: f64,
        /// 1/length.
        g: f64,
        /// A point on the axis, default [0, 0, 0].
        #[serde(default = "origin")]
        center: [f64; 3],
        /// Axis direction, default [0, 0, 1].
        #[serde(default = "z_axis")]
        axis: [f64; 3],
    },
    /// n = √(2 − (r/R)²) inside the sphere, 1 outside.
    Luneburg {
        /// Name.
        name: String,
        /// Default [0, 0, 0].
        #[serde(default = "origin")]
        center: [f64; 3],
        /// R (length).
        radius: f64,
    },
    /// n = n0 / (1 + (r/R)²).
    Fisheye {
        /// Name.
        name: String,
        /// Index at the centre.
        n0: f64,
        /// Default [0, 0, 0].
        #[serde(default = "origin")]
        center: [f64; 3],
        /// R (length).
        radius: f64,
    },
    /// n = ρ²/(ρ² − ρ + q²), ρ = |x − center|/rs; captures at the horizon.
    BlackHole {
        /// Name.
        name: String,
        /// Default [0, 0, 0].
        #[serde(default = "origin")]
        center: [f64; 3],
        /// Schwarzschild radius (length).
        rs: f64,
        /// Charge (dimensionless, ≥ 0), default 0.
        #[serde(default)]
        q: f64,
    },
    /// Trilinear n on a box.
    Grid {
        /// Name.
        name: String,
        /// [[min x, y, z], [max x, y, z]].
        bounds: [[f64; 3]; 2],
        /// Nodes per axis, each ≥ 2.
        dims: [usize; 3],
        /// n at the nodes, x fastest; or give `file`.
        #[serde(default)]
        values: Option<Vec<f64>>,
        /// A text file of whitespace-separated values (x fastest), relative to the scene file.
        #[serde(default)]
        file: Option<String>,
    },
}

impl MediumDesc {
    /// The medium's name.
    pub fn name(&self) -> &str {
        match self {
            MediumDesc::Uniform { name, .. }
            | MediumDesc::Linear { name, .. }
            | MediumDesc::Exponential { name, .. }
            | MediumDesc::Parabolic { name, .. }
            | MediumDesc::Sech { name, .. }
            | MediumDesc::Luneburg { name, .. }
            | MediumDesc::Fisheye { name, .. }
            | MediumDesc::BlackHole { name, .. }
            | MediumDesc::Grid { name, .. } => name,
        }
    }
}
