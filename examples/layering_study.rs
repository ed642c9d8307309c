//! How fast does the layered twin of `scenes/fiber_led.toml` converge to the GRIN fiber, ray
//! by ray? Principal rays (at each interface the likelier branch: reflected where the Fresnel
//! reflectance exceeds 1/2, refracted otherwise) cross the fiber and land on the receiver; each layered twin's landing point is
//! compared with the GRIN fiber's (RK4, adaptive 1e-9). Two families of 64 rays each, all
//! guided by the gradient (θ ≤ 0.16 rad inside, below the 0.163 rad at which they would reach
//! the wall): meridional rays from the axis at angle θ, and skew rays from r = 0.1 mm turned
//! by θ out of the meridional plane. Layerings: equal Δn (Zhdanov et al.'s (2020) rule) and equal width.
//! Prints the RMS and median landing error against the layer count and writes
//! `out/layering_study.csv` and `out/layering_study.png` (RMS error against the largest layer
//! width, log-log; red equal Δn, blue equal width).
//!
//! `cargo run --release --example layering_study`

use glam::DVec3;
use grinlight::plot::{canvas, save, Labels, Panel, PALETTE};
use grinlight::scene::{load_description, Scene};
use grinlight::settings::TraceSettings;
use grinlight::transport::chain::principal_ray;
use grinlight::transport::Tracer;
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// The rays: (start, direction, start radius).
fn rays() -> Vec<(DVec3, DVec3, f64)> {
    let mut v = Vec::new();
    for i in 1..=64 {
        let t = 0.16 * i as f64 / 64.0;
        v.push((
            DVec3::new(0.0, 0.0, 1e-9),
            DVec3::new(t.sin(), 0.0, t.cos()),
            0.0,
        ));
        v.push((
            DVec3::new(0.1, 0.0, 1e-9),
            DVec3::new(0.0, t.sin(), t.cos()),
            0.1,
        ));
    }
    v
}

/// Landing points on the receiver, with the mean number of surfaces met, for the rays started
/// in the medium `medium_at(r)`.
fn land(
    scene: &Scene,
    trace: &TraceSettings,
    medium_at: impl Fn(f64) -> grinlight::ids::MediumId,
) -> (Vec<Option<DVec3>>, f64) {
    let tracer = Tracer::new(scene, trace);
    let mut events = 0;
    let hits: Vec<Option<DVec3>> = rays()
        .into_iter()
        .map(|(o, d, r)| {
            principal_ray(&tracer, o, d, Some(medium_at(r)), 1_000_000).map(|(p, n)| {
                events += n;
                p
            })
        })
        .collect();
    let n = hits.len() as f64;
    (hits, events as f64 / n)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = Path::new("scenes/fiber_led.toml");
    let (grin, mut grin_settings) = load_description(path)?;
    grin_settings.trace.control = grinlight::curve::StepControl::Adaptive { tolerance: 1e-9 };
    let core = grin.grin_fiber().ok_or("no GRIN fiber")?.medium;
    let grin = grin.build();
    let (reference, _) = land(&grin, &grin_settings.trace, |_| core);
    if reference.iter().any(Option::is_none) {
        return Err("a GRIN ray missed the receiver".into());
    }
    println!("| layering | layers | widest layer (mm) | surfaces per ray | RMS error (mm) | median error (mm) | time (s) |");
    println!("|---|---|---|---|---|---|---|");
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/layering_study.csv")?;
    writeln!(
        csv,
        "rule,parameter,layers,widest,surfaces_per_ray,rms,median,seconds"
    )?;
    let mut series = [Vec::new(), Vec::new()];
    let configs = [0.01, 0.005, 0.0025, 0.001, 0.0005, 0.00025, 0.0001]
        .map(|dn| ("equal Δn", dn, (dn, f64::INFINITY)))
        .into_iter()
        .chain(
            [0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 0.0005]
                .map(|w| ("equal width", w, (1.0, w))),
        );
    for (rule, parameter, (dn, width)) in configs {
        let (mut twin, mut settings) = load_description(path)?;
        let t = Instant::now();
        let layers = twin.layer_fiber(&mut settings.trace, dn, width)?;
        let twin = twin.build();
        let first = twin.medium_names().count() - layers.len();
        let (hits, per_ray) = land(&twin, &settings.trace, |r| {
            grinlight::ids::MediumId::new(
                first + layers.iter().position(|l| r < l.outer).unwrap_or(0),
            )
        });
        let seconds = t.elapsed().as_secs_f64();
        let mut errors: Vec<f64> = hits
            .iter()
            .zip(&reference)
            .map(|(h, r)| h.map_or(f64::INFINITY, |h| (h - r.unwrap()).length()))
            .collect();
        errors.sort_by(f64::total_cmp);
        let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
        let median = errors[errors.len() / 2];
        let widest = layers.iter().map(|l| l.outer - l.inner).fold(0.0, f64::max);
        println!(
            "| {rule} {parameter} | {} | {widest:.4} | {per_ray:.0} | {rms:.4} | {median:.4} | {seconds:.2} |",
            layers.len()
        );
        writeln!(
            csv,
            "{rule},{parameter},{},{widest},{per_ray},{rms},{median},{seconds}",
            layers.len()
        )?;
        series[usize::from(rule == "equal width")].push((widest, rms));
    }
    for (k, s) in series.iter().enumerate() {
        // Least-squares slope of log RMS against log width.
        let n = s.len() as f64;
        let (x, y): (Vec<f64>, Vec<f64>) = s.iter().map(|p| (p.0.ln(), p.1.ln())).unzip();
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let slope = x
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - mx) * (b - my))
            .sum::<f64>()
            / x.iter().map(|a| (a - mx).powi(2)).sum::<f64>();
        let name = ["equal Δn", "equal width"][k];
        println!("{name}: RMS error ∝ (widest layer)^{slope:.2}");
    }
    let all = || series.iter().flatten();
    let range = |f: fn(&(f64, f64)) -> f64| {
        (
            all().map(f).fold(f64::INFINITY, f64::min) * 0.8,
            all().map(f).fold(0.0, f64::max) * 1.25,
        )
    };
    let mut img = canvas(680, 540);
    let mut panel = Panel::new(
        &mut img,
        (90, 60, 560, 420),
        range(|p| p.0),
        range(|p| p.1),
        (true, true),
    );
    panel.axes(&Labels {
        title: "layered twin: landing error of principal rays",
        x: "widest layer (mm)",
        y: "RMS landing error (mm)",
    });
    panel.legend(&[(PALETTE[0], "equal Δn"), (PALETTE[1], "equal width")]);
    for (s, color) in series.iter().zip(PALETTE) {
        panel.polyline(s, color);
        for p in s {
            panel.marker(p.0, p.1, color);
        }
    }
    save(&img, Path::new("out/layering_study.png"))?;
    println!("wrote out/layering_study.csv and out/layering_study.png");
    Ok(())
}
