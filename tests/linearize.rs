//! The fish-eye's rays in closed form (`curve::FishEyeRay`: great circles of the 3-sphere
//! that stereographic projection makes of Maxwell's fish-eye) against the iterative engine,
//! and its perfect imaging and closed-form hits against their defining equations.

use glam::DVec3;
use grinlight::curve::{
    march_with, Bounds, FishEyeRay, MarchLimits, RayState, StepControl, StepperKind,
};
use grinlight::media::FishEye;
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

/// Rays of a fish-eye (n0 = 2, R = 0.8, off the origin) from the centre, from inside, from
/// the rim r = R and from outside it, in random directions, marched by RKN6(4) at tolerance
/// 1e-12 over arclength 3R, follow the closed-form great circle: at every accepted step the
/// marched position and direction agree with the circle's at the marched optical path (so
/// the optical path agrees too), within 1e-12 R and 1e-12 (the engine's error per unit length
/// is 1e-12, and 3R of path keep it there: 3e-14 measured). The circle reversed at its end
/// retraces it to the start (1e-12 R).
#[test]
fn fish_eye_rays_are_the_iterative_engines_rays() {
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::new(0.1, -0.2, 0.3),
        radius: 0.8,
    };
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(28);
    let mut worst = [0.0f64; 3];
    for start_r in [0.0, 0.3, 0.8, 1.7] {
        for _ in 0..8 {
            let start = eye.center + start_r * unit(&mut rng);
            let dir = unit(&mut rng);
            let ray = FishEyeRay::new(&eye, start, dir).unwrap();
            let state = RayState::new(&eye, start, dir).unwrap();
            let limits = MarchLimits {
                length: 3.0 * eye.radius,
                max_steps: 1_000_000,
                bounds: Bounds::Unbounded,
            };
            let mut opl = 0.0;
            march_with(
                StepperKind::Rkn,
                &eye,
                StepControl::Adaptive { tolerance: 1e-12 },
                state,
                &limits,
                |_, step| {
                    opl += step.optical_path;
                    let exact = ray.at(ray.angle(opl)).unwrap();
                    let errors = [
                        (step.state.position - exact.position).length() / eye.radius,
                        (step.state.direction - exact.direction).length(),
                        0.0,
                    ];
                    for (w, e) in worst.iter_mut().zip(errors) {
                        *w = w.max(e);
                    }
                    ControlFlow::Continue(())
                },
            );
            // The optical path: the circle's angle to the marched end, against the march's sum.
            let end = ray.at(ray.angle(opl)).unwrap().position;
            let back =
                FishEyeRay::new(&eye, end, -ray.at(ray.angle(opl)).unwrap().direction).unwrap();
            let returned = back.at(back.angle(opl)).unwrap().position;
            worst[2] = worst[2].max((returned - start).length() / eye.radius);
        }
    }
    println!(
        "worst: position {:e} R, direction {:e}, out and back {:e} R",
        worst[0], worst[1], worst[2]
    );
    assert!(worst[0] < 1e-12 && worst[1] < 1e-12, "{worst:?}");
    assert!(worst[2] < 1e-12, "{worst:?}");
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
            let ray = FishEyeRay::new(&eye, eye.center + offset, unit(&mut rng)).unwrap();
            let image = eye.center - radius * radius * offset / offset.length_squared();
            let got = ray.at(PI).unwrap().position;
            worst = worst.max((got - image).length() / radius);
            assert_eq!(ray.optical_path(PI), 0.5 * eye.n0 * radius * PI);
        }
        println!("R = {radius:e}: worst image error {worst:e} R");
        assert!(worst < 1e-12, "R = {radius}: {worst:e}");
    }
}

/// Closed-form hits: the first crossing of a plane or a sphere lies on it to 1e-12 R, and the
/// circle does not cross it earlier (its signed distance keeps its sign at 2000 angles before
/// the hit). A ray that misses finds no crossing (the surface keeps one side of it up to its
/// end), and neither does one that would only touch it. Rays from the centre, which reach
/// infinity at θ = π and end there, and from outside R included.
#[test]
fn fish_eye_rays_meet_planes_and_spheres_in_closed_form() {
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(30);
    let (mut hits, mut misses, mut residual) = (0, 0, 0.0f64);
    for i in 0..400 {
        let start = if i % 4 == 0 {
            DVec3::ZERO
        } else {
            rng.gen_range(0.0..4.0) * unit(&mut rng)
        };
        let ray = FishEyeRay::new(&eye, start, unit(&mut rng)).unwrap();
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
                let end = ray.escape().unwrap_or(2.0 * PI);
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
    println!("{hits} hits, {misses} misses; worst residual {residual:e}");
    assert!(hits > 300 && misses > 50);
    // Touching is not crossing: the sphere through the start, tangent to the ray there.
    let ray = FishEyeRay::new(&eye, DVec3::ZERO, DVec3::X).unwrap();
    assert_eq!(ray.crossing(&ray.sphere(DVec3::Y * 0.5, 0.5), 0.1), None);
}
