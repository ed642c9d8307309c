//! Where a ray meets a surface, and the boxes and rays BVHs take.

use crate::curve::{ArcHull, Path};
use crate::math::Bounds3;
use glam::{DVec2, DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::ray::Ray;

/// Where a ray meets a primitive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along a straight ray, or arclength along a curved segment.
    pub t: f64,
    /// Unit geometric normal at the hit: outward for spheres and tubes, the primitive's own
    /// normal for quads, disks and triangles (not flipped toward the ray).
    pub normal: DVec3,
    /// Unit shading normal, on the same side as `normal`: a smooth mesh's interpolated
    /// vertex normal, else `normal` itself.
    pub shading: DVec3,
    /// Surface coordinates (u, v) of a mesh's hit (its `vt`, or the weights of the corners);
    /// None for an analytic primitive, whose come from [`super::Primitive::uv_at`] at the
    /// point when a texture asks (most hits are never textured: candidates a nearer hit
    /// replaces, shadow rays, untextured surfaces).
    pub uv: Option<DVec2>,
}

impl Hit {
    /// A hit whose shading normal is its geometric one, without (u, v).
    pub fn flat(t: f64, normal: DVec3) -> Self {
        Self {
            t,
            normal,
            shading: normal,
            uv: None,
        }
    }
}

/// An f32 box containing the f64 box `b`, rounded outward (BVHs hold f32 boxes; the exact
/// tests are in f64).
pub(crate) fn padded_box(b: Bounds3) -> Aabb {
    let pad = |v: DVec3| v.abs() * 1e-6 + DVec3::splat(1e-6);
    Aabb::new(
        Vec3A::from((b.lo - pad(b.lo)).as_vec3()),
        Vec3A::from((b.hi + pad(b.hi)).as_vec3()),
    )
}

/// Where a curved path first meets a surface: the question the march asks of a step's path
/// (an exact arc, a step's Hermite path), of a primitive, a mesh and the whole scene alike.
pub trait SegmentHits {
    /// What a hit reports: the [`Hit`], and for a set of surfaces which one it is.
    type Found;

    /// Nearest crossing of the path `seg`, held by `hull` over [0, `length`], at arclength
    /// s ∈ (`s_min`, `length`] (None at once where the hull cannot reach a surface).
    fn intersect_segment<P: Path + ?Sized>(
        &self,
        seg: &P,
        hull: &ArcHull,
        s_min: f64,
        length: f64,
    ) -> Option<Self::Found>;
}

/// A straight ray o + t d as the BVHs' f32 traversals take it, conservatively: no node
/// holding a hit the f64 test would find is skipped.
///
/// Its inverse direction is 1/d, with ±K = ±10²⁰ only where a component is below 1/K.
/// obvhs's `Ray::new` takes K = 1/ε (ε = 1.2e-7) below ε, so a ray nearly parallel to a
/// slab's faces leaves the slab, in the box test, before it truly does. A hit at t inside a
/// primitive's box, which the node's box holds with a padding p ≥ 10⁻⁶ ([`padded_box`]), puts
/// the origin at least p − t |d_i| inside the node's face; the test has the ray leave after
/// (p − t |d_i|) K ≥ pK − t, so it keeps every hit at t ≤ pK/2: 4 units with obvhs's K and
/// p = 10⁻⁶ (a ray along a wall missed the far wall 100 units on, `tests/shapes.rs`), 5·10¹³
/// with 10²⁰. And |b − o| K stays finite for |b − o| up to 3·10¹⁸.
pub(crate) struct TraversalRay {
    /// The f32 ray, its bound `t_max` rounded up.
    pub(crate) ray: Ray,
}

impl TraversalRay {
    /// The ray o + t d (d unit) for t up to `t_max`.
    pub(crate) fn new(o: DVec3, d: DVec3, t_max: f64) -> Self {
        let direction = Vec3A::from(d.as_vec3());
        // Built field by field: `Ray::new` would invert the direction its own way first.
        let ray = Ray {
            origin: Vec3A::from(o.as_vec3()),
            direction,
            inv_direction: direction.signum() / direction.abs().max(Vec3A::splat(1e-20)),
            tmin: 0.0,
            tmax: Self::bound(t_max),
        };
        Self { ray }
    }

    /// The f32 bound of the ray's parameter t: rounded up, so that it never culls a node
    /// holding a hit at t (an f64 tie included).
    pub(crate) fn bound(t: f64) -> f32 {
        (t as f32).next_up()
    }
}
