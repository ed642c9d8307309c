//! The film: one RGB plane per luminance component, written as a multi-layer EXR (one layer
//! per component, readable by standard OpenEXR tools) and a tone-mapped sRGB PNG preview.

use crate::color::{preview_byte, Rgb};
use crate::error::{Error, Result};
use exr::prelude::*;
use std::path::Path;

/// The layers, in order. `beauty` = direct + caustic + secondary + emitted (radiance,
/// W/(m²·sr)); `albedo` and `normal` describe the first diffuse surface seen.
pub const LAYERS: [&str; 7] = [
    "beauty",
    "direct",
    "caustic",
    "secondary",
    "emitted",
    "albedo",
    "normal",
];

/// A layer (film plane) by its index in [`LAYERS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plane {
    /// The sum of the radiance components.
    Beauty,
    /// Light sampling with a straight shadow connection.
    Direct,
    /// The caustic map's estimate.
    Caustic,
    /// The final gather over the global map.
    Secondary,
    /// Emission and environment seen directly or along the camera's specular chain.
    Emitted,
    /// Albedo of the first diffuse surface.
    Albedo,
    /// Normal of the first diffuse surface (facing the camera path).
    Normal,
}

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

    /// Stores every layer's value at pixel (x, y).
    pub fn set(&mut self, x: usize, y: usize, value: &PixelSample) {
        for (plane, v) in self.planes.iter_mut().zip(value) {
            plane[y * self.width + x] = v.as_vec3().to_array();
        }
    }

    /// The plane of a layer by name.
    pub fn layer(&self, name: &str) -> Option<&[[f32; 3]]> {
        LAYERS
            .iter()
            .position(|l| *l == name)
            .map(|i| self.planes[i].as_slice())
    }

    /// Writes every layer into one EXR file (32-bit float, channels R, G, B per layer),
    /// atomically (see [`crate::output::write_atomic`]).
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
        crate::output::write_atomic(path, |tmp| {
            image.write().to_file(tmp).map_err(|e| Error::Image {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
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

/// Averages `factor` × `factor` pixel squares of a `width` × `height` plane (box filter), as
/// needed to compare a smaller render with a reference; the sizes must divide.
pub fn downsample(plane: &[[f32; 3]], width: usize, height: usize, factor: usize) -> Vec<[f32; 3]> {
    let (w, h) = (width / factor, height / factor);
    let mut out = vec![[0.0f32; 3]; w * h];
    let scale = 1.0 / (factor * factor) as f32;
    for y in 0..h * factor {
        for x in 0..w * factor {
            let o = &mut out[(y / factor) * w + x / factor];
            for c in 0..3 {
                o[c] += plane[y * width + x][c] * scale;
            }
        }
    }
    out
}

/// How a render compares with a reference of the same size: the ratio of their means over the
/// whole image (all channels) and the ratios over `block` × `block` pixel blocks, row by row.
/// Blocks whose reference mean is zero are left out.
pub fn mean_ratios(
    render: &[[f32; 3]],
    reference: &[[f32; 3]],
    width: usize,
    block: usize,
) -> (f64, Vec<f64>) {
    let sum = |p: &[f32; 3]| p.iter().map(|&c| c as f64).sum::<f64>();
    let total = |img: &[[f32; 3]]| img.iter().map(sum).sum::<f64>();
    let overall = total(render) / total(reference);
    let height = render.len() / width;
    let mut blocks = Vec::new();
    for by in 0..height / block {
        for bx in 0..width / block {
            let (mut a, mut b) = (0.0, 0.0);
            for y in by * block..(by + 1) * block {
                for x in bx * block..(bx + 1) * block {
                    a += sum(&render[y * width + x]);
                    b += sum(&reference[y * width + x]);
                }
            }
            if b > 0.0 {
                blocks.push(a / b);
            }
        }
    }
    (overall, blocks)
}
