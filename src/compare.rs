//! Images compared with a reference: an EXR layer read back, box downsampling, and a render's
//! relative RMSE and mean ratios against a reference of the same size — what the validation
//! tests, the studies and the peer-renderer comparisons measure with.

use crate::error::{Error, Result};
use exr::prelude::*;
use std::path::Path;

/// One RGB layer of an image: `width` × `height` pixels, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// Pixels across.
    pub width: usize,
    /// Pixels down.
    pub height: usize,
    /// Linear RGB per pixel.
    pub pixels: Vec<[f32; 3]>,
}

/// Reads one RGB layer of an EXR file (e.g. a reference image): `name`, or the first.
pub fn read_exr_layer(path: &Path, name: Option<&str>) -> Result<Plane> {
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
    Ok(Plane {
        width: layer.size.width(),
        height: layer.size.height(),
        pixels: layer.channel_data.pixels.1.clone(),
    })
}

impl Plane {
    /// Its `factor` × `factor` pixel squares averaged (box filter), as needed to compare a
    /// smaller render with a reference; a remainder of rows or columns is left out.
    pub fn downsample(&self, factor: usize) -> Plane {
        let (w, h) = (self.width / factor, self.height / factor);
        let mut pixels = vec![[0.0f32; 3]; w * h];
        let scale = 1.0 / (factor * factor) as f32;
        for y in 0..h * factor {
            for x in 0..w * factor {
                let o = &mut pixels[(y / factor) * w + x / factor];
                for (o, p) in o.iter_mut().zip(self.pixels[y * self.width + x]) {
                    *o += p * scale;
                }
            }
        }
        Plane {
            width: w,
            height: h,
            pixels,
        }
    }
}

/// The root-mean-square difference of a render from a reference of the same size, per pixel
/// and channel, relative to the reference's mean.
pub fn relative_rmse(render: &[[f32; 3]], reference: &[[f32; 3]]) -> f64 {
    let pairs = || {
        render
            .iter()
            .zip(reference)
            .flat_map(|(a, b)| (0..3).map(|c| (a[c] as f64, b[c] as f64)))
    };
    let channels = (3 * reference.len()) as f64;
    let mean = pairs().map(|(_, b)| b).sum::<f64>() / channels;
    let squares = pairs().map(|(a, b)| (a - b).powi(2)).sum::<f64>();
    (squares / channels).sqrt() / mean
}

/// How a render's means compare with a reference's of the same size.
#[derive(Clone, Debug, PartialEq)]
pub struct MeanRatios {
    /// The ratio of their means over the whole image (all channels).
    pub overall: f64,
    /// The ratios over `block` × `block` pixel blocks, row by row; blocks whose reference
    /// mean is zero are left out.
    pub blocks: Vec<f64>,
}

/// The ratios of a render's means to a reference's of the same size, `width` pixels wide: over
/// the whole image and over `block` × `block` pixel blocks.
pub fn mean_ratios(
    render: &[[f32; 3]],
    reference: &[[f32; 3]],
    width: usize,
    block: usize,
) -> MeanRatios {
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
    MeanRatios { overall, blocks }
}
