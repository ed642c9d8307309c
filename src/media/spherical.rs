//! Profiles that depend on the distance from a centre: Luneburg lens, Maxwell fish-eye, black
//! holes (Tessendorf's (2022) weak-field index and the exact Schwarzschild / Reissner–Nordström one).

use super::{ConstantCurvature, IndexSample, Medium};
use glam::DVec3;

/// Luneburg lens n = √(2 − (r/R)²) inside the sphere of radius R, 1 outside: parallel rays
/// focus on the antipodal surface point.
#[derive(Clone, Debug)]
pub struct Luneburg {
    /// Centre of the lens.
    pub center: DVec3,
    /// Radius R.
    pub radius: f64,
}

impl Medium for Luneburg {
    /// Transparent.
    fn symmetry_center(&self) -> Option<DVec3> {
        Some(self.center)
    }
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        // In units of R (d/R, never R², which underflows for the smallest lenses).
        let v = (p - self.center) / self.radius;
        let u2 = v.length_squared();
        if u2 > 1.0 {
            return Some(IndexSample::constant(1.0));
        }
        let n = (2.0 - u2).sqrt();
        Some(IndexSample {
            n,
            grad: -v / (n * self.radius),
        })
    }
    /// A quarter of R inside the lens; outside, where n = 1, the distance to the lens plus
    /// that (a step may reach the lens, not cross it): a ray far from a small lens is not
    /// held to the lens's scale.
    fn step_hint(&self, p: DVec3, _dir: DVec3) -> f64 {
        ((p - self.center).length() - self.radius).max(0.0) + 0.25 * self.radius
    }
}

/// Maxwell fish-eye n = n0 / (1 + (r/R)²): with n0 = 2, R = 1 a ray from P0 passes through −P0/|P0|².
#[derive(Clone, Debug)]
pub struct FishEye {
    /// Index at the centre.
    pub n0: f64,
    /// Centre.
    pub center: DVec3,
    /// Radius scale R.
    pub radius: f64,
}

impl Medium for FishEye {
    /// Transparent.
    fn symmetry_center(&self) -> Option<DVec3> {
        Some(self.center)
    }
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let d = p - self.center;
        let r2 = self.radius * self.radius;
        let w = 1.0 + d.length_squared() / r2;
        let n = self.n0 / w;
        Some(IndexSample {
            n,
            grad: -2.0 * n / (w * r2) * d,
        })
    }
    /// ∇ln n = −2d/(R² + r²) varies on the scale max(R, r).
    fn step_hint(&self, p: DVec3, _dir: DVec3) -> f64 {
        0.25 * self.radius.max((p - self.center).length())
    }
    fn constant_curvature(&self) -> Option<ConstantCurvature<'_>> {
        Some(ConstantCurvature::FishEye(self))
    }
    /// πR/2: n ≤ n0, so the geodesic's angle grows as dθ/ds = 2n/(n0 R) ≤ 2/R and turns at most
    /// half the great circle, and the x-space circle (of radius ≥ R: it holds a point and its
    /// antipodal image) at most a right angle, where surfaces still meet it in closed form
    /// ([`crate::curve::CircleArc::crossings`]).
    fn exact_reach(&self) -> Option<f64> {
        Some(0.5 * std::f64::consts::PI * self.radius)
    }
}

/// The hyperbolic medium n = n0 / (1 − (r/R)²) inside the ball r < R: the Poincaré ball, a
/// space of constant negative curvature whose rays are straightened in closed form
/// ([`crate::curve::GeodesicRay`]) and reach the rim only after an infinite optical path. A
/// ray is captured within a relative [`HyperbolicMedium::RIM_MARGIN`] of the rim (where n
/// exceeds 10⁸ n0) and outside it.
#[derive(Clone, Debug)]
pub struct HyperbolicMedium {
    /// Index at the centre.
    pub n0: f64,
    /// Centre.
    pub center: DVec3,
    /// Radius R of the rim.
    pub radius: f64,
}

impl HyperbolicMedium {
    /// 1 − (r/R)² below which a ray counts as captured at the rim.
    pub const RIM_MARGIN: f64 = 1e-8;
}

impl Medium for HyperbolicMedium {
    /// Transparent.
    fn symmetry_center(&self) -> Option<DVec3> {
        Some(self.center)
    }
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let u = (p - self.center) / self.radius;
        let w = 1.0 - u.length_squared();
        if w.is_nan() || w < Self::RIM_MARGIN {
            return None;
        }
        let n = self.n0 / w;
        Some(IndexSample {
            n,
            grad: 2.0 * n / (w * self.radius) * u,
        })
    }
    /// ∇ln n = 2u/(wR) varies on the scale w R: a quarter of it.
    fn step_hint(&self, p: DVec3, _dir: DVec3) -> f64 {
        let w = 1.0 - ((p - self.center) / self.radius).length_squared();
        0.25 * self.radius * w.max(Self::RIM_MARGIN)
    }
    fn constant_curvature(&self) -> Option<ConstantCurvature<'_>> {
        Some(ConstantCurvature::Hyperbolic(self))
    }
    /// θ is unique along the hyperbolic medium's geodesics, but the rim is near: nothing beyond
    /// the medium's own hint.
    fn exact_reach(&self) -> Option<f64> {
        Some(0.0)
    }
}

/// Weak-field index of a Reissner–Nordström black hole, n = ρ²/(ρ² − ρ + q²) with
/// ρ = |x − center|/rs (Tessendorf (2022) eq. 25). A ray is captured at and inside the horizon
/// ρ+ = (1 + √(1 − 4q²))/2, where the index diverges, and at the centre.
#[derive(Clone, Debug)]
pub struct BlackHole {
    center: DVec3,
    rs: f64,
    q: f64,
    /// q², and the u = rs/r at which a ray is captured (∞ without a horizon): what every
    /// evaluation of the index asks, worked out once.
    q2: f64,
    capture_u: f64,
}

impl BlackHole {
    /// Relative distance above the horizon at which a ray counts as captured: there n is
    /// ~1e9 and no step can resolve the path any further in f64.
    const CAPTURE_MARGIN: f64 = 1e-9;

    /// The black hole at `center` of Schwarzschild radius `rs` (length) and dimensionless
    /// charge `q`.
    pub fn new(center: DVec3, rs: f64, q: f64) -> Self {
        let mut hole = Self {
            center,
            rs,
            q,
            q2: q * q,
            capture_u: f64::INFINITY,
        };
        let horizon = hole.horizon();
        if horizon > 0.0 {
            hole.capture_u = 1.0 / (horizon * (1.0 + Self::CAPTURE_MARGIN));
        }
        hole
    }

    /// Outer root of ρ² − ρ + q² in units of rs (0 when 4q² > 1: no horizon).
    pub fn horizon(&self) -> f64 {
        let disc = 1.0 - 4.0 * self.q * self.q;
        if disc >= 0.0 {
            0.5 * (1.0 + disc.sqrt())
        } else {
            0.0
        }
    }
}

impl Medium for BlackHole {
    /// Transparent.
    fn symmetry_center(&self) -> Option<DVec3> {
        Some(self.center)
    }
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let d = p - self.center;
        let inv_r = d.length().recip();
        // In u = 1/ρ = rs/r, which neither overflows for the smallest rs nor loses ρ² to
        // infinity: n = 1/D with D = 1 − u + q²u². Captured at the horizon, and at the
        // centre (u = ∞); a NaN position is no index either.
        let u = self.rs * inv_r;
        if u.is_nan() || u >= self.capture_u {
            return None;
        }
        let den = 1.0 - u + self.q2 * u * u;
        if den <= 0.0 {
            return None;
        }
        let n = den.recip();
        // dn/du = (1 − 2q²u)/D², and ∇u = −u d/r².
        let grad = d * (-(1.0 - 2.0 * self.q2 * u) * n * n * u * inv_r * inv_r);
        (n.is_finite() && grad.is_finite()).then_some(IndexSample { n, grad })
    }
    /// A quarter of the distance to the horizon (far away, a quarter of the distance to the
    /// centre: the scale on which ∇ln n ∝ 1/r² varies). Steps toward the horizon shrink
    /// geometrically, so a plunging ray reaches the capture margin in ~70 steps.
    fn step_hint(&self, p: DVec3, _dir: DVec3) -> f64 {
        let r = (p - self.center).length();
        0.25 * (r - self.horizon() * self.rs).max(0.0)
    }
}

/// A Reissner–Nordström black hole — Schwarzschild when `q` = 0 — as the exact index medium
/// (Misner, Thorne & Wheeler 1973): in isotropic coordinates ρ (the scene's lengths: ρ = |x − center|) the
/// spatial metric is conformally flat, so light follows the rays of
/// n(ρ) = A² / (1 − K/ρ²), A = 1 + M/ρ + K/ρ², K = (M² − Q²)/4,
/// with M = rs/2 and Q = q·rs (Tessendorf's (2022) q). nρ is GR's turning-point impact parameter, so
/// deflections are GR's exactly; far away n ≈ 1 + rs/ρ, the weak-field index. The areal
/// radius is r = ρA ([`ExactBlackHole::areal_radius`]). Rays are captured at the horizon
/// ρ_h = √K (q ≤ ½); with no horizon (q > ½) the singularity r = 0 lies at ρ₀ = (Q − M)/2,
/// where n → 0: only rays aimed almost at it come near, and they end there, captured.
#[derive(Clone, Debug)]
pub struct ExactBlackHole {
    /// Centre.
    pub center: DVec3,
    /// Schwarzschild radius rs = 2M (length).
    pub rs: f64,
    /// Dimensionless charge q = Q/rs (0: Schwarzschild).
    pub q: f64,
}

impl ExactBlackHole {
    /// Relative distance above the horizon (or the singularity) at which a ray counts as
    /// captured: there n is ~1e9 (or ~1e-18) and no step resolves the path further in f64.
    const CAPTURE_MARGIN: f64 = 1e-9;

    /// (M, K) in scene lengths: M = rs/2, K = (M² − Q²)/4.
    fn constants(&self) -> (f64, f64) {
        let m = 0.5 * self.rs;
        let charge = self.q * self.rs;
        (m, 0.25 * (m * m - charge * charge))
    }

    /// Where rays end, in isotropic ρ: the horizon √K, or with no horizon the singularity
    /// (Q − M)/2 (0 when Q = M).
    pub fn capture_radius(&self) -> f64 {
        let (m, k) = self.constants();
        if k >= 0.0 {
            k.sqrt()
        } else {
            0.5 * (self.q * self.rs - m)
        }
    }

    /// The areal radius r = ρ·A(ρ) of isotropic radius ρ (what Schwarzschild coordinates call
    /// r: a sphere of radius ρ has area 4πr²).
    pub fn areal_radius(&self, rho: f64) -> f64 {
        let (m, k) = self.constants();
        rho + m + k / rho
    }

    /// GR's f(r) = 1 − 2M/r + Q²/r² at u = 1/r (areal).
    fn lapse2(&self, u: f64) -> f64 {
        let (m, charge) = (0.5 * self.rs, self.q * self.rs);
        1.0 - 2.0 * m * u + charge * charge * u * u
    }

    /// General relativity's deflection (rad) of a light ray of impact parameter `b` between
    /// two static observers at areal radii 1/`u1` and 1/`u2` (0: infinity) on either side of
    /// its turning point, computed from the metric in areal coordinates — not from the index,
    /// so it is the reference the index is checked against: Φ(u1) + Φ(u2) − π + ψ1 + ψ2, with
    /// Φ(u) = ∫_u^{u₀} du'/√(1/b² − u'² f(u')) the polar angle swept to the turning point
    /// (1/b² = u₀² f(u₀)) and sin ψ = b u √f(u) the angle a static observer measures from the
    /// radial direction. None when the ray has no turning point (it is captured).
    pub fn gr_deflection(&self, b: f64, u1: f64, u2: f64) -> Option<f64> {
        let g = |u: f64| 1.0 / (b * b) - u * u * self.lapse2(u);
        // Beyond u = 2/rs (r = rs/2) lies the horizon of every q ≤ ½: no turning point.
        let u0 = turning_point(&g, b, |u| u * self.rs > 2.0)?;
        // Φ(u) with u' = u0(1 − w²), which takes the inverse square root off the turning point.
        let phi = |u: f64| {
            let top = (1.0 - u / u0).max(0.0).sqrt();
            let f = |t: f64| {
                let w = top * t;
                let v = u0 * (1.0 - w * w);
                2.0 * u0 * w * top / g(v).max(0.0).sqrt()
            };
            gauss_legendre(f, 4000)
        };
        let psi = |u: f64| (b * u * self.lapse2(u).sqrt()).asin();
        Some(phi(u1) + phi(u2) - std::f64::consts::PI + psi(u1) + psi(u2))
    }
}

impl Medium for ExactBlackHole {
    /// Transparent.
    fn symmetry_center(&self) -> Option<DVec3> {
        Some(self.center)
    }
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let d = p - self.center;
        let rho = d.length();
        // (At q = ½ the horizon is at ρ = 0, where n ∝ 1/ρ²: captured a hair off it.)
        let floor = self.capture_radius().max(Self::CAPTURE_MARGIN * self.rs);
        if rho <= floor * (1.0 + Self::CAPTURE_MARGIN) {
            return None;
        }
        let (m, k) = self.constants();
        let inv = 1.0 / rho;
        let a = 1.0 + m * inv + k * inv * inv;
        let den = 1.0 - k * inv * inv;
        if a <= 0.0 || den <= 0.0 {
            return None;
        }
        let n = a * a / den;
        // n'/n = 2A'/A − D'/D with A' = −M/ρ² − 2K/ρ³ and D' = 2K/ρ³; ∇ρ = d/ρ.
        let a1 = -(m + 2.0 * k * inv) * inv * inv;
        let d1 = 2.0 * k * inv * inv * inv;
        let grad = d * (n * (2.0 * a1 / a - d1 / den) * inv);
        (n.is_finite() && n > 0.0 && grad.is_finite()).then_some(IndexSample { n, grad })
    }
    /// A quarter of the distance to where rays end (far away, a quarter of the distance to the
    /// centre: ∇ln n ∝ 1/ρ² varies on that scale); steps toward the horizon shrink
    /// geometrically.
    fn step_hint(&self, p: DVec3, _dir: DVec3) -> f64 {
        0.25 * ((p - self.center).length() - self.capture_radius()).max(0.0)
    }
}

/// The turning point u₀ of a ray of impact parameter `b` in u = 1/r: the first root of `g`
/// (positive at u = 0), found by walking out in steps growing from 10⁻³/b, then bisecting to
/// rounding. None when the walk reaches a `u` that is `past` (a horizon: no turning point).
fn turning_point(g: &dyn Fn(f64) -> f64, b: f64, past: impl Fn(f64) -> bool) -> Option<f64> {
    let (mut lo, mut step) = (0.0, 1e-3 / b);
    let mut hi = step;
    while g(hi) > 0.0 {
        lo = hi;
        step *= 1.05;
        hi = lo + step;
        if past(hi) {
            return None;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        (lo, hi) = if g(mid) > 0.0 { (mid, hi) } else { (lo, mid) };
    }
    Some(0.5 * (lo + hi))
}

/// General relativity's deflection (rad) of a light ray passing a Schwarzschild hole of mass
/// M (rs = 2M) from infinity to infinity, as the perturbation series in μ = M/r₀ (r₀ the areal
/// radius of closest approach; the impact parameter is b = r₀/√(1 − 2μ)) summed to `terms`
/// orders. Tessendorf (2022) eq. 27 is such a series (Rodriguez and Marín, 20 orders in 3rs/2b); its
/// coefficients are not reproduced here, these are computed: with x = b·u, 1/b² = u₀²(1 − 2Mu₀)
/// and x = x₀s, 1 − x² + 2(M/b)x³ = x₀²(1 − s)[(1 + s) − 2μ(1 + s + s²)], so
/// π + α = 2∫₀¹ (1 − s²)^(−1/2) (1 − 2μh(s))^(−1/2) ds with h = (1 + s + s²)/(1 + s), and the
/// binomial series gives π + α = Σₖ C(2k, k) (μ/2)ᵏ Jₖ, Jₖ = 2∫₀^{π/2} h(sin θ)ᵏ dθ (a smooth
/// integrand: Gauss–Legendre to rounding). As h ≤ 3/2 the series converges for μ < 1/3, below
/// the photon sphere r₀ = 3M; the k-th term is at most about (3μ)ᵏ π/√(πk).
pub fn schwarzschild_deflection_series(mu: f64, terms: usize) -> f64 {
    let h = |s: f64| (1.0 + s + s * s) / (1.0 + s);
    let mut sum = 0.0;
    // C(2k, k)(μ/2)^k, built up term by term.
    let mut c = 1.0;
    for k in 0..=terms {
        if k > 0 {
            let kf = k as f64;
            c *= (2.0 * kf) * (2.0 * kf - 1.0) / (kf * kf) * (0.5 * mu);
        }
        let quarter = std::f64::consts::FRAC_PI_2;
        let j = 2.0 * quarter * gauss_legendre(|t| h((quarter * t).sin()).powi(k as i32), 64);
        sum += c * j;
    }
    sum - std::f64::consts::PI
}

/// 4-point Gauss–Legendre on [0, 1] with `panels` equal panels.
fn gauss_legendre(f: impl Fn(f64) -> f64, panels: usize) -> f64 {
    const X: [f64; 4] = [
        -0.861_136_311_594_052_6,
        -0.339_981_043_584_856_3,
        0.339_981_043_584_856_3,
        0.861_136_311_594_052_6,
    ];
    const W: [f64; 4] = [
        0.347_854_845_137_453_8,
        0.652_145_154_862_546_1,
        0.652_145_154_862_546_1,
        0.347_854_845_137_453_8,
    ];
    let h = 1.0 / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = (p as f64 + 0.5) * h;
        for (x, w) in X.iter().zip(W) {
            sum += w * f(mid + 0.5 * h * x);
        }
    }
    0.5 * h * sum
}

/// Exact deflection (rad) by the index n(r) = r²/(r² − r + q²) (r in units of rs) of a ray
/// with Bouguer invariant `b` = n r sin ψ (in rs) that starts at distance 1/`u_start` (0: at
/// infinity), passes its turning point and leaves to infinity: the angle between its first
/// and last directions. With u = 1/r and n(u) = 1/(1 − u + q²u²), the polar angle swept is
/// ∫ b du / √(n² − b²u²) over the path, so the deflection is
/// 2∫₀^{u0} − ∫₀^{u_start} − π + asin(b u_start / n(u_start)), u0 the turning point (the
/// smallest root of n(u) = b u; u = u0(1 − w²) removes the end-point singularity). For
/// u_start = 0 this is the deflection of a ray from infinity to infinity. `None` when the ray
/// has no turning point (it is captured) or starts inside it.
pub fn black_hole_deflection(b: f64, q: f64, u_start: f64) -> Option<f64> {
    let n = |u: f64| 1.0 / (1.0 - u + q * q * u * u);
    let g = |u: f64| n(u) - b * u;
    let u0 = turning_point(&g, b, |u| 1.0 - u + q * q * u * u <= 0.0 || u > 1e3)?;
    if u_start >= u0 {
        return None;
    }
    let to_turning_point = |w: f64| {
        let u = u0 * (1.0 - w * w);
        let nu = n(u);
        2.0 * b * u0 * w / (nu * nu - b * b * u * u).sqrt()
    };
    let to_start = |t: f64| {
        let u = u_start * t;
        let nu = n(u);
        b * u_start / (nu * nu - b * b * u * u).sqrt()
    };
    let full = gauss_legendre(to_turning_point, 4000);
    let start = if u_start > 0.0 {
        gauss_legendre(to_start, 400)
    } else {
        0.0
    };
    Some(2.0 * full - start - std::f64::consts::PI + (b * u_start / n(u_start)).asin())
}
