//! Light sources and their sampling for direct illumination at a surface point.
//! Radiometry per RGB channel: intensity W/sr, radiance W/(m²·sr), irradiance W/m².

use crate::color::Rgb;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// The emitting surface of an area light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Emitter {
    /// The parallelogram origin + u e1 + v e2; it emits on the side of e1 × e2.
    Quad {
        /// Corner.
        origin: DVec3,
        /// First edge.
        e1: DVec3,
        /// Second edge.
        e2: DVec3,
    },
    /// A disk emitting on the side of `normal`.
    Disk {
        /// Centre.
        center: DVec3,
        /// Unit normal.
        normal: DVec3,
        /// Radius.
        radius: f64,
    },
}

impl Emitter {
    /// Area (length²).
    pub fn area(&self) -> f64 {
        match *self {
            Emitter::Quad { e1, e2, .. } => e1.cross(e2).length(),
            Emitter::Disk { radius, .. } => PI * radius * radius,
        }
    }

    /// Unit normal of the emitting side.
    pub fn normal(&self) -> DVec3 {
        match *self {
            Emitter::Quad { e1, e2, .. } => e1.cross(e2).normalize(),
            Emitter::Disk { normal, .. } => normal,
        }
    }

    /// A point uniformly distributed over the surface for `uv` uniform in [0,1)².
    pub fn sample(&self, uv: (f64, f64)) -> DVec3 {
        match *self {
            Emitter::Quad { origin, e1, e2 } => origin + uv.0 * e1 + uv.1 * e2,
            Emitter::Disk {
                center,
                normal,
                radius,
            } => {
                let t = normal.any_orthonormal_vector();
                let b = normal.cross(t);
                let r = radius * uv.0.sqrt();
                let phi = TAU * uv.1;
                center + r * (phi.cos() * t + phi.sin() * b)
            }
        }
    }
}

/// A light source.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// Isotropic point source.
    Point {
        /// Position.
        position: DVec3,
        /// Intensity, W/sr.
        intensity: Rgb,
    },
    /// A point source emitting inside a cone, with a smooth falloff between two angles.
    Spot {
        /// Position.
        position: DVec3,
        /// Unit axis of the cone.
        direction: DVec3,
        /// Intensity on the axis, W/sr.
        intensity: Rgb,
        /// cos of the angle where the falloff starts.
        cos_inner: f64,
        /// cos of the cone's half angle (no light beyond).
        cos_outer: f64,
    },
    /// Constant radiance from one side of a quad or disk (also visible to the camera).
    Area {
        /// The surface.
        emitter: Emitter,
        /// Radiance, W/(m²·sr).
        radiance: Rgb,
    },
    /// A small disk LED with intensity I(θ) = I0 cos^m θ, I0 = P (m + 1)/(2π) for total power P.
    Led {
        /// The disk.
        emitter: Emitter,
        /// Peak intensity I0 per channel, W/sr.
        peak_intensity: Rgb,
        /// The exponent m.
        m: f64,
    },
    /// Parallel light.
    Directional {
        /// Unit direction of propagation.
        direction: DVec3,
        /// Irradiance on a surface facing the light, W/m².
        irradiance: Rgb,
    },
}

/// Light arriving at a point from one sample of a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incident {
    /// Unit direction from the point toward the light.
    pub wi: DVec3,
    /// Distance to the sampled light point (∞ for directional light).
    pub distance: f64,
    /// Irradiance estimate on a surface facing the light (W/m²): multiply by the BRDF and
    /// the receiving cosine.
    pub irradiance: Rgb,
}

impl Light {
    /// One sample of the light arriving at `p`; `None` when this sample sends nothing there.
    pub fn sample_incident(&self, p: DVec3, uv: (f64, f64)) -> Option<Incident> {
        let toward = |x: DVec3| {
            let v = x - p;
            let d = v.length();
            (d > 0.0).then(|| (v / d, d))
        };
        match self {
            Light::Point {
                position,
                intensity,
            } => {
                let (wi, d) = toward(*position)?;
                Some(Incident {
                    wi,
                    distance: d,
                    irradiance: *intensity / (d * d),
                })
            }
            Light::Spot {
                position,
                direction,
                intensity,
                cos_inner,
                cos_outer,
            } => {
                let (wi, d) = toward(*position)?;
                let c = -wi.dot(*direction);
                let f = smoothstep(*cos_outer, *cos_inner, c);
                (f > 0.0).then(|| Incident {
                    wi,
                    distance: d,
                    irradiance: *intensity * f / (d * d),
                })
            }
            Light::Area { emitter, radiance } => {
                let x = emitter.sample(uv);
                let (wi, d) = toward(x)?;
                let cos_l = -wi.dot(emitter.normal());
                (cos_l > 0.0).then(|| Incident {
                    wi,
                    distance: d,
                    irradiance: *radiance * (cos_l * emitter.area() / (d * d)),
                })
            }
            Light::Led {
                emitter,
                peak_intensity,
                m,
            } => {
                let x = emitter.sample(uv);
                let (wi, d) = toward(x)?;
                let cos_l = -wi.dot(emitter.normal());
                (cos_l > 0.0).then(|| Incident {
                    wi,
                    distance: d,
                    irradiance: *peak_intensity * (cos_l.powf(*m) / (d * d)),
                })
            }
            Light::Directional {
                direction,
                irradiance,
            } => Some(Incident {
                wi: -*direction,
                distance: f64::INFINITY,
                irradiance: *irradiance,
            }),
        }
    }
}

fn smoothstep(lo: f64, hi: f64, x: f64) -> f64 {
    if hi <= lo {
        return if x >= hi { 1.0 } else { 0.0 };
    }
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}
