//! A product quadrature over the hemisphere about +z for integrands that peak at the pole
//! (microfacet distributions, lobes about the normal): cos θ = 1 − t² with t on a midpoint
//! grid crowds the nodes toward the pole, dω = 2t dt dφ.

use glam::DVec3;
use std::f64::consts::PI;

/// ∫ g(ω) dω over the hemisphere z > 0 on `nt` × `np` nodes in (t, φ).
pub fn hemisphere(nt: usize, np: usize, mut g: impl FnMut(DVec3) -> f64) -> f64 {
    let mut sum = 0.0;
    for i in 0..nt {
        let t = (i as f64 + 0.5) / nt as f64;
        let cos = 1.0 - t * t;
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        for j in 0..np {
            let phi = 2.0 * PI * (j as f64 + 0.5) / np as f64;
            sum += g(DVec3::new(sin * phi.cos(), sin * phi.sin(), cos)) * 2.0 * t;
        }
    }
    sum * (1.0 / nt as f64) * (2.0 * PI / np as f64)
}

/// The directional albedo ∫ f(ωo, ωi) cos θi dωi of a reflecting BSDF `f(ωi)` about +z, over
/// microfacet normals (ωi = 2(ωo·m)m − ωo, dωi = 4 (ωo·m) dωm): nodes crowd where a
/// microfacet distribution peaks, independently of any sampler.
pub fn reflected_fraction(nt: usize, np: usize, wo: DVec3, f: impl Fn(DVec3) -> f64) -> f64 {
    hemisphere(nt, np, |m| {
        let om = wo.dot(m);
        let wi = 2.0 * om * m - wo;
        if om > 0.0 && wi.z > 0.0 {
            f(wi) * wi.z * 4.0 * om
        } else {
            0.0
        }
    })
}

/// Gauss–Legendre nodes and weights on [0, 1] (`n` of them), the nodes found by Newton's
/// method on Pₙ from Chebyshev guesses (to rounding).
pub fn gauss_legendre_unit(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut nodes, mut weights) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let k = k as f64;
                (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let step = p1 / dp;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        nodes.push(0.5 * (1.0 - x));
        weights.push(1.0 / ((1.0 - x * x) * dp * dp));
    }
    (nodes, weights)
}

/// ∫₋₁¹ f(μ) dμ of a pair of integrands, by 48-node Gauss–Legendre on panels that shrink
/// toward μ = ±1 (where forward- or backward-peaked phase functions peak).
pub fn integrate_mu(f: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    let edges = [-1.0, -0.999, -0.99, -0.9, 0.0, 0.9, 0.99, 0.999, 1.0];
    let (nodes, weights) = gauss_legendre_unit(48);
    let mut sum = (0.0, 0.0);
    for pair in edges.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        for (x, w) in nodes.iter().zip(&weights) {
            let (p, q) = f(a + (b - a) * x);
            sum.0 += w * (b - a) * p;
            sum.1 += w * (b - a) * q;
        }
    }
    sum
}
