//! Raster figures (PNG) with words: panels of lines, markers and shaded backgrounds, framed
//! by axes with tick marks and labels, axis names with units, titles and legends, set in
//! DejaVu Sans (shipped in `assets/`, rasterised by ab_glyph, so any Unicode a label needs —
//! Δn, µm, ², ± — draws). Enough for ray-path figures, heat maps and log-log
//! error-against-time charts; a full plotting crate (plotters, with its own image stack)
//! costs 30 s of a fresh build against 7 s for ab_glyph alone (measured on this machine).

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

/// Writes `img` as PNG, its `Software` text chunk naming grinlight ([`crate::output::signature`]).
pub fn save(img: &RgbImage, path: &Path) -> Result<()> {
    crate::output::write_atomic(path, |tmp| {
        let failed = |e: &dyn std::fmt::Display| Error::Image {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        let file = std::fs::File::create(tmp).map_err(|e| Error::io(path, e))?;
        let mut encoder =
            png::Encoder::new(std::io::BufWriter::new(file), img.width(), img.height());
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder
            .add_text_chunk("Software".into(), crate::output::signature())
            .map_err(|e| failed(&e))?;
        let mut writer = encoder.write_header().map_err(|e| failed(&e))?;
        writer
            .write_image_data(img.as_raw())
            .map_err(|e| failed(&e))?;
        writer.finish().map_err(|e| failed(&e))
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

    /// A frame with tick marks and labels along both axes (about five "nice" values on a
    /// linear axis, every decade on a log one), the axes' names under and above the panel,
    /// and a title above it.
    pub fn axes(&mut self, labels: &Labels) {
        let (l, t, w, h) = self.px;
        let black = [0, 0, 0];
        for i in 0..w {
            self.img.put_pixel(l + i, t, Rgb(black));
            self.img.put_pixel(l + i, t + h - 1, Rgb(black));
        }
        for j in 0..h {
            self.img.put_pixel(l, t + j, Rgb(black));
            self.img.put_pixel(l + w - 1, t + j, Rgb(black));
        }
        for v in ticks(self.x, self.log.0) {
            let x = l as f64 + (v - self.x.0) / (self.x.1 - self.x.0) * w as f64;
            let x = (x.round() as u32).min(l + w - 1);
            for k in 0..6 {
                self.img.put_pixel(x, t + h - 1 - k, Rgb(black));
            }
            let label = tick_label(v, self.log.0);
            let width = text_width(&label, TICK);
            text(
                self.img,
                x.saturating_sub(width / 2),
                t + h + 4,
                &label,
                TICK,
            );
        }
        for v in ticks(self.y, self.log.1) {
            let y = t as f64 + (1.0 - (v - self.y.0) / (self.y.1 - self.y.0)) * h as f64;
            let y = (y.round() as u32).min(t + h - 1);
            for k in 0..6 {
                self.img.put_pixel(l + k, y, Rgb(black));
            }
            let label = tick_label(v, self.log.1);
            let width = text_width(&label, TICK);
            text(
                self.img,
                l.saturating_sub(width + 5),
                y.saturating_sub(TICK as u32 / 2),
                &label,
                TICK,
            );
        }
        let x_name = text_width(labels.x, NAME);
        text(
            self.img,
            (l + w / 2).saturating_sub(x_name / 2),
            t + h + 6 + TICK as u32,
            labels.x,
            NAME,
        );
        text(
            self.img,
            l.saturating_sub(40),
            t.saturating_sub(2 * NAME as u32 + 6),
            labels.y,
            NAME,
        );
        let title = text_width(labels.title, NAME);
        text(
            self.img,
            (l + w / 2).saturating_sub(title / 2),
            t.saturating_sub(NAME as u32 + 4),
            labels.title,
            NAME,
        );
    }

    /// A legend box in the panel's top-right corner: a colour swatch and a label per entry.
    pub fn legend(&mut self, entries: &[(Color, &str)]) {
        if entries.is_empty() {
            return;
        }
        let (l, t, w, _) = self.px;
        let line = TICK as u32 + 6;
        let widest = entries
            .iter()
            .map(|(_, s)| text_width(s, TICK))
            .max()
            .unwrap_or(0);
        let (bw, bh) = (widest + 34, line * entries.len() as u32 + 8);
        let (x0, y0) = ((l + w).saturating_sub(bw + 6), t + 6);
        for y in y0..y0 + bh {
            for x in x0..x0 + bw {
                let edge = y == y0 || y == y0 + bh - 1 || x == x0 || x == x0 + bw - 1;
                self.put(
                    x as i64,
                    y as i64,
                    if edge {
                        [120, 120, 120]
                    } else {
                        [255, 255, 255]
                    },
                );
            }
        }
        for (k, (c, label)) in entries.iter().enumerate() {
            let y = y0 + 4 + line * k as u32;
            for dy in 0..TICK as u32 - 4 {
                for dx in 0..18 {
                    self.put((x0 + 6 + dx) as i64, (y + 2 + dy) as i64, *c);
                }
            }
            text(self.img, x0 + 28, y, label, TICK);
        }
    }
}

/// The words around a panel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Labels<'a> {
    /// Above the panel.
    pub title: &'a str,
    /// Under the horizontal axis: its quantity and unit.
    pub x: &'a str,
    /// Above the vertical axis: its quantity and unit.
    pub y: &'a str,
}

/// Pixel height of tick labels and legend entries.
pub const TICK: f32 = 14.0;
/// Pixel height of axis names and titles.
pub const NAME: f32 = 16.0;

/// About five round values inside `range` (data units; log10 units on a log axis, where they
/// are the whole decades).
fn ticks(range: (f64, f64), log: bool) -> Vec<f64> {
    let (lo, hi) = (range.0.min(range.1), range.0.max(range.1));
    if hi <= lo || !lo.is_finite() || !hi.is_finite() {
        return vec![lo];
    }
    let step = if log {
        ((hi - lo) / 6.0).ceil().max(1.0)
    } else {
        let raw = (hi - lo) / 5.0;
        let mag = 10f64.powf(raw.log10().floor());
        let f = raw / mag;
        mag * if f < 1.5 {
            1.0
        } else if f < 3.5 {
            2.0
        } else if f < 7.5 {
            5.0
        } else {
            10.0
        }
    };
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).take(50).map(|k| k as f64 * step).collect()
}

/// A tick's label: the value with as few digits as it needs (1e-3 style on a log axis).
fn tick_label(v: f64, log: bool) -> String {
    if log {
        return format!("1e{}", v.round() as i64);
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        return format!("{v:.1e}");
    }
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The font every figure uses.
fn font() -> &'static ab_glyph::FontRef<'static> {
    static FONT: std::sync::OnceLock<ab_glyph::FontRef<'static>> = std::sync::OnceLock::new();
    FONT.get_or_init(|| {
        ab_glyph::FontRef::try_from_slice(include_bytes!("../assets/DejaVuSans.ttf"))
            .expect("the shipped font parses")
    })
}

/// The width in pixels of `s` set at `size` pixels.
pub fn text_width(s: &str, size: f32) -> u32 {
    use ab_glyph::{Font, ScaleFont};
    let font = font().as_scaled(size);
    s.chars()
        .map(|c| font.h_advance(font.glyph_id(c)))
        .sum::<f32>()
        .ceil() as u32
}

/// Draws `s` in black at `size` pixels high with its top-left corner at (x, y), blended over
/// the image (anti-aliased); what falls outside the image is cut.
pub fn text(img: &mut RgbImage, x: u32, y: u32, s: &str, size: f32) {
    use ab_glyph::{Font, ScaleFont};
    let font = font().as_scaled(size);
    let mut pen = x as f32;
    let baseline = y as f32 + font.ascent();
    for c in s.chars() {
        let id = font.glyph_id(c);
        let glyph = id.with_scale_and_position(size, ab_glyph::point(pen, baseline));
        pen += font.h_advance(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let (px, py) = (
                bounds.min.x as i64 + gx as i64,
                bounds.min.y as i64 + gy as i64,
            );
            if px >= 0 && py >= 0 && (px as u32) < img.width() && (py as u32) < img.height() {
                let p = img.get_pixel_mut(px as u32, py as u32);
                for ch in p.0.iter_mut() {
                    *ch = (*ch as f32 * (1.0 - coverage.clamp(0.0, 1.0))) as u8;
                }
            }
        });
    }
}
