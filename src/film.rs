//! The film: per pixel, the sums of camera samples' values for every layer an integrator
//! writes and the number of samples summed — raw sums, never means, so films of the same view
//! rendered apart (other passes, other machines) merge by adding ([`Film::merge`]). The sums
//! are fixed-point ([`Fixed`]): adding is exact, so a film merged from parts is bit for bit
//! the film of one run, in whatever order the parts come. Developed,
//! each layer is its sum over its count, and `beauty` the sum of the radiance layers; written
//! as a multi-layer EXR (one RGB layer each, readable by standard OpenEXR tools) and a
//! tone-mapped sRGB PNG preview of `beauty`.

use crate::color::{preview_byte, Rgb};
use crate::error::{Error, Result};
use crate::exact::Fixed;
use exr::prelude::*;
use rayon::prelude::*;
use std::path::Path;

/// What a layer holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum LayerKind {
    /// A part of the radiance reaching the camera (W/(m²·sr)); `beauty` is their sum.
    Radiance,
    /// A description of what the camera sees (albedo, normal), not summed into `beauty`.
    Aux,
}

/// One layer an integrator writes besides `beauty`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Layer {
    /// Its name in the EXR.
    pub name: std::borrow::Cow<'static, str>,
    /// What it holds.
    pub kind: LayerKind,
}

impl Layer {
    /// A part of the radiance named `name`.
    pub const fn radiance(name: &'static str) -> Layer {
        Layer {
            name: std::borrow::Cow::Borrowed(name),
            kind: LayerKind::Radiance,
        }
    }

    /// A description of what the camera sees, named `name`.
    pub const fn aux(name: &'static str) -> Layer {
        Layer {
            name: std::borrow::Cow::Borrowed(name),
            kind: LayerKind::Aux,
        }
    }
}

/// Sums of samples per layer and pixel, and the samples per pixel.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Film {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The layers summed (`beauty` is developed from them).
    pub layers: Vec<Layer>,
    /// Per layer, per pixel (row-major from the top): the sum of the samples' values, RGB.
    sums: Vec<Vec<[Fixed; 3]>>,
    /// Per pixel: the number of samples summed.
    counts: Vec<u64>,
    /// Pixel values left out because a fixed-point sum cannot hold them (not finite, or of
    /// magnitude ≥ [`Fixed::LIMIT`]): a render reports them.
    rejected: u64,
}

impl Film {
    /// An empty film.
    pub fn new(width: usize, height: usize, layers: &[Layer]) -> Self {
        Self {
            width,
            height,
            layers: layers.to_vec(),
            sums: vec![vec![[Fixed::ZERO; 3]; width * height]; layers.len()],
            counts: vec![0; width * height],
            rejected: 0,
        }
    }

    /// Adds `samples` samples at pixel (x, y) whose values sum to `values` (one per layer),
    /// each rounded to the nearest 2⁻⁶⁴; a value a fixed-point sum cannot hold adds nothing
    /// and is counted in [`Film::rejected`].
    pub fn add(&mut self, x: usize, y: usize, values: &[Rgb], samples: u64) {
        let i = y * self.width + x;
        for (plane, v) in self.sums.iter_mut().zip(values) {
            for (sum, c) in plane[i].iter_mut().zip(v.to_array()) {
                match Fixed::from_f64(c) {
                    Some(f) => *sum += f,
                    None => self.rejected += 1,
                }
            }
        }
        self.counts[i] += samples;
    }

    /// Whether its buffers match its size and layers (a film read from a file): the reason
    /// when not.
    pub fn check(&self) -> std::result::Result<(), String> {
        let pixels = self.width.checked_mul(self.height);
        if pixels.is_none_or(|p| self.counts.len() != p || self.sums.iter().any(|s| s.len() != p))
            || self.sums.len() != self.layers.len()
        {
            return Err(format!(
                "a {}×{} film of {} layers whose buffers do not match",
                self.width,
                self.height,
                self.layers.len()
            ));
        }
        Ok(())
    }

    /// Pixel values left out (see [`Film::add`]).
    pub fn rejected(&self) -> u64 {
        self.rejected
    }

    /// Adds another film of the same view (size and layers): its samples join these.
    pub fn merge(&mut self, other: &Film) -> Result<()> {
        if (other.width, other.height) != (self.width, self.height) || other.layers != self.layers {
            return Err(Error::Usage(format!(
                "cannot merge a {}×{} film of layers {:?} into a {}×{} film of layers {:?}",
                other.width,
                other.height,
                other.names(),
                self.width,
                self.height,
                self.names()
            )));
        }
        for (a, b) in self.sums.iter_mut().zip(&other.sums) {
            for (x, y) in a.iter_mut().zip(b) {
                add_rgb(x, y);
            }
        }
        for (a, b) in self.counts.iter_mut().zip(&other.counts) {
            *a += b;
        }
        self.rejected += other.rejected;
        Ok(())
    }

    /// Empties it: every sum and count 0, nothing rejected (its buffers kept for reuse).
    pub fn clear(&mut self) {
        for plane in &mut self.sums {
            plane.fill([Fixed::ZERO; 3]);
        }
        self.counts.fill(0);
        self.rejected = 0;
    }

    /// Adds `tile`, a film of a rectangle of this one, with its top-left corner at (x0, y0).
    pub fn paste(&mut self, tile: &Film, x0: usize, y0: usize) {
        for y in 0..tile.height {
            for x in 0..tile.width {
                let (i, j) = (y * tile.width + x, (y0 + y) * self.width + x0 + x);
                for (a, b) in self.sums.iter_mut().zip(&tile.sums) {
                    add_rgb(&mut a[j], &b[i]);
                }
                self.counts[j] += tile.counts[i];
            }
        }
        self.rejected += tile.rejected;
    }

    /// The layers' names, `beauty` first.
    pub fn names(&self) -> Vec<&str> {
        std::iter::once("beauty")
            .chain(self.layers.iter().map(|l| &*l.name))
            .collect()
    }

    /// Samples summed at each pixel.
    pub fn counts(&self) -> &[u64] {
        &self.counts
    }

    /// The developed layer `name` (`beauty`: the sum of the radiance layers), row-major, linear
    /// RGB in f32; None for a layer the film does not hold. Developed in parallel, straight to
    /// f32 (an HD frame's layer is 2·10⁶ pixels of exact sums).
    pub fn layer(&self, name: &str) -> Option<Vec<[f32; 3]>> {
        let mean = |plane: &[[Fixed; 3]], i: usize| {
            Rgb::new(
                plane[i][0].to_f64(),
                plane[i][1].to_f64(),
                plane[i][2].to_f64(),
            ) / self.counts[i].max(1) as f64
        };
        let pixels = (0..self.width * self.height).into_par_iter();
        let f32s = |v: Rgb| v.as_vec3().to_array();
        Some(if name == "beauty" {
            pixels
                .map(|i| {
                    f32s(
                        self.layers
                            .iter()
                            .zip(&self.sums)
                            .filter(|(l, _)| l.kind == LayerKind::Radiance)
                            .map(|(_, p)| mean(p, i))
                            .fold(Rgb::ZERO, |a, b| a + b),
                    )
                })
                .collect()
        } else {
            let k = self.layers.iter().position(|l| l.name == name)?;
            pixels.map(|i| f32s(mean(&self.sums[k], i))).collect()
        })
    }

    /// Every developed layer, in [`Film::names`] order.
    pub fn planes(&self) -> Vec<Vec<[f32; 3]>> {
        self.names()
            .iter()
            .map(|n| self.layer(n).expect("a layer of the film"))
            .collect()
    }

    /// Writes every developed layer into one EXR file (32-bit float, channels R, G, B per
    /// layer), atomically (see [`crate::output::write_atomic`]).
    pub fn write_exr(&self, path: &Path) -> Result<()> {
        let size = Vec2(self.width, self.height);
        let names = self.names();
        let planes = self.planes();
        let layers: Vec<_> = names
            .iter()
            .zip(&planes)
            .map(|(name, plane)| {
                let width = self.width;
                exr::prelude::Layer::new(
                    size,
                    LayerAttributes::named(*name),
                    Encoding::SMALL_LOSSLESS,
                    SpecificChannels::rgb(move |pos: Vec2<usize>| {
                        let p = plane[pos.y() * width + pos.x()];
                        (p[0], p[1], p[2])
                    }),
                )
            })
            .collect();
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
        let beauty = self.layer("beauty").expect("every film has beauty");
        let img = image::RgbImage::from_fn(self.width as u32, self.height as u32, |x, y| {
            let p = beauty[y as usize * self.width + x as usize];
            image::Rgb(p.map(|c| preview_byte(c * exposure)))
        });
        crate::plot::save(&img, path)
    }
}

/// Adds fixed-point RGB `b` to `a`.
fn add_rgb(a: &mut [Fixed; 3], b: &[Fixed; 3]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x += *y;
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
