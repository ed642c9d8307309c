//! Stanford PLY meshes (Turk 1994), the format scanned meshes ship in: ASCII and binary (little
//! and big endian). The `vertex` element's `x`, `y`, `z` (and `nx`, `ny`, `nz` normals and `s`,
//! `t` or `u`, `v` texture coordinates when it has them) and the `face` element's index list
//! (`vertex_indices` or `vertex_index`; faces fanned from their first corner) are kept; every
//! other element and property is read past. Scalars of any PLY type are read as f64 and stored
//! as the OBJ reader's are: positions in f32, indices in u32.

use super::mesh::ObjTriangles;
use std::path::Path;

/// The triangles of a PLY file (gzip-compressed when its name ends in `.gz`, as pbrt's scenes
/// ship them). The error names the file and what is wrong: the header line, or the element
/// and record (1-based) where the data is not what the header says.
pub fn load_ply(path: &Path) -> Result<ObjTriangles, String> {
    let at = |why: String| format!("{}: {why}", path.display());
    let gzipped = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
    // The file is read whole, and its triangles take about as much again (a compressed one
    // perhaps five times as much): refused at once where the machine has not the room.
    let size = std::fs::metadata(path).map_or(0, |m| m.len());
    let factor = if gzipped { 12 } else { 3 };
    crate::resources::check_memory(size.saturating_mul(factor), "reading this PLY file")
        .map_err(|e| at(e.to_string()))?;
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let bytes = match gzipped {
        true => {
            let mut plain = Vec::new();
            std::io::Read::read_to_end(&mut flate2::read::GzDecoder::new(&bytes[..]), &mut plain)
                .map_err(|e| at(format!("the gzip-compressed data is damaged ({e})")))?;
            plain
        }
        false => bytes,
    };
    parse(&bytes).map_err(at)
}

/// How the records are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Ascii,
    Little,
    Big,
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Self> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Bytes in binary.
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }
}

/// A property of an element: one scalar, or a list (its count's type and its items').
#[derive(Clone, Debug, PartialEq)]
struct Property {
    name: String,
    count: Option<Scalar>,
    item: Scalar,
}

/// An element of the header: its name, how many records, and their properties.
#[derive(Clone, Debug, PartialEq)]
struct Element {
    name: String,
    records: usize,
    properties: Vec<Property>,
}

/// The header: the format, the elements in order, and where the data starts.
struct Header {
    format: Format,
    elements: Vec<Element>,
    data: usize,
}

fn header(bytes: &[u8]) -> Result<Header, String> {
    // `end_header` on a line of its own (a comment may say it too).
    let end = (0..bytes.len())
        .filter(|&i| i == 0 || bytes[i - 1] == b'\n')
        .find(|&i| {
            let rest = &bytes[i..];
            rest.starts_with(b"end_header")
                && matches!(rest.get(10), None | Some(b'\n') | Some(b'\r'))
        })
        .ok_or("not a PLY file: no `end_header` line")?;
    let text = std::str::from_utf8(&bytes[..end]).map_err(|_| "a header that is not text")?;
    let mut data = end + b"end_header".len();
    // The header's last line ends with \n (or \r\n).
    if bytes.get(data) == Some(&b'\r') {
        data += 1;
    }
    if bytes.get(data) == Some(&b'\n') {
        data += 1;
    }
    let mut lines = text.lines().enumerate();
    if lines.next().map(|(_, l)| l.trim()) != Some("ply") {
        return Err("not a PLY file: the first line is not `ply`".into());
    }
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    for (i, line) in lines {
        let at = |why: &str| format!("header line {}: {why} (`{}`)", i + 1, line.trim());
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", kind, _version] => {
                format = Some(match *kind {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Little,
                    "binary_big_endian" => Format::Big,
                    _ => return Err(at("an unknown format")),
                })
            }
            ["element", name, count] => elements.push(Element {
                name: name.to_string(),
                records: count
                    .parse()
                    .map_err(|_| at("a count that is not a number"))?,
                properties: Vec::new(),
            }),
            ["property", "list", count, item, name] => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| at("a property of no element"))?;
                let scalar = |w: &str| Scalar::parse(w).ok_or_else(|| at("an unknown type"));
                element.properties.push(Property {
                    name: name.to_string(),
                    count: Some(scalar(count)?),
                    item: scalar(item)?,
                });
            }
            ["property", item, name] => {
                let element = elements
                    .last_mut()
                    .ok_or_else(|| at("a property of no element"))?;
                element.properties.push(Property {
                    name: name.to_string(),
                    count: None,
                    item: Scalar::parse(item).ok_or_else(|| at("an unknown type"))?,
                });
            }
            _ => return Err(at("a line that is not PLY")),
        }
    }
    Ok(Header {
        format: format.ok_or("no `format` line")?,
        elements,
        data,
    })
}

/// Reads the scalars of the records, in order, from binary or ASCII data (where a record is
/// one line: [`Reader::record`] moves to the next).
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    format: Format,
    /// In ASCII: where the current record's line ends.
    line_end: usize,
}

impl Reader<'_> {
    /// Starts the next record: in ASCII, the next line that is not blank (None at the data's
    /// end); in binary, nothing to do.
    fn record(&mut self) -> Option<()> {
        if self.format != Format::Ascii {
            return Some(());
        }
        loop {
            self.at = self.line_end;
            if self.at >= self.bytes.len() {
                return None;
            }
            let rest = &self.bytes[self.at..];
            let len = rest
                .iter()
                .position(|&b| b == b'\n')
                .map_or(rest.len(), |n| n + 1);
            self.line_end = self.at + len;
            if rest[..len].iter().any(|b| !b.is_ascii_whitespace()) {
                return Some(());
            }
        }
    }

    /// The words the current ASCII record has left unread (0 in binary).
    fn left_on_line(&self) -> usize {
        match self.format {
            Format::Ascii => self.bytes[self.at..self.line_end]
                .split(|b| b.is_ascii_whitespace())
                .filter(|w| !w.is_empty())
                .count(),
            _ => 0,
        }
    }

    /// The next scalar of type `kind`, as f64; None at the data's end or, in ASCII, at the
    /// end of the record's line or a word that is not a number.
    fn next(&mut self, kind: Scalar) -> Option<f64> {
        if self.format == Format::Ascii {
            let rest = &self.bytes[self.at..self.line_end];
            let start = rest.iter().position(|b| !b.is_ascii_whitespace())?;
            let len = rest[start..]
                .iter()
                .position(|b| b.is_ascii_whitespace())
                .unwrap_or(rest.len() - start);
            self.at += start + len;
            return std::str::from_utf8(&rest[start..start + len])
                .ok()?
                .parse()
                .ok();
        }
        let size = kind.size();
        let raw = self.bytes.get(self.at..self.at + size)?;
        self.at += size;
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(raw);
        if self.format == Format::Big {
            b[..size].reverse();
        }
        Some(match kind {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }
}

/// Where the vertex element's kept properties are among its properties.
struct VertexLayout {
    position: [usize; 3],
    normal: Option<[usize; 3]>,
    texcoord: Option<[usize; 2]>,
}

impl VertexLayout {
    fn of(element: &Element) -> Result<Self, String> {
        let find = |names: &[&str]| {
            element
                .properties
                .iter()
                .position(|p| p.count.is_none() && names.contains(&p.name.as_str()))
        };
        let all = |names: [&[&str]; 3]| -> Option<[usize; 3]> {
            Some([find(names[0])?, find(names[1])?, find(names[2])?])
        };
        Ok(Self {
            position: all([&["x"], &["y"], &["z"]])
                .ok_or("the vertex element has no `x`, `y` and `z`")?,
            normal: all([&["nx"], &["ny"], &["nz"]]),
            texcoord: find(&["s", "u", "texture_u"])
                .zip(find(&["t", "v", "texture_v"]))
                .map(|(s, t)| [s, t]),
        })
    }
}

fn parse(bytes: &[u8]) -> Result<ObjTriangles, String> {
    let header = header(bytes)?;
    let vertex = header
        .elements
        .iter()
        .position(|e| e.name == "vertex")
        .ok_or("no `vertex` element")?;
    let face = header
        .elements
        .iter()
        .position(|e| e.name == "face")
        .ok_or("no `face` element")?;
    let layout = VertexLayout::of(&header.elements[vertex])?;
    let indices = header.elements[face]
        .properties
        .iter()
        .position(|p| p.count.is_some() && (p.name == "vertex_indices" || p.name == "vertex_index"))
        .ok_or("the face element has no `vertex_indices` list")?;
    let vertices = header.elements[vertex].records;
    // Room for what the header promises, but never for more records than the file has bytes:
    // a header's count is not trusted with memory.
    let room = vertices.min(bytes.len());
    let mut out = ObjTriangles {
        positions: Vec::with_capacity(room),
        triangles: Vec::with_capacity(header.elements[face].records.min(bytes.len())),
        normals: layout.normal.map(|_| Vec::with_capacity(room)),
        texcoords: layout.texcoord.map(|_| Vec::with_capacity(room)),
    };
    let mut reader = Reader {
        bytes,
        at: header.data,
        format: header.format,
        line_end: header.data,
    };
    let mut values: Vec<f64> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    for (e, element) in header.elements.iter().enumerate() {
        // An element of no properties holds no data, however many records it claims.
        if element.properties.is_empty() {
            continue;
        }
        for r in 0..element.records {
            let at = |why: &str| format!("{} {}: {why}", element.name, r + 1);
            crate::interrupt::check(r, "a PLY file")?;
            reader
                .record()
                .ok_or_else(|| at("the data ends early (the header promises more records)"))?;
            values.clear();
            corners.clear();
            for (k, property) in element.properties.iter().enumerate() {
                let mut read = |kind| {
                    reader
                        .next(kind)
                        .ok_or_else(|| at("the data ends early or is not a number"))
                };
                match property.count {
                    None => values.push(read(property.item)?),
                    Some(count) => {
                        let n = read(count)?;
                        if n < 0.0 || n.fract() != 0.0 {
                            return Err(at(&format!(
                                "its list `{}` is said to hold {n} items: not a count",
                                property.name
                            )));
                        }
                        for _ in 0..n as usize {
                            let index = read(property.item)?;
                            if e == face && k == indices {
                                if !(0.0..vertices as f64).contains(&index) || index.fract() != 0.0
                                {
                                    return Err(at(&format!(
                                        "corner {index} names no vertex (the file has {vertices})"
                                    )));
                                }
                                corners.push(index as u32);
                            }
                        }
                        values.push(n);
                    }
                }
            }
            let extra = reader.left_on_line();
            if extra > 0 {
                return Err(at(&format!(
                    "{extra} more number(s) on its line than the header's properties of `{}`",
                    element.name
                )));
            }
            if e == vertex {
                let pick = |i: usize| values[i] as f32;
                let finite = |v: &[f32]| v.iter().all(|c| c.is_finite());
                let p = layout.position.map(pick);
                if !finite(&p) {
                    return Err(at("a position that is not three finite numbers"));
                }
                let normal = layout.normal.map(|i| i.map(pick));
                let uv = layout.texcoord.map(|i| i.map(pick));
                if normal.is_some_and(|n| !finite(&n)) || uv.is_some_and(|t| !finite(&t)) {
                    return Err(at("a normal or texture coordinate that is not finite"));
                }
                out.positions.push(p);
                if let (Some(all), Some(n)) = (&mut out.normals, normal) {
                    all.push(n);
                }
                if let (Some(all), Some(t)) = (&mut out.texcoords, uv) {
                    all.push(t);
                }
            } else if e == face {
                if corners.len() < 3 {
                    return Err(at("a face of fewer than three corners"));
                }
                for k in 1..corners.len() - 1 {
                    out.triangles.push([corners[0], corners[k], corners[k + 1]]);
                }
            }
        }
    }
    if out.triangles.is_empty() {
        return Err("has no faces".into());
    }
    Ok(out)
}
