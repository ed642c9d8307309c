//! Writing results without ever destroying a user's file.
//!
//! Every file a command writes is first declared in an [`Outputs`] plan, which is checked
//! before any work starts: the directory must exist and take a new file; the path must not be
//! one of the run's inputs (the scene, a mesh, an environment map, a grid) nor another output
//! of the same run; and a file already there is replaced only if it is a file of the kind the
//! run writes (an EXR, a PNG, a CSV) that may be written, never a scene or anything else.
//!
//! Then each file is written by [`write_atomic`]: into a temporary file in the same directory,
//! renamed over the target only once it is complete, so a crash, a kill or a full disk leaves
//! either the previous file or the new one, never a truncated one.

use crate::error::{Error, Result};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The first bytes of a grinlight partial result of any version ([`crate::shard::file`]).
pub const PARTIAL_MAGIC: &[u8] = b"GRINLIGHT PARTIAL ";

/// What kind of file an output is: what an existing file at its path must look like to be
/// replaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An OpenEXR image (magic number 76 2f 31 01).
    Exr,
    /// A PNG image.
    Png,
    /// A CSV table whose first line is a header of lower-case names separated by commas.
    Csv,
    /// A grinlight partial result (see [`crate::shard`]).
    Partial,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Exr => "an EXR image",
            Kind::Png => "a PNG image",
            Kind::Csv => "a CSV table",
            Kind::Partial => "a grinlight partial result",
        }
    }

    /// Whether the start of a file's content is a file of this kind.
    fn recognises(self, head: &[u8]) -> bool {
        match self {
            Kind::Exr => head.starts_with(&[0x76, 0x2f, 0x31, 0x01]),
            Kind::Partial => head.starts_with(PARTIAL_MAGIC),
            Kind::Png => head.starts_with(b"\x89PNG\r\n\x1a\n"),
            Kind::Csv => {
                let line = head.split(|&b| b == b'\n').next().unwrap_or_default();
                !line.is_empty()
                    && line.split(|&b| b == b',').all(|name| {
                        !name.is_empty()
                            && name
                                .iter()
                                .all(|&b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_')
                    })
            }
        }
    }
}

/// The files a run reads and writes, checked before any work.
#[derive(Debug, Default)]
pub struct Outputs {
    /// The run's inputs, resolved (absolute, symbolic links followed).
    inputs: Vec<PathBuf>,
    /// The planned outputs: (resolved, as given).
    planned: Vec<(PathBuf, PathBuf)>,
}

impl Outputs {
    /// A plan for a run that reads `inputs` (files that do not exist are ignored).
    pub fn new<P: AsRef<Path>>(inputs: impl IntoIterator<Item = P>) -> Self {
        Self {
            inputs: inputs
                .into_iter()
                .filter_map(|p| p.as_ref().canonicalize().ok())
                .collect(),
            planned: Vec::new(),
        }
    }

    /// Declares that the run will write `path` as a file of `kind`; refuses (with the reason)
    /// when that could destroy or clash with anything, or when the directory cannot take it.
    pub fn add(&mut self, path: &Path, kind: Kind) -> Result<()> {
        let refuse = |why: String| Err(Error::Usage(format!("{}: {why}", path.display())));
        let Some(name) = path.file_name() else {
            return refuse("is not a file name".into());
        };
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        if !dir.is_dir() {
            return refuse(format!("the directory {} does not exist", dir.display()));
        }
        let resolved = match path.canonicalize() {
            Ok(p) => p,
            Err(_) => dir
                .canonicalize()
                .map_err(|e| Error::io(dir, e))?
                .join(name),
        };
        if self.inputs.contains(&resolved) {
            return refuse(
                "is an input of this run (the scene or a file it reads): refusing to overwrite it"
                    .into(),
            );
        }
        if let Some((_, other)) = self.planned.iter().find(|(r, _)| *r == resolved) {
            return refuse(format!(
                "this run would write two outputs to one file (also as {}): choose other names",
                other.display()
            ));
        }
        if let Ok(meta) = std::fs::metadata(path) {
            if !meta.is_file() {
                return refuse("exists and is not a regular file".into());
            }
            if meta.permissions().readonly() {
                return refuse("exists and is read-only: refusing to replace it".into());
            }
            let mut head = [0u8; 256];
            let read = std::fs::File::open(path)
                .and_then(|mut f| f.read(&mut head))
                .map_err(|e| Error::io(path, e))?;
            if meta.len() > 0 && !kind.recognises(&head[..read]) {
                return refuse(format!(
                    "exists and is not {}: refusing to overwrite it (move it or choose another output)",
                    kind.name()
                ));
            }
        }
        // The directory must take a new file (the temporary one the output is written to).
        let probe = temporary(path);
        std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&probe)
            .map_err(|e| {
                Error::Usage(format!(
                    "{}: cannot write in {}: {e}",
                    path.display(),
                    dir.display()
                ))
            })?;
        let _ = std::fs::remove_file(&probe);
        self.planned.push((resolved, path.to_path_buf()));
        Ok(())
    }
}

/// A fresh temporary path beside `path` (hidden, named after it and this process).
fn temporary(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.grinlight-{}-{n}.tmp", std::process::id()))
}

/// Writes `path` atomically: `write` fills a temporary file beside it (it is given that
/// file's path), which is flushed to disk and renamed over `path` only if `write` succeeded.
/// On any failure the previous file at `path`, if any, is left as it was and the temporary
/// file is removed.
pub fn write_atomic(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let tmp = temporary(path);
    let finish = || -> Result<()> {
        write(&tmp)?;
        std::fs::File::open(&tmp)
            .and_then(|f| f.sync_all())
            .map_err(|e| Error::io(&tmp, e))?;
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    };
    let result = finish();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Writes `text` to `path` atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |tmp| {
        std::fs::write(tmp, text).map_err(|e| Error::io(path, e))
    })
}
