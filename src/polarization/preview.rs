//! A false-colour picture of the light's linear polarization, for a render's Stokes layers:
//! hue the angle of linear polarization, saturation its degree, value the light's radiance as
//! the ordinary preview shows it. Unpolarized light is grey; light polarized along the image's
//! right is red, along its up cyan, halfway between them (45°) yellow-green, at 135° violet —
//! the hue turns once as the angle turns by 180° (a polarization at ψ and at ψ + 180° is the
//! same).

use crate::color::preview_byte;

/// The angle of linear polarization (radians in [0, π), from the basis's first axis toward
/// its second) and its degree √(S1² + S2²)/S0 (clamped to [0, 1]; 0 where S0 is not
/// positive) of the Stokes vector `s` = (S0, S1, S2, S3).
pub fn linear(s: [f64; 4]) -> (f64, f64) {
    let [s0, s1, s2, _] = s;
    let degree = s1.hypot(s2) / s0;
    if s0.is_nan() || s0 <= 0.0 || !degree.is_finite() {
        return (0.0, 0.0);
    }
    let angle = (0.5 * s2.atan2(s1)).rem_euclid(std::f64::consts::PI);
    // A tiny negative angle's remainder rounds to π itself: the same polarization as 0.
    let angle = match angle < std::f64::consts::PI {
        true => angle,
        false => 0.0,
    };
    (angle, degree.clamp(0.0, 1.0))
}

/// The 8-bit sRGB colour of a pixel whose Stokes vector is `s` (its channels' mean), with the
/// preview's `exposure`: HSV with H = 2ψ (ψ the angle of linear polarization), S its degree
/// and V the sRGB-encoded radiance S0 × exposure (clamped to [0, 1], as the preview's).
pub fn colour(s: [f64; 4], exposure: f32) -> [u8; 3] {
    let (angle, degree) = linear(s);
    let value = f64::from(preview_byte(s[0] as f32 * exposure)) / 255.0;
    let hue = angle / std::f64::consts::PI * 6.0; // in [0, 6): sextants of the hue circle
    let sextant = hue.floor();
    let f = hue - sextant;
    let (p, q, t) = (
        value * (1.0 - degree),
        value * (1.0 - degree * f),
        value * (1.0 - degree * (1.0 - f)),
    );
    let rgb = match sextant as u8 {
        0 => [value, t, p],
        1 => [q, value, p],
        2 => [p, value, t],
        3 => [p, q, value],
        4 => [t, p, value],
        _ => [value, p, q],
    };
    rgb.map(|c| (c * 255.0).round().clamp(0.0, 255.0) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unpolarized light is its preview's grey; wholly polarized light along the first axis
    /// red, along the second cyan, at 45° chartreuse (hue 90°), at 135° violet (hue 270°), and
    /// a polarization half as strong half as saturated; S3 does not enter; no light is black;
    /// an angle a hair below 0 is red.
    #[test]
    fn hue_is_the_angle_and_saturation_the_degree() {
        let grey = preview_byte(0.5);
        assert_eq!(colour([0.5, 0.0, 0.0, 0.3], 1.0), [grey; 3]);
        assert_eq!(colour([0.5, 0.5, 0.0, 0.0], 1.0), [grey, 0, 0]);
        assert_eq!(colour([0.5, -0.5, 0.0, 0.0], 1.0), [0, grey, grey]);
        let half = (f64::from(grey) / 2.0).round() as u8;
        assert_eq!(colour([0.5, 0.0, 0.5, 0.0], 1.0), [half, grey, 0]);
        assert_eq!(colour([0.5, 0.0, -0.5, 0.0], 1.0), [half, 0, grey]);
        assert_eq!(colour([0.5, 0.25, 0.0, 0.0], 1.0), [grey, half, half]);
        assert_eq!(colour([0.0, 0.0, 0.0, 0.0], 1.0), [0; 3]);
        assert_eq!(colour([f64::NAN, 1.0, 0.0, 0.0], 1.0), [0; 3]);
        // Along the first axis from a hair below it: red, not the far end of the hue circle.
        assert_eq!(colour([0.5, 0.5, -1e-20, 0.0], 1.0), [grey, 0, 0]);
        let (angle, degree) = linear([2.0, 0.0, -1.0, 0.0]);
        assert!((angle - 0.75 * std::f64::consts::PI).abs() < 1e-15 && degree == 0.5);
    }
}
