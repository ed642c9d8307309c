//! The visibility query: the one shadow ray. A straight connection from a point through a
//! uniform medium is blocked by any surface but a receiver's detector (detectors are
//! transparent to every query), and keeps exp(−∫(σa + σs) ds) of the light: what a
//! scattering medium scatters out of it is lost to it.

use super::{offset, Tracer};
use crate::color::Rgb;
use crate::ids::{MediumId, PrimId};
use crate::math::Bounds3;
use glam::DVec3;
use std::cell::OnceCell;

/// The fraction of light per channel kept along the straight segment from `from` along
/// unit `dir` over `reach` (∞: to the world sphere) in `medium`: 0 if a surface other than a
/// detector lies on it ([`blocked`]) — but for an index-matched boundary between uniform
/// media ([`Tracer::crosses_unchanged`]), which the segment crosses into the medium beyond —
/// else what the media on the way let through ([`Tracer::transmittance`]: neither absorbed
/// nor scattered out of the line).
pub fn transmittance(
    tracer: &Tracer,
    from: DVec3,
    medium: Option<MediumId>,
    dir: DVec3,
    reach: f64,
) -> Rgb {
    // The world's edge is sought only where a medium's transmittance reads the length.
    let length = || reach.min(tracer.world.exit_distance(from, dir));
    if !tracer.may_match_indices {
        if blocked(tracer, from, dir, reach) {
            return Rgb::ZERO;
        }
        return match medium {
            Some(_) => tracer.transmittance(medium, from, dir, length()),
            None => Rgb::ONE,
        };
    }
    let length = length();
    let scene = tracer.scene;
    let (mut origin, mut medium, mut kept) = (from, medium, Rgb::ONE);
    for _ in 0..super::chain::MAX_CROSSINGS {
        // What is left of the segment from here.
        let gone = (origin - from).dot(dir);
        let (left, span) = (reach - gone, length - gone);
        let Some(found) = scene.accel.intersect_ray(origin, dir, 0.0, left) else {
            return kept * tracer.transmittance(medium, origin, dir, span.max(0.0));
        };
        kept *= tracer.transmittance(medium, origin, dir, found.hit.t);
        let hit = super::SurfaceHit::straight(origin, dir, found);
        let surface = scene.surface(found.prim);
        if !surface.is_detector() {
            let crossed = tracer
                .vertex(hit, surface, medium)
                .filter(|v| tracer.crosses_unchanged(v));
            let Some(vertex) = crossed else {
                return Rgb::ZERO;
            };
            medium = vertex.beyond;
        }
        origin = offset(hit.position, dir);
    }
    Rgb::ZERO
}

/// Whether a surface other than a detector lies on the straight segment from `from` along
/// unit `dir` over `reach`.
pub fn blocked(tracer: &Tracer, from: DVec3, dir: DVec3, reach: f64) -> bool {
    let scene = tracer.scene;
    scene.accel.blocked(from, dir, 0.0, reach, |prim| {
        scene.surface(prim).is_detector()
    })
}

/// The surfaces that may stand between a point on a surface and the photons a density
/// estimate reads around it: every primitive but the point's own whose surface may meet the
/// estimate's ball (its box meets the ball's, and [`crate::shapes::Primitive::may_meet_ball`]: a glass ball
/// resting on the floor stands in the way only of estimates near where it touches). A photon behind one of them — on the far side of a thin wall standing on
/// the floor — lit another place than this one, and a disc estimate that read it would leak
/// that light through the wall (a bright caustic inside a ring read outside it). Detectors
/// hide nothing. They are looked up at the first photon asked about (most estimates find
/// none); at most [`Near::KEPT`] are kept, and a crowded neighbourhood asks the whole scene.
pub struct Occluders<'a> {
    tracer: &'a Tracer<'a>,
    /// The point's primitive.
    prim: PrimId,
    position: DVec3,
    radius: f64,
    near: OnceCell<Near>,
}

/// The primitives near a point that may hide photons from it.
struct Near {
    ids: [PrimId; Near::KEPT],
    count: usize,
}

impl Near {
    /// Primitives listed one by one before a query falls back to the whole scene.
    const KEPT: usize = 8;
}

impl<'a> Occluders<'a> {
    /// The surfaces that may hide photons within `radius` of `position` (on primitive
    /// `prim`) from points on that primitive within the ball.
    pub fn around(tracer: &'a Tracer<'a>, prim: PrimId, position: DVec3, radius: f64) -> Self {
        Self {
            tracer,
            prim,
            position,
            radius,
            near: OnceCell::new(),
        }
    }

    fn near(&self) -> &Near {
        self.near.get_or_init(|| {
            let scene = self.tracer.scene;
            let mut near = Near {
                ids: [PrimId::new(0); Near::KEPT],
                count: 0,
            };
            let reach = DVec3::splat(self.radius);
            let ball_box = Bounds3::new(self.position - reach, self.position + reach);
            // Room for the points' offsets off their surfaces (math::offset) and rounding.
            let radius = self.radius + 1e-6 * (self.radius + self.position.abs().max_element());
            scene.accel.boxes_meeting(ball_box, |id| {
                let detector = scene.surface(id).is_detector();
                let meets = scene
                    .accel
                    .primitive(id)
                    .may_meet_ball(self.position, radius);
                if id != self.prim && !detector && meets {
                    if near.count < Near::KEPT {
                        near.ids[near.count] = id;
                    }
                    near.count += 1;
                }
            });
            near
        })
    }

    /// Whether the straight segment from `origin` (a point on the primitive within the ball,
    /// offset off its surface: [`offset`]) to `position` (a photon's, offset along its unit
    /// `normal` as the point is) crosses a surface.
    pub fn hide(&self, origin: DVec3, position: DVec3, normal: DVec3) -> bool {
        let near = self.near();
        if near.count == 0 {
            return false;
        }
        let d = offset(position, normal) - origin;
        let length = d.length();
        if length <= 0.0 {
            return false;
        }
        let (dir, reach) = (d / length, length * (1.0 - 1e-7));
        let accel = &self.tracer.scene.accel;
        match near.count <= Near::KEPT {
            true => near.ids[..near.count].iter().any(|&id| {
                accel
                    .primitive(id)
                    .intersect_ray(origin, dir, 0.0, reach)
                    .is_some()
            }),
            false => blocked(self.tracer, origin, dir, reach),
        }
    }
}
