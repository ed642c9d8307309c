//! What Mitsuba 3's RGB variants make of a `<spectrum>` (its `xml.cpp`,
//! `create_texture_from_spectrum`, and `spectrum_list_to_srgb`), so that a converted scene has
//! the colours Mitsuba renders it with:
//!
//! - one value v in an emitter: v times the sRGB of equal-energy white of luminance 1,
//!   M·(1, 1, 1) with M Mitsuba's XYZ → linear sRGB matrix (Lindbloom's, for D65): the
//!   pinkish (1.2048, 0.9483, 0.9089) — not grey; anywhere else, v itself;
//! - wavelength–value pairs (nm, increasing; linear between them, zero outside them) in an
//!   emitter: M·∫ v x̄ȳz̄ dλ / ∫ ȳ dλ, negative channels clamped to 0; as a reflectance:
//!   M·∫ v D65 x̄ȳz̄ dλ / ∫ D65 ȳ dλ (a constant spectrum of 1 is white) clamped to [0, 1]; as
//!   `eta`, `k`, `int_ior`, `ext_ior` or `sigma_t` the same, clamped only below.
//!
//! The integrals are Mitsuba's sums (1000 points over 360–830 nm, which a band a few nm wide
//! feels) of grinlight's CIE 1931 and D65 tables (1 nm, CIE 15) where Mitsuba reads its own
//! (5 nm): the two agree to 3e-3 (`tests/import.rs` holds values Mitsuba 3.9.1 reported).

use crate::spectrum::colour::{d65, observer, visible_sum};
use glam::{DMat3, DVec3};

/// Mitsuba's XYZ → linear sRGB matrix (`xyz_to_srgb`), rows as written.
const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.240479, -1.537150, -0.498535],
    [-0.969256, 1.875991, 0.041556],
    [0.055648, -0.204043, 1.057311],
];

fn xyz_to_srgb(xyz: DVec3) -> DVec3 {
    DMat3::from_cols_array_2d(&XYZ_TO_SRGB).transpose() * xyz
}

/// Where a spectrum stands, which decides how Mitsuba's RGB variants read it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// A property of an emitter (its radiance, intensity, irradiance).
    Emission,
    /// A reflectance, an albedo or any other colour in [0, 1].
    Bounded,
    /// `eta`, `k`, `int_ior`, `ext_ior`, `sigma_t`: any value ≥ 0.
    Unbounded,
}

impl Role {
    /// The role of the property `name` of an object of tag `tag`.
    pub fn of(tag: &str, name: &str) -> Role {
        match (tag, name) {
            (_, "eta" | "k" | "int_ior" | "ext_ior" | "sigma_t") => Role::Unbounded,
            ("emitter", _) => Role::Emission,
            _ => Role::Bounded,
        }
    }
}

/// The RGB of `<spectrum value="v">` in the role `role` (None where it is not finite).
pub fn uniform(v: f64, role: Role) -> Option<DVec3> {
    let rgb = match role {
        Role::Emission => v * xyz_to_srgb(DVec3::ONE),
        Role::Bounded | Role::Unbounded => DVec3::splat(v),
    };
    rgb.is_finite().then_some(rgb)
}

/// The RGB of a spectrum given by `pairs` (wavelength in nm, value), in the role `role`: at
/// least two, their wavelengths increasing ([`pairs`] makes them so). None where the integral
/// is not finite (values near the largest number overflow it): never a colour made up.
pub fn sampled(pairs: &[(f64, f64)], role: Role) -> Option<DVec3> {
    let (first, last) = (pairs[0].0, pairs[pairs.len() - 1].0);
    let at = |nm: f64| -> f64 {
        let i = pairs
            .partition_point(|&(w, _)| w <= nm)
            .clamp(1, pairs.len() - 1);
        let ((w0, v0), (w1, v1)) = (pairs[i - 1], pairs[i]);
        v0 + (v1 - v0) * (nm - w0) / (w1 - w0)
    };
    let weight = |nm: f64| match role {
        Role::Emission => 1.0,
        Role::Bounded | Role::Unbounded => d65(nm),
    };
    let xyz = mitsuba_sum(|nm| match (first..=last).contains(&nm) {
        true => observer(nm) * (at(nm) * weight(nm)),
        false => DVec3::ZERO,
    });
    // The integral of ȳ (times D65's for a reflectance) that Mitsuba divides by: its light's
    // by the same sum (a constant spectrum of 1 has luminance 1), its reflectance's as an
    // integral (a constant reflectance of 1 reads 0.999, as Mitsuba's does).
    let y = match role {
        Role::Emission => mitsuba_sum(|nm| observer(nm).y),
        Role::Bounded | Role::Unbounded => visible_sum(|nm| observer(nm).y * d65(nm)),
    };
    let rgb = xyz_to_srgb(xyz / y);
    rgb.is_finite().then(|| match role {
        Role::Bounded => rgb.clamp(DVec3::ZERO, DVec3::ONE),
        Role::Emission | Role::Unbounded => rgb.max(DVec3::ZERO),
    })
}

/// Mitsuba's sum over wavelength of `f`: 1000 points spread evenly over 360–830 nm, each
/// standing for 0.47 nm.
fn mitsuba_sum<T: Default + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T>>(
    f: impl Fn(f64) -> T,
) -> T {
    (0..1000)
        .map(|i| 360.0 + f64::from(i) * 470.0 / 999.0)
        .fold(T::default(), |sum, nm| sum + f(nm) * 0.47)
}

/// The pairs of a `value` attribute such as "400:0.1, 500:0.4" (wavelengths increasing), or
/// why not.
pub fn pairs(text: &str) -> Result<Vec<(f64, f64)>, String> {
    let mut pairs = Vec::new();
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let parsed = item
            .split_once(':')
            .and_then(|(w, v)| Some((w.trim().parse::<f64>().ok()?, v.trim().parse::<f64>().ok()?)))
            .filter(|(w, v)| w.is_finite() && v.is_finite());
        let Some((w, v)) = parsed else {
            return Err(format!(
                "'{item}' is not a wavelength:value pair of numbers"
            ));
        };
        if pairs.last().is_some_and(|&(last, _)| w <= last) {
            return Err(format!(
                "the wavelengths must increase ({w} nm comes after a longer one)"
            ));
        }
        pairs.push((w, v));
    }
    match pairs.len() {
        0 | 1 => Err("a spectrum over wavelength needs at least two wavelength:value pairs".into()),
        _ => Ok(pairs),
    }
}
