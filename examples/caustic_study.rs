//! Caustic-region error against run time on `scenes/cornell_caustic.toml` (256 × 256, all
//! cores): progressive renders with time budgets of 5, 10, 20, 40 and 80 s, each compared
//! with a long progressive render of the same scene (its own seed). The caustic region is
//! where the reference's caustic layer holds ≥ 10 % of its beauty; the error is the RMSE of
//! `beauty` there (linear radiance, all channels). The same budgets are then given to the path
//! tracer (same samples per pass, no photons).
//!
//! `cargo run --release --example caustic_study -- [REFERENCE_SECONDS] [CAUSTIC_PHOTONS] [SPP]
//! [GATHER] [MAX_BUDGET]` (defaults 300 s, 100000 per pass, 4, 2 for the timed runs, 80 s); the reference (300 000
//! caustic photons, 4 spp, 2 gather rays per pass) is kept in `out/caustic_reference.exr` and
//! reused while that file exists; writes `out/caustic_study.csv`.

use grinlight::compare::read_exr_layer;
use grinlight::film::Film;
use grinlight::settings::IntegratorKind;
use std::io::Write;
use std::path::Path;

/// Settings of a run: caustic photons per pass, spp per pass, gather rays.
type Settings = (u64, u32, u32);

fn run(
    seconds: f64,
    seed: u64,
    (caustic, spp, gather): Settings,
    integrator: IntegratorKind,
) -> Result<(Film, f64, u32), Box<dyn std::error::Error>> {
    let (scene, mut settings) =
        grinlight::scene::load_scene(Path::new("scenes/cornell_caustic.toml"))?;
    settings.integrator = integrator;
    settings.seed = seed;
    settings.spp = spp;
    settings.photons.gather = gather;
    settings.photons.caustic = caustic;
    settings.passes = u32::MAX;
    settings.time_budget = Some(seconds);
    let t = std::time::Instant::now();
    let (film, report) = grinlight::render::render(&scene, &settings, &())?;
    Ok((film, t.elapsed().as_secs_f64(), report.passes))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let reference_seconds: f64 = args.first().map_or(Ok(300.0), |a| a.parse())?;
    let settings: Settings = (
        args.get(1).map_or(Ok(100_000), |a| a.parse())?,
        args.get(2).map_or(Ok(4), |a| a.parse())?,
        args.get(3).map_or(Ok(2), |a| a.parse())?,
    );
    let cached = Path::new("out/caustic_reference.exr");
    std::fs::create_dir_all("out")?;
    if !cached.exists() {
        let (reference, t, passes) = run(
            reference_seconds,
            1000,
            (300_000, 4, 2),
            IntegratorKind::PhotonMap,
        )?;
        println!("reference: {passes} passes in {t:.0} s");
        reference.write_exr(cached)?;
    }
    let beauty = read_exr_layer(cached, Some("beauty"))?;
    assert_eq!(beauty.width, 256);
    let beauty = beauty.pixels;
    let caustic = read_exr_layer(cached, Some("caustic"))?.pixels;
    let region: Vec<usize> = (0..beauty.len())
        .filter(|&i| {
            caustic[i][0] + caustic[i][1] + caustic[i][2]
                >= 0.1 * (beauty[i][0] + beauty[i][1] + beauty[i][2])
                && caustic[i][0] > 0.0
        })
        .collect();
    println!("caustic region: {} pixels", region.len());
    let mut csv = std::fs::File::create("out/caustic_study.csv")?;
    writeln!(
        csv,
        "integrator,budget_s,seconds,passes,rmse,mean_reference"
    )?;
    let mean_ref = region
        .iter()
        .map(|&i| beauty[i].iter().sum::<f32>() as f64 / 3.0)
        .sum::<f64>()
        / region.len() as f64;
    println!("| integrator | budget (s) | time (s) | passes | caustic-region RMSE |\n|---|---|---|---|---|");
    let max_budget: f64 = args.get(4).map_or(Ok(80.0), |a| a.parse())?;
    let budgets = [5.0, 10.0, 20.0, 40.0, 80.0]
        .into_iter()
        .filter(|b| *b <= max_budget);
    // The path tracer at the same camera samples per pass (no photons).
    let runs = budgets
        .clone()
        .map(|b| (IntegratorKind::PhotonMap, b))
        .chain(budgets.map(|b| (IntegratorKind::Path, b)));
    for (integrator, budget) in runs {
        let (film, t, passes) = run(budget, 1, settings, integrator)?;
        let b = film.layer("beauty").ok_or("no beauty")?;
        let se: f64 = region
            .iter()
            .map(|&i| {
                (0..3)
                    .map(|c| ((b[i][c] - beauty[i][c]) as f64).powi(2))
                    .sum::<f64>()
            })
            .sum();
        let rmse = (se / (3 * region.len()) as f64).sqrt();
        println!("| {integrator:?} | {budget} | {t:.1} | {passes} | {rmse:.4} |");
        writeln!(
            csv,
            "{integrator:?},{budget},{t:.2},{passes},{rmse:.6},{mean_ref:.6}"
        )?;
    }
    println!("mean beauty in the region (reference): {mean_ref:.4}");
    Ok(())
}
