//! Where a path scatters: a [`Vertex`] is a surface point (the BSDF made there, the normals
//! it is evaluated about, the direction the path arrived from and the media on both sides) or
//! a point inside a scattering medium (its phase function). The chain ([`super::chain`])
//! passes through surface vertices whose BSDF is purely specular and ends at any other
//! vertex, where the integrators estimate light and photons are stored.
//!
//! **Normals.** Specular and glossy lobes work about the shading normal (turned to the
//! arrival side), unless a sample about it would leave on the wrong side of the geometric
//! surface (a reflection into it, a refraction back out of it) or the path arrives from
//! behind it: then about the geometric normal, so a smooth mesh neither leaks light nor
//! blackens its facets' edges. Diffuse lobes work about the geometric normal.

use super::chain::Ray;
use super::offset;
use crate::bsdf::{Bsdf, BsdfSample, Lobes};
use crate::color::Rgb;
use crate::ids::{MediumId, PrimId};
use crate::polarization::{Element, Polarization, Sense};
use crate::sampling::Given;
use crate::volume::Phase;
use glam::DVec3;

/// A scattering vertex: where a path's chain ends and light is estimated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Vertex<'s> {
    /// On a surface whose BSDF is not purely specular.
    Surface(SurfaceVertex<'s>),
    /// Inside a scattering medium, where a free flight ended.
    Medium(MediumVertex),
}

/// A point inside a scattering medium where a path scatters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MediumVertex {
    /// Where.
    pub position: DVec3,
    /// Unit direction back along the arrival (ωo).
    pub wo: DVec3,
    /// The medium.
    pub medium: Option<MediumId>,
    /// How it redirects light.
    pub phase: Phase,
}

impl MediumVertex {
    /// The phase function's density for light arriving from direction `wi` (travelling along
    /// −`wi`) and leaving along ωo, per steradian; also the density a path arriving along −ωo
    /// draws `wi` with ([`Phase::sample`] about −ωo: the cosine is the same).
    fn density(&self, wi: DVec3) -> f64 {
        self.phase.between(-wi, self.wo)
    }

    /// The scattering into unit `wi` as a sample drawn from the phase function (weight 1).
    pub fn toward(&self, wi: DVec3) -> Scattered {
        Scattered {
            sample: BsdfSample {
                wi,
                weight: Rgb::ONE,
                pdf: self.density(wi),
                lobe: Lobes::PHASE,
            },
            ray: Ray {
                origin: self.position,
                direction: wi,
                medium: self.medium,
            },
            radiance_scale: 1.0,
        }
    }
}

impl<'s> Vertex<'s> {
    /// Where it is.
    pub fn position(&self) -> DVec3 {
        match self {
            Vertex::Surface(v) => v.position,
            Vertex::Medium(v) => v.position,
        }
    }

    /// Unit direction back along the arrival (ωo).
    pub fn wo(&self) -> DVec3 {
        match self {
            Vertex::Surface(v) => v.wo,
            Vertex::Medium(v) => v.wo,
        }
    }

    /// The medium a path leaving it toward ωo travels in (a surface's arrival side).
    pub fn medium(&self) -> Option<MediumId> {
        match self {
            Vertex::Surface(v) => v.medium,
            Vertex::Medium(v) => v.medium,
        }
    }

    /// What the vertex does to the polarization of light arriving from unit `wi` as it
    /// leaves toward ωo (a camera path's sense): a rough conductor's or dielectric's
    /// microfacet Fresnel matrix, a plastic's ([`Bsdf::mueller`]), Rayleigh's
    /// ([`Phase::mueller`]); None where it depolarizes (every other lobe and phase function).
    pub fn mueller(&self, wi: DVec3) -> Option<Element> {
        match self {
            Vertex::Surface(v) => v.bsdf.mueller(v.wo, wi, v.normal, Sense::AgainstLight),
            Vertex::Medium(v) => v.phase.mueller(-wi, v.wo),
        }
    }

    /// A camera path's measurement `measure` (carried against the light) past the vertex, for
    /// the path going on toward unit `wi`: the vertex's Mueller matrix met
    /// ([`Vertex::mueller`]), or the light depolarized.
    pub fn measure_toward(&self, measure: &mut Polarization, wi: DVec3) {
        match self.mueller(wi) {
            Some(element) => {
                measure.meet(&element, -self.wo());
            }
            None => measure.depolarize(),
        }
    }

    /// The surface point, if it is one.
    pub fn surface(&self) -> Option<&SurfaceVertex<'s>> {
        match self {
            Vertex::Surface(v) => Some(v),
            Vertex::Medium(_) => None,
        }
    }

    /// The albedo a denoiser is given: the BSDF's; none (zero) in a medium.
    pub fn albedo(&self) -> Rgb {
        match self {
            Vertex::Surface(v) => v.bsdf.albedo(),
            Vertex::Medium(_) => Rgb::ZERO,
        }
    }

    /// The normal a denoiser is given (as RGB): the geometric normal on the arrival side;
    /// none (zero) in a medium.
    pub fn normal(&self) -> Rgb {
        match self {
            Vertex::Surface(v) => Rgb(v.normal),
            Vertex::Medium(_) => Rgb::ZERO,
        }
    }

    /// Its lobes: the BSDF's, or [`Lobes::PHASE`] in a medium.
    pub fn lobes(&self) -> Lobes {
        match self {
            Vertex::Surface(v) => v.lobes(),
            Vertex::Medium(_) => Lobes::PHASE,
        }
    }

    /// The scattering function for light arriving along −`wi` leaving toward ωo: the BSDF's f
    /// (1/sr, times the cosine at `wi` where a light sample needs it: [`Vertex::cos`]) or the
    /// phase function p (1/sr).
    pub fn eval(&self, wi: DVec3) -> Rgb {
        match self {
            Vertex::Surface(v) => v.eval(wi),
            Vertex::Medium(v) => Rgb::splat(v.density(wi)),
        }
    }

    /// The foreshortening of light arriving from direction `wi`: its cosine at the normal the
    /// BSDF is evaluated about (`SurfaceVertex::frame`: a smooth mesh's shading normal for
    /// glossy and coated lobes, the geometric normal for a Lambertian one), the cosine a BSDF
    /// sample's weight f·|cos|/pdf holds — so that a light sample and a BSDF sample estimate
    /// the same integral; ≤ 0 where light from there cannot be sampled (the far side, which
    /// only a transmitted sample reaches); 1 in a medium.
    pub fn cos(&self, wi: DVec3) -> f64 {
        match self {
            Vertex::Surface(v) => wi.dot(v.frame()),
            Vertex::Medium(_) => 1.0,
        }
    }

    /// Where straight connections from it start: off a surface on its arrival side, or the
    /// point itself in a medium.
    pub fn origin(&self) -> DVec3 {
        match self {
            Vertex::Surface(v) => offset(v.position, v.normal),
            Vertex::Medium(v) => v.position,
        }
    }

    /// The pdf with which [`Vertex::scatter_with`] draws `wi` (1/sr).
    pub fn pdf(&self, wi: DVec3) -> f64 {
        match self {
            Vertex::Surface(v) => v.pdf(wi),
            Vertex::Medium(v) => v.density(wi),
        }
    }

    /// A direction drawn from `rng` and the ray leaving along it (see
    /// [`SurfaceVertex::scatter_given`]; a medium draws two numbers, and its sample's weight
    /// p/pdf is 1).
    pub fn scatter_with(&self, rng: &mut impl rand::Rng) -> Option<Scattered> {
        self.scatter_given(BsdfNumbers::default(), rng)
    }

    /// [`Vertex::scatter_with`] taking `numbers` where they are given.
    pub fn scatter_given(
        &self,
        numbers: BsdfNumbers,
        rng: &mut impl rand::Rng,
    ) -> Option<Scattered> {
        match self {
            Vertex::Surface(v) => v.scatter_given(numbers, rng),
            Vertex::Medium(v) => {
                let [a, b] = numbers.direction.or_draw(rng);
                Some(v.toward(v.phase.sample(-v.wo, (a, b))))
            }
        }
    }
}

/// A surface point a path reached, with the BSDF it met there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceVertex<'s> {
    /// Primitive index.
    pub prim: PrimId,
    /// Where.
    pub position: DVec3,
    /// Unit geometric normal on the side the path arrived on.
    pub normal: DVec3,
    /// Unit shading normal turned to the arrival side.
    pub shading: DVec3,
    /// Unit direction back along the arrival (ωo).
    pub wo: DVec3,
    /// How the surface scatters here.
    pub bsdf: Bsdf<'s>,
    /// The medium on the arrival side (None: vacuum).
    pub medium: Option<MediumId>,
    /// The medium on the other side, where a transmitted path goes.
    pub beyond: Option<MediumId>,
}

/// The numbers a vertex's BSDF or phase sample takes in place of its stream's, where given.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BsdfNumbers {
    /// The direction's two.
    pub direction: Given<2>,
    /// The choice among lobes (read only by a BSDF that makes one).
    pub choice: Given<1>,
}

/// A direction sampled at a vertex and the ray leaving along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattered {
    /// The BSDF's sample (direction, weight f·|cos|/pdf, pdf, lobe).
    pub sample: BsdfSample,
    /// The ray leaving: offset off the surface to the side it leaves on, in that side's medium.
    pub ray: Ray,
    /// What radiance arriving along the ray becomes toward ωo besides the sample's weight:
    /// (n_ωo/n_ωi)² across a rough interface, 1 otherwise ([`SurfaceVertex::radiance_scale`]).
    pub radiance_scale: f64,
}

impl SurfaceVertex<'_> {
    /// Its BSDF's lobes.
    pub fn lobes(&self) -> Lobes {
        self.bsdf.lobes()
    }

    /// The normal its BSDF is evaluated about for a direction leaving on the side `wi` lies
    /// on (see the module's notes).
    fn frame(&self) -> DVec3 {
        match self.bsdf {
            Bsdf::Lambert { .. } => self.normal,
            Bsdf::Conductor { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::Plastic { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Sheet { .. } => match self.wo.dot(self.shading) > 0.0 {
                true => self.shading,
                false => self.normal,
            },
        }
    }

    /// Whether `wi` leaves on the side of the geometric surface its lobe says: above it for
    /// a reflection, below for a transmission.
    fn lands_right(&self, wi: DVec3, transmitted: bool) -> bool {
        let lands = wi.dot(self.normal);
        (transmitted && lands < 0.0) || (!transmitted && lands > 0.0)
    }

    /// f(ωo, `wi`) of the non-delta lobes; 0 where `wi` would leave on the wrong side.
    pub fn eval(&self, wi: DVec3) -> Rgb {
        let frame = self.frame();
        if !self.lands_right(wi, wi.dot(frame) < 0.0) {
            return Rgb::ZERO;
        }
        self.bsdf.eval(self.wo, wi, frame)
    }

    /// The share of light arriving along ωo that reaches the BSDF's diffuse base
    /// ([`Bsdf::diffuse_entry`]): what a photon arriving here brings to the diffuse lobe.
    pub fn diffuse_entry(&self) -> f64 {
        self.bsdf.diffuse_entry(self.wo, self.frame())
    }

    /// The diffuse lobe's factor toward ωo ([`Bsdf::diffuse_exit`], 1/sr): times the
    /// irradiance that reaches the base, the radiance the diffuse lobe sends toward ωo.
    pub fn diffuse_exit(&self) -> Rgb {
        self.bsdf.diffuse_exit(self.wo, self.frame())
    }

    /// The change of radiance from light arriving along `wi` to light leaving toward ωo that
    /// the BSDF leaves to the transport: basic radiance L/n² is what f carries, so radiance
    /// from the other side of a rough interface (index n2, ωo's side n1) gains (n1/n2)². 1 for
    /// reflection and for every other BSDF. Power (a photon's flux) never scales: photons
    /// ignore it. (Through a smooth interface the chain's own end-to-end ratio accounts for
    /// it: [`super::chain::Chain::radiance_scale`].)
    pub fn radiance_scale(&self, wi: DVec3) -> f64 {
        match self.bsdf {
            Bsdf::Dielectric { n1, n2, .. } if wi.dot(self.normal) < 0.0 => {
                let r = n1 / n2;
                r * r
            }
            Bsdf::Lambert { .. }
            | Bsdf::Conductor { .. }
            | Bsdf::Dielectric { .. }
            | Bsdf::ThinDielectric { .. }
            | Bsdf::Plastic { .. }
            | Bsdf::Sheet { .. } => 1.0,
        }
    }

    /// The pdf with which [`SurfaceVertex::scatter`] draws `wi` (per unit solid angle).
    pub fn pdf(&self, wi: DVec3) -> f64 {
        self.bsdf.pdf(self.wo, wi, self.frame())
    }

    /// A direction for uniform numbers `u` (see [`Bsdf::sample`]) and the ray leaving along
    /// it; None where the BSDF gives none.
    pub fn scatter(&self, u: (f64, f64, f64)) -> Option<Scattered> {
        self.leave(|n| self.bsdf.sample(self.wo, n, u))
    }

    /// The ray leaving along a direction `sample` draws about a normal: about the shading
    /// frame, or about the geometric normal where that sample would leave on the wrong side.
    fn leave(&self, sample: impl Fn(DVec3) -> Option<BsdfSample>) -> Option<Scattered> {
        let frame = self.frame();
        let s = match sample(frame) {
            Some(s) if frame == self.normal || self.lands_right(s.wi, s.transmitted()) => s,
            _ => sample(self.normal)?,
        };
        let transmitted = s.transmitted();
        Some(Scattered {
            radiance_scale: self.radiance_scale(s.wi),
            sample: s,
            ray: Ray {
                origin: offset(
                    self.position,
                    if transmitted {
                        -self.normal
                    } else {
                        self.normal
                    },
                ),
                direction: s.wi,
                medium: if transmitted {
                    self.beyond
                } else {
                    self.medium
                },
            },
        })
    }

    /// [`SurfaceVertex::scatter`] with `numbers` where they are given, else drawn from `rng`:
    /// two for the direction and a third only where the BSDF makes a discrete choice (a
    /// Lambertian surface draws two).
    pub fn scatter_given(
        &self,
        numbers: BsdfNumbers,
        rng: &mut impl rand::Rng,
    ) -> Option<Scattered> {
        let [a, b] = numbers.direction.or_draw(rng);
        let choice = match self.bsdf.draws_choice() {
            true => numbers.choice.or_draw(rng)[0],
            false => 0.0,
        };
        self.scatter((a, b, choice))
    }

    /// A direction from the lobes beyond the diffuse one, drawn from `rng`
    /// ([`Bsdf::sample_beyond_diffuse`]), and the ray leaving along it: None at once (drawing
    /// nothing) where the diffuse lobe is all there is.
    pub fn scatter_beyond_diffuse_with(&self, rng: &mut impl rand::Rng) -> Option<Scattered> {
        if self.lobes() == Lobes::DIFFUSE_REFLECTION {
            return None;
        }
        let u = (rng.gen(), rng.gen(), rng.gen());
        self.leave(|n| self.bsdf.sample_beyond_diffuse(self.wo, n, u))
    }
}
