//! Between spectra and the linear sRGB the images are written in.
//!
//! - **Out**: a spectral power distribution Φ(λ) (per nm) appears in the image as
//!   ∫ Φ(λ) r̄(λ) dλ, where r̄ = M x̄ȳz̄ is the CIE 1931 2° observer's colour-matching functions
//!   taken to linear sRGB by the standard XYZ → sRGB matrix, scaled per channel so that
//!   illuminant D65 of unit power appears as exactly (1, 1, 1), sRGB's white ([`sensor`]).
//! - **In**: an RGB reflectance (an albedo, a mirror's reflectance) is Jakob and Hanika's
//!   (2019) smooth spectrum of it — a sigmoid of a quadratic in λ fitted so that the spectrum
//!   under D65 has that RGB ([`reflectance`]); an RGB light is that spectrum times D65
//!   ([`illuminant`]), so white light is D65 and a grey is a constant spectrum, exactly.
//!
//! The observer and D65 are CIE 15:2004's tables at 1 nm over 380–780 nm, from the
//! `colorimetry` crate (zero outside: light there is invisible and contributes nothing to an
//! image); the XYZ → sRGB matrix is computed by the same crate from sRGB's primaries and white
//! point (IEC 61966-2-1). The Jakob–Hanika coefficient table is optimised once, on first use
//! (≈ 1.6 s, resolution 16; the `rgb2spec` crate), only by scenes that trace wavelengths.

use crate::color::Rgb;
use colorimetry::illuminant::Illuminant;
use colorimetry::observer::Observer;
use colorimetry::rgb::RgbSpace;
use colorimetry::traits::Light;
use glam::DVec3;
use std::sync::LazyLock;

/// First wavelength of the CIE tables, nm.
const FIRST: usize = 380;
/// Last wavelength of the CIE tables, nm.
const LAST: usize = 780;

/// The observer in linear sRGB and D65, per nm over [`FIRST`, `LAST`].
struct Tables {
    /// r̄(λ): linear sRGB response to unit power at λ (1/nm scale: see [`sensor`]).
    sensor: Vec<DVec3>,
    /// ȳ(λ) over the luminance of unit-power D65 (see [`luminance_of`]).
    luminance: Vec<f64>,
    /// D65 normalised to unit power, 1/nm.
    d65: Vec<f64>,
    /// The observer's x̄, ȳ, z̄ themselves (ȳ peaking at 1).
    xyz: Vec<DVec3>,
}

static TABLES: LazyLock<Tables> = LazyLock::new(|| {
    let observer = Observer::Cie1931;
    let m = observer.calc_xyz2rgb_matrix(RgbSpace::SRGB);
    let d65 = Illuminant::d65().spectrum().as_array().to_vec();
    let power: f64 = d65.iter().sum();
    let d65: Vec<f64> = d65.iter().map(|s| s / power).collect();
    let xyz: Vec<DVec3> = (FIRST..=LAST)
        .map(|nm| {
            DVec3::from_array(
                observer
                    .xyz_at_wavelength(nm)
                    .expect("380–780 nm is the observer's range")
                    .to_array(),
            )
        })
        .collect();
    let rgb: Vec<DVec3> = xyz
        .iter()
        .map(|xyz| {
            let row = |r: usize| (0..3).map(|c| m[(r, c)] * xyz[c]).sum::<f64>();
            DVec3::new(row(0), row(1), row(2))
        })
        .collect();
    // White balance: unit-power D65 → (1, 1, 1) (a scale per channel of ≈ 1e-3 relative
    // spread: the matrix is made for D65 already; this makes white exact at 1 nm sums).
    let white: DVec3 = rgb.iter().zip(&d65).map(|(r, s)| *r * *s).sum();
    let ybar: Vec<f64> = xyz.iter().map(|v| v.y).collect();
    let white_y: f64 = ybar.iter().zip(&d65).map(|(y, s)| y * s).sum();
    Tables {
        sensor: rgb.iter().map(|r| *r / white).collect(),
        luminance: ybar.iter().map(|y| y / white_y).collect(),
        d65,
        xyz,
    }
});

/// The Jakob–Hanika coefficient table for sRGB.
static UPSAMPLING: LazyLock<rgb2spec::RGB2Spec> = LazyLock::new(|| {
    rgb2spec::optimize::optimize(rgb2spec::optimize::gamut::Gamut::SRGB, 16)
        .expect("resolution 16 is well above the optimiser's degenerate range (< 10)")
});

/// Linear interpolation of a per-nm table at `nm` (zero outside it).
fn lerp<T: Copy + Default + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>>(
    table: &[T],
    nm: f64,
) -> T {
    let x = nm - FIRST as f64;
    if !(0.0..=(LAST - FIRST) as f64).contains(&x) {
        return T::default();
    }
    let i = (x as usize).min(LAST - FIRST - 1);
    let t = x - i as f64;
    table[i] * (1.0 - t) + table[i + 1] * t
}

/// r̄(λ): the linear sRGB in which unit spectral power at `nm` appears, so that a spectral
/// power distribution Φ (per nm) appears as ∫ Φ r̄ dλ; unit-power D65 appears as (1, 1, 1).
/// Channels may be negative (pure spectral colours lie outside sRGB's gamut).
pub fn sensor(nm: f64) -> Rgb {
    Rgb(lerp(&TABLES.sensor, nm))
}

/// The CIE 1931 2° observer's colour-matching functions (x̄, ȳ, z̄) at `nm` (ȳ peaks at 1;
/// zero outside 380–780 nm).
pub fn observer(nm: f64) -> DVec3 {
    lerp(&TABLES.xyz, nm)
}

/// The sum over the observer's range, 1 nm apart, of `f`(λ) at each wavelength λ (nm): the
/// integral of a function over the visible the way every conversion here takes it.
pub fn visible_sum<T: Default + std::ops::Add<Output = T>>(f: impl Fn(f64) -> T) -> T {
    (FIRST..=LAST).fold(T::default(), |sum, nm| sum + f(nm as f64))
}

/// CIE illuminant D65 at `nm`, normalised to unit power over 380–780 nm (1/nm).
pub fn d65(nm: f64) -> f64 {
    lerp(&TABLES.d65, nm)
}

/// The linear sRGB of a spectral power distribution `power` (per nm), by 1 nm sums over the
/// observer's range.
pub fn colour_of(power: impl Fn(f64) -> f64) -> Rgb {
    visible_sum(|nm| sensor(nm) * power(nm))
}

/// The luminance (CIE 1931 Y) of a spectral power distribution `power` (per nm) relative to
/// unit-power D65's, by 1 nm sums over the observer's range: 1 for unit-power D65, whose
/// colour is (1, 1, 1).
pub fn luminance_of(power: impl Fn(f64) -> f64) -> f64 {
    visible_sum(|nm| lerp(&TABLES.luminance, nm) * power(nm))
}

/// The value at `nm` of the smooth reflectance spectrum of `rgb` (Jakob and Hanika 2019): a
/// grey is the constant spectrum of its value, exactly; colours brighter than 1 are scaled
/// into the table's range and back (pbrt-v4's unbounded spectrum); negative channels count as
/// zero.
pub fn reflectance(rgb: Rgb, nm: f64) -> f64 {
    let c = rgb.0.max(DVec3::ZERO);
    if c.x == c.y && c.y == c.z {
        return c.x;
    }
    let m = c.max_element();
    let scale = if m > 1.0 { 2.0 * m } else { 1.0 };
    let q = c / scale;
    let coefficients = UPSAMPLING.fetch([q.x as f32, q.y as f32, q.z as f32]);
    scale * rgb2spec::eval_precise(coefficients, nm as f32) as f64
}

/// The spectral power (per nm) at `nm` of light whose colour is `rgb`: its
/// [`reflectance`] spectrum times unit-power D65, so that it appears as `rgb`.
pub fn illuminant(rgb: Rgb, nm: f64) -> f64 {
    reflectance(rgb, nm) * d65(nm)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit-power D65 is white, to rounding; equal energy (CIE E) in sRGB is the pinkish
    /// (1.205, 0.948, 0.909) of the literature (Lindbloom's E → sRGB under D65-relative
    /// sRGB, normalised to Y = 1: 1.2049, 0.9484, 0.9086) — a check on the observer and the
    /// matrix to 2e-3 (the tables' 5 nm vs 1 nm sampling).
    #[test]
    fn white_points() {
        let white = colour_of(d65);
        assert!(
            (white.0 - DVec3::ONE).abs().max_element() < 1e-12,
            "{white}"
        );
        let e = colour_of(|_| 1.0);
        let luminance = 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z;
        let e = e.0 / luminance;
        let expected = DVec3::new(1.2049, 0.9484, 0.9086);
        assert!((e - expected).abs().max_element() < 2e-3, "{e}");
    }

    /// Greys are constant spectra exactly; a colour's spectrum seen under D65 gives the
    /// colour back to the coefficient table's accuracy (measured: 7.3e-3 at most over these
    /// four at resolution 16; tolerance 1e-2), and reflectances stay in [0, 1]. A colour
    /// brighter than 1 comes back within 0.7 % of its largest channel (4, 2, 1 → 3.991, 1.973,
    /// 0.976).
    #[test]
    fn upsampling_round_trips() {
        assert_eq!(reflectance(Rgb::splat(0.37), 512.3), 0.37);
        assert_eq!(illuminant(Rgb::ONE, 500.0), d65(500.0));
        for rgb in [
            Rgb::new(0.8, 0.2, 0.1),
            Rgb::new(0.1, 0.5, 0.2),
            Rgb::new(0.2, 0.3, 0.9),
            Rgb::new(0.9, 0.9, 0.2),
        ] {
            let back = colour_of(|nm| illuminant(rgb, nm));
            assert!(
                (back.0 - rgb.0).abs().max_element() < 1e-2,
                "{rgb} → {back}"
            );
            for nm in (380..=780).step_by(10) {
                let r = reflectance(rgb, nm as f64);
                assert!((0.0..=1.0).contains(&r), "{rgb} at {nm}: {r}");
            }
        }
        let bright = Rgb::new(4.0, 2.0, 1.0);
        let back = colour_of(|nm| illuminant(bright, nm));
        assert!((back.0 - bright.0).abs().max_element() < 0.03, "{back}");
    }
}
