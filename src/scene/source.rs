//! A scene's text and path: byte offsets turned into file:line:col messages (or, for a scene
//! given as data, key paths), and the other files the scene names.

use super::data::SceneText;
use crate::error::Error;
use std::path::{Path, PathBuf};

/// A scene's text with its path, for turning byte offsets into line:col messages, and the
/// other files it names (meshes, images, grids).
pub struct Source {
    /// The file (for a scene given as data, a name in the directory its relative paths
    /// are resolved against).
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// For a scene given as data: where each key went in `text` (errors name the key's path).
    pub data: Option<Vec<super::data::KeyPlace>>,
    /// The files the scene reads besides itself, as resolved (see [`Source::input`]).
    pub(super) inputs: std::cell::RefCell<Vec<PathBuf>>,
    /// What the scene's user should know though the scene loads (file:line:col: message).
    pub(super) warnings: std::cell::RefCell<Vec<String>>,
}

/// The file name a scene given as data goes by (in messages and partial results).
pub const DATA_NAME: &str = "<scene data>";

impl Source {
    /// 1-based line and column (in characters) of byte `offset`.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    }

    /// A file's source.
    pub fn file(path: PathBuf, text: String) -> Self {
        Source {
            path,
            text,
            data: None,
            inputs: Default::default(),
            warnings: Default::default(),
        }
    }

    /// The source of a scene given as data, its relative paths resolved in `dir`.
    pub fn data(text: SceneText, dir: &Path) -> Self {
        Source {
            path: dir.join(DATA_NAME),
            text: text.text,
            data: Some(text.keys),
            inputs: Default::default(),
            warnings: Default::default(),
        }
    }

    /// An error at byte `offset`: at its file's line and column, or its data's key.
    pub fn error_at(&self, offset: usize, message: impl Into<String>) -> Error {
        if let Some(keys) = &self.data {
            let key = super::data::key_at(keys, offset, self.text.len());
            return Error::Key {
                key: key.unwrap_or("top level").to_string(),
                message: message.into(),
            };
        }
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

    /// The path of a file the scene reads, `relative` to the scene's directory; remembered as
    /// one of the scene's inputs (which no output may overwrite).
    pub fn input(&self, relative: &str) -> PathBuf {
        let path = self.dir().join(relative);
        self.inputs.borrow_mut().push(path.clone());
        path
    }
}
