//! The film: per pixel, the sums of camera samples' values for every layer an integrator
//! writes and the number of samples summed — raw sums, never means, so films of the same view
//! rendered apart (other passes, other machines) merge by adding ([`Film::merge`]). The sums
//! are fixed-point ([`Fixed`]): adding is exact, so a film merged from parts is bit for bit
//! the film of one run, in whatever order the parts come. A layer holds a plane of sums only
//! once a sample gives it a value other than zero: a layer nothing writes (the surfaces'
//! layers of a view of the sky) costs no memory and is not written. Developed, each layer is
//! its sum over its count, and `beauty` the sum of the radiance layers; written as a
//! multi-layer EXR (one RGB layer each, readable by standard OpenEXR tools) and a tone-mapped
//! sRGB PNG preview of `beauty`.
//!
//! Beside the layers the film sums, per pixel, the squares of each pass's `beauty` sum over
//! its samples (Σ_p S_p²/n_p): with the passes' count that gives the spread of the passes'
//! estimates, and so each pixel's standard error and the whole image's expected relative
//! error ([`Film::error`]; the EXR's `error` layer).

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
    /// A component S0–S3 of the Stokes vector of the radiance reaching the camera
    /// (W/(m²·sr), in the basis of [`crate::camera::Camera::stokes_axis`]), not summed into
    /// `beauty` (S0 is `beauty` itself).
    Stokes,
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

    /// A Stokes component named `name`.
    pub const fn stokes(name: &'static str) -> Layer {
        Layer {
            name: std::borrow::Cow::Borrowed(name),
            kind: LayerKind::Stokes,
        }
    }
}

/// The layers of the camera's Stokes vector, S0–S3, which a render measuring it
/// (`stokes`) writes after the integrator's.
pub const STOKES_LAYERS: [Layer; 4] = [
    Layer::stokes("S0"),
    Layer::stokes("S1"),
    Layer::stokes("S2"),
    Layer::stokes("S3"),
];

/// A film of a rectangle of a larger one, with the rectangle's top-left pixel there.
#[derive(Clone, Debug)]
pub struct Tile {
    /// Column of the top-left pixel.
    pub x0: usize,
    /// Row of the top-left pixel.
    pub y0: usize,
    /// The rectangle's film.
    pub film: Film,
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
    /// Per layer, per pixel (row-major from the top): the sum of the samples' values, RGB;
    /// empty for a layer no sample has written (its sums are all zero). One plane more than
    /// `layers`, last: the sum over passes of each pass's `beauty` sum squared over its
    /// sample count.
    sums: Vec<Vec<[Fixed; 3]>>,
    /// The passes summed (each adds every pixel once).
    pub passes: u32,
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
            sums: vec![Vec::new(); layers.len() + 1],
            passes: 0,
            counts: vec![0; width * height],
            rejected: 0,
        }
    }

    /// Adds `samples` samples at pixel (x, y) whose values sum to `values` (one per layer),
    /// each rounded to the nearest 2⁻⁶⁴; a value a fixed-point sum cannot hold adds nothing
    /// and is counted in [`Film::rejected`].
    pub fn add(&mut self, x: usize, y: usize, values: &[Rgb], samples: u64) {
        self.accumulate(x, y, values, samples, false);
    }

    /// Takes back exactly what [`Film::add`] with the same arguments added (a plane the add
    /// allocated stays, holding zeros: see [`Film::keep_planes`]).
    pub fn remove(&mut self, x: usize, y: usize, values: &[Rgb], samples: u64) {
        self.accumulate(x, y, values, samples, true);
    }

    fn accumulate(&mut self, x: usize, y: usize, values: &[Rgb], samples: u64, remove: bool) {
        let (i, pixels) = (y * self.width + x, self.width * self.height);
        let beauty = self
            .layers
            .iter()
            .zip(values)
            .filter(|(l, _)| l.kind == LayerKind::Radiance)
            .fold(Rgb::ZERO, |a, (_, v)| a + *v);
        let square = beauty * beauty / samples.max(1) as f64;
        let values = values.iter().chain(std::iter::once(&square));
        for (plane, v) in self.sums.iter_mut().zip(values) {
            if plane.is_empty() {
                if *v == Rgb::ZERO || remove {
                    continue;
                }
                *plane = vec![[Fixed::ZERO; 3]; pixels];
            }
            for (sum, c) in plane[i].iter_mut().zip(v.to_array()) {
                match (Fixed::from_f64(c), remove) {
                    (Some(f), false) => *sum += f,
                    (Some(f), true) => *sum += Fixed(-f.0),
                    (None, false) => self.rejected += 1,
                    (None, true) => self.rejected -= 1,
                }
            }
        }
        match remove {
            false => self.counts[i] += samples,
            true => self.counts[i] -= samples,
        }
    }

    /// Which of its planes hold sums (the layers', then the squares'), for
    /// [`Film::keep_planes`].
    pub fn planes_held(&self) -> Vec<bool> {
        self.sums.iter().map(|p| !p.is_empty()).collect()
    }

    /// Frees the planes not `held` (as [`Film::planes_held`] said before samples were added
    /// and then removed): they hold only zeros, and a film that never held them has none.
    pub fn keep_planes(&mut self, held: &[bool]) {
        for (plane, &keep) in self.sums.iter_mut().zip(held) {
            if !keep {
                debug_assert!(plane.iter().all(|s| *s == [Fixed::ZERO; 3]));
                *plane = Vec::new();
            }
        }
    }

    /// The whole `width` × `height` film of `passes` passes of `layers` from `tiles`,
    /// assembled plane by plane, each tile's plane freed once copied: at most one plane more
    /// than the tiles is held.
    pub fn from_tiles(
        width: usize,
        height: usize,
        layers: &[Layer],
        passes: u32,
        tiles: impl IntoIterator<Item = Tile>,
    ) -> Film {
        let mut whole = Film::new(width, height, layers);
        whole.passes = passes;
        let mut tiles: Vec<Tile> = tiles.into_iter().collect();
        for k in 0..whole.sums.len() {
            for t in &mut tiles {
                let plane = std::mem::take(&mut t.film.sums[k]);
                whole.paste_plane(k, &plane, t.film.width, t.film.height, t.x0, t.y0);
            }
        }
        for t in &tiles {
            whole.paste_counts(&t.film, t.x0, t.y0);
        }
        whole
    }

    /// The whole film of `passes` passes from `tiles`, copied (the tiles go on).
    pub fn assembled<'a>(
        width: usize,
        height: usize,
        layers: &[Layer],
        passes: u32,
        tiles: impl IntoIterator<Item = &'a Tile>,
    ) -> Film {
        let mut whole = Film::new(width, height, layers);
        whole.passes = passes;
        for t in tiles {
            whole.paste(&t.film, t.x0, t.y0);
        }
        whole
    }

    /// Whether its buffers match its size and layers (a film read from a file): the reason
    /// when not.
    pub fn check(&self) -> std::result::Result<(), String> {
        let pixels = self.width.checked_mul(self.height);
        if pixels.is_none_or(|p| {
            self.counts.len() != p || self.sums.iter().any(|s| !s.is_empty() && s.len() != p)
        }) || self.sums.len() != self.layers.len() + 1
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
            if a.is_empty() {
                a.clone_from(b);
                continue;
            }
            for (x, y) in a.iter_mut().zip(b) {
                add_rgb(x, y);
            }
        }
        for (a, b) in self.counts.iter_mut().zip(&other.counts) {
            *a += b;
        }
        self.rejected += other.rejected;
        self.passes = self.passes.saturating_add(other.passes);
        Ok(())
    }

    /// The `w` × `h` rectangle of this film with its top-left corner at (x0, y0), as a film of
    /// its own (the same passes; what was rejected is not said of a part).
    pub fn crop(&self, x0: usize, y0: usize, w: usize, h: usize) -> Film {
        let rows = |plane: &[[Fixed; 3]]| -> Vec<[Fixed; 3]> {
            (y0..y0 + h)
                .flat_map(|y| {
                    plane[y * self.width + x0..y * self.width + x0 + w]
                        .iter()
                        .copied()
                })
                .collect()
        };
        Film {
            width: w,
            height: h,
            layers: self.layers.clone(),
            sums: self
                .sums
                .iter()
                .map(|p| if p.is_empty() { Vec::new() } else { rows(p) })
                .collect(),
            passes: self.passes,
            counts: (y0..y0 + h)
                .flat_map(|y| {
                    self.counts[y * self.width + x0..y * self.width + x0 + w]
                        .iter()
                        .copied()
                })
                .collect(),
            rejected: 0,
        }
    }

    /// Adds `tile`, a film of a rectangle of this one, with its top-left corner at (x0, y0).
    pub fn paste(&mut self, tile: &Film, x0: usize, y0: usize) {
        for (k, plane) in tile.sums.iter().enumerate() {
            self.paste_plane(k, plane, tile.width, tile.height, x0, y0);
        }
        self.paste_counts(tile, x0, y0);
    }

    /// Adds plane `k` of a `w` × `h` tile at (x0, y0) (nothing for an empty plane).
    fn paste_plane(
        &mut self,
        k: usize,
        plane: &[[Fixed; 3]],
        w: usize,
        h: usize,
        x0: usize,
        y0: usize,
    ) {
        if plane.is_empty() {
            return;
        }
        let pixels = self.width * self.height;
        let whole = &mut self.sums[k];
        if whole.is_empty() {
            *whole = vec![[Fixed::ZERO; 3]; pixels];
        }
        for y in 0..h {
            for x in 0..w {
                add_rgb(
                    &mut whole[(y0 + y) * self.width + x0 + x],
                    &plane[y * w + x],
                );
            }
        }
    }

    /// Adds a tile's sample counts and rejected values.
    fn paste_counts(&mut self, tile: &Film, x0: usize, y0: usize) {
        for y in 0..tile.height {
            for x in 0..tile.width {
                self.counts[(y0 + y) * self.width + x0 + x] += tile.counts[y * tile.width + x];
            }
        }
        self.rejected += tile.rejected;
    }

    /// The names of the layers written — `beauty` first, then every layer a sample gave a
    /// value other than zero: the EXR's layers.
    pub fn names(&self) -> Vec<&str> {
        std::iter::once("beauty")
            .chain(
                self.layers
                    .iter()
                    .zip(&self.sums)
                    .filter(|(_, plane)| !plane.is_empty())
                    .map(|(l, _)| &*l.name),
            )
            .chain(self.error().is_some().then_some(ERROR))
            .collect()
    }

    /// Samples summed at each pixel.
    pub fn counts(&self) -> &[u64] {
        &self.counts
    }

    /// The developed pixel `i` of layer `name`: the sum over the count (`beauty`: of the
    /// radiance layers'), zero in a layer nothing wrote; None for a layer the film does not
    /// have.
    fn developer(&self, name: &str) -> Option<Box<dyn Fn(usize) -> [f32; 3] + Send + Sync + '_>> {
        if name == ERROR {
            let error = self.error()?;
            return Some(Box::new(move |i| {
                error.variance(i).map(|v| v.sqrt() as f32)
            }));
        }
        let planes: Vec<&[[Fixed; 3]]> = if name == "beauty" {
            self.layers
                .iter()
                .zip(&self.sums)
                .filter(|(l, _)| l.kind == LayerKind::Radiance)
                .map(|(_, p)| p.as_slice())
                .collect()
        } else {
            let k = self.layers.iter().position(|l| l.name == name)?;
            vec![self.sums[k].as_slice()]
        };
        let planes: Vec<&[[Fixed; 3]]> = planes.into_iter().filter(|p| !p.is_empty()).collect();
        Some(Box::new(move |i: usize| {
            let sum = planes.iter().fold(Rgb::ZERO, |a, p| a + rgb(&p[i]));
            (sum / self.counts[i].max(1) as f64).as_vec3().to_array()
        }))
    }

    /// The sums behind the image's relative RMSE over this film's pixels (see [`FilmError`]),
    /// to be added over the films of an image's parts: a black film's pixels count, with no
    /// error; none count before two passes.
    pub fn error_totals(&self) -> ErrorTotals {
        match self.error() {
            Some(e) => e.totals(),
            None if self.passes >= 2 => ErrorTotals {
                values: 3 * self.width * self.height,
                ..Default::default()
            },
            None => ErrorTotals::default(),
        }
    }

    /// How far the developed `beauty` may be from what infinitely many passes would give,
    /// judged by the spread of the passes' own estimates (so: the noise; a bias common to
    /// every pass is not seen); None before two passes, or for a black image (whose passes
    /// agree exactly).
    pub fn error(&self) -> Option<FilmError<'_>> {
        let squares = self.sums.last().filter(|p| !p.is_empty())?;
        if self.passes < 2 {
            return None;
        }
        let beauty: Vec<&[[Fixed; 3]]> = self
            .layers
            .iter()
            .zip(&self.sums)
            .filter(|(l, p)| l.kind == LayerKind::Radiance && !p.is_empty())
            .map(|(_, p)| p.as_slice())
            .collect();
        Some(FilmError {
            film: self,
            beauty,
            squares,
        })
    }

    /// The developed layer `name` (`beauty`: the sum of the radiance layers), row-major, linear
    /// RGB in f32 (zeros for a layer nothing wrote); None for a layer the film does not have.
    /// Developed in parallel, straight to f32 (an HD frame's layer is 2·10⁶ pixels of exact
    /// sums).
    pub fn layer(&self, name: &str) -> Option<Vec<[f32; 3]>> {
        let develop = self.developer(name)?;
        Some(
            (0..self.width * self.height)
                .into_par_iter()
                .map(develop)
                .collect(),
        )
    }

    /// Every written layer developed, in [`Film::names`] order.
    pub fn planes(&self) -> Vec<Vec<[f32; 3]>> {
        self.names()
            .iter()
            .map(|n| self.layer(n).expect("a layer of the film"))
            .collect()
    }

    /// Writes every written layer into one EXR file (32-bit float, channels R, G, B per
    /// layer), atomically (see [`crate::output::write_atomic`]); each pixel is developed as
    /// the encoder asks for it, so no developed copy of the film is held.
    pub fn write_exr(&self, path: &Path) -> Result<()> {
        let size = Vec2(self.width, self.height);
        let layers: Vec<_> = self
            .names()
            .into_iter()
            .map(|name| {
                let develop = self.developer(name).expect("a layer of the film");
                let width = self.width;
                exr::prelude::Layer::new(
                    size,
                    LayerAttributes::named(name),
                    Encoding::SMALL_LOSSLESS,
                    SpecificChannels::rgb(move |pos: Vec2<usize>| {
                        let p = develop(pos.y() * width + pos.x());
                        (p[0], p[1], p[2])
                    }),
                )
            })
            .collect();
        let mut image = Image::from_layers(
            ImageAttributes::new(IntegerBounds::from_dimensions(size)),
            layers,
        );
        // Every layer's header says who wrote it: a later render may replace the file.
        for layer in image.layer_data.iter_mut() {
            layer.attributes.software_name = Some(crate::output::signature().as_str().into());
        }
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

    /// Writes a false-colour picture of the linear polarization of the light its Stokes layers
    /// hold (each pixel's channels' mean: [`crate::polarization::preview::colour`]) to `path`,
    /// the radiance times `exposure` as in [`Film::write_png`]. An error where the film has no
    /// Stokes layers.
    pub fn write_polarization_png(&self, path: &Path, exposure: f32) -> Result<()> {
        let layers = STOKES_LAYERS.map(|l| self.layer(&l.name));
        let [Some(s0), Some(s1), Some(s2), Some(s3)] = layers else {
            return Err(Error::Usage(format!(
                "{}: the film holds no Stokes layers (render with stokes = true)",
                path.display()
            )));
        };
        let mean = |p: [f32; 3]| p.iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0;
        let img = image::RgbImage::from_fn(self.width as u32, self.height as u32, |x, y| {
            let i = y as usize * self.width + x as usize;
            let stokes = [mean(s0[i]), mean(s1[i]), mean(s2[i]), mean(s3[i])];
            image::Rgb(crate::polarization::preview::colour(stokes, exposure))
        });
        crate::plot::save(&img, path)
    }
}

/// The name of the EXR layer of each pixel's standard error.
pub const ERROR: &str = "error";

/// A film's estimate of its own error: the spread of its passes' `beauty` estimates.
///
/// Pass p's estimate of a pixel is L_p = S_p/n_p (its samples' sum over their count); the film
/// holds S = Σ S_p, n = Σ n_p and Q = Σ S_p²/n_p. With N passes of equal n_p the samples'
/// variance is estimated without bias by σ² = (Q − S²/n)/(N − 1), and the developed mean
/// M = S/n has variance σ²/n. Over the image, the expected relative RMSE (the measure
/// [`relative_rmse`] takes against a reference) is √(mean of σ²/n) / (mean of M), over
/// pixels and channels.
pub struct FilmError<'a> {
    film: &'a Film,
    beauty: Vec<&'a [[Fixed; 3]]>,
    squares: &'a [[Fixed; 3]],
}

impl FilmError<'_> {
    /// The expected relative RMSE of the developed `beauty` (see above).
    pub fn relative_rmse(&self) -> f64 {
        self.totals().relative_rmse()
    }

    /// The sums over its pixels behind [`FilmError::relative_rmse`].
    fn totals(&self) -> ErrorTotals {
        let pixels = self.film.width * self.film.height;
        let (mean, variance) = (0..pixels)
            .into_par_iter()
            .map(|i| {
                let (m, v) = self.moments(i);
                (m.iter().sum::<f64>(), v.iter().sum::<f64>())
            })
            .reduce(|| (0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1));
        ErrorTotals {
            mean,
            variance,
            values: 3 * pixels,
        }
    }

    /// Pixel `i`'s developed `beauty`, RGB.
    pub fn mean(&self, i: usize) -> [f64; 3] {
        self.moments(i).0
    }

    /// The variance of pixel `i`'s developed `beauty`, RGB (its standard error squared).
    pub fn variance(&self, i: usize) -> [f64; 3] {
        self.moments(i).1
    }

    /// Pixel `i`'s developed `beauty` and its variance (see above), RGB.
    fn moments(&self, i: usize) -> ([f64; 3], [f64; 3]) {
        let n = self.film.counts[i].max(1) as f64;
        let sum = self.beauty.iter().fold(Rgb::ZERO, |a, p| a + rgb(&p[i]));
        let q = rgb(&self.squares[i]);
        let dof = (self.film.passes - 1) as f64;
        let v = (q - sum * sum / n) / (dof * n);
        ((sum / n).to_array(), v.to_array().map(|c| c.max(0.0)))
    }
}

/// Over a set of pixel-channels: the sums of the developed values and of their variances, and
/// how many there are — what the image's relative RMSE is made of, summed over the films of
/// its parts (tiles) as over pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ErrorTotals {
    /// Σ developed value.
    pub mean: f64,
    /// Σ variance of the developed value.
    pub variance: f64,
    /// How many pixel-channels.
    pub values: usize,
}

impl ErrorTotals {
    /// √(mean variance) / (mean value).
    pub fn relative_rmse(&self) -> f64 {
        (self.variance / self.mean.powi(2) * self.values as f64).sqrt()
    }
}

impl std::ops::Add for ErrorTotals {
    type Output = ErrorTotals;
    fn add(self, o: ErrorTotals) -> ErrorTotals {
        ErrorTotals {
            mean: self.mean + o.mean,
            variance: self.variance + o.variance,
            values: self.values + o.values,
        }
    }
}

/// Fixed-point RGB as floating point.
fn rgb(c: &[Fixed; 3]) -> Rgb {
    Rgb::new(c[0].to_f64(), c[1].to_f64(), c[2].to_f64())
}

/// Adds fixed-point RGB `b` to `a`.
fn add_rgb(a: &mut [Fixed; 3], b: &[Fixed; 3]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x += *y;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pass added and taken back leaves the film exactly as it was — sums, squares, counts,
    /// rejected values, and no plane the pass alone allocated.
    #[test]
    fn a_pass_taken_back_leaves_the_film_as_it_was() {
        let layers = [Layer::radiance("direct"), Layer::radiance("caustic")];
        let mut film = Film::new(3, 2, &layers);
        let before_values = [Rgb::new(0.25, 1.0 / 3.0, 7.0), Rgb::ZERO];
        for i in 0..6 {
            film.add(i % 3, i / 3, &before_values, 4);
        }
        film.passes = 1;
        let before = film.clone();
        let held = film.planes_held();
        let pass = [
            [Rgb::new(0.1, 0.2, 1e-30), Rgb::new(0.5, 0.0, 3.0)],
            [Rgb::new(f64::NAN, 1.0, 2.0), Rgb::new(1e300, 0.0, 0.0)],
        ];
        for i in 0..6 {
            film.add(i % 3, i / 3, &pass[i % 2], 4);
        }
        assert_ne!(film, before);
        assert!(film.rejected() > 0 && film.planes_held() != held);
        for i in 0..6 {
            film.remove(i % 3, i / 3, &pass[i % 2], 4);
        }
        film.keep_planes(&held);
        assert_eq!(film, before);
    }
}
