//! `[render]` and `[output]`: how to render and where to write. Every key's unit and default is in `docs/scene-format.md`.

use crate::curve::{StepControl, StepperKind};
use crate::error::Result;
use crate::scene::table::TableReader;
use crate::settings::{OutputSettings, PhotonSettings, Settings, TraceSettings};

/// `[render]`: every setting but the output's.
pub fn read_render(t: &mut TableReader) -> Result<Settings> {
    let stepper: StepperKind = t
        .string_opt("stepper")?
        .map_or(Ok(StepperKind::DEFAULT), |s| {
            s.parse().map_err(|e: String| t.error("stepper", e))
        })?;
    let control = match t.string_opt("control")?.as_deref().unwrap_or("adaptive") {
        "adaptive" => {
            let tolerance = t.f64_or("tolerance", stepper.default_tolerance())?;
            t.check("tolerance", tolerance > 0.0, "must be > 0")?;
            StepControl::Adaptive { tolerance }
        }
        "fixed" => StepControl::Fixed {
            step: t.positive("step")?,
        },
        "tessendorf" => {
            let (t_max, t_min) = (t.f64_or("t_max", 1e-2)?, t.f64_or("t_min", 1e-4)?);
            t.check(
                "t_max",
                t_min >= 0.0 && t_max > t_min,
                "need 0 ≤ t_min < t_max",
            )?;
            StepControl::Tessendorf {
                initial_step: t.positive("step")?,
                t_max,
                t_min,
                seed: 1,
            }
        }
        other => {
            return Err(t.error(
                "control",
                format!("unknown control '{other}' (adaptive, fixed, tessendorf)"),
            ))
        }
    };
    let world_radius = optional_positive(t, "world_radius")?;
    let radius = optional_positive(t, "radius")?;
    let time_budget = optional_positive(t, "time_budget")?;
    let d = Settings::default();
    let integrator = t.string_opt("integrator")?.map_or(Ok(d.integrator), |s| {
        s.parse().map_err(|e: String| t.error("integrator", e))
    })?;
    Ok(Settings {
        integrator,
        deflection_table: t.bool_or("deflection_table", d.deflection_table)?,
        spp: count_u32(t, "spp", d.spp)?,
        seed: t.natural_or("seed", d.seed)?,
        threads: t.natural_or("threads", 0)? as usize,
        trace: TraceSettings {
            max_depth: count_u32(t, "max_depth", d.trace.max_depth)?,
            stepper,
            control,
            max_steps: t.count_or("max_steps", d.trace.max_steps)?,
            world_radius,
        },
        photons: PhotonSettings {
            global: t.natural_or("photons", d.photons.global)?,
            caustic: t.natural_or("caustic_photons", d.photons.caustic)?,
            gather: {
                let g = t.natural_or("gather", d.photons.gather as u64)?;
                within_limit(t, "gather", g)?
            },
            radius,
            knn: {
                let k = t.count_or("knn", d.photons.knn as u64)?;
                within_limit(t, "knn", k)?
            },
        },
        passes: count_u32(t, "passes", d.passes)?,
        time_budget,
        receiver_photons: t.count_or("receiver_photons", d.receiver_photons)?,
        output: d.output,
    })
}

/// An integer ≥ 1 that fits 32 bits (beyond, an error at `key`, never a silent clamp).
fn count_u32(t: &mut TableReader, key: &str, default: u32) -> Result<u32> {
    let v = t.count_or(key, default as u64)?;
    u32::try_from(v).map_err(|_| t.error(key, format!("must be at most {}, got {v}", u32::MAX)))
}

/// `gather` or `knn` = `v`, refused beyond the limit the command line enforces too
/// ([`crate::settings::beyond_gather_or_knn_limit`]).
fn within_limit(t: &TableReader, key: &str, v: u64) -> Result<u32> {
    match crate::settings::beyond_gather_or_knn_limit(v) {
        Some(why) => Err(t.error(key, why)),
        None => Ok(v as u32),
    }
}

/// A key that is either absent or a finite number > 0.
fn optional_positive(t: &mut TableReader, key: &str) -> Result<Option<f64>> {
    if t.has(key) {
        Ok(Some(t.positive(key)?))
    } else {
        Ok(None)
    }
}

/// `[output]`; relative paths are relative to the scene file's directory `dir`.
pub fn read_output(t: &mut TableReader) -> Result<OutputSettings> {
    let exposure = t.f64_or("exposure", 1.0)?;
    t.check("exposure", exposure > 0.0, "must be > 0")?;
    let path = t.output_file("path")?;
    t.check(
        "path",
        path.as_ref().is_none_or(|p| crate::output::is_exr(p)),
        "must name an EXR file (…/name.exr): the PNG preview and receiver files are written beside it",
    )?;
    Ok(OutputSettings {
        path,
        png: t.bool_or("png", true)?,
        exposure: exposure as f32,
    })
}
