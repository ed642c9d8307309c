//! `[render]` and `[output]`: how to render and where to write. Every key's unit and default is in `docs/scene-format.md`.

use crate::curve::{StepControl, StepperKind};
use crate::error::Result;
use crate::scene::table::TableReader;
use crate::settings::{self, OutputSettings, PhotonSettings, Settings, TraceSettings};

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
    let target_error = optional_positive(t, "target_error")?;
    // A time budget or a target error with no count of passes renders as many as it takes
    // (as the command line's options do).
    let open_ended = time_budget.is_some() || target_error.is_some();
    let passes = match (open_ended, t.has("passes")) {
        (true, false) => u32::MAX,
        _ => t.setting(settings::PASSES, Settings::default().passes as u64)? as u32,
    };
    let d = Settings::default();
    let integrator = t.string_opt("integrator")?.map_or(Ok(d.integrator), |s| {
        s.parse().map_err(|e: String| t.error("integrator", e))
    })?;
    Ok(Settings {
        integrator,
        deflection_table: t.bool_or("deflection_table", d.deflection_table)?,
        spp: t.setting(settings::SPP, d.spp as u64)? as u32,
        seed: t.natural_or("seed", d.seed)?,
        threads: t.natural_or("threads", 0)? as usize,
        trace: TraceSettings {
            max_depth: t.setting(settings::MAX_DEPTH, d.trace.max_depth as u64)? as u32,
            stepper,
            control,
            max_steps: t.setting(settings::MAX_STEPS, d.trace.max_steps)?,
            world_radius,
        },
        photons: PhotonSettings {
            global: t.setting(settings::PHOTONS, d.photons.global)?,
            caustic: t.setting(settings::CAUSTIC_PHOTONS, d.photons.caustic)?,
            gather: t.setting(settings::GATHER, d.photons.gather as u64)? as u32,
            radius,
            knn: t.setting(settings::KNN, d.photons.knn as u64)? as u32,
        },
        passes,
        time_budget,
        target_error,
        receiver_photons: t.setting(settings::RECEIVER_PHOTONS, d.receiver_photons)?,
        output: d.output,
    })
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
