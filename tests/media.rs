//! Every index profile's gradient against central differences of its own n, and the values
//! the profiles promise at known points.

use glam::DVec3;
use grinlight::media::*;
use rand::{Rng, SeedableRng};

fn media() -> Vec<(&'static str, Box<dyn Medium>)> {
    let axis = Axis {
        center: DVec3::new(0.1, -0.2, 0.0),
        axis: DVec3::new(0.0, 0.6, 0.8),
    };
    let grid_values: Vec<f64> = (0..4 * 3 * 5)
        .map(|i| 1.0 + 0.01 * ((i * 37) % 11) as f64)
        .collect();
    vec![
        (
            "linear",
            Box::new(LinearMedium {
                n0: 1.2,
                gradient: DVec3::new(0.01, 0.05, -0.02),
                origin: DVec3::ONE,
            }),
        ),
        (
            "exponential",
            Box::new(ExponentialMedium {
                n0: 1.1,
                gradient: DVec3::new(0.1, -0.3, 0.2),
                origin: DVec3::ZERO,
            }),
        ),
        (
            "parabolic",
            Box::new(ParabolicFiber {
                n0: 1.5,
                a: 0.2,
                axis,
            }),
        ),
        (
            "sech",
            Box::new(SechFiber {
                n0: 1.5,
                g: 0.7,
                axis,
            }),
        ),
        (
            "radial_table",
            Box::new(
                RadialTable::new(
                    (0..=12).map(|i| 0.1 * i as f64).collect(),
                    (0..=12)
                        .map(|i| {
                            let r = 0.1 * i as f64;
                            1.5 - 0.1 * r * r + 0.03 * r * r * r
                        })
                        .collect(),
                    axis,
                )
                .unwrap(),
            ),
        ),
        (
            "height_table",
            Box::new(
                HeightTable::new(
                    (0..=8).map(|i| -1.2 + 0.3 * i as f64).collect(),
                    (0..=8)
                        .map(|i| {
                            let h = -1.2 + 0.3 * i as f64;
                            1.0003 - 2e-4 * (-(h + 1.2) / 0.4).exp()
                        })
                        .collect(),
                    DVec3::ZERO,
                    DVec3::new(0.0, 0.8, 0.6),
                )
                .unwrap(),
            ),
        ),
        (
            "luneburg",
            Box::new(Luneburg {
                center: DVec3::new(0.0, 0.1, 0.0),
                radius: 1.3,
            }),
        ),
        (
            "fisheye",
            Box::new(FishEye {
                n0: 2.0,
                center: DVec3::ZERO,
                radius: 0.8,
            }),
        ),
        (
            "hyperbolic",
            Box::new(HyperbolicMedium {
                n0: 1.3,
                center: DVec3::new(0.1, 0.0, -0.1),
                radius: 1.4,
            }),
        ),
        (
            "black_hole",
            Box::new(BlackHole::new(DVec3::ZERO, 0.1, 0.3)),
        ),
        (
            "schwarzschild",
            Box::new(ExactBlackHole {
                center: DVec3::new(0.1, 0.0, -0.1),
                rs: 0.1,
                q: 0.0,
            }),
        ),
        (
            "reissner_nordstrom",
            Box::new(ExactBlackHole {
                center: DVec3::ZERO,
                rs: 0.1,
                q: 0.3,
            }),
        ),
        (
            "naked_singularity",
            Box::new(ExactBlackHole {
                center: DVec3::ZERO,
                rs: 0.1,
                q: 0.8,
            }),
        ),
        (
            "grid",
            Box::new(
                GridMedium::new(
                    DVec3::splat(-1.0),
                    DVec3::new(1.0, 1.5, 1.0),
                    [4, 3, 5],
                    grid_values.clone(),
                    Interpolation::Linear,
                )
                .unwrap(),
            ),
        ),
        (
            "cubic grid",
            Box::new(
                GridMedium::new(
                    DVec3::splat(-1.0),
                    DVec3::new(1.0, 1.5, 1.0),
                    [4, 3, 5],
                    grid_values,
                    Interpolation::Cubic,
                )
                .unwrap(),
            ),
        ),
    ]
}

/// Central differences with h = 1e-6 err by ~h²·n‴ ≈ 1e-12 plus rounding ε·n/h ≈ 2e-10; the
/// tolerance 1e-7·(1 + |∇n|) leaves a wide margin. Grid points sit inside cells (the
/// interpolant's gradient is discontinuous across cell faces), the Luneburg points off its
/// surface and the radial table's off its node radii (n″ jumps there by O(1): a difference
/// across one errs by h·Δn″/4).
#[test]
fn gradients_match_central_differences() {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(11);
    for (name, m) in media() {
        let mut checked = 0;
        while checked < 200 {
            let p = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            );
            let Some(s) = m.sample(p) else { continue };
            let h = 1e-6;
            let mut fd = DVec3::ZERO;
            let mut ok = true;
            for a in 0..3 {
                let mut e = DVec3::ZERO;
                e[a] = h;
                match (m.sample(p + e), m.sample(p - e)) {
                    (Some(u), Some(v)) => fd[a] = (u.n - v.n) / (2.0 * h),
                    _ => ok = false,
                }
            }
            let near_kink = match name {
                "grid" => {
                    let u = (p + 1.0) * DVec3::new(1.5, 0.8, 2.0);
                    (u - u.round()).abs().min_element() < 1e-4
                }
                "luneburg" => ((p - DVec3::new(0.0, 0.1, 0.0)).length() - 1.3).abs() < 1e-4,
                // n″ jumps at the nodes (the Hermite pieces are only C¹).
                "radial_table" => {
                    let d = p - DVec3::new(0.1, -0.2, 0.0);
                    let r =
                        (d - DVec3::new(0.0, 0.6, 0.8) * d.dot(DVec3::new(0.0, 0.6, 0.8))).length();
                    ((r * 10.0) - (r * 10.0).round()).abs() < 1e-3
                }
                "height_table" => {
                    let h = (p.dot(DVec3::new(0.0, 0.8, 0.6)) + 1.2) / 0.3;
                    (h - h.round()).abs() < 1e-3
                }
                _ => false,
            };
            if !ok || near_kink {
                continue;
            }
            let err = (fd - s.grad).length();
            assert!(
                err <= 1e-7 * (1.0 + s.grad.length()),
                "{name} at {p}: ∇n {} vs differences {fd} ({err:e})",
                s.grad
            );
            assert!(s.n > 0.0 && s.n.is_finite());
            checked += 1;
        }
    }
}

/// A height table through nodes of a linear profile is that profile (Fritsch–Carlson slopes
/// of equal secants are the secant: every Hermite piece is the line itself, to rounding:
/// 1e-15 for n ≈ 1, and ε·n/(piece length ≥ 0.1) ≈ 2e-15 for n′, so 1e-14), with n and ∇n
/// constant beyond its ends and ∇n along `up`; the step hint is four node spacings inside the
/// table and the distance to it plus four end spacings outside, so no step crosses it.
#[test]
fn a_height_table_reproduces_a_linear_profile() {
    let up = DVec3::new(0.0, 0.6, 0.8);
    let h: Vec<f64> = vec![0.0, 0.1, 0.25, 0.5, 1.0, 2.0];
    let line = |x: f64| 1.0 + 3e-4 - 1e-4 * x;
    let table = HeightTable::new(
        h.clone(),
        h.iter().map(|&x| line(x)).collect(),
        DVec3::Y,
        up,
    )
    .unwrap();
    for k in 0..=400 {
        let x = -0.5 + 3.0 * k as f64 / 400.0;
        let p = DVec3::Y + up * x + DVec3::new(0.3, -0.8, 0.6) * 0.7; // the offset is ⊥ up
        let s = table.sample(p).unwrap();
        let (want, slope) = match x {
            x if x < 0.0 => (line(0.0), 0.0),
            x if x >= 2.0 => (line(2.0), 0.0),
            x => (line(x), -1e-4),
        };
        assert!((s.n - want).abs() < 1e-15, "n at h {x}: {} vs {want}", s.n);
        assert!(
            (s.grad - up * slope).length() < 1e-14,
            "∇n at h {x}: {}",
            s.grad
        );
        let hint = table.step_hint(p, up);
        let want = match x {
            x if x < 0.0 => -x + 0.4,
            x if x >= 2.0 => x - 2.0 + 4.0,
            x => {
                4.0 * h
                    .windows(2)
                    .find(|w| w[0] <= x && x < w[1])
                    .map_or(0.0, |w| w[1] - w[0])
            }
        };
        let at_node = h.iter().any(|&node| (x - node).abs() < 1e-9);
        assert!(
            at_node || (hint - want).abs() < 1e-12,
            "hint at h {x}: {hint} vs {want}"
        );
    }
}

/// A radial table through nodes of the parabolic profile reproduces it: the Fritsch–Carlson
/// slope at an inner node of equal spacing is the mean of the two secants, exact for a
/// quadratic, n'(0) = 0 is exact too, so every piece but the last is the quadratic itself
/// (to rounding, 1e-14); the last piece takes the last secant as its end slope (off by
/// n0·a·h/2) and stays within 1e-5. The table returns its nodes exactly, and beyond the last
/// node n stays constant. A ray traced through the table fiber lands where the parabolic
/// fiber's does while it keeps inside the exact pieces.
#[test]
fn a_radial_table_reproduces_the_parabolic_profile() {
    use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
    let axis = Axis {
        center: DVec3::ZERO,
        axis: DVec3::Z,
    };
    let (n0, a) = (1.5, 0.10667);
    let exact = |r: f64| n0 * (1.0 - 0.5 * a * r * r);
    let r: Vec<f64> = (0..=40).map(|i| 0.0125 * i as f64).collect();
    let table = RadialTable::new(r.clone(), r.iter().map(|&x| exact(x)).collect(), axis).unwrap();
    let fiber = ParabolicFiber { n0, a, axis };
    // Below the last node (where ∇n drops to 0, as documented).
    for k in 0..4000 {
        let x = 0.5 * k as f64 / 4000.0;
        let (n, dn) = table.at(x);
        let tol = if x < r[39] { 1e-14 } else { 1e-5 };
        assert!((n - exact(x)).abs() <= tol, "n at {x}: {n} vs {}", exact(x));
        assert!((dn + n0 * a * x).abs() <= 1e3 * tol, "n' at {x}: {dn}");
    }
    for &x in &r {
        assert_eq!(table.at(x).0, exact(x));
    }
    let beyond = table.sample(DVec3::new(0.7, 0.0, 3.0)).unwrap();
    assert_eq!((beyond.n, beyond.grad), (exact(0.5), DVec3::ZERO));
    // A ray from r = 0.2 along the axis oscillates within 0.2 < r[39]: same path.
    let limits = MarchLimits {
        length: 20.0,
        max_steps: 1_000_000,
        bounds: Bounds::Unbounded,
    };
    let control = StepControl::Adaptive { tolerance: 1e-10 };
    let end = |m: &dyn Medium| {
        let start = RayState::new(m, DVec3::new(0.2, 0.0, 0.0), DVec3::Z).unwrap();
        march_with(StepperKind::Rk4, m, control, start, &limits, |_, _| {
            std::ops::ControlFlow::Continue(())
        })
        .state
        .position
    };
    let (p, q) = (end(&table), end(&fiber));
    assert!((p - q).length() < 1e-8, "{p} vs {q}");
}

#[test]
fn profiles_have_their_defining_values() {
    let lune = Luneburg {
        center: DVec3::ZERO,
        radius: 2.0,
    };
    assert_eq!(lune.sample(DVec3::ZERO).unwrap().n, 2f64.sqrt());
    assert_eq!(lune.sample(DVec3::new(2.0, 0.0, 0.0)).unwrap().n, 1.0);
    assert_eq!(lune.sample(DVec3::new(3.0, 0.0, 0.0)).unwrap().n, 1.0);
    let eye = FishEye {
        n0: 2.0,
        center: DVec3::ZERO,
        radius: 1.0,
    };
    assert_eq!(eye.sample(DVec3::X).unwrap().n, 1.0);
    // Black hole: n = ρ²/(ρ² − ρ + q²); captured at and inside the horizon and at the centre.
    let hole = BlackHole::new(DVec3::ZERO, 0.5, 0.1);
    let s = hole.sample(DVec3::new(1.0, 0.0, 0.0)).unwrap(); // ρ = 2
    assert!((s.n - 4.0 / (4.0 - 2.0 + 0.01)).abs() < 1e-15);
    let horizon = hole.horizon() * 0.5;
    assert!(hole.sample(DVec3::new(horizon, 0.0, 0.0)).is_none());
    assert!(hole
        .sample(DVec3::new(horizon * (1.0 + 1e-6), 0.0, 0.0))
        .is_some());
    assert!(hole.sample(DVec3::ZERO).is_none());
    // q > 1/2: no horizon; only the centre captures.
    let naked = BlackHole::new(DVec3::ZERO, 1.0, 0.6);
    assert_eq!(naked.horizon(), 0.0);
    assert!(naked.sample(DVec3::new(0.3, 0.0, 0.0)).is_some());
    // Parabolic fiber: n ≤ 0 beyond r = √(2/a) captures.
    let rod = ParabolicFiber {
        n0: 1.5,
        a: 2.0,
        axis: Axis {
            center: DVec3::ZERO,
            axis: DVec3::Z,
        },
    };
    assert!(rod.sample(DVec3::new(1.0, 0.0, 5.0)).is_none());
    assert!((rod.sample(DVec3::new(0.5, 0.0, 5.0)).unwrap().n - 1.5 * 0.75).abs() < 1e-15);
    // Grid: exact at the nodes, clamped outside.
    let g = GridMedium::new(
        DVec3::ZERO,
        DVec3::ONE,
        [2, 2, 2],
        vec![1.0, 2.0, 1.0, 2.0, 1.0, 2.0, 1.0, 2.0],
        Interpolation::Linear,
    )
    .unwrap();
    assert_eq!(g.sample(DVec3::new(1.0, 0.0, 0.0)).unwrap().n, 2.0);
    let outside = g.sample(DVec3::new(3.0, 0.5, 0.5)).unwrap();
    assert_eq!((outside.n, outside.grad), (2.0, DVec3::ZERO));
    assert!(UniformMedium { n: 1.3 }.is_uniform());
}

/// The march sums ∫ n ds along the path (1.5·4 = 6 in n = 1.5), and a participating
/// medium's optical depth summed over the steps it shows is ∫ σa ds: for σa = 0.2 + 0.1 x,
/// a density linear in x (which trilinear interpolation reproduces exactly) integrated
/// along each step's chord, ∫₀⁴ (0.2 + 0.1 s) ds = 1.6 — to rounding, 1e-12, whatever the
/// steps.
#[test]
fn march_sums_optical_path_and_its_steps_the_optical_depth() {
    use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
    use grinlight::volume::Absorption;
    let uniform = UniformMedium { n: 1.5 };
    let density = Density::new(
        DVec3::new(-1.0, -1.0, -1.0),
        DVec3::new(5.0, 1.0, 1.0),
        [2, 2, 2],
        [0.1, 0.7].repeat(4),
    )
    .unwrap();
    let absorption = Absorption {
        sigma_a: grinlight::color::Rgb::ONE,
        density: Some(std::sync::Arc::new(density)),
    };
    let start = RayState::new(&uniform, DVec3::ZERO, DVec3::X).unwrap();
    let limits = MarchLimits {
        length: 4.0,
        max_steps: 1000,
        bounds: Bounds::Unbounded,
    };
    for kind in StepperKind::ALL {
        let (mut depth, mut last) = (grinlight::color::Rgb::ZERO, start.position);
        let out = march_with(
            kind,
            &uniform,
            StepControl::default_for(kind),
            start,
            &limits,
            |_, step| {
                depth += absorption.step_depth(last, step.state.position, step.length);
                last = step.state.position;
                std::ops::ControlFlow::Continue(())
            },
        );
        assert!((depth.x - 1.6).abs() < 1e-12, "{kind:?}: {depth}");
        assert!(
            (out.optical_path - 6.0).abs() < 1e-12,
            "{kind:?}: {}",
            out.optical_path
        );
    }
}

/// The cubic grid: ∇n is continuous across cell faces where the
/// trilinear one jumps; on a grid sampled from the exponential medium n = 1.2·exp(0.4 x +
/// 0.25 y) the largest error of n over 2 000 points falls at the interpolant's order as the
/// grid is refined (cubic 3, linear 2; slopes within ±0.4: the sup over a finite sample
/// wobbles), and a ray through the grid lands where the analytic medium's does, the cubic
/// grid's always closer than the linear one's and within 1e-7 at 64 cells (RKN at tolerance
/// 1e-11: its own error ~1e-11). The ray's error sequence is not monotone (the cell phase of
/// its path changes with the grid), so its order is printed, not asserted.
#[test]
fn cubic_grid_is_c1_and_converges_at_third_order() {
    use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
    let analytic = ExponentialMedium {
        n0: 1.2,
        gradient: DVec3::new(0.4, 0.25, 0.0),
        origin: DVec3::ZERO,
    };
    let grid = |cells: usize, interpolation| {
        let n = cells + 1;
        let (lo, hi) = (DVec3::splat(-1.0), DVec3::splat(1.0));
        let mut values = Vec::with_capacity(n * n * n);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let ijk = DVec3::new(i as f64, j as f64, k as f64);
                    values.push(
                        analytic
                            .sample(lo + (hi - lo) * ijk / cells as f64)
                            .unwrap()
                            .n,
                    );
                }
            }
        }
        GridMedium::new(lo, hi, [n; 3], values, interpolation).unwrap()
    };
    // Continuity across the face x = 0 of an 8-cell grid (cells of 0.25), at a generic point.
    for (interpolation, continuous) in
        [(Interpolation::Cubic, true), (Interpolation::Linear, false)]
    {
        let g = grid(8, interpolation);
        let p = DVec3::new(0.0, 0.1234, -0.377);
        let eps = 1e-9;
        let jump = (g.sample(p + eps * DVec3::X).unwrap().grad
            - g.sample(p - eps * DVec3::X).unwrap().grad)
            .length();
        println!("{interpolation:?}: ∇n jump across a cell face {jump:e}");
        assert_eq!(jump < 1e-6, continuous, "{interpolation:?}: {jump:e}");
    }
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(15);
    let points: Vec<DVec3> = (0..2000)
        .map(|_| {
            DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
        })
        .collect();
    let end = |m: &dyn Medium| {
        let start =
            RayState::new(m, DVec3::new(-0.9, -0.3, 0.1), DVec3::new(1.0, 0.2, 0.05)).unwrap();
        let limits = MarchLimits {
            length: 1.6,
            max_steps: 1_000_000,
            bounds: Bounds::Unbounded,
        };
        march_with(
            StepperKind::Rkn,
            m,
            StepControl::Adaptive { tolerance: 1e-11 },
            start,
            &limits,
            |_, _| std::ops::ControlFlow::Continue(()),
        )
        .state
        .position
    };
    let exact = end(&analytic);
    let cells = [8, 16, 32, 64];
    let mut ray_errors = Vec::new();
    for (interpolation, order) in [(Interpolation::Cubic, 3.0), (Interpolation::Linear, 2.0)] {
        let (mut sup, mut rays) = (Vec::new(), Vec::new());
        for &c in &cells {
            let g = grid(c, interpolation);
            sup.push(
                points
                    .iter()
                    .map(|&p| (g.sample(p).unwrap().n - analytic.sample(p).unwrap().n).abs())
                    .fold(0.0, f64::max),
            );
            rays.push((end(&g) - exact).length());
        }
        let slopes: Vec<f64> = sup.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
        println!("{interpolation:?}: sup |Δn| {sup:?} slopes {slopes:?}; ray errors {rays:?}");
        for s in &slopes {
            assert!(
                (s - order).abs() <= 0.4,
                "{interpolation:?}: slopes {slopes:?}"
            );
        }
        ray_errors.push(rays);
    }
    for (cubic, linear) in ray_errors[0].iter().zip(&ray_errors[1]) {
        assert!(cubic < linear, "cubic {cubic:e} vs linear {linear:e}");
    }
    assert!(ray_errors[0][3] < 1e-7, "{:e}", ray_errors[0][3]);
}

/// Grids of air's state become indices by the Gladstone–Dale relation n − 1 = K ρ (K = 2.2644e-4
/// m³/kg) and, for temperature, the ideal gas ρ = p M/(R T): at 0 °C and 101 325 Pa air's
/// n − 1 is 2.9262e-4 (the constant's definition: to 1e-4 of n − 1, the rounding of K), at
/// 50 °C it is 273.15/323.15 of that, a density of 1.29228 kg/m³ gives the same as 0 °C, and
/// at 2 atm n − 1 doubles. A hot cell has the lower index (a mirage's cause).
#[test]
fn grids_of_temperature_and_density_are_air_indices() {
    use grinlight::scene::load::parse_scene;
    let n_of = |extra: &str, value: f64| {
        let text = format!(
            "ambient = \"g\"\n[[medium]]\nname = \"g\"\nprofile = \"grid\"\n\
             bounds = [[0,0,0],[1,1,1]]\ndims = [2,2,2]\nvalues = [{v},{v},{v},{v},{v},{v},{v},{v}]\n{extra}",
            v = value
        );
        let (scene, settings) = parse_scene(std::path::Path::new("air.toml"), text).unwrap();
        grinlight::transport::Tracer::new(&scene, &settings.trace)
            .index(Some(grinlight::ids::MediumId::new(0)), DVec3::splat(0.5))
            .unwrap()
    };
    let stp = 2.9262e-4;
    let cold = n_of("quantity = \"temperature\"\n", 273.15) - 1.0;
    let hot = n_of("quantity = \"temperature\"\n", 323.15) - 1.0;
    let dense = n_of("quantity = \"density\"\n", 1.29228) - 1.0;
    let high = n_of("quantity = \"temperature\"\npressure = 202650\n", 273.15) - 1.0;
    println!("n − 1: 0 °C {cold:.6e}, 50 °C {hot:.6e}, ρ_STP {dense:.6e}, 2 atm {high:.6e}");
    assert!((cold / stp - 1.0).abs() < 1e-4, "{cold}");
    assert!((hot / (stp * 273.15 / 323.15) - 1.0).abs() < 1e-4, "{hot}");
    assert!((dense / cold - 1.0).abs() < 1e-4, "{dense}");
    assert!((high / (2.0 * cold) - 1.0).abs() < 1e-12, "{high}");
    assert!(n_of("", 1.3) == 1.3, "values are indices by default");
}

/// The weak-field black hole in 1/ρ: for the smallest rs its index is 1 + rs/r to rounding
/// (ρ² would overflow: rs = 1e-160 at r = 1 gives ρ² = 1e320), and for ordinary rs the same
/// as ρ²/(ρ² − ρ + q²) evaluated directly, to 1e-15.
#[test]
fn the_weak_field_black_hole_holds_for_any_rs() {
    let p = DVec3::new(0.6, 0.0, 0.8);
    for rs in [1e-300, 1e-160, 1e-150] {
        let hole = BlackHole::new(DVec3::ZERO, rs, 0.0);
        let s = hole.sample(p).expect("far outside the horizon");
        assert_eq!(s.n, 1.0, "rs {rs}");
        // |∇n| = rs/r² to first order in rs.
        assert!(
            ((s.grad / rs).length() - 1.0).abs() < 1e-12,
            "rs {rs:e}: {:?}",
            s.grad
        );
    }
    for (rs, q) in [(0.01, 0.0), (0.3, 0.2), (0.5, 0.45)] {
        let hole = BlackHole::new(DVec3::ZERO, rs, q);
        let rho = 1.0 / rs;
        let direct = rho * rho / (rho * rho - rho + q * q);
        let s = hole.sample(p).unwrap();
        assert!((s.n - direct).abs() < 1e-15 * direct, "rs {rs}, q {q}");
    }
}

/// A tabulated fiber's step hint is its node spacing where the ray is, not the smallest
/// spacing anywhere (found by a node search, not a scan of the table): a table with one fine
/// interval at the axis gives 4 coarse spacings at r = 0.5, over |dir⊥| (a ray at 60° to the
/// axis: 2/√3 of it), and beyond the table the distance to it plus 4 end spacings.
#[test]
fn a_tabulated_fibers_step_follows_its_local_spacing() {
    let mut r = vec![0.0, 1e-6];
    r.extend((1..=10).map(|i| 0.1 * i as f64));
    let n: Vec<f64> = r.iter().map(|x| 1.5 - 0.1 * x * x).collect();
    let axis = Axis {
        center: DVec3::ZERO,
        axis: DVec3::Z,
    };
    let table = RadialTable::new(r, n, axis).unwrap();
    let across = DVec3::new(3f64.sqrt() / 2.0, 0.0, 0.5);
    let at = |x: f64| DVec3::new(x, 0.0, 0.0);
    let spacing = 0.1;
    assert!(
        (table.step_hint(at(0.55), across) - 4.0 * spacing / (3f64.sqrt() / 2.0)).abs() < 1e-12
    );
    assert!((table.step_hint(at(3.0), DVec3::X) - (2.0 + 4.0 * spacing)).abs() < 1e-12);
    assert!(
        table.step_hint(at(5e-7), DVec3::X) < 1e-5,
        "the fine interval where it is"
    );
}

/// A shape filled with the hyperbolic medium up to its rim (where n → ∞ and rays are captured)
/// loses the paths that meet it, and the render's statistics say how many; inside the rim
/// (radius 0.95 R) no path is lost so.
#[test]
fn paths_lost_to_an_undefined_index_are_counted() {
    for (radius, lost) in [(1.0, true), (0.95, false)] {
        let text = format!(
            "[[medium]]\nname = \"ball\"\nprofile = \"hyperbolic\"\nn0 = 1.2\nradius = 1.0\n\
             [[material]]\nname = \"glass\"\ntype = \"dielectric\"\ninterior = \"ball\"\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = {radius}\n\
             material = \"glass\"\n\
             [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n\
             [camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\n\
             width = 16\nheight = 16\n[render]\nspp = 1\nintegrator = \"path\"\n"
        );
        let (scene, settings) =
            grinlight::scene::load::parse_scene(std::path::Path::new("rim.toml"), text).unwrap();
        let (_, report) = grinlight::render::render(&scene, &settings, &()).unwrap();
        let n = report.stats.undefined_index;
        println!("ball of radius {radius} R: {n} paths lost to an undefined index");
        assert_eq!(n > 0, lost, "{}", report.stats.summary());
    }
}
