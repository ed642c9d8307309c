//! How a surface scatters light at one point: sample a direction, evaluate f, give the pdf.
//! Directions are unit vectors pointing away from the surface (`wo` toward where the path
//! came from, `wi` where it goes next); `n` is the unit normal on the side `wo` lies on.
//! Radiance per RGB channel; f in 1/sr.
//!
//! A dielectric's sample carries weight 1: the change of radiance across indices,
//! (n_far/n_near)², is accounted once for a whole path by the transport (see
//! [`crate::transport::chain`]), so no BSDF scales by it.

use crate::color::Rgb;
use crate::material::{fresnel, reflect, refract};
use crate::sampling::{cosine_hemisphere, Frame};
use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

/// A scattering function at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf {
    /// Lambertian, f = albedo/π on the side of `n`.
    Lambert {
        /// Reflectance per channel.
        albedo: Rgb,
    },
    /// A perfect mirror.
    Mirror {
        /// Reflectance per channel.
        reflectance: Rgb,
    },
    /// A smooth interface from index `n1` (the side of `wo`) to `n2`: Fresnel reflection and
    /// Snell refraction.
    Dielectric {
        /// Index on the side of `wo`.
        n1: f64,
        /// Index on the other side.
        n2: f64,
    },
}

/// A sampled direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The new direction (unit).
    pub wi: DVec3,
    /// f·|cos θi| / pdf: what the path's throughput is multiplied by.
    pub weight: Rgb,
    /// Solid-angle pdf of `wi` (1/sr); ∞ for a specular (delta) choice.
    pub pdf: f64,
    /// Whether `wi` crosses the surface (a refraction).
    pub transmitted: bool,
}

impl Bsdf {
    /// Samples a direction for uniform numbers `u` (u.0, u.1 for the lobe, u.2 for a
    /// discrete choice such as Fresnel's; a specular surface uses only u.2). None when `wo`
    /// lies below a dielectric's side `n`.
    pub fn sample(&self, wo: DVec3, n: DVec3, u: (f64, f64, f64)) -> Option<BsdfSample> {
        match *self {
            Bsdf::Lambert { albedo } => {
                let wi = Frame::new(n).to_world(cosine_hemisphere((u.0, u.1)));
                Some(BsdfSample {
                    wi,
                    weight: albedo,
                    pdf: wi.dot(n).max(0.0) * FRAC_1_PI,
                    transmitted: false,
                })
            }
            Bsdf::Mirror { reflectance } => Some(BsdfSample {
                wi: reflect(-wo, n),
                weight: reflectance,
                pdf: f64::INFINITY,
                transmitted: false,
            }),
            Bsdf::Dielectric { n1, n2 } => {
                if wo.dot(n) < 0.0 {
                    return None;
                }
                let (r, cos_t) = fresnel(wo.dot(n), n1, n2);
                let (wi, transmitted) = if u.2 < r {
                    (reflect(-wo, n), false)
                } else {
                    (refract(-wo, n, n1, n2, cos_t), true)
                };
                Some(BsdfSample {
                    wi,
                    weight: Rgb::ONE,
                    pdf: f64::INFINITY,
                    transmitted,
                })
            }
        }
    }

    /// f(wo, wi) (1/sr): albedo/π for a Lambertian pair on the side of `n`, 0 for specular
    /// surfaces (whose f is a delta).
    pub fn eval(&self, wo: DVec3, wi: DVec3, n: DVec3) -> Rgb {
        match *self {
            Bsdf::Lambert { albedo } if wo.dot(n) > 0.0 && wi.dot(n) > 0.0 => albedo * FRAC_1_PI,
            _ => Rgb::ZERO,
        }
    }

    /// The solid-angle pdf with which [`Bsdf::sample`] draws `wi` (0 for specular surfaces).
    pub fn pdf(&self, wo: DVec3, wi: DVec3, n: DVec3) -> f64 {
        match *self {
            Bsdf::Lambert { .. } if wo.dot(n) > 0.0 => wi.dot(n).max(0.0) * FRAC_1_PI,
            _ => 0.0,
        }
    }

    /// Whether every scattered direction is a delta (mirror, dielectric).
    pub fn is_specular(&self) -> bool {
        !matches!(self, Bsdf::Lambert { .. })
    }
}
