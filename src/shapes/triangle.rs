//! Planes and triangles: the geometry a planar primitive (quad, disk, triangle) and a mesh's
//! triangles share — where a straight ray or a curved path meets a plane, and whether a point
//! of the plane lies in a triangle.

use super::curved::round_roots;
use super::hit::Hit;
use crate::curve::{ArcHull, Path, RoundSurface};
use glam::{DVec2, DVec3};

/// The plane through `point` with unit `normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point on it.
    pub point: DVec3,
    /// Its unit normal.
    pub normal: DVec3,
}

impl Plane {
    /// Where the straight ray o + t d meets the plane, t ∈ (t_min, t_max) (None: parallel, or
    /// outside the range).
    pub fn ray_hit(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let denom = d.dot(self.normal);
        if denom == 0.0 {
            return None;
        }
        let t = (self.point - o).dot(self.normal) / denom;
        (t > t_min && t < t_max).then_some(t)
    }

    /// The plane as a level set: g(x) its signed distance, whose roots along a curved path
    /// are its crossings.
    pub fn surface(&self) -> RoundSurface {
        RoundSurface::plane(self.point, self.normal)
    }

    /// The signed distance of `x` from the plane.
    pub fn distance(&self, x: DVec3) -> f64 {
        (x - self.point).dot(self.normal)
    }

    /// Whether a curved path held by `hull` may cross the plane: false when the capsule lies
    /// wholly on one side (the distance is linear along the chord, so its extremes are at the
    /// ends).
    pub fn may_cross(&self, hull: &ArcHull) -> bool {
        let dev = hull.deviation;
        let (oa, ob) = (self.distance(hull.a), self.distance(hull.b));
        oa.min(ob) <= dev && oa.max(ob) >= -dev
    }
}

/// Coordinates (u, v) of an in-plane vector r = u e1 + v e2.
pub fn plane_coordinates(r: DVec3, e1: DVec3, e2: DVec3) -> (f64, f64) {
    let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (p, q) = (r.dot(e1), r.dot(e2));
    let det = a * c - b * b;
    ((c * p - b * q) / det, (a * q - b * p) / det)
}

/// Where the straight ray o + t d meets the plane spanned by `e1` and `e2` through `origin`,
/// t ∈ (t_min, t_max): t and the point's coordinates (u, v), origin + u e1 + v e2 — Möller and
/// Trumbore's determinants, which need neither the plane's unit normal nor a division per
/// coordinate (None: parallel to the plane, or out of range).
pub fn edge_coordinates_hit(
    origin: DVec3,
    e1: DVec3,
    e2: DVec3,
    o: DVec3,
    d: DVec3,
    t_min: f64,
    t_max: f64,
) -> Option<(f64, DVec2)> {
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - origin;
    let q = s.cross(e1);
    let t = e2.dot(q) * inv;
    (t > t_min && t < t_max).then(|| (t, DVec2::new(s.dot(p) * inv, d.dot(q) * inv)))
}

/// The triangle v0, v0 + e1, v0 + e2; its normal e1 × e2 normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// First vertex.
    pub v0: DVec3,
    /// v1 − v0.
    pub e1: DVec3,
    /// v2 − v0.
    pub e2: DVec3,
}

impl Triangle {
    /// The triangle of corners a, b, c.
    pub fn new(a: DVec3, b: DVec3, c: DVec3) -> Self {
        Triangle {
            v0: a,
            e1: b - a,
            e2: c - a,
        }
    }

    /// Its plane.
    pub fn plane(&self) -> Plane {
        Plane {
            point: self.v0,
            normal: self.e1.cross(self.e2).normalize(),
        }
    }

    /// Whether a point of its plane lies in it (edges included).
    pub fn contains(&self, p: DVec3) -> bool {
        let (u, v) = plane_coordinates(p - self.v0, self.e1, self.e2);
        u >= 0.0 && v >= 0.0 && u + v <= 1.0
    }

    /// Nearest hit of the straight ray o + t d with t ∈ (t_min, t_max) (its (u, v) not set).
    pub fn intersect_ray(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let t = self.ray_parameter(o, d, t_min, t_max)?;
        Some(Hit::flat(t, self.plane().normal))
    }

    /// The parameter t ∈ (t_min, t_max) where the straight ray o + t d meets the triangle:
    /// [`Self::intersect_ray`]'s test without its normal (a shadow ray's question).
    #[inline]
    pub fn ray_parameter(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let (t, uv) = edge_coordinates_hit(self.v0, self.e1, self.e2, o, d, t_min, t_max)?;
        (uv.x >= 0.0 && uv.y >= 0.0 && uv.x + uv.y <= 1.0).then_some(t)
    }

    /// Nearest crossing of a curved path at arclength s ∈ (s_min, length] (its (u, v) not
    /// set).
    pub fn intersect_segment<P: Path + ?Sized>(
        &self,
        seg: &P,
        s_min: f64,
        length: f64,
    ) -> Option<Hit> {
        let plane = self.plane();
        round_roots(seg, length, &plane.surface())
            .into_iter()
            .filter(|&s| s > s_min)
            .find_map(|s| {
                let x = seg.at(s).position;
                self.contains(x).then_some(Hit::flat(s, plane.normal))
            })
    }
}
