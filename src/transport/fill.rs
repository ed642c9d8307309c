//! Which medium fills a point of the scene: the interior of the innermost dielectric shape
//! holding it, else the ambient medium (where a light or the camera sits).

use super::Tracer;
use crate::ids::MediumId;
use crate::material::Material;
use crate::math::offset;
use glam::DVec3;

/// Directions along which [`Tracer::medium_containing`] looks for the enclosing surface: far
/// from any axis, so they rarely graze the axis-aligned walls of a scene.
const PROBES: [DVec3; 3] = [
    DVec3::new(
        0.267_261_241_912_424_4,
        0.534_522_483_824_848_8,
        0.801_783_725_737_273_2,
    ),
    DVec3::new(
        -0.615_457_454_897_398_3,
        0.492_365_963_917_918_6,
        0.615_457_454_897_398_3,
    ),
    DVec3::new(
        0.455_842_305_838_552_3,
        -0.683_763_458_757_828_4,
        -0.569_802_882_298_190_4,
    ),
];

impl Tracer<'_> {
    /// The medium filling point `p`: the interior of the innermost dielectric shape holding
    /// it, else the ambient medium. Found by the first dielectric surface along fixed probe
    /// rays (met from its back: `p` is inside it; from its front: outside, in its exterior);
    /// the majority of three probes decides, so a probe grazing an edge does not.
    pub fn medium_containing(&self, p: DVec3) -> Option<MediumId> {
        let [a, b, c] = PROBES.map(|d| self.enclosing_along(p, d));
        if a == b || a == c {
            a
        } else {
            b
        }
    }

    fn enclosing_along(&self, p: DVec3, d: DVec3) -> Option<MediumId> {
        let scene = self.scene;
        let mut o = p;
        loop {
            let Some(found) = scene.accel.intersect_ray(o, d, 0.0, f64::INFINITY) else {
                return scene.ambient();
            };
            let (s, h) = (scene.surface(found.prim), found.hit);
            if matches!(scene.material(s), Some(Material::Dielectric { .. })) {
                return if d.dot(h.normal) > 0.0 {
                    s.interior
                } else {
                    s.exterior
                };
            }
            o = offset(o + h.t * d, d);
        }
    }
}
