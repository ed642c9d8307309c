//! Scenes written for other renderers, brought in: a Mitsuba 3 XML scene ([`mitsuba`]) or a
//! pbrt-v4 scene ([`pbrt`]) converted to grinlight's scene schema and read as any scene is — rendered as it is
//! (`grinlight render scene.xml`) or written out as a grinlight scene file (`grinlight
//! convert`) to which a GRIN medium can be added. What cannot be converted exactly is refused
//! by file, line and element, or — asked for — approximated and listed.

pub mod geometry;
pub mod mitsuba;
pub mod pbrt;
pub mod table;

use crate::error::{Error, Result};
use crate::scene::Description;
use crate::settings::Settings;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// How a scene written for another renderer is read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImportOptions {
    /// Values of the scene's `$name` parameters (Mitsuba's `-D name=value`), before its
    /// `<default>`s.
    pub defines: Vec<(String, String)>,
    /// Convert what converts only approximately (each approximation listed) instead of
    /// refusing it.
    pub approximate: bool,
}

/// The format of a scene file, from its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// grinlight's own TOML.
    Grinlight,
    /// Mitsuba 3's XML (`.xml`).
    Mitsuba,
    /// pbrt-v4's scene format (`.pbrt`).
    Pbrt,
}

impl Format {
    /// The format of `path`: Mitsuba for `.xml`, pbrt for `.pbrt` (or `.pbrt.gz`), else
    /// grinlight's.
    pub fn of(path: &Path) -> Format {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("xml") => Format::Mitsuba,
            Some(e) if e.eq_ignore_ascii_case("pbrt") => Format::Pbrt,
            Some(e)
                if e.eq_ignore_ascii_case("gz")
                    && path
                        .to_string_lossy()
                        .to_ascii_lowercase()
                        .ends_with(".pbrt.gz") =>
            {
                Format::Pbrt
            }
            _ => Format::Grinlight,
        }
    }
}

/// Where something was written: file, line and column (1-based).
#[derive(Clone, Debug)]
pub struct Place {
    /// The scene file.
    pub file: Rc<PathBuf>,
    /// Line, 1-based.
    pub line: usize,
    /// Column, 1-based.
    pub col: usize,
}

impl Place {
    /// An error at this place.
    pub fn error(&self, message: impl Into<String>) -> Error {
        Error::Scene {
            path: self.file.as_ref().clone(),
            line: self.line,
            col: self.col,
            message: message.into(),
        }
    }
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}:{}", self.file.display(), self.line, self.col)
    }
}

/// What a conversion tells the user besides the scene: what it approximated (only when
/// allowed; otherwise an approximation is refused) and what converts exactly but is worth
/// knowing.
pub struct Told {
    approximate: bool,
    approximations: Vec<String>,
    notes: Vec<String>,
}

impl Told {
    /// Nothing told yet; `approximate`: whether approximations are allowed.
    pub fn new(approximate: bool) -> Told {
        Told {
            approximate,
            approximations: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// An approximation: listed if allowed, else refused at `place`.
    pub fn approximate(&mut self, place: &Place, what: impl std::fmt::Display) -> Result<()> {
        if self.approximate {
            self.approximations.push(format!("{place}: {what}"));
            Ok(())
        } else {
            Err(place.error(format!(
                "{what} — grinlight cannot convert this exactly; `--approximate` accepts it \
                 and lists it"
            )))
        }
    }

    /// Something the user should know, though it converts exactly.
    pub fn note(&mut self, place: &Place, what: impl std::fmt::Display) {
        self.notes.push(format!("{place}: {what}"));
    }

    /// The note a thin dielectric (`what`, from `renderer`'s scene) converts with: grinlight
    /// sums a pane's internal reflections for s and p light apart, the source renderer for
    /// their average.
    pub fn thin_pane(&mut self, place: &Place, what: &str, renderer: &str) {
        self.note(
            place,
            format!(
                "{what}: grinlight sums the pane's internal reflections for s and p light apart \
                 ({renderer}: for their average, 2R/(1 + R)): the same square on, less reflected \
                 obliquely (0.1519 against 0.1638 at 60° for η = 1.5)"
            ),
        );
    }

    /// The converted scene `table`, read from `files`, with what was told.
    pub fn into_imported(self, table: toml::Table, files: Vec<PathBuf>) -> Imported {
        Imported {
            table,
            approximations: self.approximations,
            notes: self.notes,
            files,
        }
    }
}

/// A scene of another format, converted: its grinlight scene table and what the user should
/// be told (approximations first).
pub struct Imported {
    /// The scene as grinlight's schema.
    pub table: toml::Table,
    /// Each approximation made (file:line: what).
    pub approximations: Vec<String>,
    /// What converts exactly but differs in a way worth knowing (file:line: what).
    pub notes: Vec<String>,
    /// The files of the scene read.
    pub files: Vec<PathBuf>,
}

/// Converts the scene `path` (not grinlight's own format) to a grinlight scene table.
pub fn import(path: &Path, options: &ImportOptions) -> Result<Imported> {
    match Format::of(path) {
        Format::Mitsuba => {
            let doc = mitsuba::xml::read(path, &options.defines)?;
            mitsuba::convert(&doc, options.approximate)
        }
        Format::Pbrt => {
            if let Some((name, _)) = options.defines.first() {
                return Err(Error::Usage(format!(
                    "{}: -D {name}=…: a pbrt scene has no $parameters (Mitsuba's XML has)",
                    path.display()
                )));
            }
            pbrt::convert(&pbrt::parse::read(path)?, options.approximate)
        }
        Format::Grinlight => Err(Error::Usage(format!(
            "{}: a grinlight scene needs no conversion",
            path.display()
        ))),
    }
}

/// Reads any scene file: grinlight's own, or another renderer's converted. The files an
/// imported scene read are among the description's inputs (no output may replace them); its
/// approximations and notes are among its warnings.
pub fn load_description(path: &Path, options: &ImportOptions) -> Result<(Description, Settings)> {
    match Format::of(path) {
        Format::Grinlight => {
            if *options != ImportOptions::default() {
                return Err(Error::Usage(format!(
                    "{}: -D and --approximate apply to scenes of other renderers (.xml, .pbrt), \
                     not to a grinlight scene",
                    path.display()
                )));
            }
            crate::scene::load_description(path)
        }
        Format::Mitsuba | Format::Pbrt => {
            let imported = import(path, options)?;
            let dir = path.parent().unwrap_or(Path::new("."));
            // The converted table's own errors (a value grinlight refuses) name its key.
            let (mut description, settings) = crate::scene::parse_data(&imported.table, dir)
                .map_err(|e| match e {
                    Error::Key { key, message } => Error::Key {
                        key: format!("{} as converted, {key}", path.display()),
                        message,
                    },
                    other => other,
                })?;
            description.inputs.extend(imported.files);
            let told = imported
                .approximations
                .iter()
                .map(|a| format!("approximated: {a}"))
                .chain(imported.notes);
            description.warnings.splice(0..0, told);
            Ok((description, settings))
        }
    }
}

impl Imported {
    /// The grinlight scene file equivalent to the scene read from `source`: a header naming
    /// where it came from and each approximation and note, then the scene (mesh and image
    /// files referenced by absolute path).
    pub fn to_toml(&self, source: &Path) -> String {
        let mut text = format!(
            "{}{} from {}.\n",
            crate::output::CONVERTED,
            env!("CARGO_PKG_VERSION"),
            source.display()
        );
        for a in &self.approximations {
            text.push_str(&format!("# approximated: {a}\n"));
        }
        for n in &self.notes {
            text.push_str(&format!("# note: {n}\n"));
        }
        text.push('\n');
        text.push_str(&crate::scene::data::SceneText::write(&self.table).text);
        text
    }
}
