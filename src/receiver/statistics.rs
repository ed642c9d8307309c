//! What a receiver measured: irradiance per bin with its standard error from the photons'
//! crossings, the radial profile, and how two measurements compare.

use super::{Detection, Receiver};

/// What a receiver measured: irradiance and its standard error per bin.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// Irradiance per bin, W per scene-unit².
    pub irradiance: Vec<f64>,
    /// Standard error of each bin's irradiance.
    pub stderr: Vec<f64>,
    /// Total flux on the receiver, W, and its standard error.
    pub flux: (f64, f64),
    /// The same from the photons in each of the receiver's wavelength bands, in order (their
    /// own `bands` empty).
    pub bands: Vec<Measurement>,
}

impl Measurement {
    /// The irradiance-weighted mean of r² over the receiver's bins, r from its centre (scene
    /// units²): the square of a spot's RMS radius (NaN where nothing arrived).
    pub fn mean_square_radius(&self, rec: &Receiver) -> f64 {
        let (mut weight, mut sum) = (0.0, 0.0);
        for (bin, e) in self.irradiance.iter().enumerate() {
            let (x, y) = rec.bin_center(bin);
            weight += e;
            sum += e * (x * x + y * y);
        }
        sum / weight
    }
}

/// The receivers' measurements from the detections of `photons` photons (each detection's
/// flux already divided by `photons`, in photon order), with each receiver's bands.
pub fn measure(receivers: &[Receiver], detections: &[Detection], photons: u64) -> Vec<Measurement> {
    receivers
        .iter()
        .enumerate()
        .map(|(r, rec)| {
            let mine = |d: &&Detection| d.receiver == r as u32;
            let mut m = tally(rec, detections.iter().filter(mine), photons);
            m.bands = rec
                .bands
                .iter()
                .map(|&(lo, hi)| {
                    let inside = |d: &&Detection| mine(d) && (lo..hi).contains(&d.wavelength);
                    tally(rec, detections.iter().filter(inside), photons)
                })
                .collect();
            m
        })
        .collect()
}

/// One receiver's measurement from its detections among `photons` photons. A bin's value is
/// the sum Σ x_i over photons of their flux into it; as the photons are independent, its
/// variance is N·Var(x) = Σ x² − (Σ x)²/N (crossings of one bin by one photon are added
/// first).
fn tally<'a>(
    rec: &Receiver,
    detections: impl Iterator<Item = &'a Detection>,
    photons: u64,
) -> Measurement {
    let n = photons.max(1) as f64;
    let bins = rec.bins.0 * rec.bins.1;
    let (mut sum, mut sq) = (vec![0.0; bins], vec![0.0; bins]);
    let (mut total, mut total_sq) = (0.0, 0.0);
    let mut photon_total = (u64::MAX, 0.0);
    let mut last: Option<(u64, u32, f64)> = None;
    let close = |(_, bin, x): (u64, u32, f64), sq: &mut Vec<f64>| sq[bin as usize] += x * x;
    for d in detections {
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
        bands: Vec::new(),
    }
}

/// A radial profile: per ring, (centre radius, mean irradiance, its standard error).
pub type Profile = [(f64, f64, f64)];

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
