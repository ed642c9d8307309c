//! χ² tests of every sampling routine the photon and camera passes use, against its pdf:
//! directions binned over (cos θ, φ) on the whole sphere, expected counts by integrating the
//! pdf over each bin (dω = d(cos θ) dφ), bins with fewer than 5 expected merged. The test
//! fails at significance 1e-4 (critical value by the Wilson–Hilferty approximation), so a
//! correct sampler fails it once in 10⁴ seeds, and this seed is fixed.

use crate::common::chi2::chi2;
use glam::DVec3;
use grinlight::color::Rgb;
use grinlight::lights::{Falloff, Light};
use grinlight::math::Ball;
use grinlight::sampling::{
    cosine_hemisphere, power_cosine_hemisphere, power_cosine_pdf, uniform_cone, uniform_sphere,
    Strata, UNIFORM_SPHERE_PDF,
};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::{PI, TAU};

fn uv(rng: &mut Pcg64Mcg) -> (f64, f64) {
    (rng.gen(), rng.gen())
}

#[test]
fn cosine_hemisphere_matches_its_pdf() {
    chi2(
        "cosine",
        |r| Some(cosine_hemisphere(uv(r))),
        |d| d.z.max(0.0) / PI,
    );
}

#[test]
fn power_cosine_lobes_match_their_pdf() {
    for m in [0.0, 1.0, 4.5, 30.0] {
        chi2(
            &format!("cos^{m}"),
            |r| Some(power_cosine_hemisphere(m, uv(r))),
            |d| power_cosine_pdf(m, d.z),
        );
    }
}

#[test]
fn uniform_sphere_and_cone_match_their_pdfs() {
    chi2(
        "sphere",
        |r| Some(uniform_sphere(uv(r))),
        |_| UNIFORM_SPHERE_PDF,
    );
    // On a bin edge (−1 + 15·2/24), so the midpoint rule integrates the step exactly.
    let cos_max = 0.25f64;
    chi2(
        "cone",
        |r| Some(uniform_cone(cos_max, uv(r))),
        |d| {
            if d.z >= cos_max {
                1.0 / (TAU * (1.0 - cos_max))
            } else {
                0.0
            }
        },
    );
}

/// The LED's emitted directions (about its normal +z) follow I(θ) ∝ cos^m θ, and every
/// photon carries the LED's power (the pdf and the profile cancel).
#[test]
fn led_emission_follows_its_profile() {
    let m = 3.0;
    let led = Light::Led {
        disk: grinlight::shapes::Disk::full(DVec3::ZERO, DVec3::Z, 0.01),
        peak_intensity: Rgb::splat(2.0 * (m + 1.0) / TAU),
        m,
    };
    let ball = grinlight::lights::Aim::whole(
        Ball {
            center: DVec3::ZERO,
            radius: 1.0,
        },
        grinlight::lights::Entry::Upstream,
    );
    chi2(
        "led",
        |r| {
            let e = led.emit([r.gen(), r.gen(), r.gen(), r.gen()], ball)?;
            assert!(
                (e.power - Rgb::splat(2.0)).length() < 1e-12,
                "power {}",
                e.power
            );
            assert!(e.origin.z == 0.0 && e.origin.truncate().length() <= 0.01);
            Some(e.direction)
        },
        |d| power_cosine_pdf(m, d.z),
    );
}

/// A spot light's photons stay inside its cone and their mean power is the light's power
/// 2π I ∫ f(cos θ) d(cos θ), for either falloff curve (integrated by the midpoint rule here:
/// the smooth step in cos θ, and linear in θ).
#[test]
fn spot_emission_carries_its_power() {
    let (cos_inner, cos_outer) = (0.9f64, 0.7f64);
    let smooth = |c: f64| {
        let t = ((c - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    let linear = |c: f64| {
        let (o, i) = (cos_outer.acos(), cos_inner.acos());
        ((o - c.acos()) / (o - i)).clamp(0.0, 1.0)
    };
    spot_power(Falloff::SmoothStep, cos_inner, cos_outer, smooth);
    spot_power(Falloff::LinearInAngle, cos_inner, cos_outer, linear);
}

fn spot_power(falloff: Falloff, cos_inner: f64, cos_outer: f64, f: impl Fn(f64) -> f64) {
    let spot = Light::Spot {
        position: DVec3::ZERO,
        direction: DVec3::Z,
        intensity: Rgb::ONE,
        cos_inner,
        cos_outer,
        falloff,
    };
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    let n = 200_000;
    let mut sum = 0.0;
    for _ in 0..n {
        if let Some(e) = spot.emit(
            [rng.gen(), rng.gen(), rng.gen(), rng.gen()],
            grinlight::lights::Aim::whole(
                Ball {
                    center: DVec3::ZERO,
                    radius: 1.0,
                },
                grinlight::lights::Entry::Upstream,
            ),
        ) {
            assert!(e.direction.z >= cos_outer - 1e-12);
            sum += e.power.x;
        }
    }
    let steps = 100_000;
    let exact: f64 = (0..steps)
        .map(|i| f(cos_outer + (1.0 - cos_outer) * (i as f64 + 0.5) / steps as f64))
        .sum::<f64>()
        * (1.0 - cos_outer)
        / steps as f64
        * TAU;
    // Relative sd of the mean of f·Ω over 2e5 samples is < 0.2 %; tolerance 1 %.
    assert!(
        (sum / n as f64 / exact - 1.0).abs() < 0.01,
        "{falloff:?}: {} vs {exact}",
        sum / n as f64
    );
}

/// A pixel's stratified numbers: each of the n intervals [i/n, (i+1)/n) holds exactly one of
/// its n samples' numbers, and each sample's number is uniform on [0, 1) — sample 0's of
/// 10⁵ draws of n = 4 binned into 40 bins (its stratum and its place within it) passes a χ²
/// test at significance 1e-4 (critical value of 39 degrees of freedom: 77.6). Memory is
/// bounded for any n.
#[test]
fn strata_hold_one_number_each_and_every_sample_is_uniform() {
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let mut strata = Strata::default();
    for n in [1u32, 7, 32] {
        strata.draw(n, &mut rng);
        let mut held = vec![0; n as usize];
        for s in 0..n {
            let u = strata.get(s).unwrap();
            assert!((0.0..1.0).contains(&u), "{u}");
            held[(u * n as f64) as usize] += 1;
        }
        assert!(held.iter().all(|&h| h == 1), "n = {n}: {held:?}");
    }
    let (draws, bins) = (100_000, 40);
    let mut counts = vec![0.0; bins];
    for _ in 0..draws {
        strata.draw(4, &mut rng);
        counts[(strata.get(0).unwrap() * bins as f64) as usize] += 1.0;
    }
    let expected = draws as f64 / bins as f64;
    let chi2: f64 = counts
        .iter()
        .map(|c| (c - expected).powi(2) / expected)
        .sum();
    assert!(chi2 < 77.6, "χ² = {chi2}");
    // Any spp: the strata hold at most Strata::MOST samples, the rest draw their own.
    strata.draw(u32::MAX, &mut rng);
    assert!(strata.get(Strata::MOST - 1).is_some() && strata.get(Strata::MOST).is_none());
}

/// A pixel's jittered 2D points: each cell of the m × m grid (m = ⌊√n⌋) holds exactly one of
/// its first m² samples' points, the rest are not given; and sample 0's point over 10⁵ draws
/// of n = 16, binned 8 × 8, is uniform on [0, 1)² (χ² at significance 1e-4, 63 degrees of
/// freedom: critical value 113.7, by Wilson–Hilferty).
#[test]
fn jittered_strata_hold_one_point_a_cell_and_every_point_is_uniform() {
    use grinlight::sampling::Strata2;
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    let mut strata = Strata2::default();
    for (n, m) in [(1u32, 1usize), (16, 4), (20, 4), (1024, 32)] {
        strata.draw(n, &mut rng);
        let mut held = vec![0; m * m];
        for s in 0..(m * m) as u32 {
            let [u, v] = strata.get(s).0.unwrap();
            assert!((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v));
            held[(u * m as f64) as usize + m * (v * m as f64) as usize] += 1;
        }
        assert!(held.iter().all(|&h| h == 1), "n = {n}");
        assert!(strata.get((m * m) as u32).0.is_none());
    }
    let (draws, side) = (100_000, 8);
    let mut counts = vec![0.0; side * side];
    for _ in 0..draws {
        strata.draw(16, &mut rng);
        let [u, v] = strata.get(0).0.unwrap();
        counts[(u * side as f64) as usize + side * (v * side as f64) as usize] += 1.0;
    }
    let expected = draws as f64 / (side * side) as f64;
    let chi2: f64 = counts
        .iter()
        .map(|c| (c - expected).powi(2) / expected)
        .sum();
    assert!(chi2 < 113.7, "χ² = {chi2}");
}

/// Parallel light entering the world sphere of a scattering ambient medium: the lines its
/// photons set off along are drawn from a mixture (the target's disk, and the world's lines
/// uniform in their distance from the centre), each weighed by the reciprocal of that
/// mixture's density, so the weights add up to the area of any part of the beam — the world's
/// disk πR² in all, the target's πr² over the lines through it (4 standard errors); each
/// starts on the world sphere, travelling along the light.
#[test]
fn world_entry_lines_cover_the_beam() {
    use grinlight::lights::{covering_disk, Aim, Entry};
    let world = Ball {
        center: DVec3::new(0.3, -0.2, 0.1),
        radius: 10.0,
    };
    let target = Ball {
        center: DVec3::new(0.5, 0.0, 0.0),
        radius: 1.5,
    };
    let aim = Aim {
        scene: target,
        target,
        entry: Entry::World {
            ball: world,
            scatters: true,
        },
    };
    let direction = DVec3::new(0.3, -1.0, 0.2).normalize();
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let n = 400_000;
    let (mut all, mut all2, mut through, mut through2) = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..n {
        let Some((origin, area)) = covering_disk(aim, direction, (rng.gen(), rng.gen())) else {
            continue;
        };
        let on_sphere = (origin - world.center).length() / world.radius;
        assert!((on_sphere - 1.0).abs() < 1e-8, "{on_sphere}");
        assert!(
            (origin - world.center).dot(direction) < 0.0,
            "starts upstream"
        );
        all += area;
        all2 += area * area;
        let off = (origin - target.center) - direction * (origin - target.center).dot(direction);
        if off.length() <= target.radius {
            through += area;
            through2 += area * area;
        }
    }
    let n = n as f64;
    for (sum, sum2, expected) in [
        (
            all,
            all2,
            std::f64::consts::PI * world.radius * world.radius,
        ),
        (
            through,
            through2,
            std::f64::consts::PI * target.radius * target.radius,
        ),
    ] {
        let mean = sum / n;
        let se = ((sum2 / n - mean * mean) / n).sqrt();
        assert!(
            (mean - expected).abs() < 4.0 * se,
            "{mean} ± {se} against {expected}"
        );
    }
}

/// A discrete distribution draws each index in proportion to its weight and never one of
/// weight 0 (trailing zeros included): 10⁶ stratified draws over weights (0, 1, 3, 0, 6, 0)
/// land in each index's share of [0, 1) exactly, to one draw in 10⁶.
#[test]
fn a_discrete_distribution_draws_in_proportion_to_its_weights() {
    use grinlight::sampling::Discrete;
    let weights = [0.0, 1.0, 3.0, 0.0, 6.0, 0.0];
    let d = Discrete::new(&weights).unwrap();
    let n = 1_000_000;
    let mut counts = [0usize; 6];
    for i in 0..n {
        let pick = d.pick((i as f64 + 0.5) / n as f64);
        assert!((pick.probability - weights[pick.index] / 10.0).abs() < 1e-15);
        counts[pick.index] += 1;
    }
    for (i, w) in weights.iter().enumerate() {
        let share = counts[i] as f64 / n as f64;
        assert!((share - w / 10.0).abs() <= 1e-6, "index {i}: {share}");
    }
    assert!(Discrete::new(&[0.0, 0.0]).is_none());
}

/// The light choice at a point: probabilities that sum to 1 over the lights, each light drawn
/// at its probability (10⁵ draws, within 4 standard errors), a near lamp favoured over a far
/// one of equal intensity by the squared distances, parallel light weighed by its irradiance,
/// a given number used as a drawn one, and a single light taken without drawing.
#[test]
fn the_light_choice_follows_each_lights_irradiance_bound() {
    use glam::DVec3;
    use grinlight::color::Rgb;
    use grinlight::lights::{LightSampler, LightSamples};
    use grinlight::sampling::Given;
    use rand::SeedableRng;
    let point = |x: f64| grinlight::lights::Light::Point {
        position: DVec3::new(x, 0.0, 0.0),
        intensity: Rgb::ONE,
    };
    let sun = grinlight::lights::Light::Directional {
        direction: DVec3::NEG_Y,
        irradiance: Rgb::splat(0.5),
    };
    let lights = [point(1.0), point(3.0), sun];
    let sampler = LightSampler::new(&lights);
    let choice = sampler.at(DVec3::ZERO);
    // Weights 1, 1/9 and 0.5.
    let total = 1.0 + 1.0 / 9.0 + 0.5;
    let want = [1.0 / total, 1.0 / 9.0 / total, 0.5 / total];
    let sum: f64 = (0..3).map(|i| choice.probability(i)).sum();
    assert!((sum - 1.0).abs() < 1e-15);
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(7);
    let n = 100_000;
    let mut counts = [0usize; 3];
    for _ in 0..n {
        let pick = choice.pick(Given(None), &mut rng).unwrap();
        assert!((pick.probability - want[pick.index]).abs() < 1e-15);
        assert_eq!(
            pick.probability,
            choice.chance(LightSamples::One, grinlight::ids::LightId::new(pick.index))
        );
        counts[pick.index] += 1;
    }
    for i in 0..3 {
        let p = want[i];
        let se = (p * (1.0 - p) / n as f64).sqrt();
        let share = counts[i] as f64 / n as f64;
        assert!(
            (share - p).abs() <= 4.0 * se,
            "light {i}: {share} against {p}"
        );
    }
    assert!(
        (0..3).all(|i| choice.chance(LightSamples::Each, grinlight::ids::LightId::new(i)) == 1.0)
    );
    // A given number picks as a drawn one does: u below light 0's share takes light 0.
    let given = choice.pick(Given(Some([0.5 * want[0]])), &mut rng).unwrap();
    assert_eq!(given.index, 0);
    let one = LightSampler::new(&lights[..1]);
    let mut counting = rand_pcg::Pcg64Mcg::seed_from_u64(7);
    let before = counting.clone();
    let pick = one
        .at(DVec3::ZERO)
        .pick(Given(None), &mut counting)
        .unwrap();
    assert_eq!((pick.index, pick.probability), (0, 1.0));
    assert_eq!(counting, before, "one light draws no number");
}
