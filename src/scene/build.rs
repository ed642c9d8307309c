//! Names ⇒ objects, values ⇒ validated: the render-ready [`Scene`].

use super::desc::{MediumDesc, SceneDesc};
use super::load::Source;
use crate::error::{Error, Result};
use crate::media::{
    Axis, BlackHole, ExponentialMedium, FishEye, GridMedium, LinearMedium, Luneburg, Medium,
    ParabolicFiber, SechFiber, UniformMedium,
};
use glam::DVec3;
use std::ops::Range;

/// A validated scene, immutable and shareable across threads.
pub struct Scene {
    media: Vec<(String, Box<dyn Medium>)>,
    path: std::path::PathBuf,
}

impl Scene {
    /// The medium called `name`; the error lists the names that exist.
    pub fn medium(&self, name: &str) -> Result<&dyn Medium> {
        self.media
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, m)| m.as_ref())
            .ok_or_else(|| {
                let known: Vec<&str> = self.media.iter().map(|(n, _)| n.as_str()).collect();
                Error::Usage(format!(
                    "{}: no medium named '{name}' (the scene has: {})",
                    self.path.display(),
                    if known.is_empty() { "none".to_string() } else { known.join(", ") }
                ))
            })
    }

    /// Names of all media, in file order.
    pub fn medium_names(&self) -> impl Iterator<Item = &str> {
        self.media.iter().map(|(n, _)| n.as_str())
    }
}

/// Checks of one table's values, reporting at the offending key.
struct Table<'a> {
    source: &'a Source,
    span: Range<usize>,
}

impl Table<'_> {
    fn fail(&self, key: &str, message: impl Into<String>) -> Error {
        self.source.key_error(self.span.clone(), key, message)
    }
    fn positive(&self, key: &str, v: f64) -> Result<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.fail(key, format!("must be a finite number > 0, got {v}")))
        }
    }
    fn finite(&self, key: &str, v: f64) -> Result<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.fail(key, format!("must be finite, got {v}")))
        }
    }
    fn vector(&self, key: &str, v: [f64; 3]) -> Result<DVec3> {
        let d = DVec3::from_array(v);
        if d.is_finite() {
            Ok(d)
        } else {
            Err(self.fail(key, format!("must be three finite numbers, got {v:?}")))
        }
    }
    fn direction(&self, key: &str, v: [f64; 3]) -> Result<DVec3> {
        self.vector(key, v)?
            .try_normalize()
            .ok_or_else(|| self.fail(key, "must be a non-zero vector"))
    }
}

/// Builds the scene, validating every value.
pub fn build(source: &Source, desc: SceneDesc) -> Result<Scene> {
    let mut media: Vec<(String, Box<dyn Medium>)> = Vec::new();
    for spanned in desc.medium {
        let table = Table {
            source,
            span: spanned.span(),
        };
        let m = spanned.get_ref();
        if m.name().is_empty() {
            return Err(table.fail("name", "must not be empty"));
        }
        if media.iter().any(|(n, _)| n == m.name()) {
            return Err(table.fail("name", format!("a medium named '{}' is already defined", m.name())));
        }
        media.push((m.name().to_string(), build_medium(&table, m)?));
    }
    Ok(Scene {
        media,
        path: source.path.clone(),
    })
}

fn build_medium(t: &Table, m: &MediumDesc) -> Result<Box<dyn Medium>> {
    Ok(match m {
        MediumDesc::Uniform { n, .. } => Box::new(UniformMedium { n: t.positive("n", *n)? }),
        MediumDesc::Linear { n0, gradient, origin, .. } => Box::new(LinearMedium {
            n0: t.positive("n0", *n0)?,
            gradient: t.vector("gradient", *gradient)?,
            origin: t.vector("origin", *origin)?,
        }),
        MediumDesc::Exponential { n0, gradient, origin, .. } => Box::new(ExponentialMedium {
            n0: t.positive("n0", *n0)?,
            gradient: t.vector("gradient", *gradient)?,
            origin: t.vector("origin", *origin)?,
        }),
        MediumDesc::Parabolic { n0, a, center, axis, .. } => Box::new(ParabolicFiber {
            n0: t.positive("n0", *n0)?,
            a: t.finite("a", *a)?,
            axis: Axis {
                center: t.vector("center", *center)?,
                axis: t.direction("axis", *axis)?,
            },
        }),
        MediumDesc::Sech { n0, g, center, axis, .. } => Box::new(SechFiber {
            n0: t.positive("n0", *n0)?,
            g: t.positive("g", *g)?,
            axis: Axis {
                center: t.vector("center", *center)?,
                axis: t.direction("axis", *axis)?,
            },
        }),
        MediumDesc::Luneburg { center, radius, .. } => Box::new(Luneburg {
            center: t.vector("center", *center)?,
            radius: t.positive("radius", *radius)?,
        }),
        MediumDesc::Fisheye { n0, center, radius, .. } => Box::new(FishEye {
            n0: t.positive("n0", *n0)?,
            center: t.vector("center", *center)?,
            radius: t.positive("radius", *radius)?,
        }),
        MediumDesc::BlackHole { center, rs, q, .. } => {
            if !(q.is_finite() && *q >= 0.0) {
                return Err(t.fail("q", format!("must be a finite number ≥ 0, got {q}")));
            }
            Box::new(BlackHole {
                center: t.vector("center", *center)?,
                rs: t.positive("rs", *rs)?,
                q: *q,
            })
        }
        MediumDesc::Grid { bounds, dims, values, file, .. } => {
            let values = match (values, file) {
                (Some(v), None) => v.clone(),
                (None, Some(f)) => read_grid_file(t, f)?,
                _ => return Err(t.fail("values", "give exactly one of `values` and `file`")),
            };
            let key = if file.is_some() { "file" } else { "values" };
            let grid = GridMedium::new(
                t.vector("bounds", bounds[0])?,
                t.vector("bounds", bounds[1])?,
                *dims,
                values,
            )
            .map_err(|e| t.fail(key, e.to_string()))?;
            Box::new(grid)
        }
    })
}

fn read_grid_file(t: &Table, file: &str) -> Result<Vec<f64>> {
    let path = t.source.dir().join(file);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| t.fail("file", format!("cannot read {}: {e}", path.display())))?;
    text.split_whitespace()
        .enumerate()
        .map(|(i, w)| {
            w.parse::<f64>()
                .map_err(|_| t.fail("file", format!("{}: value #{i} '{w}' is not a number", path.display())))
        })
        .collect()
}
