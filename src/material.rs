//! Surface materials: what a scene says a surface is. [`crate::bsdf`] is how it scatters;
//! [`crate::transport::Tracer::vertex_bsdf`] makes the one from the other at a hit.

use crate::bsdf::{Coat, Ggx, Lobes, Metal};
use crate::color::Rgb;
use crate::texture::Texture;
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
    /// A conductor (`conductor`, and `mirror`: a smooth one of constant reflectance), two-sided:
    /// a mirror where `roughness` is below [`crate::bsdf::SMOOTH_ALPHA`], else GGX.
    Conductor {
        /// Its complex index or reflectance.
        index: ConductorIndex,
        /// GGX α.
        roughness: f64,
    },
    /// A dielectric boundary, with the index on each side evaluated at the hit point: Fresnel
    /// reflection and Snell refraction where `roughness` is below
    /// [`crate::bsdf::SMOOTH_ALPHA`], else Walter et al.'s rough interface. The inside is the
    /// shape's interior medium.
    Dielectric {
        /// GGX α.
        roughness: f64,
    },
    /// A diffuse base under a rough dielectric coat, two-sided.
    Plastic {
        /// The base's reflectance per channel in [0, 1] (times the texture's, if any).
        albedo: Rgb,
        /// An image texture over the surface's (u, v), multiplying `albedo`.
        texture: Option<Arc<Texture>>,
        /// The coat, with its tabulated albedo.
        coat: Arc<Coat>,
    },
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

/// What a conductor's Fresnel reflectance is made from.
#[derive(Clone, Debug, PartialEq)]
pub enum ConductorIndex {
    /// The same reflectance at every angle (a `mirror`; `metal = "perfect"` is 1).
    Constant(Rgb),
    /// A measured metal's η + ik over wavelength, relative to vacuum: one of the named
    /// metals, or one given by forms over wavelength (`eta` and `k`).
    Measured(Arc<Metal>),
    /// η + ik per channel relative to vacuum (`eta`, `k`); at one wavelength, each read as
    /// a smooth spectrum of its RGB ([`crate::spectrum::colour::reflectance`]).
    Rgb {
        /// Real part.
        eta: Rgb,
        /// Extinction coefficient.
        k: Rgb,
    },
}

impl Material {
    /// The lobes of the BSDF this material makes at any hit (None for a detector or an
    /// emitter, which scatter nothing): what the photon plan reads before any ray is traced.
    pub fn lobes(&self) -> Option<Lobes> {
        let rough = |alpha: f64| Ggx::rough([alpha, alpha]).is_some();
        Some(match self {
            Material::Diffuse { .. } => Lobes::DIFFUSE_REFLECTION,
            Material::Conductor { roughness, .. } if rough(*roughness) => Lobes::GLOSSY_REFLECTION,
            Material::Conductor { .. } => Lobes::SPECULAR_REFLECTION,
            Material::Dielectric { roughness } if rough(*roughness) => {
                Lobes::GLOSSY_REFLECTION.with(Lobes::GLOSSY_TRANSMISSION)
            }
            Material::Dielectric { .. } => {
                Lobes::SPECULAR_REFLECTION.with(Lobes::SPECULAR_TRANSMISSION)
            }
            Material::Plastic { .. } => Lobes::DIFFUSE_REFLECTION.with(Lobes::GLOSSY_REFLECTION),
            Material::Detector { .. } | Material::Emissive { .. } => return None,
        })
    }
}
