//! The values of a grinlight scene table as converters write them (docs/scene-format.md).

use crate::pixel_filter::{PixelFilter, Reach};
use glam::{DMat4, DVec3};
use toml::{Table, Value as Toml};

/// A name no table of `tables` has: `wanted` itself where it is free, else `wanted-1`,
/// `wanted-2`, ….
pub fn free_name(tables: &[Table], wanted: &str) -> String {
    let taken = |n: &str| {
        tables
            .iter()
            .any(|t| t.get("name").and_then(Toml::as_str) == Some(n))
    };
    std::iter::once(wanted.to_string())
        .chain((1..).map(|i| format!("{wanted}-{i}")))
        .find(|n| !taken(n))
        .expect("a free name")
}

/// A vector as a TOML array.
pub fn vec3(v: DVec3) -> Toml {
    Toml::Array(v.to_array().iter().map(|&x| Toml::Float(x)).collect())
}

/// A medium's `absorption` σa per channel: one number where the channels agree to 1e-9 of the
/// largest (a grey σa computed from a colour, σt·(1 − albedo), rounds apart by channel), else
/// RGB.
pub fn absorption(sigma_a: DVec3) -> Toml {
    match sigma_a.max_element() - sigma_a.min_element() > 1e-9 * sigma_a.max_element() {
        true => vec3(sigma_a),
        false => Toml::Float(sigma_a.x),
    }
}

/// A table from key–value pairs.
pub fn table<const N: usize>(pairs: [(&str, Toml); N]) -> Table {
    pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}

/// The arrays of tables a converter builds: `[[medium]]`, `[[material]]`, `[[shape]]` and
/// `[[light]]`.
#[derive(Debug, Default)]
pub struct Lists {
    /// `[[medium]]` tables.
    pub media: Vec<Table>,
    /// `[[material]]` tables.
    pub materials: Vec<Table>,
    /// `[[shape]]` tables.
    pub shapes: Vec<Table>,
    /// `[[light]]` tables.
    pub lights: Vec<Table>,
}

impl Lists {
    /// Each array into `table` under its key, when it is not empty.
    pub fn insert_into(self, table: &mut Table) {
        for (key, list) in [
            ("medium", self.media),
            ("material", self.materials),
            ("shape", self.shapes),
            ("light", self.lights),
        ] {
            if !list.is_empty() {
                table.insert(
                    key.into(),
                    Toml::Array(list.into_iter().map(Toml::Table).collect()),
                );
            }
        }
    }
}

/// An affine map's 3 rows [a b c t] as the 12 numbers of a mesh's `matrix`.
pub fn affine_rows(m: &DMat4) -> Toml {
    let rows = m.transpose().to_cols_array();
    Toml::Array(rows[..12].iter().map(|&x| Toml::Float(x)).collect())
}

/// A string as a TOML value.
pub fn string(s: &str) -> Toml {
    Toml::String(s.to_string())
}

/// The surface of an area light a converter found: a parallelogram (corners v0..v3, emitting
/// on the side of (v1 − v0) × (v3 − v0)), a disk emitting on its normal's side, a sphere
/// emitting outward, or a triangle mesh.
#[derive(Clone, Debug)]
pub enum AreaEmitter {
    /// A parallelogram's corners v0..v3.
    Quad([DVec3; 4]),
    /// A disk.
    Disk {
        /// Its centre.
        center: DVec3,
        /// The unit normal of its emitting side.
        normal: DVec3,
        /// Its radius.
        radius: f64,
    },
    /// A sphere.
    Sphere {
        /// Its centre.
        center: DVec3,
        /// Its radius.
        radius: f64,
    },
    /// A triangle mesh.
    Mesh {
        /// Its `[[light]]` keys but the radiance: type `mesh`, where its triangles come from,
        /// how they are placed, and `flip` where they emit against their winding.
        keys: Table,
        /// Its area in the world (length²).
        area: f64,
    },
}

impl AreaEmitter {
    /// Its area (length²).
    pub fn area(&self) -> f64 {
        match *self {
            AreaEmitter::Quad(v) => (v[1] - v[0]).cross(v[3] - v[0]).length(),
            AreaEmitter::Disk { radius, .. } => std::f64::consts::PI * radius * radius,
            AreaEmitter::Sphere { radius, .. } => 4.0 * std::f64::consts::PI * radius * radius,
            AreaEmitter::Mesh { area, .. } => area,
        }
    }

    /// The `[[light]]` table of this surface (its radiance to be added).
    pub fn light(self) -> Table {
        match self {
            AreaEmitter::Quad(v) => table([
                ("type", string("quad")),
                ("vertices", Toml::Array(v.into_iter().map(vec3).collect())),
            ]),
            AreaEmitter::Disk {
                center,
                normal,
                radius,
            } => table([
                ("type", string("disk")),
                ("center", vec3(center)),
                ("normal", vec3(normal)),
                ("radius", Toml::Float(radius)),
            ]),
            AreaEmitter::Sphere { center, radius } => table([
                ("type", string("sphere")),
                ("center", vec3(center)),
                ("radius", Toml::Float(radius)),
            ]),
            AreaEmitter::Mesh { keys, .. } => keys,
        }
    }
}

/// A pixel filter as `[camera]` keys in `camera`: none for a box, grinlight's default; a
/// Gaussian's `filter`, `filter_stddev`, and `filter_radius` and `filter_beyond_image` where
/// they are not the defaults (4σ, false).
pub fn pixel_filter_keys(filter: PixelFilter, camera: &mut Table) {
    match filter {
        PixelFilter::Box => {}
        PixelFilter::Gaussian {
            stddev,
            radius,
            reach,
        } => {
            camera.insert("filter".into(), string("gaussian"));
            camera.insert("filter_stddev".into(), Toml::Float(stddev));
            if radius != 4.0 * stddev {
                camera.insert("filter_radius".into(), Toml::Float(radius));
            }
            match reach {
                Reach::Image => {}
                Reach::Beyond => {
                    camera.insert("filter_beyond_image".into(), Toml::Boolean(true));
                }
            }
        }
    }
}

/// A round shape's keys `t` with, where given, the frame its texture coordinates are read in
/// and whether v counts from the image's top (`uv_frame`, `v_from_top`).
pub fn with_uv_frame(mut t: Table, frame: Option<([DVec3; 3], bool)>) -> Table {
    if let Some((axes, v_from_top)) = frame {
        t.insert(
            "uv_frame".into(),
            Toml::Array(axes.into_iter().map(vec3).collect()),
        );
        t.insert("v_from_top".into(), Toml::Boolean(v_from_top));
    }
    t
}
