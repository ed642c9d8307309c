//! The curved-ray engine against exact solutions. Every tolerance is stated with
//! its reason next to the assertion.

use glam::DVec3;
use grinlight::curve::{
    march_with, Bounds, CurvedSegment, MarchLimits, MarchOutcome, RayState, StepControl,
    StepperKind, Termination,
};
use grinlight::media::{
    Axis, BlackHole, ExponentialMedium, FishEye, Luneburg, Medium, ParabolicFiber, SechFiber,
};

fn trace(
    medium: &dyn Medium,
    kind: StepperKind,
    control: StepControl,
    from: DVec3,
    dir: DVec3,
    length: f64,
    bounds: Bounds,
) -> MarchOutcome {
    let start = RayState::new(medium, from, dir).expect("start outside capture region");
    let limits = MarchLimits {
        length,
        max_steps: 5_000_000,
        bounds,
    };
    let out = march_with(kind, medium, control, start, &limits, |_, _| {
        std::ops::ControlFlow::Continue(())
    });
    assert!(
        out.state.position.is_finite() && out.state.direction.is_finite(),
        "{kind:?}: non-finite end"
    );
    out
}

fn z_fiber<M>(make: impl Fn(Axis) -> M) -> M {
    make(Axis {
        center: DVec3::ZERO,
        axis: DVec3::Z,
    })
}

/// Exact meridional path of the sech fiber n0 sech(g x): sinh(g x) is harmonic in z with
/// period 2π/g: sinh(g x) = sinh(g x0) cos(g z) + m cosh(g x0) sin(g z), m the launch slope.
fn sech_exact_x(g: f64, x0: f64, slope: f64, z: f64) -> f64 {
    ((g * x0).sinh() * (g * z).cos() + slope * (g * x0).cosh() * (g * z).sin()).asinh() / g
}

/// One exact-arc step in the exponential medium (∇ln n constant) against an independent
/// RK4 integration of dx/ds = t̂, dt̂/ds = F − t̂(t̂·F) with 20 000 steps (truncation ~h⁴ ≈
/// 1e-16 relative), for rays along, across and against F.
#[test]
fn exponential_medium_single_arc_step_is_exact() {
    let grad = DVec3::new(0.2, -0.5, 0.3);
    let medium = ExponentialMedium {
        n0: 1.3,
        gradient: grad,
        origin: DVec3::ZERO,
    };
    let rhs = |t: DVec3| grad - t * t.dot(grad);
    for dir in [
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.2, 0.9, -0.1),
        -grad,
        DVec3::new(-0.3, 1.0, -0.5),
    ] {
        let s = 2.0;
        let start = RayState::new(&medium, DVec3::new(0.1, 0.2, 0.3), dir).unwrap();
        let got =
            CurvedSegment::new(start.position, start.direction, start.index.log_gradient()).at(s);
        // RK4 with Kahan-compensated accumulation, so 20 000 steps add no visible rounding.
        let (mut x, mut t) = (start.position, start.direction);
        let (mut cx, mut ct) = (DVec3::ZERO, DVec3::ZERO);
        // The optical path ∫ n ds alongside, with RK4's weights at its stage positions.
        let mut opl = 0.0;
        let n = 20_000;
        let h = s / n as f64;
        for _ in 0..n {
            let (k1x, k1t) = (t, rhs(t));
            let (k2x, k2t) = (t + 0.5 * h * k1t, rhs(t + 0.5 * h * k1t));
            let (k3x, k3t) = (t + 0.5 * h * k2t, rhs(t + 0.5 * h * k2t));
            let (k4x, k4t) = (t + h * k3t, rhs(t + h * k3t));
            let index = |p: DVec3| medium.sample(p).unwrap().n;
            opl += h / 6.0
                * (index(x)
                    + 2.0 * index(x + 0.5 * h * k1x)
                    + 2.0 * index(x + 0.5 * h * k2x)
                    + index(x + h * k3x));
            let dx = h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x) - cx;
            let nx = x + dx;
            cx = (nx - x) - dx;
            x = nx;
            let dt = h / 6.0 * (k1t + 2.0 * k2t + 2.0 * k3t + k4t) - ct;
            let nt = t + dt;
            ct = (nt - t) - dt;
            t = nt;
        }
        // Tolerance 1e-12 of the step length: the arc is exact here, and the compensated
        // reference's error is truncation (~1e-16) plus a few ulps.
        let ex = (got.position - x).length() / s;
        let et = (got.direction - t.normalize()).length();
        assert!(
            ex < 1e-12 && et < 1e-12,
            "dir {dir}: position {ex:e}, direction {et:e}"
        );
        // And the engine's march with the arc stepper takes it in one step.
        let limits = MarchLimits {
            length: s,
            max_steps: 10,
            bounds: Bounds::Unbounded,
        };
        let out = march_with(
            StepperKind::Arc,
            &medium,
            StepControl::Fixed { step: s },
            start,
            &limits,
            |_, _| std::ops::ControlFlow::Continue(()),
        );
        assert_eq!(out.steps, 1);
        let ex = (out.state.position - x).length() / s;
        let eo = (out.optical_path - opl).abs() / opl;
        println!("dir {dir}: chain step position {ex:e}, optical path {eo:e}");
        assert!(ex < 1e-12 && eo < 1e-12, "chain: {ex:e}, {eo:e}");
    }
}

/// The steppers' orders on a curved black-hole ray (the weak-field index
/// with q = 0.1, rs = 1, from (−20, 6, 0.5) along +x for 40 rs), against the RKN pair at
/// h = 0.02 (its error there, ~h⁶, is below 1e-15; rounding over its 2 000 steps ~1e-13):
/// the arc chain 4 ± 0.2 (measured 3.97, 3.99, 4.00), the RKN pair
/// 6 ± 0.5 (5.62, 5.88; at h = 0.2 its error, 7e-12, meets the reference's rounding).
#[test]
fn orders_on_a_black_hole_ray() {
    let hole = BlackHole::new(DVec3::ZERO, 1.0, 0.1);
    let run = |kind, h| {
        trace(
            &hole,
            kind,
            StepControl::Fixed { step: h },
            DVec3::new(-20.0, 6.0, 0.5),
            DVec3::X,
            40.0,
            Bounds::Unbounded,
        )
        .state
        .position
    };
    let reference = run(StepperKind::Rkn, 0.02);
    for (kind, order, band, steps) in [
        (StepperKind::Arc, 4.0, 0.2, &[0.8, 0.4, 0.2, 0.1][..]),
        (StepperKind::Rkn, 6.0, 0.5, &[1.6, 0.8, 0.4][..]),
    ] {
        let errors: Vec<f64> = steps
            .iter()
            .map(|&h| (run(kind, h) - reference).length())
            .collect();
        let orders: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
        println!("{kind:?}: h {steps:?} errors {errors:?} orders {orders:?}");
        for o in orders {
            assert!((o - order).abs() <= band, "{kind:?} order {o}");
        }
    }
}

/// A ray launched in the sech fiber at `x0` with slope `slope`, followed for `length` units of
/// arclength.
struct Launch {
    x0: f64,
    slope: f64,
    length: f64,
}

/// The ray of the order studies: x0 = 0.5, slope 0.1, 20 units — over three periods of the
/// fiber, through six turning points.
const THROUGH_TURNS: Launch = Launch {
    x0: 0.5,
    slope: 0.1,
    length: 20.0,
};

/// The error against the exact path at the end of a fixed-step trace of `launch` in a sech
/// fiber (n0 = 1.5, g = 1), for each step in `steps`.
fn end_errors(kind: StepperKind, steps: &[f64], launch: &Launch) -> Vec<f64> {
    let g = 1.0;
    let fiber = z_fiber(|axis| SechFiber { n0: 1.5, g, axis });
    steps
        .iter()
        .map(|&h| {
            let out = trace(
                &fiber,
                kind,
                StepControl::Fixed { step: h },
                DVec3::new(launch.x0, 0.0, 0.0),
                DVec3::new(launch.slope, 0.0, 1.0),
                launch.length,
                Bounds::Unbounded,
            );
            let p = out.state.position;
            (p.x - sech_exact_x(g, launch.x0, launch.slope, p.z)).abs()
        })
        .collect()
}

/// Convergence orders with fixed steps on [`THROUGH_TURNS`]: log(e(h)/e(h'))/log(h/h') for
/// each consecutive pair of `steps`.
fn measured_order(kind: StepperKind, steps: &[f64]) -> Vec<f64> {
    let errors = end_errors(kind, steps, &THROUGH_TURNS);
    let orders: Vec<f64> = errors
        .windows(2)
        .zip(steps.windows(2))
        .map(|(e, h)| (e[0] / e[1]).ln() / (h[0] / h[1]).ln())
        .collect();
    println!("{kind:?}: h {steps:?} errors {errors:?} orders {orders:?}");
    orders
}

/// The least-squares slope of ln e against ln h, and its standard error (from the residuals'
/// spread, n − 2 degrees of freedom).
fn fitted_order(steps: &[f64], errors: &[f64]) -> (f64, f64) {
    let n = steps.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = steps
        .iter()
        .zip(errors)
        .map(|(h, e)| (h.ln(), e.ln()))
        .unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let slope = sxy / sxx;
    let residuals: f64 = x
        .iter()
        .zip(&y)
        .map(|(a, b)| (b - my - slope * (a - mx)).powi(2))
        .sum();
    (slope, (residuals / (n - 2.0) / sxx).sqrt())
}

#[test]
fn rk4_and_arc_chain_are_fourth_order_rkn_sixth() {
    // RK4 and the RKN pair: 4 ± 0.3 (steps large enough that rounding, ~1e-14, is far below
    // the smallest error, ~1e-10).
    for o in measured_order(StepperKind::Rk4, &[0.1, 0.05, 0.025, 0.0125]) {
        assert!((o - 4.0).abs() <= 0.3, "RK4 order {o}");
    }
    // The RKN pair: sixth order. Measured 6.58, 6.48, 6.34, falling toward 6 as the steps
    // shrink (the next terms still count at h = 0.4; at h = 0.025 the error, ~1e-14, is
    // rounding): each slope within 6 ± 0.7, the last within 6 ± 0.4.
    let orders = measured_order(StepperKind::Rkn, &[0.4, 0.2, 0.1, 0.05]);
    for o in &orders {
        assert!((o - 6.0).abs() <= 0.7, "RKN order {o}");
    }
    assert!((orders[2] - 6.0).abs() <= 0.4, "RKN order {}", orders[2]);
    // The arc chain: 4 ± 0.2 (the band asked for) (measured 4.14, 4.07, 4.03; at
    // h = 0.4 the next terms still count: 4.40).
    for o in measured_order(StepperKind::Arc, &[0.1, 0.05, 0.025, 0.0125]) {
        assert!((o - 4.0).abs() <= 0.2, "arc order {o}");
    }
}

/// The Snell stepper's order. Between turning points it is a first-order method: the
/// direction is refracted once per step from the step's end, so on a stretch with no turning
/// point (x0 = 0.5 heading for the axis with slope −0.1, 2 units: the next turn is at
/// z ≈ 2.9) the fitted order over 8 halvings is 1 within 0.05 (measured 1.010 ± 0.002). At a
/// turning point a ray is
/// reflected at a layer's face, up to h from where the smooth ray turns; a ray grazing a layer
/// covers a distance ∝ √δ along it while it dips δ into it, so each turn adds an error of
/// order h^½ whose factor depends on where the faces fall (erratic from one h to the next).
/// Through six turns ([`THROUGH_TURNS`]) the fitted order must lie between those two,
/// [½, 1], widened by twice the fit's standard error.
#[test]
fn snell_steps_are_first_order_between_turning_points_and_slower_through_them() {
    let steps: Vec<f64> = (0..8).map(|k| 0.1 / 2f64.powi(k)).collect();
    let between = Launch {
        x0: 0.5,
        slope: -0.1,
        length: 2.0,
    };
    let errors = end_errors(StepperKind::Snell, &steps, &between);
    let (order, error) = fitted_order(&steps, &errors);
    println!("Snell steps between turns: errors {errors:?}, order {order:.3} ± {error:.3}");
    assert!(
        (order - 1.0).abs() <= 0.05,
        "Snell order between turns {order}"
    );
    let errors = end_errors(StepperKind::Snell, &steps, &THROUGH_TURNS);
    let (order, error) = fitted_order(&steps, &errors);
    println!("Snell steps through turns: errors {errors:?}, order {order:.3} ± {error:.3}");
    assert!(
        (0.5 - 2.0 * error..=1.0 + 2.0 * error).contains(&order),
        "Snell order through turns {order} ± {error}"
    );
}

/// Adaptive control at each stepper's default tolerance keeps the global position error
/// within 10·tol·L: a step's error is ≤ tol·h and errors add over L (measured growth factor
/// ~3 on these rays, 10 leaves margin).
fn default_bound(kind: StepperKind, length: f64) -> f64 {
    10.0 * kind.default_tolerance() * length
}

#[test]
fn sech_fiber_rays_follow_the_exact_path_with_every_stepper() {
    let g = 1.0;
    let fiber = z_fiber(|axis| SechFiber { n0: 1.5, g, axis });
    let length = 10.0 * std::f64::consts::TAU / g;
    for kind in StepperKind::ALL {
        // Snell steps cannot leave an exact turning point (see SnellSteps), so every stepper
        // is checked on a ray launched with a slope; arc and RK4 also on the sech ray
        // x(z) = asinh(sinh(g x0) cos(g z))/g launched parallel to the axis.
        let slopes: &[f64] = if kind == StepperKind::Snell {
            &[0.1]
        } else {
            &[0.0, 0.1]
        };
        for &slope in slopes {
            let out = trace(
                &fiber,
                kind,
                StepControl::default_for(kind),
                DVec3::new(0.5, 0.0, 0.0),
                DVec3::new(slope, 0.0, 1.0),
                length,
                Bounds::Unbounded,
            );
            assert_eq!(out.reason, Termination::LengthReached);
            let p = out.state.position;
            let err = (p.x - sech_exact_x(g, 0.5, slope, p.z))
                .abs()
                .max(p.y.abs());
            println!(
                "{kind:?} slope {slope}: error {err:e} in {} steps",
                out.steps
            );
            assert!(
                err <= default_bound(kind, out.arclength),
                "{kind:?} slope {slope}: {err:e}"
            );
        }
    }
}

/// The known-limit check for Snell steps: launched exactly at a turning point the ray
/// is not bent (documented in SnellSteps); this pins that behaviour so a change is noticed.
#[test]
fn snell_steps_do_not_leave_an_exact_turning_point() {
    let fiber = z_fiber(|axis| SechFiber {
        n0: 1.5,
        g: 1.0,
        axis,
    });
    let out = trace(
        &fiber,
        StepperKind::Snell,
        StepControl::Fixed { step: 0.01 },
        DVec3::new(0.5, 0.0, 0.0),
        DVec3::Z,
        5.0,
        Bounds::Unbounded,
    );
    assert_eq!(out.state.position.x, 0.5);
}

/// Parabolic rod n0(1 − a r²/2): a ray launched from the axis with slope θ has the paraxial
/// path x = (θ/√a) sin(√a z), pitch 2π/√a. The exact ray's frequency is higher by
/// (5/16) a A² (amplitude A = θ/√a: the index's a²r⁴ term and the Duffing correction), so
/// at z = P/2 and z = P the ray is at |x| ≤ A·π·(5/16)aA²·(z/(P/2)) plus the stepper's error.
#[test]
fn parabolic_rod_has_the_paraxial_pitch() {
    let a = 0.1;
    let rod = z_fiber(|axis| ParabolicFiber { n0: 1.5, a, axis });
    let pitch = std::f64::consts::TAU / a.sqrt();
    let theta = 0.003;
    let amp = theta / a.sqrt();
    for kind in StepperKind::ALL {
        for (zmax, halves) in [(0.5 * pitch, 1.0), (pitch, 2.0)] {
            let bounds = Bounds::Box {
                min: DVec3::new(-1.0, -1.0, -1.0),
                max: DVec3::new(1.0, 1.0, zmax),
            };
            let out = trace(
                &rod,
                kind,
                StepControl::default_for(kind),
                DVec3::ZERO,
                DVec3::new(theta, 0.0, 1.0),
                2.0 * pitch,
                bounds,
            );
            assert_eq!(out.reason, Termination::LeftBounds);
            assert!((out.state.position.z - zmax).abs() < 1e-9);
            let nonlinear = amp * std::f64::consts::PI * halves * 5.0 / 16.0 * a * amp * amp;
            let bound = 2.0 * nonlinear + default_bound(kind, out.arclength);
            println!(
                "{kind:?} z={zmax:.4}: x = {:e} (bound {bound:e})",
                out.state.position.x
            );
            assert!(
                out.state.position.x.abs() <= bound,
                "{kind:?}: x({zmax}) = {:e}",
                out.state.position.x
            );
        }
    }
}

/// Luneburg lens: rays parallel to +x entering at heights h exit at the focus (R, 0, 0).
#[test]
fn luneburg_lens_focuses_parallel_rays_on_the_antipode() {
    let lens = Luneburg {
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let ball = Bounds::Ball {
        center: DVec3::ZERO,
        radius: 1.0,
    };
    for kind in StepperKind::ALL {
        for h in [0.05, 0.3, 0.6, 0.9] {
            let entry = DVec3::new(-(1.0f64 - h * h).sqrt(), h, 0.0);
            let out = trace(
                &lens,
                kind,
                StepControl::default_for(kind),
                entry,
                DVec3::X,
                10.0,
                ball,
            );
            assert_eq!(out.reason, Termination::LeftBounds, "{kind:?} h={h}");
            let err = (out.state.position - DVec3::X).length();
            println!("{kind:?} h={h}: focus error {err:e}");
            assert!(
                err <= default_bound(kind, out.arclength),
                "{kind:?} h={h}: {err:e}"
            );
        }
    }
}

/// Maxwell fish-eye n = 2/(1 + r²): rays are circles through P0 and Q = −P0/|P0|². The arc
/// of that circle from P0 along t̂0 to Q has length 2φR_c, φ the tangent–chord angle and
/// R_c = |Q − P0|/(2 sin φ); after that arclength the ray must be at Q.
///
/// Snell steps are left out: at the ray's farthest point from the centre (a turning point on
/// a spherical layer) their total internal reflections hold the ray on that sphere
/// ("whispering gallery", see `snell_steps_trap_at_a_spherical_turning_point`).
#[test]
fn fisheye_images_p0_onto_its_antipodal_conjugate() {
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let p0 = DVec3::new(0.6, 0.2, -0.3);
    let q = -p0 / p0.length_squared();
    for kind in [StepperKind::Arc, StepperKind::Rk4, StepperKind::Rkn] {
        for t0 in [
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(-1.0, 0.3, 0.5),
            DVec3::new(0.2, -0.1, 1.0),
        ] {
            let t = t0.normalize();
            let chord = q - p0;
            let phi = t.dot(chord.normalize()).clamp(-1.0, 1.0).acos();
            let length = 2.0 * phi * chord.length() / (2.0 * phi.sin());
            let out = trace(
                &eye,
                kind,
                StepControl::default_for(kind),
                p0,
                t,
                length,
                Bounds::Unbounded,
            );
            let err = (out.state.position - q).length();
            println!("{kind:?} t0={t0}: error {err:e}");
            assert!(
                err <= default_bound(kind, length),
                "{kind:?} t0={t0}: {err:e}"
            );
        }
    }
}

/// The documented limit of Snell steps: launched tangentially to a spherical layer of the
/// fish-eye whose true ray turns inward (curvature |∇ln n| = 2r/(1 + r²) = 0.8 > 1/r = 0.5 at
/// r = 2), each step's total internal reflection keeps the ray on the sphere r = 2 instead.
#[test]
fn snell_steps_trap_at_a_spherical_turning_point() {
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let p0 = DVec3::new(2.0, 0.0, 0.0);
    let snell = trace(
        &eye,
        StepperKind::Snell,
        StepControl::Fixed { step: 1e-3 },
        p0,
        DVec3::Y,
        3.0,
        Bounds::Unbounded,
    );
    let rk4 = trace(
        &eye,
        StepperKind::Rk4,
        StepControl::default_for(StepperKind::Rk4),
        p0,
        DVec3::Y,
        3.0,
        Bounds::Unbounded,
    );
    let (r_snell, r_rk4) = (snell.state.position.length(), rk4.state.position.length());
    println!("after 3 units: Snell r = {r_snell}, RK4 r = {r_rk4}");
    assert!(
        (r_snell - 2.0).abs() < 1e-3,
        "Snell left the sphere: r = {r_snell}"
    );
    assert!(r_rk4 < 1.5, "the true ray turns inward: r = {r_rk4}");
}

fn deflection(out: &MarchOutcome, incoming: DVec3) -> f64 {
    let d = out.state.direction;
    incoming.cross(d).length().atan2(incoming.dot(d))
}

/// Black-hole index, rays passing at impact parameter b: the traced deflection equals the
/// exact deflection of the index model (Bouguer quadrature, `media::black_hole_deflection`), and
/// tends to the weak-field 2 rs/b.
#[test]
fn black_hole_deflection_matches_quadrature_and_weak_field() {
    let rs = 0.01;
    let q = 0.1;
    let hole = BlackHole::new(DVec3::ZERO, rs, q);
    let mut weak = Vec::new();
    for b in [6.0, 20.0, 100.0, 1000.0] {
        // Start 1e4·b away. There n = 1 + rs/D + …, so the launched ray's Bouguer invariant
        // is n(start)·b, not b (a 1/D effect, 1e-4·rs/b here, that the quadrature must use);
        // the deflection still to come at either end is ≈ rs b/(2D²), 1e-8 of the total.
        let d = 1e4 * b * rs;
        let from = DVec3::new(-d, b * rs, 0.0);
        let b_invariant = b * hole.sample(from).unwrap().n;
        let exact =
            grinlight::media::black_hole_deflection(b_invariant, q, 0.0).expect("not captured");
        for kind in [StepperKind::Rk4, StepperKind::Rkn, StepperKind::Arc] {
            let out = trace(
                &hole,
                kind,
                StepControl::default_for(kind),
                DVec3::new(-d, b * rs, 0.0),
                DVec3::X,
                2.0 * d,
                Bounds::Unbounded,
            );
            assert_eq!(out.reason, Termination::LengthReached);
            let phi = deflection(&out, DVec3::X);
            let rel = (phi - exact).abs() / exact;
            println!("{kind:?} b={b} rs: deflection {phi:.12e}, exact {exact:.12e}, rel {rel:.1e}, 2rs/b ratio {:.6}, steps {}", phi / (2.0 / b), out.steps);
            // 1e-5 relative: the default tolerances give ~1e-8 rad per unit length of
            // direction error, the far-field tail 2e-8, the quadrature 1e-12.
            assert!(rel <= 1e-5, "{kind:?} b={b}: {rel:e}");
        }
        weak.push((
            b,
            grinlight::media::black_hole_deflection(b, q, 0.0).unwrap() / (2.0 / b) - 1.0,
        ));
    }
    // Weak field: φ/(2 rs/b) − 1 falls as c1 rs/b (measured c1 ≈ 2.35 for this index
    // model; GR's is 15π/32 ≈ 1.47). The next term, ~c2 rs²/b² with c2 ≈ 7, makes
    // (ratio − 1)·b differ between b = 100 and 1000 by ≈ 3 %: the bound is 5 %. At 1000 rs
    // the ratio is within 0.3 % of 1.
    println!("deflection/(2rs/b) − 1: {weak:?}");
    let (c100, c1000) = (weak[2].1 * weak[2].0, weak[3].1 * weak[3].0);
    assert!(
        (c100 / c1000 - 1.0).abs() < 0.05,
        "(ratio − 1)·b: {c100} vs {c1000}"
    );
    assert!(weak[3].1.abs() < 3e-3);
}

/// Rays aimed into the hole end as captured (or step underflow) with a finite state, for
/// every stepper and control, never NaN and never running away.
#[test]
fn black_hole_captures_rays_aimed_at_it() {
    let hole = BlackHole::new(DVec3::ZERO, 0.01, 0.1);
    for kind in StepperKind::ALL {
        for control in [
            StepControl::default_for(kind),
            StepControl::Fixed { step: 1e-3 },
        ] {
            for b in [0.0, 0.5, 2.0, 3.0] {
                let out = trace(
                    &hole,
                    kind,
                    control,
                    DVec3::new(-5.0, b * 0.01, 0.0),
                    DVec3::X,
                    20.0,
                    Bounds::Unbounded,
                );
                let r = out.state.position.length() / 0.01;
                println!(
                    "{kind:?} {control:?} b={b}: {} at r = {r:.6} rs after {} steps",
                    out.reason.name(),
                    out.steps
                );
                assert!(
                    matches!(
                        out.reason,
                        Termination::Captured | Termination::StepUnderflow
                    ),
                    "{kind:?} {control:?} b={b}: {:?} at r={r}",
                    out.reason
                );
                // Adaptive marches stop at the capture margin (1e-9 above the horizon
                // ρ+ = 0.98990); a fixed step of 0.1 rs stops at the last state before a
                // sample fell inside, at most two steps out (RK4's stage points reach one
                // step ahead, further where n∇n is huge).
                let reach = if let StepControl::Fixed { step } = control {
                    2.0 * step / 0.01
                } else {
                    1e-6
                };
                assert!(r < 0.9899 + reach, "{kind:?} b={b}: stopped at r = {r} rs");
            }
        }
    }
}

/// Tessendorf's (2022) settings (T_max 1e-2, T_min 1e-4, N_max 1e5, initial step 0.1) on a ray that
/// falls in: the step collapses toward the horizon and the march runs to N_max, as in the
/// seed's figs. 6–7; the adaptive control ends the same ray as captured in under a tenth of
/// N_max attempts (measured: RK4 997, RKN 1 487, arc chain 2 125; the chain's (4, 2) control
/// sizes its steps for the second-order estimate where F ~ 1/(distance to the horizon)).
#[test]
fn tessendorf_control_reproduces_the_seed_while_adaptive_ends_quickly() {
    let hole = BlackHole::new(DVec3::ZERO, 0.01, 0.1);
    let from = DVec3::new(-5.0, 0.001, 0.0);
    let start = RayState::new(&hole, from, DVec3::X).unwrap();
    let limits = MarchLimits {
        length: 20.0,
        max_steps: 100_000,
        bounds: Bounds::Unbounded,
    };
    let seed = StepControl::Tessendorf {
        initial_step: 0.1,
        t_max: 1e-2,
        t_min: 1e-4,
        seed: 1,
    };
    for kind in [StepperKind::Arc, StepperKind::Rk4, StepperKind::Rkn] {
        let out = march_with(kind, &hole, seed, start, &limits, |_, _| {
            std::ops::ControlFlow::Continue(())
        });
        println!(
            "{kind:?} tessendorf: {} after {} attempts, min step {:e}",
            out.reason.name(),
            out.attempts,
            out.min_step
        );
        assert_eq!(out.reason, Termination::MaxSteps);
        assert!(
            out.min_step < 1e-12,
            "step did not collapse: {:e}",
            out.min_step
        );
        assert!(out.state.position.is_finite());
        let adaptive = march_with(
            kind,
            &hole,
            StepControl::default_for(kind),
            start,
            &limits,
            |_, _| std::ops::ControlFlow::Continue(()),
        );
        println!(
            "{kind:?} adaptive: {} after {} attempts",
            adaptive.reason.name(),
            adaptive.attempts
        );
        assert_eq!(adaptive.reason, Termination::Captured);
        assert!(
            adaptive.attempts <= limits.max_steps / 10,
            "{kind:?}: {} attempts",
            adaptive.attempts
        );
    }
}

/// A ray that starts near the hole (D = 30 b, as a camera ray of the black-hole scene does)
/// misses the deflection of its incoming leg beyond D, O(rs/D): the finite-start quadrature
/// must match the traced ray where the infinite one does not. Tolerance 1e-5 relative, as in
/// the test above; the start term changes the deflection by 1.6e-4 (b = 6) and 2.5e-4 (b = 20)
/// relative here, so the check resolves it.
#[test]
fn black_hole_deflection_from_a_finite_start_matches_quadrature() {
    let (rs, q) = (0.01, 0.1);
    let hole = BlackHole::new(DVec3::ZERO, rs, q);
    for b in [6.0, 20.0] {
        let d = 30.0 * b * rs;
        let from = DVec3::new(-d, b * rs, 0.0);
        let r0 = from.length() / rs;
        // Launched along +x: sin ψ = b/r0, so the invariant is n(r0)·r0·sin ψ = n(r0)·b.
        let b_invariant = b * hole.sample(from).unwrap().n;
        let exact = grinlight::media::black_hole_deflection(b_invariant, q, 1.0 / r0).unwrap();
        let infinite = grinlight::media::black_hole_deflection(b_invariant, q, 0.0).unwrap();
        // Trace far past the hole (the outgoing tail beyond 1e4 b is ≈ rs b/(2D²), 1e-9).
        let out = trace(
            &hole,
            StepperKind::Rk4,
            StepControl::default_for(StepperKind::Rk4),
            from,
            DVec3::X,
            1e4 * b * rs,
            Bounds::Unbounded,
        );
        let phi = deflection(&out, DVec3::X);
        println!(
            "b={b}: traced {phi:.10e}, finite-start {exact:.10e}, from infinity {infinite:.10e}"
        );
        assert!(
            (phi - exact).abs() / exact <= 1e-5,
            "b={b}: {phi} vs {exact}"
        );
        assert!((infinite - exact).abs() / exact >= 1e-4);
    }
}

/// Optical path length against closed forms, for every stepper at its default control.
///
/// Sech fiber n0 sech(g x), meridional ray launched at x0 with slope m: with the invariant
/// β = n cos θ, ds = n dz/β, so OPL = (n0²/β) ∫ dz/(1 + A² sin²(g z + φ)), sinh(g x) =
/// A sin(g z + φ); over whole periods each half period adds π/(g √(1 + A²)). The march ends
/// on the plane z = 10 periods. Luneburg lens: every ray of a parallel beam has the same
/// optical path from the plane x = −R to the focus (R, 0, 0), R (1 + π/2) (the axial ray's
/// ∫ √(2 − x²) dx), the part outside the lens being straight in n = 1.
///
/// Bound: the position bound of `default_bound` (10·tol·L), as asked ("within 10×
/// the position tolerance"): the optical path must be as accurate as the position.
#[test]
fn optical_path_matches_closed_forms_with_every_stepper() {
    use std::f64::consts::{PI, TAU};
    let (n0, g) = (1.5, 1.0);
    let fiber = z_fiber(|axis| SechFiber { n0, g, axis });
    let z_end = 10.0 * TAU / g;
    let plane = Bounds::HalfSpace {
        point: DVec3::new(0.0, 0.0, z_end),
        normal: DVec3::Z,
        reach: 2.0 * z_end,
    };
    for kind in StepperKind::ALL {
        for (x0, m) in [(0.0, 0.3), (0.5, 0.1), (0.2, -0.4)] {
            let out = trace(
                &fiber,
                kind,
                StepControl::default_for(kind),
                DVec3::new(x0, 0.0, 0.0),
                DVec3::new(m, 0.0, 1.0),
                10.0 * z_end,
                plane,
            );
            assert_eq!(out.reason, Termination::LeftBounds, "{kind:?}");
            let beta = n0 / (g * x0).cosh() / (1.0 + m * m).sqrt();
            let a2 = (g * x0).sinh().powi(2) + (m * (g * x0).cosh()).powi(2);
            let exact = n0 * n0 / beta * 20.0 * PI / (g * (1.0 + a2).sqrt());
            let err = (out.optical_path - exact).abs();
            println!(
                "{kind:?} sech x0 {x0} m {m}: OPL {} exact {exact} error {err:e}",
                out.optical_path
            );
            assert!(
                err <= default_bound(kind, out.arclength),
                "{kind:?} sech: {err:e}"
            );
        }
    }
    let lens = Luneburg {
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let ball = Bounds::Ball {
        center: DVec3::ZERO,
        radius: 1.0,
    };
    let exact = 1.0 + PI / 2.0;
    for kind in StepperKind::ALL {
        for h in [0.0, 0.3, 0.6, 0.9] {
            let x_in = (1.0f64 - h * h).sqrt();
            let out = trace(
                &lens,
                kind,
                StepControl::default_for(kind),
                DVec3::new(-x_in, h, 0.0),
                DVec3::X,
                10.0,
                ball,
            );
            assert_eq!(out.reason, Termination::LeftBounds, "{kind:?} h={h}");
            let opl = (1.0 - x_in) + out.optical_path;
            let err = (opl - exact).abs();
            println!("{kind:?} Luneburg h={h}: OPL error {err:e}");
            assert!(
                err <= default_bound(kind, out.arclength),
                "{kind:?} Luneburg h={h}: {err:e}"
            );
        }
    }
}

/// A march that replays a step sequence (`curve::march_replay_with`) is a smooth function of
/// its launch, so central differences of it give the derivative of the end point with
/// respect to the launch — what the curved connections' bundle spread needs. Sech fiber
/// (n0 1.5, g 1), meridional rays from x0 = 0.5 with slope m = 0.1 to the plane z = 7.3:
/// dx/dm = cosh(g x0) sin(g z) / (g cosh(g x)) exactly. Each stepper at its default control
/// replays its own adaptive march's lengths at m ± δ. The derivative must match the closed
/// form to 1e-7 relative (measured ≤ 1.8e-8, rk4; the end point itself errs by ~1e-8 at the
/// defaults) and must not move between δ = 1e-4 and 1e-6 by more than 1e-8 (measured
/// ≤ 1.4e-9: a smooth function's difference quotient, rounding apart; an adaptive march's
/// end changes its step sequence as the launch moves).
#[test]
fn replayed_marches_differentiate_smoothly() {
    use grinlight::curve::march_replay_with;
    let g = 1.0;
    let fiber = z_fiber(|axis| SechFiber { n0: 1.5, g, axis });
    let (x0, m, z) = (0.5, 0.1, 7.3);
    let x_end = sech_exact_x(g, x0, m, z);
    let exact = (g * x0).cosh() * (g * z).sin() / (g * (g * x_end).cosh());
    let limits = MarchLimits {
        length: 20.0,
        max_steps: 1_000_000,
        bounds: Bounds::HalfSpace {
            point: DVec3::new(0.0, 0.0, z),
            normal: DVec3::Z,
            reach: 100.0,
        },
    };
    let start = |slope: f64| {
        RayState::new(
            &fiber,
            DVec3::new(x0, 0.0, 0.0),
            DVec3::new(slope, 0.0, 1.0),
        )
        .unwrap()
    };
    for kind in [StepperKind::Rk4, StepperKind::Rkn, StepperKind::Arc] {
        let control = StepControl::default_for(kind);
        let mut lengths = Vec::new();
        let central = march_with(kind, &fiber, control, start(m), &limits, |_, step| {
            if step.length > 0.0 {
                lengths.push(step.length);
            }
            std::ops::ControlFlow::Continue(())
        });
        assert_eq!(central.reason, Termination::LeftBounds);
        let replayed = |slope: f64| {
            let out = march_replay_with(kind, &fiber, start(slope), &lengths, &limits);
            assert_eq!(out.reason, Termination::LeftBounds, "{kind:?}");
            assert!(
                (out.state.position.z - z).abs() < 1e-10,
                "{kind:?}: on the plane"
            );
            out.state.position.x
        };
        let d = |f: &dyn Fn(f64) -> f64, delta: f64| (f(m + delta) - f(m - delta)) / (2.0 * delta);
        let (coarse, fine) = (d(&replayed, 1e-4), d(&replayed, 1e-6));
        println!(
            "{kind:?}: dx/dm {fine:.12} exact {exact:.12}: rel {:.1e}; δ 1e-4 vs 1e-6 {:.1e}",
            (fine / exact - 1.0).abs(),
            (coarse / fine - 1.0).abs(),
        );
        assert!(
            (fine / exact - 1.0).abs() < 1e-7,
            "{kind:?}: {fine} vs {exact}"
        );
        assert!(
            (coarse / fine - 1.0).abs() < 1e-8,
            "{kind:?}: {coarse} vs {fine}"
        );
    }
}

/// A step's quintic Hermite path (`curve::HermitePath`, where RK steps look for surfaces)
/// against the ray itself: sech fiber (n0 1.5, g 1), a skew ray; the two end states and the
/// reference points come from an RKN march at tolerance 1e-13 (errs ≲ 1e-13 here). The path's
/// largest deviation over 16 interior points must fall as len⁶ (measured slopes printed;
/// bar 5.5–6.5 between steps of 0.8, 0.4 and 0.2) and every point must lie in its hull (the
/// capsule that decides whether a surface may be met).
#[test]
fn hermite_step_paths_are_sixth_order_and_held_by_their_hull() {
    use grinlight::curve::{HermitePath, Path};
    let fiber = z_fiber(|axis| SechFiber {
        n0: 1.5,
        g: 1.0,
        axis,
    });
    let start = RayState::new(
        &fiber,
        DVec3::new(0.4, -0.2, 0.0),
        DVec3::new(0.3, 0.25, 1.0),
    )
    .unwrap();
    let fine = StepControl::Adaptive { tolerance: 1e-13 };
    let state_at = |s: f64| {
        let limits = MarchLimits {
            length: s,
            max_steps: 1_000_000,
            bounds: Bounds::Unbounded,
        };
        let out = march_with(StepperKind::Rkn, &fiber, fine, start, &limits, |_, _| {
            std::ops::ControlFlow::Continue(())
        });
        assert_eq!(out.reason, Termination::LengthReached);
        out.state
    };
    let mut errors = Vec::new();
    for len in [0.8, 0.4, 0.2] {
        let path = HermitePath::new(&start, &state_at(len), len);
        let hull = path.hull();
        let mut worst = 0.0f64;
        for i in 1..16 {
            let s = len * i as f64 / 16.0;
            let p = path.at(s).position;
            worst = worst.max((p - state_at(s).position).length());
            assert!(
                hull.chord_distance(p) <= hull.deviation * (1.0 + 1e-12),
                "len {len}: a point outside the hull"
            );
        }
        errors.push(worst);
    }
    let slopes: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    println!("Hermite path errors {errors:?}, slopes {slopes:.2?}");
    for slope in slopes {
        assert!((5.5..6.5).contains(&slope), "slope {slope}");
    }
}

/// A march that starts on a face of its region going in (a ray refracted into a GRIN cube, as
/// the CS 184 scene's) leaves through the far face at every stepper and tolerance, even when
/// its first trial step overshoots the whole region: the crossing out is bracketed from a
/// point inside the step, not taken at the start, where the boundary's signed distance is
/// already 0. Checked against the exact ray of the linear medium n = 4 + (z − 0.4) across a
/// unit depth: the transverse momentum a = n sin θ is conserved, and the offset is
/// y = (a/b)(arcosh(n/a) − arcosh(n0/a)) — within 4 times the tolerance (1e-3, 1e-9).
#[test]
fn a_march_from_its_regions_face_leaves_by_the_far_face() {
    use grinlight::media::LinearMedium;
    let cube = LinearMedium {
        n0: 4.0,
        gradient: DVec3::Z,
        origin: DVec3::new(0.0, 0.0, 0.4),
    };
    let bounds = Bounds::Box {
        min: DVec3::new(-0.5, -0.5, -0.6),
        max: DVec3::new(0.5, 0.5, 0.4),
    };
    let theta = 0.05f64;
    let a = 4.0 * theta.sin();
    let exact = a * ((3.0 / a).acosh() - (4.0 / a).acosh()).abs();
    // On the face, and inside it by a rounding (as a camera ray's entry point lands).
    for (kind, z) in StepperKind::ALL
        .into_iter()
        .flat_map(|k| [(k, 0.4), (k, 0.4 - 1e-16)])
    {
        for tolerance in [1e-3, 1e-9] {
            let out = trace(
                &cube,
                kind,
                StepControl::Adaptive { tolerance },
                DVec3::new(0.0, 0.0, z),
                DVec3::new(theta.sin(), 0.0, -theta.cos()),
                100.0,
                bounds,
            );
            assert_eq!(out.reason, Termination::LeftBounds, "{kind:?}");
            let p = out.state.position;
            assert!(
                (p.z + 0.6).abs() < 1e-9,
                "{kind:?} {tolerance}: left at {p}"
            );
            let error = (p.x - exact).abs();
            println!("{kind:?} {tolerance}: {error:e}");
            // The control bounds each step's error by the tolerance per unit length; summed
            // over the unit depth that is about the tolerance (the first-order Snell stepper
            // measured 2.3 times it at 1e-9): 4 times it is the bound.
            assert!(error < 4.0 * tolerance, "{kind:?} {tolerance}: {error:e}");
        }
    }
}
