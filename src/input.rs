//! Reading a user's files without hanging or swallowing the machine: every input (a scene, a
//! mesh, an image, a grid, a partial result) must be a regular file — a FIFO, a device such as
//! `/dev/zero` or a directory would block forever or never end — and text read whole is
//! bounded in size.

use crate::error::{Error, Result};
use std::io::Read;
use std::path::Path;

/// The largest scene file read (bytes): a scene is a page of keys; its bulk data (meshes,
/// grids, images) lives in files of their own.
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

/// Why `path` cannot be read as an input, if it cannot: it must be a regular file (checked
/// without opening it, so a FIFO does not block). A path that does not exist passes (opening
/// it then says so).
pub fn not_regular(path: &Path) -> Option<String> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => None,
        Ok(m) if m.is_dir() => Some("is a directory, not a file".into()),
        Ok(_) => Some(
            "is not a regular file (a pipe, a device or a socket): grinlight reads inputs from \
             regular files only"
                .into(),
        ),
        Err(_) => None,
    }
}

/// Refuses `path` (naming it) unless it is a regular file.
pub fn check_regular(path: &Path) -> Result<()> {
    match not_regular(path) {
        Some(why) => Err(Error::Usage(format!("{}: {why}", path.display()))),
        None => Ok(()),
    }
}

/// The text of the regular file `path`, refused (naming it) when it is larger than `limit`
/// bytes (`what` says what the file is, for the message).
pub fn read_text(path: &Path, limit: u64, what: &str) -> Result<String> {
    check_regular(path)?;
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path, e))?;
    if bytes.len() as u64 > limit {
        return Err(Error::Usage(format!(
            "{}: larger than {} MiB: not {what}",
            path.display(),
            limit >> 20
        )));
    }
    String::from_utf8(bytes).map_err(|e| {
        Error::Usage(format!(
            "{}: not UTF-8 text (byte {}): not {what}",
            path.display(),
            e.utf8_error().valid_up_to()
        ))
    })
}
