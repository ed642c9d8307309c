//! Compares a render of a scene with an independent reference image (linear RGB EXR of the
//! same camera, e.g. `refs/cornell_diffuse.reference.exr` or one made by
//! `bench/mitsuba_reference.py`) and prints the render's time, its root-mean-square error per
//! pixel and channel relative to the reference's mean, the mean ratio over the image and the
//! 16 × 16 block ratios: their 5th and 95th percentiles, the worst, and the grid.
//!
//! `cargo run --release --example reference_check -- SCENE.toml REFERENCE.exr [WIDTH] [PASSES] [INTEGRATOR]`
//!
//! WIDTH (default: the scene's) must divide the reference's width; PASSES defaults to the
//! scene's; INTEGRATOR is `photon_map` (default) or `path`.

use grinlight::compare::{mean_ratios, read_exr_layer, relative_rmse, MeanRatios};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(scene_path), Some(reference_path)) = (args.first(), args.get(1)) else {
        return Err(
            "usage: reference_check SCENE.toml REFERENCE.exr [WIDTH] [PASSES] [INTEGRATOR]".into(),
        );
    };
    let (mut scene, mut settings) = grinlight::scene::load_scene(Path::new(scene_path))?;
    let camera = scene.camera.as_mut().ok_or("the scene has no camera")?;
    if let Some(w) = args.get(2) {
        let width: u32 = w.parse()?;
        camera.height = camera.height * width / camera.width;
        camera.width = width;
    }
    let (width, height) = (camera.width as usize, camera.height as usize);
    if let Some(p) = args.get(3) {
        settings.passes = p.parse()?;
    }
    if let Some(i) = args.get(4) {
        let integrator =
            grinlight::settings::INTEGRATOR.read(&grinlight::settings::Given::from_text(i))?;
        integrator.apply(&mut grinlight::settings::Target {
            settings: &mut settings,
            camera: None,
        });
    }
    let t = std::time::Instant::now();
    let (film, report) = grinlight::render::render(&scene, &settings, &())?;
    let seconds = t.elapsed().as_secs_f64();
    let reference = read_exr_layer(Path::new(reference_path), None)?;
    let (rw, rh) = (reference.width, reference.height);
    if rw % width != 0 || rh / (rw / width) != height {
        return Err(format!("the reference is {rw}×{rh}, the render {width}×{height}").into());
    }
    let reference = reference.downsample(rw / width).pixels;
    let beauty = film.layer("beauty").ok_or("no beauty layer")?;
    let MeanRatios { overall, blocks } = mean_ratios(&beauty, &reference, width, 16);
    let mut sorted = blocks.clone();
    sorted.sort_by(f64::total_cmp);
    let at = |q: f64| sorted[((sorted.len() - 1) as f64 * q).round() as usize];
    let worst = blocks.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    let rmse = relative_rmse(&beauty, &reference);
    println!(
        "{width}×{height}, {} passes, {:?}, {seconds:.1} s: relative RMSE {rmse:.4}; mean ratio \
         {overall:.4}; 16×16 \
         blocks: 5th percentile {:.4}, 95th {:.4}, worst |ratio − 1| {worst:.4} over {}",
        settings.passes,
        settings.integrator,
        at(0.05),
        at(0.95),
        blocks.len()
    );
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
