//! Linear RGB radiometry (not spectral): radiance in W/(m²·sr) per channel, as in the
//! reference scenes. Tone mapping for previews only.

/// A linear RGB triple (radiance, reflectance or throughput).
pub type Rgb = glam::DVec3;

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
