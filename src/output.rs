//! Writing results without ever destroying a user's file.
//!
//! Every file a command writes is first declared in an [`Outputs`] plan, which is checked
//! before any work starts: the directory must exist and take a new file; the path must not be
//! one of the run's inputs (the scene, a mesh, an environment map, a grid) nor another output
//! of the same run; and a file already there is replaced only if grinlight wrote it — every
//! file it writes says so ([`signature`]: an EXR's `software` attribute, a PNG's `Software`
//! text chunk, a CSV's first line, a partial's magic number) — never a user's image, table,
//! scene or anything else.
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

/// Whether `path` ends in `.exr` (any case).
pub fn is_exr(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// What every file grinlight writes says of itself: `grinlight` and its version.
pub fn signature() -> String {
    format!("grinlight {}", env!("CARGO_PKG_VERSION"))
}

/// How much of a file's start is read to find its signature (an EXR's header holds its
/// attributes, a PNG's text chunk comes before its image data).
const SIGNED_WITHIN: usize = 1 << 16;

/// The first words of a scene file `grinlight convert` writes.
pub const CONVERTED: &str = "# Converted by grinlight ";

/// What kind of file an output is: what an existing file at its path must look like to be
/// replaced — one grinlight wrote.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An OpenEXR image (magic number 76 2f 31 01) whose `software` attribute is grinlight's.
    Exr,
    /// A PNG image whose `Software` text chunk is grinlight's.
    Png,
    /// A CSV table whose first line is `# grinlight …` ([`write_csv`]).
    Csv,
    /// A grinlight partial result (see [`crate::shard`]).
    Partial,
    /// A scene file `grinlight convert` wrote, whose first line is `# Converted by grinlight `.
    ConvertedScene,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Exr => "an EXR image grinlight wrote",
            Kind::Png => "a PNG image grinlight wrote",
            Kind::Csv => "a CSV table grinlight wrote",
            Kind::Partial => "a grinlight partial result",
            Kind::ConvertedScene => "a scene file grinlight converted",
        }
    }

    /// Whether the start of a file's content is a file of this kind that grinlight wrote.
    fn recognises(self, head: &[u8]) -> bool {
        let find = |needle: &[u8]| head.windows(needle.len()).position(|w| w == needle);
        match self {
            Kind::Exr => {
                // The attribute: its name, its type, a 4-byte length, then the text.
                let attribute = b"software\0string\0";
                head.starts_with(&[0x76, 0x2f, 0x31, 0x01])
                    && find(attribute).is_some_and(|at| {
                        head[at + attribute.len()..]
                            .get(4..)
                            .is_some_and(|text| text.starts_with(b"grinlight "))
                    })
            }
            Kind::Partial => head.starts_with(PARTIAL_MAGIC),
            Kind::Png => {
                head.starts_with(b"\x89PNG\r\n\x1a\n")
                    && find(b"tEXtSoftware\0grinlight ").is_some()
            }
            Kind::Csv => head.starts_with(b"# grinlight "),
            Kind::ConvertedScene => head.starts_with(CONVERTED.as_bytes()),
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
            let mut head = Vec::new();
            std::fs::File::open(path)
                .and_then(|f| f.take(SIGNED_WITHIN as u64).read_to_end(&mut head))
                .map_err(|e| Error::io(path, e))?;
            let read = head.len();
            if meta.len() > 0 && !kind.recognises(&head[..read]) {
                return refuse(format!(
                    "exists and is not {}: refusing to overwrite it (move it or choose another output)",
                    kind.name()
                ));
            }
        }
        remove_stale_temporaries(dir, name);
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

/// Removes the temporary files of the output `name` in `dir` that a grinlight process killed
/// while writing it left behind (`.NAME.grinlight-PID-N.tmp` whose process PID no longer runs). Temporary
/// files of running processes, and every other file, are left alone.
fn remove_stale_temporaries(dir: &Path, name: &std::ffi::OsStr) {
    if !Path::new("/proc/self").exists() {
        return; // No way to tell which processes run: leave every file.
    }
    let prefix = temporary_prefix(name);
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = file
            .strip_prefix(&prefix)
            .and_then(|rest| rest.strip_suffix(".tmp"))
            .and_then(|rest| rest.split_once('-'))
            .and_then(|(pid, n)| n.parse::<u64>().ok().and(pid.parse::<u32>().ok()))
        else {
            continue;
        };
        let running = Path::new("/proc").join(pid.to_string()).exists();
        if !running && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// The start of the name of every temporary file grinlight writes for an output named
/// `name`: `.NAME.grinlight-`, then `PID-N.tmp`.
fn temporary_prefix(name: &std::ffi::OsStr) -> String {
    format!(".{}.grinlight-", name.to_string_lossy())
}

/// A fresh temporary path beside `path` (hidden, named after it and this process).
fn temporary(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let prefix = temporary_prefix(path.file_name().unwrap_or_default());
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!("{prefix}{}-{n}.tmp", std::process::id()))
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
        let staged = GROUP.with_borrow_mut(|group| match group {
            Some(files) => {
                files.push((tmp.clone(), path.to_path_buf()));
                true
            }
            None => false,
        });
        if staged {
            return Ok(());
        }
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    };
    let result = finish();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

std::thread_local! {
    /// The files written so far inside [`together`] on this thread: (temporary, target).
    static GROUP: std::cell::RefCell<Option<Vec<(PathBuf, PathBuf)>>> =
        const { std::cell::RefCell::new(None) };
}

/// Runs `write`, whose files (every [`write_atomic`] on this thread) land together: each is
/// written complete to its temporary file first, and only when all are written are they
/// renamed into place — so a disk that fills, or an error, part way leaves every previous
/// file as it was (no new EXR beside an old PNG). On failure the temporary files are removed.
pub fn together<T>(write: impl FnOnce() -> Result<T>) -> Result<T> {
    let outer = GROUP.with_borrow_mut(|g| g.replace(Vec::new()));
    let result = write();
    let files = GROUP
        .with_borrow_mut(|g| std::mem::replace(g, outer))
        .expect("the group set above");
    let nested = GROUP.with_borrow(|g| g.is_some());
    let renamed = result.and_then(|value| {
        if nested {
            // An enclosing group renames them with its own.
            GROUP.with_borrow_mut(|g| g.as_mut().expect("nested").extend(files.iter().cloned()));
            return Ok(value);
        }
        for (tmp, path) in &files {
            std::fs::rename(tmp, path).map_err(|e| Error::io(path, e))?;
        }
        Ok(value)
    });
    if renamed.is_err() {
        for (tmp, _) in &files {
            let _ = std::fs::remove_file(tmp);
        }
    }
    renamed
}

/// Writes a CSV table to `path` atomically: a first line `# grinlight VERSION: what` (a
/// comment to CSV readers that take one: pandas' `comment="#"`), then `table`.
pub fn write_csv(path: &Path, what: &str, table: &str) -> Result<()> {
    write_text(path, &format!("# {}: {what}\n{table}", signature()))
}

/// Writes `text` to `path` atomically.
pub fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |tmp| {
        std::fs::write(tmp, text).map_err(|e| Error::io(path, e))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Files written together land together: when the second of two writes fails (a full
    /// disk, say), the first file keeps its previous content and no temporary file is left;
    /// when both succeed, both are replaced.
    #[test]
    fn files_written_together_land_together() {
        let dir = std::env::temp_dir().join(format!("grinlight-together-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
        write_text(&a, "x\n1\n").unwrap();
        write_text(&b, "x\n1\n").unwrap();
        let failed = together(|| {
            write_text(&a, "x\n2\n")?;
            write_atomic(&b, |_| Err(Error::Usage("no space left".into())))
        });
        assert!(failed.is_err());
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "x\n1\n");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "x\n1\n");
        together(|| {
            together(|| write_text(&a, "x\n3\n"))?;
            assert_eq!(
                std::fs::read_to_string(&a).unwrap(),
                "x\n1\n",
                "not before the end"
            );
            write_text(&b, "x\n3\n")
        })
        .unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "x\n3\n");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "x\n3\n");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names.len(), 2, "{names:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A temporary file of a process that no longer runs is removed when its output is
    /// planned again; a running process's (this one's) and other files stay.
    #[test]
    fn stale_temporaries_are_removed() {
        let dir = std::env::temp_dir().join(format!("grinlight-stale-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("m.exr");
        // PID 4194305 exceeds Linux's largest (2²²): no process has it.
        let stale = dir.join(".m.exr.grinlight-4194305-0.tmp");
        let live = dir.join(format!(".m.exr.grinlight-{}-99.tmp", std::process::id()));
        let other = dir.join(".m.exr.notes.tmp");
        for f in [&stale, &live, &other] {
            std::fs::write(f, "x").unwrap();
        }
        Outputs::new(Vec::<PathBuf>::new())
            .add(&out, Kind::Exr)
            .unwrap();
        assert!(!stale.exists());
        assert!(live.exists() && other.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
