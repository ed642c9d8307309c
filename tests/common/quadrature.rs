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
