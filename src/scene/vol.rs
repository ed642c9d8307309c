//! Mitsuba's `.vol` volume grids (its `gridvolume` files): the bytes `VOL` and version 3, then
//! little-endian i32s — the encoding (1: f32, the one Mitsuba 3 reads), the resolution along x,
//! y and z, the channels — six f32s of a bounding box, and the values, x fastest then y then z,
//! a value's channels together. Read for a medium's density, one channel; the box is not read
//! (Mitsuba 3 places a grid by its `to_world` too: the import turns that into the scene's
//! `density_bounds`).

use std::path::Path;

/// What the header says of a grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// Values along x, y and z.
    pub dims: [usize; 3],
    /// Numbers a value holds.
    pub channels: usize,
}

/// The header's size in bytes: `VOL`, the version, five i32s and six f32s.
const HEADER_BYTES: usize = 48;

/// The most values a grid may hold (4 GiB of f64, as a VDB file's).
const MAX_VALUES: u64 = 1 << 29;

/// The header of the `.vol` file at `path`. Errors say what is wrong, not where (the caller
/// names the file and the scene key).
pub fn header(path: &Path) -> Result<Header, String> {
    use std::io::Read;
    let mut bytes = Vec::with_capacity(HEADER_BYTES);
    std::fs::File::open(path)
        .and_then(|f| f.take(HEADER_BYTES as u64).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read: {e}"))?;
    parse_header(&bytes)
}

/// The values of the one-channel `.vol` file at `path` and their resolution, x fastest. The
/// header is checked against the file's size before anything else is read.
pub fn read(path: &Path) -> Result<([usize; 3], Vec<f64>), String> {
    let h = header(path)?;
    if h.channels != 1 {
        return Err(format!(
            "{} channels: a density is one number a node",
            h.channels
        ));
    }
    let count: usize = h.dims.iter().product();
    let size = std::fs::metadata(path)
        .map_err(|e| format!("cannot read: {e}"))?
        .len();
    let data = size.saturating_sub(HEADER_BYTES as u64);
    if data != 4 * count as u64 {
        return Err(format!(
            "{data} bytes of values where {} × {} × {} f32 values take {}",
            h.dims[0],
            h.dims[1],
            h.dims[2],
            4 * count
        ));
    }
    crate::resources::check_memory(8 * count as u64, "reading this volume")
        .map_err(|e| e.to_string())?;
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read: {e}"))?;
    let values = bytes[HEADER_BYTES..]
        .chunks_exact(4)
        .map(|b| f64::from(f32::from_le_bytes(b.try_into().expect("4 bytes"))))
        .collect();
    Ok((h.dims, values))
}

fn parse_header(bytes: &[u8]) -> Result<Header, String> {
    if bytes.len() < HEADER_BYTES || &bytes[..3] != b"VOL" {
        return Err(
            "not a Mitsuba volume (it does not start with \"VOL\" and a 48-byte header)".into(),
        );
    }
    if bytes[3] != 3 {
        return Err(format!(
            "version {}: Mitsuba's volumes are version 3",
            bytes[3]
        ));
    }
    let int = |k: usize| i32::from_le_bytes(bytes[4 + 4 * k..8 + 4 * k].try_into().expect("4"));
    let encoding = int(0);
    if encoding != 1 {
        return Err(format!(
            "encoding {encoding}: Mitsuba 3 reads f32 volumes (encoding 1) only"
        ));
    }
    let [x, y, z, channels] = [int(1), int(2), int(3), int(4)];
    if [x, y, z, channels].iter().any(|&n| n < 1) {
        return Err(format!(
            "a resolution of {x} × {y} × {z} with {channels} channels: each must be ≥ 1"
        ));
    }
    let dims = [x, y, z].map(|n| n as usize);
    let total = dims.iter().map(|&n| n as u64).product::<u64>() * channels as u64;
    if total > MAX_VALUES {
        return Err(format!(
            "{x} × {y} × {z} × {channels} values: more than the {MAX_VALUES} a grid may hold"
        ));
    }
    Ok(Header {
        dims,
        channels: channels as usize,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(version: u8, encoding: i32, dims: [i32; 3], channels: i32, values: &[f32]) -> Vec<u8> {
        let mut b = b"VOL".to_vec();
        b.push(version);
        for n in [encoding, dims[0], dims[1], dims[2], channels] {
            b.extend(n.to_le_bytes());
        }
        for x in [0f32, 0.0, 0.0, 1.0, 1.0, 1.0] {
            b.extend(x.to_le_bytes());
        }
        for v in values {
            b.extend(v.to_le_bytes());
        }
        b
    }

    /// Values come back in the file's order (x fastest), and every damaged header or body is
    /// refused with what is wrong.
    #[test]
    fn values_read_in_order_and_damage_is_named() {
        let dir = std::env::temp_dir().join(format!("grinlight-vol-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("g.vol");
        let values: Vec<f32> = (0..12).map(|i| i as f32 * 0.5).collect();
        std::fs::write(&path, file(3, 1, [3, 2, 2], 1, &values)).unwrap();
        let (dims, got) = read(&path).unwrap();
        assert_eq!(dims, [3, 2, 2]);
        assert_eq!(got, values.iter().map(|&v| v as f64).collect::<Vec<_>>());
        assert_eq!(
            header(&path).unwrap(),
            Header {
                dims: [3, 2, 2],
                channels: 1
            }
        );
        for (bytes, words) in [
            (b"VOX".to_vec(), "not a Mitsuba volume"),
            (file(2, 1, [3, 2, 2], 1, &values), "version 2"),
            (file(3, 2, [3, 2, 2], 1, &values), "encoding 2"),
            (file(3, 1, [3, 0, 2], 1, &[]), "each must be ≥ 1"),
            (file(3, 1, [3, 2, 2], 3, &values), "3 channels"),
            (
                file(3, 1, [3, 2, 2], 1, &values[..11]),
                "44 bytes of values",
            ),
            (file(3, 1, [1 << 12, 1 << 12, 1 << 12], 1, &[]), "more than"),
        ] {
            std::fs::write(&path, bytes).unwrap();
            let e = read(&path).unwrap_err();
            assert!(e.contains(words), "{e}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }
}
