//! The transformation method where it is exact: rays straightened by a change of coordinates.
//!
//! A ray is a geodesic of the optical metric n(x)²|dx|², and a change of coordinates maps every
//! geodesic of a metric to a straight line exactly when the metric has constant curvature
//! (Beltrami's theorem). Maxwell's fish-eye n = n0 / (1 + r²/R²) is such a metric: with
//! u = (x − c)/R, stereographic projection
//!
//! X = (2u, |u|² − 1) / (1 + |u|²),   u = X_xyz / (1 − X_w)
//!
//! carries it to the round unit 3-sphere in R⁴, scaled by n0·R/2 (the sphere's metric is
//! 4|du|²/(1 + |u|²)²). Its rays are therefore great circles X(θ) = P cos θ + Q sin θ, with
//! optical path n0·R·θ/2 — advanced in closed form, with no steps — and every plane and every
//! sphere of x-space is the section of the 3-sphere by a hyperplane a·X = b, so a ray meets it
//! where A cos θ + B sin θ = b: a closed-form hit. θ = π is the antipode −X, the point
//! c − R² (x − c)/|x − c|²: the fish-eye images every point perfectly (Maxwell 1854;
//! Luneburg 1964, *Mathematical Theory of Optics*, §28). Lengths are scene units.

use crate::media::FishEye;
use glam::{DVec3, DVec4};
use std::f64::consts::TAU;

/// How far from the centre, in units of R, x-space ends for [`FishEyeRay`]: points farther out
/// are the pole, infinity.
pub const FAR: f64 = 1e6;

/// A ray of a Maxwell fish-eye as the great circle it is on the 3-sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FishEyeRay {
    /// The medium's centre c.
    center: DVec3,
    /// Its radius scale R.
    radius: f64,
    /// Optical path per radian of the great circle, n0·R/2.
    scale: f64,
    /// The ray's start on the unit 3-sphere.
    p: DVec4,
    /// The unit tangent there, toward the ray's direction (orthogonal to `p`).
    q: DVec4,
}

/// A hyperplane a·X = b of R⁴ whose section of the 3-sphere is a plane or a sphere of x-space
/// (see [`FishEyeRay::plane`], [`FishEyeRay::sphere`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyperplane {
    /// a.
    pub normal: DVec4,
    /// b.
    pub offset: f64,
}

/// Where a fish-eye ray is at some angle along its great circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FishEyePoint {
    /// Position (scene units).
    pub position: DVec3,
    /// Unit direction of propagation.
    pub direction: DVec3,
}

impl FishEyeRay {
    /// The ray of `eye` from `position` along `direction` (any length); None if either is not
    /// finite or the direction is zero.
    pub fn new(eye: &FishEye, position: DVec3, direction: DVec3) -> Option<Self> {
        let u = (position - eye.center) / eye.radius;
        let d = direction.normalize_or_zero();
        if !u.is_finite() || d == DVec3::ZERO || !(eye.radius > 0.0 && eye.n0 > 0.0) {
            return None;
        }
        let s = 1.0 + u.length_squared();
        let p = (2.0 * u / s).extend((u.length_squared() - 1.0) / s);
        // The differential of the projection along d: conformal, so only its direction counts.
        let ud = u.dot(d);
        let q = (2.0 * d / s - 4.0 * ud * u / (s * s)).extend(4.0 * ud / (s * s));
        // Gram–Schmidt once more against rounding: p and q orthonormal to the last bit.
        let p = p.normalize();
        let q = (q - q.dot(p) * p).normalize();
        q.is_finite().then_some(FishEyeRay {
            center: eye.center,
            radius: eye.radius,
            scale: 0.5 * eye.n0 * eye.radius,
            p,
            q,
        })
    }

    /// The optical path ∫ n ds from the start to angle `theta` (radians) along the circle.
    pub fn optical_path(&self, theta: f64) -> f64 {
        self.scale * theta
    }

    /// The angle along the circle at which the optical path from the start is `opl`.
    pub fn angle(&self, opl: f64) -> f64 {
        opl / self.scale
    }

    /// The point of the circle at angle `theta` and its tangent there.
    fn lifted(&self, theta: f64) -> (DVec4, DVec4) {
        let (sin, cos) = theta.sin_cos();
        (self.p * cos + self.q * sin, self.q * cos - self.p * sin)
    }

    /// Whether the circle's point `x` is the projection's pole to rounding: x-space's infinity,
    /// taken to be every point beyond [`FAR`] R from the centre (there 1 − X_w < 2/FAR², and a
    /// position carries a relative error of about ε |x − c|²/R²).
    fn at_infinity(x: DVec4) -> bool {
        1.0 - x.w < 2.0 / (FAR * FAR)
    }

    /// The ray at angle `theta` along its circle; None at the projection's pole, where the ray
    /// passes through infinity (beyond [`FAR`] R from the centre).
    pub fn at(&self, theta: f64) -> Option<FishEyePoint> {
        let (x, v) = self.lifted(theta);
        if Self::at_infinity(x) {
            return None;
        }
        let w = 1.0 - x.w;
        let position = self.center + self.radius * x.truncate() / w;
        let du = v.truncate() / w + x.truncate() * (v.w / (w * w));
        let direction = du.normalize();
        (position.is_finite() && direction.is_finite()).then_some(FishEyePoint {
            position,
            direction,
        })
    }

    /// The hyperplane whose section of the 3-sphere is the plane through `point` with normal
    /// `normal`: (m, k)·X = k with m the normal and k = m·(point − c)/R.
    pub fn plane(&self, point: DVec3, normal: DVec3) -> Hyperplane {
        let k = normal.dot(point - self.center) / self.radius;
        Hyperplane {
            normal: normal.extend(k),
            offset: k,
        }
    }

    /// The hyperplane whose section of the 3-sphere is the sphere of `center` and `radius`:
    /// with m = (center − c)/R and K = |m|² − (radius/R)², (−2m, 1 − K)·X = −(1 + K).
    pub fn sphere(&self, center: DVec3, radius: f64) -> Hyperplane {
        let m = (center - self.center) / self.radius;
        let k = m.length_squared() - (radius / self.radius).powi(2);
        Hyperplane {
            normal: (-2.0 * m).extend(1.0 - k),
            offset: -(1.0 + k),
        }
    }

    /// The angle in (0, 2π] at which the ray reaches infinity, if its circle passes through
    /// the pole (the rays through the centre, radially): there n → 0 and the arclength
    /// diverges, so the ray ends — nothing beyond it is reached.
    pub fn escape(&self) -> Option<f64> {
        let (a, b) = (self.p.w, self.q.w);
        (1.0 - a.hypot(b) < 2.0 / (FAR * FAR)).then(|| {
            let t = b.atan2(a);
            if t > 0.0 {
                t
            } else {
                t + TAU
            }
        })
    }

    /// The first angle beyond `after` (radians) at which the ray crosses `h`, within one turn
    /// of the circle: A cos θ + B sin θ = b with A = a·P, B = a·Q. None if the circle never
    /// meets it (a miss) or only touches it, or if the ray reaches infinity first
    /// ([`FishEyeRay::escape`]; every plane's hyperplane holds the pole, which a ray from the
    /// centre reaches at θ = π, and a root there is not a crossing either).
    pub fn crossing(&self, h: &Hyperplane, after: f64) -> Option<f64> {
        let (a, b) = (h.normal.dot(self.p), h.normal.dot(self.q));
        let rho = a.hypot(b);
        let c = h.offset / rho;
        if c.is_nan() || c.abs() >= 1.0 {
            return None;
        }
        let (phi, delta) = (b.atan2(a), c.acos());
        // The roots φ ± δ, each moved to the first turn beyond `after`.
        [phi - delta, phi + delta]
            .map(|t| t + TAU * (((after - t) / TAU).floor() + 1.0))
            .into_iter()
            .filter(|&t| !Self::at_infinity(self.lifted(t).0))
            .min_by(f64::total_cmp)
            .filter(|&t| self.escape().is_none_or(|end| t < end))
    }
}
