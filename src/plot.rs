//! Minimal raster plots (PNG): a canvas with lines, markers, shaded backgrounds and numeric
//! tick labels from a built-in 3×5 digit font. Enough for ray-path figures and log-log
//! error-against-time charts without a plotting dependency.

use crate::error::{Error, Result};
use image::{Rgb, RgbImage};
use std::path::Path;

/// An RGB colour.
pub type Color = [u8; 3];

/// Distinct series colours.
pub const PALETTE: [Color; 9] = [
    [220, 50, 47],
    [38, 139, 210],
    [133, 153, 0],
    [211, 54, 130],
    [181, 137, 0],
    [42, 161, 152],
    [108, 113, 196],
    [203, 75, 22],
    [88, 110, 117],
];

/// 3×5 glyphs for tick labels, rows top to bottom, 3 bits each (MSB left).
fn glyph(c: char) -> Option<[u8; 5]> {
    Some(match c {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        'e' => [0, 7, 7, 4, 7],
        '+' => [0, 2, 7, 2, 0],
        _ => return None,
    })
}

/// A data-space rectangle mapped onto a pixel rectangle of an image.
pub struct Panel<'a> {
    img: &'a mut RgbImage,
    /// Pixel rectangle: left, top, width, height.
    px: (u32, u32, u32, u32),
    /// Data ranges (already log10'd for log axes).
    x: (f64, f64),
    y: (f64, f64),
    log: (bool, bool),
}

/// A blank white image.
pub fn canvas(width: u32, height: u32) -> RgbImage {
    RgbImage::from_pixel(width, height, Rgb([255, 255, 255]))
}

/// Writes `img` as PNG.
pub fn save(img: &RgbImage, path: &Path) -> Result<()> {
    crate::output::write_atomic(path, |tmp| {
        img.save_with_format(tmp, image::ImageFormat::Png)
            .map_err(|e| Error::Image {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
    })
}

/// A range covering `values` (finite ones), padded by 5 % and never empty.
pub fn range_of(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = 0.05 * (hi - lo).max(1e-12 * hi.abs().max(1.0));
    (lo - pad, hi + pad)
}

impl<'a> Panel<'a> {
    /// A panel at pixel rectangle `px` showing data ranges `x`, `y` (in data units; with
    /// `log` set on an axis the range is given in data units and shown in decades).
    pub fn new(
        img: &'a mut RgbImage,
        px: (u32, u32, u32, u32),
        x: (f64, f64),
        y: (f64, f64),
        log: (bool, bool),
    ) -> Self {
        let t = |r: (f64, f64), l: bool| if l { (r.0.log10(), r.1.log10()) } else { r };
        Self {
            img,
            px,
            x: t(x, log.0),
            y: t(y, log.1),
            log,
        }
    }

    fn to_px(&self, x: f64, y: f64) -> (f64, f64) {
        let x = if self.log.0 { x.log10() } else { x };
        let y = if self.log.1 { y.log10() } else { y };
        let (l, t, w, h) = self.px;
        (
            l as f64 + (x - self.x.0) / (self.x.1 - self.x.0) * w as f64,
            t as f64 + (1.0 - (y - self.y.0) / (self.y.1 - self.y.0)) * h as f64,
        )
    }

    fn put(&mut self, x: i64, y: i64, c: Color) {
        let (l, t, w, h) = self.px;
        if x >= l as i64 && y >= t as i64 && x < (l + w) as i64 && y < (t + h) as i64 {
            self.img.put_pixel(x as u32, y as u32, Rgb(c));
        }
    }

    /// Shades every pixel by `f(x, y)` (data coordinates) mapped linearly from `range` to
    /// dark–light grey; NaN (e.g. a singular medium) is black, +∞ (outside, nothing to show)
    /// white.
    pub fn shade(&mut self, range: (f64, f64), f: impl Fn(f64, f64) -> f64) {
        let (l, t, w, h) = self.px;
        for j in 0..h {
            for i in 0..w {
                let x = self.x.0 + (i as f64 + 0.5) / w as f64 * (self.x.1 - self.x.0);
                let y = self.y.1 - (j as f64 + 0.5) / h as f64 * (self.y.1 - self.y.0);
                let v = f(x, y);
                let u = if range.1 > range.0 {
                    ((v - range.0) / (range.1 - range.0)).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                let g = if v.is_finite() {
                    (90.0 + 150.0 * u) as u8
                } else if v == f64::INFINITY {
                    255
                } else {
                    0
                };
                self.img.put_pixel(l + i, t + j, Rgb([g, g, g]));
            }
        }
    }

    /// A polyline through data points.
    pub fn polyline(&mut self, pts: &[(f64, f64)], c: Color) {
        for w in pts.windows(2) {
            let (a, b) = (self.to_px(w[0].0, w[0].1), self.to_px(w[1].0, w[1].1));
            let n = ((b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil() as usize).clamp(1, 100_000);
            for k in 0..=n {
                let u = k as f64 / n as f64;
                self.put(
                    (a.0 + u * (b.0 - a.0)) as i64,
                    (a.1 + u * (b.1 - a.1)) as i64,
                    c,
                );
            }
        }
    }

    /// A 5×5 square marker at a data point.
    pub fn marker(&mut self, x: f64, y: f64, c: Color) {
        let (px, py) = self.to_px(x, y);
        for dy in -2..=2 {
            for dx in -2..=2 {
                self.put(px as i64 + dx, py as i64 + dy, c);
            }
        }
    }

    /// A frame and tick labels at the ends of both axes (decade exponents on log axes).
    pub fn axes(&mut self) {
        let (l, t, w, h) = self.px;
        for i in 0..w {
            self.img.put_pixel(l + i, t, Rgb([0, 0, 0]));
            self.img.put_pixel(l + i, t + h - 1, Rgb([0, 0, 0]));
        }
        for j in 0..h {
            self.img.put_pixel(l, t + j, Rgb([0, 0, 0]));
            self.img.put_pixel(l + w - 1, t + j, Rgb([0, 0, 0]));
        }
        let label = |v: f64, log: bool| {
            if log {
                format!("1e{}", v.round() as i64)
            } else {
                format!("{v:.3}")
            }
        };
        let (x0, x1, y0, y1) = (
            label(self.x.0, self.log.0),
            label(self.x.1, self.log.0),
            label(self.y.0, self.log.1),
            label(self.y.1, self.log.1),
        );
        text(self.img, l, t + h + 4, &x0);
        text(
            self.img,
            (l + w).saturating_sub(8 * x1.len() as u32),
            t + h + 4,
            &x1,
        );
        text(
            self.img,
            l.saturating_sub(8 * y0.len() as u32 + 4),
            t + h - 10,
            &y0,
        );
        text(self.img, l.saturating_sub(8 * y1.len() as u32 + 4), t, &y1);
    }
}

/// Draws `s` with the 3×5 font at 2× scale, top-left at (x, y); unknown characters are skipped.
pub fn text(img: &mut RgbImage, x: u32, y: u32, s: &str) {
    for (k, c) in s.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        for (r, bits) in rows.iter().enumerate() {
            for b in 0..3 {
                if bits & (4 >> b) != 0 {
                    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                        let (px, py) = (x + 8 * k as u32 + 2 * b + dx, y + 2 * r as u32 + dy);
                        if px < img.width() && py < img.height() {
                            img.put_pixel(px, py, Rgb([0, 0, 0]));
                        }
                    }
                }
            }
        }
    }
}
