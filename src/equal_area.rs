//! The equal-area octahedral map of the sphere onto the unit square (Clarberg 2008, "Fast
//! Equal-Area Mapping of the (Hemi)Sphere using SIMD"), as pbrt-v4 stores its environment and
//! goniometric light images: every region of the square covers a solid angle 4π times its
//! area, so each of an N × N image's pixels covers 4π/N² sr. The square's centre is +z, its
//! corners −z; the equator runs along the diamond joining the edges' midpoints. (u, v) count
//! from an image's left column and its row 0, the top row as stored: +x lies at the right
//! edge's midpoint, +y at the bottom edge's.
//!
//! grinlight computes the map's angle with `atan` where pbrt-v4 evaluates a 6th-degree minimax
//! polynomial of it: the two maps agree to 5·10⁻⁶ of the square's side (tests/import_pbrt.rs),
//! so a nearest-pixel lookup differs only within that distance of a pixel's edge.

use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_2_PI, FRAC_PI_4};

/// The unit direction at point `p` of the unit square ([0, 1]²).
pub fn square_to_sphere(p: DVec2) -> DVec3 {
    let (u, v) = (2.0 * p.x - 1.0, 2.0 * p.y - 1.0);
    let (up, vp) = (u.abs(), v.abs());
    // The signed distance from the diagonal |u| + |v| = 1: the equator.
    let signed = 1.0 - (up + vp);
    let r = 1.0 - signed.abs();
    let phi = match r == 0.0 {
        true => 1.0,
        false => (vp - up) / r + 1.0,
    } * FRAC_PI_4;
    let z = (1.0 - r * r).copysign(signed);
    let across = r * (2.0 - r * r).max(0.0).sqrt();
    DVec3::new(
        phi.cos().copysign(u) * across,
        phi.sin().copysign(v) * across,
        z,
    )
}

/// The point of the unit square where unit direction `d` lies.
pub fn sphere_to_square(d: DVec3) -> DVec2 {
    let (x, y, z) = (d.x.abs(), d.y.abs(), d.z.abs());
    let r = (1.0 - z).max(0.0).sqrt();
    let (a, b) = (x.max(y), x.min(y));
    let ratio = match a == 0.0 {
        true => 0.0,
        false => b / a,
    };
    // The angle from the nearer of the x and y axes, as a fraction of a quadrant.
    let phi = match x < y {
        true => 1.0 - ratio.atan() * FRAC_2_PI,
        false => ratio.atan() * FRAC_2_PI,
    };
    let (mut u, mut v) = (r - phi * r, phi * r);
    if d.z < 0.0 {
        (u, v) = (1.0 - v, 1.0 - u);
    }
    DVec2::new(0.5 * (u.copysign(d.x) + 1.0), 0.5 * (v.copysign(d.y) + 1.0))
}

/// The pixel (column, row) of an `n` × `n` image that point `p` of the unit square lies in,
/// as pbrt-v4's nearest lookup takes it: (⌊u n⌋, ⌊v n⌋), the square's far edges in the last.
pub fn pixel(p: DVec2, n: usize) -> (usize, usize) {
    let at = |t: f64| ((t * n as f64).max(0.0) as usize).min(n - 1);
    (at(p.x), at(p.y))
}

/// An `size` × `size` image laid over the sphere by the map, its rows read as stored or, with
/// `flip_v`, in the opposite order (v as 1 − v, which is y as −y: the image seen in a mirror).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Grid {
    /// Pixels along each side.
    pub size: usize,
    /// Whether the rows are read in the opposite order.
    pub flip_v: bool,
}

impl Grid {
    /// Direction `d` in the map's frame, and back: y negated where the rows are flipped.
    fn oriented(&self, d: DVec3) -> DVec3 {
        match self.flip_v {
            true => DVec3::new(d.x, -d.y, d.z),
            false => d,
        }
    }

    /// The row-major index of the pixel unit direction `d` lies in (nearest lookup).
    pub fn index(&self, d: DVec3) -> usize {
        let (x, y) = pixel(sphere_to_square(self.oriented(d)), self.size);
        y * self.size + x
    }

    /// The direction at the point `u` ∈ [0, 1)² of pixel `index` (uniform points of a pixel
    /// are uniform over the directions it covers: the map is equal-area).
    pub fn direction(&self, index: usize, u: [f64; 2]) -> DVec3 {
        let n = self.size as f64;
        let (x, y) = ((index % self.size) as f64, (index / self.size) as f64);
        self.oriented(square_to_sphere(DVec2::new((x + u[0]) / n, (y + u[1]) / n)))
    }

    /// The solid angle a pixel covers, 4π/N² sr.
    pub fn pixel_solid_angle(&self) -> f64 {
        4.0 * std::f64::consts::PI / (self.size * self.size) as f64
    }
}

/// The pixels of an image to be laid over the sphere by the map, row-major from the top, and
/// its side; or why it cannot be: it must be square, and of floating-point pixels (an EXR or
/// HDR file: its values are linear, where an 8-bit image holds sRGB levels).
pub fn square_pixels(image: &image::DynamicImage) -> Result<(usize, Vec<[f32; 3]>), String> {
    use image::DynamicImage as D;
    match image {
        D::ImageRgb32F(_) | D::ImageRgba32F(_) => {}
        _ => {
            return Err(
                "an image in the equal-area map must hold floating-point pixels (an EXR or HDR \
                 file): its values are linear, not sRGB levels"
                    .into(),
            )
        }
    }
    let rgb = image.to_rgb32f();
    let (w, h) = rgb.dimensions();
    if w != h || w == 0 {
        return Err(format!(
            "an image in the equal-area map is square; this one is {w} × {h}"
        ));
    }
    Ok((w as usize, rgb.pixels().map(|p| p.0).collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The map and its inverse undo each other (1e-12) over a grid of the square and at its
    /// centre, corners, edges' midpoints and diagonals; the directions are unit, +z at the
    /// centre, −z at the corners, the equator on the diamond.
    #[test]
    fn the_map_and_its_inverse_undo_each_other() {
        let n = 97;
        for i in 0..=n {
            for j in 0..=n {
                let p = DVec2::new(i as f64 / n as f64, j as f64 / n as f64);
                let d = square_to_sphere(p);
                assert!((d.length() - 1.0).abs() < 1e-12, "{p}: {d}");
                let back = square_to_sphere(sphere_to_square(d));
                assert!((back - d).length() < 1e-12, "{p}: {d} → {back}");
                let q = sphere_to_square(d);
                // The square's boundary is folded (each edge's halves meet on the southern
                // hemisphere): compare the inner points, where the map is one to one.
                if p.x > 0.0 && p.x < 1.0 && p.y > 0.0 && p.y < 1.0 {
                    assert!((q - p).length() < 1e-12, "{p} → {q}");
                }
            }
        }
        assert!((square_to_sphere(DVec2::splat(0.5)) - DVec3::Z).length() < 1e-15);
        assert!((square_to_sphere(DVec2::ZERO) + DVec3::Z).length() < 1e-15);
        assert!((square_to_sphere(DVec2::new(1.0, 0.5)) - DVec3::X).length() < 1e-15);
        assert!((square_to_sphere(DVec2::new(0.5, 1.0)) - DVec3::Y).length() < 1e-15);
        assert!((square_to_sphere(DVec2::new(0.75, 0.75)).z).abs() < 1e-15);
    }

    /// Equal area: directions drawn uniformly over the sphere (by z and the azimuth) fall into
    /// an 8 × 8 image's 64 pixels equally — χ² over 6.4·10⁵ directions below its 10⁻⁴
    /// quantile for 63 degrees of freedom (113.7; expected 63).
    #[test]
    fn every_pixel_covers_the_same_solid_angle() {
        let (n, draws) = (8, 640_000u64);
        let mut counts = vec![0u64; n * n];
        for k in 0..draws {
            let h = crate::sampling::mix(k);
            let u = (
                (h >> 32) as f64 / 2f64.powi(32),
                (h & 0xffff_ffff) as f64 / 2f64.powi(32),
            );
            let (x, y) = pixel(sphere_to_square(crate::sampling::uniform_sphere(u)), n);
            counts[y * n + x] += 1;
        }
        let expected = draws as f64 / (n * n) as f64;
        let chi2: f64 = counts
            .iter()
            .map(|&c| (c as f64 - expected).powi(2) / expected)
            .sum();
        assert!(chi2 < 113.7, "χ² {chi2}");
    }
}
