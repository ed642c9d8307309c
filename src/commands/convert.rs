//! `grinlight convert`: a scene written for another renderer (Mitsuba 3 XML) written out as
//! the equivalent grinlight scene file, to be rendered or edited (a GRIN medium added).

use crate::error::{Error, Result};
use crate::import::{Format, ImportOptions};
use crate::output::{Kind, Outputs};
use std::path::PathBuf;

/// What `grinlight convert` is asked to do.
#[derive(Clone, Debug)]
pub struct ConvertJob {
    /// The scene of another renderer.
    pub scene: PathBuf,
    /// The grinlight scene file to write (ending in `.toml`); it may replace only a file
    /// `grinlight convert` wrote.
    pub output: PathBuf,
    /// How the scene is read.
    pub import: ImportOptions,
}

/// Converts the job's scene and writes it (atomically); returns what the user should be told
/// (each approximation and note), which the file's header also lists.
pub fn convert(job: &ConvertJob) -> Result<Vec<String>> {
    if Format::of(&job.scene) == Format::Grinlight {
        return Err(Error::Usage(format!(
            "{}: convert reads a Mitsuba 3 scene (.xml) or a pbrt-v4 scene (.pbrt)",
            job.scene.display()
        )));
    }
    if job.output.extension().is_none_or(|e| e != "toml") {
        return Err(Error::Usage(format!(
            "{}: the converted scene's name should end in .toml",
            job.output.display()
        )));
    }
    let imported = crate::import::import(&job.scene, &job.import)?;
    let mut outputs = Outputs::new(&imported.files);
    outputs.add(&job.output, Kind::ConvertedScene)?;
    crate::output::write_text(&job.output, &imported.to_toml(&job.scene))?;
    Ok(imported
        .approximations
        .iter()
        .map(|a| format!("approximated: {a}"))
        .chain(imported.notes)
        .collect())
}
