//! Reading a scene file: TOML text ⇒ [`SceneDesc`] ⇒ [`Scene`], with every error located at
//! file:line:col.

use super::build::{build, Scene};
use super::desc::SceneDesc;
use crate::error::{Error, Result};
use std::ops::Range;
use std::path::{Path, PathBuf};

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

    /// An error about `key` inside the table spanning `table`: located at the key's own line
    /// when it is written there, else at the table.
    pub fn key_error(&self, table: Range<usize>, key: &str, message: impl Into<String>) -> Error {
        let offset = self.find_key(table.clone(), key).unwrap_or(table.start);
        self.error_at(offset, format!("key `{key}`: {}", message.into()))
    }

    fn find_key(&self, table: Range<usize>, key: &str) -> Option<usize> {
        let body = self.text.get(table.clone())?;
        let mut at = 0;
        for line in body.split_inclusive('\n') {
            let trimmed = line.trim_start();
            if let Some(rest) = trimmed.strip_prefix(key) {
                if rest.trim_start().starts_with('=') {
                    return Some(table.start + at + (line.len() - trimmed.len()));
                }
            }
            at += line.len();
        }
        None
    }

    /// The directory relative paths in the scene are resolved against.
    pub fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }
}

/// Parses scene text (already read from `path`).
pub fn parse_scene(path: &Path, text: String) -> Result<Scene> {
    let source = Source {
        path: path.to_path_buf(),
        text,
    };
    let desc: SceneDesc = toml::from_str(&source.text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        source.error_at(offset, e.message().trim().to_string())
    })?;
    build(&source, desc)
}

/// Reads, parses and builds the scene file at `path`.
pub fn load_scene(path: &Path) -> Result<Scene> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_scene(path, text)
}
