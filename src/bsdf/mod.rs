//! How a surface scatters light at one point: its lobes, and `sample`, `eval` and `pdf`.
//! Directions are unit vectors pointing away from the surface (`wo` toward where the path
//! came from, `wi` where it goes next); `n` is the unit shading normal on the side `wo` lies
//! on. Work is done in the local frame of `n` ([`Frame`]). Radiance per RGB channel; f in
//! 1/sr; pdfs per unit solid angle.
//!
//! **Basic radiance.** f is the transfer of basic radiance L/n² (and of power): a refraction's
//! change of radiance, (n_far/n_near)², is accounted once for a whole path by the transport
//! ([`crate::transport::chain`]), so no BSDF carries it. For a rough dielectric this is Walter
//! et al.'s (2007) transmission term with the index of `wi`'s side squared in the numerator:
//! sampling it then weighs (1 − F)·G₂/G₁ / (1 − F) = G₂/G₁, as the smooth interface weighs 1,
//! and f(wo, wi)/n_wi² = f(wi, wo)/n_wo² (the generalised reciprocity).
//!
//! **Lobes.** Each BSDF names its lobes ([`Lobes`]): diffuse, glossy or specular (a delta),
//! each in reflection or transmission. The one rule that reads them is
//! [`Lobes::is_specular`]: a path continues through a purely specular surface within one
//! chain; at any other it is a scattering vertex (photons are stored there, direct light is
//! estimated there).

mod fresnel;
mod metals;
mod microfacet;
mod plastic;
pub mod walk;

pub use fresnel::{
    conductor, conductor_rgb, dielectric, dielectric_transmittance, reflect, refract,
    thin_dielectric,
};
pub use metals::{named as metal, Metal, METALS, WAVELENGTHS};
pub use microfacet::{Distribution, Microsurface, SMOOTH_ALPHA};
pub use plastic::Coat;

use crate::color::Rgb;
use crate::polarization::{mueller, Element, Sense, Sheet};
use crate::sampling::{cosine_hemisphere, Frame};
use glam::{DMat4, DVec3};
use std::f64::consts::FRAC_1_PI;

/// The lobes of a BSDF, or the one lobe a sample came from: a set of flags.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lobes(u8);

impl Lobes {
    /// Lambertian-like reflection.
    pub const DIFFUSE_REFLECTION: Lobes = Lobes(1);
    /// A microfacet reflection.
    pub const GLOSSY_REFLECTION: Lobes = Lobes(2);
    /// A microfacet transmission.
    pub const GLOSSY_TRANSMISSION: Lobes = Lobes(4);
    /// A mirror reflection (a delta).
    pub const SPECULAR_REFLECTION: Lobes = Lobes(8);
    /// A refraction through a smooth interface (a delta).
    pub const SPECULAR_TRANSMISSION: Lobes = Lobes(16);
    /// Not a surface's: a scattering medium's phase function at a point inside it. Neither
    /// specular nor diffuse — a path passes it by sampling, as a glossy-only vertex.
    pub const PHASE: Lobes = Lobes(32);
    const SPECULAR: u8 = 8 | 16;
    const DIFFUSE: u8 = 1;
    const TRANSMISSION: u8 = 4 | 16;

    /// Both sets of lobes.
    pub const fn with(self, other: Lobes) -> Lobes {
        Lobes(self.0 | other.0)
    }

    /// Whether every lobe is a delta: a path goes on through such a surface within its chain,
    /// and nothing is stored or estimated there. The one place a vertex's kind is decided.
    pub fn is_specular(self) -> bool {
        self.0 & !Self::SPECULAR == 0
    }

    /// Whether some lobe is diffuse: there the photon mapper's camera path makes its visible
    /// point (glossy-only vertices are passed by sampling the BSDF).
    pub fn has_diffuse(self) -> bool {
        self.0 & Self::DIFFUSE != 0
    }

    /// Whether some lobe crosses the surface.
    pub fn transmits(self) -> bool {
        self.0 & Self::TRANSMISSION != 0
    }
}

/// The Fresnel reflectance of a conductor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reflectance<'a> {
    /// The same reflectance at every angle (a mirror's; 1 for the perfect conductor of
    /// furnace tests).
    Constant(Rgb),
    /// The exact conductor Fresnel term of complex index η + ik, relative to the medium
    /// outside, per channel.
    Complex {
        /// Real part per channel.
        eta: Rgb,
        /// Extinction coefficient per channel.
        k: Rgb,
    },
    /// A measured metal's colour ([`Metal::colour`]) seen from a medium of index `n_out`.
    Measured {
        /// The metal.
        metal: &'a Metal,
        /// The index outside.
        n_out: f64,
    },
}

impl Reflectance<'_> {
    /// The reflectance at cos θ = `cos`.
    pub fn at(&self, cos: f64) -> Rgb {
        match *self {
            Reflectance::Constant(r) => r,
            Reflectance::Complex { eta, k } => conductor_rgb(cos, eta, k),
            Reflectance::Measured { metal, n_out } => metal.colour(cos, n_out),
        }
    }

    /// The reflection's Mueller matrix per channel at cos θ = `cos` (module conventions of
    /// [`crate::polarization::mueller`]): a constant reflectance's is a perfect conductor's
    /// (its state kept) scaled by it; a measured metal's is summed band by band as its colour.
    pub fn mueller(&self, cos: f64) -> [DMat4; 3] {
        match *self {
            Reflectance::Constant(r) => r.0.to_array().map(|c| mueller::perfect_mirror() * c),
            Reflectance::Complex { eta, k } => {
                std::array::from_fn(|c| mueller::conductor_reflection(cos, eta.0[c], k.0[c]))
            }
            Reflectance::Measured { metal, n_out } => metal.mueller(cos, n_out),
        }
    }
}

/// A scattering function at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf<'a> {
    /// Lambertian, f = albedo/π on the side of `n`.
    Lambert {
        /// Reflectance per channel.
        albedo: Rgb,
    },
    /// A conductor: a mirror reflection where `microsurface` is None, else microfacet reflection
    /// with Smith's height-correlated G₂.
    Conductor {
        /// Its Fresnel reflectance.
        fresnel: Reflectance<'a>,
        /// The microsurface (None: smooth).
        microsurface: Option<Microsurface>,
    },
    /// An interface from index `n1` (the side of `wo`) to `n2`: Fresnel reflection and Snell
    /// refraction where `microsurface` is None, else Walter et al.'s (2007) rough reflection and
    /// transmission.
    Dielectric {
        /// Index on the side of `wo`.
        n1: f64,
        /// Index on the other side.
        n2: f64,
        /// The microsurface (None: smooth).
        microsurface: Option<Microsurface>,
    },
    /// A thin dielectric pane (a window) of index `eta` relative to the medium around it:
    /// light is reflected specularly with its internal reflections summed
    /// ([`thin_dielectric`]) or crosses it without turning, into the medium it came from.
    ThinDielectric {
        /// The pane's index relative to its surroundings.
        eta: f64,
    },
    /// A diffuse base under a rough dielectric coat ([`Coat`]).
    Plastic {
        /// The base's reflectance per channel.
        albedo: Rgb,
        /// The coat.
        coat: &'a Coat,
    },
    /// A thin polarizing or retarding sheet ([`Sheet`]): light crosses it without turning,
    /// keeping [`Sheet::transmittance`] of its power when unpolarized.
    Sheet {
        /// The sheet.
        sheet: &'a Sheet,
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
    /// The lobe it came from.
    pub lobe: Lobes,
}

impl BsdfSample {
    /// Whether `wi` crosses the surface.
    pub fn transmitted(&self) -> bool {
        self.lobe.transmits()
    }
}

/// The local frame of `n` and unit `v` in it. The normal is normalised first: a hit's normal
/// is unit only to the accuracy of the hit point (a sphere's (p − c)/R is off by the point's
/// error over R), and a frame that is not orthonormal would stretch every direction it turns —
/// a path reflected many times inside a rough glass ball drifted 10⁻⁸ off unit length and
/// its hit points off the surface by more than a ray's offset. (Sampled directions are
/// normalised on the way out.)
fn local(n: DVec3, v: DVec3) -> (Frame, DVec3) {
    let f = Frame::new(n.normalize());
    let l = f.to_local(v);
    (f, l)
}

/// The two directions of an evaluation about the unit normal: their cosines, and their
/// local coordinates ([`local`]'s frame) made only for a lobe that reads more than the
/// cosines (a Lambertian surface does not).
struct Pair {
    n: DVec3,
    wo: DVec3,
    wi: DVec3,
    /// ωo · n, ωi · n: the local coordinates' z.
    cos_o: f64,
    cos_i: f64,
}

impl Pair {
    fn of(n: DVec3, wo: DVec3, wi: DVec3) -> Self {
        let n = n.normalize();
        Self {
            n,
            wo,
            wi,
            cos_o: wo.dot(n),
            cos_i: wi.dot(n),
        }
    }

    /// Both directions on the normal's side.
    fn above(&self) -> bool {
        self.cos_o > 0.0 && self.cos_i > 0.0
    }

    /// ωo and ωi in the local frame (z along n).
    fn local(&self) -> (DVec3, DVec3) {
        let frame = Frame::new(self.n);
        (frame.to_local(self.wo), frame.to_local(self.wi))
    }
}

/// A sample drawn by `sample` in the local frame of `n` from ωo = `wo` there (None where
/// `wo` is not above the surface), its direction turned to world coordinates; None when its
/// weight or pdf is not finite and positive.
fn in_local(
    n: DVec3,
    wo: DVec3,
    sample: impl FnOnce(DVec3) -> Option<BsdfSample>,
) -> Option<BsdfSample> {
    let (frame, o) = local(n, wo);
    if o.z <= 0.0 {
        return None;
    }
    let s = sample(o)?;
    (s.weight.0.is_finite() && s.pdf > 0.0).then(|| BsdfSample {
        wi: frame.to_world(s.wi).normalize(),
        ..s
    })
}

impl Bsdf<'_> {
    /// Its lobes.
    pub fn lobes(&self) -> Lobes {
        match self {
            Bsdf::Lambert { .. } => Lobes::DIFFUSE_REFLECTION,
            Bsdf::Conductor {
                microsurface: None, ..
            } => Lobes::SPECULAR_REFLECTION,
            Bsdf::Conductor { .. } => Lobes::GLOSSY_REFLECTION,
            Bsdf::Dielectric {
                microsurface: None, ..
            } => Lobes::SPECULAR_REFLECTION.with(Lobes::SPECULAR_TRANSMISSION),
            Bsdf::Dielectric { .. } => Lobes::GLOSSY_REFLECTION.with(Lobes::GLOSSY_TRANSMISSION),
            Bsdf::ThinDielectric { .. } => {
                Lobes::SPECULAR_REFLECTION.with(Lobes::SPECULAR_TRANSMISSION)
            }
            Bsdf::Plastic { .. } => Lobes::DIFFUSE_REFLECTION.with(Lobes::GLOSSY_REFLECTION),
            Bsdf::Sheet { .. } => Lobes::SPECULAR_TRANSMISSION,
        }
    }

    /// Whether a sample reads its third number, u.2 (a discrete choice: Fresnel's between
    /// reflection and refraction, a plastic's between its lobes, the seed of a rough
    /// interface's walk). A Lambertian surface and a conductor read none; the two direction
    /// numbers are read by every BSDF but a smooth one.
    pub fn draws_choice(&self) -> bool {
        match self {
            Bsdf::Lambert { .. } | Bsdf::Conductor { .. } | Bsdf::Sheet { .. } => false,
            Bsdf::Dielectric { .. } | Bsdf::ThinDielectric { .. } | Bsdf::Plastic { .. } => true,
        }
    }

    /// Whether light crosses it unchanged: a smooth interface between equal indices reflects
    /// nothing and turns nothing (Fresnel's R = 0, Snell's law the identity) — a medium's
    /// boundary that is no optical surface (Mitsuba's `null` BSDF).
    pub fn is_index_matched(&self) -> bool {
        matches!(self, Bsdf::Dielectric { n1, n2, microsurface: None } if n1 == n2)
    }

    /// Samples a direction for uniform numbers `u` (u.0, u.1 for the lobe's direction, u.2
    /// for a discrete choice such as Fresnel's: [`Bsdf::draws_choice`]; a specular surface
    /// uses only u.2). None when the sample carries nothing (it would leave on the wrong side
    /// of the surface).
    pub fn sample(&self, wo: DVec3, n: DVec3, u: (f64, f64, f64)) -> Option<BsdfSample> {
        // Smooth surfaces and the Lambertian lobe in world coordinates (as the transport has
        // always computed them, to the bit); rough lobes in the local frame of `n`.
        match *self {
            Bsdf::Lambert { albedo } => {
                let wi = Frame::new(n).to_world(cosine_hemisphere((u.0, u.1)));
                Some(BsdfSample {
                    wi,
                    weight: albedo,
                    pdf: wi.dot(n).max(0.0) * FRAC_1_PI,
                    lobe: Lobes::DIFFUSE_REFLECTION,
                })
            }
            Bsdf::Conductor {
                fresnel,
                microsurface: None,
            } => Some(BsdfSample {
                wi: reflect(-wo, n),
                weight: fresnel.at(wo.dot(n)),
                pdf: f64::INFINITY,
                lobe: Lobes::SPECULAR_REFLECTION,
            }),
            Bsdf::Dielectric {
                n1,
                n2,
                microsurface: None,
            } => {
                if wo.dot(n) < 0.0 {
                    return None;
                }
                let (r, cos_t) = dielectric(wo.dot(n), n1, n2);
                let (wi, lobe) = if u.2 < r {
                    (reflect(-wo, n), Lobes::SPECULAR_REFLECTION)
                } else {
                    (refract(-wo, n, n1, n2, cos_t), Lobes::SPECULAR_TRANSMISSION)
                };
                Some(BsdfSample {
                    wi,
                    weight: Rgb::ONE,
                    pdf: f64::INFINITY,
                    lobe,
                })
            }
            Bsdf::ThinDielectric { eta } => {
                let (wi, lobe) = match u.2 < thin_dielectric(wo.dot(n).abs().min(1.0), eta) {
                    true => (reflect(-wo, n), Lobes::SPECULAR_REFLECTION),
                    false => (-wo, Lobes::SPECULAR_TRANSMISSION),
                };
                Some(BsdfSample {
                    wi,
                    weight: Rgb::ONE,
                    pdf: f64::INFINITY,
                    lobe,
                })
            }
            Bsdf::Conductor {
                fresnel,
                microsurface: Some(g),
            } => in_local(n, wo, |o| {
                let m = g.sample_visible(o, (u.0, u.1));
                let i = reflect(-o, m);
                (i.z > 0.0).then(|| BsdfSample {
                    wi: i,
                    weight: fresnel.at(o.dot(m)) * (g.g2(i, o) / g.g1(o)),
                    pdf: g.visible_d(o, m) / (4.0 * o.dot(m)),
                    lobe: Lobes::GLOSSY_REFLECTION,
                })
            }),
            Bsdf::Dielectric {
                n1,
                n2,
                microsurface: Some(g),
            } => in_local(n, wo, |o| {
                let exit = walk::dielectric(&g, n1, n2, o, u)?;
                let i = exit.wi;
                let lobe = match i.z > 0.0 {
                    true => Lobes::GLOSSY_REFLECTION,
                    false => Lobes::GLOSSY_TRANSMISSION,
                };
                // Single scattering is what [`Bsdf::eval`] gives, with this density; light
                // sampled at a vertex finds nothing of the later orders (nor of the delta a
                // walk between equal indices leaves by), so they stand alone (∞).
                let single = rough_dielectric_pdf(&g, n1, n2, o, i);
                let pdf = match exit.order == 1 && single > 0.0 && single.is_finite() {
                    true => single,
                    false => f64::INFINITY,
                };
                Some(BsdfSample {
                    wi: i,
                    weight: Rgb::ONE,
                    pdf,
                    lobe,
                })
            }),
            Bsdf::Plastic { albedo, coat } => in_local(n, wo, |o| {
                let p = coat.specular_probability(o.z, albedo);
                let (i, lobe) = if u.2 < p {
                    let m = coat.microsurface.sample_visible(o, (u.0, u.1));
                    (reflect(-o, m), Lobes::GLOSSY_REFLECTION)
                } else {
                    (cosine_hemisphere((u.0, u.1)), Lobes::DIFFUSE_REFLECTION)
                };
                if i.z <= 0.0 {
                    return None;
                }
                let pdf = coat.pdf(o, i, p);
                Some(BsdfSample {
                    wi: i,
                    weight: coat.f(o, i, albedo) * (i.z / pdf),
                    pdf,
                    lobe,
                })
            }),
            Bsdf::Sheet { sheet } => Some(BsdfSample {
                wi: -wo,
                weight: Rgb::splat(sheet.transmittance()),
                pdf: f64::INFINITY,
                lobe: Lobes::SPECULAR_TRANSMISSION,
            }),
        }
    }

    /// f(wo, wi) (1/sr) of the non-delta lobes: 0 for directions only a delta reaches.
    pub fn eval(&self, wo: DVec3, wi: DVec3, n: DVec3) -> Rgb {
        let pair = Pair::of(n, wo, wi);
        let above = pair.above();
        match *self {
            Bsdf::Conductor {
                microsurface: None, ..
            }
            | Bsdf::Dielectric {
                microsurface: None, ..
            }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Sheet { .. } => Rgb::ZERO,
            Bsdf::Lambert { albedo } => match above {
                true => albedo * FRAC_1_PI,
                false => Rgb::ZERO,
            },
            Bsdf::Conductor {
                fresnel,
                microsurface: Some(g),
            } => match above {
                true => {
                    let (o, i) = pair.local();
                    let m = (i + o).normalize();
                    fresnel.at(o.dot(m)) * (g.d(m) * g.g2(i, o) / (4.0 * i.z * o.z))
                }
                false => Rgb::ZERO,
            },
            Bsdf::Dielectric {
                n1,
                n2,
                microsurface: Some(g),
            } => match pair.cos_o > 0.0 && pair.cos_i != 0.0 {
                true => {
                    let (o, i) = pair.local();
                    Rgb::splat(rough_dielectric_f(&g, n1, n2, o, i))
                }
                false => Rgb::ZERO,
            },
            Bsdf::Plastic { albedo, coat } => match above {
                true => {
                    let (o, i) = pair.local();
                    coat.f(o, i, albedo)
                }
                false => Rgb::ZERO,
            },
        }
    }

    /// The solid-angle pdf with which [`Bsdf::sample`] draws `wi` (0 for directions only a
    /// delta lobe reaches).
    pub fn pdf(&self, wo: DVec3, wi: DVec3, n: DVec3) -> f64 {
        let pair = Pair::of(n, wo, wi);
        let above = pair.above();
        match *self {
            Bsdf::Conductor {
                microsurface: None, ..
            }
            | Bsdf::Dielectric {
                microsurface: None, ..
            }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Sheet { .. } => 0.0,
            Bsdf::Lambert { .. } => match pair.cos_o > 0.0 {
                true => pair.cos_i.max(0.0) * FRAC_1_PI,
                false => 0.0,
            },
            Bsdf::Conductor {
                microsurface: Some(g),
                ..
            } => match above {
                true => {
                    let (o, i) = pair.local();
                    let m = (i + o).normalize();
                    g.visible_d(o, m) / (4.0 * o.dot(m))
                }
                false => 0.0,
            },
            Bsdf::Dielectric {
                n1,
                n2,
                microsurface: Some(g),
            } => match pair.cos_o > 0.0 && pair.cos_i != 0.0 {
                true => {
                    let (o, i) = pair.local();
                    rough_dielectric_pdf(&g, n1, n2, o, i)
                }
                false => 0.0,
            },
            Bsdf::Plastic { albedo, coat } => match above {
                true => {
                    let (o, i) = pair.local();
                    coat.pdf(o, i, coat.specular_probability(o.z, albedo))
                }
                false => 0.0,
            },
        }
    }

    /// The diffuse lobe's factor for light arriving from `wi`: the diffuse lobe factorises,
    /// f_d(wo, wi) = [`Bsdf::diffuse_exit`](wo)·`diffuse_entry`(wi), and this is the share of
    /// the light that reaches the diffuse base — 1 at a Lambertian surface, the coat's
    /// transmittance 1 − E(μi) under a plastic's coat; 0 without a diffuse lobe or from below
    /// the surface. A photon map sums photons' flux times it into the irradiance that
    /// reaches the base, which the exit factor turns into radiance toward any ωo.
    pub fn diffuse_entry(&self, wi: DVec3, n: DVec3) -> f64 {
        let cos = wi.dot(n);
        if cos <= 0.0 {
            return 0.0;
        }
        match *self {
            Bsdf::Lambert { .. } => 1.0,
            Bsdf::Plastic { coat, .. } => coat.entering(cos / n.length()),
            Bsdf::Conductor { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Sheet { .. } => 0.0,
        }
    }

    /// The diffuse lobe's factor toward `wo` (1/sr; see [`Bsdf::diffuse_entry`]): albedo/π at
    /// a Lambertian surface, ρ(1 − E(μo))/(πη²(1 − ρF̄ᵢ)) at a plastic ([`Coat::leaving`]); 0
    /// without a diffuse lobe or below the surface.
    pub fn diffuse_exit(&self, wo: DVec3, n: DVec3) -> Rgb {
        let cos = wo.dot(n);
        if cos <= 0.0 {
            return Rgb::ZERO;
        }
        match *self {
            Bsdf::Lambert { albedo } => albedo * FRAC_1_PI,
            Bsdf::Plastic { albedo, coat } => coat.leaving(cos / n.length(), albedo),
            Bsdf::Conductor { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Sheet { .. } => Rgb::ZERO,
        }
    }

    /// A direction from the lobes other than the diffuse one, for uniform numbers `u` (as
    /// [`Bsdf::sample`]): none at a Lambertian surface; a plastic's coat lobe played for
    /// with the probability it reflects ([`Coat::sample_lobe`]); every lobe of a BSDF without
    /// a diffuse one. Where a photon map gives the diffuse lobe's light, this estimates the
    /// rest.
    pub fn sample_beyond_diffuse(
        &self,
        wo: DVec3,
        n: DVec3,
        u: (f64, f64, f64),
    ) -> Option<BsdfSample> {
        match *self {
            Bsdf::Lambert { .. } => None,
            Bsdf::Plastic { coat, .. } => in_local(n, wo, |o| coat.sample_lobe(o, u)),
            Bsdf::Conductor { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Sheet { .. } => self.sample(wo, n, u),
        }
    }

    /// The Lambertian albedo where the BSDF is Lambertian (a photon map's precomputed
    /// irradiance stands for its radiance there), else None.
    pub fn lambert_albedo(&self) -> Option<Rgb> {
        match self {
            Bsdf::Lambert { albedo } => Some(*albedo),
            Bsdf::Conductor { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Plastic { .. }
            | Bsdf::Sheet { .. } => None,
        }
    }

    /// A colour describing the surface for the albedo layer: the diffuse albedo, a
    /// conductor's reflectance at normal incidence, white for a dielectric.
    pub fn albedo(&self) -> Rgb {
        match self {
            Bsdf::Lambert { albedo } | Bsdf::Plastic { albedo, .. } => *albedo,
            Bsdf::Conductor { fresnel, .. } => fresnel.at(1.0),
            Bsdf::Dielectric { .. } | Bsdf::ThinDielectric { .. } => Rgb::ONE,
            Bsdf::Sheet { sheet } => Rgb::splat(sheet.transmittance()),
        }
    }

    /// The Mueller matrices per channel of a specular sample's event, from the path's `wo` to
    /// its `wi` about `n` ([`crate::polarization::carried`]), in the s/p basis of its plane of
    /// incidence (any basis at normal incidence) or a sheet's axis; a rough conductor's or
    /// dielectric's, the Fresnel matrix of the microfacet that reflects or refracts `wo` into
    /// `wi` (normal h = wo + wi, or n1 wo + n2 wi for a refraction, at cos θ = wo·h, in the s/p
    /// basis of the plane of wo and wi, which holds h: the microfacet model's, whose first
    /// element is the scalar F or 1 − F its BSDF holds — for the light a rough dielectric's walk
    /// scatters more than once, the matrix of one scattering toward the same direction); None
    /// a plastic's, its coat's reflection and its diffuse part's refractions in and out
    /// ([`Coat::element`]), whose light goes from `wi` to `wo` against the light (`sense`: a
    /// camera path) and from `wo` to `wi` with it (a photon); None for every other lobe (they
    /// scatter, and polarized transport takes their light as depolarized). Every other
    /// matrix holds either way along the path: a reflection's is the same both ways, and a
    /// transmission's differs only in its scale, which the scalar transport carries.
    pub fn mueller(&self, wo: DVec3, wi: DVec3, n: DVec3, sense: Sense) -> Option<Element> {
        let cos = wo.dot(n).abs().min(1.0);
        // The s direction, across the plane of incidence (any across the ray square on).
        let s = || {
            wo.cross(n)
                .try_normalize()
                .unwrap_or_else(|| wo.any_orthonormal_vector())
        };
        // A microfacet's: across the plane of wo and wi.
        let across = || {
            wo.cross(wi)
                .try_normalize()
                .unwrap_or_else(|| wo.any_orthonormal_vector())
        };
        let reflected = wi.dot(n) * wo.dot(n) > 0.0;
        match *self {
            Bsdf::Dielectric {
                n1,
                n2,
                microsurface: None,
            } => Some(Element::grey(
                match reflected {
                    true => mueller::dielectric_reflection(cos, n1, n2),
                    false => mueller::dielectric_transmission(cos, n1, n2),
                },
                s(),
            )),
            Bsdf::Dielectric {
                n1,
                n2,
                microsurface: Some(_),
            } => {
                let h = match reflected {
                    true => wo + wi,
                    false => n1 * wo + n2 * wi,
                };
                // Between equal indices the light goes straight through (n1 wo + n2 wi = 0):
                // any facet passes it as one square on, unchanged.
                let cos = h.try_normalize().map_or(1.0, |h| wo.dot(h).abs().min(1.0));
                Some(Element::grey(
                    match reflected {
                        true => mueller::dielectric_reflection(cos, n1, n2),
                        false => mueller::dielectric_transmission(cos, n1, n2),
                    },
                    across(),
                ))
            }
            Bsdf::Conductor {
                fresnel,
                microsurface: None,
            } => {
                let x = s();
                Some(Element {
                    mueller: fresnel.mueller(cos),
                    x,
                    x_leaving: x,
                })
            }
            Bsdf::Conductor {
                fresnel,
                microsurface: Some(_),
            } => {
                let h = (wo + wi).try_normalize()?;
                let x = across();
                Some(Element {
                    mueller: fresnel.mueller(wo.dot(h).abs().min(1.0)),
                    x,
                    x_leaving: x,
                })
            }
            Bsdf::ThinDielectric { eta } => {
                let [reflection, transmission] = mueller::thin_pane(cos, eta);
                Some(Element::grey(
                    match reflected {
                        true => reflection,
                        false => transmission,
                    },
                    s(),
                ))
            }
            Bsdf::Sheet { sheet } => Some(sheet.element(n, wo)),
            Bsdf::Plastic { albedo, coat } => {
                let (from, to) = match sense {
                    Sense::AgainstLight => (wi, wo),
                    Sense::WithLight => (wo, wi),
                };
                coat.element(albedo, n.normalize(), from, to)
            }
            Bsdf::Lambert { .. } => None,
        }
    }
}

/// The microfacet normal of the pair (o, i) across an interface from `n1` (o's side) to `n2`
/// (local, z > 0), or None where no microfacet refracts one into the other.
fn half_vector(n1: f64, n2: f64, o: DVec3, i: DVec3) -> Option<DVec3> {
    let reflected = i.z > 0.0;
    let h = if reflected { o + i } else { n1 * o + n2 * i };
    let len = h.length();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let m = if h.z < 0.0 { -h / len } else { h / len };
    // The facet must face o, and face i from its side.
    let fits = o.dot(m) > 0.0 && (i.dot(m) > 0.0) == reflected;
    fits.then_some(m)
}

/// 1 − F for a refracted pair through a facet, cos θ = `om` on the side of index `n1` and
/// |`im`| on the side of `n2`: computed from the rarer side, where Snell's cos θt is well
/// conditioned (from the denser side it loses digits near the critical angle), and without
/// the cancellation of 1 − F at grazing incidence.
fn transmittance(n1: f64, n2: f64, om: f64, im: f64) -> f64 {
    match n1 <= n2 {
        true => dielectric_transmittance(om, n1, n2),
        false => dielectric_transmittance(im.abs(), n2, n1),
    }
}

/// Walter et al.'s (2007) rough dielectric f for basic radiance (see the module's notes): the
/// single scattering of [`walk::dielectric`], with the Smith G₂ of correlated heights, a
/// reflection's or a transmission's ([`Microsurface::g2_transmission`]).
fn rough_dielectric_f(g: &Microsurface, n1: f64, n2: f64, o: DVec3, i: DVec3) -> f64 {
    let Some(m) = half_vector(n1, n2, o, i) else {
        return 0.0;
    };
    let (om, im) = (o.dot(m), i.dot(m));
    if i.z > 0.0 {
        let (r, _) = dielectric(om, n1, n2);
        r * g.d(m) * g.g2(i, o) / (4.0 * i.z * o.z)
    } else {
        let t = transmittance(n1, n2, om, im);
        let denom = n1 * om + n2 * im;
        let dg = g.d(m) * g.g2_transmission(i, o);
        t * dg * (im.abs() * om * n2 * n2) / (i.z.abs() * o.z * denom * denom)
    }
}

/// The density with which [`Bsdf::sample`]'s walk leaves along `i` after a single scattering:
/// f·|cos θi| (a walk's weight is 1).
fn rough_dielectric_pdf(g: &Microsurface, n1: f64, n2: f64, o: DVec3, i: DVec3) -> f64 {
    rough_dielectric_f(g, n1, n2, o, i) * i.z.abs()
}
