//! The transformation method against the iterative engine on Maxwell's fish-eye
//! (n = 2/(1 + r²), R = 1), where it is exact: rays from random points of the ball r ≤ R in
//! random directions, marched until they leave it (Bounds::Ball), by every stepper at a few
//! tolerances. For each: the median wall time per ray over five repeats, the accepted steps
//! per ray, and the median and worst error of the exit point (units of R) against the closed
//! form (the exit on the exact circle, `linearize`; the worst are rays leaving the rim at
//! grazing incidence, where an error across the ray moves the exit far along the rim).
//!
//! `cargo run --release --example linearize_study [RAYS]` (default 2000 rays).

use glam::DVec3;
use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
use grinlight::media::FishEye;
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
