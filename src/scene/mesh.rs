//! Wavefront OBJ meshes: the triangles of a file, read line by line (its `v`, `vt`, `vn` and
//! `f` lines; faces fanned), and a line-precise diagnosis of files that cannot be used.

use rayon::prelude::*;
use std::collections::HashMap;
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

/// An OBJ file's triangles: vertex positions (as the file has them, f32) and index triples
/// into them, all objects and groups of the file in one list.
pub struct ObjTriangles {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles as indices into `positions` (faces with more corners fanned).
    pub triangles: Vec<[u32; 3]>,
    /// The file's vertex normals (`vn`), one per position, when every face gives them.
    pub normals: Option<Vec<[f32; 3]>>,
    /// The file's texture coordinates (`vt`), one per position, when every face gives them.
    pub texcoords: Option<Vec<[f32; 2]>>,
}

/// The triangles of an OBJ file (zero-area ones included: whether a triangle has an area
/// depends on where the scene puts it), read line by line: what is kept is the vertices and
/// the corners' indices, never the file's text. Faces of more than three corners are fanned
/// from their first. The error names the file, the line where it can, and what is wrong
/// there.
pub fn load_triangles(path: &Path) -> Result<ObjTriangles, String> {
    let at = |what: String| format!("{}: {what}", path.display());
    let file = File::open(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    // What is wrong is found again by reading the file whole (errors are rare).
    let fail = |fallback: &str| {
        at(std::fs::read(path)
            .ok()
            .and_then(|b| diagnose(&b))
            .unwrap_or_else(|| fallback.into()))
    };
    let mut obj = Parsed::default();
    let mut reader = BufReader::new(file);
    let mut line = Vec::new();
    for number in 0.. {
        crate::interrupt::check(number, "an OBJ file").map_err(&at)?;
        line.clear();
        match reader.read_until(b'\n', &mut line) {
            Ok(0) => break,
            Ok(_) => {}
            Err(e) => return Err(at(format!("cannot read: {e}"))),
        }
        let text = std::str::from_utf8(&line).map_err(|_| fail("not text"))?;
        obj.line(text)
            .ok_or_else(|| fail("a line that is not OBJ"))?;
    }
    obj.finish().map_err(|why| fail(&why))
}

/// An OBJ file as read so far: vertices, texture coordinates and normals as given, and per
/// triangle corner the (0-based) indices of each (`NONE` where a corner gives none).
#[derive(Default)]
struct Parsed {
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    normals: Vec<[f32; 3]>,
    /// Per corner: vertex, texture coordinate, normal.
    corners: Vec<[u32; 3]>,
}

/// A corner that gives no texture coordinate or normal.
const NONE: u32 = u32::MAX;

/// The next `N` words as finite numbers (None if there are fewer or one is not).
fn finite<'a, const N: usize>(words: &mut impl Iterator<Item = &'a str>) -> Option<[f32; N]> {
    let mut out = [0.0; N];
    for x in &mut out {
        *x = words.next()?.parse().ok().filter(|x: &f32| x.is_finite())?;
    }
    Some(out)
}

impl Parsed {
    /// Takes one line; None when it is unusable (the caller diagnoses it).
    fn line(&mut self, text: &str) -> Option<()> {
        let mut words = text.split_whitespace();
        match words.next() {
            Some("v") => {
                let [x, y, z] = finite(&mut words)?;
                self.positions.push([x, y, z]);
            }
            Some("vt") => {
                let [u] = finite(&mut words)?;
                let v = match words.next() {
                    Some(w) => w.parse().ok().filter(|v: &f32| v.is_finite())?,
                    None => 0.0,
                };
                self.texcoords.push([u, v]);
            }
            Some("vn") => {
                let [x, y, z] = finite(&mut words)?;
                self.normals.push([x, y, z]);
            }
            Some("f") => {
                let corners: Vec<[u32; 3]> =
                    words.map(|c| self.corner(c)).collect::<Option<_>>()?;
                if corners.len() < 3 {
                    return None;
                }
                for k in 1..corners.len() - 1 {
                    self.corners
                        .extend([corners[0], corners[k], corners[k + 1]]);
                }
            }
            _ => {}
        }
        Some(())
    }

    /// A corner `v[/vt][/vn]` as 0-based indices: positive ones may refer forward (checked at
    /// the end), negative ones count back from the last of their kind so far.
    fn corner(&self, text: &str) -> Option<[u32; 3]> {
        let counts = [
            self.positions.len(),
            self.texcoords.len(),
            self.normals.len(),
        ];
        let mut out = [NONE; 3];
        for (kind, index) in text.split('/').enumerate() {
            if kind > 2 {
                return None;
            }
            if index.is_empty() && kind > 0 {
                continue;
            }
            let i: i64 = index.parse().ok()?;
            let resolved = match i {
                0 => return None,
                i if i > 0 => i - 1,
                i => counts[kind] as i64 + i,
            };
            out[kind] = u32::try_from(resolved).ok().filter(|&r| r != NONE)?;
        }
        Some(out)
    }

    /// The triangles: the vertices as the file has them when no corner names a texture
    /// coordinate or a normal; else one vertex per distinct (v, vt, vn), with the normals and
    /// texture coordinates kept only when every corner gives them.
    fn finish(self) -> Result<ObjTriangles, String> {
        if self.corners.is_empty() {
            return Err("has no faces (no `f` lines)".into());
        }
        let counts = [
            self.positions.len(),
            self.texcoords.len(),
            self.normals.len(),
        ];
        if self
            .corners
            .iter()
            .any(|c| (0..3).any(|k| c[k] != NONE && c[k] as usize >= counts[k]))
        {
            return Err("a face names an index that does not exist".into());
        }
        let every = |k: usize| self.corners.iter().all(|c| c[k] != NONE);
        let (all_vt, all_vn) = (every(1), every(2));
        if self.corners.iter().all(|c| c[1] == NONE && c[2] == NONE) {
            return Ok(ObjTriangles {
                triangles: self
                    .corners
                    .chunks_exact(3)
                    .map(|t| [t[0][0], t[1][0], t[2][0]])
                    .collect(),
                positions: self.positions,
                normals: None,
                texcoords: None,
            });
        }
        let mut index: HashMap<[u32; 3], u32> = HashMap::new();
        let mut out = ObjTriangles {
            positions: Vec::new(),
            triangles: Vec::with_capacity(self.corners.len() / 3),
            normals: all_vn.then(Vec::new),
            texcoords: all_vt.then(Vec::new),
        };
        let mut vertex = |c: [u32; 3]| -> Result<u32, String> {
            if let Some(&i) = index.get(&c) {
                return Ok(i);
            }
            let i = u32::try_from(out.positions.len())
                .map_err(|_| "more than 2³² vertices".to_string())?;
            out.positions.push(self.positions[c[0] as usize]);
            if let Some(t) = &mut out.texcoords {
                t.push(self.texcoords[c[1] as usize]);
            }
            if let Some(n) = &mut out.normals {
                n.push(self.normals[c[2] as usize]);
            }
            index.insert(c, i);
            Ok(i)
        };
        let mut triangles = Vec::with_capacity(self.corners.len() / 3);
        for t in self.corners.chunks_exact(3) {
            triangles.push([vertex(t[0])?, vertex(t[1])?, vertex(t[2])?]);
        }
        out.triangles = triangles;
        Ok(out)
    }
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
            let names = ["vertices", "texture coordinates", "normals"][kind];
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
                    "corner `{corner}`: {name} index {i} does not exist (the file has {} {names}{})",
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

/// Drops every triangle whose three corners lie where an earlier triangle's do (in any order
/// of corners, through any vertex indices): a duplicate adds nothing to a surface, and many
/// of them at one place give a BVH builder boxes it cannot split. Returns how many were
/// dropped. A sort of the triangles by a 64-bit hash of their corner positions (computed once
/// a triangle; equal hashes compared corner by corner): O(n log n), 16 bytes a triangle while
/// it runs.
pub fn drop_duplicate_triangles(vertices: &[[f32; 3]], triangles: &mut Vec<[u32; 3]>) -> usize {
    let corners = |t: &[u32; 3]| {
        let mut c = t.map(|i| vertices[i as usize].map(f32::to_bits));
        c.sort_unstable();
        c
    };
    // FxHash's multiply-rotate over the nine words.
    let hash = |c: [[u32; 3]; 3]| {
        c.iter().flatten().fold(0u64, |h, &w| {
            (h.rotate_left(5) ^ u64::from(w)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
        })
    };
    let mut order: Vec<(u64, u32)> = triangles
        .par_iter()
        .enumerate()
        .map(|(i, t)| (hash(corners(t)), i as u32))
        .collect();
    order.par_sort_unstable();
    let mut keep = vec![true; triangles.len()];
    for run in order
        .chunk_by(|a, b| a.0 == b.0)
        .filter(|run| run.len() > 1)
    {
        // In file order within a run: of equal triangles the first in the file stays.
        for (j, &(_, later)) in run.iter().enumerate() {
            let c = corners(&triangles[later as usize]);
            if run[..j]
                .iter()
                .any(|&(_, k)| keep[k as usize] && corners(&triangles[k as usize]) == c)
            {
                keep[later as usize] = false;
            }
        }
    }
    let before = triangles.len();
    let mut k = keep.iter();
    triangles.retain(|_| *k.next().expect("a flag a triangle"));
    before - triangles.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Duplicates are found by corner positions, in any order, through any indices; the
    /// first of equal triangles stays and the order of the rest is kept.
    #[test]
    fn duplicate_triangles_are_dropped() {
        let v = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let mut t = vec![[0, 1, 2], [2, 0, 3], [0, 1, 4], [1, 0, 2], [0, 1, 2]];
        assert_eq!(drop_duplicate_triangles(&v, &mut t), 3);
        assert_eq!(t, vec![[0, 1, 2], [0, 1, 4]]);
    }

    /// On a larger mesh (3000 distinct triangles over a 12³ lattice, 700 copies of earlier
    /// ones mixed in, each with its corners rotated and through duplicated vertices), exactly
    /// the copies go and the distinct triangles stay in their order.
    #[test]
    fn duplicates_among_many_triangles_are_dropped() {
        let lattice = |i: u32| [(i % 12) as f32, (i / 12 % 12) as f32, (i / 144) as f32];
        let mut vertices: Vec<[f32; 3]> = (0..1728).map(lattice).collect();
        let mut state = 7u64;
        let mut next = |n: u32| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 33) % u64::from(n)) as u32
        };
        let mut distinct: Vec<[u32; 3]> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        while distinct.len() < 3000 {
            let t = [next(1728), next(1728), next(1728)];
            let mut key = t;
            key.sort_unstable();
            if key[0] != key[1] && key[1] != key[2] && seen.insert(key) {
                distinct.push(t);
            }
        }
        let mut mixed = distinct.clone();
        for _ in 0..700 {
            let [a, b, c] = distinct[next(3000) as usize];
            // The copy names new vertices at the same places.
            let copy = |i: u32, vertices: &mut Vec<[f32; 3]>| {
                vertices.push(lattice(i));
                vertices.len() as u32 - 1
            };
            let t = [
                copy(b, &mut vertices),
                copy(c, &mut vertices),
                copy(a, &mut vertices),
            ];
            let at = next(mixed.len() as u32 + 1) as usize;
            // After its original, so that the original is the one that stays.
            let original = mixed
                .iter()
                .position(|x| *x == [a, b, c])
                .expect("in the mesh");
            mixed.insert(at.max(original + 1), t);
        }
        assert_eq!(drop_duplicate_triangles(&vertices, &mut mixed), 700);
        assert_eq!(mixed, distinct);
    }

    fn parse(text: &str) -> Result<ObjTriangles, String> {
        let mut obj = Parsed::default();
        for line in text.lines() {
            obj.line(line).ok_or_else(|| format!("bad line {line:?}"))?;
        }
        obj.finish()
    }

    /// Polygons are fanned from their first corner; negative indices count back; forward
    /// references resolve; positions alone keep the file's vertices.
    #[test]
    fn faces_fan_and_indices_resolve() {
        let t = parse("f 1 2 3 4\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -2 -1\n").unwrap();
        assert_eq!(t.positions.len(), 4);
        assert_eq!(t.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 2, 3]]);
        assert!(t.normals.is_none() && t.texcoords.is_none());
        assert!(
            parse("v 0 0 0\nf 1 2 3\n").is_err(),
            "index beyond the vertices"
        );
        assert!(parse("v 0 0 0\nf 1 1\n").is_err(), "two corners");
        assert!(
            parse("v 0 0 0\nv 1 0 0\nf 1 2 -3\n").is_err(),
            "back beyond the start"
        );
    }

    /// Corners naming normals and texture coordinates get one vertex per distinct triple;
    /// the normals and coordinates are kept only when every corner gives them.
    #[test]
    fn corners_with_normals_and_coordinates_split_vertices() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\nvt 0.5\nvt 0 1\n\
                    f 1/1/1 2/2/1 3/1/1\nf 1/1/2 3/1/2 2/2/2\n";
        let t = parse(text).unwrap();
        assert_eq!(t.positions.len(), 6, "each position with two normals");
        assert_eq!(t.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        let n = t.normals.unwrap();
        assert_eq!((n[0], n[3]), ([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]));
        assert_eq!(t.texcoords.unwrap()[0], [0.5, 0.0]);
        let mixed = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3\n").unwrap();
        assert!(mixed.normals.is_none(), "a corner without a normal");
    }
}
