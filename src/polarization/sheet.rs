//! Thin sheets light crosses without turning: an ideal linear polarizer and an ideal linear
//! retarder (a wave plate), each with its axis fixed in the scene.
//!
//! **Oblique light.** A polarizer absorbs the field along its absorbing axis a = n × t (n the
//! sheet's normal, t its transmission axis in the sheet): light crossing it along k keeps the
//! field across a's part across k, so it leaves polarized along k × a — the tilted polarizer's
//! geometric model that Korger et al. (2013) measured, and Mitsuba 3's `polarizer`. Square on,
//! that is t itself. A retarder acts along its fast axis's part across the light.

use super::mueller::{linear_polarizer, linear_retarder};
use super::Element;
use glam::DVec3;

/// An ideal thin sheet (`type = "polarizer"` or `"retarder"`). Its axis is a direction in the
/// scene; where light crosses it, the axis's part across the light is the axis it acts along
/// (for light crossing the sheet square on, the axis itself when it lies in the sheet).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sheet {
    /// Passes the field's component along `axis` and absorbs the rest: half of unpolarized
    /// light, cos² of the angle between a linear polarization and the axis (Malus's law).
    Polarizer {
        /// The transmission axis (unit).
        axis: DVec3,
    },
    /// Delays the field's component across `fast_axis` by `retardance` (radians) against the
    /// component along it, and absorbs nothing.
    Retarder {
        /// The fast axis (unit).
        fast_axis: DVec3,
        /// The slow component's phase lag (radians; π/2 a quarter-wave plate).
        retardance: f64,
    },
}

impl Sheet {
    /// The share of unpolarized light it passes.
    pub fn transmittance(&self) -> f64 {
        match self {
            Sheet::Polarizer { .. } => 0.5,
            Sheet::Retarder { .. } => 1.0,
        }
    }

    /// Its Mueller matrix for light crossing it along unit `direction` where its unit normal
    /// is `normal` (either way, each): a polarizer's in the basis of k × a, what it passes
    /// (its axis's part across the light where the light runs along a: a set of no
    /// measure); a retarder's in the basis of its fast axis.
    pub fn element(&self, normal: DVec3, direction: DVec3) -> Element {
        match *self {
            Sheet::Polarizer { axis } => {
                let passed = direction.cross(normal.cross(axis));
                let x = match passed.length_squared() > 1e-24 {
                    true => passed,
                    false => axis,
                };
                Element::grey(linear_polarizer(0.0), x)
            }
            Sheet::Retarder {
                fast_axis,
                retardance,
            } => Element::grey(linear_retarder(retardance, 0.0), fast_axis),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polarization::{Polarization, Sense};

    /// Linearly polarized light through a tilted polarizer keeps what a field E across the
    /// light keeps when the sheet absorbs its component along the absorbing axis's part across
    /// the light, â: |E − (E·â)â|² (the Jones vector written out, Korger et al. 2013's
    /// geometric model), to 1e-12, over 200 oblique crossings of a sheet turned in space;
    /// square on, the transmission axis itself (Malus's law). A model keeping the field along
    /// the transmission axis's part across the light instead differs there by up to 0.9.
    #[test]
    fn a_tilted_polarizer_absorbs_along_its_absorbing_axis() {
        let normal = DVec3::new(0.2, -0.3, 0.93).normalize();
        let t = normal.any_orthonormal_vector();
        let sheet = Sheet::Polarizer { axis: t };
        let a = normal.cross(t);
        let mut largest_other = 0.0f64;
        for k in 0..200 {
            let (u, v) = (
                (k as f64 * 0.618_034).fract(),
                (k as f64 * 0.414_214).fract(),
            );
            let z = 0.2 + 0.8 * u;
            let (e1, e2) = normal.any_orthonormal_pair();
            let phi = std::f64::consts::TAU * v;
            let dir =
                (z * normal + (1.0 - z * z).sqrt() * (phi.cos() * e1 + phi.sin() * e2)).normalize();
            // A linear polarization across the light at a turn ψ from a fixed reference.
            let reference = dir.cross(DVec3::new(0.3, 0.5, -0.8)).normalize();
            let psi = 2.9 * u + 1.3 * v;
            let field = reference * psi.cos() + dir.cross(reference) * psi.sin();
            let a_across = (a - dir * a.dot(dir)).normalize();
            let kept = (field - a_across * field.dot(a_across)).length_squared();
            let mut light = Polarization::unpolarized(Sense::WithLight, dir);
            let linear = Element::grey(linear_polarizer(0.0), field);
            light.meet(&linear, dir);
            // The factor beyond unpolarized light's ½.
            let through = 0.5 * light.meet(&sheet.element(normal, dir), dir).0.x;
            assert!((through - kept).abs() < 1e-12, "{through} against {kept}");
            let t_across = (t - dir * t.dot(dir)).normalize();
            largest_other = largest_other.max((field.dot(t_across).powi(2) - kept).abs());
        }
        assert!(largest_other > 0.1, "the models differ by {largest_other}");
        let square = sheet.element(normal, normal);
        let mut light = Polarization::unpolarized(Sense::WithLight, normal);
        light.meet(&Element::grey(linear_polarizer(0.0), t), normal);
        assert!((0.5 * light.meet(&square, normal).0.x - 1.0).abs() < 1e-12);
    }
}
