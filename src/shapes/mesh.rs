//! A triangle mesh stored compactly: f32 vertices shared through u32 indices, with its own
//! BVH, so that millions of triangles fit (Zhdanov et al. (2020): a GRIN medium bounded by "millions of
//! independent triangles"). The f32 vertices *are* the geometry; every test converts them to
//! f64 exactly and runs in f64, as for any other primitive.

use super::hit::{padded_box, Hit, SegmentHits, TraversalRay};
use super::triangle::Triangle;
use crate::bvh::{build_bvh, Tuning};
use crate::curve::{ArcHull, Path};
use crate::math::Ball;
use crate::math::Bounds3;
use glam::{DVec2, DVec3};
use obvhs::bvh2::Bvh2;
use obvhs::ray::RayHit;
use rayon::prelude::*;

/// Triangles over shared vertices, with a BVH over the triangles; with vertex normals, a
/// smooth mesh (its hits' shading normals interpolated across each triangle).
pub struct TriangleMesh {
    vertices: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    /// Unit vertex normals, one per vertex, or none (a faceted mesh).
    normals: Option<Vec<[f32; 3]>>,
    /// Texture coordinates (u, v), one pair per vertex, or none.
    texcoords: Option<Vec<[f32; 2]>>,
    /// Whether the mesh's v counts from an image's top row down ([`TriangleMesh::v_from_top`]).
    v_from_top: bool,
    bvh: Bvh2,
    /// f64 bounds of all vertices.
    bounds: Bounds3,
    /// A ball around the bounds' centre that no triangle meets (radius 0 where one passes
    /// through the centre): a lens's or a ball's empty core, where a curved step's capsule
    /// needs no search at all.
    core: Ball,
}

impl TriangleMesh {
    /// The mesh of `triangles` (indices into `vertices`), smooth when `normals` gives each
    /// vertex a normal, textured by `texcoords` when it gives each a (u, v), or why not: at
    /// least one triangle, every index a vertex, every vertex finite, one finite non-zero
    /// normal and one finite (u, v) per vertex. Zero-area triangles are kept out of the BVH's
    /// answers by the triangle test itself.
    pub fn new(
        vertices: Vec<[f32; 3]>,
        triangles: Vec<[u32; 3]>,
        normals: Option<Vec<[f32; 3]>>,
        texcoords: Option<Vec<[f32; 2]>>,
    ) -> Result<Self, String> {
        if let Some(t) = &texcoords {
            if t.len() != vertices.len() || t.iter().flatten().any(|c| !c.is_finite()) {
                return Err(format!(
                    "{} texture coordinates for {} vertices, or one not finite",
                    t.len(),
                    vertices.len()
                ));
            }
        }
        if let Some(n) = &normals {
            if n.len() != vertices.len() {
                return Err(format!(
                    "{} vertex normals for {} vertices",
                    n.len(),
                    vertices.len()
                ));
            }
            if let Some(i) = n.iter().position(|v| {
                let l = DVec3::from(v.map(f64::from)).length();
                !(l.is_finite() && l > 0.0)
            }) {
                return Err(format!(
                    "the normal of vertex {} is {:?}: zero or not finite",
                    i + 1,
                    n[i]
                ));
            }
        }
        if triangles.is_empty() {
            return Err("a mesh needs at least one triangle".into());
        }
        if let Some(t) = triangles
            .par_iter()
            .find_first(|t| t.iter().any(|&i| i as usize >= vertices.len()))
        {
            return Err(format!(
                "triangle {t:?} names a vertex beyond the {} given",
                vertices.len()
            ));
        }
        if vertices.par_iter().flatten().any(|c| !c.is_finite()) {
            return Err("a vertex is not finite".into());
        }
        let vertex = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
        let bvh = build_bvh(
            triangles
                .par_iter()
                .map(|t| padded_box(Bounds3::of_points(t.iter().map(|&i| vertex(i))))),
            Tuning::Memory,
        );
        let bounds = Bounds3::of_points(vertices.iter().map(|v| DVec3::from(v.map(f64::from))));
        let centre = bounds.center();
        // A lower bound on each triangle's distance from the centre: the larger of the
        // distances to its box and to its plane (shrunk by 1e-9 against rounding).
        let core = triangles
            .par_iter()
            .map(|t| {
                let [a, b, c] = t.map(vertex);
                let to_box = (a.min(b).min(c) - centre)
                    .max(centre - a.max(b).max(c))
                    .max(DVec3::ZERO)
                    .length();
                let n = (b - a).cross(c - a);
                let to_plane = match n.length() {
                    l if l > 0.0 => (centre - a).dot(n).abs() / l,
                    _ => 0.0,
                };
                to_box.max(to_plane)
            })
            .reduce(|| f64::INFINITY, f64::min);
        Ok(Self {
            vertices,
            triangles,
            normals,
            texcoords,
            v_from_top: false,
            bvh,
            bounds,
            core: Ball {
                center: centre,
                radius: core * (1.0 - 1e-9),
            },
        })
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// The same mesh with its v counted from an image's top row down, as Mitsuba reads a
    /// PLY's and a serialized mesh's (u, v) (and the corners' weights of a mesh without
    /// them): its hits report grinlight's v, from the bottom row up, 1 − that.
    pub fn v_from_top(self) -> Self {
        Self {
            v_from_top: true,
            ..self
        }
    }

    /// The same mesh with every triangle wound the other way (its corners b and c swapped):
    /// each geometric normal turned over. The BVH stands (each triangle keeps its corners).
    pub fn turned_over(mut self) -> Self {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
        self
    }

    /// Whether the mesh has no triangle (never: [`TriangleMesh::new`] refuses that).
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Whether the mesh has vertex normals (smooth shading).
    pub fn is_smooth(&self) -> bool {
        self.normals.is_some()
    }

    /// Bytes held: vertices, normals, triangles and the BVH's nodes and leaf order.
    pub fn bytes(&self) -> usize {
        use std::mem::size_of_val;
        size_of_val(self.vertices.as_slice())
            + self.normals.as_deref().map_or(0, size_of_val)
            + self.texcoords.as_deref().map_or(0, size_of_val)
            + size_of_val(self.triangles.as_slice())
            + size_of_val(self.bvh.nodes.as_slice())
            + size_of_val(self.bvh.primitive_indices.as_slice())
    }

    /// Axis-aligned bounds of the vertices.
    pub fn bounds(&self) -> Bounds3 {
        self.bounds
    }

    /// The corners of triangle `i`, in f64.
    pub fn corners(&self, i: usize) -> [DVec3; 3] {
        self.triangles[i].map(|k| DVec3::from(self.vertices[k as usize].map(f64::from)))
    }

    /// Triangle `i`, in f64.
    fn triangle(&self, i: usize) -> Triangle {
        let [a, b, c] = self.corners(i);
        Triangle::new(a, b, c)
    }

    /// `hit` on triangle `i` at `point`, completed there by barycentric weights: its (u, v)
    /// (the texture coordinates interpolated, or the weights of the second and third corners
    /// without them) and, on a smooth mesh, its shading normal (the vertex normals
    /// interpolated, turned to the geometric normal's side; a faceted mesh's hits keep their
    /// geometric normal).
    fn shaded(&self, i: usize, point: DVec3, hit: Hit) -> Hit {
        let [a, b, c] = self.corners(i);
        let (e1, e2, r) = (b - a, c - a, point - a);
        let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (d20, d21) = (r.dot(e1), r.dot(e2));
        let det = d00 * d11 - d01 * d01;
        let v = ((d11 * d20 - d01 * d21) / det).clamp(0.0, 1.0);
        let w = ((d00 * d21 - d01 * d20) / det).clamp(0.0, 1.0 - v);
        let (corner, weight) = (self.triangles[i], [1.0 - v - w, v, w]);
        let uv = match &self.texcoords {
            Some(t) => (0..3)
                .map(|k| weight[k] * DVec2::from(t[corner[k] as usize].map(f64::from)))
                .sum(),
            None => DVec2::new(v, w),
        };
        let uv = match self.v_from_top {
            true => DVec2::new(uv.x, 1.0 - uv.y),
            false => uv,
        };
        let shading = match &self.normals {
            Some(n) => (0..3)
                .map(|k| weight[k] * DVec3::from(n[corner[k] as usize].map(f64::from)))
                .sum::<DVec3>()
                .normalize_or_zero(),
            None => DVec3::ZERO,
        };
        let shading = match shading {
            DVec3::ZERO => hit.normal,
            s if s.dot(hit.normal) < 0.0 => -s,
            s => s,
        };
        Hit {
            shading,
            uv: Some(uv),
            ..hit
        }
    }

    /// Nearest hit of the straight ray o + t d (d unit) with t ∈ (t_min, t_max).
    pub fn intersect_ray(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let ray = TraversalRay::new(o, d, t_max);
        let mut best: Option<(usize, Hit)> = None;
        let mut hit = RayHit::none();
        self.bvh.ray_traverse(ray.ray, &mut hit, |_, i| {
            let id = self.bvh.primitive_indices[i] as usize;
            let limit = best.map_or(t_max, |(_, h)| h.t);
            match self.triangle(id).intersect_ray(o, d, t_min, limit) {
                Some(h) => {
                    best = Some((id, h));
                    TraversalRay::bound(h.t)
                }
                None => f32::INFINITY,
            }
        });
        best.map(|(id, h)| self.shaded(id, o + h.t * d, h))
    }

    /// Whether the straight ray o + t d (d unit) meets a triangle with t ∈ (t_min, t_max): an
    /// any-hit query, which stops at the first triangle it finds ([`Self::intersect_ray`]
    /// would go on to the nearest and complete its hit).
    pub fn meets_ray(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> bool {
        let ray = TraversalRay::new(o, d, t_max);
        let missed = self.bvh.ray_traverse_miss(ray.ray, |_, i| {
            let id = self.bvh.primitive_indices[i] as usize;
            match self.triangle(id).ray_parameter(o, d, t_min, t_max) {
                // Any value below the ray's bound ends the traversal.
                Some(_) => f32::NEG_INFINITY,
                None => f32::INFINITY,
            }
        });
        !missed
    }

    /// Calls `visit` with each triangle that may meet the path `hull` holds, until `visit`
    /// returns false: the BVH is descended where a node's box, grown by the hull's deviation,
    /// meets the hull's chord (a long diagonal step's own box would take in a whole patch of
    /// a fine mesh's surface), and a leaf's triangles are kept where
    /// their plane may be crossed ([`super::Plane::may_cross`]).
    fn candidates(&self, hull: &ArcHull, mut visit: impl FnMut(usize, Triangle) -> bool) {
        let Ball { center, radius } = self.core;
        let room = radius - hull.deviation;
        if (hull.a - center).length() < room && (hull.b - center).length() < room {
            return;
        }
        let nodes = &self.bvh.nodes;
        let mut stack = NodeStack::new();
        stack.push(0);
        while let Some(index) = stack.pop() {
            let node = &nodes[index as usize];
            let (lo, hi) = (node.aabb().min.as_dvec3(), node.aabb().max.as_dvec3());
            if !chord_meets_box(hull, lo - hull.deviation, hi + hull.deviation) {
                continue;
            }
            if node.is_leaf() {
                let leaf = node.first_index..node.first_index + node.prim_count;
                for i in leaf {
                    let id = self.bvh.primitive_indices[i as usize] as usize;
                    let [a, b, c] = self.corners(id);
                    let grow = DVec3::splat(hull.deviation);
                    let (lo, hi) = (a.min(b).min(c) - grow, a.max(b).max(c) + grow);
                    if !chord_meets_box(hull, lo, hi) {
                        continue;
                    }
                    let tri = Triangle::new(a, b, c);
                    if tri.plane().may_cross(hull) && !visit(id, tri) {
                        return;
                    }
                }
            } else {
                stack.push(node.first_index);
                stack.push(node.first_index + 1);
            }
        }
    }

    /// Whether any triangle may meet a path held by `hull`.
    pub fn may_cross(&self, hull: &ArcHull) -> bool {
        let mut found = false;
        self.candidates(hull, |_, _| {
            found = true;
            false
        });
        found
    }
}

/// Whether the segment from `hull.a` to `hull.b` meets the box [lo, hi] (slab test; a
/// degenerate chord is its end point).
fn chord_meets_box(hull: &ArcHull, lo: DVec3, hi: DVec3) -> bool {
    let d = hull.b - hull.a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..3 {
        if d[k] == 0.0 {
            if hull.a[k] < lo[k] || hull.a[k] > hi[k] {
                return false;
            }
            continue;
        }
        let (ta, tb) = ((lo[k] - hull.a[k]) / d[k], (hi[k] - hull.a[k]) / d[k]);
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// A traversal stack: 64 entries inline (a BVH of 10⁷ triangles is ~30 deep), more on the
/// heap for a degenerate tree.
struct NodeStack {
    inline: [u32; 64],
    len: usize,
    spill: Vec<u32>,
}

impl NodeStack {
    fn new() -> Self {
        Self {
            inline: [0; 64],
            len: 0,
            spill: Vec::new(),
        }
    }

    fn push(&mut self, v: u32) {
        if self.len < self.inline.len() {
            self.inline[self.len] = v;
            self.len += 1;
        } else {
            self.spill.push(v);
        }
    }

    fn pop(&mut self) -> Option<u32> {
        if let Some(v) = self.spill.pop() {
            return Some(v);
        }
        (self.len > 0).then(|| {
            self.len -= 1;
            self.inline[self.len]
        })
    }
}

/// Two meshes are equal when their vertices and triangles are (the BVH follows from them).
impl PartialEq for TriangleMesh {
    fn eq(&self, other: &Self) -> bool {
        self.vertices == other.vertices
            && self.triangles == other.triangles
            && self.normals == other.normals
            && self.texcoords == other.texcoords
    }
}

impl std::fmt::Debug for TriangleMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TriangleMesh")
            .field("vertices", &self.vertices.len())
            .field("triangles", &self.triangles.len())
            .field("smooth", &self.is_smooth())
            .finish()
    }
}

impl SegmentHits for TriangleMesh {
    type Found = Hit;

    fn intersect_segment<P: Path + ?Sized>(
        &self,
        seg: &P,
        hull: &ArcHull,
        s_min: f64,
        length: f64,
    ) -> Option<Hit> {
        let mut best: Option<(usize, Hit)> = None;
        self.candidates(hull, |id, tri| {
            let limit = best.map_or(length, |(_, h)| h.t);
            if let Some(h) = tri.intersect_segment(seg, s_min, limit) {
                best = Some((id, h));
            }
            true
        });
        best.map(|(id, h)| self.shaded(id, seg.at(h.t).position, h))
    }
}
