//! The path of a step whose stepper knows only its ends (RK4, RKN, Snell): dense output by
//! quintic Hermite interpolation, and the [`Path`] interface surfaces are tested against.

use super::segment::{ArcHull, ArcPoint, CurvedSegment};
use super::state::RayState;
use glam::DVec3;

/// A smooth path parametrised by arclength from its start: what a surface's crossing is
/// searched on ([`crate::shapes::segment_roots`]).
pub trait Path {
    /// Point and unit tangent at arclength `s` from the start.
    fn at(&self, s: f64) -> ArcPoint;
    /// A bound on the path's curvature (1/scene units): how finely a root search must sample
    /// it so that each piece turns little.
    fn curvature(&self) -> f64;
    /// The path as an exact circle, if it is one: planes and spheres then meet it in closed
    /// form ([`super::CircleArc::crossings`]).
    fn circle(&self) -> Option<&super::CircleArc> {
        None
    }
}

impl Path for CurvedSegment {
    fn at(&self, s: f64) -> ArcPoint {
        CurvedSegment::at(self, s)
    }
    /// |F|, which bounds the arc's curvature |F − t̂(t̂·F)|.
    fn curvature(&self) -> f64 {
        self.force()
    }
}

/// The quintic Hermite interpolant of a step from `a` to `b` of arclength `len`: it matches
/// position, tangent t̂ and curvature vector k = dt̂/ds = F − t̂(t̂·F) (F = ∇ln n, from the
/// states' own samples) at both ends, so it errs from the ray by O(len⁶) — below a sixth-order
/// step's own error, and far below the mean-force arc's O(len²|∇F|) that it replaces. Held as
/// a degree-5 Bézier curve in u = s/len (the control polygon bounds it: [`Self::hull`]) and
/// evaluated from its power form. Its parameter is the ray's arclength at both ends and to
/// O(len⁶) between.
#[derive(Clone, Copy, Debug)]
pub struct HermitePath {
    /// Power-form coefficients: x(u) = Σ c_i u^i.
    coeff: [DVec3; 6],
    /// Bézier control points B0 … B5.
    control: [DVec3; 6],
    len: f64,
    curvature: f64,
}

impl HermitePath {
    /// The path between two accepted states `len` apart along the ray (len > 0).
    pub fn new(a: &RayState, b: &RayState, len: f64) -> Self {
        let bend = |s: &RayState| {
            let f = s.index.log_gradient();
            f - s.direction * s.direction.dot(f)
        };
        let (k0, k1) = (bend(a), bend(b));
        // dx/du = len t̂, d²x/du² = len² k at the ends.
        let (v0, v1) = (len * a.direction, len * b.direction);
        let (w0, w1) = (len * len * k0, len * len * k1);
        let (p0, p5) = (a.position, b.position);
        let control = [
            p0,
            p0 + v0 / 5.0,
            p0 + 0.4 * v0 + w0 / 20.0,
            p5 - 0.4 * v1 + w1 / 20.0,
            p5 - v1 / 5.0,
            p5,
        ];
        // Bernstein to power basis: c_i = C(5, i) Σ_j (−1)^(i−j) C(i, j) B_j.
        const BINOM: [[f64; 6]; 6] = [
            [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            [1.0, 2.0, 1.0, 0.0, 0.0, 0.0],
            [1.0, 3.0, 3.0, 1.0, 0.0, 0.0],
            [1.0, 4.0, 6.0, 4.0, 1.0, 0.0],
            [1.0, 5.0, 10.0, 10.0, 5.0, 1.0],
        ];
        let mut coeff = [DVec3::ZERO; 6];
        for (i, c) in coeff.iter_mut().enumerate() {
            let mut sum = DVec3::ZERO;
            for (j, &bj) in control.iter().enumerate().take(i + 1) {
                let sign = if (i - j) % 2 == 0 { 1.0 } else { -1.0 };
                sum += sign * BINOM[i][j] * bj;
            }
            *c = BINOM[5][i] * sum;
        }
        Self {
            coeff,
            control,
            len,
            curvature: k0.length().max(k1.length()),
        }
    }

    /// The capsule around the chord that holds the path: the Bézier curve lies in the convex
    /// hull of its control points, each within `deviation` of the chord.
    pub fn hull(&self) -> ArcHull {
        let chord = ArcHull {
            a: self.control[0],
            b: self.control[5],
            deviation: 0.0,
        };
        let deviation = self.control[1..5]
            .iter()
            .map(|&p| chord.chord_distance(p))
            .fold(0.0, f64::max);
        ArcHull { deviation, ..chord }
    }
}

impl Path for HermitePath {
    fn at(&self, s: f64) -> ArcPoint {
        let u = s / self.len;
        let c = &self.coeff;
        let position = c[0] + u * (c[1] + u * (c[2] + u * (c[3] + u * (c[4] + u * c[5]))));
        let tangent =
            c[1] + u * (2.0 * c[2] + u * (3.0 * c[3] + u * (4.0 * c[4] + u * 5.0 * c[5])));
        ArcPoint {
            position,
            direction: tangent.normalize(),
        }
    }

    fn curvature(&self) -> f64 {
        self.curvature
    }
}
