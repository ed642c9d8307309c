//! The exact constant-gradient arc (Tessendorf 2022, §2–3, with its sign errors corrected: see docs/validation.md).
//!
//! With F = ∇ln n frozen, dx/ds = t̂ and dt̂/ds = F − t̂(t̂·F) have the closed-form solution
//! t̂(s) = tanh τ F̂ + sech τ p̂, τ = |F| s + artanh(cos β), and
//! x(s) = x0 + (L(s) F̂ + Δ(s) p̂)/|F| with L = ln(cosh |F|s + cos β sinh |F|s) and Δ the angle
//! turned. Everything here follows a stable f64 recipe (relative error ~1e-15, checked against 320-bit arithmetic in tests/exact_arc.rs).

use crate::math::Bounds3;
use glam::DVec3;

/// a·b − c·d with one rounding (Kahan's FMA trick).
fn diff_of_products(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let w = d * c;
    let e = (-d).mul_add(c, w);
    let f = a.mul_add(b, -w);
    f + e
}

/// a × b with every component accurate to an ulp, even when a ∥ b nearly.
pub fn accurate_cross(a: DVec3, b: DVec3) -> DVec3 {
    DVec3::new(
        diff_of_products(a.y, b.z, a.z, b.y),
        diff_of_products(a.z, b.x, a.x, b.z),
        diff_of_products(a.x, b.y, a.y, b.x),
    )
}

/// |v| without underflow or overflow of the squares (for vectors of ~1e-300 components).
fn robust_length(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * (v / m).length()
}

/// Below this bending x = |F|s the arc is evaluated by its fourth-order series (truncation x⁵ ≤ 1e-20).
const SERIES_LIMIT: f64 = 1e-4;
/// Below this sin β a ray running against F is evaluated through τ directly.
const TINY_SIN: f64 = 1e-100;

/// A path of constant F = ∇ln n from `origin`: a planar curve in the plane of t̂0 and F.
#[derive(Clone, Copy, Debug)]
pub struct CurvedSegment {
    origin: DVec3,
    /// Unit initial direction (used for the straight case).
    t0: DVec3,
    /// |F| (1/length); 0 marks a straight segment.
    f: f64,
    /// |F| even where the segment is straight because t̂0 ∥ F (then c = ±1): the index still
    /// changes along it.
    f_index: f64,
    /// F̂ and p̂: the in-plane frame (p̂ ⊥ F̂, along the part of t̂0 across F).
    f_hat: DVec3,
    p_hat: DVec3,
    /// cos β, sin β, 1 + cos β, 1 − cos β (the smaller of the last two as σ²/larger).
    c: f64,
    sigma: f64,
    a: f64,
    b: f64,
}

/// How far a C¹ path of `length` whose curvature never exceeds `curvature` can stray from its
/// chord: the sagitta of a circle of that curvature, ≤ curvature·length²/8, while the path
/// turns by at most 2 rad; beyond, length/2 (every point is that close to one of the ends).
pub fn deviation_bound(curvature: f64, length: f64) -> f64 {
    if curvature * length <= 2.0 {
        0.125 * curvature * length * length
    } else {
        0.5 * length
    }
}

/// A capsule that holds a curved segment: every point of the segment lies within `deviation`
/// of the straight chord from `a` to `b`. Surfaces test it before looking for crossings on
/// the arc itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcHull {
    /// The segment's start.
    pub a: DVec3,
    /// Its end.
    pub b: DVec3,
    /// Bound on the distance of any of its points from the chord ab.
    pub deviation: f64,
}

impl ArcHull {
    /// The axis-aligned box that holds the capsule.
    pub fn bounds(&self) -> Bounds3 {
        Bounds3::new(self.a.min(self.b), self.a.max(self.b)).grown(DVec3::splat(self.deviation))
    }

    /// Distance from `p` to the chord ab.
    pub fn chord_distance(&self, p: DVec3) -> f64 {
        let ab = self.b - self.a;
        let len2 = ab.length_squared();
        let u = if len2 > 0.0 {
            ((p - self.a).dot(ab) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (self.a + u * ab)).length()
    }
}

/// Position and unit direction at one arclength of a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPoint {
    /// Position.
    pub position: DVec3,
    /// Unit tangent.
    pub direction: DVec3,
}

impl CurvedSegment {
    /// The arc from `origin` with initial direction `t0` (any non-zero length) under constant
    /// `force` = ∇ln n. `t0` is deliberately not normalised first.
    pub fn new(origin: DVec3, t0: DVec3, force: DVec3) -> Self {
        let t_len = t0.length();
        let f = force.length();
        let unit_t = t0 / t_len;
        let straight = Self {
            origin,
            t0: unit_t,
            f: 0.0,
            f_index: 0.0,
            f_hat: DVec3::ZERO,
            p_hat: DVec3::ZERO,
            c: 1.0,
            sigma: 0.0,
            a: 2.0,
            b: 0.0,
        };
        if f == 0.0 || !f.is_finite() {
            return straight;
        }
        let k = accurate_cross(t0, force);
        let norm = t_len * f;
        let sigma = (robust_length(k) / norm).min(1.0);
        let c = (t0.dot(force) / norm).clamp(-1.0, 1.0);
        if sigma == 0.0 {
            // Along F, or exactly against it (an exact but unstable equilibrium): straight,
            // with ln n changing at the rate ±|F|.
            let c = c.signum();
            return Self {
                f_index: f,
                c,
                a: 1.0 + c,
                b: 1.0 - c,
                ..straight
            };
        }
        let (a, b) = if c >= 0.0 {
            let a = 1.0 + c;
            (a, sigma * sigma / a)
        } else {
            let b = 1.0 - c;
            (sigma * sigma / b, b)
        };
        Self {
            origin,
            t0: unit_t,
            f,
            f_index: f,
            f_hat: force / f,
            p_hat: {
                let fk = accurate_cross(force, k);
                fk / robust_length(fk)
            },
            c,
            sigma,
            a,
            b,
        }
    }

    /// |F| (1/length): the curvature bound of the segment; 0 when straight.
    pub fn force(&self) -> f64 {
        self.f
    }

    /// ln(n(s)/n(0)) along the segment: ln n changes by F·(x(s) − x0) = L(s) =
    /// ln(cosh |F|s + cos β sinh |F|s), evaluated without overflow for any s ≥ 0.
    pub fn log_index_gain(&self, s: f64) -> f64 {
        let x = self.f_index * s;
        if x <= 1.0 {
            // cosh x + c sinh x − 1 = c sinh x + 2 sinh²(x/2): no cancellation for small x.
            let half = (0.5 * x).sinh();
            (self.c * x.sinh() + 2.0 * half * half).ln_1p()
        } else {
            // ln((a eˣ + b e⁻ˣ)/2) with a = 1 + cos β, b = 1 − cos β, by its larger term.
            let e2 = (-2.0 * x).exp();
            if self.a == 0.0 {
                -x + (0.5 * self.b).ln()
            } else if self.a >= self.b * e2 {
                x + (0.5 * (self.a + self.b * e2)).ln()
            } else {
                -x + (0.5 * (self.a / e2 + self.b)).ln()
            }
        }
    }

    /// The optical path ∫₀ˢ n ds along the segment in units of n(0): with n = n(0) e^L,
    /// ∫ e^L ds = (sinh |F|s + cos β (cosh |F|s − 1))/|F| in closed form (s where F = 0).
    pub fn relative_optical_path(&self, s: f64) -> f64 {
        let (f, c) = (self.f_index, self.c);
        let x = f * s;
        if x < SERIES_LIMIT {
            // Truncation x⁴/120 ≤ 1e-18.
            return s * (1.0 + x * (0.5 * c + x * (1.0 / 6.0 + x * c / 24.0)));
        }
        if x <= 1.0 {
            let half = (0.5 * x).sinh();
            (x.sinh() + 2.0 * c * half * half) / f
        } else {
            // (a eˣ − b e⁻ˣ)/2 − c: no cancellation where 1 + cos β is tiny (against F); a = 0
            // (exactly against F) must not meet an overflowed eˣ.
            let grow = if self.a == 0.0 { 0.0 } else { self.a * x.exp() };
            (0.5 * (grow - self.b * (-x).exp()) - c) / f
        }
    }

    /// Largest distance of the arc over [0, s] from its chord (the segment between its ends):
    /// its curvature is |F| sin θ ≤ |F| (the bound of `deviation_bound`).
    pub fn max_deviation(&self, s: f64) -> f64 {
        deviation_bound(self.f, s)
    }

    /// The region that holds the arc over [0, s]: within [`Self::max_deviation`] of its chord.
    pub fn hull(&self, s: f64) -> ArcHull {
        ArcHull {
            a: self.origin,
            b: self.at(s).position,
            deviation: self.max_deviation(s),
        }
    }

    /// The in-plane components (along F̂, along p̂) of x(s) − x0 and of t̂(s).
    /// Returns (L/|F|, Δ/|F|, tanh τ, sech τ).
    fn components(&self, s: f64) -> (f64, f64, f64, f64) {
        let (c, sigma, a, b) = (self.c, self.sigma, self.a, self.b);
        let x = self.f * s;
        if x < SERIES_LIMIT {
            let q = sigma * sigma;
            let (c2, x2) = (c * c, x * x);
            let (x3, x4) = (x2 * x, x2 * x2);
            let tanh = c + q * x - c * q * x2
                + q * (3.0 * c2 - 1.0) * x3 / 3.0
                + c * q * (2.0 - 3.0 * c2) * x4 / 3.0;
            let poly_sech = 1.0 - c * x
                + (2.0 * c2 - 1.0) * x2 / 2.0
                + c * (5.0 - 6.0 * c2) * x3 / 6.0
                + (24.0 * c2 * c2 - 28.0 * c2 + 5.0) * x4 / 24.0;
            let along = s
                * (c + q * x / 2.0 - c * q * x2 / 3.0
                    + q * (3.0 * c2 - 1.0) * x3 / 12.0
                    + c * q * (2.0 - 3.0 * c2) * x4 / 15.0);
            let across = s
                * sigma
                * (1.0 - c * x / 2.0
                    + (2.0 * c2 - 1.0) * x2 / 6.0
                    + c * (5.0 - 6.0 * c2) * x3 / 24.0
                    + (24.0 * c2 * c2 - 28.0 * c2 + 5.0) * x4 / 120.0);
            return (along, across, tanh, sigma * poly_sech);
        }
        if c < 0.0 && sigma < TINY_SIN {
            return self.components_against_force(x);
        }
        let e = (-x).exp();
        let e1 = -(-x).exp_m1();
        let den = a + b * e * e;
        let tanh = (a - b * e * e) / den;
        let sech = 2.0 * sigma * e / den;
        let delta = 2.0 * (sigma * e1 / (a + b * e)).atan();
        let m = 0.5 * b * e1 * (1.0 + e);
        let l = if m <= 0.5 {
            x + (-m).ln_1p()
        } else {
            x + (0.5 * den).ln()
        };
        (l / self.f, delta / self.f, tanh, sech)
    }

    /// A ray launched (almost) exactly against F, where 1 + cos β underflows.
    /// Everything goes through e^τ0 = σ/(1 − cos β) (exact) and τ = x + τ0, with
    /// L = ln cosh τ − ln cosh τ0 and Δ = 2(atan e^τ − atan e^τ0) arranged so that no large
    /// terms cancel; what is left is the inherent ε·|τ0| of the U-turn's position.
    fn components_against_force(&self, x: f64) -> (f64, f64, f64, f64) {
        let e0 = self.sigma / self.b;
        let tau0 = e0.ln();
        let tau = x + tau0;
        let (l, delta) = if tau <= 0.0 {
            // Still heading against F: e^τ − e^τ0 = e^τ0 expm1(x), accurate for small x.
            let diff = if x < 1.0 {
                e0 * x.exp_m1()
            } else {
                tau.exp() - e0
            };
            (
                -x + (2.0 * tau).exp().ln_1p() - (e0 * e0).ln_1p(),
                2.0 * (diff / (1.0 + e0 * tau.exp())).atan(),
            )
        } else {
            (
                x + 2.0 * tau0 + (-2.0 * tau).exp().ln_1p() - (e0 * e0).ln_1p(),
                2.0 * (tau.exp().atan() - e0.atan()),
            )
        };
        (l / self.f, delta / self.f, tau.tanh(), 1.0 / tau.cosh())
    }

    /// Position and direction at arclength `s` ≥ 0.
    pub fn at(&self, s: f64) -> ArcPoint {
        if self.f == 0.0 {
            return ArcPoint {
                position: self.origin + s * self.t0,
                direction: self.t0,
            };
        }
        let (along, across, tanh, sech) = self.components(s);
        ArcPoint {
            position: self.origin + along * self.f_hat + across * self.p_hat,
            direction: (tanh * self.f_hat + sech * self.p_hat).normalize(),
        }
    }

    /// Signed distance of x(s) from the plane through `point` with unit `normal`, and its
    /// derivative t̂(s)·normal.
    fn plane_offset(&self, s: f64, normal: DVec3, point: DVec3) -> (f64, f64) {
        let p = self.at(s);
        ((p.position - point).dot(normal), p.direction.dot(normal))
    }

    /// Where t̂(s)·m = 0 on (0, length): the single turning point of the offset from a plane
    /// with unit normal m, at sinh τ* = −(p̂·m)/(F̂·m).
    fn plane_turning_point(&self, normal: DVec3, length: f64) -> Option<f64> {
        if self.f == 0.0 {
            return None;
        }
        let fm = self.f_hat.dot(normal);
        let pm = self.p_hat.dot(normal);
        if fm == 0.0 {
            return None;
        }
        let tau_star = (-pm / fm).asinh();
        let tau0 = 0.5 * (self.a / self.b).ln();
        let s_star = (tau_star - tau0) / self.f;
        (s_star > 0.0 && s_star < length).then_some(s_star)
    }

    /// First arclength in (0, length] at which the segment crosses the plane through `point`
    /// with unit `normal`, to a relative arclength accuracy of ~1e-12.
    ///
    /// Unlike Tessendorf's (2022) test (no hit when the offsets at both ends have one sign), this finds a
    /// segment that enters and leaves the plane's far side within one step: the offset has at
    /// most one extremum, at [`Self::plane_turning_point`], and each monotone piece is refined
    /// separately.
    pub fn first_plane_crossing(&self, normal: DVec3, point: DVec3, length: f64) -> Option<f64> {
        let mut pieces = [(0.0, length), (length, length)];
        if let Some(s_star) = self.plane_turning_point(normal, length) {
            pieces = [(0.0, s_star), (s_star, length)];
        }
        pieces
            .iter()
            .filter(|(lo, hi)| hi > lo)
            .find_map(|&(lo, hi)| self.refine_plane_root(normal, point, lo, hi))
    }

    /// Root of the (monotone) plane offset on [lo, hi] by safeguarded Newton, if it changes sign.
    fn refine_plane_root(&self, normal: DVec3, point: DVec3, lo: f64, hi: f64) -> Option<f64> {
        let (f_lo, _) = self.plane_offset(lo, normal, point);
        let (f_hi, _) = self.plane_offset(hi, normal, point);
        if f_lo == 0.0 && lo > 0.0 {
            return Some(lo);
        }
        if f_lo * f_hi > 0.0 || (f_lo == 0.0 && f_hi == 0.0) {
            return None;
        }
        if f_hi == 0.0 {
            return Some(hi);
        }
        let (mut a, mut b) = (lo, hi);
        let rising = f_hi > f_lo;
        let mut s = 0.5 * (a + b);
        for _ in 0..200 {
            let (g, dg) = self.plane_offset(s, normal, point);
            if g == 0.0 {
                return Some(s);
            }
            if (g > 0.0) == rising {
                b = s;
            } else {
                a = s;
            }
            let newton = s - g / dg;
            if dg != 0.0 && newton > a && newton < b {
                if (newton - s).abs() <= 1e-14 * s.abs() {
                    return Some(newton);
                }
                s = newton;
            } else {
                s = 0.5 * (a + b);
            }
            if b - a <= 1e-14 * b.abs() {
                break;
            }
        }
        (s > 0.0).then_some(s)
    }
}
