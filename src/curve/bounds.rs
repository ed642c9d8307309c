//! Regions a march may be confined to, with the signed distance used to locate the exit.

use glam::DVec3;

/// A closed region of space; a march that leaves it ends with [`super::Termination::LeftBounds`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bounds {
    /// No limit.
    Unbounded,
    /// An axis-aligned box [min, max].
    Box {
        /// Lower corner.
        min: DVec3,
        /// Upper corner.
        max: DVec3,
    },
    /// A ball.
    Ball {
        /// Centre.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// The half-space behind a plane: points p with (p − point)·normal ≤ 0, within a ball
    /// around `point` of radius `reach` (a ray that misses the plane leaves through the
    /// ball instead of running on).
    HalfSpace {
        /// A point of the plane.
        point: DVec3,
        /// Unit normal, pointing out of the region.
        normal: DVec3,
        /// Radius of the ball around `point` the region is cut to.
        reach: f64,
    },
}

impl Bounds {
    /// Signed distance to the boundary: ≤ 0 inside, > 0 outside (for the box, exact outside
    /// and the negated distance to the nearest face inside).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        match *self {
            Bounds::Unbounded => f64::NEG_INFINITY,
            Bounds::Box { min, max } => {
                let center = 0.5 * (min + max);
                let half = 0.5 * (max - min);
                let q = (p - center).abs() - half;
                q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
            }
            Bounds::Ball { center, radius } => (p - center).length() - radius,
            Bounds::HalfSpace {
                point,
                normal,
                reach,
            } => ((p - point).dot(normal)).max((p - point).length() - reach),
        }
    }

    /// Distance along the straight ray o + t d (d unit) from a point `o` inside to where it
    /// leaves the region (0 from outside; ∞ unbounded).
    pub fn exit_distance(&self, o: DVec3, d: DVec3) -> f64 {
        match *self {
            Bounds::Unbounded => f64::INFINITY,
            Bounds::Box { min, max } => {
                let t = |lo: f64, hi: f64, o: f64, d: f64| {
                    if d > 0.0 {
                        (hi - o) / d
                    } else if d < 0.0 {
                        (lo - o) / d
                    } else {
                        f64::INFINITY
                    }
                };
                (0..3)
                    .map(|a| t(min[a], max[a], o[a], d[a]))
                    .fold(f64::INFINITY, f64::min)
                    .max(0.0)
            }
            Bounds::Ball { center, radius } => ball_exit(o - center, d, radius),
            Bounds::HalfSpace {
                point,
                normal,
                reach,
            } => {
                let toward = d.dot(normal);
                let plane = if toward > 0.0 {
                    -(o - point).dot(normal) / toward
                } else {
                    f64::INFINITY
                };
                plane.min(ball_exit(o - point, d, reach)).max(0.0)
            }
        }
    }

    /// A length scale of the region (for exit-location tolerances).
    pub fn scale(&self) -> f64 {
        match *self {
            Bounds::Unbounded => 1.0,
            Bounds::Box { min, max } => (max - min).max_element(),
            Bounds::Ball { radius, .. } => radius,
            Bounds::HalfSpace { reach, .. } => reach,
        }
    }
}

/// Distance along unit `d` from `oc` (relative to a ball's centre, inside it) to where the
/// ray leaves the ball of `radius`: the positive root of t² + 2bt + c = 0 (c ≤ 0 inside).
fn ball_exit(oc: DVec3, d: DVec3, radius: f64) -> f64 {
    let b = oc.dot(d);
    let c = oc.length_squared() - radius * radius;
    (-b + (b * b - c).max(0.0).sqrt()).max(0.0)
}
