//! A luminaire's intensity as an image over the sphere in the equal-area octahedral map
//! ([`crate::equal_area`]), as pbrt-v4's goniometric light reads it: a square image whose
//! pixel holds the intensity toward the directions it covers (the mean of its R, G and B,
//! read by nearest pixel). The image's +z (its centre) is the luminaire's zenith, opposite its
//! nadir; its +x the luminaire's C = 0 direction, +y its C = 90° direction (C = 270° with the
//! rows flipped).

use crate::equal_area::{pixel, sphere_to_square, square_to_sphere};
use crate::sampling::Discrete;
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// An intensity image: N × N values, row-major from row 0 (the image's top row), each the
/// intensity (in the image's unit) toward the 4π/N² sr its pixel covers.
#[derive(Clone, Debug, PartialEq)]
pub struct IntensityImage {
    /// N.
    size: usize,
    /// The pixels' intensities, ≥ 0.
    values: Vec<f64>,
    /// The pixels weighed by their intensity, for drawing photon directions; None when the
    /// image is black.
    pixels: Option<Discrete>,
    /// Whether the rows are read in the opposite order, v as 1 − v: the image seen in a
    /// mirror, its +y along C = 270°.
    flip_v: bool,
}

impl IntensityImage {
    /// The image of `values` (`size` × `size`, row-major from the top row; finite, ≥ 0).
    pub fn new(size: usize, values: Vec<f64>) -> Self {
        debug_assert_eq!(values.len(), size * size);
        let pixels = Discrete::new(&values);
        Self {
            size,
            values,
            pixels,
            flip_v: false,
        }
    }

    /// The same image with its rows read in the opposite order (v as 1 − v), or not.
    pub fn with_flip_v(self, flip_v: bool) -> Self {
        Self { flip_v, ..self }
    }

    /// Direction `d` of the luminaire's frame in the image's, and back: y negated where the
    /// rows are flipped (v ↦ 1 − v is y ↦ −y in the map).
    fn oriented(&self, d: DVec3) -> DVec3 {
        match self.flip_v {
            true => DVec3::new(d.x, -d.y, d.z),
            false => d,
        }
    }

    /// The image read from `image`: square, of floating-point pixels (EXR, HDR: intensities
    /// are linear, so an 8-bit image, sRGB-encoded, is refused), each finite and ≥ 0; a
    /// pixel's intensity is the mean of its R, G and B, as pbrt-v4 takes it.
    pub fn from_image(image: &image::DynamicImage) -> Result<Self, String> {
        use image::DynamicImage as D;
        match image {
            D::ImageRgb32F(_) | D::ImageRgba32F(_) => {}
            _ => {
                return Err(
                    "an intensity image must hold floating-point pixels (an EXR or HDR file): \
                     its values are linear intensities, not sRGB levels"
                        .into(),
                )
            }
        }
        let rgb = image.to_rgb32f();
        let (w, h) = rgb.dimensions();
        if w != h || w == 0 {
            return Err(format!(
                "an intensity image in the equal-area map is square; this one is {w} × {h}"
            ));
        }
        let mut values = Vec::with_capacity((w * h) as usize);
        for (x, y, p) in rgb.enumerate_pixels() {
            if !p.0.iter().all(|c| c.is_finite() && *c >= 0.0) {
                return Err(format!(
                    "the pixel (x {x}, y {y}) is {:?}: intensities are finite and ≥ 0",
                    p.0
                ));
            }
            values.push(p.0.iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0);
        }
        Ok(Self::new(w as usize, values))
    }

    /// The intensity toward unit direction `d` of the image's frame.
    pub fn intensity(&self, d: DVec3) -> f64 {
        let (x, y) = pixel(sphere_to_square(self.oriented(d)), self.size);
        self.values[y * self.size + x]
    }

    /// The solid angle of one pixel, 4π/N² sr.
    fn pixel_solid_angle(&self) -> f64 {
        4.0 * PI / (self.size * self.size) as f64
    }

    /// The largest intensity.
    pub fn peak(&self) -> f64 {
        self.values.iter().copied().fold(0.0, f64::max)
    }

    /// The power ∫ I dω, exactly: the pixels' sum times a pixel's solid angle.
    pub fn power(&self) -> f64 {
        self.values.iter().sum::<f64>() * self.pixel_solid_angle()
    }

    /// The same image with every intensity times `factor` (≥ 0).
    pub fn scaled(self, factor: f64) -> Self {
        Self::new(
            self.size,
            self.values.into_iter().map(|v| v * factor).collect(),
        )
        .with_flip_v(self.flip_v)
    }

    /// A unit direction of the image's frame drawn for three uniform numbers, and its
    /// solid-angle density: a pixel by its intensity, then a uniform point of it, which is
    /// uniform in solid angle over the directions it covers (the map is equal-area). A photon
    /// sent along it carries I/pdf, the image's power. None when the image is black.
    pub fn draw(&self, u: [f64; 3]) -> Option<(DVec3, f64)> {
        let pick = self.pixels.as_ref()?.pick(u[0]);
        let n = self.size as f64;
        let (x, y) = (
            (pick.index % self.size) as f64,
            (pick.index / self.size) as f64,
        );
        let p = DVec2::new((x + u[1]) / n, (y + u[2]) / n);
        Some((
            self.oriented(square_to_sphere(p)),
            pick.probability / self.pixel_solid_angle(),
        ))
    }
}
