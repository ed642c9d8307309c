//! Error against run time for every stepper × step control × tolerance on four rays:
//! (a) a meridional ray in a sech fiber over 10 periods, launched at x0 with slope m (error:
//! distance from the exact path sinh(g x) = sinh(g x0) cos(g z) + m cosh(g x0) sin(g z), which
//! for m = 0 is x(z) = asinh(sinh(g x0) cos(g z))/g; m ≠ 0 because a Snell step
//! cannot leave an exact turning point), (b) a Luneburg crossing (error: exit point against
//! the antipodal focus), (c) black-hole rays at b = 3 rs (captured) and b = 20 rs (error: final
//! position against an RK4 run at tolerance 1e-14, which agrees with the exact arc at 1e-12).
//!
//! `cargo run --release --example stepper_study` prints a table and writes
//! `out/stepper_study.csv` and `out/stepper_study.png` (error against time per case, log-log).
//! Times are medians of 5 repetitions on this machine; they are noisy, ratios within one run
//! are what to compare.

use glam::DVec3;
use grinlight::curve::{
    march_with, Bounds, CurvedSegment, MarchLimits, MarchOutcome, RayState, StepControl,
    StepperKind,
};
use grinlight::media::{Axis, BlackHole, ExponentialMedium, Luneburg, Medium, SechFiber};
use grinlight::plot::{self, Panel};
use std::hint::black_box;
use std::io::Write;
use std::time::Instant;

struct Case {
    name: &'static str,
    medium: Box<dyn Medium>,
    start: (DVec3, DVec3),
    limits: MarchLimits,
    /// Fixed step lengths to try.
    fixed: Vec<f64>,
    error: Box<dyn Fn(&MarchOutcome) -> f64>,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn run(case: &Case, kind: StepperKind, control: StepControl) -> (MarchOutcome, f64) {
    let start = RayState::new(case.medium.as_ref(), case.start.0, case.start.1).expect("start");
    let mut times = Vec::new();
    let mut out = None;
    for _ in 0..5 {
        let t = Instant::now();
        let o = march_with(
            kind,
            case.medium.as_ref(),
            control,
            start,
            &case.limits,
            |_, _| std::ops::ControlFlow::Continue(()),
        );
        times.push(t.elapsed().as_secs_f64());
        out = Some(o);
        if times[0] > 2.0 {
            break;
        }
    }
    (out.expect("ran"), median(times))
}

fn black_hole_case(name: &'static str, b_rs: f64, reference: Option<DVec3>) -> (Case, DVec3) {
    let hole = BlackHole::new(DVec3::ZERO, 0.01, 0.1);
    let start = (DVec3::new(-5.0, b_rs * 0.01, 0.0), DVec3::X);
    let limits = MarchLimits {
        length: 10.0,
        max_steps: 1_000_000,
        bounds: Bounds::Unbounded,
    };
    let reference = reference.unwrap_or_else(|| {
        let s = RayState::new(&hole, start.0, start.1).unwrap();
        march_with(
            StepperKind::Rk4,
            &hole,
            StepControl::Adaptive { tolerance: 1e-14 },
            s,
            &limits,
            |_, _| std::ops::ControlFlow::Continue(()),
        )
        .state
        .position
    });
    let case = Case {
        name,
        medium: Box::new(hole),
        start,
        limits,
        fixed: vec![0.1, 0.01, 1e-3, 1e-4],
        error: Box::new(move |o| (o.state.position - reference).length()),
    };
    (case, reference)
}

fn cases() -> Vec<Case> {
    let g = 1.0;
    let x0 = 0.5;
    let slope = 0.1;
    let fiber = Case {
        name: "sech fiber 10 periods",
        medium: Box::new(SechFiber {
            n0: 1.5,
            g,
            axis: Axis {
                center: DVec3::ZERO,
                axis: DVec3::Z,
            },
        }),
        start: (DVec3::new(x0, 0.0, 0.0), DVec3::new(slope, 0.0, 1.0)),
        limits: MarchLimits {
            length: 10.0 * std::f64::consts::TAU / g * 1.05,
            max_steps: 2_000_000,
            bounds: Bounds::Unbounded,
        },
        fixed: vec![0.5, 0.1, 0.02, 0.004, 0.0008],
        error: Box::new(move |o| {
            let p = o.state.position;
            let u = (g * x0).sinh() * (g * p.z).cos() + slope * (g * x0).cosh() * (g * p.z).sin();
            let exact = u.asinh() / g;
            ((p.x - exact).powi(2) + p.y * p.y).sqrt()
        }),
    };
    let h = 0.5f64;
    let lune = Case {
        name: "Luneburg crossing",
        medium: Box::new(Luneburg {
            center: DVec3::ZERO,
            radius: 1.0,
        }),
        start: (DVec3::new(-(1.0 - h * h).sqrt(), h, 0.0), DVec3::X),
        limits: MarchLimits {
            length: 10.0,
            max_steps: 2_000_000,
            bounds: Bounds::Ball {
                center: DVec3::ZERO,
                radius: 1.0,
            },
        },
        fixed: vec![0.2, 0.05, 0.01, 0.002, 0.0004],
        error: Box::new(|o| (o.state.position - DVec3::X).length()),
    };
    let (bh3, r3) = black_hole_case("black hole b = 3 rs", 3.0, None);
    let (bh20, r20) = black_hole_case("black hole b = 20 rs", 20.0, None);
    // The references from RK4 agree with the exact arc at tight tolerance:
    for (c, r) in [(&bh3, r3), (&bh20, r20)] {
        let s = RayState::new(c.medium.as_ref(), c.start.0, c.start.1).unwrap();
        let arc = march_with(
            StepperKind::Arc,
            c.medium.as_ref(),
            StepControl::Adaptive { tolerance: 1e-12 },
            s,
            &c.limits,
            |_, _| std::ops::ControlFlow::Continue(()),
        );
        println!(
            "# {}: reference end {r:.9}, exact arc at 1e-12 differs by {:.2e}",
            c.name,
            (arc.state.position - r).length()
        );
    }
    vec![fiber, lune, bh3, bh20]
}

fn controls(case: &Case) -> Vec<(String, StepControl)> {
    let mut v = Vec::new();
    for tol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12] {
        v.push((
            format!("adaptive tol={tol:.0e}"),
            StepControl::Adaptive { tolerance: tol },
        ));
    }
    for &step in &case.fixed {
        v.push((format!("fixed h={step}"), StepControl::Fixed { step }));
    }
    for (t_max, t_min) in [(1e-1, 1e-4), (1e-2, 1e-4), (1e-3, 1e-5)] {
        v.push((
            format!("tessendorf Tmax={t_max:.0e} Tmin={t_min:.0e}"),
            StepControl::Tessendorf {
                initial_step: case.fixed[1],
                t_max,
                t_min,
                seed: 7,
            },
        ));
    }
    v
}

/// Nanoseconds per step of the bare exact arc, and of full arc / RK4 steps in a medium.
fn step_costs() {
    let n = 5_000_000;
    let mut times = Vec::new();
    for _ in 0..5 {
        let t = Instant::now();
        let mut acc = DVec3::ZERO;
        for i in 0..n {
            let f = DVec3::new(0.3, 0.1 + 1e-9 * i as f64, 2.0);
            let seg = CurvedSegment::new(
                black_box(DVec3::ZERO),
                black_box(DVec3::new(0.6, 0.0, 0.8)),
                black_box(f),
            );
            acc += seg.at(black_box(0.37)).position;
        }
        black_box(acc);
        times.push(t.elapsed().as_secs_f64() / n as f64 * 1e9);
    }
    println!(
        "exact arc, one segment (build + evaluate): {:.1} ns (median of 5)",
        median(times)
    );
    let medium = ExponentialMedium {
        n0: 1.0,
        gradient: DVec3::new(0.0, 0.3, 0.1),
        origin: DVec3::ZERO,
    };
    for kind in StepperKind::ITERATIVE {
        let start = RayState::new(&medium, DVec3::ZERO, DVec3::new(1.0, -0.5, 0.2)).unwrap();
        let steps = 1_000_000u64;
        let limits = MarchLimits {
            length: steps as f64 * 1e-5,
            max_steps: steps + 10,
            bounds: Bounds::Unbounded,
        };
        let mut times = Vec::new();
        for _ in 0..5 {
            let t = Instant::now();
            let o = march_with(
                kind,
                &medium,
                StepControl::Fixed { step: 1e-5 },
                start,
                &limits,
                |_, _| std::ops::ControlFlow::Continue(()),
            );
            times.push(t.elapsed().as_secs_f64() / o.steps as f64 * 1e9);
        }
        println!("{} step in the exponential medium (incl. medium samples, march loop): {:.1} ns (median of 5)", kind.name(), median(times));
    }
}

fn main() -> std::io::Result<()> {
    step_costs();
    std::fs::create_dir_all("out")?;
    let mut csv = std::fs::File::create("out/stepper_study.csv")?;
    writeln!(
        csv,
        "case,stepper,control,error,time_s,steps,attempts,reason"
    )?;
    let cases = cases();
    let mut img = plot::canvas(1400, 1100);
    let mut best = Vec::new();
    for (ci, case) in cases.iter().enumerate() {
        println!("\n## {}\n", case.name);
        println!("| stepper | control | error | time/ray | steps | attempts | end |");
        println!("|---|---|---|---|---|---|---|");
        let mut series: Vec<(usize, Vec<(f64, f64)>)> = Vec::new();
        let mut points = Vec::new();
        for (ki, kind) in StepperKind::ITERATIVE.into_iter().enumerate() {
            for (label, control) in controls(case) {
                let (out, t) = run(case, kind, control);
                let err = (case.error)(&out);
                println!(
                    "| {} | {label} | {err:.2e} | {:.3e} s | {} | {} | {} |",
                    kind.name(),
                    t,
                    out.steps,
                    out.attempts,
                    out.reason.name()
                );
                writeln!(
                    csv,
                    "{},{},{label},{err:e},{t:e},{},{},{}",
                    case.name,
                    kind.name(),
                    out.steps,
                    out.attempts,
                    out.reason.name()
                )?;
                // Plotted: adaptive and fixed runs, one colour each per stepper.
                let e = err.max(1e-16);
                let family = ki * 2 + usize::from(label.starts_with("fixed"));
                if !label.starts_with("tessendorf") {
                    match series.iter_mut().find(|(f, _)| *f == family) {
                        Some((_, v)) => v.push((t, e)),
                        None => series.push((family, vec![(t, e)])),
                    }
                    points.push((t, e));
                }
                if label.starts_with("adaptive") {
                    best.push((case.name, kind, label.clone(), err, t));
                }
            }
        }
        let (col, row) = ((ci % 2) as u32, (ci / 2) as u32);
        let xr = plot::range_of(points.iter().map(|p| p.0));
        let yr = plot::range_of(points.iter().map(|p| p.1));
        let mut panel = Panel::new(
            &mut img,
            (110 + col * 690, 60 + row * 530, 560, 430),
            (xr.0.max(xr.1 * 1e-8), xr.1 * 1.5),
            (yr.0.max(1e-17), yr.1 * 2.0),
            (true, true),
        );
        for (family, mut pts) in series {
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let c = plot::PALETTE[family % plot::PALETTE.len()];
            panel.polyline(&pts, c);
            for p in pts {
                panel.marker(p.0, p.1, c);
            }
        }
        panel.axes(&plot::Labels {
            title: case.name,
            x: "time per ray (s)",
            y: "final-position error (scene units)",
        });
        let labels: Vec<String> = (0..2 * StepperKind::ITERATIVE.len())
            .map(|f| {
                let control = if f % 2 == 0 { "adaptive" } else { "fixed" };
                format!("{} {control}", StepperKind::ITERATIVE[f / 2].name())
            })
            .collect();
        let legend: Vec<(plot::Color, &str)> = labels
            .iter()
            .enumerate()
            .map(|(f, l)| (plot::PALETTE[f % plot::PALETTE.len()], l.as_str()))
            .collect();
        panel.legend(&legend);
    }
    plot::save(&img, std::path::Path::new("out/stepper_study.png"))
        .map_err(std::io::Error::other)?;
    println!("\nwrote out/stepper_study.csv and out/stepper_study.png (x: time per ray [s], y: error; one colour per stepper and control, adaptive and fixed; Tessendorf's control in the table only)");
    equal_error_summary(&cases, &best);
    Ok(())
}

/// Per case: RK4 at its default tolerance (the previous default) sets the error to meet; for
/// each stepper, the fastest adaptive run whose error is at most that, and its speed-up.
fn equal_error_summary(cases: &[Case], best: &[(&str, StepperKind, String, f64, f64)]) {
    println!("\n## At equal error: each stepper's fastest adaptive run at most as far off as rk4 at its default tolerance\n");
    println!("| case | rk4 at 1e-9: error, time | arc | rkn | snell |");
    println!("|---|---|---|---|---|");
    let default_label = format!("adaptive tol={:.0e}", StepperKind::Rk4.default_tolerance());
    for case in cases {
        let runs: Vec<_> = best.iter().filter(|r| r.0 == case.name).collect();
        let Some(reference) = runs
            .iter()
            .find(|r| r.1 == StepperKind::Rk4 && r.2 == default_label)
        else {
            continue;
        };
        let (target, t_ref) = (reference.3, reference.4);
        let cell = |kind: StepperKind| {
            runs.iter()
                .filter(|r| r.1 == kind && r.3 <= target)
                .min_by(|a, b| a.4.total_cmp(&b.4))
                .map_or("never".to_string(), |r| {
                    format!("{:.2}× ({}, {:.2e})", t_ref / r.4, r.2, r.3)
                })
        };
        println!(
            "| {} | {target:.2e}, {t_ref:.3e} s | {} | {} | {} |",
            case.name,
            cell(StepperKind::Arc),
            cell(StepperKind::Rkn),
            cell(StepperKind::Snell)
        );
    }
}
