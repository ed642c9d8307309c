//! Colour: linear RGB radiometry (not yet spectral) — radiance in W/(m²·sr) per channel, as in
//! the reference scenes — as one type, [`Rgb`]; tone mapping for previews.

use glam::DVec3;
use std::ops::{Add, AddAssign, Deref, Div, DivAssign, Mul, MulAssign, Neg, Sub};

/// A colour quantity — radiance, irradiance, power, reflectance or throughput — per linear
/// RGB channel. One type, so that a spectral sample can take its place: read its channels
/// through [`Deref`] (`.x`, `max_element()`), combine colours with colours and with scalars.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb(pub DVec3);

impl Rgb {
    /// Black, or zero throughput.
    pub const ZERO: Rgb = Rgb(DVec3::ZERO);
    /// White, or unit throughput.
    pub const ONE: Rgb = Rgb(DVec3::ONE);

    /// The colour (r, g, b).
    pub const fn new(r: f64, g: f64, b: f64) -> Rgb {
        Rgb(DVec3::new(r, g, b))
    }

    /// The grey of value `v` in every channel.
    pub const fn splat(v: f64) -> Rgb {
        Rgb(DVec3::splat(v))
    }

    /// The channels' mean (power and flux are booked so).
    pub fn mean(&self) -> f64 {
        self.0.element_sum() / 3.0
    }

    /// Whether every channel holds the same value.
    pub fn is_grey(&self) -> bool {
        self.0.x == self.0.y && self.0.y == self.0.z
    }

    /// exp of each channel (a transmittance from its optical depth's negative).
    pub fn exp(&self) -> Rgb {
        Rgb(self.0.exp())
    }
}

impl Deref for Rgb {
    type Target = DVec3;
    fn deref(&self) -> &DVec3 {
        &self.0
    }
}

impl std::fmt::Display for Rgb {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let [r, g, b] = self.0.to_array();
        write!(f, "[{r:?}, {g:?}, {b:?}]")
    }
}

impl From<DVec3> for Rgb {
    fn from(v: DVec3) -> Rgb {
        Rgb(v)
    }
}

impl Add for Rgb {
    type Output = Rgb;
    fn add(self, o: Rgb) -> Rgb {
        Rgb(self.0 + o.0)
    }
}

impl Sub for Rgb {
    type Output = Rgb;
    fn sub(self, o: Rgb) -> Rgb {
        Rgb(self.0 - o.0)
    }
}

impl Neg for Rgb {
    type Output = Rgb;
    fn neg(self) -> Rgb {
        Rgb(-self.0)
    }
}

impl Mul for Rgb {
    type Output = Rgb;
    fn mul(self, o: Rgb) -> Rgb {
        Rgb(self.0 * o.0)
    }
}

impl Mul<f64> for Rgb {
    type Output = Rgb;
    fn mul(self, k: f64) -> Rgb {
        Rgb(self.0 * k)
    }
}

impl Mul<Rgb> for f64 {
    type Output = Rgb;
    fn mul(self, c: Rgb) -> Rgb {
        Rgb(self * c.0)
    }
}

impl Div for Rgb {
    type Output = Rgb;
    fn div(self, o: Rgb) -> Rgb {
        Rgb(self.0 / o.0)
    }
}

impl Div<f64> for Rgb {
    type Output = Rgb;
    fn div(self, k: f64) -> Rgb {
        Rgb(self.0 / k)
    }
}

impl AddAssign for Rgb {
    fn add_assign(&mut self, o: Rgb) {
        self.0 += o.0;
    }
}

impl MulAssign for Rgb {
    fn mul_assign(&mut self, o: Rgb) {
        self.0 *= o.0;
    }
}

impl MulAssign<f64> for Rgb {
    fn mul_assign(&mut self, k: f64) {
        self.0 *= k;
    }
}

impl DivAssign<f64> for Rgb {
    fn div_assign(&mut self, k: f64) {
        self.0 /= k;
    }
}

impl std::iter::Sum for Rgb {
    fn sum<I: Iterator<Item = Rgb>>(iter: I) -> Rgb {
        iter.fold(Rgb::ZERO, |a, b| a + b)
    }
}

/// The sRGB transfer function of a linear value in [0, 1].
pub fn srgb_encode(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// An 8-bit sRGB preview value of a linear channel: clamped to [0, 1], then encoded.
pub fn preview_byte(x: f32) -> u8 {
    let v = if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    };
    (srgb_encode(v) * 255.0 + 0.5) as u8
}
