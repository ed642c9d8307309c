//! Surface materials and the Fresnel equations at a dielectric interface.

use crate::color::Rgb;
use crate::texture::Texture;
use glam::DVec3;
use std::sync::Arc;

/// How a surface scatters light.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// Lambertian, BRDF = albedo/π, two-sided.
    Diffuse {
        /// Reflectance per channel in [0, 1] (times the texture's, if any).
        albedo: Rgb,
        /// An image texture over the surface's (u, v), multiplying `albedo`.
        texture: Option<Arc<Texture>>,
    },
    /// A perfect mirror.
    Mirror {
        /// Reflectance per channel in [0, 1].
        reflectance: Rgb,
    },
    /// A smooth dielectric boundary: Fresnel reflection and Snell refraction, with the index
    /// on each side evaluated at the hit point. The inside is the shape's interior medium.
    Dielectric,
    /// A receiver's detector plane: transparent, it records the photons crossing it.
    Detector {
        /// Index into the scene's receivers.
        receiver: usize,
    },
    /// An emitter of constant radiance from its front side (the side its normal points to),
    /// black on the back; it reflects nothing.
    Emissive {
        /// Radiance per channel, W/(m²·sr).
        radiance: Rgb,
    },
}

/// Unpolarised Fresnel reflectance for a ray from index `n1` to `n2` with cos θi = `cos_i`
/// (> 0); 1 under total internal reflection. Also returns cos θt.
pub fn fresnel(cos_i: f64, n1: f64, n2: f64) -> (f64, f64) {
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return (1.0, 0.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    (0.5 * (rs * rs + rp * rp), cos_t)
}

/// Mirror reflection of direction `d` about unit normal `n`.
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refraction of unit `d` through a surface with unit normal `n` facing the incident side
/// (d·n < 0), from `n1` to `n2`, given cos θt from [`fresnel`].
pub fn refract(d: DVec3, n: DVec3, n1: f64, n2: f64, cos_t: f64) -> DVec3 {
    let eta = n1 / n2;
    let cos_i = -d.dot(n);
    (eta * d + (eta * cos_i - cos_t) * n).normalize()
}
