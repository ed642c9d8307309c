//! Tessendorf (2022) fig. 9 from the rendered rays: the camera rays of `scenes/black_hole.toml` along
//! the image's middle row, traced through the hole's index by the renderer's own transport,
//! give deflection against impact parameter. Each is compared with the exact deflection of the
//! index model for a ray starting at the camera (`media::black_hole_deflection`) and with the
//! weak-field 2 rs/b. Prints a table and the worst relative disagreement with the exact
//! curve, also after adding back the deflection the scene gives up by ending rays at its
//! `world_radius` R (a straight-line tail estimate, (rs/b)(1 − √(1 − (b/R)²)) ≈ rs b/2R²); writes `out/black_hole_deflection.csv` and a log-log plot
//! `out/black_hole_deflection.png` (red: rendered rays, blue: exact, green: 2 rs/b).
//!
//! Then the same row of `scenes/schwarzschild.toml` (the exact index), each ray's
//! deflection against general relativity's between the camera and the point where the ray
//! left the world ([`ExactBlackHole::gr_deflection`], no tail needed); both curves are drawn
//! side by side (purple: exact hole's rendered rays, yellow: GR), with the perturbation series
//! of GR's deflection from infinity to infinity to 20 orders (Tessendorf (2022) eq. 27 is such a
//! series; [`schwarzschild_deflection_series`]), down to the photon sphere where it stops
//! converging.

use grinlight::media::{
    black_hole_deflection, schwarzschild_deflection_series, ExactBlackHole, Medium,
};
use grinlight::plot::{canvas, save, Labels, Panel, PALETTE};
use grinlight::transport::{Event, Stats, Tracer};
use std::io::Write;
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (scene, settings) = grinlight::scene::load_scene(Path::new("scenes/black_hole.toml"))?;
    let camera = scene.camera.as_ref().ok_or("no camera")?;
    let hole = scene.ambient().ok_or("no ambient medium")?;
    let medium = scene.medium_at(hole);
    let (rs, q, center) = (0.01, 0.1, glam::DVec3::ZERO); // as in the scene file
    let tracer = Tracer::new(&scene, &settings.trace);
    let mut stats = Stats::default();
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/black_hole_deflection.csv")?;
    writeln!(csv, "pixel,b_rs,rendered_rad,exact_rad,weak_field_rad")?;
    let (mut rendered, mut exact, mut weak) = (Vec::new(), Vec::new(), Vec::new());
    let mut worst: f64 = 0.0;
    let mut worst_with_tail: f64 = 0.0;
    let world = settings.trace.world_radius.ok_or("no world_radius")? / rs;
    let row = camera.height / 2;
    let t = std::time::Instant::now();
    for px in camera.width / 2..camera.width {
        let grinlight::camera::PrimaryRay {
            origin: o,
            direction: d,
        } = camera.ray(grinlight::camera::FilmPoint::pixel_centre(px, row));
        let r0 = (o - center).length();
        let sin_psi = (o - center).normalize().cross(d).length();
        let n0 = medium.sample(o).ok_or("camera inside the horizon")?.n;
        let b = n0 * r0 * sin_psi / rs;
        let Event::Escaped { direction: out, .. } =
            tracer.next_event(o, d, scene.ambient(), &mut stats)
        else {
            continue; // captured
        };
        let phi = d.cross(out).length().atan2(d.dot(out));
        let Some(want) = black_hole_deflection(b, q, rs / r0) else {
            continue;
        };
        worst = worst.max((phi - want).abs() / want);
        let tail = (1.0 - (1.0 - (b / world).powi(2)).sqrt()) / b;
        worst_with_tail = worst_with_tail.max((phi + tail - want).abs() / want);
        writeln!(csv, "{px},{b:.6},{phi:.9e},{want:.9e},{:.9e}", 2.0 / b)?;
        rendered.push((b, phi));
        exact.push((b, want));
        weak.push((b, 2.0 / b));
    }
    println!(
        "{} escaping rays of the middle row traced in {:.2} s ({} curved steps)",
        rendered.len(),
        t.elapsed().as_secs_f64(),
        stats.curved_steps
    );
    println!("| b (rs) | rendered (rad) | exact (rad) | 2 rs/b |\n|---|---|---|---|");
    for i in (0..rendered.len()).step_by((rendered.len() / 8).max(1)) {
        println!(
            "| {:.2} | {:.6e} | {:.6e} | {:.6e} |",
            rendered[i].0, rendered[i].1, exact[i].1, weak[i].1
        );
    }
    println!("worst |rendered − exact| / exact: {worst:.2e}; with the tail beyond world_radius added back: {worst_with_tail:.2e}");
    let (schwarzschild, gr) = exact_row()?;
    let mut img = canvas(680, 540);
    let bs = rendered.iter().chain(&schwarzschild).map(|p| p.0);
    let bx = (
        bs.clone().fold(f64::INFINITY, f64::min),
        bs.fold(0.0, f64::max),
    );
    let ys = rendered
        .iter()
        .chain(&weak)
        .chain(&schwarzschild)
        .map(|p| p.1);
    let y = (
        ys.clone().fold(f64::INFINITY, f64::min),
        ys.fold(0.0, f64::max),
    );
    let mut panel = Panel::new(&mut img, (90, 60, 560, 420), bx, y, (true, true));
    panel.axes(&Labels {
        title: "black hole: deflection of the rendered rays",
        x: "impact parameter b (rs)",
        y: "deflection (rad)",
    });
    panel.legend(&[
        (PALETTE[0], "rendered rays"),
        (PALETTE[1], "exact, index model"),
        (PALETTE[2], "weak field 2 rs/b"),
        (PALETTE[3], "Schwarzschild: rendered"),
        (PALETTE[4], "Schwarzschild: GR"),
        (PALETTE[5], "GR series, 20 orders"),
    ]);
    // The series in μ = M/r₀ (M = rs/2), b = r₀/√(1 − 2μ): b/rs = 1/(2μ√(1 − 2μ)).
    let series: Curve = (1..=300)
        .map(|k| 1e-3 * k as f64)
        .map(|mu| {
            let b = 1.0 / (2.0 * mu * (1.0 - 2.0 * mu).sqrt());
            (b, schwarzschild_deflection_series(mu, 20))
        })
        .filter(|&(b, _)| (bx.0..=bx.1).contains(&b))
        .collect();
    panel.polyline(&series, PALETTE[5]);
    panel.polyline(&weak, PALETTE[2]);
    panel.polyline(&exact, PALETTE[1]);
    panel.polyline(&gr, PALETTE[4]);
    for (x, v) in rendered.iter().step_by(8) {
        panel.marker(*x, *v, PALETTE[0]);
    }
    for (x, v) in schwarzschild.iter().step_by(8) {
        panel.marker(*x, *v, PALETTE[3]);
    }
    save(&img, Path::new("out/black_hole_deflection.png"))?;
    println!("wrote out/black_hole_deflection.csv and out/black_hole_deflection.png");
    Ok(())
}

/// The middle row of `scenes/schwarzschild.toml` traced ray by ray: (b in rs, deflection) of
/// the rendered rays and of GR between the camera and each ray's exit from the world.
type Curve = Vec<(f64, f64)>;
fn exact_row() -> Result<(Curve, Curve), Box<dyn std::error::Error>> {
    let (scene, settings) = grinlight::scene::load_scene(Path::new("scenes/schwarzschild.toml"))?;
    let camera = scene.camera.as_ref().ok_or("no camera")?;
    let rs = 0.01; // as in the scene file
    let hole = ExactBlackHole {
        center: glam::DVec3::ZERO,
        rs,
        q: 0.0,
    };
    let tracer = Tracer::new(&scene, &settings.trace);
    let (mut rendered, mut gr) = (Vec::new(), Vec::new());
    let mut worst: f64 = 0.0;
    let row = camera.height / 2;
    for px in camera.width / 2..camera.width {
        let grinlight::camera::PrimaryRay {
            origin: o,
            direction: d,
        } = camera.ray(grinlight::camera::FilmPoint::pixel_centre(px, row));
        let n0 = hole.sample(o).ok_or("camera inside the horizon")?.n;
        let b = n0 * o.length() * o.normalize().cross(d).length();
        let Event::Escaped {
            direction: out,
            position,
            ..
        } = tracer.next_event(o, d, scene.ambient(), &mut Stats::default())
        else {
            continue; // captured
        };
        let phi = d.cross(out).length().atan2(d.dot(out));
        let u = |rho: f64| 1.0 / hole.areal_radius(rho);
        let Some(want) = hole.gr_deflection(b, u(o.length()), u(position.length())) else {
            continue;
        };
        worst = worst.max((phi - want).abs() / want);
        rendered.push((b / rs, phi));
        gr.push((b / rs, want));
    }
    println!(
        "schwarzschild.toml: {} escaping rays of the middle row, worst |rendered − GR| / GR {worst:.2e}",
        rendered.len()
    );
    Ok((rendered, gr))
}
