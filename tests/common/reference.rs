//! Closed forms and quadratures used as references.

/// 4-point Gauss–Legendre on [0, 1] with `panels` equal panels.
pub fn gauss_legendre(f: impl Fn(f64) -> f64, panels: usize) -> f64 {
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
        for k in 0..4 {
            sum += W[k] * f(mid + 0.5 * h * X[k]);
        }
    }
    0.5 * h * sum
}

/// Exact total deflection (rad) of a ray with impact parameter `b` (in rs) by the
/// spherically symmetric index n(r) = r²/(r² − r + q²) (r in rs), from Bouguer's invariant
/// n r sin ψ = b: φ = 2∫₀^{u0} b du / √(n(u)² − b²u²) − π, u = 1/r, n(u) = 1/(1 − u + q²u²),
/// u0 the turning point (n(u0) = b u0, smallest root). Substituting u = u0(1 − w²) removes the
/// inverse-square-root end point. `None` when the ray has no turning point (captured).
pub fn black_hole_deflection(b: f64, q: f64) -> Option<f64> {
    let n = |u: f64| 1.0 / (1.0 - u + q * q * u * u);
    let g = |u: f64| n(u) - b * u;
    // Walk out from u = 0 (g > 0) to the first sign change, then bisect.
    let mut lo = 0.0;
    let mut step = 1e-3 / b;
    let mut hi = lo + step;
    while g(hi) > 0.0 {
        lo = hi;
        step *= 1.1;
        hi = lo + step;
        let den = 1.0 - hi + q * q * hi * hi;
        if den <= 0.0 || hi > 1e3 {
            return None;
        }
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let u0 = 0.5 * (lo + hi);
    let integrand = |w: f64| {
        let u = u0 * (1.0 - w * w);
        let nu = n(u);
        2.0 * b * u0 * w / (nu * nu - b * b * u * u).sqrt()
    };
    Some(2.0 * gauss_legendre(integrand, 4000) - std::f64::consts::PI)
}
