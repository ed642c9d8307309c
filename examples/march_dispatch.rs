//! What the medium's dynamic dispatch costs the curved march: the same RKN6(4) marches
//! (tolerance 1e-5, 2 000 rays of 200 units each) through a parabolic fiber and a Luneburg
//! lens, with the medium's type known to the compiler (its samples inlined into the stepper)
//! and behind `&dyn Medium`, as the renderer holds a scene's media. Median of 5 runs each,
//! 1 thread; both reach the same points to the bit.
//!
//! `cargo run --release --example march_dispatch`

use glam::DVec3;
use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
use grinlight::media::{Axis, Luneburg, Medium, ParabolicFiber};
use std::time::Instant;

/// The marches' end points summed, their steps, and the seconds they took.
fn marches<M: Medium + ?Sized>(medium: &M, from: DVec3, along: DVec3) -> (DVec3, u64, f64) {
    let t = Instant::now();
    let (mut sum, mut steps) = (DVec3::ZERO, 0);
    for k in 0..2000 {
        let d = (along + DVec3::new(1e-5 * k as f64, 0.0, 0.0)).normalize();
        let start = RayState::new(medium, from, d).expect("a ray in the medium");
        let limits = MarchLimits {
            length: 200.0,
            max_steps: 1_000_000,
            bounds: Bounds::Unbounded,
        };
        let control = StepControl::Adaptive { tolerance: 1e-5 };
        let out = march_with(StepperKind::Rkn, medium, control, start, &limits, |_, _| {
            std::ops::ControlFlow::Continue(())
        });
        sum += out.state.position;
        steps += out.steps;
    }
    (sum, steps, t.elapsed().as_secs_f64())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One row of the table: the medium marched as itself and as `dyn Medium`.
fn row<M: Medium>(name: &str, medium: &M, from: DVec3, along: DVec3) {
    let dynamic: &dyn Medium = medium;
    let (mut known, mut behind) = (Vec::new(), Vec::new());
    let mut same = true;
    let mut steps = 0;
    for _ in 0..5 {
        let (a, n, t) = marches(medium, from, along);
        let (b, _, u) = marches(dynamic, from, along);
        same &= a == b;
        steps = n;
        known.push(t);
        behind.push(u);
    }
    let (known, behind) = (median(known), median(behind));
    println!(
        "{name:<16} {steps:>9} {:>12.2} {:>12.2} {:>8.2} {same:>6}",
        1e9 * known / steps as f64,
        1e9 * behind / steps as f64,
        behind / known
    );
}

fn main() {
    println!(
        "{:<16} {:>9} {:>12} {:>12} {:>8} {:>6}",
        "medium", "steps", "known ns", "dyn ns", "ratio", "same"
    );
    let fiber = ParabolicFiber {
        n0: 1.5,
        a: 0.10667,
        axis: Axis {
            center: DVec3::ZERO,
            axis: DVec3::Z,
        },
    };
    row(
        "parabolic fiber",
        &fiber,
        DVec3::new(0.1, 0.0, 0.0),
        DVec3::new(0.05, 0.02, 1.0),
    );
    let lens = Luneburg {
        center: DVec3::ZERO,
        radius: 150.0,
    };
    row(
        "Luneburg lens",
        &lens,
        DVec3::new(0.0, 20.0, -100.0),
        DVec3::new(0.01, 0.0, 1.0),
    );
}
