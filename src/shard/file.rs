//! The partial-result file: what is checked before a byte of it is trusted.
//!
//! ```text
//! GRINLIGHT PARTIAL <version>\n        the magic line
//! header length      u32, little-endian
//! header             postcard: the Header
//! header checksum    u64 LE, FNV-1a of the header bytes
//! payload length     u64 LE
//! payload            postcard: the whole Partial (its header again, then the sums)
//! payload checksum   u64 LE, FNV-1a of the payload bytes
//! ```
//!
//! A reader checks the magic line (naming another version's), the header's length and
//! checksum, and that the file is exactly as long as its lengths say — all before the payload
//! is read — so a merge can compare every partial's header first, and a truncated, grown or
//! damaged file is refused rather than merged. FNV-1a detects every change of a single byte
//! (each step is a bijection of the running hash) and a random corruption with probability
//! 1 − 2⁻⁶⁴.

use super::{Header, Partial};
use crate::error::{Error, Result};
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// The version of the partial file written (the magic line's last word).
pub const VERSION: u32 = 3;

/// The magic line's words before the version.
const MAGIC_WORDS: &[u8] = b"GRINLIGHT PARTIAL ";

/// The largest header read (bytes): a header is a few hundred.
const MAX_HEADER: u32 = 1 << 20;

/// The magic line of this version.
pub fn magic() -> Vec<u8> {
    format!("GRINLIGHT PARTIAL {VERSION}\n").into_bytes()
}

/// FNV-1a (64-bit) of `bytes`, continuing from `h` (start with [`FNV_START`]).
pub fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// FNV-1a's offset basis.
pub const FNV_START: u64 = 0xcbf2_9ce4_8422_2325;

/// The bytes of the file of `partial`.
pub fn encode(partial: &Partial) -> std::result::Result<Vec<u8>, postcard::Error> {
    let header = postcard::to_stdvec(&partial.header)?;
    let payload = postcard::to_stdvec(partial)?;
    let mut out = magic();
    out.extend((header.len() as u32).to_le_bytes());
    out.extend(&header);
    out.extend(fnv1a(FNV_START, &header).to_le_bytes());
    out.extend((payload.len() as u64).to_le_bytes());
    out.extend(&payload);
    out.extend(fnv1a(FNV_START, &payload).to_le_bytes());
    Ok(out)
}

/// A partial file whose header has been read and checked, its payload not yet.
pub struct Opened {
    file: std::fs::File,
    path: std::path::PathBuf,
    /// The header, its checksum verified.
    pub header: Header,
    payload_len: u64,
}

/// A damaged or foreign file, named.
pub(super) fn damaged(path: &Path, why: impl std::fmt::Display) -> Error {
    Error::Usage(format!(
        "{}: a damaged partial result ({why}): refusing to use it (render that shard again)",
        path.display()
    ))
}

impl Opened {
    /// Opens the partial file at `path` and reads and checks its header (see the module's
    /// documentation); the payload is left unread.
    pub fn open(path: &Path) -> Result<Opened> {
        crate::input::check_regular(path)?;
        let mut file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
        let size = file.metadata().map_err(|e| Error::io(path, e))?.len();
        let mut head = Vec::new();
        (&mut file)
            .take(MAGIC_WORDS.len() as u64 + 12)
            .read_to_end(&mut head)
            .map_err(|e| Error::io(path, e))?;
        let Some(rest) = head.strip_prefix(MAGIC_WORDS) else {
            return Err(Error::Usage(format!(
                "{}: not a grinlight partial result (made by `render --shard`)",
                path.display()
            )));
        };
        let line = rest.split(|&b| b == b'\n').next().unwrap_or_default();
        if line != VERSION.to_string().as_bytes() {
            return Err(Error::Usage(format!(
                "{}: a partial result of file version {} (this grinlight {} reads version \
                 {VERSION}): merge or resume it with the grinlight that made it",
                path.display(),
                String::from_utf8_lossy(line),
                env!("CARGO_PKG_VERSION"),
            )));
        }
        let start = magic().len() as u64;
        file.seek(SeekFrom::Start(start))
            .map_err(|e| Error::io(path, e))?;
        let mut read = |n: u64, what: &str| -> Result<Vec<u8>> {
            let mut buf = Vec::new();
            (&mut file)
                .take(n)
                .read_to_end(&mut buf)
                .map_err(|e| Error::io(path, e))?;
            if (buf.len() as u64) < n {
                return Err(damaged(path, format!("it ends inside its {what}")));
            }
            Ok(buf)
        };
        let word = |b: &[u8]| u64::from_le_bytes(b.try_into().expect("8 bytes"));
        let header_len = u32::from_le_bytes(read(4, "header")?.try_into().expect("4 bytes"));
        if header_len > MAX_HEADER {
            return Err(damaged(path, format!("a header of {header_len} bytes")));
        }
        let header_bytes = read(header_len as u64, "header")?;
        let sums = read(16, "header")?;
        if word(&sums[..8]) != fnv1a(FNV_START, &header_bytes) {
            return Err(damaged(path, "its header's checksum does not match"));
        }
        let payload_len = word(&sums[8..]);
        let expected = (start + 4 + header_len as u64 + 16)
            .checked_add(payload_len)
            .and_then(|n| n.checked_add(8));
        if expected != Some(size) {
            return Err(damaged(
                path,
                format!(
                    "{size} bytes where its lengths say {}",
                    expected.unwrap_or(0)
                ),
            ));
        }
        let header = postcard::from_bytes(&header_bytes)
            .map_err(|e| damaged(path, format!("its header does not decode: {e}")))?;
        Ok(Opened {
            file,
            path: path.to_path_buf(),
            header,
            payload_len,
        })
    }

    /// Reads the payload, checks its checksum, decodes it and checks the result is whole and
    /// consistent ([`Partial::check`]) and of the header read.
    pub fn payload(mut self) -> Result<Partial> {
        let path = &self.path;
        let mut payload = Vec::new();
        (&mut self.file)
            .take(self.payload_len + 8)
            .read_to_end(&mut payload)
            .map_err(|e| Error::io(path, e))?;
        let sum = payload.split_off(self.payload_len as usize);
        if sum.len() != 8
            || u64::from_le_bytes(sum.try_into().expect("8 bytes")) != fnv1a(FNV_START, &payload)
        {
            return Err(damaged(path, "its payload's checksum does not match"));
        }
        let partial: Partial = postcard::from_bytes(&payload)
            .map_err(|e| damaged(path, format!("its payload does not decode: {e}")))?;
        if partial.header != self.header {
            return Err(damaged(path, "its payload is of another header"));
        }
        partial.check().map_err(|why| damaged(path, why))?;
        Ok(partial)
    }
}
