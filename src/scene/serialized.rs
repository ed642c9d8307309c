//! Mitsuba's `.serialized` meshes, the compressed format of its own scenes: a file of one or
//! more meshes, each a little-endian header (`0x041C`, version 3 or 4) and a zlib stream of
//! flags, (version 4) a name, the vertex and triangle counts, positions, normals and texture
//! coordinates when the flags say so (f32, or f64), vertex colours (read past) and u32 vertex
//! indices; a file of several ends with the offset of each (u64 in version 4, u32 in 3) and
//! their count (u32). Read as Mitsuba 3's `serialized` plugin reads them (its
//! `src/shapes/serialized.cpp`), into the OBJ reader's triangles.

use super::mesh::ObjTriangles;
use std::io::Read;
use std::path::Path;

/// The header's format identifier.
const MAGIC: u16 = 0x041C;

/// Per-vertex normals follow the positions.
const HAS_NORMALS: u32 = 0x0001;
/// Texture coordinates follow.
const HAS_TEXCOORDS: u32 = 0x0002;
/// Vertex colours follow (read past).
const HAS_COLORS: u32 = 0x0008;
/// The arrays are f64 (else f32).
const DOUBLE: u32 = 0x2000;

/// The triangles of mesh `index` (from 0) of the serialized file `path`. The error names the
/// file and what is wrong.
pub fn load_serialized(path: &Path, index: usize) -> Result<ObjTriangles, String> {
    let at = |why: String| format!("{}: {why}", path.display());
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    // Compressed: its triangles take several times the file.
    crate::resources::check_memory(size.saturating_mul(8), "reading this serialized mesh")
        .map_err(|e| at(e.to_string()))?;
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    parse(&bytes, index).map_err(at)
}

/// Mesh `index` of a serialized file's bytes.
pub fn parse(bytes: &[u8], index: usize) -> Result<ObjTriangles, String> {
    let u16_at = |i: usize| -> Option<u16> {
        Some(u16::from_le_bytes(bytes.get(i..i + 2)?.try_into().ok()?))
    };
    let (magic, version) = (u16_at(0), u16_at(2));
    if magic != Some(MAGIC) {
        return Err("not a Mitsuba serialized mesh (its first two bytes are not 0x041C)".into());
    }
    let version = version.unwrap_or(0);
    if version != 3 && version != 4 {
        return Err(format!(
            "version {version}: Mitsuba's serialized meshes are versions 3 and 4"
        ));
    }
    let start = match index {
        0 => 0,
        _ => offset(bytes, version, index)?,
    };
    if u16_at(start) != Some(MAGIC) || u16_at(start + 2) != Some(version) {
        return Err(format!(
            "mesh {index}: no mesh header where the file's table puts it"
        ));
    }
    let mut stream = flate2::read::ZlibDecoder::new(&bytes[start + 4..]);
    let mut data = Reader {
        stream: &mut stream,
        what: "the mesh's header",
    };
    let flags = data.u32()?;
    if version == 4 {
        // The mesh's name, null-terminated.
        while data.bytes::<1>()? != [0] {}
    }
    let vertices = data.u64()?;
    let triangles = data.u64()?;
    if vertices > u32::MAX as u64 || triangles > (u32::MAX / 3) as u64 {
        return Err(format!(
            "{vertices} vertices and {triangles} triangles: more than 32-bit indices hold"
        ));
    }
    let (vertices, triangles) = (vertices as usize, triangles as usize);
    // Each vertex and triangle takes at least 12 compressed bits of the file; a count the
    // file cannot hold is refused before anything is allocated for it.
    if vertices.saturating_add(triangles) > bytes.len().saturating_mul(8) {
        return Err(format!(
            "{vertices} vertices and {triangles} triangles in a file of {} bytes",
            bytes.len()
        ));
    }
    let double = flags & DOUBLE != 0;
    let floats = |data: &mut Reader<_>, n: usize, what: &'static str| -> Result<Vec<f32>, String> {
        data.what = what;
        Ok(match double {
            true => data
                .array(8 * n)?
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")) as f32)
                .collect(),
            false => data
                .array(4 * n)?
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
                .collect(),
        })
    };
    let positions = floats(&mut data, 3 * vertices, "the positions")?;
    if let Some(i) = positions.iter().position(|x| !x.is_finite()) {
        return Err(format!(
            "vertex {}: a position that is not finite",
            i / 3 + 1
        ));
    }
    let normals = match flags & HAS_NORMALS != 0 {
        true => Some(floats(&mut data, 3 * vertices, "the normals")?),
        false => None,
    };
    let texcoords = match flags & HAS_TEXCOORDS != 0 {
        true => Some(floats(&mut data, 2 * vertices, "the texture coordinates")?),
        false => None,
    };
    if flags & HAS_COLORS != 0 {
        floats(&mut data, 3 * vertices, "the vertex colours")?;
    }
    data.what = "the triangles";
    let indices = data.array(12 * triangles)?;
    let mut corners = Vec::with_capacity(triangles);
    for (t, tri) in indices.chunks_exact(12).enumerate() {
        let corner =
            |k: usize| u32::from_le_bytes(tri[4 * k..4 * k + 4].try_into().expect("4 bytes"));
        let tri = [corner(0), corner(1), corner(2)];
        if let Some(c) = tri.iter().find(|&&c| c as usize >= vertices) {
            return Err(format!(
                "triangle {}: corner {c} names no vertex (the mesh has {vertices})",
                t + 1
            ));
        }
        corners.push(tri);
    }
    let triples = |v: Vec<f32>| v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    Ok(ObjTriangles {
        positions: triples(positions),
        triangles: corners,
        normals: normals.map(triples),
        texcoords: texcoords.map(|v| v.chunks_exact(2).map(|c| [c[0], c[1]]).collect()),
    })
}

/// Where mesh `index` starts, from the table at the file's end.
fn offset(bytes: &[u8], version: u16, index: usize) -> Result<usize, String> {
    let n = bytes.len();
    let count = bytes
        .get(n.saturating_sub(4)..)
        .map(|b| u32::from_le_bytes(b.try_into().unwrap_or([0; 4])) as usize)
        .unwrap_or(0);
    if index >= count {
        return Err(format!(
            "mesh {index}: the file holds {count} (shape_index counts from 0)"
        ));
    }
    let width = match version {
        4 => 8,
        _ => 4,
    };
    let at = n
        .checked_sub(4 + width * (count - index))
        .ok_or("the table of meshes at the file's end is cut short")?;
    let raw = &bytes[at..at + width];
    let offset = match width {
        8 => u64::from_le_bytes(raw.try_into().expect("8 bytes")),
        _ => u32::from_le_bytes(raw.try_into().expect("4 bytes")) as u64,
    };
    match offset < n as u64 {
        true => Ok(offset as usize),
        false => Err(format!(
            "mesh {index}: its offset {offset} lies past the file's end"
        )),
    }
}

/// The decompressed stream, read in little-endian pieces; `what` names the part being read
/// for an error.
struct Reader<'a, R: Read> {
    stream: &'a mut R,
    what: &'static str,
}

impl<R: Read> Reader<'_, R> {
    fn bytes<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let mut b = [0u8; N];
        self.stream.read_exact(&mut b).map_err(|e| {
            format!(
                "{}: the compressed data ends early or is damaged ({e})",
                self.what
            )
        })?;
        Ok(b)
    }

    /// The next `n` bytes.
    fn array(&mut self, n: usize) -> Result<Vec<u8>, String> {
        let mut b = Vec::new();
        self.stream
            .take(n as u64)
            .read_to_end(&mut b)
            .map_err(|e| {
                format!(
                    "{}: the compressed data ends early or is damaged ({e})",
                    self.what
                )
            })?;
        match b.len() == n {
            true => Ok(b),
            false => Err(format!("{}: the compressed data ends early", self.what)),
        }
    }

    fn u32(&mut self) -> Result<u32, String> {
        self.bytes::<4>().map(u32::from_le_bytes)
    }

    fn u64(&mut self) -> Result<u64, String> {
        self.bytes::<8>().map(u64::from_le_bytes)
    }
}
