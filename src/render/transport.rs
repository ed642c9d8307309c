//! Moving a ray through the scene to its next event: straight through uniform media (BVH ray
//! traversal), curved through gradient media (the march, each accepted step tested against
//! the BVH as an exact arc).

use super::stats::Stats;
use crate::curve::{march_with, Bounds, CurvedSegment, MarchLimits, RayState, Termination};
use crate::scene::Scene;
use glam::DVec3;
use std::ops::ControlFlow;

/// What a ray meets next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A surface: the primitive, the hit point, the primitive's geometric normal there and
    /// the ray's direction on arrival.
    Surface {
        /// Primitive index.
        prim: usize,
        /// Hit point.
        position: DVec3,
        /// Geometric normal (see [`crate::shapes::Hit`]).
        normal: DVec3,
        /// Unit direction of arrival.
        direction: DVec3,
    },
    /// The ray left the world in this direction.
    Escaped(DVec3),
    /// The ray ended without reaching a surface or escaping: captured, out of steps, or lost
    /// inside an object it should have left (reported in the statistics).
    Lost,
}

/// Where rays travel: the scene and the sphere beyond which they count as escaped.
pub struct Tracer<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The world sphere.
    pub world: Bounds,
}

impl<'a> Tracer<'a> {
    /// The tracer of a scene; the world sphere is the scene's `world_radius` around the centre
    /// of everything in it (primitives and camera), or 10× its extent (at least 10 units).
    pub fn new(scene: &'a Scene) -> Self {
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for p in scene.accel.primitives() {
            let (a, b) = p.bounds();
            lo = lo.min(a);
            hi = hi.max(b);
        }
        if let Some(c) = &scene.camera {
            lo = lo.min(c.position);
            hi = hi.max(c.position);
        }
        if !lo.is_finite() {
            (lo, hi) = (DVec3::ZERO, DVec3::ZERO);
        }
        let center = 0.5 * (lo + hi);
        let extent = 0.5 * (hi - lo).length();
        let radius = scene.render.world_radius.unwrap_or(10.0 * extent.max(1.0));
        Self {
            scene,
            world: Bounds::Ball { center, radius },
        }
    }

    /// The next event of a ray from `origin` along unit `dir` inside medium `medium` (None:
    /// vacuum).
    pub fn next_event(
        &self,
        origin: DVec3,
        dir: DVec3,
        medium: Option<usize>,
        stats: &mut Stats,
    ) -> Event {
        let m = medium.map(|i| self.scene.medium_at(i));
        match m {
            Some(m) if !m.is_uniform() => self.curved(m, origin, dir, stats),
            _ => {
                stats.straight_rays += 1;
                match self
                    .scene
                    .accel
                    .intersect_ray(origin, dir, 0.0, f64::INFINITY)
                {
                    Some((prim, h)) => Event::Surface {
                        prim,
                        position: origin + h.t * dir,
                        normal: h.normal,
                        direction: dir,
                    },
                    None => Event::Escaped(dir),
                }
            }
        }
    }

    fn curved(
        &self,
        medium: &dyn crate::media::Medium,
        origin: DVec3,
        dir: DVec3,
        stats: &mut Stats,
    ) -> Event {
        let settings = &self.scene.render;
        let Some(start) = RayState::new(medium, origin, dir) else {
            stats.record_end(Termination::Captured);
            return Event::Lost;
        };
        let limits = MarchLimits {
            length: 100.0 * self.world.scale(),
            max_steps: settings.max_steps,
            bounds: self.world,
        };
        let accel = &self.scene.accel;
        let mut prev = start;
        let mut prev_s = 0.0;
        let mut hit = None;
        let out = march_with(
            settings.stepper,
            medium,
            settings.control,
            start,
            &limits,
            |s, st| {
                if s == 0.0 {
                    return ControlFlow::Continue(());
                }
                // The step as an exact arc with the mean F of its ends, then a straight connector
                // from the arc's end to the step's end: a continuous path from one accepted state
                // to the next, so no surface between them is stepped over.
                let len = s - prev_s;
                let seg = CurvedSegment::new(
                    prev.position,
                    prev.direction,
                    0.5 * (prev.index.log_gradient() + st.index.log_gradient()),
                );
                if let Some((prim, h)) = accel.intersect_segment(&seg, 0.0, len) {
                    let p = seg.at(h.t);
                    hit = Some(Event::Surface {
                        prim,
                        position: p.position,
                        normal: h.normal,
                        direction: p.direction,
                    });
                    return ControlFlow::Break(());
                }
                let arc_end = seg.at(len).position;
                let gap = st.position - arc_end;
                let gap_len = gap.length();
                if gap_len > 0.0 {
                    if let Some((prim, h)) =
                        accel.intersect_ray(arc_end, gap / gap_len, 0.0, gap_len)
                    {
                        hit = Some(Event::Surface {
                            prim,
                            position: arc_end + h.t * gap / gap_len,
                            normal: h.normal,
                            direction: st.direction,
                        });
                        return ControlFlow::Break(());
                    }
                }
                prev = *st;
                prev_s = s;
                ControlFlow::Continue(())
            },
        );
        stats.curved_marches += 1;
        stats.curved_steps += out.steps;
        stats.record_end(out.reason);
        match out.reason {
            Termination::Stopped => hit.unwrap_or(Event::Lost),
            Termination::LeftBounds | Termination::LengthReached => {
                Event::Escaped(out.state.direction)
            }
            _ => Event::Lost,
        }
    }
}
