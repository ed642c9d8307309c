//! What a receiver measured: irradiance per bin with its standard error from the photons'
//! crossings, the radial profile, and how two measurements compare.

use super::{Detection, Receiver};
use crate::exact::ExactSum;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

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
    /// Where the transport is polarized, the same of the Stokes components S1, S2 and S3 in
    /// the receiver's basis ([`Receiver::stokes_basis`]; "irradiance" their flux per area, of
    /// either sign), each for all wavelengths; empty otherwise.
    pub stokes: Vec<Measurement>,
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
/// flux already divided by `photons`, in photon order), with each receiver's bands (and Stokes
/// components where `polarized`).
pub fn measure(
    receivers: &[Receiver],
    detections: &[Detection],
    photons: u64,
    polarized: bool,
) -> Vec<Measurement> {
    receivers
        .iter()
        .zip(tally(receivers, detections, polarized))
        .map(|(rec, t)| t.measurement(rec, photons, 1.0))
        .collect()
}

/// Each receiver's tally of `detections` (in photon order), with its bands and, where
/// `polarized`, its Stokes components: the detections grouped by receiver in one pass
/// (keeping their order), the receivers tallied in parallel.
pub fn tally(receivers: &[Receiver], detections: &[Detection], polarized: bool) -> Vec<Tally> {
    let mut grouped: Vec<Vec<&Detection>> = vec![Vec::new(); receivers.len()];
    for d in detections {
        if let Some(g) = grouped.get_mut(d.receiver as usize) {
            g.push(d);
        }
    }
    receivers
        .par_iter()
        .zip(grouped)
        .map(|(rec, mine)| {
            let bins = rec.bins.0 * rec.bins.1;
            let flux = |d: &Detection| d.flux;
            let mut t = Tally::of(mine.iter().copied(), bins, flux);
            t.bands = rec
                .bands
                .iter()
                .map(|&(lo, hi)| {
                    let inside = |d: &&Detection| (lo..hi).contains(&d.wavelength);
                    Tally::of(mine.iter().copied().filter(inside), bins, flux)
                })
                .collect();
            if polarized {
                t.stokes = (0..3)
                    .map(|i| {
                        let component =
                            |d: &Detection| d.flux * d.stokes.map_or(0.0, |s| f64::from(s[i]));
                        Tally::of(mine.iter().copied(), bins, component)
                    })
                    .collect();
            }
            t
        })
        .collect()
}

/// Σ x and Σ x² over photons of their flux x into something (a bin, a receiver), exactly.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
struct Moments {
    sum: ExactSum,
    squares: ExactSum,
}

impl Moments {
    fn merge(&mut self, other: &Moments) {
        self.sum.merge(&other.sum);
        self.squares.merge(&other.squares);
    }

    /// The sum over N photons, times `scale`, and its standard error: as the photons are
    /// independent, the sum's variance is N·Var(x) = Σ x² − (Σ x)²/N.
    fn estimate(&self, photons: u64, scale: f64) -> (f64, f64) {
        let (s, q) = (self.sum.value(), self.squares.value());
        let variance = (q - s * s / photons.max(1) as f64).max(0.0);
        (s * scale, variance.sqrt() * scale)
    }
}

/// One photon's flux summed over its consecutive detections with the same key (a bin, or `()`
/// for the whole receiver): a photon's crossings of one place are added before squaring.
#[derive(Clone, Copy, Debug)]
struct Run<K> {
    photon: u64,
    key: K,
    flux: f64,
}

/// The run under way, of detections in photon order.
#[derive(Debug)]
struct Runs<K> {
    current: Option<Run<K>>,
}

impl<K> Default for Runs<K> {
    fn default() -> Self {
        Self { current: None }
    }
}

impl<K: PartialEq + Copy> Runs<K> {
    /// Adds a detection of `flux` by `photon` at `key`; returns the run it ends (another
    /// photon, or another key).
    fn add(&mut self, photon: u64, key: K, flux: f64) -> Option<Run<K>> {
        match &mut self.current {
            Some(run) if run.photon == photon && run.key == key => {
                run.flux += flux;
                None
            }
            _ => self.current.replace(Run { photon, key, flux }),
        }
    }
}

/// What one receiver's crossings add up to, per bin (those crossed) and in all, and the same
/// for each of its wavelength bands: exact sums, so tallies of disjoint sets of photons (other
/// ranges, other machines) merge into bit for bit the tally of all of them.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Tally {
    bins: BTreeMap<u32, Moments>,
    total: Moments,
    bands: Vec<Tally>,
    /// S1, S2, S3 where the transport is polarized (their own `bands` and `stokes` empty).
    stokes: Vec<Tally>,
}

impl Tally {
    /// The tally of what `flux` reads of one receiver's detections, in photon order (a
    /// photon's crossings of one bin are added before squaring).
    fn of<'a>(
        detections: impl Iterator<Item = &'a Detection>,
        bins: usize,
        flux: impl Fn(&Detection) -> f64,
    ) -> Tally {
        // The bins crossed, in the order first crossed, found through a table of all bins.
        let mut slot = vec![u32::MAX; bins];
        let mut crossed: Vec<(u32, Moments)> = Vec::new();
        let mut at = |b: u32, crossed: &mut Vec<(u32, Moments)>| {
            let s = &mut slot[b as usize];
            if *s == u32::MAX {
                *s = crossed.len() as u32;
                crossed.push((b, Moments::default()));
            }
            *s as usize
        };
        let mut total = Moments::default();
        let (mut in_bin, mut in_receiver) = (Runs::default(), Runs::default());
        for d in detections {
            let x = flux(d);
            let i = at(d.bin, &mut crossed);
            crossed[i].1.sum.add(x);
            total.sum.add(x);
            if let Some(done) = in_bin.add(d.photon, d.bin, x) {
                let j = at(done.key, &mut crossed);
                crossed[j].1.squares.add(done.flux * done.flux);
            }
            if let Some(done) = in_receiver.add(d.photon, (), x) {
                total.squares.add(done.flux * done.flux);
            }
        }
        if let Some(done) = in_bin.current {
            let j = at(done.key, &mut crossed);
            crossed[j].1.squares.add(done.flux * done.flux);
        }
        if let Some(done) = in_receiver.current {
            total.squares.add(done.flux * done.flux);
        }
        Tally {
            bins: crossed.into_iter().collect(),
            total,
            bands: Vec::new(),
            stokes: Vec::new(),
        }
    }

    /// Adds the tally of other photons of the same receiver, exactly.
    pub fn merge(&mut self, other: &Tally) {
        for (b, m) in &other.bins {
            self.bins.entry(*b).or_default().merge(m);
        }
        self.total.merge(&other.total);
        for (mine, theirs) in [
            (&mut self.bands, &other.bands),
            (&mut self.stokes, &other.stokes),
        ] {
            if mine.is_empty() {
                *mine = vec![Tally::default(); theirs.len()];
            }
            for (a, b) in mine.iter_mut().zip(theirs) {
                a.merge(b);
            }
        }
    }

    /// Whether a tally read from a file fits `rec` (its bins, its bands, well-formed sums):
    /// the reason when not.
    pub fn fits(&self, rec: &Receiver) -> Result<(), String> {
        let bins = rec.bins.0 * rec.bins.1;
        if let Some(b) = self.bins.keys().find(|&&b| b as usize >= bins) {
            return Err(format!(
                "a tally of bin {b} for receiver '{}' of {bins} bins",
                rec.name
            ));
        }
        if !self
            .bins
            .values()
            .chain([&self.total])
            .all(|m| m.sum.is_well_formed() && m.squares.is_well_formed())
        {
            return Err(format!("a malformed sum in receiver '{}'", rec.name));
        }
        if !self.bands.is_empty() && self.bands.len() != rec.bands.len() {
            return Err(format!(
                "{} bands for receiver '{}' of {}",
                self.bands.len(),
                rec.name,
                rec.bands.len()
            ));
        }
        if !matches!(self.stokes.len(), 0 | 3) {
            return Err(format!(
                "{} Stokes components for receiver '{}' (0 or 3)",
                self.stokes.len(),
                rec.name
            ));
        }
        let flat = Receiver {
            bands: Vec::new(),
            ..rec.clone()
        };
        (self.bands.iter().chain(&self.stokes)).try_for_each(|b| b.fits(&flat))
    }

    /// The measurement of receiver `rec` from this tally of `photons` photons, every flux
    /// times `scale` (1, or the share of a batch traced, to its full count).
    pub fn measurement(&self, rec: &Receiver, photons: u64, scale: f64) -> Measurement {
        let area = rec.bin_area();
        let (mut irradiance, mut stderr) = (vec![0.0; rec.bins.0 * rec.bins.1], Vec::new());
        stderr.resize(irradiance.len(), 0.0);
        for (&b, m) in &self.bins {
            let (e, se) = m.estimate(photons, scale);
            irradiance[b as usize] = e / area;
            stderr[b as usize] = se / area;
        }
        Measurement {
            irradiance,
            stderr,
            flux: self.total.estimate(photons, scale),
            bands: self
                .bands
                .iter()
                .map(|b| b.measurement(rec, photons, scale))
                .collect(),
            stokes: self
                .stokes
                .iter()
                .map(|s| s.measurement(rec, photons, scale))
                .collect(),
        }
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
