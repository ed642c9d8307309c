//! `grinlight merge`: the partial results of a render's shards merged into its results, bit
//! for bit those of one run of the whole render (see [`crate::shard`]).

use super::render::{output_exr, publish, Files, RenderOutcome, Work};
use super::Observer;
use crate::error::{Error, Result};
use crate::output::Outputs;
use crate::shard::file::Opened;
use crate::shard::{Header, Merge, Partial, Shard};
use std::path::PathBuf;

/// What `grinlight merge` is asked to do.
#[derive(Clone, Debug, Default)]
pub struct MergeJob {
    /// The partial files, one per shard, in any order.
    pub partials: Vec<PathBuf>,
    /// The EXR to write (None: the scene's `[output] path`, else `<scene stem>.exr` in the
    /// working directory); the PNG preview and receivers' files are named after it.
    pub output: Option<PathBuf>,
    /// Merge even when shards are missing: the film holds the passes there are, the
    /// receivers' fluxes are scaled from the photons there are (an estimate, said so).
    pub allow_missing: bool,
}

/// Runs `grinlight merge`: reads the first partial, reloads the scene it names (refusing it if
/// its files changed since) and checks every file the merge will write; then reads the
/// partials one at a time, refusing any that is not a part of the same render (naming the
/// difference), duplicates and overlaps, and missing work unless allowed; and writes the
/// render's results as `grinlight render` does.
pub fn merge(job: &MergeJob, observer: &dyn Observer) -> Result<RenderOutcome> {
    if job.partials.is_empty() {
        return Err(Error::Usage(
            "nothing to merge: name the partial files".into(),
        ));
    }
    // Every header first: a partial of another render, or a damaged header, is refused
    // before any payload is read.
    let mut merge = Merge::new();
    let mut first = None;
    for p in &job.partials {
        let header = Opened::open(p)?.header;
        merge.admit(p, &header)?;
        first.get_or_insert(header);
    }
    let first = first.expect("at least one partial");
    let path = first.scene.clone();
    let (description, settings) = crate::import::load_description(&path, &Default::default())?;
    let scene = description.build();
    if Header::new(&scene, &settings, Shard::WHOLE, first.role)?.inputs != first.inputs {
        return Err(Error::Usage(format!(
            "{}: the scene or a file it reads changed since the partials were rendered: merging \
             them would describe a scene that no longer exists",
            path.display()
        )));
    }
    let exr = output_exr(job.output.clone(), &settings, &path);
    let mut outputs = Outputs::new(scene.inputs.iter().chain(&job.partials));
    let stokes = settings.trace.stokes;
    let files = Files::plan(&scene, exr, settings.output.png, stokes, 0, &mut outputs)?;
    for p in &job.partials {
        let part = Partial::read(p)?;
        part.fits(&scene, p)?;
        merge.add(p, part)?;
    }
    let merged = merge.finish(job.allow_missing)?;
    observer.line(&format!(
        "merged {} partial(s) of {}: passes {}, receiver photons {}",
        job.partials.len(),
        path.display(),
        merged.passes,
        merged.photons
    ));
    let complete = merged.is_complete();
    let mut outcome = publish(&scene, &settings, merged, Work::default(), &files, observer)?;
    outcome.incomplete = !complete;
    Ok(outcome)
}
