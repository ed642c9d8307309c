//! The `grinlight._grinlight` extension: the library's commands for Python, a thin layer.
//! Scenes are read from files or from dicts (converted to the scene file's TOML schema, each
//! error naming the key's path); renders, receiver measurements and traced rays come back as
//! numpy arrays. Every call releases the interpreter while it works and polls for signals, so
//! Ctrl-C stops a render with its finished passes kept (the Python layer in
//! `grinlight/__init__.py` raises `KeyboardInterrupt` carrying them).

mod arrays;
mod convert;
mod watch;

use grinlight::commands::{self, MergeJob, RenderJob, RenderOutcome};
use grinlight::error::Error;
use grinlight::film::Film;
use grinlight::import::{Format, ImportOptions};
use grinlight::output::{Kind, Outputs};
use grinlight::receiver::Receiver;
use grinlight::scene::{self, Description};
use grinlight::settings::Settings;
use grinlight::shard::Shard;
use pyo3::exceptions::{PyKeyboardInterrupt, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};
use watch::{watched, Watched};

/// A library error as the Python exception a caller expects: a missing or unreadable file
/// is an `OSError`, an interrupt a `KeyboardInterrupt`, everything the user gave wrong a
/// `ValueError`; the message is the command line's.
fn py_err(e: Error) -> PyErr {
    match e {
        Error::Io { .. } => PyOSError::new_err(e.to_string()),
        Error::Interrupted(_) => PyKeyboardInterrupt::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// Where a scene comes from: a file (its text as read when loaded), a dict, or another
/// renderer's scene file (converted anew for each render).
enum Source {
    File {
        path: PathBuf,
        text: String,
    },
    Data {
        table: toml::Table,
        dir: PathBuf,
    },
    Imported {
        path: PathBuf,
        options: ImportOptions,
    },
}

/// A loaded scene: checked when loaded, parsed anew for each render (so every render starts
/// from the same description, as the command line's does).
#[pyclass(module = "grinlight._grinlight", frozen)]
struct Scene {
    source: Source,
    /// The media's names, in scene order.
    #[pyo3(get)]
    media: Vec<String>,
    /// The receivers' names, in scene order.
    #[pyo3(get)]
    receivers: Vec<String>,
    /// The camera's image size (width, height) in pixels, before any override; None
    /// without a camera.
    #[pyo3(get)]
    camera: Option<(u32, u32)>,
}

impl Scene {
    fn description(&self) -> PyResult<(Description, Settings)> {
        match &self.source {
            Source::File { path, text } => scene::load::parse_description(path, text.clone()),
            Source::Data { table, dir } => scene::parse_data(table, dir),
            Source::Imported { path, options } => {
                grinlight::import::load_description(path, options)
            }
        }
        .map_err(py_err)
    }

    /// The scene from `source`, checked with `overrides` applied as a render applies them.
    fn checked(source: Source, overrides: &Bound<'_, PyDict>) -> PyResult<Scene> {
        let mut scene = Scene {
            source,
            media: Vec::new(),
            receivers: Vec::new(),
            camera: None,
        };
        let (mut description, mut settings) = scene.description()?;
        scene.media = description.media.names().map(str::to_string).collect();
        scene.receivers = description
            .receivers
            .iter()
            .map(|r| r.name.clone())
            .collect();
        scene.camera = description
            .camera
            .as_ref()
            .map(|c| (c.window().width, c.window().height));
        convert::overrides(overrides)?
            .apply(&mut description, &mut settings)
            .map_err(py_err)?;
        Ok(scene)
    }
}

/// Reads the scene file at `path` (grinlight's TOML, a Mitsuba 3 scene ending in `.xml` — its
/// `$parameters` given `defines` — or a pbrt-v4 scene ending in `.pbrt`, approximated where
/// `approximate`), checked now with the
/// render settings `overrides`: an error names its file, line, column and key.
#[pyfunction]
#[pyo3(signature = (path, overrides, defines=Vec::new(), approximate=false))]
fn load(
    path: PathBuf,
    overrides: &Bound<'_, PyDict>,
    defines: Vec<(String, String)>,
    approximate: bool,
) -> PyResult<Scene> {
    let options = ImportOptions {
        defines,
        approximate,
    };
    if Format::of(&path) != Format::Grinlight {
        return Scene::checked(Source::Imported { path, options }, overrides);
    }
    if options != ImportOptions::default() {
        return Err(PyValueError::new_err(format!(
            "{}: defines and approximate apply to scenes of other renderers (.xml, .pbrt), not \
             to a grinlight scene",
            path.display()
        )));
    }
    let text =
        grinlight::input::read_text(&path, grinlight::input::MAX_SCENE_BYTES, "a scene file")
            .map_err(py_err)?;
    Scene::checked(Source::File { path, text }, overrides)
}

/// Reads a scene given as a dict of the scene file's schema, checked now with the render
/// settings `overrides`: an error names the key's path. Relative file names in it are
/// resolved in `base_dir`.
#[pyfunction]
fn load_dict(
    data: &Bound<'_, PyAny>,
    base_dir: PathBuf,
    overrides: &Bound<'_, PyDict>,
) -> PyResult<Scene> {
    let table = convert::scene_table(data)?;
    let source = Source::Data {
        table,
        dir: base_dir,
    };
    Scene::checked(source, overrides)
}

#[pymethods]
impl Scene {
    /// The scene file's path (for a dict, a name in the directory its relative paths are
    /// resolved against).
    #[getter]
    fn path(&self) -> PathBuf {
        match &self.source {
            Source::File { path, .. } => path.clone(),
            Source::Data { dir, .. } => dir.join(scene::source::DATA_NAME),
            Source::Imported { path, .. } => path.clone(),
        }
    }

    /// Renders in memory with `overrides` (the command line's `[render]` and `[camera]`
    /// values), the camera's view only when `camera`; `progress(done, total, stage)` is
    /// called as it goes. Returns a dict: `film` (a `Film`, None without a camera),
    /// `receivers`, `budget`, `report`, `warnings`, `interrupted`.
    #[pyo3(signature = (overrides, progress=None, camera=true))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        overrides: &Bound<'py, PyDict>,
        progress: Option<Bound<'py, PyAny>>,
        camera: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let overrides = convert::overrides(overrides)?;
        let (mut description, settings) = self.description()?;
        if !camera {
            description.camera = None;
        }
        let inputs = description.inputs.clone();
        let receivers = description.receivers.clone();
        let media: Vec<String> = description.media.names().map(str::to_string).collect();
        let exposure = settings.output.exposure;
        let Watched {
            result,
            report,
            interrupted,
        } = watched(py, progress.as_ref(), |observer| {
            commands::render_in_memory(description, settings, &overrides, observer)
        })?;
        let outcome: RenderOutcome = result.map_err(py_err)?;
        let out = PyDict::new(py);
        let film = outcome.film.map(|r| RenderedFilm {
            film: r.film,
            passes: r.passes,
            inputs,
            exposure,
        });
        out.set_item("film", film)?;
        out.set_item(
            "receivers",
            receivers_dict(py, &receivers, &outcome.measurements)?,
        )?;
        let budget = match &outcome.budget {
            Some(b) => Some(arrays::budget(py, b, &media)?),
            None => None,
        };
        out.set_item("budget", budget)?;
        out.set_item("report", PyList::new(py, &report.lines)?)?;
        out.set_item("warnings", PyList::new(py, &report.warnings)?)?;
        out.set_item("interrupted", outcome.interrupted || interrupted)?;
        Ok(out)
    }

    /// Renders the shard `shard` ("K/N", as `grinlight render --shard K/N` reads it) of the
    /// scene file's render into a partial result; returns the partial's path.
    #[pyo3(signature = (overrides, shard, output=None, resume=false, progress=None))]
    fn render_shard(
        &self,
        py: Python<'_>,
        overrides: &Bound<'_, PyDict>,
        shard: &str,
        output: Option<PathBuf>,
        resume: bool,
        progress: Option<Bound<'_, PyAny>>,
    ) -> PyResult<PathBuf> {
        let (path, import) =
            match &self.source {
                Source::File { path, .. } => (path, ImportOptions::default()),
                Source::Imported { path, options } => (path, options.clone()),
                Source::Data { .. } => return Err(PyValueError::new_err(
                    "shards are rendered from a scene file (merging them reloads it): save the \
                     dict as TOML and load that",
                )),
            };
        let shard = Shard::parse(shard).map_err(py_err)?;
        let job = RenderJob {
            scene: path.clone(),
            output: output.clone(),
            overrides: convert::overrides(overrides)?,
            shard: Some(shard),
            resume,
            import,
            ..RenderJob::default()
        };
        let watched = watched(py, progress.as_ref(), |observer| {
            commands::render(&job, observer)
        })?;
        let lines = watched.report.lines.join("\n");
        // Interrupted, the shard saved what it did: the report says how to resume it.
        let outcome = watched.result.map_err(py_err)?;
        if watched.interrupted || outcome.interrupted {
            return Err(PyKeyboardInterrupt::new_err(lines));
        }
        Ok(output.unwrap_or_else(|| commands::shard_partial(path, shard)))
    }

    /// Follows one ray through the medium `medium`, unbounded, as `grinlight trace` does;
    /// `options` holds the stepper and its control. Returns a dict of numpy arrays.
    fn trace<'py>(
        &self,
        py: Python<'py>,
        medium: String,
        origin: &Bound<'py, PyAny>,
        direction: &Bound<'py, PyAny>,
        length: f64,
        options: &Bound<'py, PyDict>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let ray = convert::ray_trace(medium, origin, direction, length, options)?;
        let scene = self.description()?.0.build();
        let traced = watched(py, None, |observer| {
            commands::trace_ray(&scene, &ray, observer)
        })?;
        arrays::traced(py, &traced.uninterrupted()?.map_err(py_err)?)
    }
}

/// Each receiver's measurement as a dict of numpy arrays, by name.
fn receivers_dict<'py>(
    py: Python<'py>,
    receivers: &[Receiver],
    measurements: &[grinlight::receiver::Measurement],
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for (r, m) in receivers.iter().zip(measurements) {
        out.set_item(&r.name, arrays::measurement(py, r, m)?)?;
    }
    Ok(out)
}

/// A rendered film: every layer developed to float32 linear RGB on demand, and written as
/// the command line writes it (the Python layer's `grinlight.Image` holds one).
#[pyclass(module = "grinlight._grinlight", name = "Film", frozen)]
struct RenderedFilm {
    film: Film,
    /// The passes it holds.
    #[pyo3(get)]
    passes: u32,
    /// The files the scene read (no output may replace one).
    inputs: Vec<PathBuf>,
    /// The scene's `[output] exposure` for the PNG preview.
    exposure: f32,
}

#[pymethods]
impl RenderedFilm {
    /// Pixels across.
    #[getter]
    fn width(&self) -> usize {
        self.film.width
    }

    /// Pixels down.
    #[getter]
    fn height(&self) -> usize {
        self.film.height
    }

    /// The film's estimate of its relative RMSE, from the spread of its passes (None before
    /// two passes).
    #[getter]
    fn error(&self, py: Python<'_>) -> Option<f64> {
        py.detach(|| self.film.error().map(|e| e.relative_rmse()))
    }

    /// The layers' names, `beauty` (the sum of the radiance layers) first.
    #[getter]
    fn names(&self) -> Vec<String> {
        self.film.names().into_iter().map(str::to_string).collect()
    }

    /// The layer `name` as a float32 array of shape (height, width, 3), row 0 at the top.
    fn layer<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let pixels = py.detach(|| self.film.layer(name)).ok_or_else(|| {
            PyValueError::new_err(format!(
                "no layer named '{name}' (the film holds {})",
                self.film.names().join(", ")
            ))
        })?;
        arrays::rgb_image(py, pixels, self.film.width, self.film.height)
    }

    /// Writes every layer into one EXR at `path` (ending in .exr), as `grinlight render`
    /// writes it: atomically, never over the scene's inputs or a file that is not an EXR.
    fn write(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        self.checked_output(&path, Kind::Exr)?;
        py.detach(|| self.film.write_exr(&path)).map_err(py_err)
    }

    /// Writes the beauty layer as an 8-bit sRGB PNG at `path`, scaled by `exposure`
    /// (default: the scene's `[output] exposure`).
    #[pyo3(signature = (path, exposure=None))]
    fn write_png(&self, py: Python<'_>, path: PathBuf, exposure: Option<f32>) -> PyResult<()> {
        self.checked_output(&path, Kind::Png)?;
        let exposure = exposure.unwrap_or(self.exposure);
        if !exposure.is_finite() || exposure < 0.0 {
            return Err(PyValueError::new_err(format!(
                "exposure: must be a finite number ≥ 0, got {exposure}"
            )));
        }
        py.detach(|| self.film.write_png(&path, exposure))
            .map_err(py_err)
    }
}

impl RenderedFilm {
    fn checked_output(&self, path: &Path, kind: Kind) -> PyResult<()> {
        if kind == Kind::Exr && !grinlight::output::is_exr(path) {
            return Err(PyValueError::new_err(format!(
                "{}: an image with its layers is written as an EXR, ending in .exr",
                path.display()
            )));
        }
        Outputs::new(&self.inputs).add(path, kind).map_err(py_err)
    }
}

/// Merges the partial results of a render's shards, as `grinlight merge` does (writing the
/// render's files); returns the merged image (None without a camera).
#[pyfunction]
#[pyo3(signature = (partials, output=None, allow_missing=false))]
fn merge(
    py: Python<'_>,
    partials: Vec<PathBuf>,
    output: Option<PathBuf>,
    allow_missing: bool,
) -> PyResult<Option<RenderedFilm>> {
    let job = MergeJob {
        partials,
        output,
        allow_missing,
    };
    let merged = watched(py, None, |observer| commands::merge(&job, observer))?;
    let outcome = merged.uninterrupted()?.map_err(py_err)?;
    let Some(rendered) = outcome.film else {
        return Ok(None);
    };
    let first = job.partials.first().expect("merge refuses no partials");
    let header = grinlight::shard::file::Opened::open(first)
        .map_err(py_err)?
        .header;
    let (description, settings) =
        grinlight::import::load_description(&header.scene, &ImportOptions::default())
            .map_err(py_err)?;
    Ok(Some(RenderedFilm {
        film: rendered.film,
        passes: rendered.passes,
        inputs: description.inputs,
        exposure: settings.output.exposure,
    }))
}

/// The render settings a keyword of `Scene.render` may give, as (name, meaning, values,
/// default): the settings table the scene file and the command line read.
#[pyfunction]
fn render_settings() -> Vec<(&'static str, &'static str, String, &'static str)> {
    grinlight::settings::KEYS
        .iter()
        .map(|k| (k.name, k.doc, k.range(), k.default))
        .collect()
}

#[pymodule]
fn _grinlight(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_class::<RenderedFilm>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(load_dict, m)?)?;
    m.add_function(wrap_pyfunction!(merge, m)?)?;
    m.add_function(wrap_pyfunction!(render_settings, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
