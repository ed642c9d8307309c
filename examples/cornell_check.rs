//! Compares `scenes/cornell_diffuse.toml` with the independent reference in
//! `refs/` at a chosen size and sampling, and prints the mean ratio over the image
//! and the worst 16×16-block ratios.
//!
//! `cargo run --release --example cornell_check -- [WIDTH] [SPP] [PHOTONS] [GATHER] [PASSES] [KNN]`

use grinlight::film::{downsample, mean_ratios, read_exr_layer};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let arg = |i: usize, d: u64| args.get(i).copied().unwrap_or(d);
    let width = arg(0, 128) as usize;
    let (mut scene, mut settings) =
        grinlight::scene::load_scene(Path::new("scenes/cornell_diffuse.toml"))?;
    settings.spp = arg(1, 4) as u32;
    settings.photons.global = arg(2, 100_000);
    settings.photons.gather = arg(3, 16) as u32;
    settings.passes = arg(4, 1) as u32;
    settings.photons.knn = arg(5, 64) as u32;
    let camera = scene.camera.as_mut().ok_or("no camera")?;
    (camera.width, camera.height) = (width as u32, width as u32);
    let t = std::time::Instant::now();
    let (film, report) = grinlight::render::render(&scene, &settings, &())?;
    let seconds = t.elapsed().as_secs_f64();
    let (rw, rh, reference) =
        read_exr_layer(Path::new("refs/cornell_diffuse.reference.exr"), None)?;
    let reference = downsample(&reference, rw, rh, rw / width);
    let beauty = film.layer("beauty").ok_or("no beauty")?;
    let (overall, blocks) = mean_ratios(&beauty, &reference, width, 16);
    let worst = blocks.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    println!("{width}×{width}, {seconds:.1} s: mean ratio {overall:.4}, worst block |ratio − 1| {worst:.4} over {} blocks", blocks.len());
    for row in blocks.chunks(width / 16) {
        println!(
            "  {}",
            row.iter()
                .map(|r| format!("{r:.3}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    println!("{}", report.summary());
    Ok(())
}
