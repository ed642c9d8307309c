//! The exact arc against the same arc evaluated in 320-bit arithmetic.

use crate::common::bigarc;
use glam::DVec3;
use grinlight::curve::CurvedSegment;
use rand::Rng;
use rand_pcg::Pcg64Mcg;

/// Position error relative to the step length s and absolute direction error.
fn errors(t0: DVec3, force: DVec3, s: f64) -> (f64, f64) {
    let got = CurvedSegment::new(DVec3::ZERO, t0, force).at(s);
    let (x_ref, t_ref) = bigarc::exact_arc(t0, force, s);
    assert!(
        got.position.is_finite() && got.direction.is_finite(),
        "non-finite for t0={t0} F={force} s={s}"
    );
    (
        (got.position - x_ref).length() / s,
        (got.direction - t_ref).length(),
    )
}

fn random_unit(rng: &mut Pcg64Mcg) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        );
        if (0.1..1.0).contains(&v.length()) {
            return v.normalize();
        }
    }
}

fn log_uniform(rng: &mut Pcg64Mcg, lo: f64, hi: f64) -> f64 {
    (rng.gen_range(lo.ln()..hi.ln())).exp()
}

/// 3000 random cases over β ∈ [1e-9, π − 1e-9] (a third uniform, a third clustered
/// log-uniformly at each end), |F| ∈ [1e-6, 1e3], s ∈ [1e-8, 50], both log-uniform.
///
/// Tolerance 1e-12: the recipe's own error is ~1e-15, the
/// reference's ~1e-90; 1e-12 leaves room for the ~ε·ln(2/σ) conditioning near β = π.
#[test]
fn exact_arc_matches_320_bit_reference_on_random_cases() {
    let mut rng = Pcg64Mcg::new(0x05ee_da4c);
    let (mut worst_x, mut worst_t) = (0.0f64, 0.0f64);
    for i in 0..3000 {
        let beta = match i % 3 {
            0 => rng.gen_range(1e-9..std::f64::consts::PI - 1e-9),
            1 => log_uniform(&mut rng, 1e-9, 1.0),
            _ => std::f64::consts::PI - log_uniform(&mut rng, 1e-9, 1.0),
        };
        let f_hat = random_unit(&mut rng);
        let p = (random_unit(&mut rng) - f_hat * 0.0)
            .cross(f_hat)
            .normalize();
        let t0 = beta.cos() * f_hat + beta.sin() * p;
        let force = f_hat * log_uniform(&mut rng, 1e-6, 1e3);
        let s = log_uniform(&mut rng, 1e-8, 50.0);
        let (ex, et) = errors(t0, force, s);
        worst_x = worst_x.max(ex);
        worst_t = worst_t.max(et);
        assert!(
            ex <= 1e-12 && et <= 1e-12,
            "case {i}: β={beta} |F|={} s={s}: position {ex:e}, direction {et:e}",
            force.length()
        );
    }
    println!("worst relative position error {worst_x:e}, direction error {worst_t:e}");
}

/// Degenerate inputs: along F (β = 0), against F (β = π), F = 0, F·s = 1e6, sin β = 1e-300.
#[test]
fn exact_arc_stress_cases_are_finite_and_accurate() {
    let f = DVec3::new(0.0, 0.0, 2.0);
    // β = 0 and β = π: straight lines (β = π is an exact, unstable equilibrium).
    for t0 in [DVec3::Z, -DVec3::Z] {
        let p = CurvedSegment::new(DVec3::ZERO, t0, f).at(3.0);
        assert_eq!(p.position, 3.0 * t0);
        assert_eq!(p.direction, t0);
    }
    // F = 0: straight, any direction length.
    let p = CurvedSegment::new(DVec3::ONE, DVec3::new(3.0, 4.0, 0.0), DVec3::ZERO).at(5.0);
    assert_eq!(p.position, DVec3::new(4.0, 5.0, 1.0));
    // F·s = 1e6 at several angles: the ray ends aligned with F, displaced by L/F ≈ s.
    for beta in [1e-6, 0.5, 1.5, 3.0, std::f64::consts::PI - 1e-6] {
        let t0 = DVec3::new(beta.sin(), 0.0, beta.cos());
        let (ex, et) = errors(t0, DVec3::new(0.0, 0.0, 1e3), 1e3);
        assert!(ex <= 1e-12 && et <= 1e-12, "β={beta}: {ex:e} {et:e}");
    }
    // sin β = 1e-300, against F: τ0 ≈ −690. Its inherent error is
    // ~ε ln(2/σ) ≈ 1.5e-13; tolerance 1e-12.
    let t0 = DVec3::new(1e-300, 0.0, -1.0);
    for s in [1e-3, 1.0, 300.0, 345.0, 400.0, 1e4] {
        let (ex, et) = errors(t0, DVec3::new(0.0, 0.0, 2.0), s);
        assert!(ex <= 1e-12 && et <= 1e-12, "s={s}: {ex:e} {et:e}");
    }
    // sin β = 1e-300 along F: essentially straight.
    let (ex, et) = errors(
        DVec3::new(1e-300, 0.0, 1.0),
        DVec3::new(0.0, 0.0, 2.0),
        10.0,
    );
    assert!(ex <= 1e-12 && et <= 1e-12);
}

/// ln(n(s)/n0) and ∫ n/n0 ds along an arc (the arc chain's optical path) against
/// the 320-bit arc's F·(x(s) − x0) and a composite Simpson rule over the f64 arc's own
/// positions (2 000 panels: truncation ~1e-14 relative for |F|s ≤ 8), on 300 random cases;
/// tolerance 1e-12 relative (measured 1.5e-15 and 7.8e-15: the closed forms lose nothing to
/// cancellation). Extreme cases (|F|s = 1e6, along, across and against F, F = 0) are never
/// NaN; exactly against F they stay finite (n falls), otherwise the optical path may only
/// overflow to +∞ where n itself would.
#[test]
fn arc_index_gain_and_optical_path_match_references() {
    let mut rng = Pcg64Mcg::new(0x0071_c0de);
    let (mut worst_gain, mut worst_path) = (0.0f64, 0.0f64);
    for _ in 0..300 {
        let t0 = random_unit(&mut rng);
        let force = random_unit(&mut rng) * log_uniform(&mut rng, 1e-3, 4.0);
        let s = log_uniform(&mut rng, 1e-3, 2.0);
        let seg = CurvedSegment::new(DVec3::ZERO, t0, force);
        let (x_ref, _) = bigarc::exact_arc(t0, force, s);
        let gain = seg.log_index_gain(s);
        let want = force.dot(x_ref);
        worst_gain = worst_gain.max((gain - want).abs() / want.abs().max(1e-3));
        let panels = 2000;
        let h = s / panels as f64;
        let f = |u: f64| force.dot(seg.at(u).position).exp();
        let simpson: f64 = (0..panels)
            .map(|i| {
                let a = i as f64 * h;
                h / 6.0 * (f(a) + 4.0 * f(a + 0.5 * h) + f(a + h))
            })
            .sum();
        worst_path = worst_path.max((seg.relative_optical_path(s) - simpson).abs() / simpson);
    }
    println!("worst: ln n gain {worst_gain:e}, optical path {worst_path:e}");
    assert!(worst_gain < 1e-12 && worst_path < 1e-12);
    for t0 in [DVec3::X, DVec3::Y, -DVec3::X, DVec3::new(-1.0, 1e-12, 0.0)] {
        for force in [DVec3::X * 1e3, DVec3::ZERO] {
            let seg = CurvedSegment::new(DVec3::ZERO, t0, force);
            let (gain, path) = (seg.log_index_gain(1e3), seg.relative_optical_path(1e3));
            println!("t0 {t0} F {force}: gain {gain:e}, path {path:e}");
            assert!(!gain.is_nan() && !path.is_nan());
            // Exactly against F the ray runs into falling n; nearly against, it turns back
            // and n grows past f64 like the along-F ray's.
            if t0 == -DVec3::X || force == DVec3::ZERO {
                assert!(gain.is_finite() && path.is_finite());
            }
        }
    }
}
