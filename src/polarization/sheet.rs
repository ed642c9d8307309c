//! Thin sheets light crosses without turning: an ideal linear polarizer and an ideal linear
//! retarder (a wave plate), each with its axis fixed in the scene.

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

    /// Its Mueller matrix, in the basis of its axis.
    pub fn element(&self) -> Element {
        match *self {
            Sheet::Polarizer { axis } => Element::grey(linear_polarizer(0.0), axis),
            Sheet::Retarder {
                fast_axis,
                retardance,
            } => Element::grey(linear_retarder(retardance, 0.0), fast_axis),
        }
    }
}
