//! A pixel's footprint where its camera path meets a surface, through whatever lies on the way
//! — a glass ball, a mirror, a GRIN lens — measured by finite-difference ray differentials
//! (Igehy 1999): the camera rays through film points half a pixel away from the sample's are
//! followed along the same chain, with the same choices between reflection and refraction,
//! and where they meet the same surface after as many bounces, their points' offsets from the
//! sample's span the footprint. Seen straight on, this is the pixel's width times the
//! distance (stretched along a slanting surface), and the neighbouring rays are not traced:
//! they meet the surface's tangent plane (first order, as the traced ones are); seen through
//! a lens, the footprint is magnified or shrunk as the view through the lens is.

use super::beam::Beams;
use super::direct::camera_path;
use super::CameraRay;
use crate::camera::{Camera, PrimaryRay};
use crate::ids::PrimId;
use crate::sample_stream::SampleStream;
use crate::transport::chain::Carried;
use crate::transport::{Stats, SurfaceVertex, Vertex};
use glam::DVec3;

/// How many times wider than seen straight on at the same distance a footprint may be for it
/// to be looked for ([`Eye::may_exceed`]): behind a lens or a convex mirror that widens the
/// view more than this, a footprint wider than the k-nearest radius may go unmeasured, and
/// the radius stays the k-nearest one. (Through the Cornell box's glass ball the footprint is
/// narrower than straight on.)
const WIDENING: f64 = 4.0;

/// How far (in pixels) a neighbouring film point lies from the sample's: near enough that the
/// view changes smoothly between them, far enough that the offset of their points is not
/// lost in the rounding of the hits.
const STEP: f64 = 0.5;

/// Where a camera sample's path met its visible point: what a neighbouring ray must meet to
/// have taken the same way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Way {
    /// The primitive of the visible point.
    pub prim: PrimId,
    /// The specular bounces before it.
    pub bounces: u32,
    /// Whether it crossed a gradient medium (a curved stretch) on the way.
    pub curved: bool,
}

impl Way {
    /// One straight stretch from the camera: no bounce, no gradient medium.
    pub fn is_straight(&self) -> bool {
        self.bounces == 0 && !self.curved
    }
}

/// The camera, as footprints are measured from it.
pub struct Eye<'a> {
    camera: &'a Camera,
    /// The angle a pixel spans at the film's centre (rad; 0 for an orthographic camera).
    pixel_angle: f64,
}

impl<'a> Eye<'a> {
    /// The eye of `camera`.
    pub fn new(camera: &'a Camera) -> Self {
        Self {
            camera,
            pixel_angle: camera.pixel_angle(),
        }
    }

    /// Whether half the smallest width of the footprint at `x` may exceed √`r2`: whether it
    /// does seen straight on from [`WIDENING`] times the distance. Where it may not, a radius
    /// of √`r2` needs no floor, and a footprint seen through a lens or a GRIN medium (whose
    /// neighbouring rays are traced) is not measured: in a dim part of a caustic, where the
    /// k-nearest radius is wide, that would be the cost of a camera path or two for nothing.
    pub fn may_exceed(&self, x: DVec3, r2: f64) -> bool {
        let half = 0.5 * WIDENING * self.camera.pixel_width_at(self.pixel_angle, x);
        r2 < half * half
    }

    /// Half the smallest width of a pixel's footprint at `v`, the visible point a camera
    /// sample reached along `way` (the smaller semi-axis of the ellipse that the pixel's
    /// square, mapped onto the surface to first order, holds): the largest radius a density
    /// estimate there can have without blurring what the pixel sees by more than the pixel
    /// does. `ray` is the sample's camera ray, `carried` and `rng` what its path started with
    /// (a copy of its random stream before the path drew from it, so the neighbours make the
    /// same choices). None where no neighbour along one of the film's axes took the same way
    /// (a silhouette on both sides, a choice that went the other way).
    pub fn half_width(
        &self,
        ray: &CameraRay,
        carried: Carried,
        rng: &SampleStream,
        v: &SurfaceVertex,
        way: Way,
        stats: &mut Stats,
    ) -> Option<f64> {
        let offset = |du: f64, dv: f64, stats: &mut Stats| -> Option<DVec3> {
            let film = ray.film.moved(du, dv);
            let PrimaryRay { origin, direction } = self.camera.ray(film);
            let step = du.abs().max(dv.abs());
            if way.is_straight() {
                // Where the neighbouring ray meets the tangent plane at `v`.
                let t = (v.position - origin).dot(v.normal) / direction.dot(v.normal);
                return t
                    .is_finite()
                    .then(|| (origin + t * direction - v.position) / step);
            }
            let neighbour = CameraRay {
                origin,
                direction,
                film,
                ..*ray
            };
            let c = camera_path(
                carried,
                neighbour,
                &mut Beams::default(),
                &mut None,
                &mut rng.clone(),
                stats,
            );
            match c.visible.map(|vp| vp.vertex) {
                Some(Vertex::Surface(w)) if w.prim == way.prim && c.bounces == way.bounces => {
                    Some((w.position - v.position) / step)
                }
                Some(Vertex::Surface(_) | Vertex::Medium(_)) | None => None,
            }
        };
        // Each axis's derivative from the neighbour ahead, else from the one behind (its sign
        // does not change the footprint).
        let dx = offset(STEP, 0.0, stats).or_else(|| offset(-STEP, 0.0, stats))?;
        let dy = offset(0.0, STEP, stats).or_else(|| offset(0.0, -STEP, stats))?;
        let smallest = smallest_singular_value(tangential(dx, v.normal), tangential(dy, v.normal));
        Some(0.5 * smallest)
    }
}

/// `d` without its component along the unit `normal`.
fn tangential(d: DVec3, normal: DVec3) -> DVec3 {
    d - normal * d.dot(normal)
}

/// The smaller singular value of the 3 × 2 matrix [a b]: the smaller semi-axis of the ellipse
/// that the map (s, t) ↦ s a + t b takes the unit circle to (√ of the smaller eigenvalue of
/// its Gram matrix).
fn smallest_singular_value(a: DVec3, b: DVec3) -> f64 {
    let (aa, bb) = (a.length_squared(), b.length_squared());
    let half_trace = 0.5 * (aa + bb);
    // det = |a × b|², exact where aa·bb − ab² would cancel.
    let det = a.cross(b).length_squared();
    let spread = (half_trace * half_trace - det).max(0.0).sqrt();
    // The smaller root of λ² − (aa + bb) λ + det, without the cancellation of half_trace −
    // spread: det / the larger root.
    let larger = half_trace + spread;
    match larger > 0.0 {
        true => (det / larger).sqrt(),
        false => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smallest_singular_value_of_known_maps() {
        // A square stretched along x: the short side.
        let v = smallest_singular_value(DVec3::new(3.0, 0.0, 0.0), DVec3::new(0.0, 0.5, 0.0));
        assert!((v - 0.5).abs() < 1e-15);
        // Rotated and in 3D: the same.
        let r = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7);
        let v =
            smallest_singular_value(r * DVec3::new(3.0, 0.0, 0.0), r * DVec3::new(0.0, 0.5, 0.0));
        assert!((v - 0.5).abs() < 1e-14);
        // A shear: [1 1; 0 1] has singular values (√5 ± 1)/2.
        let v = smallest_singular_value(DVec3::X, DVec3::new(1.0, 1.0, 0.0));
        assert!((v - (5f64.sqrt() - 1.0) / 2.0).abs() < 1e-15);
        // Degenerate: parallel columns.
        assert_eq!(smallest_singular_value(DVec3::X, 2.0 * DVec3::X), 0.0);
        assert_eq!(smallest_singular_value(DVec3::ZERO, DVec3::ZERO), 0.0);
    }
}
