//! What a ray meets next ([`Event`]: a surface, the world's edge, the end of its allowed
//! reach, or nothing it can name), and where a path meets a surface ([`SurfaceHit`]).

use crate::color::Rgb;
use crate::ids::PrimId;
use glam::{DVec2, DVec3};

/// What a ray meets next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A surface.
    Surface {
        /// Where, on which primitive, with its normals and the direction of arrival.
        hit: SurfaceHit,
        /// Path length from the origin to the hit (scene units).
        distance: f64,
        /// Optical depth ∫ σa ds of absorption from the origin to the hit, per channel.
        optical_depth: Rgb,
    },
    /// The ray left the world sphere.
    Escaped {
        /// Where it left.
        position: DVec3,
        /// Unit direction when leaving.
        direction: DVec3,
        /// Path length from the origin to the world sphere (scene units).
        distance: f64,
        /// Optical depth ∫ σa ds of absorption from the origin to the world sphere, per channel.
        optical_depth: Rgb,
    },
    /// The ray went the arclength it was allowed ([`Tracer::next_event_within`]) before any
    /// surface: where a free flight in a scattering medium ends.
    Reached {
        /// Where.
        position: DVec3,
        /// Unit direction of travel there.
        direction: DVec3,
        /// Path length from the origin (the allowed arclength).
        distance: f64,
        /// Optical depth ∫ σa ds of absorption from the origin, per channel.
        optical_depth: Rgb,
    },
    /// The ray ended without reaching a surface or escaping: captured, out of steps, trapped
    /// (a curved path 100 world radii long that never left the world), or lost inside an
    /// object it should have left; the reason is counted in the statistics.
    Lost,
}

impl Event {
    /// Where the ray meets a surface, if it does.
    pub fn surface_hit(&self) -> Option<SurfaceHit> {
        match *self {
            Event::Surface { hit, .. } => Some(hit),
            Event::Escaped { .. } | Event::Reached { .. } | Event::Lost => None,
        }
    }

    /// The path length from the origin to the event (0 when lost).
    pub fn distance(&self) -> f64 {
        match *self {
            Event::Surface { distance, .. }
            | Event::Escaped { distance, .. }
            | Event::Reached { distance, .. } => distance,
            Event::Lost => 0.0,
        }
    }

    /// The ray's unit direction where the event happens (None when lost).
    pub fn direction(&self) -> Option<DVec3> {
        match *self {
            Event::Surface { hit, .. } => Some(hit.incoming),
            Event::Escaped { direction, .. } | Event::Reached { direction, .. } => Some(direction),
            Event::Lost => None,
        }
    }

    /// Where the event happens (None when lost).
    pub fn position(&self) -> Option<DVec3> {
        match *self {
            Event::Surface { hit, .. } => Some(hit.position),
            Event::Escaped { position, .. } | Event::Reached { position, .. } => Some(position),
            Event::Lost => None,
        }
    }

    /// The event of a ray that had gone `distance` with absorption `depth` before the start
    /// it was traced from: both added to its own.
    pub fn continuing(mut self, before: f64, depth_before: Rgb) -> Event {
        if let Event::Surface {
            distance,
            optical_depth,
            ..
        }
        | Event::Escaped {
            distance,
            optical_depth,
            ..
        }
        | Event::Reached {
            distance,
            optical_depth,
            ..
        } = &mut self
        {
            *distance += before;
            *optical_depth += depth_before;
        }
        self
    }

    /// The optical depth ∫σa ds of absorption per channel on the way to the event (∞ when
    /// lost).
    pub fn optical_depth(&self) -> Rgb {
        match *self {
            Event::Surface { optical_depth, .. }
            | Event::Escaped { optical_depth, .. }
            | Event::Reached { optical_depth, .. } => optical_depth,
            Event::Lost => Rgb::splat(f64::INFINITY),
        }
    }

    /// The fraction exp(−∫σa ds) of light kept per channel on the way to the event (0 when
    /// lost).
    pub fn transmittance(&self) -> Rgb {
        (-self.optical_depth()).exp()
    }
}

/// A surface's two normals at a hit (see [`crate::shapes::Hit`]): the geometric one tells
/// which side a ray is on, the shading one (same side) is what a specular surface reflects
/// and refracts about.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Normals {
    /// Unit geometric normal.
    pub geometric: DVec3,
    /// Unit shading normal.
    pub shading: DVec3,
}

/// Where a path meets a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    /// Primitive index.
    pub prim: PrimId,
    /// Hit point.
    pub position: DVec3,
    /// The surface's normals there.
    pub normals: Normals,
    /// A mesh's surface coordinates (u, v) there ([`crate::shapes::Hit::uv`]; an analytic
    /// primitive's are worked out where a texture asks).
    pub uv: Option<DVec2>,
    /// Unit direction of arrival.
    pub incoming: DVec3,
}

impl SurfaceHit {
    /// Where the straight ray from `origin` along unit `dir` meets the surface `hit` reports.
    pub fn straight(origin: DVec3, dir: DVec3, hit: crate::accel::PrimHit) -> Self {
        let crate::accel::PrimHit { prim, hit: h } = hit;
        Self {
            prim,
            position: origin + h.t * dir,
            normals: Normals {
                geometric: h.normal,
                shading: h.shading,
            },
            uv: h.uv,
            incoming: dir,
        }
    }
}
