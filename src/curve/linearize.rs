//! The transformation method where it is exact: rays straightened by a change of coordinates.
//!
//! A ray is a geodesic of the optical metric n(x)²|dx|², and a change of coordinates maps every
//! geodesic of a metric to a straight line exactly when the metric has constant curvature
//! (Beltrami's theorem). Two isotropic index fields about a centre c, with u = (x − c)/R, are
//! such metrics, both (n0·R/2)² times a model of constant curvature k:
//!
//! - **Maxwell's fish-eye** n = n0 / (1 + |u|²), k = +1: stereographic projection makes it the
//!   unit 3-sphere |X|² = 1 of R⁴ (metric 4|du|²/(1 + |u|²)²); rays are great circles
//!   X(θ) = P cos θ + Q sin θ. θ = π is the antipode: every ray from x reaches its image
//!   c − R²(x − c)/|x − c|², perfect imaging (Maxwell 1854; Luneburg 1964, *Mathematical
//!   Theory of Optics*, §28).
//! - **The hyperbolic medium** n = n0 / (1 − |u|²) inside r < R, k = −1: the Poincaré ball,
//!   made the hyperboloid −X_w² + |X_xyz|² = −1 (metric 4|du|²/(1 − |u|²)²); rays are
//!   X(θ) = P cosh θ + Q sinh θ, reaching the rim r = R only as θ → ∞ (infinite optical path).
//!
//! Both: X = (2u, 1 − k|u|²) / (1 + k|u|²), u = X_xyz / (1 + X_w); optical path n0·R·θ/2.
//! So a ray is advanced to any optical path in closed form, with no steps. Every plane and
//! every sphere of x-space is the section of the model by a hyperplane a·X = b, so a ray meets
//! it where A C(θ) + B S(θ) = b (C, S = cos, sin or cosh, sinh): a closed-form hit. Lengths are
//! scene units.
//!
//! **Precision.** The model's coordinates grow as 1/(1 + k|u|²): far outside the fish-eye's R
//! (|u| ≫ 1) a position carries a relative error of about ε|u|², and within 1 − |u|² = w of the
//! hyperbolic medium's rim a direction one of about ε/w. Rays from the start to a few R, and to
//! w ≈ 10⁻², keep 1e-13.

use super::hermite::Path;
use super::segment::ArcPoint;
use crate::media::{ConstantCurvature, FishEye, HyperbolicMedium};
use glam::{DVec3, DVec4};
use std::f64::consts::TAU;

/// How far from the centre, in units of R, x-space ends for the fish-eye: farther points are
/// the sphere's pole X = (0, 0, 0, −1), infinity.
pub const FAR: f64 = 1e6;

/// The sign of a model's curvature.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Curvature {
    /// The 3-sphere (the fish-eye).
    Positive,
    /// The hyperboloid (the hyperbolic medium).
    Negative,
}

impl Curvature {
    /// k = ±1.
    fn k(self) -> f64 {
        match self {
            Curvature::Positive => 1.0,
            Curvature::Negative => -1.0,
        }
    }

    /// (C(θ), S(θ)): (cos, sin) or (cosh, sinh).
    fn cs(self, theta: f64) -> (f64, f64) {
        match self {
            Curvature::Positive => {
                let (s, c) = theta.sin_cos();
                (c, s)
            }
            Curvature::Negative => (theta.cosh(), theta.sinh()),
        }
    }
}

/// A ray of a constant-curvature index field as the geodesic it is on its model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeodesicRay {
    curvature: Curvature,
    /// The medium's centre c.
    center: DVec3,
    /// Its radius scale R.
    radius: f64,
    /// Optical path per unit of θ, n0·R/2.
    scale: f64,
    /// The ray's start on the model.
    p: DVec4,
    /// The unit tangent there, toward the ray's direction.
    q: DVec4,
}

/// A hyperplane a·X = b of R⁴ whose section of the model is a plane or a sphere of x-space
/// (see [`GeodesicRay::plane`], [`GeodesicRay::sphere`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hyperplane {
    /// a.
    pub normal: DVec4,
    /// b.
    pub offset: f64,
}

/// Where a ray is at some θ along its geodesic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeodesicPoint {
    /// Position (scene units).
    pub position: DVec3,
    /// Unit direction of propagation.
    pub direction: DVec3,
}

impl GeodesicRay {
    /// The ray of the constant-curvature index field `field` from `position` along
    /// `direction`; None where that field has no ray ([`GeodesicRay::fish_eye`],
    /// [`GeodesicRay::hyperbolic`]).
    pub fn of(field: ConstantCurvature, position: DVec3, direction: DVec3) -> Option<Self> {
        match field {
            ConstantCurvature::FishEye(eye) => Self::fish_eye(eye, position, direction),
            ConstantCurvature::Hyperbolic(m) => Self::hyperbolic(m, position, direction),
        }
    }

    /// The ray of the fish-eye `eye` from `position` along `direction` (any length); None if
    /// either is not finite or the direction is zero.
    pub fn fish_eye(eye: &FishEye, position: DVec3, direction: DVec3) -> Option<Self> {
        Self::new(
            Curvature::Positive,
            eye.center,
            eye.radius,
            eye.n0,
            position,
            direction,
        )
    }

    /// The ray of the hyperbolic medium `m` from `position` (inside its rim) along
    /// `direction`; None outside the rim, or if either is not finite or the direction zero.
    pub fn hyperbolic(m: &HyperbolicMedium, position: DVec3, direction: DVec3) -> Option<Self> {
        Self::new(
            Curvature::Negative,
            m.center,
            m.radius,
            m.n0,
            position,
            direction,
        )
    }

    /// The ray from `position` along `direction` of the medium of `curvature` about `center`,
    /// of radius scale `radius` and central index `n0`.
    fn new(
        curvature: Curvature,
        center: DVec3,
        radius: f64,
        n0: f64,
        position: DVec3,
        direction: DVec3,
    ) -> Option<Self> {
        let k = curvature.k();
        let u = (position - center) / radius;
        let d = direction.normalize_or_zero();
        let s = 1.0 + k * u.length_squared();
        if !u.is_finite() || d == DVec3::ZERO || s <= 0.0 || radius <= 0.0 || n0 <= 0.0 {
            return None;
        }
        let p = (2.0 * u / s).extend((1.0 - k * u.length_squared()) / s);
        // The differential of the projection along d times s/2, the inverse of its conformal
        // factor: the unit tangent, orthogonal to p, exactly (normalising numerically would
        // cancel catastrophically where P is large: near the hyperbolic medium's rim).
        let ud = u.dot(d);
        let q = (d - 2.0 * k * ud * u / s).extend(-2.0 * k * ud / s);
        (p.is_finite() && q.is_finite()).then_some(GeodesicRay {
            curvature,
            center,
            radius,
            scale: 0.5 * n0 * radius,
            p,
            q,
        })
    }

    /// The optical path ∫ n ds from the start to `theta` along the geodesic.
    pub fn optical_path(&self, theta: f64) -> f64 {
        self.scale * theta
    }

    /// The θ at which the optical path from the start is `opl`.
    pub fn angle(&self, opl: f64) -> f64 {
        opl / self.scale
    }

    /// The geodesic's point at `theta` and its tangent there.
    fn lifted(&self, theta: f64) -> (DVec4, DVec4) {
        let (c, s) = self.curvature.cs(theta);
        let x = self.p * c + self.q * s;
        (x, self.q * c - self.curvature.k() * self.p * s)
    }

    /// Whether the model's point `x` is x-space's infinity to rounding (the fish-eye's pole:
    /// every point beyond [`FAR`] R, where a position carries a relative error of about
    /// ε |x − c|²/R² anyway).
    fn at_infinity(x: DVec4) -> bool {
        1.0 + x.w < 2.0 / (FAR * FAR)
    }

    /// The ray at `theta` along its geodesic; None at infinity (the fish-eye's pole: beyond
    /// [`FAR`] R from the centre) or where the hyperbolic medium's rim is reached to rounding.
    pub fn at(&self, theta: f64) -> Option<GeodesicPoint> {
        let (x, v) = self.lifted(theta);
        if Self::at_infinity(x) {
            return None;
        }
        let w = 1.0 + x.w;
        let position = self.center + self.radius * x.truncate() / w;
        let du = v.truncate() / w - x.truncate() * (v.w / (w * w));
        let direction = du.normalize();
        (position.is_finite() && direction.is_finite()).then_some(GeodesicPoint {
            position,
            direction,
        })
    }

    /// The θ of `position`, a point of this ray's geodesic (to rounding), nearest `estimate`:
    /// the fish-eye's great circle knows θ modulo 2π, the hyperbolic medium's geodesic
    /// exactly (θ < 0 behind the start).
    pub fn theta_of(&self, position: DVec3, estimate: f64) -> f64 {
        let k = self.curvature.k();
        let u = (position - self.center) / self.radius;
        let s = 1.0 + k * u.length_squared();
        let x = (2.0 * u / s).extend((1.0 - k * u.length_squared()) / s);
        match self.curvature {
            // X = P cos θ + Q sin θ, P and Q orthonormal.
            Curvature::Positive => {
                let t = x.dot(self.q).atan2(x.dot(self.p));
                t - TAU * ((t - estimate) / TAU).round()
            }
            // X = P cosh θ + Q sinh θ, Q a unit spacelike vector Lorentz-orthogonal to P.
            Curvature::Negative => (x.truncate().dot(self.q.truncate()) - x.w * self.q.w).asinh(),
        }
    }

    /// The θ in (0, 2π] at which a fish-eye ray reaches infinity, if its circle passes through
    /// the pole (the rays through the centre, radially): there n → 0 and the arclength
    /// diverges, so the ray ends — nothing beyond is reached. None for every other ray and in
    /// the hyperbolic medium (whose rays reach its rim only as θ → ∞).
    pub fn escape(&self) -> Option<f64> {
        let (a, b) = (self.p.w, self.q.w);
        (self.curvature == Curvature::Positive && 1.0 - a.hypot(b) < 2.0 / (FAR * FAR)).then(|| {
            let t = (-b).atan2(-a);
            if t > 0.0 {
                t
            } else {
                t + TAU
            }
        })
    }

    /// The hyperplane whose section of the model is the plane through `point` with normal
    /// `normal`: with m the normal and k₀ = m·(point − c)/R, (m, −k₀)·X = k₀.
    pub fn plane(&self, point: DVec3, normal: DVec3) -> Hyperplane {
        let k0 = normal.dot(point - self.center) / self.radius;
        Hyperplane {
            normal: normal.extend(-k0),
            offset: k0,
        }
    }

    /// The hyperplane whose section of the model is the sphere of `center` and `radius`: with
    /// m = (center − c)/R and K = |m|² − (radius/R)², (−2m, K − k)·X = −(K + k).
    pub fn sphere(&self, center: DVec3, radius: f64) -> Hyperplane {
        let m = (center - self.center) / self.radius;
        let big_k = m.length_squared() - (radius / self.radius).powi(2);
        let k = self.curvature.k();
        Hyperplane {
            normal: (-2.0 * m).extend(big_k - k),
            offset: -(big_k + k),
        }
    }

    /// The first θ beyond `after` at which the ray crosses `h` (within one turn of a circle):
    /// A C(θ) + B S(θ) = b with A = a·P, B = a·Q. None if the geodesic never meets it (a miss)
    /// or only touches it, or if the ray reaches infinity first ([`GeodesicRay::escape`];
    /// every plane's hyperplane holds the fish-eye's pole, which a ray from the centre reaches
    /// at θ = π, and a root there is not a crossing either).
    pub fn crossing(&self, h: &Hyperplane, after: f64) -> Option<f64> {
        let (a, b, c) = (h.normal.dot(self.p), h.normal.dot(self.q), h.offset);
        let roots: [f64; 2] = match self.curvature {
            Curvature::Positive => {
                let cos = c / a.hypot(b);
                if cos.is_nan() || cos.abs() >= 1.0 {
                    return None;
                }
                let (phi, delta) = (b.atan2(a), cos.acos());
                // φ ± δ, each moved to the first turn beyond `after`.
                [phi - delta, phi + delta].map(|t| t + TAU * (((after - t) / TAU).floor() + 1.0))
            }
            Curvature::Negative => {
                // With e = e^θ: (A + B) e² − 2b e + (A − B) = 0.
                let disc = c * c - a * a + b * b;
                if disc.is_nan() || disc <= 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                // The product of the roots is (A − B)/(A + B): each from the stable side.
                let big = if c >= 0.0 { c + root } else { c - root };
                [big / (a + b), (a - b) / big].map(f64::ln)
            }
        };
        roots
            .into_iter()
            .filter(|&t| t > after && t.is_finite() && !Self::at_infinity(self.lifted(t).0))
            .min_by(f64::total_cmp)
            .filter(|&t| self.escape().is_none_or(|end| t < end))
    }
}

/// A ray of a constant-curvature index field in x-space: a circle (Maxwell 1854 for the
/// fish-eye; the Poincaré ball's geodesics for the hyperbolic medium), or a line through the
/// centre — the path of constant curvature vector κ = ∇ln n − t̂(t̂·∇ln n) (1/length, ⊥ t̂) from
/// its start. Exact at every arclength, in a form that stays accurate as |κ|s → 0:
/// x(s) = x0 + t̂0 s sinc(|κ|s) + κ s² sinc²(|κ|s/2)/2, t̂(s) = t̂0 cos(|κ|s) + κ s sinc(|κ|s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleArc {
    /// The start.
    pub origin: DVec3,
    /// The unit direction there.
    pub direction: DVec3,
    /// The curvature vector κ (1/length), orthogonal to `direction`.
    pub curvature: DVec3,
}

/// sin x / x, to rounding near 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

impl CircleArc {
    /// The arc from `origin` along unit `direction` where ∇ln n is `force` (its curvature
    /// vector is `force`'s part across `direction`).
    pub fn new(origin: DVec3, direction: DVec3, force: DVec3) -> Self {
        Self {
            origin,
            direction,
            curvature: force - direction * direction.dot(force),
        }
    }

    /// Where the arc crosses `surface` at arclengths in (0, `length`], ascending, in closed
    /// form; None when the arc turns by a right angle or more over `length` (search it).
    ///
    /// With k = |κ|, S = sin(ks)/k and C = (1 − cos ks)/k², x(s) − x0 = t̂0 S + κ C and
    /// |x(s) − x0|² = S² + k²C² = 2C, so g(x(s)) = w + (v·t̂0) S + (2α + v·κ) C, where
    /// v = ∇g(x0) and w = g(x0). With σ = tan(ks/2)/k, S = 2σ/(1 + k²σ²) and C = 2σ²/(1 + k²σ²),
    /// and g = 0 is the quadratic [w k² + 2(2α + v·κ)] σ² + 2 (v·t̂0) σ + w = 0, regular as
    /// k → 0 (σ → s/2: a line's, and a parabola's to first order); s = 2 atan(kσ)/k.
    pub fn crossings(&self, surface: &RoundSurface, length: f64) -> Option<CircleCrossings> {
        let k = self.curvature.length();
        let turn = k * length;
        if turn.is_nan() || turn >= 0.5 * std::f64::consts::PI {
            return None;
        }
        let (w, v) = surface.implicit(self.origin);
        let a = w * k * k + 2.0 * (2.0 * surface.alpha + v.dot(self.curvature));
        let b = v.dot(self.direction);
        let c = w;
        // a σ² + 2 b σ + c = 0, each root from its stable side.
        let mut sigma = [f64::NAN; 2];
        let disc = b * b - a * c;
        if disc > 0.0 {
            let q = -(b + disc.sqrt().copysign(b));
            sigma = [q / a, c / q];
        } else if a == 0.0 && b != 0.0 {
            sigma[0] = -0.5 * c / b;
        }
        let arclength = |sigma: f64| {
            let x = k * sigma;
            if x.abs() < 1e-6 {
                2.0 * sigma * (1.0 - x * x / 3.0)
            } else {
                2.0 * x.atan() / k
            }
        };
        let mut found = CircleCrossings {
            s: [0.0; 2],
            count: 0,
        };
        for s in sigma.map(arclength) {
            if s > 0.0 && s <= length {
                found.s[found.count] = s;
                found.count += 1;
            }
        }
        if found.count == 2 && found.s[1] < found.s[0] {
            found.s.swap(0, 1);
        }
        Some(found)
    }
}

/// A plane or a sphere as the level set g(x) = α|x − c|² + m·(x − c) − d = 0: the plane through
/// c of normal m (α = 0, d = 0) or the sphere about c (α = 1, m = 0, d = r²) — the surfaces a
/// ray's circle meets in closed form ([`CircleArc::crossings`]). g is signed: positive on the
/// normal's side of a plane and outside a sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoundSurface {
    alpha: f64,
    center: DVec3,
    normal: DVec3,
    offset: f64,
}

impl RoundSurface {
    /// The plane through `point` with normal `normal` (g is the distance to it along a unit
    /// normal).
    pub fn plane(point: DVec3, normal: DVec3) -> Self {
        Self {
            alpha: 0.0,
            center: point,
            normal,
            offset: 0.0,
        }
    }

    /// The sphere of `center` and `radius`.
    pub fn sphere(center: DVec3, radius: f64) -> Self {
        Self {
            alpha: 1.0,
            center,
            normal: DVec3::ZERO,
            offset: radius * radius,
        }
    }

    /// g(x) and ∇g(x).
    pub fn implicit(&self, x: DVec3) -> (f64, DVec3) {
        let d = x - self.center;
        (
            self.alpha * d.length_squared() + self.normal.dot(d) - self.offset,
            2.0 * self.alpha * d + self.normal,
        )
    }
}

/// Up to two arclengths along a circle where it crosses a surface, ascending.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleCrossings {
    s: [f64; 2],
    count: usize,
}

impl CircleCrossings {
    /// The arclengths, ascending.
    pub fn iter(&self) -> impl Iterator<Item = f64> + '_ {
        self.s[..self.count].iter().copied()
    }
}

impl Path for CircleArc {
    fn at(&self, s: f64) -> ArcPoint {
        let phi = self.curvature.length() * s;
        let half = sinc(0.5 * phi);
        let along = s * sinc(phi);
        ArcPoint {
            position: self.origin
                + self.direction * along
                + self.curvature * (0.5 * s * s * half * half),
            direction: (self.direction * phi.cos() + self.curvature * along).normalize(),
        }
    }

    fn curvature(&self) -> f64 {
        self.curvature.length()
    }

    fn circle(&self) -> Option<&CircleArc> {
        Some(self)
    }
}
