//! The film: one RGB plane per luminance component, written as a multi-layer EXR (one layer
//! per component, readable by standard OpenEXR tools) and a tone-mapped sRGB PNG preview.

use crate::color::{preview_byte, Rgb};
use crate::error::{Error, Result};
use exr::prelude::*;
use std::path::Path;

/// The components, in layer order. `beauty` is the sum of the others' radiance terms.
pub const LAYERS: [&str; 5] = ["beauty", "direct", "emitted", "albedo", "normal"];

/// Per-pixel averages of every layer.
#[derive(Clone, Debug)]
pub struct Film {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// One plane per entry of [`LAYERS`], row-major from the top, linear RGB.
    pub planes: Vec<Vec<[f32; 3]>>,
}

/// One camera sample's value for every layer.
pub type PixelSample = [Rgb; LAYERS.len()];

impl Film {
    /// A black film.
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            planes: vec![vec![[0.0; 3]; width * height]; LAYERS.len()],
        }
    }

    /// Stores the mean of `sum` over `count` samples at pixel (x, y).
    pub fn set_mean(&mut self, x: usize, y: usize, sum: &PixelSample, count: u32) {
        for (plane, value) in self.planes.iter_mut().zip(sum) {
            let m = *value / count as f64;
            plane[y * self.width + x] = [m.x as f32, m.y as f32, m.z as f32];
        }
    }

    /// The plane of a layer by name.
    pub fn layer(&self, name: &str) -> Option<&[[f32; 3]]> {
        LAYERS
            .iter()
            .position(|l| *l == name)
            .map(|i| self.planes[i].as_slice())
    }

    /// Writes every layer into one EXR file (32-bit float, channels R, G, B per layer).
    pub fn write_exr(&self, path: &Path) -> Result<()> {
        let size = Vec2(self.width, self.height);
        let layer = |i: usize| {
            let plane = &self.planes[i];
            let width = self.width;
            Layer::new(
                size,
                LayerAttributes::named(LAYERS[i]),
                Encoding::SMALL_LOSSLESS,
                SpecificChannels::rgb(move |pos: Vec2<usize>| {
                    let p = plane[pos.y() * width + pos.x()];
                    (p[0], p[1], p[2])
                }),
            )
        };
        let layers: Vec<_> = (0..LAYERS.len()).map(layer).collect();
        let image = Image::from_layers(
            ImageAttributes::new(IntegerBounds::from_dimensions(size)),
            layers,
        );
        image.write().to_file(path).map_err(|e| Error::Image {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }

    /// Writes the `beauty` layer as an 8-bit sRGB PNG (linear values clamped to [0, 1] after
    /// multiplying by `exposure`).
    pub fn write_png(&self, path: &Path, exposure: f32) -> Result<()> {
        let beauty = &self.planes[0];
        let img = image::RgbImage::from_fn(self.width as u32, self.height as u32, |x, y| {
            let p = beauty[y as usize * self.width + x as usize];
            image::Rgb(p.map(|c| preview_byte(c * exposure)))
        });
        crate::plot::save(&img, path)
    }
}

/// Reads one RGB layer of an EXR file (e.g. a reference image): (width, height, pixels).
pub fn read_exr_layer(path: &Path, name: Option<&str>) -> Result<(usize, usize, Vec<[f32; 3]>)> {
    let err = |message: String| Error::Image {
        path: path.to_path_buf(),
        message,
    };
    let image = read_all_rgba_layers_from_file(
        path,
        |res, _| (res.width(), vec![[0.0f32; 3]; res.width() * res.height()]),
        |(w, px), pos, (r, g, b, _a): (f32, f32, f32, f32)| px[pos.y() * *w + pos.x()] = [r, g, b],
    )
    .map_err(|e| err(e.to_string()))?;
    let layer = match name {
        None => image.layer_data.first(),
        Some(n) => image
            .layer_data
            .iter()
            .find(|l| l.attributes.layer_name.as_ref().is_some_and(|t| t == n)),
    }
    .ok_or_else(|| err(format!("no layer {}", name.unwrap_or("at all"))))?;
    let size = layer.size;
    Ok((
        size.width(),
        size.height(),
        layer.channel_data.pixels.1.clone(),
    ))
}
