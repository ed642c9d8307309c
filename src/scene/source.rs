//! A scene file's text and path: byte offsets turned into file:line:col messages, and the other
//! files the scene names.

use crate::error::Error;
use std::path::{Path, PathBuf};

/// A scene file's text with its path, for turning byte offsets into line:col messages, and
/// the other files it names (meshes, images, grids).
pub struct Source {
    /// The file.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// The files the scene reads besides itself, as resolved (see [`Source::input`]).
    pub(super) inputs: std::cell::RefCell<Vec<PathBuf>>,
    /// What the scene's user should know though the scene loads (file:line:col: message).
    pub(super) warnings: std::cell::RefCell<Vec<String>>,
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

    /// The path of a file the scene reads, `relative` to the scene's directory; remembered as
    /// one of the scene's inputs (which no output may overwrite).
    pub fn input(&self, relative: &str) -> PathBuf {
        let path = self.dir().join(relative);
        self.inputs.borrow_mut().push(path.clone());
        path
    }
}
