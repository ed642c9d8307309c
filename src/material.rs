//! Surface materials: what a scene says a surface is. [`crate::bsdf`] is how it scatters;
//! [`Material::bsdf`] makes the one from the other at a point of the surface.

use crate::bsdf::{Bsdf, Coat, Lobes, Metal, Microsurface, Reflectance};
use crate::color::Rgb;
pub use crate::fluorescent_layer::FluorescentLayer;
use crate::polarization::Sheet;
use crate::spectrum::colour;
use crate::texture::Texture;
use glam::DVec2;
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
        /// A fluorescent layer on it (None: none).
        fluorescence: Option<Arc<FluorescentLayer>>,
    },
    /// A conductor (`conductor`, and `mirror`: a smooth one of constant reflectance), two-sided:
    /// a mirror where `microsurface` is None, else microfacet reflection.
    Conductor {
        /// Its complex index or reflectance.
        index: ConductorIndex,
        /// The microsurface; None: smooth (a roughness below [`crate::bsdf::SMOOTH_ALPHA`],
        /// decided once by [`Microsurface::rough`] where the scene is read).
        microsurface: Option<Microsurface>,
    },
    /// A dielectric boundary, with the index on each side evaluated at the hit point: Fresnel
    /// reflection and Snell refraction where `microsurface` is None, else the rough interface. The
    /// inside is the shape's interior medium.
    Dielectric {
        /// The microsurface; None: smooth (as a conductor's).
        microsurface: Option<Microsurface>,
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
    /// A thin dielectric pane (`thin_dielectric`, a window), two-sided: light is reflected or
    /// crosses it without turning, into the medium it came from.
    ThinDielectric {
        /// The pane's index (relative to vacuum; to the medium around it where it stands).
        ior: f64,
    },
    /// A thin polarizer or retarder (`polarizer`, `retarder`), two-sided: light crosses it
    /// without turning. Its scene is rendered with polarized transport.
    Sheet(Sheet),
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
    /// The lobes of the BSDF this material makes at any hit: what the photon plan reads
    /// before any ray is traced.
    pub fn lobes(&self) -> Lobes {
        match self {
            Material::Diffuse { .. } => Lobes::DIFFUSE_REFLECTION,
            Material::Conductor {
                microsurface: Some(_),
                ..
            } => Lobes::GLOSSY_REFLECTION,
            Material::Conductor {
                microsurface: None, ..
            } => Lobes::SPECULAR_REFLECTION,
            Material::Dielectric {
                microsurface: Some(_),
            } => Lobes::GLOSSY_REFLECTION.with(Lobes::GLOSSY_TRANSMISSION),
            Material::Dielectric { microsurface: None } => {
                Lobes::SPECULAR_REFLECTION.with(Lobes::SPECULAR_TRANSMISSION)
            }
            Material::ThinDielectric { .. } => {
                Lobes::SPECULAR_REFLECTION.with(Lobes::SPECULAR_TRANSMISSION)
            }
            Material::Plastic { .. } => Lobes::DIFFUSE_REFLECTION.with(Lobes::GLOSSY_REFLECTION),
            Material::Sheet(_) => Lobes::SPECULAR_TRANSMISSION,
        }
    }

    /// Its fluorescent layer (None: none).
    pub fn fluorescence(&self) -> Option<&FluorescentLayer> {
        match self {
            Material::Diffuse { fluorescence, .. } => fluorescence.as_deref(),
            Material::Conductor { .. }
            | Material::Dielectric { .. }
            | Material::Plastic { .. }
            | Material::ThinDielectric { .. }
            | Material::Sheet(_) => None,
        }
    }

    /// Whether light crosses it without changing medium (a thin sheet), rather than into the
    /// shape's other side.
    pub fn is_thin(&self) -> bool {
        match self {
            Material::Sheet(_) | Material::ThinDielectric { .. } => true,
            Material::Diffuse { .. }
            | Material::Conductor { .. }
            | Material::Dielectric { .. }
            | Material::Plastic { .. } => false,
        }
    }

    /// The BSDF this material makes at the surface point `at`, whose lobes are
    /// [`Material::lobes`]; None where an index it needs is undefined (a singular medium).
    pub fn bsdf(&self, at: &impl SurfacePoint) -> Option<Bsdf<'_>> {
        let textured = |albedo: Rgb, texture: &Option<Arc<Texture>>| {
            let albedo = texture.as_ref().map_or(albedo, |t| albedo * t.at(at.uv()));
            reflectance(albedo, at.wavelength())
        };
        Some(match self {
            Material::Diffuse {
                albedo, texture, ..
            } => Bsdf::Lambert {
                albedo: textured(*albedo, texture),
            },
            Material::Conductor {
                index,
                microsurface,
            } => Bsdf::Conductor {
                fresnel: index.reflectance(at.wavelength(), at.index_near()?),
                microsurface: *microsurface,
            },
            Material::Dielectric { microsurface } => Bsdf::Dielectric {
                n1: at.index_near()?,
                n2: at.index_far()?,
                microsurface: *microsurface,
            },
            Material::Plastic {
                albedo,
                texture,
                coat,
            } => Bsdf::Plastic {
                albedo: textured(*albedo, texture),
                coat,
            },
            Material::ThinDielectric { ior } => Bsdf::ThinDielectric {
                eta: ior / at.index_near()?,
            },
            Material::Sheet(sheet) => Bsdf::Sheet { sheet },
        })
    }
}

/// What a material asks of the point where a path meets it, to make its BSDF there
/// ([`Material::bsdf`]); each answer is computed only when asked.
pub trait SurfacePoint {
    /// The surface coordinates (u, v) there.
    fn uv(&self) -> DVec2;
    /// The wavelength the path carries (vacuum nm); None where it carries RGB.
    fn wavelength(&self) -> Option<f64>;
    /// The index on the side the path arrives from; None where it is undefined.
    fn index_near(&self) -> Option<f64>;
    /// The index on the far side of a transmitting surface; None where it is undefined.
    fn index_far(&self) -> Option<f64>;
}

/// A reflectance as a path carries it: the RGB itself, or its smooth spectrum's value at the
/// path's wavelength ([`colour::reflectance`]).
pub fn reflectance(rgb: Rgb, wavelength: Option<f64>) -> Rgb {
    match wavelength {
        None => rgb,
        Some(nm) => Rgb::splat(colour::reflectance(rgb, nm)),
    }
}

impl ConductorIndex {
    /// The Fresnel reflectance at wavelength `wavelength` (None: the path carries RGB),
    /// relative to an outside of index `n_out`: a measured metal's exact term at one
    /// wavelength, or its colour (the reflected D65 over the observer,
    /// [`crate::bsdf::Metal::colour`]) when the path carries every wavelength.
    pub fn reflectance(&self, wavelength: Option<f64>, n_out: f64) -> Reflectance<'_> {
        match (self, wavelength) {
            (&ConductorIndex::Constant(c), nm) => Reflectance::Constant(reflectance(c, nm)),
            (ConductorIndex::Measured(metal), Some(nm)) => {
                let (eta, k) = metal.index(nm);
                Reflectance::Complex {
                    eta: Rgb::splat(eta / n_out),
                    k: Rgb::splat(k / n_out),
                }
            }
            (ConductorIndex::Measured(metal), None) => Reflectance::Measured { metal, n_out },
            (&ConductorIndex::Rgb { eta, k }, Some(nm)) => Reflectance::Complex {
                eta: Rgb::splat(colour::reflectance(eta, nm) / n_out),
                k: Rgb::splat(colour::reflectance(k, nm) / n_out),
            },
            (&ConductorIndex::Rgb { eta, k }, None) => Reflectance::Complex {
                eta: eta / n_out,
                k: k / n_out,
            },
        }
    }
}
