//! A luminaire's intensity as an image over the sphere in the equal-area octahedral map
//! ([`crate::equal_area`]), as pbrt-v4's goniometric light reads it: a square image whose
//! pixel holds the intensity toward the directions it covers (the mean of its R, G and B,
//! read by nearest pixel). The image's +z (its centre) is the luminaire's zenith, opposite its
//! nadir; its +x the luminaire's C = 0 direction, +y its C = 90° direction (C = 270° with the
//! rows flipped).

use crate::equal_area::{square_pixels, Grid};
use crate::sampling::Discrete;
use glam::DVec3;

/// An intensity image: N × N values, row-major from row 0 (the image's top row), each the
/// intensity (in the image's unit) toward the 4π/N² sr its pixel covers.
#[derive(Clone, Debug, PartialEq)]
pub struct IntensityImage {
    /// How the pixels lie over the sphere.
    grid: Grid,
    /// The pixels' intensities, ≥ 0.
    values: Vec<f64>,
    /// The pixels weighed by their intensity, for drawing photon directions; None when the
    /// image is black.
    pixels: Option<Discrete>,
}

impl IntensityImage {
    /// The image of `values` (`size` × `size`, row-major from the top row; finite, ≥ 0).
    pub fn new(size: usize, values: Vec<f64>) -> Self {
        debug_assert_eq!(values.len(), size * size);
        let pixels = Discrete::new(&values);
        Self {
            grid: Grid {
                size,
                flip_v: false,
            },
            values,
            pixels,
        }
    }

    /// The same image with its rows read in the opposite order (v as 1 − v), or not.
    pub fn with_flip_v(self, flip_v: bool) -> Self {
        Self {
            grid: Grid {
                flip_v,
                ..self.grid
            },
            ..self
        }
    }

    /// The image read from `image` ([`square_pixels`]), each pixel finite and ≥ 0; a pixel's
    /// intensity is the mean of its R, G and B, as pbrt-v4 takes it.
    pub fn from_image(image: &image::DynamicImage) -> Result<Self, String> {
        let (size, pixels) = square_pixels(image)?;
        let mut values = Vec::with_capacity(pixels.len());
        for (i, p) in pixels.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite() && *c >= 0.0) {
                return Err(format!(
                    "the pixel (x {}, y {}) is {p:?}: intensities are finite and ≥ 0",
                    i % size,
                    i / size
                ));
            }
            values.push(p.iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0);
        }
        Ok(Self::new(size, values))
    }

    /// The intensity toward unit direction `d` of the image's frame.
    pub fn intensity(&self, d: DVec3) -> f64 {
        self.values[self.grid.index(d)]
    }

    /// The largest intensity.
    pub fn peak(&self) -> f64 {
        self.values.iter().copied().fold(0.0, f64::max)
    }

    /// The power ∫ I dω, exactly: the pixels' sum times a pixel's solid angle.
    pub fn power(&self) -> f64 {
        self.values.iter().sum::<f64>() * self.grid.pixel_solid_angle()
    }

    /// A unit direction of the image's frame drawn for three uniform numbers, and its
    /// solid-angle density: a pixel by its intensity, then a uniform point of it, which is
    /// uniform in solid angle over the directions it covers (the map is equal-area). A photon
    /// sent along it carries I/pdf, the image's power. None when the image is black.
    pub fn draw(&self, u: [f64; 3]) -> Option<(DVec3, f64)> {
        let pick = self.pixels.as_ref()?.pick(u[0]);
        Some((
            self.grid.direction(pick.index, [u[1], u[2]]),
            pick.probability / self.grid.pixel_solid_angle(),
        ))
    }
}
