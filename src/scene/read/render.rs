//! `[render]` and `[output]`: how to render and where to write. Every key's unit and default is in `docs/scene-format.md`.

use crate::curve::{StepControl, StepperKind};
use crate::error::Result;
use crate::scene::table::TableReader;
use crate::settings::{apply_all, OutputSettings, Settings, Table, Target, KEYS};

/// `[render]`: every setting but the output's; those of the settings table
/// ([`crate::settings::keys`]) as the command line and Python read them, the stepper and its
/// control (which depend on each other) here.
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
    let mut assignments = Vec::new();
    for key in KEYS.iter().filter(|k| k.table == Table::Render) {
        assignments.extend(t.setting(key)?);
    }
    let mut settings = Settings::default();
    settings.trace.stepper = stepper;
    settings.trace.control = control;
    apply_all(
        &assignments,
        &mut Target {
            settings: &mut settings,
            camera: None,
        },
    );
    Ok(settings)
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
