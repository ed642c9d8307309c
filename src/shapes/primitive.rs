//! The primitives: sphere, open cylinder (tube), parallelogram (quad), disk, triangle and
//! triangle mesh.

use super::hit::{Hit, SegmentHits};
use super::mesh::TriangleMesh;
use super::triangle::{edge_coordinates_hit, plane_coordinates, Plane, Triangle};
use crate::curve::{ArcHull, Path, RoundSurface};
use crate::math::{Ball, Bounds3};
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

/// The parallelogram origin + u·e1 + v·e2, u, v ∈ [0, 1], normal e1 × e2 normalised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    /// Corner v0.
    pub origin: DVec3,
    /// v1 − v0.
    pub e1: DVec3,
    /// v3 − v0.
    pub e2: DVec3,
}

impl Quad {
    /// Area (length²).
    pub fn area(&self) -> f64 {
        self.e1.cross(self.e2).length()
    }

    /// Its centre.
    pub fn center(&self) -> DVec3 {
        self.origin + 0.5 * (self.e1 + self.e2)
    }

    /// Unit normal, e1 × e2 normalised.
    pub fn normal(&self) -> DVec3 {
        self.e1.cross(self.e2).normalize()
    }

    /// The largest distance of a point of it from its centre.
    pub fn extent(&self) -> f64 {
        0.5 * (self.e1 + self.e2)
            .length()
            .max((self.e1 - self.e2).length())
    }

    /// A point uniformly distributed over it for `uv` uniform in [0, 1)².
    pub fn point_at(&self, (u, v): (f64, f64)) -> DVec3 {
        self.origin + u * self.e1 + v * self.e2
    }

    /// The parameter t ∈ (t_min, t_max) where the straight ray o + t d meets it.
    #[inline]
    pub fn ray_parameter(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<f64> {
        let (t, uv) = edge_coordinates_hit(self.origin, self.e1, self.e2, o, d, t_min, t_max)?;
        ((0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y)).then_some(t)
    }
}

/// A disk, or an annulus when `inner` > 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disk {
    /// Centre.
    pub center: DVec3,
    /// Unit normal.
    pub normal: DVec3,
    /// Outer radius.
    pub radius: f64,
    /// Inner radius (0: a full disk).
    pub inner: f64,
}

impl Disk {
    /// A full disk.
    pub fn full(center: DVec3, normal: DVec3, radius: f64) -> Self {
        Self {
            center,
            normal,
            radius,
            inner: 0.0,
        }
    }

    /// Area (length²).
    pub fn area(&self) -> f64 {
        PI * (self.radius * self.radius - self.inner * self.inner)
    }

    /// A point uniformly distributed over it (by area) for `uv` uniform in [0, 1)².
    pub fn point_at(&self, (u, v): (f64, f64)) -> DVec3 {
        let t = self.normal.any_orthonormal_vector();
        let b = self.normal.cross(t);
        let r = match self.inner > 0.0 {
            true => (self.inner * self.inner
                + u * (self.radius * self.radius - self.inner * self.inner))
                .sqrt(),
            false => self.radius * u.sqrt(),
        };
        let phi = TAU * v;
        self.center + r * (phi.cos() * t + phi.sin() * b)
    }
}

/// A surface primitive. Vectors in scene units.
#[derive(Clone, Debug, PartialEq)]
pub enum Primitive {
    /// A sphere.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// The side of a cylinder of `radius` from `base` along the unit `axis` for `height`
    /// (no caps: capped cylinders add two disks).
    Tube {
        /// Centre of the base circle.
        base: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius.
        radius: f64,
        /// Length along the axis.
        height: f64,
    },
    /// A parallelogram.
    Quad(Quad),
    /// A disk or an annulus.
    Disk(Disk),
    /// A triangle.
    Triangle(Triangle),
    /// A triangle mesh (shared, compact; its own BVH): one surface, many triangles.
    Mesh(Arc<TriangleMesh>),
}

impl Primitive {
    /// A triangle from three vertices.
    pub fn triangle(a: DVec3, b: DVec3, c: DVec3) -> Self {
        Primitive::Triangle(Triangle::new(a, b, c))
    }

    /// Axis-aligned bounds.
    pub fn bounds(&self) -> Bounds3 {
        match *self {
            Primitive::Sphere { center, radius } => Bounds3::new(center - radius, center + radius),
            Primitive::Tube {
                base,
                axis,
                radius,
                height,
            } => {
                // Each end circle's extent along world axis i is r·√(1 − a_i²).
                let ext = radius * (DVec3::ONE - axis * axis).max(DVec3::ZERO).sqrt();
                let top = base + axis * height;
                Bounds3::new(base.min(top) - ext, base.max(top) + ext)
            }
            Primitive::Quad(Quad { origin, e1, e2 }) => {
                Bounds3::of_points([origin, origin + e1, origin + e2, origin + e1 + e2])
            }
            Primitive::Disk(Disk {
                center,
                normal,
                radius,
                ..
            }) => {
                let ext = radius * (DVec3::ONE - normal * normal).max(DVec3::ZERO).sqrt();
                Bounds3::new(center - ext, center + ext)
            }
            Primitive::Triangle(Triangle { v0, e1, e2 }) => {
                Bounds3::of_points([v0, v0 + e1, v0 + e2])
            }
            Primitive::Mesh(ref mesh) => mesh.bounds(),
        }
    }

    /// A ball holding the primitive: a sphere's or a disk's own, otherwise the ball through
    /// its bounds' corners.
    pub fn bounding_ball(&self) -> Ball {
        match *self {
            Primitive::Sphere { center, radius } | Primitive::Disk(Disk { center, radius, .. }) => {
                Ball { center, radius }
            }
            Primitive::Triangle(..)
            | Primitive::Quad(..)
            | Primitive::Tube { .. }
            | Primitive::Mesh(..) => {
                let b = self.bounds();
                Ball {
                    center: b.center(),
                    radius: 0.5 * b.diagonal().length(),
                }
            }
        }
    }

    /// Whether the primitive's surface may come within `radius` of `point` — false only where
    /// it certainly does not: a sphere's surface by its distance, a planar primitive's by its
    /// plane's, any other's by its bounding ball.
    pub fn may_meet_ball(&self, point: DVec3, radius: f64) -> bool {
        if let Primitive::Sphere { center, radius: r } = *self {
            return ((point - center).length() - r).abs() <= radius;
        }
        if let Some(plane) = self.plane() {
            if (point - plane.point).dot(plane.normal).abs() > radius {
                return false;
            }
        }
        let ball = self.bounding_ball();
        point.distance(ball.center) <= ball.radius + radius
    }

    /// The plane of a planar primitive.
    fn plane(&self) -> Option<Plane> {
        let plane = |point, normal| Some(Plane { point, normal });
        match *self {
            Primitive::Quad(Quad { origin, e1, e2 }) => plane(origin, e1.cross(e2).normalize()),
            Primitive::Disk(Disk { center, normal, .. }) => plane(center, normal),
            Primitive::Triangle(t) => Some(t.plane()),
            Primitive::Sphere { .. } | Primitive::Tube { .. } | Primitive::Mesh(_) => None,
        }
    }

    /// Whether a point of a planar primitive's plane lies on the primitive (edges included).
    fn contains_planar(&self, p: DVec3) -> bool {
        match *self {
            Primitive::Quad(Quad { origin, e1, e2 }) => {
                let (u, v) = plane_coordinates(p - origin, e1, e2);
                (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v)
            }
            Primitive::Disk(Disk {
                center,
                radius,
                inner,
                ..
            }) => (inner * inner..=radius * radius).contains(&(p - center).length_squared()),
            Primitive::Triangle(t) => t.contains(p),
            Primitive::Sphere { .. } | Primitive::Tube { .. } | Primitive::Mesh(_) => false,
        }
    }

    /// Surface coordinates of a point `x` on the primitive: a sphere's and a tube's
    /// longitude (u, around the axis, 0 to 1) and latitude or height (v, 0 at the bottom, 1 at
    /// the top); a quad's (u, v) along its two edges from its first corner; a triangle's
    /// weights of its second and third corners; a disk's position across its square, 0 to 1
    /// (a mesh's come from its hits: the file's `vt` or the weights of the corners).
    pub fn uv_at(&self, x: DVec3) -> DVec2 {
        let around = |p: DVec3, axis: DVec3| {
            let (e1, e2) = axis.any_orthonormal_pair();
            0.5 + p.dot(e2).atan2(p.dot(e1)) / std::f64::consts::TAU
        };
        match *self {
            Primitive::Sphere { center, radius } => {
                let d = ((x - center) / radius).clamp(DVec3::NEG_ONE, DVec3::ONE);
                DVec2::new(around(d, DVec3::Y), 1.0 - d.y.acos() / std::f64::consts::PI)
            }
            Primitive::Tube {
                base, axis, height, ..
            } => DVec2::new(around(x - base, axis), (x - base).dot(axis) / height),
            Primitive::Quad(Quad { origin, e1, e2 }) => {
                plane_coordinates(x - origin, e1, e2).into()
            }
            Primitive::Triangle(Triangle { v0, e1, e2 }) => {
                plane_coordinates(x - v0, e1, e2).into()
            }
            Primitive::Disk(Disk {
                center,
                normal,
                radius,
                ..
            }) => {
                let (e1, e2) = normal.any_orthonormal_pair();
                let p = (x - center) / (2.0 * radius);
                DVec2::new(0.5 + p.dot(e1), 0.5 + p.dot(e2))
            }
            Primitive::Mesh(_) => DVec2::ZERO,
        }
    }

    /// Nearest hit of the straight ray o + t d (d unit) with t ∈ (t_min, t_max).
    pub fn intersect_ray(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        if let Primitive::Mesh(mesh) = self {
            return mesh.intersect_ray(o, d, t_min, t_max);
        }
        self.flat_ray_hit(o, d, t_min, t_max)
    }

    /// Whether the straight ray o + t d (d unit) meets the primitive with t ∈ (t_min, t_max):
    /// [`Self::intersect_ray`]'s answer without the hit (a shadow ray's question; a mesh
    /// stops at the first triangle it finds).
    pub fn meets_ray(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> bool {
        match self {
            Primitive::Mesh(mesh) => mesh.meets_ray(o, d, t_min, t_max),
            Primitive::Quad(q) => q.ray_parameter(o, d, t_min, t_max).is_some(),
            Primitive::Triangle(t) => t.ray_parameter(o, d, t_min, t_max).is_some(),
            Primitive::Sphere { .. } | Primitive::Tube { .. } | Primitive::Disk(..) => {
                self.flat_ray_hit(o, d, t_min, t_max).is_some()
            }
        }
    }

    /// [`Self::intersect_ray`] for the analytic primitives.
    fn flat_ray_hit(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let valid = |t: f64| t > t_min && t < t_max;
        match *self {
            Primitive::Mesh(_) => None,
            Primitive::Sphere { center, radius } => {
                // Hearn & Baker: discriminant from the perpendicular offset (no cancellation).
                let oc = o - center;
                let b = oc.dot(d);
                let perp = oc - b * d;
                let disc = radius * radius - perp.length_squared();
                if disc < 0.0 {
                    return None;
                }
                let q = -b - b.signum() * disc.sqrt();
                let c = oc.length_squared() - radius * radius;
                let (t0, t1) = ordered(q, if q != 0.0 { c / q } else { 0.0 });
                [t0, t1]
                    .into_iter()
                    .find(|&t| valid(t))
                    .map(|t| Hit::flat(t, (o + t * d - center) / radius))
            }
            Primitive::Tube {
                base,
                axis,
                radius,
                height,
            } => {
                let oc = o - base;
                let dp = across_axis(d, axis);
                let op = across_axis(oc, axis);
                let a = dp.length_squared();
                if a == 0.0 {
                    return None;
                }
                let b = op.dot(dp);
                let c = op.length_squared() - radius * radius;
                let disc = b * b - a * c;
                if disc < 0.0 {
                    return None;
                }
                let q = -b - b.signum() * disc.sqrt();
                let (t0, t1) = ordered(q / a, if q != 0.0 { c / q } else { 0.0 });
                [t0, t1].into_iter().find_map(|t| {
                    let h = (oc + t * d).dot(axis);
                    (valid(t) && (0.0..=height).contains(&h)).then(|| {
                        let p = oc + t * d;
                        Hit::flat(t, (p - axis * p.dot(axis)).normalize())
                    })
                })
            }
            Primitive::Quad(q) => {
                let t = q.ray_parameter(o, d, t_min, t_max)?;
                Some(Hit::flat(t, q.normal()))
            }
            Primitive::Triangle(t) => t.intersect_ray(o, d, t_min, t_max),
            Primitive::Disk(..) => {
                let plane = self.plane()?;
                let t = plane.ray_hit(o, d, t_min, t_max)?;
                self.contains_planar(o + t * d)
                    .then_some(Hit::flat(t, plane.normal))
            }
        }
    }

    /// The primitive's surface as a plane or a sphere, if it is one (a ray's circle meets it
    /// in closed form); None for a cylinder's side and a mesh.
    fn round_surface(&self) -> Option<RoundSurface> {
        match *self {
            Primitive::Sphere { center, radius } => Some(RoundSurface::sphere(center, radius)),
            Primitive::Tube { .. } | Primitive::Mesh(_) => None,
            Primitive::Quad(..) | Primitive::Disk(..) | Primitive::Triangle(_) => {
                self.plane().map(|p| p.surface())
            }
        }
    }

    /// Whether a point where the implicit function vanishes is on the primitive proper.
    pub(crate) fn accepts(&self, x: DVec3) -> bool {
        match *self {
            Primitive::Sphere { .. } => true,
            Primitive::Tube {
                base, axis, height, ..
            } => (0.0..=height).contains(&(x - base).dot(axis)),
            Primitive::Quad(..)
            | Primitive::Disk(..)
            | Primitive::Triangle(_)
            | Primitive::Mesh(_) => self.contains_planar(x),
        }
    }

    /// The unit geometric normal at a surface point (convention as in [`Hit`]).
    pub fn normal_at(&self, x: DVec3) -> DVec3 {
        match *self {
            Primitive::Sphere { center, .. } => (x - center).normalize(),
            Primitive::Tube { base, axis, .. } => across_axis(x - base, axis).normalize(),
            // A mesh's points are its triangles': asked of them, never of the mesh.
            Primitive::Quad(..)
            | Primitive::Disk(..)
            | Primitive::Triangle(_)
            | Primitive::Mesh(_) => self.plane().expect("planar").normal,
        }
    }

    /// Whether a curved segment held by `hull` may cross the primitive's surface: false when
    /// the capsule lies wholly on one side of it (inside or outside a sphere or a cylinder,
    /// beyond a cylinder's ends, on one side of a plane). Distances from the axis, the centre
    /// or a plane are convex along the chord, so their largest values are at its ends.
    pub fn may_cross(&self, hull: &ArcHull) -> bool {
        let dev = hull.deviation;
        match *self {
            Primitive::Mesh(ref mesh) => mesh.may_cross(hull),
            Primitive::Sphere { center, radius } => {
                let far = (hull.a - center).length().max((hull.b - center).length());
                far + dev >= radius && hull.chord_distance(center) - dev <= radius
            }
            Primitive::Tube {
                base,
                axis,
                radius,
                height,
            } => {
                let along = |x: DVec3| (x - base).dot(axis);
                let off_axis = |x: DVec3| across_axis(x - base, axis).length();
                let (za, zb) = (along(hull.a), along(hull.b));
                let beyond_ends = za.max(zb) < -dev || za.min(zb) > height + dev;
                let inside = off_axis(hull.a).max(off_axis(hull.b)) + dev < radius;
                !(beyond_ends || inside)
            }
            Primitive::Quad(..) | Primitive::Disk(..) | Primitive::Triangle(_) => {
                self.plane().expect("planar").may_cross(hull)
            }
        }
    }
}

/// A short description for reports, e.g. "cylinder side r 0.5 at (0, 0, 0) along (0, 0, 1)".
impl std::fmt::Display for Primitive {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
        match *self {
            Primitive::Sphere { center, radius } => write!(f, "sphere r {radius} at {}", v(center)),
            Primitive::Tube {
                base,
                axis,
                radius,
                height,
            } => write!(
                f,
                "cylinder side r {radius} at {} along {} for {height}",
                v(base),
                v(axis)
            ),
            // Its centre and the way it faces: a box's six faces each read apart.
            Primitive::Quad(Quad { origin, e1, e2 }) => write!(
                f,
                "quad at {} facing {}",
                v(origin + 0.5 * (e1 + e2)),
                v(e1.cross(e2).normalize_or_zero())
            ),
            Primitive::Disk(Disk {
                center,
                normal,
                radius,
                inner,
            }) => {
                let ring = if inner > 0.0 {
                    format!("r {inner}–{radius}")
                } else {
                    format!("r {radius}")
                };
                write!(f, "disk {ring} at {} facing {}", v(center), v(normal))
            }
            Primitive::Triangle(t) => write!(f, "triangle at {}", v(t.v0)),
            Primitive::Mesh(ref mesh) => {
                let b = mesh.bounds();
                write!(
                    f,
                    "mesh of {} triangles in {} – {}",
                    mesh.len(),
                    v(b.lo),
                    v(b.hi)
                )
            }
        }
    }
}

fn ordered(a: f64, b: f64) -> (f64, f64) {
    if a <= b {
        (a, b)
    } else {
        (b, a)
    }
}

/// The part of `v` across the unit `axis` (a tube's radial offset).
fn across_axis(v: DVec3, axis: DVec3) -> DVec3 {
    v - axis * v.dot(axis)
}

impl SegmentHits for Primitive {
    type Found = Hit;

    fn intersect_segment<P: Path + ?Sized>(
        &self,
        seg: &P,
        hull: &ArcHull,
        s_min: f64,
        length: f64,
    ) -> Option<Hit> {
        // A mesh culls its triangles by the hull as it searches; any other primitive first asks
        // whether the hull can meet it at all (a cheap test before a root search).
        if let Primitive::Mesh(mesh) = self {
            return mesh.intersect_segment(seg, hull, s_min, length);
        }
        if !self.may_cross(hull) {
            return None;
        }
        let roots = match *self {
            Primitive::Tube {
                base, axis, radius, ..
            } => super::segment_roots(seg, length, |x| {
                let p = across_axis(x - base, axis);
                (p.length_squared() - radius * radius, 2.0 * p)
            }),
            // (A mesh returned above: it has no round surface.)
            Primitive::Sphere { .. }
            | Primitive::Quad(..)
            | Primitive::Disk(..)
            | Primitive::Triangle(_)
            | Primitive::Mesh(_) => super::round_roots(seg, length, &self.round_surface()?),
        };
        roots.into_iter().filter(|&s| s > s_min).find_map(|s| {
            let x = seg.at(s).position;
            self.accepts(x).then(|| Hit::flat(s, self.normal_at(x)))
        })
    }
}
