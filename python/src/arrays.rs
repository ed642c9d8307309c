//! The library's results as numpy arrays and dicts: image layers, receiver measurements, the
//! energy budget, traced rays.

use grinlight::color::Rgb;
use grinlight::commands::Traced;
use grinlight::photon::Budget;
use grinlight::receiver::{Measurement, Receiver};
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Row-major RGB pixels as a float32 array of shape (height, width, 3).
pub fn rgb_image<'py>(
    py: Python<'py>,
    pixels: Vec<[f32; 3]>,
    width: usize,
    height: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<f32> = pixels.into_iter().flatten().collect();
    let array = Array3::from_shape_vec((height, width, 3), flat)
        .expect("a film's layer holds width × height pixels");
    Ok(array.into_pyarray(py).into_any())
}

/// A receiver's bins (k = j·nx + i) as an array of shape (ny, nx).
fn bins(values: &[f64], r: &Receiver) -> Array2<f64> {
    Array2::from_shape_vec((r.bins.1, r.bins.0), values.to_vec())
        .expect("a measurement holds one value per bin")
}

/// One receiver's measurement: `irradiance` and `stderr` (W per scene unit², shape
/// (ny, nx)), the bins' centres `x` (nx) and `y` (ny) in the receiver's plane, `flux` and
/// `flux_stderr` (W), `bands`, one such dict per wavelength band with its `nm` range, and
/// `stokes`: where the transport is polarized, [S1, S2, S3] as such dicts (their irradiance
/// the Stokes component's flux per area, in the receiver's basis with first axis u), else None.
pub fn measurement<'py>(
    py: Python<'py>,
    r: &Receiver,
    m: &Measurement,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("irradiance", bins(&m.irradiance, r).into_pyarray(py))?;
    d.set_item("stderr", bins(&m.stderr, r).into_pyarray(py))?;
    let (nx, ny) = r.bins;
    let x: Array1<f64> = (0..nx).map(|i| r.bin_center(i).0).collect();
    let y: Array1<f64> = (0..ny).map(|j| r.bin_center(j * nx).1).collect();
    d.set_item("x", x.into_pyarray(py))?;
    d.set_item("y", y.into_pyarray(py))?;
    d.set_item("flux", m.flux.0)?;
    d.set_item("flux_stderr", m.flux.1)?;
    let bands = r
        .bands
        .iter()
        .zip(&m.bands)
        .map(|(nm, b)| {
            let band = measurement(py, r, b)?;
            band.del_item("bands")?;
            band.del_item("stokes")?;
            band.set_item("nm", *nm)?;
            Ok(band)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("bands", bands)?;
    // S1, S2, S3 where the transport is polarized: each a dict as this one (without bands
    // or Stokes), in the receiver's basis (first axis u); None otherwise.
    let stokes = match &m.stokes[..] {
        [] => None,
        parts => Some(
            parts
                .iter()
                .map(|s| {
                    let part = measurement(py, r, s)?;
                    part.del_item("bands")?;
                    part.del_item("stokes")?;
                    Ok(part)
                })
                .collect::<PyResult<Vec<_>>>()?,
        ),
    };
    d.set_item("stokes", stokes)?;
    Ok(d)
}

/// Where the receiver photons' power went (W): `emitted`, `reflected`, `missed`,
/// `absorbed` (by surfaces), `lost`, `out_through` (by primitive index), `absorbed_in` (by
/// medium name), `scattered` (the same for light a medium scattered, or None), `fluoresced`
/// (the same for light dyes and fluorescent layers emitted, or None), `dyes` (by medium
/// name: `absorbed`, `reabsorbed`, `emitted`), `layers` (the same by primitive index),
/// `bands`.
pub fn budget<'py>(py: Python<'py>, b: &Budget, media: &[String]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("emitted", b.emitted)?;
    d.set_item("reflected", b.reflected)?;
    d.set_item("missed", b.missed)?;
    d.set_item("absorbed", b.absorbed)?;
    d.set_item("lost", b.lost)?;
    d.set_item("out_through", b.out_through.clone())?;
    let name = |i: usize| {
        media
            .get(i)
            .cloned()
            .unwrap_or_else(|| format!("medium {i}"))
    };
    let absorbed_in = PyDict::new(py);
    for (i, w) in &b.absorbed_in {
        absorbed_in.set_item(name(*i), w)?;
    }
    d.set_item("absorbed_in", absorbed_in)?;
    let fluorophore = |dye: &grinlight::photon::Dye| -> PyResult<Bound<'py, PyDict>> {
        let entry = PyDict::new(py);
        entry.set_item("absorbed", dye.absorbed)?;
        entry.set_item("reabsorbed", dye.reabsorbed)?;
        entry.set_item("emitted", dye.emitted)?;
        Ok(entry)
    };
    let dyes = PyDict::new(py);
    for (i, dye) in &b.dyes {
        dyes.set_item(name(*i), fluorophore(dye)?)?;
    }
    d.set_item("dyes", dyes)?;
    let layers = PyDict::new(py);
    for (p, layer) in &b.layers {
        layers.set_item(*p, fluorophore(layer)?)?;
    }
    d.set_item("layers", layers)?;
    for (key, part) in [("scattered", &b.scattered), ("fluoresced", &b.fluoresced)] {
        let part = match part {
            Some(s) => Some(budget(py, s, media)?),
            None => None,
        };
        d.set_item(key, part)?;
    }
    let bands = b
        .bands
        .iter()
        .map(|(nm, band)| {
            let band_dict = budget(py, band, media)?;
            band_dict.set_item("nm", *nm)?;
            Ok(band_dict)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("bands", bands)?;
    Ok(d)
}

/// A traced ray: per accepted point (the start first) `s` (arclength), `opl` (optical path
/// ∫ n ds), `points` and `directions` (N × 3) and `n`; then how it ended: `reason`,
/// `steps`, `attempts`, `arclength`, `optical_path`, `optical_depth` (per RGB channel).
pub fn traced<'py>(py: Python<'py>, t: &Traced) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let column = |f: &dyn Fn(&grinlight::commands::PathPoint) -> f64| -> Array1<f64> {
        t.points.iter().map(f).collect()
    };
    let vectors = |f: &dyn Fn(&grinlight::commands::PathPoint) -> [f64; 3]| -> Array2<f64> {
        let flat: Vec<f64> = t.points.iter().flat_map(f).collect();
        Array2::from_shape_vec((t.points.len(), 3), flat).expect("three per point")
    };
    d.set_item("s", column(&|p| p.s).into_pyarray(py))?;
    d.set_item("opl", column(&|p| p.opl).into_pyarray(py))?;
    d.set_item(
        "points",
        vectors(&|p| p.state.position.to_array()).into_pyarray(py),
    )?;
    d.set_item(
        "directions",
        vectors(&|p| p.state.direction.to_array()).into_pyarray(py),
    )?;
    d.set_item("n", column(&|p| p.state.index.n).into_pyarray(py))?;
    let o = &t.outcome;
    d.set_item("reason", o.reason.name())?;
    d.set_item("steps", o.steps)?;
    d.set_item("attempts", o.attempts)?;
    d.set_item("arclength", o.arclength)?;
    d.set_item("optical_path", o.optical_path)?;
    let depth = t.points.last().map_or(Rgb::ZERO, |p| p.optical_depth);
    d.set_item(
        "optical_depth",
        Array1::from(depth.0.to_array().to_vec()).into_pyarray(py),
    )?;
    if let Some(p) = &t.polarization {
        d.set_item(
            "field",
            Array1::from(p.field.to_array().to_vec()).into_pyarray(py),
        )?;
        d.set_item("phase", p.phase)?;
    }
    Ok(d)
}
