//! Receivers: rectangular detector planes with a bin grid that record the flux of the photons
//! crossing them (grinlight as a measuring instrument). A receiver is transparent: rays and
//! photons pass through it unchanged. It records the mean over the RGB channels of each
//! crossing photon's flux (for a white source, its power per channel), in W, and reports
//! irradiance per bin in W per scene-unit² (W/mm² when the scene is in millimetres).
//!
//! Here the receiver's geometry; its [`statistics`] (irradiance and standard errors from the
//! photons' crossings, comparisons) and [`output`] (CSV, heat maps, radial plots) beside it.

mod output;
mod statistics;

pub use output::{draw_heat_map, write_csv, write_png, write_radial_csv, write_radial_png};
pub use statistics::{
    compare, measure, radial_profile, tally, Comparison, Measurement, Profile, Tally,
};

use crate::shapes::{Primitive, Quad};
use glam::DVec3;

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
    /// Wavelength bands [lo, hi) in nm measured apart (besides the total), if any.
    pub bands: Vec<(f64, f64)>,
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
    /// The photon's vacuum wavelength, nm.
    pub wavelength: f64,
    /// Its Stokes vector's S1, S2, S3 over S0 in the receiver's basis ([`Receiver::stokes_basis`]),
    /// where the transport is polarized (f32, as a photon's power: a share known to 1e-7).
    pub stokes: Option<[f32; 3]>,
}

impl Receiver {
    /// The receiver's surface, a quad with normal u × v.
    pub fn primitive(&self) -> Primitive {
        let (w, h) = self.size;
        Primitive::Quad(Quad {
            origin: self.center - 0.5 * w * self.u - 0.5 * h * self.v,
            e1: self.u * w,
            e2: self.v * h,
        })
    }

    /// The first axis of the basis its Stokes vectors are measured in: `u`, with the second
    /// k × u for light crossing along k (`v` for light crossing along u × v). S1 > 0 is light
    /// polarized along u, S2 > 0 along u + v (for light along u × v), S3 > 0 a field turning
    /// from the second axis toward u ([`crate::polarization::mueller`]'s conventions).
    pub fn stokes_basis(&self) -> DVec3 {
        self.u
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

/// The wavelength bands of `receivers`, each once, in the order first named: the bands an
/// energy budget books apart.
pub fn distinct_bands(receivers: &[Receiver]) -> Vec<(f64, f64)> {
    let mut bands: Vec<(f64, f64)> = Vec::new();
    for band in receivers.iter().flat_map(|r| &r.bands) {
        if !bands.contains(band) {
            bands.push(*band);
        }
    }
    bands
}
