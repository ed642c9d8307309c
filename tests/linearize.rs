//! Rays of the constant-curvature media in closed form (`curve::GeodesicRay`: great circles of
//! the 3-sphere stereographic projection makes of Maxwell's fish-eye, geodesics of the
//! hyperboloid the Poincaré ball's hyperbolic medium is) against the iterative engine, and the
//! fish-eye's perfect imaging and the closed-form hits against their defining equations.

use glam::DVec3;
use grinlight::curve::{
    march_with, Bounds, CircleArc, GeodesicRay, MarchLimits, MarchOutcome, Path, RayState,
    RoundSurface, StepControl, StepperKind, Termination,
};
use grinlight::media::{FishEye, HyperbolicMedium, Medium};
use grinlight::shapes::segment_roots;
use rand::{Rng, SeedableRng};
use std::f64::consts::PI;
use std::ops::ControlFlow;

/// A surface's signed distance (or a function of x-space with the same zero set and signs).
type SignedDistance = Box<dyn Fn(DVec3) -> f64>;

/// A unit vector uniform on the sphere.
fn unit(rng: &mut impl Rng) -> DVec3 {
    let z: f64 = rng.gen_range(-1.0..1.0);
    let phi = rng.gen_range(0.0..2.0 * PI);
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A fish-eye (n0 = 2, R = 0.8) and a hyperbolic medium (n0 = 1.5, R = 1.2), both off the
/// origin.
fn off_centre_media() -> (FishEye, HyperbolicMedium) {
    (
        FishEye {
            n0: 2.0,
            center: DVec3::new(0.1, -0.2, 0.3),
            radius: 0.8,
        },
        HyperbolicMedium {
            n0: 1.5,
            center: DVec3::new(-0.3, 0.2, 0.1),
            radius: 1.2,
        },
    )
}

/// The worst differences between rays marched by RKN6(4) at tolerance 1e-12 and their closed
/// forms (`ray_of`), over random directions from centre distances `starts` (units of R) and
/// `length` R of arclength each (or until they leave the ball of radius `reach` R): position
/// (units of R) and direction at every accepted step, at the marched optical path; and the
/// closed form reversed at the end, back to the start.
fn against_engine(
    medium: &dyn Medium,
    (center, radius): (DVec3, f64),
    ray_of: impl Fn(DVec3, DVec3) -> Option<GeodesicRay>,
    starts: &[f64],
    (length, reach): (f64, f64),
) -> [f64; 3] {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(28);
    let mut worst = [0.0f64; 3];
    for &start_r in starts {
        for _ in 0..8 {
            let start = center + start_r * radius * unit(&mut rng);
            let dir = unit(&mut rng);
            let ray = ray_of(start, dir).unwrap();
            let state = RayState::new(medium, start, dir).unwrap();
            let limits = MarchLimits {
                length: length * radius,
                max_steps: 1_000_000,
                bounds: Bounds::Unbounded,
            };
            let mut opl = 0.0;
            march_with(
                StepperKind::Rkn,
                medium,
                StepControl::Adaptive { tolerance: 1e-12 },
                state,
                &limits,
                |_, step| {
                    if (step.state.position - center).length() > reach * radius {
                        return ControlFlow::Break(());
                    }
                    opl += step.optical_path;
                    let exact = ray.at(ray.angle(opl)).unwrap();
                    worst[0] =
                        worst[0].max((step.state.position - exact.position).length() / radius);
                    worst[1] = worst[1].max((step.state.direction - exact.direction).length());
                    ControlFlow::Continue(())
                },
            );
            let end = ray.at(ray.angle(opl)).unwrap();
            let back = ray_of(end.position, -end.direction).unwrap();
            let returned = back.at(back.angle(opl)).unwrap().position;
            worst[2] = worst[2].max((returned - start).length() / radius);
        }
    }
    worst
}

/// Rays of a fish-eye (n0 = 2, R = 0.8, off the origin) from the centre, from inside, from
/// the rim r = R and from outside it, marched over 3R, and of a hyperbolic medium (n0 = 1.5,
/// R = 1.2) from the centre and from 0.3, 0.6 and 0.9 R, marched over 0.5 R or to 0.99 R
/// (near the rim the closed form's directions lose ε/(1 − r²/R²)), follow their closed forms: at every accepted step the marched position and
/// direction agree with the closed form's at the marched optical path (so the optical path
/// agrees too) within 1e-12 R and 1e-12 (the engine's error per unit length is 1e-12); the
/// closed form reversed at the end retraces it to the start (1e-12 R).
#[test]
fn closed_form_rays_are_the_iterative_engines_rays() {
    let (eye, hyperbolic) = off_centre_media();
    let cases = [
        (
            "fish-eye",
            against_engine(
                &eye,
                (eye.center, eye.radius),
                |x, d| GeodesicRay::fish_eye(&eye, x, d),
                &[0.0, 0.375, 1.0, 2.125],
                (3.0, f64::INFINITY),
            ),
        ),
        (
            "hyperbolic",
            against_engine(
                &hyperbolic,
                (hyperbolic.center, hyperbolic.radius),
                |x, d| GeodesicRay::hyperbolic(&hyperbolic, x, d),
                &[0.0, 0.3, 0.6, 0.9],
                (0.5, 0.99),
            ),
        ),
    ];
    for (name, worst) in cases {
        println!(
            "{name}: position {:e} R, direction {:e}, out and back {:e} R",
            worst[0], worst[1], worst[2]
        );
        assert!(worst.iter().all(|&w| w < 1e-12), "{name}: {worst:?}");
    }
}

/// Every ray from a point on the rim r = R reaches the antipodal point c − (x − c) at optical
/// path n0 R π / 2 (θ = π), and every ray from any point x reaches c − R²(x − c)/|x − c|²:
/// perfect imaging, to 1e-12 R. Also for R = 1e-6 and 1e6 (the map is in units of R).
#[test]
fn the_fish_eye_images_every_point_perfectly() {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(29);
    for radius in [1e-6, 1.0, 1e6] {
        let eye = FishEye {
            n0: 1.7,
            center: DVec3::new(0.3, 0.1, -0.2) * radius,
            radius,
        };
        let mut worst = 0.0f64;
        for i in 0..1000 {
            let r = if i % 2 == 0 {
                radius
            } else {
                rng.gen_range(0.05..3.0) * radius
            };
            let offset = r * unit(&mut rng);
            let ray = GeodesicRay::fish_eye(&eye, eye.center + offset, unit(&mut rng)).unwrap();
            let image = eye.center - radius * radius * offset / offset.length_squared();
            let got = ray.at(PI).unwrap().position;
            worst = worst.max((got - image).length() / radius);
            assert_eq!(ray.optical_path(PI), 0.5 * eye.n0 * radius * PI);
        }
        println!("R = {radius:e}: worst image error {worst:e} R");
        assert!(worst < 1e-12, "R = {radius}: {worst:e}");
    }
}

/// Closed-form hits, in the fish-eye (R = 1) and in the hyperbolic medium (R = 2): the first
/// crossing of a plane or a sphere lies on it to 1e-12 R, and the ray does not cross it
/// earlier (its signed distance keeps its sign at 2000 points before the hit). A ray that
/// misses finds no crossing (the surface keeps one side of it up to its end: θ = 2π, or 12
/// in the hyperbolic medium, within 10⁻¹⁰ of its rim), and neither does one that would only
/// touch it. Fish-eye rays from the centre, which reach infinity at θ = π and end there, and
/// from outside R included.
#[test]
fn rays_meet_planes_and_spheres_in_closed_form() {
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let hyperbolic = HyperbolicMedium {
        n0: 1.2,
        center: DVec3::ZERO,
        radius: 2.0,
    };
    type RayOf<'a> = Box<dyn Fn(DVec3, DVec3) -> Option<GeodesicRay> + 'a>;
    let kinds: [(&str, RayOf, f64, f64); 2] = [
        (
            "fish-eye",
            Box::new(|x, d| GeodesicRay::fish_eye(&eye, x, d)),
            4.0,
            2.0 * PI,
        ),
        (
            "hyperbolic",
            Box::new(|x, d| GeodesicRay::hyperbolic(&hyperbolic, x, d)),
            1.9,
            12.0,
        ),
    ];
    for (name, ray_of, farthest, last) in kinds {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(30);
        let (mut hits, mut misses, mut residual) = (0, 0, 0.0f64);
        for i in 0..400 {
            let start = if i % 4 == 0 {
                DVec3::ZERO
            } else {
                rng.gen_range(0.0..farthest) * unit(&mut rng)
            };
            let ray = ray_of(start, unit(&mut rng)).unwrap();
            let point = rng.gen_range(0.0..2.0) * unit(&mut rng);
            let normal = unit(&mut rng);
            let (centre, radius) = (
                rng.gen_range(0.0..2.0) * unit(&mut rng),
                rng.gen_range(0.1..1.5),
            );
            let surfaces: [(_, SignedDistance); 2] = [
                (
                    ray.plane(point, normal),
                    Box::new(move |x: DVec3| normal.dot(x - point)),
                ),
                (
                    ray.sphere(centre, radius),
                    Box::new(move |x: DVec3| (x - centre).length() - radius),
                ),
            ];
            for (h, signed) in &surfaces {
                let Some(theta) = ray.crossing(h, 1e-9) else {
                    misses += 1;
                    // A miss: the whole circle keeps one side.
                    let side = signed(ray.at(1e-9).unwrap().position).signum();
                    let end = ray.escape().unwrap_or(last);
                    for k in 0..2000 {
                        if let Some(p) = ray.at(end * k as f64 / 2000.0) {
                            assert!(
                                signed(p.position) * side >= -1e-9,
                                "a missed surface crossed"
                            );
                        }
                    }
                    continue;
                };
                hits += 1;
                let hit = ray.at(theta).unwrap().position;
                let before = signed(ray.at(1e-9).unwrap().position).signum();
                residual = residual.max(signed(hit).abs() / (1.0 + hit.length()));
                assert!(
                    signed(hit).abs() < 1e-12 * (1.0 + hit.length()),
                    "{}",
                    signed(hit)
                );
                assert!(ray.escape().is_none_or(|end| theta < end));
                for k in 1..2000 {
                    let t = theta * k as f64 / 2000.0;
                    let p = ray.at(t).expect("short of infinity");
                    assert!(
                        signed(p.position) * before > -1e-9,
                        "crossed before θ = {theta}"
                    );
                }
            }
        }
        println!("{name}: {hits} hits, {misses} misses; worst residual {residual:e}");
        assert!(hits > 200 && misses > 50, "both branches covered");
    }
    // Touching is not crossing: the sphere through the start, tangent to the ray there.
    for ray in [
        GeodesicRay::fish_eye(&eye, DVec3::ZERO, DVec3::X).unwrap(),
        GeodesicRay::hyperbolic(&hyperbolic, DVec3::ZERO, DVec3::X).unwrap(),
    ] {
        assert_eq!(ray.crossing(&ray.sphere(DVec3::Y * 0.5, 0.5), 0.1), None);
    }
}

/// A ray's circle in x-space (what the `linearize` stepper steps along) meets planes and
/// spheres in closed form (`CircleArc::crossings`, a quadratic in tan(ks/2)/k) where the root
/// search the other steppers' paths use finds them: 3000 random circles of curvature 0, 1e-12,
/// 1e-6, 1e-3, 0.1 and 1 (per unit length) against random planes and spheres, over arcs that
/// turn up to just short of a right angle — the same crossings, each at the same arclength
/// within 1e-12 of the arc's length (the search refines to ~1e-14 relative), every one on its
/// surface within 1e-12; both entering-and-leaving pairs and misses covered.
#[test]
fn a_circle_meets_planes_and_spheres_where_the_search_finds_them() {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(31);
    let (mut found, mut pairs, mut misses, mut worst) = (0, 0, 0, 0.0f64);
    for i in 0..3000 {
        let k = [0.0, 1e-12, 1e-6, 1e-3, 0.1, 1.0][i % 6];
        let direction = unit(&mut rng);
        let across = direction.any_orthonormal_vector();
        let turn = rng.gen_range(0.0..2.0 * PI);
        let bend = (across * turn.cos() + direction.cross(across) * turn.sin()) * k;
        let circle = CircleArc::new(rng.gen_range(0.0..1.0) * unit(&mut rng), direction, bend);
        let length = if k > 0.0 {
            (rng.gen_range(0.05..1.5) / k).min(4.0)
        } else {
            rng.gen_range(0.1..4.0)
        };
        let surfaces = [
            RoundSurface::plane(rng.gen_range(0.0..2.0) * unit(&mut rng), unit(&mut rng)),
            RoundSurface::sphere(
                rng.gen_range(0.0..2.0) * unit(&mut rng),
                rng.gen_range(0.1..1.5),
            ),
        ];
        for surface in surfaces {
            let closed: Vec<f64> = circle
                .crossings(&surface, length)
                .expect("an arc short of a right angle")
                .iter()
                .collect();
            let searched: Vec<f64> = segment_roots(&circle, length, |x| surface.implicit(x))
                .into_iter()
                .filter(|&s| s > 0.0)
                .collect();
            assert_eq!(
                closed.len(),
                searched.len(),
                "{closed:?} vs {searched:?} (k {k})"
            );
            for (a, b) in closed.iter().zip(&searched) {
                worst = worst.max((a - b).abs() / length);
                assert!((a - b).abs() < 1e-12 * length, "{a} vs {b} (k {k})");
                let (g, grad) = surface.implicit(circle.at(*a).position);
                assert!(
                    g.abs() < 1e-12 * grad.length().max(1.0),
                    "off the surface: {g}"
                );
            }
            found += closed.len();
            pairs += usize::from(closed.len() == 2);
            misses += usize::from(closed.is_empty());
        }
    }
    println!("{found} crossings ({pairs} pairs), {misses} misses; worst {worst:e} of the length");
    assert!(
        found > 1000 && pairs > 100 && misses > 500,
        "all cases covered"
    );
}

/// Rays driven into the hyperbolic medium's rim end finitely: marched radially and obliquely
/// toward it by RKN6(4) (adaptive, its default tolerance), for R = 1e-6, 1 and 1e6, a march
/// ends captured within the rim margin (1 − r²/R² < 1e-8) in under 1000 steps (about 490
/// measured) — never past the rim, never NaN; the closed form takes the same rays to any
/// optical path inside the rim (θ = 30: 1 − r²/R² ≈ e⁻³⁰).
#[test]
fn rays_into_the_hyperbolic_rim_end_finitely() {
    use grinlight::curve::Termination;
    for radius in [1e-6, 1.0, 1e6] {
        let m = HyperbolicMedium {
            n0: 1.5,
            center: DVec3::ZERO,
            radius,
        };
        for dir in [
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.1, 1.0, 0.3),
        ] {
            let start = DVec3::new(0.5, 0.0, 0.0) * radius;
            let state = RayState::new(&m, start, dir).unwrap();
            let limits = MarchLimits {
                length: 10.0 * radius,
                max_steps: 100_000,
                bounds: Bounds::Unbounded,
            };
            let out = march_with(
                StepperKind::Rkn,
                &m,
                StepControl::default_for(StepperKind::Rkn),
                state,
                &limits,
                |_, _| ControlFlow::Continue(()),
            );
            let r = out.state.position.length() / radius;
            println!(
                "R = {radius:e}, {dir}: {:?} at r = {r} R after {} steps",
                out.reason, out.steps
            );
            assert!(out.state.position.is_finite() && r < 1.0, "{out:?}");
            assert_eq!(out.reason, Termination::Captured);
            assert!(out.steps < 1000, "{} steps", out.steps);
            let ray = GeodesicRay::hyperbolic(&m, start, dir).unwrap();
            let far = ray.at(30.0).unwrap();
            assert!(far.position.length() / radius < 1.0 && far.direction.is_finite());
        }
    }
}

/// A march of `kind` (adaptive at `tolerance`) from `start` along `dir` over `length`.
fn march_over(
    medium: &dyn Medium,
    kind: StepperKind,
    tolerance: f64,
    (start, dir): (DVec3, DVec3),
    length: f64,
) -> MarchOutcome {
    let limits = MarchLimits {
        length,
        max_steps: 1_000_000,
        bounds: Bounds::Unbounded,
    };
    march_with(
        kind,
        medium,
        StepControl::Adaptive { tolerance },
        RayState::new(medium, start, dir).unwrap(),
        &limits,
        |_, _| ControlFlow::Continue(()),
    )
}

/// A medium with a closed form, and where its rays start.
struct Case<'a> {
    name: &'a str,
    medium: &'a dyn Medium,
    center: DVec3,
    radius: f64,
    /// Distances from the centre (units of R).
    starts: &'a [f64],
    /// Arclength marched (units of R).
    length: f64,
}

/// The `linearize` stepper follows each ray's circle exactly: over 2R of a fish-eye (from
/// inside, the rim and outside; through the centre too) and 0.3R of a hyperbolic medium (from
/// the centre to 0.6R: short of the rim, where the optical path diverges), at its default
/// tolerance, its end position, direction and optical path agree with RKN6(4)'s at 1e-12
/// within 1e-10 (R, 1, relative) — the bound the engine's own error leaves — in fewer steps
/// than RKN takes at its default tolerance.
#[test]
fn the_linearize_stepper_is_the_engine_without_error() {
    let (eye, hyperbolic) = off_centre_media();
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(29);
    let cases = [
        Case {
            name: "fish-eye",
            medium: &eye,
            center: eye.center,
            radius: eye.radius,
            starts: &[0.0, 0.4, 1.0, 1.7],
            length: 2.0,
        },
        Case {
            name: "hyperbolic",
            medium: &hyperbolic,
            center: hyperbolic.center,
            radius: hyperbolic.radius,
            starts: &[0.0, 0.3, 0.6],
            length: 0.3,
        },
    ];
    for case in cases {
        let (name, radius) = (case.name, case.radius);
        let (mut worst, mut steps) = ([0.0f64; 3], [0u64; 2]);
        for &r in case.starts {
            for k in 0..8 {
                let start = case.center + r * radius * unit(&mut rng);
                // One ray of each start straight through the centre.
                let dir = match k {
                    0 if r > 0.0 => (case.center - start).normalize(),
                    _ => unit(&mut rng),
                };
                let run = |kind, tolerance| {
                    march_over(
                        case.medium,
                        kind,
                        tolerance,
                        (start, dir),
                        case.length * radius,
                    )
                };
                let exact = run(StepperKind::Linearize, 1e-6);
                let engine = run(StepperKind::Rkn, 1e-12);
                let usual = run(StepperKind::Rkn, 1e-6);
                worst[0] =
                    worst[0].max((exact.state.position - engine.state.position).length() / radius);
                worst[1] = worst[1].max((exact.state.direction - engine.state.direction).length());
                worst[2] = worst[2].max((exact.optical_path / engine.optical_path - 1.0).abs());
                steps[0] += exact.steps;
                steps[1] += usual.steps;
            }
        }
        println!(
            "{name}: position {:e} R, direction {:e}, optical path {:e}; steps {} against \
             RKN's {} at 1e-6",
            worst[0], worst[1], worst[2], steps[0], steps[1]
        );
        assert!(worst.iter().all(|&w| w < 1e-10), "{name}: {worst:?}");
        assert!(steps[0] < steps[1], "{name}: {steps:?}");
    }
}

/// `text`'s beauty layer.
fn beauty(text: &str) -> Vec<[f32; 3]> {
    let (scene, settings) =
        grinlight::scene::load::parse_scene(std::path::Path::new("fish_eye.toml"), text.into())
            .unwrap();
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    film.layer("beauty").unwrap().to_vec()
}

/// The shipped fish-eye scene (a scattering fish-eye ball lit through its surface: volume
/// caustics read by beams along the camera paths' curved stretches, single scattering by
/// curved connections), small, rendered with its rays on their exact circles and marched by
/// RKN6(4) from the same seed: the two pictures differ by noise only — each channel's mean
/// pixel difference within four standard errors of it (the two share most of their random
/// numbers, so this is tight: 0.1 % of the mean). The exact stepper's steps turn up to a
/// right angle of their circle; what follows a path by its chords (the beams) sees points
/// 0.03 rad apart (0.1 rad apart, the difference is +0.22 % at 4.9 standard errors; a step's
/// ends alone, +4 % in the ball).
#[test]
fn the_fish_eye_renders_alike_on_exact_circles_and_marched() {
    let text = std::fs::read_to_string("scenes/fish_eye.toml")
        .unwrap()
        .replace("width = 320", "width = 40")
        .replace("height = 240", "height = 30")
        .replace("caustic_photons = 1000000", "caustic_photons = 200000");
    let exact = beauty(&text);
    let marched = beauty(&text.replace("\"linearize\"", "\"rkn\""));
    let n = exact.len() as f64;
    for c in 0..3 {
        let d: Vec<f64> = exact
            .iter()
            .zip(&marched)
            .map(|(a, b)| f64::from(a[c]) - f64::from(b[c]))
            .collect();
        let mean = d.iter().sum::<f64>() / n;
        let se = (d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n * (n - 1.0))).sqrt();
        let level = marched.iter().map(|p| f64::from(p[c])).sum::<f64>() / n;
        println!("channel {c}: mean {level:.5}, difference {mean:+.2e} ± {se:.2e}");
        assert!(
            mean.abs() < 4.0 * se.max(1e-6 * level),
            "channel {c}: {mean} ± {se}"
        );
    }
}

/// A fish-eye ball that is a scene's sphere (n0 = 2, radius R) followed by the renderer's
/// tracer with `linearize`: each ray from inside is advanced on its circle and meets the sphere
/// in closed form. At R = 1e-6, 1 and 1e6 the same rays (scaled) end at the same point of the
/// sphere (units of R) within 1e-12 (4e-15 measured) — the closed form is scale-free — and
/// every hit lies on the sphere within 1e-12 R; rays from the centre (straight), and rays that start on the rim
/// heading along it (tangent: they follow the rim's great circle, the sphere's own) end finite.
#[test]
fn the_tracer_follows_fish_eye_rays_to_the_sphere_at_every_scale() {
    use grinlight::transport::{Event, Stats, Tracer};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(33);
    let rays: Vec<(DVec3, DVec3)> = (0..200)
        .map(|i| {
            let from = match i % 10 {
                0 => DVec3::ZERO,
                _ => rng.gen::<f64>().cbrt() * 0.99 * unit(&mut rng),
            };
            (from, unit(&mut rng))
        })
        .collect();
    let mut ends: Vec<Vec<DVec3>> = Vec::new();
    for radius in [1e-6, 1.0, 1e6] {
        let text = format!(
            "[[medium]]\nname = \"eye\"\nprofile = \"fisheye\"\nn0 = 2.0\ncenter = [0.0, 0.0, \
             0.0]\nradius = {radius:e}\n\n[[material]]\nname = \"lens\"\ntype = \
             \"dielectric\"\ninterior = \"eye\"\n\n[[shape]]\ntype = \"sphere\"\ncenter = [0.0, \
             0.0, 0.0]\nradius = {radius:e}\nmaterial = \"lens\"\n"
        );
        let (scene, settings) =
            grinlight::scene::load::parse_scene(std::path::Path::new("ball.toml"), text).unwrap();
        assert_eq!(settings.trace.stepper, StepperKind::Linearize);
        let tracer = Tracer::new(&scene, &settings.trace);
        let medium = scene.media().index("eye").unwrap();
        let mut stats = Stats::default();
        let mut hit = |from: DVec3, dir: DVec3| match tracer.next_event(
            from * radius,
            dir,
            Some(medium),
            &mut stats,
        ) {
            Event::Surface { hit, .. } => hit.position / radius,
            other => panic!("R {radius}: a ray inside the ball ended {other:?}"),
        };
        let here: Vec<DVec3> = rays.iter().map(|&(x, d)| hit(x, d)).collect();
        for p in &here {
            assert!(
                (p.length() - 1.0).abs() < 1e-12,
                "R {radius}: off the sphere {p}"
            );
        }
        // Tangent at the rim, just inside it: finite, on the sphere.
        let graze = hit(DVec3::X * (1.0 - 1e-12), DVec3::Y);
        assert!(
            graze.is_finite() && (graze.length() - 1.0).abs() < 1e-9,
            "{graze}"
        );
        ends.push(here);
    }
    for other in &ends[1..] {
        let worst = ends[0]
            .iter()
            .zip(other)
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max);
        println!("largest difference between scales: {worst:e} R");
        assert!(worst < 1e-12, "{worst}");
    }
}

/// Rays from the centre of a spherically symmetric medium keep their line (∇n lies along it):
/// a fish-eye of radius 10⁻¹⁵⁰ seen from its centre — where a stepper's rounding turned every
/// camera ray onto a circle closing near the centre, a million steps each — lets every camera
/// ray out to the world sphere in under 2000 steps, with the exact stepper and with Snell's and
/// the arc chain alike, each leaving along the direction it set off in.
#[test]
fn rays_from_the_centre_of_a_tiny_fish_eye_leave_along_their_line() {
    let text = "ambient = \"fe\"\n[[medium]]\nname = \"fe\"\nprofile = \"fisheye\"\nn0 = 1.5\n\
                radius = 1e-150\n[[light]]\ntype = \"environment\"\nsky = \"checker\"\n\
                [camera]\nposition = [0, 0, 0]\nlook_at = [0.3, 0.2, -1]\nfov_y_deg = 40\n\
                width = 8\nheight = 6\n[render]\nspp = 1\n";
    let (scene, settings) =
        grinlight::scene::load::parse_scene(std::path::Path::new("fe.toml"), text.into()).unwrap();
    let (_, report) = grinlight::render::render(&scene, &settings, &()).unwrap();
    let stats = &report.stats;
    assert_eq!(stats.curved_marches, 48);
    assert!(stats.curved_steps < 48 * 2000, "{}", stats.summary());
    assert!(
        stats.summary().contains("ends: left bounds 48"),
        "{}",
        stats.summary()
    );
    let medium = scene.medium("fe").unwrap();
    let d = DVec3::new(0.3, 0.2, -1.0).normalize();
    for kind in [StepperKind::Linearize, StepperKind::Snell, StepperKind::Arc] {
        let start = RayState::new(medium, DVec3::ZERO, d).unwrap();
        let limits = MarchLimits {
            length: 10.0,
            max_steps: 1_000_000,
            bounds: Bounds::Unbounded,
        };
        let control = StepControl::default_for(kind);
        let out = march_with(kind, medium, control, start, &limits, |_, _| {
            ControlFlow::Continue(())
        });
        assert_eq!(out.reason, Termination::LengthReached, "{kind:?}");
        assert!(out.steps < 200_000, "{kind:?}: {} steps", out.steps);
        assert!((out.state.position - 10.0 * d).length() < 1e-9, "{kind:?}");
        assert!((out.state.direction - d).length() < 1e-12, "{kind:?}");
    }
}
