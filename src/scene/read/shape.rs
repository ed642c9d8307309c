//! `[[shape]]`: primitives, boxes and OBJ meshes placed in the scene. Every key's unit and default is in `docs/scene-format.md`.

use crate::error::Result;
use crate::scene::mesh::ObjTriangles;
use crate::scene::table::{TableReader, MAX_MAGNITUDE};
use crate::shapes::{Disk, Primitive, Quad, TriangleMesh, UvFrame};
use glam::{DMat3, DVec3};
use std::sync::Arc;

/// A shape before names are resolved.
pub struct ShapeDesc {
    /// Its primitives.
    pub primitives: Vec<Primitive>,
    /// Material name.
    pub material: String,
    /// Interior override.
    pub interior: Option<String>,
    /// The frame its round primitives' surface coordinates are read in (None: their own).
    pub uv_frame: Option<UvFrame>,
}

/// A round shape's `uv_frame` (three axes [x, y, z]) and `v_from_top`, checked against each of
/// its `primitives`.
fn uv_frame(t: &mut TableReader, primitives: &[Primitive]) -> Result<Option<UvFrame>> {
    if !t.has("uv_frame") {
        return Ok(None);
    }
    let axes = t.vec3_list("uv_frame")?;
    t.check(
        "uv_frame",
        axes.len() == 3,
        format!("expected three axes [x, y, z], got {}", axes.len()),
    )?;
    let v_from_top = t.bool_or("v_from_top", false)?;
    let frame =
        UvFrame::new(axes[0], axes[1], axes[2], v_from_top).map_err(|e| t.error("uv_frame", e))?;
    if let Some(why) = primitives.iter().find_map(|p| frame.misfit(p)) {
        return Err(t.error("uv_frame", why));
    }
    Ok(Some(frame))
}

/// The parallelogram of four vertices v0..v3 (refs convention: triangles (v0,v1,v2), (v0,v2,v3)).
pub(super) fn parallelogram(t: &mut TableReader, key: &str) -> Result<(DVec3, DVec3, DVec3)> {
    let v = t.vec3_list(key)?;
    t.check(
        key,
        v.len() == 4,
        format!("expected 4 vertices, got {}", v.len()),
    )?;
    let (e1, e2) = (v[1] - v[0], v[3] - v[0]);
    let scale = e1.length().max(e2.length());
    t.check(
        key,
        (v[0] + e1 + e2 - v[2]).length() <= 1e-9 * scale.max(1e-300),
        "the 4 vertices are not a parallelogram (v2 must be v1 + v3 − v0)",
    )?;
    t.check(key, e1.cross(e2).length() > 0.0, "the quad has zero area")?;
    Ok((v[0], e1, e2))
}

/// `[[shape]]`; mesh files are relative to `dir`.
pub fn read_shape(t: &mut TableReader) -> Result<ShapeDesc> {
    let kind = t.string("type")?;
    let primitives = match kind.as_str() {
        "sphere" => vec![Primitive::Sphere {
            center: t.vec3("center")?,
            radius: t.positive("radius")?,
        }],
        "cylinder" => {
            let base = t.vec3("base")?;
            let axis = t.direction_or("axis", DVec3::Z)?;
            let radius = t.positive("radius")?;
            let height = t.positive("height")?;
            let mut p = vec![Primitive::Tube {
                base,
                axis,
                radius,
                height,
            }];
            if t.bool_or("capped", true)? {
                p.push(Primitive::Disk(Disk {
                    center: base,
                    normal: -axis,
                    radius,
                    inner: 0.0,
                }));
                p.push(Primitive::Disk(Disk {
                    center: base + axis * height,
                    normal: axis,
                    radius,
                    inner: 0.0,
                }));
            }
            p
        }
        "box" => {
            let (lo, hi) = (t.vec3("min")?, t.vec3("max")?);
            t.check(
                "max",
                lo.cmplt(hi).all(),
                "every component of `max` must exceed `min`",
            )?;
            box_faces(lo, hi)
        }
        "quad" => {
            let (origin, e1, e2) = parallelogram(t, "vertices")?;
            vec![Primitive::Quad(Quad { origin, e1, e2 })]
        }
        "disk" => {
            let center = t.vec3("center")?;
            let normal = t.direction_or("normal", DVec3::Y)?;
            let radius = t.positive("radius")?;
            let inner = t.f64_or("inner_radius", 0.0)?;
            t.check(
                "inner_radius",
                (0.0..radius).contains(&inner),
                "must be in [0, radius)",
            )?;
            vec![Primitive::Disk(Disk {
                center,
                normal,
                radius,
                inner,
            })]
        }
        "mesh" => vec![Primitive::Mesh(Arc::new(read_mesh(t)?))],
        other => {
            return Err(t.error(
                "type",
                format!("unknown shape type '{other}' (sphere, cylinder, box, quad, disk, mesh)"),
            ))
        }
    };
    let uv_frame = match kind.as_str() {
        "mesh" => None,
        _ => uv_frame(t, &primitives)?,
    };
    Ok(ShapeDesc {
        primitives,
        uv_frame,
        material: t.string("material")?,
        interior: t.string_opt("interior")?,
    })
}

/// The six outward-facing quads of an axis-aligned box.
fn box_faces(lo: DVec3, hi: DVec3) -> Vec<Primitive> {
    let d = hi - lo;
    let (x, y, z) = (DVec3::X * d.x, DVec3::Y * d.y, DVec3::Z * d.z);
    vec![
        Primitive::Quad(Quad {
            origin: lo,
            e1: y,
            e2: x,
        }), // −z
        Primitive::Quad(Quad {
            origin: lo + z,
            e1: x,
            e2: y,
        }), // +z
        Primitive::Quad(Quad {
            origin: lo,
            e1: z,
            e2: y,
        }), // −x
        Primitive::Quad(Quad {
            origin: lo + x,
            e1: y,
            e2: z,
        }), // +x
        Primitive::Quad(Quad {
            origin: lo,
            e1: x,
            e2: z,
        }), // −y
        Primitive::Quad(Quad {
            origin: lo + y,
            e1: z,
            e2: x,
        }), // +y
    ]
}

/// Where a mesh's triangles come from: a file, or the scene's own lists.
enum MeshSource {
    File(std::path::PathBuf),
    Inline,
}

impl MeshSource {
    /// The key that gives the triangles, named in errors.
    fn key(&self) -> &'static str {
        match self {
            MeshSource::File(_) => "file",
            MeshSource::Inline => "points",
        }
    }

    /// What errors call the triangles' source.
    fn label(&self) -> String {
        match self {
            MeshSource::File(path) => path.display().to_string(),
            MeshSource::Inline => "the mesh's points".into(),
        }
    }
}

/// A mesh given in the scene: `points` (3 numbers a vertex), `indices` (3 vertex indices a
/// triangle, from 0), and optionally `normals` (3 numbers a vertex) and `uv` (2 a vertex).
fn inline_triangles(t: &mut TableReader) -> Result<ObjTriangles> {
    let per_vertex = |t: &mut TableReader, key: &str, n: usize| -> Result<Option<Vec<f64>>> {
        let Some(v) = t.f64_list_opt(key)? else {
            return Ok(None);
        };
        t.check(
            key,
            !v.is_empty() && v.len() % n == 0,
            format!("expected {n} numbers a vertex, got {} numbers", v.len()),
        )?;
        Ok(Some(v))
    };
    let points = per_vertex(t, "points", 3)?.ok_or_else(|| t.error("points", "is missing"))?;
    let vertices = points.len() / 3;
    let indices = t.f64_list("indices")?;
    t.check(
        "indices",
        !indices.is_empty() && indices.len() % 3 == 0,
        format!(
            "expected 3 indices a triangle, got {} numbers",
            indices.len()
        ),
    )?;
    let mut triangles = Vec::with_capacity(indices.len() / 3);
    for (k, corner) in indices.chunks_exact(3).enumerate() {
        let mut tri = [0u32; 3];
        for (slot, &i) in tri.iter_mut().zip(corner) {
            t.check(
                "indices",
                i >= 0.0 && i.fract() == 0.0 && i < vertices as f64,
                format_args!(
                    "triangle {} names vertex {i}: indices are whole numbers from 0 to {}",
                    k + 1,
                    vertices - 1
                ),
            )?;
            *slot = i as u32;
        }
        triangles.push(tri);
    }
    let f32s = |v: Vec<f64>| v.into_iter().map(|x| x as f32).collect::<Vec<f32>>();
    let mut attribute = |key: &str, n: usize| -> Result<Option<Vec<f32>>> {
        let Some(v) = per_vertex(t, key, n)? else {
            return Ok(None);
        };
        t.check(
            key,
            v.len() == n * vertices,
            format!(
                "expected {n} numbers for each of the {vertices} points, got {} numbers",
                v.len()
            ),
        )?;
        Ok(Some(f32s(v)))
    };
    let normals =
        attribute("normals", 3)?.map(|n| n.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect());
    let texcoords = attribute("uv", 2)?.map(|n| n.chunks_exact(2).map(|c| [c[0], c[1]]).collect());
    Ok(ObjTriangles {
        positions: f32s(points)
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
        triangles,
        normals,
        texcoords,
    })
}

/// A mesh from a `file` (OBJ, PLY or Mitsuba serialized) or from `points` and `indices`,
/// placed by `matrix` or `scale`, `rotate_deg` and `translate` (a mesh shape's keys; an
/// emitting mesh's too).
pub fn read_mesh(t: &mut TableReader) -> Result<TriangleMesh> {
    let source = match t.has("points") {
        true => {
            t.check(
                "file",
                !t.has("file"),
                "give either `file` or `points` and `indices`",
            )?;
            MeshSource::Inline
        }
        false => MeshSource::File(t.input_file("file")?),
    };
    let (key, label) = (source.key(), source.label());
    let Placement {
        linear,
        scale,
        normal_map,
        translate,
        key: placed_by,
    } = read_placement(t)?;
    let obj = match &source {
        MeshSource::Inline => inline_triangles(t)?,
        MeshSource::File(path) => {
            let name = path.to_string_lossy().to_ascii_lowercase();
            let ext = match name.ends_with(".ply.gz") {
                true => Some("ply".to_string()),
                false => path
                    .extension()
                    .and_then(|e| e.to_str())
                    .map(str::to_ascii_lowercase),
            };
            let index = match ext.as_deref() {
                Some("serialized") => t.natural_or("shape_index", 0)? as usize,
                _ => {
                    t.check(
                        "shape_index",
                        !t.has("shape_index"),
                        "shape_index picks a mesh of a Mitsuba .serialized file",
                    )?;
                    0
                }
            };
            match ext.as_deref() {
                Some("ply") => crate::scene::ply::load_ply(path),
                Some("serialized") => crate::scene::serialized::load_serialized(path, index),
                _ => crate::scene::mesh::load_triangles(path),
            }
            .map_err(|e| t.error("file", e))?
        }
    };
    let smooth = t.bool_or("smooth", obj.normals.is_some())?;
    // Whether any face has an area as the file gives it (else a scale is not to blame).
    let given = |i: u32| DVec3::from(obj.positions[i as usize].map(f64::from));
    let any_area = obj.triangles.iter().any(|&[a, b, c]| {
        (given(b) - given(a))
            .cross(given(c) - given(a))
            .length_squared()
            > 0.0
    });
    // Placed in f64, stored in f32: the stored vertices are the geometry.
    let mut vertices = obj.positions;
    for (i, v) in vertices.iter_mut().enumerate() {
        let given = DVec3::from(v.map(f64::from));
        // The messages are formatted only if a check fails (a million vertices each).
        t.check(
            key,
            given.abs().max_element() <= MAX_MAGNITUDE,
            format_args!(
                "{label}: vertex {} lies at {:?}, beyond ±{MAX_MAGNITUDE:e}",
                i + 1,
                v
            ),
        )?;
        let p = translate + linear * (scale * given);
        t.check(
            placed_by,
            p.abs().max_element() <= MAX_MAGNITUDE,
            format_args!("{label}: scaled and moved, a vertex lies beyond ±{MAX_MAGNITUDE:e}"),
        )?;
        *v = p.as_vec3().to_array();
    }
    let faces = obj.triangles.len();
    let at = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
    let mut triangles = obj.triangles;
    triangles.retain(|&[a, b, c]| (at(b) - at(a)).cross(at(c) - at(a)).length_squared() > 0.0);
    if triangles.is_empty() {
        // A file with an unusable line says so rather than "zero area" (read again: only here).
        let problem = match &source {
            MeshSource::File(path) => std::fs::read(path)
                .ok()
                .and_then(|b| crate::scene::mesh::diagnose(&b)),
            MeshSource::Inline => None,
        };
        return Err(match (problem, any_area) {
            (Some(p), _) => t.error(key, format!("{label}: {p}")),
            (None, false) => t.error(
                key,
                format!(
                    "{label}: all {faces} triangles have zero area (each face's corners lie on \
                     a line)"
                ),
            ),
            (None, true) => t.error(
                placed_by,
                format!("{label}: all {faces} triangles have zero area at this scale"),
            ),
        });
    }
    let duplicates = crate::scene::mesh::drop_duplicate_triangles(&vertices, &mut triangles);
    if duplicates > 0 {
        t.warn(
            key,
            format!(
                "{label}: {duplicates} triangle(s) repeat an earlier one's corners and were left \
                 out"
            ),
        );
    }
    triangles.shrink_to_fit();
    let normals = match (smooth, obj.normals) {
        (false, _) => None,
        (true, Some(mut n)) => {
            for v in &mut n {
                let w = normal_map * DVec3::from(v.map(f64::from));
                *v = w.normalize_or_zero().as_vec3().to_array();
            }
            Some(n)
        }
        (true, None) => Some(vertex_normals(&vertices, &triangles)),
    };
    let mut texcoords = obj.texcoords;
    // v turned over as the file is read (Mitsuba's `flip_tex_coords`; no texture coordinates,
    // nothing to turn).
    if t.bool_or("flip_v", false)? {
        for uv in texcoords.iter_mut().flatten() {
            uv[1] = 1.0 - uv[1];
        }
    }
    let mesh =
        TriangleMesh::new(vertices, triangles, normals, texcoords).map_err(|e| t.error(key, e))?;
    let mesh = match t.bool_or("v_from_top", false)? {
        true => mesh.v_from_top(),
        false => mesh,
    };
    Ok(mesh)
}

/// How a mesh's file coordinates are placed in the scene: p ↦ linear·(scale·p) + translate,
/// and the key that gave it (named where a placed vertex is refused).
struct Placement {
    linear: DMat3,
    scale: f64,
    /// What normals are multiplied by before they are normalised: a multiple of the inverse
    /// transpose of `linear` (for a turn and a scale: the turn, and the sign of the scale).
    normal_map: DMat3,
    translate: DVec3,
    key: &'static str,
}

/// A mesh's placement: `matrix`, the 12 numbers of an affine map's rows [a b c t] (or 16, the
/// last row 0 0 0 1), or `scale`, then `rotate_deg` (x, then y, then z), then `translate`.
fn read_placement(t: &mut TableReader) -> Result<Placement> {
    if let Some(m) = t.f64_list_opt("matrix")? {
        for key in ["scale", "rotate_deg", "translate"] {
            t.check(
                key,
                !t.has(key),
                "give either `matrix` or scale, rotate_deg and translate",
            )?;
        }
        t.check(
            "matrix",
            m.len() == 12 || (m.len() == 16 && m[12..] == [0.0, 0.0, 0.0, 1.0]),
            format!(
                "expected the 12 numbers of 3 rows [a, b, c, t] (or 16, the last row 0, 0, 0, \
                 1), got {} numbers",
                m.len()
            ),
        )?;
        let row = |i: usize| DVec3::new(m[4 * i], m[4 * i + 1], m[4 * i + 2]);
        let linear = DMat3::from_cols(row(0), row(1), row(2)).transpose();
        t.check(
            "matrix",
            linear.determinant().abs() > 0.0 && linear.is_finite(),
            "the matrix flattens the mesh (its 3×3 part has no inverse)",
        )?;
        return Ok(Placement {
            linear,
            scale: 1.0,
            normal_map: linear.inverse().transpose(),
            translate: DVec3::new(m[3], m[7], m[11]),
            key: "matrix",
        });
    }
    let translate = t.vec3_or("translate", DVec3::ZERO)?;
    let scale = t.f64_or("scale", 1.0)?;
    t.check("scale", scale != 0.0, "must not be 0")?;
    let rot = t.vec3_or("rotate_deg", DVec3::ZERO)?;
    let turn = DMat3::from_rotation_z(rot.z.to_radians())
        * DMat3::from_rotation_y(rot.y.to_radians())
        * DMat3::from_rotation_x(rot.x.to_radians());
    Ok(Placement {
        linear: turn,
        scale,
        normal_map: turn * scale.signum(),
        translate,
        key: "scale",
    })
}

/// Vertex normals of a mesh without them, by Max's weights (J. Graphics Tools 4(2), 1999):
/// at each corner, e1 × e2 / (|e1|² |e2|²) with e1, e2 the corner's edges, summed over the
/// triangles that share the vertex (by index). Exact where the vertex and its neighbours lie on
/// a sphere, and so O(h²) on smooth surfaces, where area or angle weights err by O(h) on
/// irregular meshes. A vertex no triangle uses gets +z.
fn vertex_normals(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Vec<[f32; 3]> {
    let at = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
    let mut sum = vec![DVec3::ZERO; vertices.len()];
    for &[a, b, c] in triangles {
        for (v, next, prev) in [(a, b, c), (b, c, a), (c, a, b)] {
            let (e1, e2) = (at(next) - at(v), at(prev) - at(v));
            let w = e1.length_squared() * e2.length_squared();
            if w > 0.0 {
                sum[v as usize] += e1.cross(e2) / w;
            }
        }
    }
    sum.into_iter()
        .map(|n| n.try_normalize().unwrap_or(DVec3::Z).as_vec3().to_array())
        .collect()
}
