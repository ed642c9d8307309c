//! Where a ray meets a surface, and the boxes BVHs hold.

use crate::curve::{ArcHull, Path};
use crate::math::Bounds3;
use glam::{DVec2, DVec3, Vec3A};
use obvhs::aabb::Aabb;

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
