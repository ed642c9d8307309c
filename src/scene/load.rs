//! Reading a scene file: TOML text ⇒ spanned tables ⇒ the validated [`Scene`], with every
//! error located at file:line:col and naming the key.

use super::media::read_medium;
use super::table::{SpannedTable, TableReader};
use crate::error::{Error, Result};
use crate::media::Medium;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// A scene file's text with its path, for turning byte offsets into line:col messages.
pub struct Source {
    /// The file.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
}

impl Source {
    /// 1-based line and column (in characters) of byte `offset`.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    }

    /// An error at byte `offset`.
    pub fn error_at(&self, offset: usize, message: impl Into<String>) -> Error {
        let (line, col) = self.line_col(offset);
        Error::Scene {
            path: self.path.clone(),
            line,
            col,
            message: message.into(),
        }
    }

    /// The directory relative paths in the scene are resolved against.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }
}

/// The scene file's top level: only the tables grinlight knows; each kept with its span.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    medium: Vec<Spanned<SpannedTable>>,
}

/// A validated scene, immutable and shareable across threads.
pub struct Scene {
    media: Vec<(String, Box<dyn Medium>)>,
    path: PathBuf,
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
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ))
            })
    }

    /// Names of all media, in file order.
    pub fn medium_names(&self) -> impl Iterator<Item = &str> {
        self.media.iter().map(|(n, _)| n.as_str())
    }
}

/// Parses and builds scene text (already read from `path`).
pub fn parse_scene(path: &Path, text: String) -> Result<Scene> {
    let source = Source {
        path: path.to_path_buf(),
        text,
    };
    let file: SceneFile = toml::from_str(&source.text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        let message = e.message().trim().replace('\n', " ");
        source.error_at(offset, message)
    })?;
    let mut media: Vec<(String, Box<dyn Medium>)> = Vec::new();
    for table in file.medium {
        let span = table.span();
        let mut t = TableReader::new(&source, span, "[[medium]]", table.into_inner());
        let name = t.string("name")?;
        t.check("name", !name.is_empty(), "must not be empty")?;
        t.check(
            "name",
            media.iter().all(|(n, _)| *n != name),
            format!("a medium named '{name}' is already defined"),
        )?;
        t.describe(format!("medium '{name}'"));
        let medium = read_medium(&mut t, source.dir())?;
        t.finish()?;
        media.push((name, medium));
    }
    Ok(Scene {
        media,
        path: source.path.clone(),
    })
}

/// Reads, parses and builds the scene file at `path`.
pub fn load_scene(path: &Path) -> Result<Scene> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_scene(path, text)
}
