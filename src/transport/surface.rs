//! The vertex a path makes where it meets a surface: the BSDF the surface's material makes at
//! the hit (at the tracer's wavelength, with the index on either side evaluated there).

use super::{facing, SurfaceHit, SurfaceVertex, Tracer};
use crate::ids::{MediumId, PrimId};
use crate::material::SurfacePoint;
use crate::polarization::crystal::{Interface, Optics, Wave};
use crate::scene::Surface;
use crate::spectrum::LAMBDA_D;
use glam::{DVec2, DVec3};

impl<'a> Tracer<'a> {
    /// The scattering vertex where a path arriving along unit `incoming` in `medium` meets
    /// `surface` at `position` (with its normals and surface coordinates `uv` there): the
    /// BSDF its material makes at the tracer's wavelength, with n evaluated at the hit point
    /// on each side of a dielectric. None for a detector or an emitter (they scatter
    /// nothing), or where a side's index cannot be evaluated (a singular medium).
    pub fn vertex(
        &self,
        hit: SurfaceHit,
        surface: Surface,
        medium: Option<MediumId>,
    ) -> Option<SurfaceVertex<'a>> {
        let scene = self.scene;
        let SurfaceHit {
            prim,
            position,
            normals,
            uv,
            incoming,
        } = hit;
        let side = facing(normals.geometric, incoming);
        let material = scene.material(surface)?;
        // Light transmitted into the shape's other side: the interior from outside, the
        // exterior from inside; a thin sheet's leaves into the medium it came from.
        let beyond = match material.lobes().transmits() && !material.is_thin() {
            true => {
                let inside = surface.interior?;
                match side == normals.geometric {
                    true => Some(inside),
                    false => surface.exterior,
                }
            }
            false => medium,
        };
        let bsdf = material.bsdf(&HitPoint {
            tracer: self,
            prim,
            position,
            uv,
            near: medium,
            far: beyond,
        })?;
        let shading = if side == normals.geometric {
            normals.shading
        } else {
            -normals.shading
        };
        Some(SurfaceVertex {
            prim,
            position,
            normal: side,
            shading,
            wo: -incoming,
            bsdf,
            medium,
            beyond,
        })
    }
}

impl Tracer<'_> {
    /// Whether a path crosses the surface `vertex` is on as though it were not there: an
    /// index-matched smooth interface ([`crate::bsdf::Bsdf::is_index_matched`]) between
    /// media of uniform index, where a straight ray goes straight on into the medium beyond.
    /// Such a crossing is no specular event: light samples see through it (the shadow ray
    /// goes on, [`super::visibility::transmittance`]) and a BSDF sample through it is weighed
    /// against them, as though the boundary of a fog were no surface. Into or out of a
    /// gradient medium the ray bends beyond it, and it stays a specular surface.
    pub fn crosses_unchanged(&self, vertex: &SurfaceVertex) -> bool {
        let uniform = |m: Option<MediumId>| m.is_none_or(|m| self.medium(m).is_uniform());
        vertex.bsdf.is_index_matched()
            && uniform(vertex.medium)
            && uniform(vertex.beyond)
            && self.wave(vertex.medium).is_none()
            && self.wave(vertex.beyond).is_none()
    }

    /// The interface `vertex` is on, where a uniaxial crystal lies on either side of it: its
    /// face, which splits light into the crystal's two waves ([`crate::polarization::crystal`]);
    /// None between isotropic media, and where an isotropic side's index is undefined.
    pub fn crystal_interface(&self, vertex: &SurfaceVertex) -> Option<Interface> {
        if !self.has_crystals {
            return None;
        }
        let media = self.scene.media();
        let crystal = |m: Option<MediumId>| m.and_then(|m| media.crystal(m));
        if crystal(vertex.medium).is_none() && crystal(vertex.beyond).is_none() {
            return None;
        }
        let nm = self.single_wavelength().unwrap_or(LAMBDA_D);
        let optics = |m: Option<MediumId>| match crystal(m) {
            Some(c) => Some(Optics::Crystal(c.crystal.at(nm))),
            None => self.index(m, vertex.position).map(Optics::Isotropic),
        };
        Some(Interface {
            near: optics(vertex.medium)?,
            far: optics(vertex.beyond)?,
            normal: vertex.normal,
        })
    }

    /// The crystal's wave a path in `medium` travels as (None: an isotropic medium).
    pub fn wave(&self, medium: Option<MediumId>) -> Option<Wave> {
        let m = medium.filter(|_| self.has_crystals)?;
        self.scene.media().crystal(m).map(|c| c.wave)
    }
}

/// A surface point as [`Material::bsdf`] asks of it: the hit, the media on each side and the
/// tracer's wavelength.
struct HitPoint<'t, 'a> {
    tracer: &'t Tracer<'a>,
    prim: PrimId,
    position: DVec3,
    uv: Option<DVec2>,
    near: Option<MediumId>,
    far: Option<MediumId>,
}

impl SurfacePoint for HitPoint<'_, '_> {
    fn uv(&self) -> DVec2 {
        self.uv
            .unwrap_or_else(|| self.tracer.scene.uv_at(self.prim, self.position))
    }
    fn wavelength(&self) -> Option<f64> {
        self.tracer.single_wavelength()
    }
    fn index_near(&self) -> Option<f64> {
        self.tracer.index(self.near, self.position)
    }
    fn index_far(&self) -> Option<f64> {
        self.tracer.index(self.far, self.position)
    }
}
