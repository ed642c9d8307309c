//! The frame a round shape's surface coordinates (u, v) are read in, where the scene gives one
//! (`uv_frame`): a sphere's, a cylinder's or a disk's, placed as Mitsuba 3 places its own
//! shapes' in their local frame (its `sphere.cpp`, `cylinder.cpp`, `disk.cpp`). Without one a
//! shape keeps its own coordinates ([`Primitive::uv_at`]).
//!
//! In the frame's axes x, y, z (unit, orthogonal; φ the longitude about z from x toward y, in
//! [0, 2π)):
//! - a sphere's u = φ/2π and v = θ/π, θ the angle from +z (v = 0 at its +z pole);
//! - a cylinder's u = φ/2π about its axis and v its height over its length from its base (its
//!   own v); z is along the axis;
//! - a disk's u = r/R, its distance from the centre over its radius, and v = φ/2π; z is along
//!   its normal, either way.
//!
//! These are Mitsuba's (u, v); `v_from_top` reads v from the image's top row down (1 − v), as
//! a mesh's key does and as Mitsuba reads an image.

use super::{Disk, Primitive};
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// A round shape's frame of surface coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvFrame {
    /// Where φ = 0.
    pub x: DVec3,
    /// Where φ = π/2.
    pub y: DVec3,
    /// The pole (a sphere), the axis (a cylinder) or the normal (a disk).
    pub z: DVec3,
    /// Whether v counts from the image's top row down.
    pub v_from_top: bool,
}

impl UvFrame {
    /// The frame of axes `x`, `y`, `z`, or why not: each of length 1 and each two orthogonal,
    /// to 1e-9.
    pub fn new(x: DVec3, y: DVec3, z: DVec3, v_from_top: bool) -> Result<Self, String> {
        let unit = [x, y, z].iter().all(|a| (a.length() - 1.0).abs() <= 1e-9);
        let orthogonal = [x.dot(y), y.dot(z), z.dot(x)]
            .iter()
            .all(|d| d.abs() <= 1e-9);
        match unit && orthogonal {
            true => Ok(Self {
                x,
                y,
                z,
                v_from_top,
            }),
            false => Err(format!(
                "expected three unit, orthogonal axes [x, y, z], got {x}, {y}, {z}"
            )),
        }
    }

    /// Why the frame does not fit `primitive`, if it does not: a cylinder's z must be along
    /// its axis and a disk's along its normal (either way, to 1e-9); a quad, a triangle and a
    /// mesh have coordinates of their own.
    pub fn misfit(&self, primitive: &Primitive) -> Option<String> {
        let along = |a: DVec3| (self.z.dot(a).abs() - 1.0).abs() <= 1e-9;
        match primitive {
            Primitive::Sphere { .. } => None,
            Primitive::Tube { axis, .. } => {
                (!along(*axis)).then(|| format!("z must be along the cylinder's axis {axis}"))
            }
            Primitive::Disk(Disk { normal, .. }) => {
                (!along(*normal)).then(|| format!("z must be along the disk's normal {normal}"))
            }
            Primitive::Quad(_) | Primitive::Triangle(_) | Primitive::Mesh(_) => {
                Some("only a sphere, a cylinder or a disk takes a frame".into())
            }
        }
    }

    /// The surface coordinates of point `p` on `primitive` (one [`Self::misfit`] accepts).
    pub fn uv_at(&self, primitive: &Primitive, p: DVec3) -> DVec2 {
        let longitude = |d: DVec3| (d.dot(self.y).atan2(d.dot(self.x)) / TAU).rem_euclid(1.0);
        let uv = match *primitive {
            Primitive::Sphere { center, radius } => {
                let d = (p - center) / radius;
                let cos_theta = d.dot(self.z).clamp(-1.0, 1.0);
                DVec2::new(longitude(d), cos_theta.acos() / std::f64::consts::PI)
            }
            Primitive::Tube {
                base, axis, height, ..
            } => DVec2::new(longitude(p - base), (p - base).dot(axis) / height),
            Primitive::Disk(Disk { center, radius, .. }) => {
                let d = p - center;
                DVec2::new((d - self.z * d.dot(self.z)).length() / radius, longitude(d))
            }
            Primitive::Quad(_) | Primitive::Triangle(_) | Primitive::Mesh(_) => primitive.uv_at(p),
        };
        match self.v_from_top {
            true => DVec2::new(uv.x, 1.0 - uv.y),
            false => uv,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mitsuba 3's own parametrizations in its local frame (sphere.cpp, cylinder.cpp,
    /// disk.cpp: `dir_to_sph`, φ wrapped to [0, 2π)), written out: a sphere's (φ/2π, θ/π), a
    /// cylinder's (φ/2π, z), a disk's (r, φ/2π); with v read from the top, the frame's
    /// coordinates are (u, 1 − v) of these (1e-12) on a turned, moved and scaled shape.
    #[test]
    fn a_frame_reads_mitsubas_coordinates_of_its_local_frame() {
        let (x, y, z) = {
            let r = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0);
            (r * DVec3::X, r * DVec3::Y, r * DVec3::Z)
        };
        let centre = DVec3::new(0.4, -2.0, 1.5);
        let radius = 1.7;
        let world = |l: DVec3| centre + radius * (l.x * x + l.y * y + l.z * z);
        let phi = |l: DVec3| l.y.atan2(l.x).rem_euclid(TAU);
        let frame = UvFrame::new(x, y, z, true).unwrap();
        let sphere = Primitive::Sphere {
            center: centre,
            radius,
        };
        let tube = Primitive::Tube {
            base: centre,
            axis: z,
            radius,
            height: 2.5 * radius,
        };
        let disk = Primitive::Disk(Disk::full(centre, -z, radius));
        for k in 0..50 {
            let (a, b) = (0.37 + 1.3 * k as f64, 0.11 + 0.061 * k as f64);
            let on_sphere = DVec3::new(
                a.cos() * b.sin() * 3.0,
                a.sin() * b.sin() * 3.0,
                b.cos() * 3.0,
            ) / 3.0;
            let mitsuba = DVec2::new(
                phi(on_sphere) / TAU,
                on_sphere.z.clamp(-1.0, 1.0).acos() / std::f64::consts::PI,
            );
            let got = frame.uv_at(&sphere, world(on_sphere));
            assert!(
                (got - DVec2::new(mitsuba.x, 1.0 - mitsuba.y)).length() < 1e-12,
                "{got} {mitsuba}"
            );
            let on_tube = DVec3::new(a.cos(), a.sin(), 2.5 * b / 3.2);
            let mitsuba = DVec2::new(phi(on_tube) / TAU, on_tube.z / 2.5);
            let got = frame.uv_at(&tube, world(on_tube));
            assert!(
                (got - DVec2::new(mitsuba.x, 1.0 - mitsuba.y)).length() < 1e-12,
                "{got} {mitsuba}"
            );
            let on_disk = DVec3::new(a.cos(), a.sin(), 0.0) * (b / 3.2);
            let mitsuba = DVec2::new(on_disk.length(), phi(on_disk) / TAU);
            let got = frame.uv_at(&disk, world(on_disk));
            assert!(
                (got - DVec2::new(mitsuba.x, 1.0 - mitsuba.y)).length() < 1e-12,
                "{got} {mitsuba}"
            );
        }
        assert!(frame.misfit(&disk).is_none() && frame.misfit(&sphere).is_none());
        let aslant = Primitive::Tube {
            base: centre,
            axis: x,
            radius,
            height: 1.0,
        };
        assert!(frame.misfit(&aslant).unwrap().contains("axis"));
        assert!(UvFrame::new(x, x, z, false).is_err());
    }
}
