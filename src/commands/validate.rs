//! `grinlight validate`: a scene's GRIN fiber against its layered twins (concentric homogeneous
//! cylinders, Zhdanov et al. (2020) §5), measured with independent photon streams and compared bin by bin
//! on the first receiver.

use crate::error::positive;
use crate::error::{Error, Result};
use crate::fiber::Layer;
use crate::output::{Kind, Outputs};
use crate::receiver;
use crate::receiver::{Comparison, Measurement};
use crate::render::Observer;
use crate::report::Report;
use crate::scene::{Description, Scene};
use crate::settings::Settings;
use std::path::PathBuf;

/// What `grinlight validate` is asked to do.
#[derive(Clone, Debug, Default)]
pub struct ValidateJob {
    /// The scene file: a GRIN-filled cylinder and at least one `[[receiver]]`.
    pub scene: PathBuf,
    /// One twin per index step Δn between layers.
    pub dn: Vec<f64>,
    /// Also a new layer wherever one reaches this width (None: no limit).
    pub max_width: Option<f64>,
    /// Photons per measurement (None: the scene's `receiver_photons`).
    pub photons: Option<u64>,
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// The radial-profiles plot (None: `<scene stem>.validate.png` here).
    pub plot: Option<PathBuf>,
}

/// Runs `grinlight validate`, showing the observer a table row per twin as it is measured.
pub fn validate(job: &ValidateJob, observer: &dyn Observer) -> Result<()> {
    let threads = crate::resources::check_threads(job.threads)?;
    // Checked before any photon is traced (the twins are built after the GRIN measurement).
    if job.dn.is_empty() || job.dn.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
        return Err(Error::Usage(format!(
            "--dn must be numbers > 0, got {:?}",
            job.dn
        )));
    }
    if let Some(w) = job.max_width {
        positive("max_width", w)?;
    }
    let load = || -> Result<(Description, Settings)> {
        let (s, mut settings) = crate::import::load_description(&job.scene, &Default::default())?;
        if let Some(n) = job.photons {
            settings.receiver_photons = crate::settings::RECEIVER_PHOTONS
                .count(n)
                .map_err(|why| Error::Usage(format!("--photons {why}")))?;
        }
        settings.threads = threads;
        if s.receivers.is_empty() {
            return Err(Error::Usage(format!(
                "{}: no [[receiver]] to compare on",
                job.scene.display()
            )));
        }
        Ok((s, settings))
    };
    let (grin, grin_settings) = load()?;
    let grin = grin.build();
    let plot = job.plot.clone().unwrap_or_else(|| {
        PathBuf::from(job.scene.file_stem().unwrap_or_default()).with_extension("validate.png")
    });
    Outputs::new(&grin.inputs).add(&plot, Kind::Png)?;
    crate::resources::check_memory(
        crate::render::memory_needed(&grin, &grin_settings),
        &format!("measuring {}", job.scene.display()),
    )?;
    let reference = measure_grin(job, &grin, &grin_settings, observer)?;
    let rec = &grin.receivers[0];
    observer.line(
        "| Δn | layers | widest layer | flux ratio (layered/GRIN) | χ²/dof | dof | max |z| | cut at max_depth | time (s) |\n\
         |---|---|---|---|---|---|---|---|---|",
    );
    let mut profiles = vec![(
        "GRIN fiber".to_string(),
        receiver::radial_profile(rec, &reference),
    )];
    for (k, &dn) in job.dn.iter().enumerate() {
        let (mut twin, mut settings) = load()?;
        let layers = twin.layer_fiber(
            &mut settings.trace,
            dn,
            job.max_width.unwrap_or(f64::INFINITY),
        )?;
        let twin = twin.build();
        let t = std::time::Instant::now();
        let (layered, _, report) =
            crate::render::measure(&twin, &settings, 1 + k as u64, observer)?;
        stop_if_partial(&report)?;
        let seconds = t.elapsed().as_secs_f64();
        observer.line(&row(
            (&dn.to_string(), &layers),
            &receiver::compare(&reference, &layered[0]),
            &report,
            seconds,
        ));
        // Each wavelength band of the receiver compared apart, from the same photons.
        let bands = reference.bands.iter().zip(&layered[0].bands);
        for (&(lo, hi), (a, b)) in rec.bands.iter().zip(bands) {
            if a.flux.0 > 0.0 {
                let label = format!("{dn}, band {lo}–{hi} nm");
                let c = receiver::compare(a, b);
                observer.line(&row((&label, &layers), &c, &report, seconds));
            }
        }
        profiles.push((
            format!("twin, Δn {dn}, {} layers", layers.len()),
            receiver::radial_profile(rec, &layered[0]),
        ));
    }
    let refs: Vec<(&str, &receiver::Profile)> = profiles
        .iter()
        .map(|(name, p)| (name.as_str(), p.as_slice()))
        .collect();
    receiver::write_radial_png(&rec.name, &refs, &plot)?;
    observer.line(&format!(
        "wrote {} (radial irradiance of the GRIN fiber and each twin, ±1 standard error)",
        plot.display()
    ));
    Ok(())
}

/// The share of a measurement's photons cut at `max_depth`, in per cent.
fn cut(report: &Report) -> f64 {
    100.0 * report.stats.depth_limited as f64 / report.stats.photons_emitted.max(1) as f64
}

/// Measures the GRIN fiber on its first receiver (photon stream pass 0) and reports it.
fn measure_grin(
    job: &ValidateJob,
    grin: &Scene,
    settings: &Settings,
    observer: &dyn Observer,
) -> Result<Measurement> {
    let rec = &grin.receivers[0];
    let t = std::time::Instant::now();
    let (mut reference, _, report) = crate::render::measure(grin, settings, 0, observer)?;
    stop_if_partial(&report)?;
    let reference = reference.swap_remove(0);
    if reference.flux.0 <= 0.0 {
        return Err(Error::Usage(format!(
            "{}: receiver '{}' received no light from the GRIN fiber: nothing to compare",
            job.scene.display(),
            rec.name
        )));
    }
    observer.line(&format!(
        "GRIN fiber: receiver '{}' flux {:.6e} ± {:.1e} W ({} photons, {:.2} % cut at max_depth, {:.1} s)",
        rec.name,
        reference.flux.0,
        reference.flux.1,
        settings.receiver_photons,
        cut(&report),
        t.elapsed().as_secs_f64()
    ));
    Ok(reference)
}

/// One row of the comparison table: a twin of index step `dn` (and the band compared, if
/// one) and `layers`.
fn row((dn, layers): (&str, &[Layer]), c: &Comparison, report: &Report, seconds: f64) -> String {
    format!(
        "| {dn} | {} | {:.4} | {:.5} ± {:.5} | {:.3} | {} | {:.2} | {:.2} % | {:.1} |",
        layers.len(),
        layers.iter().map(|l| l.outer - l.inner).fold(0.0, f64::max),
        c.flux_ratio,
        c.flux_ratio_stderr,
        c.chi2_per_dof,
        c.dof,
        c.max_z,
        cut(report),
        seconds
    )
}

/// An interrupted measurement ends the comparison (a partial one would compare unequal
/// photon counts without saying so).
fn stop_if_partial(report: &Report) -> Result<()> {
    match &report.partial {
        Some(p) => Err(Error::Interrupted(format!(
            "validate stopped after {p}; nothing written"
        ))),
        None => Ok(()),
    }
}
