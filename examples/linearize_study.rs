//! The transformation method against the iterative engine.
//!
//! **Maxwell's fish-eye** (n = 2/(1 + r²), R = 1), where it is exact: rays from random points of
//! the ball r ≤ R in
//! random directions, marched until they leave it (Bounds::Ball), by every stepper at a few
//! tolerances. For each: the median wall time per ray over five repeats, the accepted steps
//! per ray, and the median and worst error of the exit point (units of R) against the closed
//! form (the exit on the exact circle, `linearize`; the worst are rays leaving the rim at
//! grazing incidence, where an error across the ray moves the exit far along the rim).
//!
//! **The paraxial map of the CS 184 nonlinear path tracer** on its own test cube, n = 4 − depth
//! over a unit depth (`scenes/grin_cube.toml`): for n = n0 + b ξ along the gradient, the map
//! ξ → ξ' = (n0/b) ln(1 + b ξ/n0) (the report's x → ln(1 + x) for n0 = b = 1) leaves the
//! transverse coordinates alone and makes the rays straight in the paraxial limit, where the
//! transverse optical momentum a = n sin θ (θ: the angle to the gradient, conserved along the
//! ray as a) is small. A ray entering the cube's front face at angle θ inside is carried to the
//! back face in closed form — straight in the transformed coordinates, as the report traces it
//! against the transformed box — and marched there by RKN6(4) at 1e-12. Exactly, the transverse
//! offset is y = (a/b)(arcosh(n/a) − arcosh(n0/a)); the map's line keeps the entry slope
//! tan θ = a/√(n0² − a²) in ξ', so y' = tan θ (n0/b) ln(n/n0). They differ by
//! (a³/b)[ln(n/n0)/(2n0²) + (1/n² − 1/n0²)/4] + O(a⁵): the map's error grows as the cube of
//! the ray's transverse momentum, and the table gives it beside the error measured.
//!
//! `cargo run --release --example linearize_study [RAYS]` (default 2000 rays).

use glam::DVec3;
use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
use grinlight::media::{FishEye, LinearMedium};
use rand::{Rng, SeedableRng};
use std::f64::consts::PI;
use std::ops::ControlFlow;
use std::time::Instant;

/// A unit vector uniform on the sphere.
fn unit(rng: &mut impl Rng) -> DVec3 {
    let z: f64 = rng.gen_range(-1.0..1.0);
    let phi = rng.gen_range(0.0..2.0 * PI);
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Where each ray leaves the ball, and the steps taken, marched by `kind` at `tolerance`.
fn exits(
    eye: &FishEye,
    rays: &[(DVec3, DVec3)],
    kind: StepperKind,
    tolerance: f64,
) -> (Vec<DVec3>, u64) {
    let limits = MarchLimits {
        length: 100.0,
        max_steps: 1_000_000,
        bounds: Bounds::Ball {
            center: eye.center,
            radius: eye.radius,
        },
    };
    let mut steps = 0;
    let ends = rays
        .iter()
        .map(|&(x, d)| {
            let out = march_with(
                kind,
                eye,
                StepControl::Adaptive { tolerance },
                RayState::new(eye, x, d).expect("inside the fish-eye"),
                &limits,
                |_, _| ControlFlow::Continue(()),
            );
            steps += out.steps;
            out.state.position
        })
        .collect();
    (ends, steps)
}

fn main() {
    fish_eye();
    paraxial_cube();
}

/// The paraxial map's exit at the back face of the cube against the engine's.
fn paraxial_cube() {
    // n = 4 at the front face z = 0.4, falling by 1 a unit of depth (toward −z).
    let cube = LinearMedium {
        n0: 4.0,
        gradient: DVec3::Z,
        origin: DVec3::new(0.0, 0.0, 0.4),
    };
    let (n0, b, depth) = (4.0f64, 1.0f64, 1.0f64);
    let n_exit = n0 - b * depth;
    // Depth along the ray's travel is −ξ (ξ = z − 0.4 along ∇n); the back face is ξ = −depth.
    let xi_exit = -depth;
    let mapped_exit = n0 / b * (1.0 + b * xi_exit / n0).ln();
    let limits = MarchLimits {
        length: 100.0,
        max_steps: 1_000_000,
        bounds: Bounds::Box {
            min: DVec3::new(-1e3, -1e3, 0.4 - depth),
            max: DVec3::new(1e3, 1e3, 0.4),
        },
    };
    println!(
        "\nThe paraxial map on the CS 184 cube (n = 4 - depth, unit depth): exit offset error"
    );
    println!(
        "{:>8} {:>8} {:>14} {:>14} {:>16} {:>12} {:>12}",
        "θ (deg)", "a", "engine offset", "map error", "predicted (a³)", "engine µs", "map µs"
    );
    for theta_deg in [1.0f64, 2.0, 5.0, 10.0, 14.0, 20.0, 30.0, 45.0] {
        let theta = theta_deg.to_radians();
        let start = DVec3::new(0.0, 0.0, 0.4);
        let dir = DVec3::new(theta.sin(), 0.0, -theta.cos());
        let a = n0 * theta.sin();
        let repeats = 200;
        let t0 = Instant::now();
        let mut engine = DVec3::ZERO;
        for _ in 0..repeats {
            engine = march_with(
                StepperKind::Rkn,
                &cube,
                StepControl::Adaptive { tolerance: 1e-12 },
                RayState::new(&cube, start, dir).expect("inside the cube"),
                &limits,
                |_, _| ControlFlow::Continue(()),
            )
            .state
            .position;
        }
        let engine_time = t0.elapsed().as_secs_f64() / repeats as f64;
        // The map: at the front face the Jacobian is 1, so the transformed direction is the
        // ray's own; a straight line in (ξ', x, y) to the transformed back face, mapped back.
        let t0 = Instant::now();
        let mut mapped = DVec3::ZERO;
        for _ in 0..repeats * 1000 {
            let d = std::hint::black_box(dir);
            let along = d.z; // the ξ component (∇n is +z)
            let run = mapped_exit / along;
            mapped = std::hint::black_box(DVec3::new(
                start.x + d.x * run,
                start.y + d.y * run,
                0.4 + xi_exit,
            ));
        }
        let map_time = t0.elapsed().as_secs_f64() / (repeats * 1000) as f64;
        let predicted = (a.powi(3) / b
            * ((n_exit / n0).ln() / (2.0 * n0 * n0)
                + 0.25 * (1.0 / (n_exit * n_exit) - 1.0 / (n0 * n0))))
            .abs();
        println!(
            "{:>8.0} {:>8.3} {:>14.6} {:>14.3e} {:>16.3e} {:>12.2} {:>12.4}",
            theta_deg,
            a,
            engine.x - start.x,
            (mapped - engine).length(),
            predicted,
            engine_time * 1e6,
            map_time * 1e6
        );
    }
}

/// Steppers against the closed form across the fish-eye.
fn fish_eye() {
    let count: usize = std::env::args()
        .nth(1)
        .map_or(2000, |a| a.parse().expect("RAYS is a count"));
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(1);
    let rays: Vec<(DVec3, DVec3)> = (0..count)
        .map(|_| {
            (
                unit(&mut rng) * rng.gen::<f64>().cbrt() * 0.999,
                unit(&mut rng),
            )
        })
        .collect();
    let (exact, _) = exits(&eye, &rays, StepperKind::Linearize, 1e-6);
    println!("Maxwell's fish-eye, {count} rays from inside the ball to its rim, one thread");
    println!(
        "{:<10} {:>9} {:>12} {:>10} {:>24} {:>8}",
        "stepper", "tolerance", "µs per ray", "steps/ray", "exit error R: median, max", "× time"
    );
    let mut rows = Vec::new();
    for (kind, tolerance) in [
        (StepperKind::Linearize, 1e-6),
        (StepperKind::Rkn, 1e-6),
        (StepperKind::Rkn, 1e-9),
        (StepperKind::Rkn, 1e-12),
        (StepperKind::Arc, 1e-6),
        (StepperKind::Arc, 1e-9),
        (StepperKind::Rk4, 1e-9),
        (StepperKind::Rk4, 1e-12),
    ] {
        let mut times: Vec<f64> = (0..5)
            .map(|_| {
                let t0 = Instant::now();
                std::hint::black_box(exits(&eye, &rays, kind, tolerance));
                t0.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let (ends, steps) = exits(&eye, &rays, kind, tolerance);
        let mut errors: Vec<f64> = ends
            .iter()
            .zip(&exact)
            .map(|(a, b)| (*a - *b).length())
            .collect();
        errors.sort_by(f64::total_cmp);
        let error = [errors[errors.len() / 2], errors[errors.len() - 1]];
        rows.push((kind, tolerance, times[2] / count as f64, steps, error));
    }
    let fastest_exact = rows[0].2;
    for (kind, tolerance, per_ray, steps, error) in rows {
        println!(
            "{:<10} {:>9.0e} {:>12.2} {:>10.1} {:>15.1e} {:>8.1e} {:>8.1}",
            kind.name(),
            tolerance,
            per_ray * 1e6,
            steps as f64 / count as f64,
            error[0],
            error[1],
            per_ray / fastest_exact
        );
    }
}
