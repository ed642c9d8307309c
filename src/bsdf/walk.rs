//! Light on a rough dielectric interface as it really goes: a random walk over the Smith
//! microsurface (Heitz, Hanika, d'Eon and Dachsbacher 2016, "Multiple-scattering microfacet
//! BSDFs with the Smith model"). A ray meets the microsurface at a height drawn from the Smith
//! statistics (heights uniform in [−1, 1]), on a facet drawn from the visible normals, is
//! reflected or refracted by the facet's Fresnel term, and goes on — above the surface or
//! below it, where the surface is seen upside down — until no facet stops it.
//!
//! Its first scattering is Walter et al.'s (2007) single-scattering BSDF with the Smith
//! masking–shadowing of correlated heights: G₂ = 1/(1 + Λo + Λi) for a reflection and
//! B(1 + Λo, 1 + Λi) (Euler's beta function) for a transmission, whose outgoing ray must
//! leave downward from the height it refracted at ([`Microsurface::g2_transmission`]). The later
//! ones are the light a single-scattering model loses: none is lost here (a dielectric
//! absorbs nothing), so a sample's weight is 1. At equal indices every facet lets the ray
//! through unbent and the walk leaves straight on: the interface is not there, as it must
//! not be (a single-scattering model keeps only G₂/G₁ of it).

use super::fresnel::{self, reflect, refract};
use super::microfacet::Microsurface;
use glam::DVec3;
use rand::Rng;
use rand_pcg::Pcg64Mcg;

/// The most scatterings a walk follows: light still on the microsurface after them is taken
/// as lost (at α = 1 the walk's 99.99th percentile is below 40).
pub const MAX_ORDER: u32 = 256;

/// Where a walk leaves the microsurface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exit {
    /// The direction it leaves along (local, unit): above the surface (z > 0) a reflection,
    /// below it a transmission.
    pub wi: DVec3,
    /// How many facets it met (1: single scattering).
    pub order: u32,
}

/// The walk of light arriving along −`o` (local, o.z > 0) on the side of index `n1`, the
/// other side of index `n2`, over microsurface `g`. `u` are the first facet's numbers (its
/// normal, then the Fresnel choice); the walk's other numbers come from a stream keyed by
/// their bits, so that the exit is a function of `u` alone. None when it meets
/// [`MAX_ORDER`] facets.
pub fn dielectric(
    g: &Microsurface,
    n1: f64,
    n2: f64,
    o: DVec3,
    u: (f64, f64, f64),
) -> Option<Exit> {
    let mut rng = Pcg64Mcg::new(
        (u128::from(u.0.to_bits()) << 64 | u128::from(u.1.to_bits()))
            ^ u128::from(u.2.to_bits()).rotate_left(37)
            ^ 0x2545_f491_4f6c_dd1d_7f4a_7c15_9e37_79b9,
    );
    let mut first = Some(u);
    let mut ray = -o;
    // Above everything: the first facet is met for sure.
    let mut height = 2.0;
    let mut above = true;
    for order in 0..=MAX_ORDER {
        // Below the surface it is seen upside down: heights and directions negated.
        let flip = if above { 1.0 } else { -1.0 };
        match next_height(g, flip * ray, flip * height, rng.gen()) {
            Some(h) => height = flip * h,
            None => {
                return Some(Exit {
                    wi: ray.normalize(),
                    order,
                })
            }
        }
        if order == MAX_ORDER {
            break;
        }
        let (a, b, c) = first
            .take()
            .unwrap_or_else(|| (rng.gen(), rng.gen(), rng.gen()));
        // The facet faces the ray: drawn from the visible normals seen from −ray on its side.
        let m = flip * g.sample_visible(-flip * ray, (a, b));
        let (from, to) = if above { (n1, n2) } else { (n2, n1) };
        let cos = -ray.dot(m);
        let (r, cos_t) = fresnel::dielectric(cos, from, to);
        if c < r {
            ray = reflect(ray, m);
        } else {
            ray = refract(ray, m, from, to, cos_t);
            above = !above;
        }
    }
    None
}

/// Smith's Λ of a direction of travel `w` (local) as Heitz et al. sign it: Λ(w) upward,
/// −1 − Λ(w) downward (a ray going down meets the surface surely).
fn signed_lambda(g: &Microsurface, w: DVec3) -> f64 {
    match w.z > 0.0 {
        true => g.lambda(w),
        false => -1.0 - g.lambda(w),
    }
}

/// The height at which a ray travelling along `w` from height `h` above the microsurface
/// next meets it, for uniform `u`; None where it leaves. Heights are uniform in [−1, 1]
/// (C₁(h) = (h + 1)/2), so the chance a ray goes on unstopped from h is C₁(h)^Λ(w).
fn next_height(g: &Microsurface, w: DVec3, h: f64, u: f64) -> Option<f64> {
    let c1 = |h: f64| (0.5 * (h + 1.0)).clamp(0.0, 1.0);
    let inverse = |c: f64| (2.0 * c - 1.0).clamp(-1.0, 1.0);
    if w.z > 0.9999 {
        return None;
    }
    if w.z < -0.9999 {
        return Some(inverse(u * c1(h)));
    }
    if w.z.abs() < 1e-4 {
        return Some(h);
    }
    let lambda = signed_lambda(g, w);
    let unstopped = match w.z > 0.0 {
        true => c1(h).powf(lambda),
        false => 0.0,
    };
    if u > 1.0 - unstopped {
        return None;
    }
    Some(inverse(c1(h) / (1.0 - u).powf(1.0 / lambda)))
}
