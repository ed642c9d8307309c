//! Textures: an 8- or 16-bit sRGB image (PNG, JPEG, …) decoded to linear RGB, looked up by
//! surface coordinates (u, v), bilinear or nearest, repeating, clamped or mirrored beyond
//! [0, 1] ([`Filter`], [`Wrap`]); or a checkerboard. Convention: u runs left to right along the image's rows, v from its bottom
//! row up — the image's own coordinates are (u, 1 − v), its top row at 0 — placed on the
//! surface by an affine map of those coordinates ([`UvMap`], the identity by default).

use crate::color::Rgb;
use glam::DVec2;
use std::path::Path;

/// A texture in linear RGB: a pattern over image coordinates, placed on the surface's (u, v)
/// by an affine map.
#[derive(Clone, PartialEq)]
pub struct Texture {
    /// What it shows.
    pub pattern: Pattern,
    /// Where: the image coordinates at a surface's (u, v).
    pub to_uv: UvMap,
}

/// What a texture shows over image coordinates (x, y): x across the image's rows, y down from
/// its top row, the image within [0, 1]² (beyond it as its [`Wrap`] says), the checkerboard's
/// cells of side ½.
#[derive(Clone, PartialEq)]
pub enum Pattern {
    /// An image.
    Image {
        /// Width in texels.
        width: usize,
        /// Height in texels.
        height: usize,
        /// Row-major from the top row.
        texels: Vec<[f32; 3]>,
        /// How it is read between its texels.
        filter: Filter,
        /// How it is read beyond its edges.
        wrap: Wrap,
    },
    /// Two colours in a checkerboard: `colours[0]` where x and y are both in the first half
    /// of their unit cells or both in the second (Mitsuba 3's `checkerboard`), `colours[1]`
    /// elsewhere.
    Checkerboard {
        /// The two colours, linear RGB.
        colours: [Rgb; 2],
    },
}

/// How an image is read between its texels (Mitsuba 3's `filter_type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// Bilinear between the texel centres (x·width − ½ and y·height − ½ between two).
    Bilinear,
    /// The texel the point lies in.
    Nearest,
}

/// How an image is read beyond its edges (Mitsuba 3's `wrap_mode`, by texel index).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    /// Periodically.
    Repeat,
    /// The edge texels extend outward.
    Clamp,
    /// Reflected at every edge: periodic over twice the image.
    Mirror,
}

impl Wrap {
    /// The texel index an index `i` along an axis of `n` texels reads.
    fn index(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        let i = match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => match i.rem_euclid(2 * n) {
                m if m < n => m,
                m => 2 * n - 1 - m,
            },
        };
        i as usize
    }
}

/// The affine map from a surface's (u, v) to a texture's image coordinates:
/// (x, y) = M·(u, 1 − v) + c, rows [a, b, c] of x = a u + b (1 − v) + c (Mitsuba 3's `to_uv`
/// in grinlight's v, which runs the other way); the identity by default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvMap(pub [[f64; 3]; 2]);

impl Default for UvMap {
    fn default() -> Self {
        Self([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    }
}

impl UvMap {
    /// The image coordinates at surface coordinates `uv`.
    pub fn image_point(&self, uv: DVec2) -> DVec2 {
        let (u, v) = (uv.x, 1.0 - uv.y);
        let at = |r: [f64; 3]| r[0] * u + r[1] * v + r[2];
        DVec2::new(at(self.0[0]), at(self.0[1]))
    }
}

/// The linear value of an sRGB-encoded channel in [0, 1].
pub fn srgb_decode(x: f32) -> f32 {
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

impl Texture {
    /// The image at `path`, read with `filter` and `wrap`, or why not (the message names the
    /// file).
    pub fn load(path: &Path, filter: Filter, wrap: Wrap) -> Result<Self, String> {
        let img = open_image(path)?.to_rgb32f();
        let (width, height) = (img.width() as usize, img.height() as usize);
        if width == 0 || height == 0 {
            return Err(format!("{}: the image is empty", path.display()));
        }
        let texels = img.pixels().map(|p| p.0.map(srgb_decode)).collect();
        Ok(Self::from_pattern(Pattern::Image {
            width,
            height,
            texels,
            filter,
            wrap,
        }))
    }

    /// `pattern` on the surface's (u, v) as they are (the identity map).
    pub fn from_pattern(pattern: Pattern) -> Self {
        Self {
            pattern,
            to_uv: UvMap::default(),
        }
    }

    /// A texture from linear texels, row-major from the top. Panics unless there are
    /// `width` × `height` of them (a caller's error, not a user's: files go through [`Self::load`]).
    pub fn from_texels(width: usize, height: usize, texels: Vec<[f32; 3]>) -> Self {
        assert_eq!(texels.len(), width * height, "texel count");
        Self::from_pattern(Pattern::Image {
            width,
            height,
            texels,
            filter: Filter::Bilinear,
            wrap: Wrap::Repeat,
        })
    }

    /// The linear colour at surface coordinates `uv`: an image's bilinear between texel
    /// centres, repeating (a non-finite `uv`, which no sound surface gives, reads (0, 0)
    /// rather than spreading NaN).
    pub fn at(&self, uv: DVec2) -> Rgb {
        let uv = if uv.is_finite() { uv } else { DVec2::ZERO };
        let p = self.to_uv.image_point(uv);
        match &self.pattern {
            Pattern::Image {
                width,
                height,
                texels,
                filter,
                wrap,
            } => {
                let texel = |i: f64, j: f64| {
                    let i = wrap.index(i as i64, *width);
                    let j = wrap.index(j as i64, *height);
                    let t = texels[j * width + i];
                    Rgb::new(t[0] as f64, t[1] as f64, t[2] as f64)
                };
                // A repeating image is read within its first period (the same texels).
                let (px, py) = match wrap {
                    Wrap::Repeat => (p.x.rem_euclid(1.0), p.y.rem_euclid(1.0)),
                    Wrap::Clamp | Wrap::Mirror => (p.x, p.y),
                };
                let (x, y) = (px * *width as f64, py * *height as f64);
                match filter {
                    Filter::Nearest => texel(x.floor(), y.floor()),
                    Filter::Bilinear => {
                        let (x, y) = (x - 0.5, y - 0.5);
                        let (x0, y0) = (x.floor(), y.floor());
                        let (fx, fy) = (x - x0, y - y0);
                        texel(x0, y0) * ((1.0 - fx) * (1.0 - fy))
                            + texel(x0 + 1.0, y0) * (fx * (1.0 - fy))
                            + texel(x0, y0 + 1.0) * ((1.0 - fx) * fy)
                            + texel(x0 + 1.0, y0 + 1.0) * (fx * fy)
                    }
                }
            }
            Pattern::Checkerboard { colours } => {
                let second_half = |x: f64| x - x.floor() > 0.5;
                match second_half(p.x) == second_half(p.y) {
                    true => colours[0],
                    false => colours[1],
                }
            }
        }
    }
}

impl std::fmt::Debug for Texture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.pattern {
            Pattern::Image { width, height, .. } => write!(f, "Texture({width} × {height})"),
            Pattern::Checkerboard { colours } => write!(f, "Checkerboard({colours:?})"),
        }
    }
}

/// Bytes an image of w × h pixels takes while it is read and made RGB f32: the decoded
/// image (up to 16 bytes a pixel) and its RGB f32 copy (12).
fn image_bytes(width: u32, height: u32) -> u64 {
    28 * width as u64 * height as u64
}

/// The image at `path` (a texture or an environment map), or why not (the message names the
/// file). Its size is read first and checked against the memory this machine has available
/// (the image crate's own 512 MiB cap does not apply: a large sky map is no error where there
/// is memory for it).
pub fn open_image(path: &Path) -> Result<image::DynamicImage, String> {
    let cannot =
        |e: &dyn std::fmt::Display| format!("cannot read {} as an image: {e}", path.display());
    let reader = || {
        image::ImageReader::open(path)
            .and_then(|r| r.with_guessed_format())
            .map_err(|e| cannot(&e))
    };
    let (width, height) = reader()?.into_dimensions().map_err(|e| cannot(&e))?;
    let needed = image_bytes(width, height);
    if let Some(free) = crate::resources::available_memory().filter(|&free| needed > free) {
        return Err(format!(
            "{}: a {width}×{height} image needs about {} of memory to read; this machine has {} available",
            path.display(),
            crate::resources::human(needed),
            crate::resources::human(free)
        ));
    }
    let mut reader = reader()?;
    reader.no_limits();
    reader.decode().map_err(|e| cannot(&e))
}
