//! A receiver's files: the bins as CSV, the irradiance as a heat map, the radial profile as CSV
//! and plot.

use super::statistics::{Measurement, Profile};
use super::Receiver;
use crate::error::Result;
use crate::plot::{canvas, save, text, Color, Labels, Panel, PALETTE};
use std::path::Path;

/// Writes, after grinlight's comment line ([`crate::output::write_csv`]),
/// `x,y,irradiance,stderr` (bin centres in the receiver's u, v frame), then
/// `irradiance_LO_HI,stderr_LO_HI` for each wavelength band [LO, HI) nm, one row per bin.
pub fn write_csv(rec: &Receiver, m: &Measurement, path: &Path) -> Result<()> {
    let mut out = String::from("x,y,irradiance,stderr");
    for (lo, hi) in &rec.bands {
        out += &format!(",irradiance_{lo}_{hi},stderr_{lo}_{hi}");
    }
    for s in ["S1", "S2", "S3"].iter().take(m.stokes.len()) {
        out += &format!(",{s},stderr_{s}");
    }
    out.push('\n');
    for (k, (e, se)) in m.irradiance.iter().zip(&m.stderr).enumerate() {
        let (x, y) = rec.bin_center(k);
        out += &format!("{x:.6e},{y:.6e},{e:.6e},{se:.6e}");
        for part in m.bands.iter().chain(&m.stokes) {
            out += &format!(",{:.6e},{:.6e}", part.irradiance[k], part.stderr[k]);
        }
        out.push('\n');
    }
    let what = format!("receiver '{}', irradiance per bin", rec.name);
    crate::output::write_csv(path, &what, &out)
}

/// Writes `r,irradiance,stderr` of [`super::radial_profile`].
pub fn write_radial_csv(profile: &[(f64, f64, f64)], path: &Path) -> Result<()> {
    let mut out = String::from("r,irradiance,stderr\n");
    for (r, e, se) in profile {
        out += &format!("{r:.6e},{e:.6e},{se:.6e}\n");
    }
    crate::output::write_csv(path, "radial irradiance profile", &out)
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
    let mut img = canvas(
        (nx as u32 * cell + 140).max(560),
        (ny as u32 * cell).max(120) + 70,
    );
    draw_heat_map(&mut img, rec, m, (10, 40), 480);
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
    let tick = crate::plot::TICK;
    text(img, bx + 26, at.1, &format!("{max:.3e}"), tick);
    text(
        img,
        bx + 26,
        at.1 + h / 2 - 7,
        &format!("{:.3e}", 0.5 * max),
        tick,
    );
    text(img, bx + 26, at.1 + h - 14, "0", tick);
    text(img, bx, at.1 + h + 4, "W per unit²", tick);
    let title = format!(
        "receiver '{}': irradiance, {} × {} over {} × {} units",
        rec.name, nx, ny, rec.size.0, rec.size.1
    );
    text(
        img,
        at.0,
        at.1.saturating_sub(22),
        &title,
        crate::plot::NAME,
    );
}

/// Plots radial profiles (r, irradiance) of receiver `name` with ±1 standard-error bars, one
/// colour each, with a legend naming them.
pub fn write_radial_png(name: &str, profiles: &[(&str, &Profile)], path: &Path) -> Result<()> {
    let mut img = canvas(680, 540);
    let all = || profiles.iter().flat_map(|(_, p)| p.iter());
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
    let mut panel = Panel::new(&mut img, (90, 60, 560, 420), x, y, (false, false));
    panel.axes(&Labels {
        title: &format!("receiver '{name}': radial profile about its centre (±1 standard error)"),
        x: "r (scene units)",
        y: "irradiance (W per scene unit²)",
    });
    let legend: Vec<(crate::plot::Color, &str)> = profiles
        .iter()
        .zip(PALETTE)
        .map(|((label, _), c)| (c, *label))
        .collect();
    panel.legend(&legend);
    for ((_, profile), color) in profiles.iter().zip(PALETTE) {
        let line: Vec<(f64, f64)> = profile.iter().map(|p| (p.0, p.1)).collect();
        panel.polyline(&line, color);
        for p in profile.iter() {
            panel.polyline(&[(p.0, p.1 - p.2), (p.0, p.1 + p.2)], color);
        }
    }
    save(&img, path)
}
