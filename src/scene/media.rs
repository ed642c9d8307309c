//! `[[medium]]` tables ⇒ media. Each profile's keys, units and defaults are listed in
//! `docs/scene-format.md`; lengths are scene units, vectors [x, y, z].

use super::table::TableReader;
use crate::error::Result;
use crate::media::{
    Absorbing, Axis, BlackHole, ExponentialMedium, FishEye, GridError, GridMedium, HeightTable,
    LinearMedium, Luneburg, Medium, ParabolicFiber, RadialTable, SechFiber, UniformMedium,
};
use glam::DVec3;

/// The profile names a `[[medium]]` table may give.
pub const PROFILES: &[&str] = &[
    "uniform",
    "linear",
    "exponential",
    "parabolic",
    "sech",
    "radial_table",
    "height_table",
    "luneburg",
    "fisheye",
    "black_hole",
    "grid",
];

/// Reads one `[[medium]]` table (its `name` already taken) and builds the medium, with its
/// `absorption` coefficient if it has one.
pub fn read_medium(t: &mut TableReader) -> Result<Box<dyn Medium>> {
    let absorption = t.f64_or("absorption", 0.0)?;
    t.check(
        "absorption",
        absorption.is_finite() && absorption >= 0.0,
        format!("must be a finite number ≥ 0 (1/length), got {absorption}"),
    )?;
    let index = read_profile(t)?;
    Ok(if absorption > 0.0 {
        Box::new(Absorbing {
            inner: index,
            sigma_a: absorption,
        })
    } else {
        index
    })
}

/// The index profile of a `[[medium]]` table.
fn read_profile(t: &mut TableReader) -> Result<Box<dyn Medium>> {
    let profile = t.string("profile")?;
    let fiber_axis = |t: &mut TableReader| -> Result<Axis> {
        Ok(Axis {
            center: t.vec3_or("center", DVec3::ZERO)?,
            axis: t.direction_or("axis", DVec3::Z)?,
        })
    };
    Ok(match profile.as_str() {
        "uniform" => Box::new(UniformMedium {
            n: t.positive("n")?,
        }),
        "linear" => Box::new(LinearMedium {
            n0: t.positive("n0")?,
            gradient: t.vec3("gradient")?,
            origin: t.vec3_or("origin", DVec3::ZERO)?,
        }),
        "exponential" => Box::new(ExponentialMedium {
            n0: t.positive("n0")?,
            gradient: t.vec3("gradient")?,
            origin: t.vec3_or("origin", DVec3::ZERO)?,
        }),
        "parabolic" => Box::new(ParabolicFiber {
            n0: t.positive("n0")?,
            a: t.f64("a")?,
            axis: fiber_axis(t)?,
        }),
        "sech" => Box::new(SechFiber {
            n0: t.positive("n0")?,
            g: t.positive("g")?,
            axis: fiber_axis(t)?,
        }),
        "radial_table" => {
            let r = t.f64_list("r")?;
            let n = t.f64_list("n")?;
            let axis = fiber_axis(t)?;
            Box::new(RadialTable::new(r, n, axis).map_err(|(key, e)| t.error(key, e))?)
        }
        "height_table" => {
            let h = t.f64_list("h")?;
            let n = t.f64_list("n")?;
            let origin = t.vec3_or("origin", DVec3::ZERO)?;
            let up = t.direction_or("up", DVec3::Y)?;
            Box::new(HeightTable::new(h, n, origin, up).map_err(|(key, e)| t.error(key, e))?)
        }
        "luneburg" => Box::new(Luneburg {
            center: t.vec3_or("center", DVec3::ZERO)?,
            radius: t.positive("radius")?,
        }),
        "fisheye" => Box::new(FishEye {
            n0: t.positive("n0")?,
            center: t.vec3_or("center", DVec3::ZERO)?,
            radius: t.positive("radius")?,
        }),
        "black_hole" => {
            let center = t.vec3_or("center", DVec3::ZERO)?;
            let rs = t.positive("rs")?;
            let q = t.f64_or("q", 0.0)?;
            t.check("q", q >= 0.0, format!("must be ≥ 0, got {q}"))?;
            Box::new(BlackHole { center, rs, q })
        }
        "grid" => Box::new(read_grid(t)?),
        other => {
            return Err(t.error(
                "profile",
                format!(
                    "unknown profile '{other}' (expected one of: {})",
                    PROFILES.join(", ")
                ),
            ))
        }
    })
}

fn read_grid(t: &mut TableReader) -> Result<GridMedium> {
    let bounds = t.vec3_list("bounds")?;
    let [min, max] = bounds[..] else {
        return Err(t.error("bounds", "expected [[min x, y, z], [max x, y, z]]"));
    };
    let dims: [usize; 3] = t.counts("dims")?;
    let values = t.f64_list_opt("values")?;
    let (values, key) = match (values, t.has("file")) {
        (Some(v), false) => (v, "values"),
        (None, true) => {
            let path = t.input_file("file")?;
            (read_grid_file(t, &path)?, "file")
        }
        _ => return Err(t.error("values", "give exactly one of `values` and `file`")),
    };
    GridMedium::new(min, max, dims, values).map_err(|e| {
        let key = match e {
            GridError::TooFewNodes(_) | GridError::TooManyNodes(_) => "dims",
            GridError::EmptyBox => "bounds",
            _ => key,
        };
        t.error(key, e)
    })
}

fn read_grid_file(t: &TableReader, path: &std::path::Path) -> Result<Vec<f64>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| t.error("file", format!("cannot read {}: {e}", path.display())))?;
    text.split_whitespace()
        .enumerate()
        .map(|(i, w)| {
            w.parse::<f64>().map_err(|_| {
                t.error(
                    "file",
                    format!("{}: value #{i} '{w}' is not a number", path.display()),
                )
            })
        })
        .collect()
}
