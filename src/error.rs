//! The crate's one error type. No user input reaches a panic: every bad scene, file or flag
//! ends here with a message naming the file, line, column and key where it can.

use std::path::PathBuf;

/// Everything that can go wrong outside the numerical core.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// A scene file is malformed or inconsistent, at `line`:`col` (1-based).
    #[error("{path}:{line}:{col}: {message}")]
    Scene {
        /// The scene file.
        path: PathBuf,
        /// Line (1-based).
        line: usize,
        /// Column (1-based, in characters).
        col: usize,
        /// What is wrong, naming the key.
        message: String,
    },
    /// A scene given as data (see [`crate::scene::data`]) is malformed or inconsistent at
    /// `key`.
    #[error("{key}: {message}")]
    Key {
        /// The key's path from the top (`medium[0].radius`).
        key: String,
        /// What is wrong, naming the key.
        message: String,
    },
    /// A setting — one name, snake_case, for a `[render]` or `[camera]` key, a command-line
    /// option (`--` and dashes: `target_error` is `--target-error`) and a Python keyword —
    /// has a value it does not take. The front ends name it their own way.
    #[error("{key} {message}")]
    Setting {
        /// The setting's name.
        key: &'static str,
        /// What is wrong with its value (its range, the value given).
        message: String,
    },
    /// A command-line argument is invalid.
    #[error("{0}")]
    Usage(String),
    /// The run was interrupted (a signal) before it could produce its result.
    #[error("interrupted: {0}")]
    Interrupted(String),
    /// An image could not be encoded.
    #[error("{path}: {message}")]
    Image {
        /// The output file.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// A piece of the user's input shown in a message: at most 40 characters, then `…` (a file
/// of one endless word must not come back as a message of the same size).
pub fn cut(text: &str) -> String {
    const SHOWN: usize = 40;
    match text.char_indices().nth(SHOWN) {
        Some((end, _)) => format!("{}…", &text[..end]),
        None => text.to_string(),
    }
}

/// A number the user gave, for a message: in exponent form beyond 10⁶ in magnitude (1e300,
/// not three hundred digits), as written below it.
pub fn number(x: f64) -> String {
    match x.abs() >= 1e6 && x.is_finite() {
        true => format!("{x:e}"),
        false => format!("{x}"),
    }
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// `v` if it is a finite number in (0, 1e30], else an error naming the setting `key`.
pub fn positive(key: &'static str, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 && v <= MAX_MAGNITUDE {
        Ok(v)
    } else {
        Err(Error::Setting {
            key,
            message: format!(
                "must be a number in (0, {MAX_MAGNITUDE:e}], got {}",
                number(v)
            ),
        })
    }
}

/// The largest magnitude of a number the user gives (a scene file's, a command line's). Lengths, radiometric values and
/// coefficients are multiplied together (squared distances, powers over areas, photon powers
/// in f32): bounding every input at 1e30 keeps those products finite, where 1e308 would
/// give infinities and NaN pixels.
pub const MAX_MAGNITUDE: f64 = 1e30;
