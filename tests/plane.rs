//! Curved segments against planes (Tessendorf 2022, §5, and the case of a path crossing a plane twice).

use glam::DVec3;
use grinlight::curve::CurvedSegment;

/// First sign change of the plane offset by dense sampling and bisection: an independent
/// brute-force oracle (relative arclength accuracy ~1e-15, sampling 20 000 points).
fn brute_force_crossing(
    seg: &CurvedSegment,
    normal: DVec3,
    point: DVec3,
    length: f64,
) -> Option<f64> {
    let f = |s: f64| (seg.at(s).position - point).dot(normal);
    let n = 20_000;
    let mut prev = f(0.0);
    for i in 1..=n {
        let s = length * i as f64 / n as f64;
        let cur = f(s);
        if prev * cur <= 0.0 && !(prev == 0.0 && i == 1) {
            let (mut a, mut b) = (length * (i - 1) as f64 / n as f64, s);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if (f(m) > 0.0) == (f(a) > 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            return Some(0.5 * (a + b));
        }
        prev = cur;
    }
    None
}

/// A ray launched at 45° against F = (0, −1, 0) rises to a peak and falls back; a plane
/// just below the peak is crossed twice within one segment (up, then down) although both
/// ends lie below it: the seed's end-point test misses it, the turning-point split finds it.
#[test]
fn a_segment_that_enters_and_leaves_a_plane_is_detected() {
    let seg = CurvedSegment::new(
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, -1.0, 0.0),
    );
    let length = 3.0;
    // Height along the segment; its maximum is at the turning point.
    let peak = (0..=30_000)
        .map(|i| seg.at(length * i as f64 / 30_000.0).position.y)
        .fold(f64::MIN, f64::max);
    let end = seg.at(length).position.y;
    assert!(
        end < peak - 0.1,
        "the segment must come back down (end {end}, peak {peak})"
    );
    let normal = DVec3::Y;
    for below in [1e-2, 1e-4, 1e-6] {
        let point = DVec3::new(0.0, peak - below, 0.0);
        assert!(end < point.y, "both ends below the plane");
        let got = seg
            .first_plane_crossing(normal, point, length)
            .expect("two-crossing case missed");
        let want = brute_force_crossing(&seg, normal, point, length).expect("oracle");
        // 1e-9 relative in arclength (the refinement target).
        assert!(
            (got - want).abs() <= 1e-9 * want,
            "below {below}: got {got}, oracle {want}"
        );
        let on_plane = (seg.at(got).position - point).dot(normal);
        assert!(on_plane.abs() < 1e-12, "offset {on_plane:e}");
    }
    // Above the peak: no crossing.
    assert_eq!(
        seg.first_plane_crossing(normal, DVec3::new(0.0, peak + 1e-6, 0.0), length),
        None
    );
}

/// Random segments and planes against the oracle: single crossings, double crossings and
/// misses must all agree (first crossing to 1e-9 relative).
#[test]
fn plane_crossings_agree_with_brute_force() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
    let rand_vec = |rng: &mut rand_pcg::Pcg64Mcg| {
        DVec3::new(
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        )
    };
    let (mut hits, mut doubles) = (0, 0);
    for _ in 0..300 {
        let t0 = rand_vec(&mut rng);
        let force = rand_vec(&mut rng) * 3.0;
        let seg = CurvedSegment::new(DVec3::ZERO, t0, force);
        let length = rng.gen_range(0.1..2.0);
        let normal = rand_vec(&mut rng).normalize();
        let point =
            seg.at(rng.gen_range(0.0..length)).position + normal * rng.gen_range(-0.05..0.05);
        let got = seg.first_plane_crossing(normal, point, length);
        let want = brute_force_crossing(&seg, normal, point, length);
        match (got, want) {
            (Some(g), Some(w)) => {
                hits += 1;
                let f = |s: f64| (seg.at(s).position - point).dot(normal);
                if f(0.0) * f(length) > 0.0 {
                    doubles += 1;
                }
                assert!((g - w).abs() <= 1e-9 * w.max(1e-3), "got {g}, oracle {w}");
            }
            (None, None) => {}
            other => panic!("disagree: {other:?}"),
        }
    }
    println!("{hits} crossings, {doubles} of them enter-and-leave");
    assert!(doubles > 0, "the sample must contain enter-and-leave cases");
}
