//! Receivers: rectangular detector planes with a bin grid that record the flux of the photons
//! crossing them (grinlight as a measuring instrument). A receiver is transparent: rays and
//! photons pass through it unchanged. It records the mean over the RGB channels of each
//! crossing photon's flux (for a white source, its power per channel), in W, and reports
//! irradiance per bin in W per scene-unit² (W/mm² when the scene is in millimetres).

use crate::error::Result;
use crate::plot::{canvas, save, text, Color, Panel, PALETTE};
use crate::shapes::Primitive;
use glam::DVec3;
use std::path::Path;

/// A detector rectangle: centre, in-plane unit axes `u` (width) and `v` (height), size and
/// bins (row-major, `v` rows of `u` columns).
#[derive(Clone, Debug, PartialEq)]
pub struct Receiver {
    /// Name (used in output file names).
    pub name: String,
    /// Centre.
    pub center: DVec3,
    /// Unit axis along the width.
    pub u: DVec3,
    /// Unit axis along the height.
    pub v: DVec3,
    /// Width and height (scene units).
    pub size: (f64, f64),
    /// Bins along u and v.
    pub bins: (usize, usize),
}

/// One photon crossing a receiver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detection {
    /// Receiver index.
    pub receiver: u32,
    /// Bin index (row-major).
    pub bin: u32,
    /// The photon's index in its batch.
    pub photon: u64,
    /// Flux, W (mean over channels).
    pub flux: f64,
}

impl Receiver {
    /// The receiver's surface, a quad with normal u × v.
    pub fn primitive(&self) -> Primitive {
        let (w, h) = self.size;
        Primitive::Quad {
            origin: self.center - 0.5 * w * self.u - 0.5 * h * self.v,
            e1: self.u * w,
            e2: self.v * h,
        }
    }

    /// Local coordinates (along u, along v) of a point, relative to the centre.
    pub fn local(&self, p: DVec3) -> (f64, f64) {
        let d = p - self.center;
        (d.dot(self.u), d.dot(self.v))
    }

    /// The bin holding point `p` of the plane, if any.
    pub fn bin(&self, p: DVec3) -> Option<usize> {
        let (x, y) = self.local(p);
        let (w, h) = self.size;
        let i = ((x / w + 0.5) * self.bins.0 as f64).floor();
        let j = ((y / h + 0.5) * self.bins.1 as f64).floor();
        let inside =
            (0.0..self.bins.0 as f64).contains(&i) && (0.0..self.bins.1 as f64).contains(&j);
        inside.then(|| j as usize * self.bins.0 + i as usize)
    }

    /// Area of one bin.
    pub fn bin_area(&self) -> f64 {
        self.size.0 * self.size.1 / (self.bins.0 * self.bins.1) as f64
    }

    /// Local coordinates of bin `k`'s centre.
    pub fn bin_center(&self, k: usize) -> (f64, f64) {
        let (i, j) = (k % self.bins.0, k / self.bins.0);
        (
            ((i as f64 + 0.5) / self.bins.0 as f64 - 0.5) * self.size.0,
            ((j as f64 + 0.5) / self.bins.1 as f64 - 0.5) * self.size.1,
        )
    }
}

/// What a receiver measured: irradiance and its standard error per bin.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// Irradiance per bin, W per scene-unit².
    pub irradiance: Vec<f64>,
    /// Standard error of each bin's irradiance.
    pub stderr: Vec<f64>,
    /// Total flux on the receiver, W, and its standard error.
    pub flux: (f64, f64),
}

/// The receivers' measurements from the detections of `photons` photons (each detection's
/// flux already divided by `photons`, in photon order). A bin's value is the sum Σ x_i over
/// photons of their flux into it; as the photons are independent, its variance is
/// N·Var(x) = Σ x² − (Σ x)²/N (crossings of one bin by one photon are added first).
pub fn measure(receivers: &[Receiver], detections: &[Detection], photons: u64) -> Vec<Measurement> {
    let n = photons.max(1) as f64;
    receivers
        .iter()
        .enumerate()
        .map(|(r, rec)| {
            let bins = rec.bins.0 * rec.bins.1;
            let (mut sum, mut sq) = (vec![0.0; bins], vec![0.0; bins]);
            let (mut total, mut total_sq) = (0.0, 0.0);
            let mut photon_total = (u64::MAX, 0.0);
            let mut last: Option<(u64, u32, f64)> = None;
            let close = |(_, bin, x): (u64, u32, f64), sq: &mut Vec<f64>| sq[bin as usize] += x * x;
            for d in detections.iter().filter(|d| d.receiver == r as u32) {
                sum[d.bin as usize] += d.flux;
                total += d.flux;
                match &mut last {
                    Some((p, b, x)) if *p == d.photon && *b == d.bin => *x += d.flux,
                    _ => {
                        if let Some(l) = last {
                            close(l, &mut sq);
                        }
                        last = Some((d.photon, d.bin, d.flux));
                    }
                }
                if photon_total.0 == d.photon {
                    photon_total.1 += d.flux;
                } else {
                    total_sq += photon_total.1 * photon_total.1;
                    photon_total = (d.photon, d.flux);
                }
            }
            if let Some(l) = last {
                close(l, &mut sq);
            }
            total_sq += photon_total.1 * photon_total.1;
            let area = rec.bin_area();
            let se = |s: f64, q: f64| (q - s * s / n).max(0.0).sqrt();
            Measurement {
                irradiance: sum.iter().map(|s| s / area).collect(),
                stderr: sum
                    .iter()
                    .zip(&sq)
                    .map(|(s, q)| se(*s, *q) / area)
                    .collect(),
                flux: (total, se(total, total_sq)),
            }
        })
        .collect()
}

/// The radial profile of a measurement about the receiver's centre: rings one bin wide (the
/// larger bin side); per ring (centre radius, mean irradiance, its standard error) over the
/// bins whose centres fall in it.
pub fn radial_profile(rec: &Receiver, m: &Measurement) -> Vec<(f64, f64, f64)> {
    let width = (rec.size.0 / rec.bins.0 as f64).max(rec.size.1 / rec.bins.1 as f64);
    let rings = (0.5 * rec.size.0.min(rec.size.1) / width).floor().max(1.0) as usize;
    let mut acc = vec![(0.0, 0.0, 0usize); rings];
    for (k, (e, se)) in m.irradiance.iter().zip(&m.stderr).enumerate() {
        let (x, y) = rec.bin_center(k);
        let ring = ((x * x + y * y).sqrt() / width) as usize;
        if let Some(a) = acc.get_mut(ring) {
            a.0 += e;
            a.1 += se * se;
            a.2 += 1;
        }
    }
    acc.iter()
        .enumerate()
        .filter(|(_, a)| a.2 > 0)
        .map(|(i, a)| {
            (
                (i as f64 + 0.5) * width,
                a.0 / a.2 as f64,
                a.1.sqrt() / a.2 as f64,
            )
        })
        .collect()
}

/// Writes `x,y,irradiance,stderr` (bin centres in the receiver's u, v frame), one row per bin.
pub fn write_csv(rec: &Receiver, m: &Measurement, path: &Path) -> Result<()> {
    let mut out = String::from("x,y,irradiance,stderr\n");
    for (k, (e, se)) in m.irradiance.iter().zip(&m.stderr).enumerate() {
        let (x, y) = rec.bin_center(k);
        out += &format!("{x:.6e},{y:.6e},{e:.6e},{se:.6e}\n");
    }
    crate::output::write_text(path, &out)
}

/// Writes `r,irradiance,stderr` of [`radial_profile`].
pub fn write_radial_csv(profile: &[(f64, f64, f64)], path: &Path) -> Result<()> {
    let mut out = String::from("r,irradiance,stderr\n");
    for (r, e, se) in profile {
        out += &format!("{r:.6e},{e:.6e},{se:.6e}\n");
    }
    crate::output::write_text(path, &out)
}

/// A colour for t ∈ [0, 1]: black → purple → orange → pale yellow (an "inferno"-like ramp).
fn heat(t: f64) -> Color {
    const STOPS: [[f64; 3]; 5] = [
        [0.0, 0.0, 0.02],
        [0.34, 0.06, 0.43],
        [0.73, 0.21, 0.33],
        [0.98, 0.55, 0.04],
        [0.99, 1.0, 0.64],
    ];
    let x = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let (i, f) = ((x as usize).min(STOPS.len() - 2), x.fract());
    let f = if x as usize >= STOPS.len() - 1 {
        1.0
    } else {
        f
    };
    [0, 1, 2].map(|c| ((STOPS[i][c] * (1.0 - f) + STOPS[i + 1][c] * f) * 255.0) as u8)
}

/// Writes the irradiance as a heat map (bins as square cells, v upward) with a colour bar
/// labelled 0 and the maximum irradiance.
pub fn write_png(rec: &Receiver, m: &Measurement, path: &Path) -> Result<()> {
    let (nx, ny) = rec.bins;
    let cell = (480 / nx.max(ny)).max(1) as u32;
    let mut img = canvas(nx as u32 * cell + 140, (ny as u32 * cell).max(120) + 20);
    draw_heat_map(&mut img, rec, m, (10, 10), 480);
    save(&img, path)
}

/// Draws the irradiance as a heat map with its top-left corner at `at`, the larger side at
/// most `size` pixels (whole pixels per bin), and a colour bar to its right labelled 0 and
/// the maximum (130 pixels wide with its labels).
pub fn draw_heat_map(
    img: &mut image::RgbImage,
    rec: &Receiver,
    m: &Measurement,
    at: (u32, u32),
    size: u32,
) {
    let (nx, ny) = rec.bins;
    let cell = (size / nx.max(ny) as u32).max(1);
    let (w, h) = (nx as u32 * cell, ny as u32 * cell);
    let max = m
        .irradiance
        .iter()
        .cloned()
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut put = |x: u32, y: u32, c: Color| {
        if x < img.width() && y < img.height() {
            img.put_pixel(x, y, image::Rgb(c));
        }
    };
    for (k, e) in m.irradiance.iter().enumerate() {
        let (i, j) = ((k % nx) as u32, (k / nx) as u32);
        let c = heat(e / max);
        for dy in 0..cell {
            for dx in 0..cell {
                put(
                    at.0 + i * cell + dx,
                    at.1 + (ny as u32 - 1 - j) * cell + dy,
                    c,
                );
            }
        }
    }
    let bx = at.0 + w + 20;
    for y in 0..h {
        let c = heat(1.0 - y as f64 / h.max(1) as f64);
        for x in 0..20 {
            put(bx + x, at.1 + y, c);
        }
    }
    text(img, bx + 26, at.1, &format!("{max:.3e}"));
    text(img, bx + 26, at.1 + h - 10, "0");
}

/// Plots radial profiles (r, irradiance) with ±1 standard-error bars, one colour each.
pub fn write_radial_png(profiles: &[&[(f64, f64, f64)]], path: &Path) -> Result<()> {
    let mut img = canvas(640, 480);
    let all = || profiles.iter().flat_map(|p| p.iter());
    let x = (
        0.0,
        all()
            .map(|p| p.0)
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE),
    );
    let y = (
        0.0,
        all()
            .map(|p| p.1 + p.2)
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE),
    );
    let mut panel = Panel::new(&mut img, (80, 20, 540, 420), x, y, (false, false));
    panel.axes();
    for (profile, color) in profiles.iter().zip(PALETTE) {
        let line: Vec<(f64, f64)> = profile.iter().map(|p| (p.0, p.1)).collect();
        panel.polyline(&line, color);
        for p in profile.iter() {
            panel.polyline(&[(p.0, p.1 - p.2), (p.0, p.1 + p.2)], color);
        }
    }
    save(&img, path)
}

/// How two measurements of one receiver agree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    /// Total flux of `b` over that of `a`.
    pub flux_ratio: f64,
    /// Standard error of that ratio.
    pub flux_ratio_stderr: f64,
    /// χ² per degree of freedom over the bins where either has a non-zero standard error:
    /// Σ (a − b)² / (σa² + σb²) / dof. About 1 ± √(2/dof) when they agree within noise.
    pub chi2_per_dof: f64,
    /// The bins counted.
    pub dof: usize,
    /// Largest |a − b| / √(σa² + σb²) over those bins.
    pub max_z: f64,
}

/// Compares two independent measurements of the same receiver.
pub fn compare(a: &Measurement, b: &Measurement) -> Comparison {
    let (mut chi2, mut dof, mut max_z) = (0.0, 0usize, 0.0f64);
    for i in 0..a.irradiance.len().min(b.irradiance.len()) {
        let var = a.stderr[i].powi(2) + b.stderr[i].powi(2);
        if var > 0.0 {
            let z2 = (a.irradiance[i] - b.irradiance[i]).powi(2) / var;
            chi2 += z2;
            dof += 1;
            max_z = max_z.max(z2.sqrt());
        }
    }
    let ratio = b.flux.0 / a.flux.0;
    Comparison {
        flux_ratio: ratio,
        flux_ratio_stderr: ratio
            * ((a.flux.1 / a.flux.0).powi(2) + (b.flux.1 / b.flux.0).powi(2)).sqrt(),
        chi2_per_dof: chi2 / dof.max(1) as f64,
        dof,
        max_z,
    }
}
