//! Caustic-region error against run time on `scenes/cornell_caustic.toml` (256 × 256, all
//! cores): progressive renders with time budgets of 5, 10, 20, 40 and 80 s, each compared
//! with a long progressive render of the same scene (its own seed). The caustic region is
//! where the reference's caustic layer holds ≥ 10 % of its beauty; the error is the RMSE of
//! `beauty` there (linear radiance, all channels).
//!
//! `cargo run --release --example caustic_study -- [REFERENCE_SECONDS]` (default 300);
//! writes `out/caustic_study.csv`.

use grinlight::film::Film;
use std::io::Write;
use std::path::Path;

fn run(seconds: f64, seed: u64) -> Result<(Film, f64, u32), Box<dyn std::error::Error>> {
    let mut scene = grinlight::scene::load_scene(Path::new("scenes/cornell_caustic.toml"))?;
    scene.render.seed = seed;
    scene.render.spp = 4;
    scene.render.gather = 2;
    scene.render.passes = u32::MAX;
    scene.render.time_budget = Some(seconds);
    let t = std::time::Instant::now();
    let (film, report) = grinlight::render::render(&scene, 0, &|_| {}, &mut |_, _| Ok(()))?;
    Ok((film, t.elapsed().as_secs_f64(), report.passes))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let reference_seconds: f64 = std::env::args().nth(1).map_or(Ok(300.0), |a| a.parse())?;
    let (reference, t, passes) = run(reference_seconds, 1000)?;
    println!("reference: {passes} passes in {t:.0} s");
    let beauty = reference.layer("beauty").ok_or("no beauty")?;
    let caustic = reference.layer("caustic").ok_or("no caustic")?;
    let region: Vec<usize> = (0..beauty.len())
        .filter(|&i| {
            caustic[i][0] + caustic[i][1] + caustic[i][2]
                >= 0.1 * (beauty[i][0] + beauty[i][1] + beauty[i][2])
                && caustic[i][0] > 0.0
        })
        .collect();
    println!("caustic region: {} pixels", region.len());
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/caustic_study.csv")?;
    writeln!(csv, "budget_s,seconds,passes,rmse,mean_reference")?;
    let mean_ref = region
        .iter()
        .map(|&i| beauty[i].iter().sum::<f32>() as f64 / 3.0)
        .sum::<f64>()
        / region.len() as f64;
    println!("| budget (s) | time (s) | passes | caustic-region RMSE |\n|---|---|---|---|");
    for budget in [5.0, 10.0, 20.0, 40.0, 80.0] {
        let (film, t, passes) = run(budget, 1)?;
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
        println!("| {budget} | {t:.1} | {passes} | {rmse:.4} |");
        writeln!(csv, "{budget},{t:.2},{passes},{rmse:.6},{mean_ref:.6}")?;
    }
    println!("mean beauty in the region (reference): {mean_ref:.4}");
    Ok(())
}
