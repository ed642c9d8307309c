//! Step-count invariance of the fiber receiver (Zhdanov et al. (2020) §5 reports that 20 to 100 steps leave
//! the image unchanged): `scenes/fiber_led.toml` measured with every stepper under fixed steps
//! (20, 50, 100 per fiber length) and adaptive control at several tolerances, each against a
//! high-accuracy run (RK4, adaptive 1e-10). All runs use the same photon streams, so the
//! differences are the stepping's, not Monte Carlo noise (though paths with many reflections
//! decorrelate). Error: relative difference of the total flux, and the RMS difference of the
//! bins' irradiance relative to the mean irradiance of the lit bins. Prints a table, writes
//! `out/fiber_study.csv` and `out/fiber_study.png` (RMS error against time, log-log, one
//! colour per stepper), then photons per second on one core for each stepper.
//!
//! `cargo run --release --example fiber_study -- [PHOTONS]` (default 20000)

use grinlight::curve::{StepControl, StepperKind};
use grinlight::plot::{canvas, save, Labels, Panel, PALETTE};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let photons: u64 = std::env::args().nth(1).map_or(Ok(20_000), |a| a.parse())?;
    let run_on = |threads: usize,
                  stepper: StepperKind,
                  control: StepControl|
     -> Result<_, Box<dyn std::error::Error>> {
        let (scene, mut settings) =
            grinlight::scene::load_scene(Path::new("scenes/fiber_led.toml"))?;
        settings.trace.stepper = stepper;
        settings.trace.control = control;
        settings.receiver_photons = photons;
        settings.threads = threads;
        let t = Instant::now();
        let (m, _, _) = grinlight::render::measure(&scene, &settings, 0, &())?;
        Ok((
            m.into_iter().next().ok_or("no receiver")?,
            t.elapsed().as_secs_f64(),
        ))
    };
    let run = |stepper, control| run_on(0, stepper, control);
    let (reference, t_ref) = run(StepperKind::Rk4, StepControl::Adaptive { tolerance: 1e-10 })?;
    let lit: Vec<usize> = (0..reference.irradiance.len())
        .filter(|&i| reference.irradiance[i] > 0.0)
        .collect();
    let mean = lit.iter().map(|&i| reference.irradiance[i]).sum::<f64>() / lit.len() as f64;
    println!(
        "reference (rk4, adaptive 1e-10): flux {:.6e} W in {t_ref:.1} s\n",
        reference.flux.0
    );
    println!("| stepper | control | time (s) | flux error | irradiance RMS error |\n|---|---|---|---|---|");
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/fiber_study.csv")?;
    writeln!(csv, "stepper,control,seconds,flux_error,rms_error")?;
    let mut series: Vec<Vec<(f64, f64)>> = Vec::new();
    for stepper in [StepperKind::Rk4, StepperKind::Arc, StepperKind::Snell] {
        let mut points = Vec::new();
        let mut controls: Vec<(String, StepControl)> = [20.0, 50.0, 100.0]
            .iter()
            .map(|n| {
                (
                    format!("fixed {n} steps"),
                    StepControl::Fixed { step: 20.0 / n },
                )
            })
            .collect();
        // Tolerances each stepper reaches in seconds here (Snell steps below 1e-5 take
        // minutes per 10⁴ photons).
        let tolerances: &[f64] = match stepper {
            StepperKind::Rk4 => &[1e-4, 1e-6, 1e-8],
            StepperKind::Rkn | StepperKind::Linearize => &[1e-4, 1e-5, 1e-6],
            StepperKind::Arc => &[1e-4, 1e-5],
            StepperKind::Snell => &[1e-3, 1e-4],
        };
        for &tol in tolerances {
            controls.push((
                format!("adaptive {tol:e}"),
                StepControl::Adaptive { tolerance: tol },
            ));
        }
        for (name, control) in controls {
            let (m, t) = run(stepper, control)?;
            let flux = (m.flux.0 - reference.flux.0) / reference.flux.0;
            let rms = (lit
                .iter()
                .map(|&i| (m.irradiance[i] - reference.irradiance[i]).powi(2))
                .sum::<f64>()
                / lit.len() as f64)
                .sqrt()
                / mean;
            println!("| {stepper:?} | {name} | {t:.2} | {flux:+.2e} | {rms:.2e} |");
            writeln!(csv, "{stepper:?},{name},{t:.3},{flux:.6e},{rms:.6e}")?;
            points.push((t, rms.max(1e-12)));
        }
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        series.push(points);
    }
    let all = || series.iter().flatten();
    let x = (
        all().map(|p| p.0).fold(f64::INFINITY, f64::min),
        all().map(|p| p.0).fold(0.0, f64::max),
    );
    let y = (
        all().map(|p| p.1).fold(f64::INFINITY, f64::min),
        all().map(|p| p.1).fold(0.0, f64::max),
    );
    let mut img = canvas(680, 540);
    let mut panel = Panel::new(
        &mut img,
        (90, 60, 560, 420),
        (x.0 * 0.8, x.1 * 1.25),
        (y.0 * 0.8, y.1 * 1.25),
        (true, true),
    );
    panel.axes(&Labels {
        title: "fiber receiver: error against run time",
        x: "time (s, 2 threads)",
        y: "RMS bin error / mean lit bin",
    });
    panel.legend(&[
        (PALETTE[0], "rk4"),
        (PALETTE[1], "arc"),
        (PALETTE[2], "snell"),
    ]);
    for (points, color) in series.iter().zip(PALETTE) {
        for (t, e) in points {
            panel.marker(*t, *e, color);
        }
    }
    save(&img, Path::new("out/fiber_study.png"))?;
    println!(
        "\nwrote out/fiber_study.csv and out/fiber_study.png (red rk4, blue arc, green snell)"
    );
    // Photons per second on one core, each stepper at a tolerance with an RMS error of
    // 0.07–0.18 in the table above (rk4 1e-6, arc 1e-4, snell 1e-4; medians of 3).
    println!("\n| stepper | adaptive tolerance | photons/s on one core |\n|---|---|---|");
    for (stepper, tolerance) in [
        (StepperKind::Rk4, 1e-6),
        (StepperKind::Arc, 1e-4),
        (StepperKind::Snell, 1e-4),
    ] {
        let mut rates = Vec::new();
        for _ in 0..3 {
            let (_, t) = run_on(1, stepper, StepControl::Adaptive { tolerance })?;
            rates.push(photons as f64 / t);
        }
        rates.sort_by(f64::total_cmp);
        println!("| {stepper:?} | {tolerance:e} | {:.0} |", rates[1]);
    }
    Ok(())
}
