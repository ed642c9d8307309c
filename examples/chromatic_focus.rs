//! The focal shift of `scenes/grin_lens_chromatic.toml`: the RMS radius of the white point
//! source's image on each of the 17 receivers behind the GRIN rod lens, per wavelength band,
//! against the distance behind the rod — each band's curve has its waist at its own focus,
//! blue first. Writes `out/chromatic_focus.csv` (distance, then the RMS radius per band, mm)
//! and `out/chromatic_focus.png`.
//!
//! `cargo run --release --example chromatic_focus -- [PHOTONS]` (default: the scene's
//! receiver_photons, 10⁶).

use grinlight::plot::{canvas, range_of, save, Labels, Panel};
use std::io::Write;
use std::path::Path;

/// The bands' line colours: blue, green, red.
const COLOURS: [[u8; 3]; 3] = [[40, 70, 220], [30, 150, 60], [210, 40, 40]];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (scene, mut settings) =
        grinlight::scene::load_scene(Path::new("scenes/grin_lens_chromatic.toml"))?;
    if let Some(n) = std::env::args().nth(1) {
        settings.receiver_photons = n.parse()?;
    }
    let t = std::time::Instant::now();
    let (m, _, _) = grinlight::render::measure(&scene, &settings, 0, &())?;
    println!(
        "{} photons in {:.1} s",
        settings.receiver_photons,
        t.elapsed().as_secs_f64()
    );
    // The rod's exit face is at z = 4 mm.
    let behind: Vec<f64> = scene.receivers.iter().map(|r| r.center.z - 4.0).collect();
    let bands = &scene.receivers[0].bands;
    let rms: Vec<Vec<f64>> = (0..bands.len())
        .map(|k| {
            scene
                .receivers
                .iter()
                .zip(&m)
                .map(|(rec, meas)| meas.bands[k].mean_square_radius(rec).sqrt())
                .collect()
        })
        .collect();
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/chromatic_focus.csv")?;
    let names: Vec<String> = bands
        .iter()
        .map(|(lo, hi)| format!("rms_radius_{lo}_{hi}"))
        .collect();
    writeln!(csv, "behind_mm,{}", names.join(","))?;
    for (i, z) in behind.iter().enumerate() {
        let row: Vec<String> = rms.iter().map(|r| format!("{:.6}", r[i])).collect();
        writeln!(csv, "{z:.3},{}", row.join(","))?;
    }
    println!("| band (nm) | least RMS radius (mm) | at (mm behind the rod) |");
    println!("|---|---|---|");
    for ((lo, hi), r) in bands.iter().zip(&rms) {
        let (i, least) = r
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("17 receivers");
        println!("| {lo}–{hi} | {least:.4} | {:.2} |", behind[i]);
    }
    let mut img = canvas(720, 480);
    let x = range_of(behind.iter().copied());
    let y = range_of(rms.iter().flatten().copied().chain([0.0]));
    let mut panel = Panel::new(&mut img, (80, 40, 600, 380), x, y, (false, false));
    panel.axes(&Labels {
        title: "GRIN rod lens: RMS spot radius per band (focal shift)",
        x: "distance behind the rod (mm)",
        y: "RMS radius (mm)",
    });
    let labels: Vec<String> = bands
        .iter()
        .map(|(lo, hi)| format!("{lo}–{hi} nm"))
        .collect();
    for (r, c) in rms.iter().zip(COLOURS) {
        let pts: Vec<(f64, f64)> = behind.iter().copied().zip(r.iter().copied()).collect();
        panel.polyline(&pts, c);
        for &(px, py) in &pts {
            panel.marker(px, py, c);
        }
    }
    let legend: Vec<([u8; 3], &str)> = COLOURS
        .iter()
        .copied()
        .zip(labels.iter().map(String::as_str))
        .collect();
    panel.legend(&legend);
    save(&img, Path::new("out/chromatic_focus.png"))?;
    println!("wrote out/chromatic_focus.csv and out/chromatic_focus.png");
    Ok(())
}
