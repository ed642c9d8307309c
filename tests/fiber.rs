//! The GRIN fiber of `scenes/fiber_led.toml` as a measuring instrument.

use grinlight::scene::load_scene;
use std::path::Path;

fn flux(tolerance: f64, photons: u64) -> (f64, f64) {
    let mut scene = load_scene(Path::new("scenes/fiber_led.toml")).unwrap();
    scene.render.control = grinlight::curve::StepControl::Adaptive { tolerance };
    scene.render.receiver_photons = photons;
    let (m, report) = grinlight::render::measure(&scene, 0, 0).unwrap();
    assert_eq!(report.stats.photons_emitted, photons);
    m[0].flux
}

/// The flux on the receiver does not depend on the step control: adaptive RK4 at 1e-5 and at
/// 1e-8 agree within 4 combined standard errors (≈ 0.25 % each with 4·10⁴ photons). Before
/// the transport re-took the step that meets a surface in sub-steps, 1e-5 gave 2.6 % more
/// flux than 1e-9 or fixed 4 µm steps (measured), and this test failed.
#[test]
fn receiver_flux_does_not_depend_on_the_step_tolerance() {
    let (coarse, se_c) = flux(1e-5, 40_000);
    let (fine, se_f) = flux(1e-8, 40_000);
    let z = (coarse - fine) / (se_c * se_c + se_f * se_f).sqrt();
    println!("flux {coarse:.5e} ± {se_c:.1e} (1e-5), {fine:.5e} ± {se_f:.1e} (1e-8), z {z:.2}");
    assert!(z.abs() < 4.0, "z = {z}");
    // Of the LED's 10 mW, ~1 % misses the entry face, Fresnel takes ~4 % at each face and
    // nothing leaks through the wall (every ray refracted in is totally reflected there):
    // the receiver gets between 80 % and 95 %.
    assert!((0.008..0.0095).contains(&fine), "flux {fine}");
}

fn measure(scene: &grinlight::scene::Scene, pass: u64) -> grinlight::receiver::Measurement {
    grinlight::render::measure(scene, 0, pass)
        .unwrap()
        .0
        .remove(0)
}

/// `validate` in small: the GRIN fiber and its layered twin (Δn = 0.005) light the receiver
/// alike within noise, judged against the same statistic for two independent GRIN runs (χ²
/// per bin is inflated above 1 by bins holding few photons, so the GRIN-vs-GRIN value is the
/// yardstick); a twin built from a wrong index (n0 = 1.7 instead of 1.5) is caught.
#[test]
fn layered_twin_matches_the_grin_fiber_and_a_wrong_twin_does_not() {
    let photons = 60_000;
    let path = Path::new("scenes/fiber_led.toml");
    let load = |text: Option<String>| {
        let mut s = match text {
            Some(t) => grinlight::scene::load::parse_scene(path, t).unwrap(),
            None => load_scene(path).unwrap(),
        };
        s.render.receiver_photons = photons;
        s
    };
    let grin = load(None);
    let a = measure(&grin, 0);
    let baseline = grinlight::receiver::compare(&a, &measure(&grin, 7));
    let mut twin = load(None);
    let layers = twin.layer_fiber(0.005).unwrap();
    assert_eq!(layers.len(), 4);
    let good = grinlight::receiver::compare(&a, &measure(&twin, 1));
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("n0 = 1.5", "n0 = 1.7");
    let mut wrong = load(Some(text));
    wrong.layer_fiber(0.005).unwrap();
    let bad = grinlight::receiver::compare(&a, &measure(&wrong, 2));
    println!("GRIN vs GRIN {baseline:?}\nGRIN vs layered {good:?}\nGRIN vs wrong {bad:?}");
    let z = |c: &grinlight::receiver::Comparison| (c.flux_ratio - 1.0) / c.flux_ratio_stderr;
    assert!(
        z(&good).abs() < 4.0,
        "flux ratio {} ± {}",
        good.flux_ratio,
        good.flux_ratio_stderr
    );
    // χ²/dof has a standard deviation of about √(2/dof) ≈ 0.03 here; allow 0.15 above the
    // GRIN-vs-GRIN value.
    assert!(
        good.chi2_per_dof < baseline.chi2_per_dof + 0.15,
        "{good:?} vs {baseline:?}"
    );
    assert!(
        z(&bad).abs() > 4.0 || bad.chi2_per_dof > baseline.chi2_per_dof + 0.15,
        "{bad:?}"
    );
}

/// A meridional ray launched along the axis direction at height x0 = 0.05 mm inside the
/// entry face reaches the receiver where the paraxial path says: x(z) = x0 cos(√a z) in
/// the core (pitch 2π/√a), slope −x0 √a sin(√a L) at the exit face, refracted there by
/// Snell (n(x(L)) sin θ = sin θ_out) and carried straight over the 0.05 mm gap. The
/// paraxial model's own error for this amplitude is O(a x0²) ≈ 3e-4 relative to x0 over one
/// pitch (measured: 1.1e-4·x0); the tolerance is 1e-3·x0 = 5e-5 mm, 1/500 of a receiver bin.
#[test]
fn a_meridional_ray_reaches_the_receiver_where_the_paraxial_path_says() {
    use glam::DVec3;
    use grinlight::transport::{Event, Stats, Tracer};
    let scene = load_scene(Path::new("scenes/fiber_led.toml")).unwrap();
    let tracer = Tracer::new(&scene);
    let core = (0..)
        .find(|&i| scene.medium_names().nth(i) == Some("core"))
        .unwrap();
    let (a, n0, len, gap, x0) = (0.10667f64, 1.5f64, 20.0f64, 0.05f64, 0.05f64);
    let mut stats = Stats::default();
    let (mut origin, mut dir, mut medium) = (DVec3::new(x0, 0.0, 1e-9), DVec3::Z, Some(core));
    // Core → exit face (refract: u = 1 is never below the Fresnel reflectance) → receiver.
    let hit = loop {
        let Event::Surface {
            prim,
            position,
            normal,
            direction,
        } = tracer.next_event(origin, dir, medium, &mut stats)
        else {
            panic!("the ray was lost");
        };
        let surface = scene.surfaces[prim];
        if matches!(
            scene.materials[surface.material],
            grinlight::material::Material::Detector { .. }
        ) {
            break position;
        }
        let b = tracer
            .specular_bounce(surface, medium, position, direction, normal, 1.0)
            .unwrap();
        (origin, dir, medium) = (b.origin, b.direction, b.medium);
    };
    let k = a.sqrt();
    let x_l = x0 * (k * len).cos();
    let slope = -x0 * k * (k * len).sin();
    let sin_in = slope / (1.0 + slope * slope).sqrt();
    let n_l = n0 * (1.0 - 0.5 * a * x_l * x_l);
    let sin_out = n_l * sin_in;
    let want = x_l + gap * sin_out / (1.0 - sin_out * sin_out).sqrt();
    println!(
        "receiver hit x {:.6e} mm, paraxial {want:.6e} mm (x(L) {x_l:.6e})",
        hit.x
    );
    assert!((hit.x - want).abs() < 1e-3 * x0, "{} vs {want}", hit.x);
    assert!(hit.y.abs() < 1e-12 && (hit.z - (len + gap)).abs() < 1e-9);
}
