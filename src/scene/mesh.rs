//! Wavefront OBJ meshes: triangles through tobj, and a line-precise diagnosis of files it
//! cannot use (tobj's own errors name neither the line nor the cause).

use std::path::Path;

/// An OBJ file's triangles: vertex positions (as the file has them, f32) and index triples
/// into them, all objects and groups of the file in one list.
pub struct ObjTriangles {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles as indices into `positions` (faces with more corners are fanned by tobj).
    pub triangles: Vec<[u32; 3]>,
    /// The file's vertex normals (`vn`), one per position, when every face gives them.
    pub normals: Option<Vec<[f32; 3]>>,
    /// The file's texture coordinates (`vt`), one per position, when every face gives them.
    pub texcoords: Option<Vec<[f32; 2]>>,
}

/// The triangles of an OBJ file (zero-area ones included: whether a triangle has an area
/// depends on where the scene puts it). The error names the file, the line where it can, and
/// what is wrong there.
pub fn load_triangles(path: &Path) -> Result<ObjTriangles, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let at = |what: String| format!("{}: {what}", path.display());
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let loaded = tobj::load_obj_buf(&mut bytes.as_slice(), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    });
    let models = match loaded {
        Ok((models, _materials)) => models,
        Err(e) => return Err(at(diagnose(&bytes).unwrap_or_else(|| e.to_string()))),
    };
    let mut out = ObjTriangles {
        positions: Vec::new(),
        triangles: Vec::new(),
        normals: Some(Vec::new()),
        texcoords: Some(Vec::new()),
    };
    for model in models {
        let mesh = model.mesh;
        if mesh.positions.iter().any(|c| !c.is_finite()) {
            return Err(at(
                diagnose(&bytes).unwrap_or_else(|| "a vertex is not finite".into())
            ));
        }
        let offset = u32::try_from(out.positions.len())
            .ok()
            .filter(|o| o.checked_add(mesh.positions.len() as u32 / 3).is_some())
            .ok_or_else(|| at("more than 2³² vertices".into()))?;
        out.positions
            .extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        // tobj's single index gives each position its normal and (u, v) when the faces name
        // them.
        out.texcoords = out
            .texcoords
            .take()
            .filter(|_| 3 * mesh.texcoords.len() == 2 * mesh.positions.len())
            .map(|mut t| {
                t.extend(mesh.texcoords.chunks_exact(2).map(|v| [v[0], v[1]]));
                t
            });
        out.normals = out
            .normals
            .take()
            .filter(|_| mesh.normals.len() == mesh.positions.len())
            .map(|mut n| {
                n.extend(mesh.normals.chunks_exact(3).map(|v| [v[0], v[1], v[2]]));
                n
            });
        out.triangles.extend(
            mesh.indices
                .chunks_exact(3)
                .map(|f| [f[0] + offset, f[1] + offset, f[2] + offset]),
        );
    }
    if out.triangles.is_empty() {
        return Err(at(
            diagnose(&bytes).unwrap_or_else(|| "has no faces (no `f` lines)".into())
        ));
    }
    Ok(out)
}

/// The first line of an OBJ file that cannot be used, and why: not text, a vertex that is not
/// three finite numbers, a face with fewer than three corners or an index that is not a
/// vertex of the file. None when every `v`, `vt`, `vn` and `f` line is sound.
pub fn diagnose(bytes: &[u8]) -> Option<String> {
    let lines: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
    // Counts of v, vt, vn over the whole file (positive indices may refer forward).
    let mut totals = [0usize; 3];
    for line in &lines {
        if let Ok(text) = std::str::from_utf8(line) {
            match text.split_whitespace().next() {
                Some("v") => totals[0] += 1,
                Some("vt") => totals[1] += 1,
                Some("vn") => totals[2] += 1,
                _ => {}
            }
        }
    }
    let mut seen = [0usize; 3];
    for (k, line) in lines.iter().enumerate() {
        let n = k + 1;
        let Ok(text) = std::str::from_utf8(line) else {
            return Some(format!(
                "line {n} is not text (invalid UTF-8): not an OBJ file?"
            ));
        };
        let mut words = text.split_whitespace();
        let (kind, need) = match words.next() {
            Some("v") => (0, 3),
            Some("vt") => (1, 1),
            Some("vn") => (2, 3),
            Some("f") => {
                if let Some(problem) = face_problem(words, &seen, &totals) {
                    return Some(format!("line {n}: {problem}"));
                }
                continue;
            }
            _ => continue,
        };
        let numbers: Vec<Option<f32>> = words.map(|w| w.parse::<f32>().ok()).collect();
        if numbers.len() < need || numbers.iter().any(|x| x.is_none_or(|x| !x.is_finite())) {
            let name = ["a vertex (v)", "a texture coordinate (vt)", "a normal (vn)"][kind];
            return Some(format!(
                "line {n}: {name} needs {need} finite numbers, got `{}`",
                text.trim()
            ));
        }
        seen[kind] += 1;
    }
    None
}

/// Why a face's corners `v[/vt][/vn]` are unusable, given the counts of each kind defined so
/// far (`seen`, for negative, relative indices) and in the whole file (`totals`).
fn face_problem<'a>(
    corners: impl Iterator<Item = &'a str>,
    seen: &[usize; 3],
    totals: &[usize; 3],
) -> Option<String> {
    let corners: Vec<&str> = corners.collect();
    if corners.len() < 3 {
        return Some(format!(
            "a face needs at least 3 corners, got {}",
            corners.len()
        ));
    }
    for corner in corners {
        for (kind, index) in corner.split('/').enumerate().take(3) {
            if index.is_empty() && kind > 0 {
                continue;
            }
            let name = ["vertex", "texture coordinate", "normal"][kind];
            let Ok(i) = index.parse::<i64>() else {
                return Some(format!(
                    "corner `{corner}`: `{index}` is not a {name} index"
                ));
            };
            let ok = match i {
                0 => false,
                i if i > 0 => i as u64 <= totals[kind] as u64,
                i => i.unsigned_abs() <= seen[kind] as u64,
            };
            if !ok {
                return Some(format!(
                    "corner `{corner}`: {name} index {i} does not exist (the file has {} {name}s{})",
                    totals[kind],
                    if i < 0 {
                        format!(", {} before this line", seen[kind])
                    } else {
                        String::new()
                    }
                ));
            }
        }
    }
    None
}
