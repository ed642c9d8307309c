//! What the colour noise of a dispersive caustic costs: the rainbow's bow on the screen of
//! `scenes/rainbow.toml` (its camera view), rendered progressively with time budgets of 2.5 to
//! 40 s, beside the same scene with a non-dispersive drop (ior 1.333: photons carry every
//! wavelength in RGB and the bow is white). Each budget is rendered with two seeds; their
//! difference over √2 is one render's noise, so no converged reference is needed (one would
//! have to be far longer than the runs: a 2-minute reference of the dispersive bow is itself as
//! noisy as a 20 s run). Over the bow region (pixels whose caustic layer, in the longest runs,
//! is at least a quarter of its brightest row's mean) the study reports the RMS noise of
//! `beauty` (all channels) relative to the region's mean, and its chromatic part, the RMS of
//! each channel's departure from the pixel's grey (r − ⟨r,g,b⟩, …): the colour noise.
//!
//! `cargo run --release --example colour_noise_study -- [MAX_BUDGET]` (default 40 s; the
//! budgets halve down to 2.5 s); writes `out/colour_noise_study.csv`.

use grinlight::film::Film;
use std::io::Write;
use std::path::Path;

/// A progressive render of `text` for `seconds` with `seed`: the film, the time and passes.
fn run(
    text: &str,
    seconds: f64,
    seed: u64,
) -> Result<(Film, f64, u32), Box<dyn std::error::Error>> {
    let (scene, mut settings) =
        grinlight::scene::load::parse_scene(Path::new("scenes/rainbow.toml"), text.to_string())?;
    settings.seed = seed;
    settings.passes = u32::MAX;
    settings.time_budget = Some(seconds);
    let t = std::time::Instant::now();
    let (film, report) = grinlight::render::render(&scene, &settings, &())?;
    Ok((film, t.elapsed().as_secs_f64(), report.passes))
}

/// A pixel's grey.
fn grey(p: &[f32; 3]) -> f64 {
    (p[0] + p[1] + p[2]) as f64 / 3.0
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let max_budget: f64 = std::env::args().nth(1).map_or(Ok(40.0), |a| a.parse())?;
    let text = std::fs::read_to_string("scenes/rainbow.toml")?;
    let variants = [
        ("dispersive", text.clone()),
        (
            "non-dispersive",
            text.replace("ior = \"water\"", "ior = 1.333"),
        ),
    ];
    let mut budgets = vec![max_budget];
    while budgets.last().is_some_and(|b| *b > 2.5) {
        budgets.push(budgets.last().unwrap() / 2.0);
    }
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/colour_noise_study.csv")?;
    writeln!(
        csv,
        "variant,budget_s,seconds,passes,relative_noise,relative_colour_noise"
    )?;
    println!("| drop | budget (s) | time (s, mean of 2) | passes | bow noise / mean | colour noise / mean |");
    println!("|---|---|---|---|---|---|");
    for (name, text) in &variants {
        let mut region: Vec<usize> = Vec::new();
        let mut mean = 0.0;
        for &budget in &budgets {
            let (a, ta, passes) = run(text, budget, 1)?;
            let (b, tb, _) = run(text, budget, 2)?;
            let (a, b) = (
                a.layer("beauty").ok_or("no beauty")?,
                b.layer("beauty").ok_or("no beauty")?,
            );
            if region.is_empty() {
                // The bow, from the longest runs' caustic layers.
                let w = 480;
                let row = |y: usize| {
                    (0..w)
                        .map(|x| grey(&a[y * w + x]) + grey(&b[y * w + x]))
                        .sum::<f64>()
                };
                let top = (0..a.len() / w).map(row).fold(0.0, f64::max) / w as f64;
                region = (0..a.len())
                    .filter(|&i| grey(&a[i]) + grey(&b[i]) >= 0.25 * top)
                    .collect();
                mean = region
                    .iter()
                    .map(|&i| 0.5 * (grey(&a[i]) + grey(&b[i])))
                    .sum::<f64>()
                    / region.len() as f64;
            }
            let (mut all, mut colour) = (0.0, 0.0);
            for &i in &region {
                let (ga, gb) = (grey(&a[i]), grey(&b[i]));
                for c in 0..3 {
                    all += ((a[i][c] - b[i][c]) as f64).powi(2);
                    colour += ((a[i][c] as f64 - ga) - (b[i][c] as f64 - gb)).powi(2);
                }
            }
            let n = (3 * region.len()) as f64 * 2.0; // a difference holds two renders' noise
            let (all, colour) = ((all / n).sqrt() / mean, (colour / n).sqrt() / mean);
            let t = 0.5 * (ta + tb);
            println!("| {name} | {budget} | {t:.1} | {passes} | {all:.4} | {colour:.4} |");
            writeln!(csv, "{name},{budget},{t:.2},{passes},{all:.6},{colour:.6}")?;
        }
        println!(
            "({name}: bow region {} pixels, mean {mean:.3e})",
            region.len()
        );
    }
    Ok(())
}
