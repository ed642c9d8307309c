//! The exact black holes (Schwarzschild and Reissner–Nordström as index media in
//! isotropic coordinates) against general relativity's own formulas in areal coordinates:
//! the index, the horizon, the photon sphere, the deflection of traced rays
//! ([`ExactBlackHole::gr_deflection`], GR's orbit quadrature from the metric, not from the
//! index), capture.

use glam::DVec3;
use grinlight::curve::{
    march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind, Termination,
};
use grinlight::media::{schwarzschild_deflection_series, ExactBlackHole, Medium};
use std::f64::consts::PI;

/// GR's f(r) = 1 − 2M/r + Q²/r² as a function of u = 1/r (M = rs/2, Q = q·rs).
fn lapse2(hole: &ExactBlackHole, u: f64) -> f64 {
    let (m, charge) = (0.5 * hole.rs, hole.q * hole.rs);
    1.0 - 2.0 * m * u + charge * charge * u * u
}

/// The ray of impact parameter `b` traced with an adaptive stepper at `tolerance` from isotropic
/// radius `start` (heading in, its local angle to the radial direction from n ρ sin ψ = b)
/// until it leaves the ball of radius `end`: its deflection and the GR value for the same
/// two observers, or None if it was captured; and the march's steps.
fn traced(
    hole: &ExactBlackHole,
    b: f64,
    (start, end): (f64, f64),
    (kind, tolerance): (StepperKind, f64),
) -> (Option<(f64, f64)>, u64) {
    let n_start = hole.sample(DVec3::new(start, 0.0, 0.0)).unwrap().n;
    let sin_psi = b / (n_start * start);
    let dir = DVec3::new(-(1.0 - sin_psi * sin_psi).sqrt(), sin_psi, 0.0);
    let state = RayState::new(hole, DVec3::new(start, 0.0, 0.0), dir).unwrap();
    let limits = MarchLimits {
        length: 10.0 * end,
        max_steps: 1_000_000,
        bounds: Bounds::Ball {
            center: DVec3::ZERO,
            radius: end,
        },
    };
    let control = StepControl::Adaptive { tolerance };
    let out = march_with(kind, hole, control, state, &limits, |_, _| {
        std::ops::ControlFlow::Continue(())
    });
    assert!(out.state.position.is_finite() && out.state.direction.is_finite());
    if out.reason != Termination::LeftBounds {
        return (None, out.steps);
    }
    // The ray runs toward −x on the +y side and bends toward the hole (−y): a counterclockwise
    // turn about +z, which may exceed π near the photon sphere.
    let end_dir = out.state.direction;
    let turn = dir.cross(end_dir).z.atan2(dir.dot(end_dir));
    let deflection = turn.rem_euclid(2.0 * PI);
    let u = |rho: f64| 1.0 / hole.areal_radius(rho);
    let exact = hole
        .gr_deflection(b, u(start), u(out.state.position.length()))
        .unwrap();
    (Some((deflection, exact)), out.steps)
}

/// n(ρ)·ρ = r/√f(r) — the index's Bouguer invariant is GR's impact
/// parameter — at radii from just outside the horizon to far away, to rounding: 1e-11, as
/// 1 − 2M/r + Q²/r² is ~1e-4 at 1.01 ρ_h and loses that much of its precision.
#[test]
fn the_index_carries_grs_impact_parameter() {
    for q in [0.0, 0.3, 0.5, 0.7] {
        let hole = ExactBlackHole {
            center: DVec3::ZERO,
            rs: 2.0,
            q,
        };
        let floor = hole.capture_radius().max(1e-3);
        for rho in [1.01 * floor, 0.6, 1.0, 3.0, 17.0, 1e4] {
            if rho <= floor {
                continue;
            }
            let n = hole.sample(DVec3::new(0.0, rho, 0.0)).unwrap().n;
            let r = hole.areal_radius(rho);
            let want = r / lapse2(&hole, 1.0 / r).sqrt();
            assert!(
                (n * rho / want - 1.0).abs() < 1e-11,
                "q {q} ρ {rho}: {} vs {want}",
                n * rho
            );
        }
    }
}

/// The horizon (where rays end, for q ≤ ½) is GR's r₊ = M + √(M² − Q²), and the photon sphere
/// (the minimum of n ρ, where circular light orbits live) is r = (3M + √(9M² − 8Q²))/2 with
/// critical impact parameter r/√f(r), both to 1e-9 (the minimum located by golden section).
#[test]
fn horizon_and_photon_sphere_are_grs() {
    for q in [0.0, 0.25, 0.45, 0.5] {
        let hole = ExactBlackHole {
            center: DVec3::ZERO,
            rs: 2.0,
            q,
        };
        let (m, charge) = (1.0, 2.0 * q);
        let r_plus = m + (m * m - charge * charge).sqrt();
        let rho_h = hole.capture_radius();
        if rho_h > 0.0 {
            assert!((hole.areal_radius(rho_h) - r_plus).abs() < 1e-12, "{q}");
        }
        let b_of = |rho: f64| rho * hole.sample(DVec3::new(rho, 0.0, 0.0)).unwrap().n;
        let (mut a, mut c) = ((rho_h * 1.001).max(1e-3), 10.0);
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let (x1, x2) = (c - golden * (c - a), a + golden * (c - a));
            if b_of(x1) < b_of(x2) {
                c = x2;
            } else {
                a = x1;
            }
        }
        let rho_ph = 0.5 * (a + c);
        let r_ph = 0.5 * (3.0 * m + (9.0 * m * m - 8.0 * charge * charge).sqrt());
        let b_c = r_ph / lapse2(&hole, 1.0 / r_ph).sqrt();
        assert!(
            (hole.areal_radius(rho_ph) / r_ph - 1.0).abs() < 1e-6,
            "q {q}: photon sphere r {} vs {r_ph}",
            hole.areal_radius(rho_ph)
        );
        assert!((b_of(rho_ph) / b_c - 1.0).abs() < 1e-9, "q {q}: b_c");
        if q == 0.0 {
            assert!((b_c - 3.0 * 3f64.sqrt()).abs() < 1e-9);
        }
    }
}

/// Traced Schwarzschild and Reissner–Nordström rays against GR's deflection between the
/// same two observers (the finite start and end are in the formula, so nothing is
/// extrapolated), for b from just outside capture to 10⁴ M.
///
/// The bar, relative 1e-6 at every b at the default tolerance, is met by the RKN
/// pair (`rkn`, sixth order, the default stepper) at its default tolerance (1e-6): measured
/// ≤ 2.2e-7, at 10⁴ M (≤ 1.1e-7 up to 10³ M, ≤ 1.2e-8 closer in). RK4 at its
/// default tolerance (1e-9) errs by ~1e-9 rad absolute at every b (measured 1.1e-9 at most,
/// 3e-7 at 1.02 b_c where the deflection is 3.6 rad): 2e-9 rad there, or 2e-7 relative for
/// the strongly bent rays; relative 1e-6 holds for it up to 10³ M (3.5e-7 measured) and, at
/// tolerance 1e-10, up to 10⁴ M (5.3e-7 measured). Rays below the critical impact parameter
/// are captured, finitely, in a bounded number of steps (no crawl: Tessendorf's (2022) step collapse).
#[test]
fn traced_rays_meet_grs_deflection() {
    for q in [0.0, 0.3] {
        let hole = ExactBlackHole {
            center: DVec3::ZERO,
            rs: 2.0,
            q,
        };
        let m = 1.0;
        let r_ph = 0.5 * (3.0 * m + (9.0 * m * m - 32.0 * q * q * m * m).sqrt());
        let b_c = r_ph / lapse2(&hole, 1.0 / r_ph).sqrt();
        let rk4 = (StepperKind::Rk4, StepperKind::Rk4.default_tolerance());
        let rkn = (StepperKind::Rkn, StepperKind::Rkn.default_tolerance());
        for b in [1.02 * b_c, 5.3 * m, 8.0, 20.0, 100.0, 1e3, 1e4] {
            for control in [rk4, (StepperKind::Rk4, 1e-10), rkn] {
                let (result, steps) = traced(&hole, b, (50.0 * b, 100.0 * b), control);
                let (got, want) = result.expect("a ray outside the photon sphere escapes");
                let (abs, rel) = ((got - want).abs(), (got / want - 1.0).abs());
                println!("q {q} b {b:.3} {control:?}: relative {rel:.2e} in {steps} steps");
                let ok = if control == rk4 {
                    abs < 2e-9 || rel < 2e-7
                } else {
                    rel < 1e-6
                };
                assert!(ok, "q {q} b {b} {control:?}: {got} vs GR {want}");
                if control == rk4 && b <= 1e3 {
                    assert!(rel < 1e-6, "q {q} b {b}: {rel:e}");
                }
            }
        }
        for b in [0.0, 0.5 * b_c, 0.98 * b_c] {
            for control in [rk4, rkn] {
                let (result, steps) = traced(&hole, b, (50.0, 100.0), control);
                assert!(result.is_none(), "q {q} b {b} escaped");
                assert!(
                    steps < 2000,
                    "q {q} b {b} {control:?}: {steps} steps to capture"
                );
            }
        }
    }
}

/// With no horizon (q > ½) rays pass the centre region: every impact parameter ends finite —
/// escaping, or (aimed at the singularity) captured — never NaN or out of steps.
#[test]
fn a_naked_singularity_ends_every_ray_finitely() {
    let hole = ExactBlackHole {
        center: DVec3::ZERO,
        rs: 2.0,
        q: 0.7,
    };
    for b in [0.0, 1e-3, 0.1, 0.5, 1.0, 2.0, 3.0, 5.0] {
        let n_start = hole.sample(DVec3::new(50.0, 0.0, 0.0)).unwrap().n;
        let sin_psi = b / (n_start * 50.0);
        let dir = DVec3::new(-(1.0 - sin_psi * sin_psi).sqrt(), sin_psi, 0.0);
        let state = RayState::new(&hole, DVec3::new(50.0, 0.0, 0.0), dir).unwrap();
        let limits = MarchLimits {
            length: 1e3,
            max_steps: 100_000,
            bounds: Bounds::Ball {
                center: DVec3::ZERO,
                radius: 100.0,
            },
        };
        let control = StepControl::Adaptive { tolerance: 1e-9 };
        let out = march_with(StepperKind::Rk4, &hole, control, state, &limits, |_, _| {
            std::ops::ControlFlow::Continue(())
        });
        assert!(out.state.position.is_finite(), "b {b}");
        assert!(
            matches!(out.reason, Termination::LeftBounds | Termination::Captured),
            "b {b}: {:?} after {} steps",
            out.reason,
            out.steps
        );
    }
}

/// `scenes/schwarzschild.toml` rendered on one row of 241 pixels across 1.2° (0.005° each),
/// tracing every ray and through the deflection table: the shadow's edge on each side lies within one pixel of a static observer's exact angular
/// radius asin((3√3 M/r_o)√(1 − 2M/r_o)), r_o the camera's areal radius — the camera at rest
/// in isotropic coordinates sees true angles (the spatial metric is conformally flat).
#[test]
fn the_rendered_shadow_has_grs_angular_radius() {
    let path = std::path::Path::new("scenes/schwarzschild.toml");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("fov_x_deg = 40.0", "fov_x_deg = 1.2")
        .replace("width = 1920", "width = 241")
        .replace("height = 1080", "height = 1")
        .replace("spp = 4", "spp = 1");
    let (scene, mut settings) = grinlight::scene::load::parse_scene(path, text).unwrap();
    for table in [false, true] {
        settings.deflection_table = table;
        let (film, _) = grinlight::render::render(&scene, &settings, &()).unwrap();
        check_shadow(&film.layer("beauty").unwrap());
    }
}

/// The shadow's edges in the 241-pixel row of `the_rendered_shadow_has_grs_angular_radius`.
fn check_shadow(row: &[[f32; 3]]) {
    let hole = ExactBlackHole {
        center: DVec3::ZERO,
        rs: 0.01,
        q: 0.0,
    };
    let r_o = hole.areal_radius(5.0);
    let m = 0.005;
    let shadow = ((3.0 * 3f64.sqrt() * m / r_o) * (1.0 - 2.0 * m / r_o).sqrt()).asin();
    let tan_half = 0.6f64.to_radians().tan();
    let angle = |px: f64| ((2.0 * (px + 0.5) / 241.0 - 1.0) * tan_half).atan();
    let pixel = angle(121.0) - angle(120.0);
    let black = |px: usize| row[px].iter().all(|&c| c == 0.0);
    assert!(black(120), "the centre is in the shadow");
    let right = (120..241).find(|&px| !black(px)).unwrap();
    let left = (0..=120).rev().find(|&px| !black(px)).unwrap();
    for (edge, inside) in [(right, right - 1), (left, left + 1)] {
        let measured = 0.5 * (angle(edge as f64).abs() + angle(inside as f64).abs());
        assert!(
            (measured - shadow).abs() <= pixel,
            "edge at {:.5}°, GR {:.5}° (pixel {:.5}°)",
            measured.to_degrees(),
            shadow.to_degrees(),
            pixel.to_degrees()
        );
    }
}

/// The deflection table against direct tracing on every pixel of small renders of the
/// exact scenes: each pixel's escape direction within the table's interpolation tolerance
/// (1e-6 rad; measured 2.4e-7 at most on the HD view's check) and the same captured pixels;
/// the render through the table the same for 1 and 2 threads.
#[test]
fn the_deflection_table_matches_direct_tracing_on_every_pixel() {
    use grinlight::integrator::DeflectionTable;
    use grinlight::transport::Tracer;
    for (file, edit) in [
        (
            "scenes/schwarzschild.toml",
            ("width = 1920", "height = 1080"),
        ),
        (
            "scenes/reissner_nordstrom.toml",
            ("width = 480", "height = 270"),
        ),
    ] {
        let path = std::path::Path::new(file);
        let text = std::fs::read_to_string(path)
            .unwrap()
            .replace(edit.0, "width = 96")
            .replace(edit.1, "height = 54");
        let (scene, mut settings) = grinlight::scene::load::parse_scene(path, text).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        let never = || false;
        let table = DeflectionTable::new(&tracer, &never).expect("the table applies");
        let worst = worst_table_error(&table, &tracer, file);
        assert!(worst < 1e-6, "{file}: {worst:e} rad");
        let films: Vec<_> = [1, 2]
            .map(|threads| {
                settings.threads = threads;
                let (film, report) = grinlight::render::render(&scene, &settings, &()).unwrap();
                assert!(report.notes[0].starts_with("deflection table"));
                film.layer("beauty").unwrap()
            })
            .into();
        assert_eq!(films[0], films[1], "{file}");
    }
}

/// The perturbation series of GR's deflection (Tessendorf (2022) eq. 27 is one; here in μ = M/r₀ to
/// 20 orders, `schwarzschild_deflection_series`) against GR's orbit quadrature from infinity to
/// infinity: for μ from 0.001 to 0.2 (b from 1000 M to 6.7 M) within the series' truncation,
/// the first neglected term's size ≈ (3μ)²¹ (1e-9 and below where μ ≤ 0.12), plus the
/// quadrature's 1e-10; at μ = 0.3, near the photon sphere where the series converges slowly, 20
/// orders are far off (it is the traced rays, not a series, that are checked there).
#[test]
fn the_deflection_series_meets_the_orbit_quadrature() {
    let hole = ExactBlackHole {
        center: DVec3::ZERO,
        rs: 2.0,
        q: 0.0,
    };
    for mu in [0.001f64, 0.01, 0.05, 0.1, 0.12, 0.15, 0.2, 0.3] {
        let b = (1.0 / mu) / (1.0 - 2.0 * mu).sqrt(); // M = 1: r₀ = 1/μ
        let exact = hole.gr_deflection(b, 0.0, 0.0).unwrap();
        let series = schwarzschild_deflection_series(mu, 20);
        let bound = (3.0 * mu).powi(21) + 1e-10;
        println!("μ {mu}: b {b:.3} M, GR {exact:.12}, series {series:.12}, |Δ| {:.2e}, bound {bound:.1e}", (series - exact).abs());
        if mu <= 0.2 {
            assert!(
                (series - exact).abs() < bound,
                "μ {mu}: {series} vs {exact}"
            );
        }
    }
    // Its first orders are the textbook ones: α = 4μ + (15π/4 − 4)μ² + … in μ = M/r₀.
    let mu = 1e-4;
    let two = 4.0 * mu + (15.0 * PI / 4.0 - 4.0) * mu * mu;
    assert!((schwarzschild_deflection_series(mu, 20) - two).abs() < 1e-10);
}

/// The largest angle (rad) between the table's escape direction and the traced one over the
/// centres of every pixel of the tracer's camera; a pixel one captures and the other does not
/// fails (`what` names the scene).
fn worst_table_error(
    table: &grinlight::integrator::DeflectionTable,
    tracer: &grinlight::transport::Tracer,
    what: &str,
) -> f64 {
    use grinlight::camera::{FilmPoint, PrimaryRay};
    use grinlight::transport::{Event, Stats};
    let camera = tracer.scene.camera.as_ref().unwrap();
    let mut worst: f64 = 0.0;
    for py in 0..camera.height {
        for px in 0..camera.width {
            let PrimaryRay {
                origin,
                direction: dir,
            } = camera.ray(FilmPoint::pixel_centre(px, py));
            let traced =
                match tracer.next_event(origin, dir, tracer.camera_medium, &mut Stats::default()) {
                    Event::Escaped { direction, .. } => Some(direction),
                    _ => None,
                };
            match (table.escape_direction(dir), traced) {
                (Some(a), Some(b)) => worst = worst.max(grinlight::math::angle_between(a, b)),
                (None, None) => {}
                (a, b) => panic!("{what}: pixel {px},{py}: table {a:?}, traced {b:?}"),
            }
        }
    }
    worst
}

/// A camera scene before one ambient medium `medium` (TOML keys), at `distance` on the z
/// axis looking at (0, `look`, 0) with vertical field `fov` degrees, 64 × 48, checker sky.
fn narrow_view(medium: &str, distance: f64, look: f64, fov: f64) -> String {
    format!(
        "ambient = \"h\"\n[[medium]]\nname = \"h\"\n{medium}\n[camera]\nposition = [0, 0, {distance:e}]\n\
         look_at = [0, {look}, 0]\nfov_y_deg = {fov:e}\nwidth = 64\nheight = 48\n[render]\nspp = 1\n\
         world_radius = {:e}\n[[light]]\ntype = \"environment\"\nsky = \"checker\"\n",
        2.0 * distance
    )
}

/// Narrow and distant views: the table is built over the view's own range of angles, so where
/// it is used every pixel's escape direction is within its stated error — a tenth of a pixel
/// — of direct tracing (a view 0.01° wide beside a black hole 10⁴ rs away, measured 6.5e-5
/// pixel on the check; a Luneburg lens 100 radii away filling a 0.5° view). Where it cannot be
/// made that accurate within its budget (a 6·10⁻⁶° view of a hole 10⁸ rs away, a 10⁻⁶° view of
/// a lens 10¹⁰ radii away: the traced turns vary by more than 0.003 pixel between any
/// affordable nodes), a render does not use it: it traces every ray, and says so.
#[test]
fn the_deflection_table_is_used_only_where_it_is_accurate() {
    use grinlight::integrator::DeflectionTable;
    use grinlight::transport::Tracer;
    let path = std::path::Path::new("narrow.toml");
    let accurate = [
        narrow_view("profile = \"schwarzschild\"\nrs = 1", 1e4, 10.0, 0.01),
        narrow_view("profile = \"luneburg\"\nradius = 1", 100.0, 0.0, 0.5),
    ];
    for text in accurate {
        let (scene, _) = grinlight::scene::load::parse_scene(path, text.clone()).unwrap();
        let tracer = Tracer::new(&scene, &Default::default());
        let never = || false;
        let table = DeflectionTable::new(&tracer, &never).expect("the table applies");
        assert!(table.usable(), "{}", table.summary());
        let camera = scene.camera.as_ref().unwrap();
        let pixel = camera.pixel_angle();
        let worst = worst_table_error(&table, &tracer, &text);
        println!("{}: worst {:.2e} pixel", table.summary(), worst / pixel);
        assert!(worst < 0.1 * pixel, "{text}: {:e} pixel", worst / pixel);
    }
    let inaccurate = [
        narrow_view("profile = \"schwarzschild\"\nrs = 1", 1e8, 0.0, 6e-6),
        narrow_view("profile = \"luneburg\"\nradius = 1", 1e10, 0.0, 1e-6),
    ];
    struct Warnings(std::sync::Mutex<Vec<String>>);
    impl grinlight::render::Observer for Warnings {
        fn warning(&self, text: &str) {
            self.0.lock().unwrap().push(text.to_string());
        }
    }
    for text in inaccurate {
        let (scene, mut settings) =
            grinlight::scene::load::parse_scene(path, text.clone()).unwrap();
        let warnings = Warnings(Default::default());
        let (film, report) = grinlight::render::render(&scene, &settings, &warnings).unwrap();
        let said = warnings.0.lock().unwrap().join("\n");
        assert!(
            said.contains("every camera ray is traced instead"),
            "{said}"
        );
        assert!(report
            .notes
            .iter()
            .all(|n| !n.starts_with("deflection table")));
        settings.deflection_table = false;
        let (traced, _) = grinlight::render::render(&scene, &settings, &()).unwrap();
        assert_eq!(film.layer("beauty"), traced.layer("beauty"), "{text}");
    }
}

/// The deflection table stands only for a medium that bends light and does nothing else: with
/// a scattering coefficient, absorption, or a density scaling either, the scene is traced
/// (through the table a fogged black hole rendered a crisp sky).
#[test]
fn the_deflection_table_refuses_a_medium_that_scatters_or_absorbs() {
    use grinlight::integrator::DeflectionTable;
    use grinlight::transport::Tracer;
    let path = std::path::Path::new("scenes/schwarzschild.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let never = || false;
    let (scene, settings) = grinlight::scene::load::parse_scene(path, text.clone()).unwrap();
    let tracer = Tracer::new(&scene, &settings.trace);
    assert!(DeflectionTable::new(&tracer, &never).is_some());
    let density = "density_bounds = [[-5, -5, -5], [5, 5, 5]]\ndensity_dims = [2, 2, 2]\n\
                   density_values = [1, 1, 1, 1, 1, 1, 1, 1]";
    for extra in [
        "scattering = [0, 0, 3]".to_string(),
        "absorption = 0.1".to_string(),
        format!("scattering = 1\n{density}"),
    ] {
        let edited = text.replacen(
            "profile = \"schwarzschild\"",
            &format!("profile = \"schwarzschild\"\n{extra}"),
            1,
        );
        assert_ne!(edited, text);
        let (scene, settings) = grinlight::scene::load::parse_scene(path, edited).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        assert!(DeflectionTable::new(&tracer, &never).is_none(), "{extra}");
    }
}
