//! The BSDFs: every sampler against its own pdf (χ², as in `tests/sampling.rs`), reflection
//! reciprocity, the generalised reciprocity of rough transmission, energy (a rough dielectric's
//! walk over its microsurface loses nothing, and its single scattering is what `eval` says; a
//! white plastic loses nothing but the coat's single-scattering loss) and GGX's directional
//! albedo — sampled against an independent quadrature over microfacet normals; every rough
//! BSDF with GGX and with Beckmann normals.

use glam::DVec3;
use grinlight::bsdf::{walk, Bsdf, Coat, Distribution, Microsurface, Reflectance};
use grinlight::color::Rgb;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;

use crate::common::chi2::chi2;
use crate::common::quadrature;

/// A direction at polar angle `theta` from +z, in the x–z plane.
fn at(theta: f64) -> DVec3 {
    DVec3::new(theta.sin(), 0.0, theta.cos())
}

/// Both distributions of microfacet normals: every test of a rough BSDF runs on each.
const DISTRIBUTIONS: [Distribution; 2] = Distribution::ALL;

fn perfect(d: Distribution, alpha: f64) -> Bsdf<'static> {
    Bsdf::Conductor {
        fresnel: Reflectance::Constant(Rgb::ONE),
        microsurface: Some(Microsurface::isotropic(d, alpha)),
    }
}

fn gold(d: Distribution, alpha: f64) -> Bsdf<'static> {
    Bsdf::Conductor {
        fresnel: Reflectance::Complex {
            eta: Rgb::new(0.143, 0.374, 1.442),
            k: Rgb::new(3.983, 2.385, 1.603),
        },
        microsurface: Some(Microsurface::isotropic(d, alpha)),
    }
}

fn glass(d: Distribution, n1: f64, n2: f64, alpha: f64) -> Bsdf<'static> {
    Bsdf::Dielectric {
        n1,
        n2,
        microsurface: Some(Microsurface::isotropic(d, alpha)),
    }
}

fn uvw(r: &mut Pcg64Mcg) -> (f64, f64, f64) {
    (r.gen(), r.gen(), r.gen())
}

/// Every sampler draws the directions its pdf gives: rough conductors, rough dielectrics from
/// either side (total internal reflection included; the pdf is their single scattering's, the
/// samples whose pdf is finite), plastic, at grazing and steep angles.
#[test]
fn each_bsdf_samples_its_pdf() {
    for d in DISTRIBUTIONS {
        let coat = Coat::new(1.5, Microsurface::isotropic(d, 0.3));
        let plastic = Bsdf::Plastic {
            albedo: Rgb::new(0.8, 0.4, 0.2),
            coat: &coat,
        };
        let cases: Vec<(String, Bsdf)> = vec![
            ("conductor α 0.1".into(), gold(d, 0.1)),
            ("conductor α 0.5".into(), perfect(d, 0.5)),
            ("conductor α 1".into(), perfect(d, 1.0)),
            ("dielectric 1→1.5 α 0.2".into(), glass(d, 1.0, 1.5, 0.2)),
            ("dielectric 1→1.5 α 0.7".into(), glass(d, 1.0, 1.5, 0.7)),
            ("dielectric 1.5→1 α 0.3".into(), glass(d, 1.5, 1.0, 0.3)),
            ("plastic α 0.3".into(), plastic),
        ];
        let n = DVec3::Z;
        for (name, bsdf) in &cases {
            for theta in [0.3f64, 1.2] {
                let wo = at(theta);
                chi2(
                    &format!("{d:?} {name}, θo {theta}"),
                    |r| {
                        let s = bsdf.sample(wo, n, uvw(r))?;
                        s.pdf.is_finite().then_some(s.wi)
                    },
                    |wi| bsdf.pdf(wo, wi, n),
                );
            }
        }
    }
}

/// Sampling weights are f·|cos θi|/pdf with the pdf the sampler reports, and `eval` and `pdf`
/// agree with the sample for every sample drawn (relative 1e-9) — but a rough dielectric's
/// samples of later orders, which no other strategy finds: pdf ∞ and weight 1.
#[test]
fn samples_agree_with_eval_and_pdf() {
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    for d in DISTRIBUTIONS {
        let coat = Coat::new(1.5, Microsurface::isotropic(d, 0.2));
        let plastic = Bsdf::Plastic {
            albedo: Rgb::splat(0.6),
            coat: &coat,
        };
        for bsdf in [
            gold(d, 0.3),
            glass(d, 1.0, 1.5, 0.4),
            glass(d, 1.5, 1.0, 0.4),
            plastic,
        ] {
            for _ in 0..20_000 {
                let wo = at(rng.gen::<f64>() * 1.5);
                let Some(s) = bsdf.sample(wo, DVec3::Z, uvw(&mut rng)) else {
                    continue;
                };
                if s.pdf.is_infinite() {
                    assert!(matches!(bsdf, Bsdf::Dielectric { .. }) && s.weight == Rgb::ONE);
                    continue;
                }
                let pdf = bsdf.pdf(wo, s.wi, DVec3::Z);
                let f = bsdf.eval(wo, s.wi, DVec3::Z);
                assert!(
                    (pdf - s.pdf).abs() <= 1e-9 * pdf,
                    "{bsdf:?}: pdf {pdf} vs {}",
                    s.pdf
                );
                let w = f * (s.wi.z.abs() / s.pdf);
                assert!(
                    (w.0 - s.weight.0).abs().max_element() <= 1e-9 * s.weight.0.max_element(),
                    "{bsdf:?}: weight {:?} vs f cos/pdf {:?}",
                    s.weight,
                    w
                );
            }
        }
    }
}

/// Reflection is reciprocal, f(ωo, ωi) = f(ωi, ωo); transmission obeys the generalised
/// reciprocity of basic radiance, f₁₂(ωo, ωi)/n₂² = f₂₁(ωi, ωo)/n₁² (relative 1e-12 both;
/// 1 − F is taken from the rarer side, where it keeps its digits near the critical angle).
#[test]
fn reflection_is_reciprocal_and_transmission_obeys_its_reciprocity() {
    for d in DISTRIBUTIONS {
        let coat = Coat::new(1.5, Microsurface::isotropic(d, 0.25));
        let plastic = Bsdf::Plastic {
            albedo: Rgb::new(0.7, 0.5, 0.3),
            coat: &coat,
        };
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        let n = DVec3::Z;
        let mut worst: f64 = 0.0;
        for _ in 0..10_000 {
            let a = at(rng.gen::<f64>() * 1.55)
                .to_array()
                .map(|v| v + 1e-3 * rng.gen::<f64>());
            let a = DVec3::from_array(a).normalize();
            let phi: f64 = rng.gen::<f64>() * 2.0 * PI;
            let t: f64 = rng.gen::<f64>() * 1.55;
            let b = DVec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos());
            for bsdf in [
                gold(d, 0.2),
                perfect(d, 0.8),
                glass(d, 1.0, 1.33, 0.3),
                plastic,
            ] {
                let (f, g) = (bsdf.eval(a, b, n), bsdf.eval(b, a, n));
                assert!(
                    (f.0 - g.0).abs().max_element() <= 1e-12 * f.0.max_element().max(1e-300),
                    "{bsdf:?}: f(a, b) {f:?} ≠ f(b, a) {g:?}"
                );
            }
            // Transmission: b below the surface, seen from glass (n2 = 1.5) to air.
            let below = DVec3::new(b.x, b.y, -b.z);
            let (n1, n2) = (1.0, 1.5);
            let f12 = glass(d, n1, n2, 0.3).eval(a, below, n).0.x;
            let f21 = glass(d, n2, n1, 0.3).eval(below, a, -n).0.x;
            let (x, y) = (f12 / (n2 * n2), f21 / (n1 * n1));
            worst = worst.max((x - y).abs() / x.max(1e-300));
            assert!(
                (x - y).abs() <= 1e-12 * x.max(1e-300),
                "f12 {f12} f21 {f21}: relative {:e}",
                (x - y).abs() / x
            );
        }
        println!("{d:?} transmission reciprocity: worst relative difference {worst:.1e}");
    }
}

/// The directional albedo of `bsdf` by quadrature over microfacet normals
/// ([`quadrature::reflected_fraction`]), independent of the visible-normal sampler.
fn reflected_fraction_by_quadrature(bsdf: &Bsdf, wo: DVec3) -> f64 {
    quadrature::reflected_fraction(4000, 720, wo, |wi| bsdf.eval(wo, wi, DVec3::Z).0.x)
}

/// The mean sampling weight (the sampler's estimate of the same integral) and its standard
/// error.
fn reflected_fraction_by_sampling(bsdf: &Bsdf, wo: DVec3, channel: usize) -> (f64, f64) {
    let mut rng = Pcg64Mcg::seed_from_u64(17);
    let n = 400_000;
    let (mut s, mut s2) = (0.0, 0.0);
    for _ in 0..n {
        let w = bsdf
            .sample(wo, DVec3::Z, uvw(&mut rng))
            .map_or(0.0, |s| s.weight.0.to_array()[channel]);
        s += w;
        s2 += w * w;
    }
    let mean = s / n as f64;
    (mean, ((s2 / n as f64 - mean * mean) / n as f64).sqrt())
}

/// A microsurface with F = 1 reflects 1 minus its single-scattering loss: the sampler's
/// estimate equals the quadrature within 0.5 % (and 4 standard errors) at α = 0.1, 0.25, 0.5,
/// 1 and μ = 1, 0.5, the loss growing with α (to the quadrature's 10⁻⁵), GGX and Beckmann
/// alike. At α = 1 and normal
/// incidence GGX's D is 1/π, the visible normals are cosine-distributed and
/// G₂ = G₁(ωi) = 2 cos θi/(1 + cos θi): its albedo is ∫₀¹ u/(1 + u) du = 1 − ln 2
/// (u = cos 2θm), which the quadrature must give to 1e-4.
#[test]
fn microfacet_directional_albedo_matches_quadrature() {
    for d in DISTRIBUTIONS {
        println!("{d:?}: α      μ     quadrature  sampled");
        let mut last = [1.0, 1.0];
        for alpha in [0.1, 0.25, 0.5, 1.0] {
            for (k, mu) in [1.0f64, 0.5].into_iter().enumerate() {
                let wo = at(mu.acos());
                let bsdf = perfect(d, alpha);
                let q = reflected_fraction_by_quadrature(&bsdf, wo);
                let (s, se) = reflected_fraction_by_sampling(&bsdf, wo, 0);
                println!("{alpha:<6} {mu:<5} {q:.5}     {s:.5} ± {se:.5}");
                // The quadrature resolves the sharpest lobe (α = 0.1, where Beckmann's albedo at
                // normal incidence is 1 to 10⁻⁶) to 10⁻⁵.
                assert!(
                    q <= 1.0 + 1e-5 && q <= last[k] + 1e-5,
                    "{d:?} α {alpha} μ {mu}: {q}"
                );
                assert!((s - q).abs() <= 0.005 * q && (s - q).abs() <= 4.0 * se + 1e-5);
                last[k] = q;
            }
        }
        if d == Distribution::Ggx {
            let exact = 1.0 - std::f64::consts::LN_2;
            assert!(
                (last[0] - exact).abs() < 1e-4,
                "α = 1, μ = 1: {} vs 1 − ln 2",
                last[0]
            );
        }
    }
}

/// ∫ f(ωo, ωi) |cos θi| dωi over the whole sphere: the hemisphere quadrature on each side
/// (nodes crowd toward both poles), independent of the samplers, fine enough for lobes of
/// α ≥ 0.3.
fn scattered_fraction_by_quadrature(bsdf: &Bsdf, wo: DVec3) -> f64 {
    let side = |flip: f64| {
        quadrature::hemisphere(3000, 720, |w| {
            let wi = DVec3::new(w.x, w.y, flip * w.z);
            bsdf.eval(wo, wi, DVec3::Z).0.x * w.z
        })
    };
    side(1.0) + side(-1.0)
}

/// A rough dielectric's walk over its microsurface (Heitz et al. 2016) loses nothing: every
/// sample's weight is 1 and every walk leaves (to 1 in 10⁴, the order cap), from either side,
/// at every angle and roughness; the share that leaves after a single scattering (the samples
/// of finite pdf) is the quadrature of `eval` — Walter's BSDF with the correlated-height G₂ of
/// a reflection, 1/(1 + Λo + Λi), and of a transmission, B(1 + Λo, 1 + Λi) — within 0.5 %
/// and 4 standard errors for α ≥ 0.3, an independent check of both forms of G₂. Where a
/// single-scattering model loses most (α = 1 at grazing incidence) the walk's later orders
/// carry more than 10 %.
#[test]
fn a_rough_dielectric_walk_keeps_all_light_and_its_first_scattering_is_eval() {
    for d in DISTRIBUTIONS {
        println!("{d:?}: n1→n2   α     θo    quadrature  single scattering");
        let mut most_lost: f64 = 0.0;
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0)] {
            for alpha in [0.05, 0.3, 1.0] {
                for theta in [0.0f64, 0.6, 1.2, 1.5] {
                    let bsdf = glass(d, n1, n2, alpha);
                    let mut rng = Pcg64Mcg::seed_from_u64(17);
                    let n = 200_000;
                    let (mut left, mut single) = (0usize, 0usize);
                    for _ in 0..n {
                        if let Some(s) = bsdf.sample(at(theta), DVec3::Z, uvw(&mut rng)) {
                            assert_eq!(s.weight, Rgb::ONE);
                            left += 1;
                            single += usize::from(s.pdf.is_finite());
                        }
                    }
                    assert!(
                        left as f64 >= 0.9999 * n as f64,
                        "{n1}→{n2} α {alpha}: {left}"
                    );
                    if alpha >= 0.3 {
                        let q = scattered_fraction_by_quadrature(&bsdf, at(theta));
                        let p = single as f64 / n as f64;
                        let se = (p * (1.0 - p) / n as f64).sqrt();
                        println!("{n1}→{n2} {alpha:<5} {theta:<5} {q:.5}     {p:.5} ± {se:.5}");
                        assert!(
                        (p - q).abs() <= 0.005 * q + 4.0 * se,
                        "{n1}→{n2} α {alpha} θ {theta}: single scattering {p} vs quadrature {q}"
                    );
                        most_lost = most_lost.max(1.0 - q);
                    }
                }
            }
        }
        assert!(most_lost > 0.1, "{d:?}: {most_lost}");
    }
}

/// Between equal indices a rough interface is not there: every walk leaves straight on, along
/// −ωo to 1e-12, weight 1, at every roughness and angle. At n₂/n₁ = 1.0001 the limit is
/// approached continuously: all but 1 in 1000 walks leave within 0.05 rad of −ωo (one
/// refraction at relative index 1 + δ turns a ray by about √(2δ) at most, 0.012 rad here,
/// and a walk crosses a few facets; only a facet met beyond the critical angle, 89.3°, turns
/// it more), weight 1 — a single-scattering model transmits only G₂/G₁ of it, 0.85 at α = 0.5
/// and 60°.
#[test]
fn a_rough_interface_between_equal_indices_lets_light_through() {
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    for (n2, tolerance, allowed) in [(1.3, 1e-12, 0), (1.3001, 0.05, 20)] {
        for (d, alpha) in DISTRIBUTIONS
            .into_iter()
            .flat_map(|d| [(d, 0.1), (d, 0.5), (d, 1.0)])
        {
            for theta in [0.0f64, 1.0, 1.5] {
                let bsdf = glass(d, 1.3, n2, alpha);
                let mut off_course = 0;
                for _ in 0..20_000 {
                    let s = bsdf.sample(at(theta), DVec3::Z, uvw(&mut rng)).unwrap();
                    assert_eq!(s.weight, Rgb::ONE);
                    off_course += usize::from((s.wi + at(theta)).length() > tolerance);
                }
                assert!(
                    off_course <= allowed,
                    "{d:?} n2 {n2} α {alpha} θ {theta}: {off_course} of 20 000 off course"
                );
            }
        }
    }
}

/// The walk is reciprocal as basic radiance is (Heitz et al. 2016 §5): the share of walks from
/// ωo that leave within 6° of ωi, over that cap's solid angle and |cos θi|, is f(ωo, ωi), and
/// f(ωo, ωi) = f(ωi, ωo) for a reflection on either side, f₁₂(ωo, ωi)/n₂² = f₂₁(ωi, ωo)/n₁² for
/// a transmission — directions far from the single-scattering lobes included, where the
/// later orders carry it all — within 4 standard errors at α = 0.6.
#[test]
fn the_walk_is_reciprocal() {
    let g = Microsurface::ggx(0.6);
    let dir = |t: f64, p: f64| DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
    let flip = |v: DVec3| DVec3::new(v.x, v.y, -v.z);
    // f from walks of light arriving from `o` on the side of `n1`, at `i` (leaving), with its
    // standard error.
    let f = |n1: f64, n2: f64, o: DVec3, i: DVec3, seed: u64| {
        let cap = 6f64.to_radians();
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let n = 1_000_000;
        let mut hits = 0.0;
        for _ in 0..n {
            if let Some(e) = walk::dielectric(&g, n1, n2, o, uvw(&mut rng)) {
                hits += f64::from(u8::from(e.wi.dot(i) > cap.cos()));
            }
        }
        let scale = n as f64 * 2.0 * PI * (1.0 - cap.cos()) * i.z.abs();
        (hits / scale, hits.sqrt() / scale)
    };
    let agree = |name: &str, (a, sa): (f64, f64), (b, sb): (f64, f64)| {
        println!("{name}: {a:.5} ± {sa:.5} against {b:.5} ± {sb:.5}");
        assert!(
            (a - b).abs() <= 4.0 * (sa * sa + sb * sb).sqrt(),
            "{name}: {a} ± {sa} vs {b} ± {sb}"
        );
    };
    for (k, (to, ti, phi)) in [(0.5, 1.1, 0.7), (1.2, 0.3, 2.5), (1.3, 1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        let (o, i) = (dir(to, 0.0), dir(ti, phi));
        let seed = 10 * k as u64;
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0)] {
            let there = f(n1, n2, o, i, seed + 1);
            let back = f(n1, n2, i, o, seed + 2);
            agree(
                &format!("reflection {n1}→{n2} θo {to} θi {ti}"),
                there,
                back,
            );
        }
        // Into the glass along flip(i), and back out from it toward o, seen from below.
        let (into, se_into) = f(1.0, 1.5, o, flip(i), seed + 3);
        let out = f(1.5, 1.0, i, flip(o), seed + 4);
        agree(
            &format!("transmission θo {to} θi {ti}"),
            (into / 2.25, se_into / 2.25),
            out,
        );
    }
}

/// The visible normals are drawn from max(0, ωo·m) D(m) for any ωo — also below the horizon,
/// where a ray going up meets the microsurface during a walk: χ² of the drawn normals against
/// that density (normalised by quadrature) at ωo.z = 0.5, 0, −0.4, −0.9.
#[test]
fn visible_normals_are_drawn_below_the_horizon_too() {
    for (d, z) in DISTRIBUTIONS
        .into_iter()
        .flat_map(|d| [0.5f64, 0.0, -0.4, -0.9].map(|z| (d, z)))
    {
        let g = Microsurface::rough(d, [0.6, 0.3]).unwrap();
        let wo = DVec3::new((1.0 - z * z).sqrt() * 0.8, (1.0 - z * z).sqrt() * 0.6, z);
        let total = quadrature::hemisphere(1000, 720, |m| wo.dot(m).max(0.0) * g.d(m));
        chi2(
            &format!("{d:?} visible normals from ωo.z {z}"),
            |r| Some(g.sample_visible(wo, (r.gen(), r.gen()))),
            |m| wo.dot(m).max(0.0) * g.d(m) / total,
        );
    }
}

/// Plastic: its albedo is at most 1 for any base; a white base loses nothing (albedo 1
/// within the coat table's quadrature, 0.5 %); its diffuse part vanishes with the base.
#[test]
fn plastic_conserves_energy() {
    for (d, alpha) in DISTRIBUTIONS
        .into_iter()
        .flat_map(|d| [(d, 0.05), (d, 0.3), (d, 0.8)])
    {
        let coat = Coat::new(1.5, Microsurface::isotropic(d, alpha));
        for (albedo, expect_one) in [(Rgb::ONE, true), (Rgb::new(0.9, 0.5, 0.0), false)] {
            let bsdf = Bsdf::Plastic {
                albedo,
                coat: &coat,
            };
            for theta in [0.0f64, 0.7, 1.3] {
                for c in 0..3 {
                    let (e, se) = reflected_fraction_by_sampling(&bsdf, at(theta), c);
                    assert!(e <= 1.0 + 4.0 * se, "α {alpha} θ {theta}: albedo {e}");
                    if expect_one {
                        assert!(
                            (e - 1.0).abs() < 0.005 + 4.0 * se,
                            "α {alpha} θ {theta}: {e}"
                        );
                    }
                    if albedo.0.to_array()[c] == 0.0 {
                        let coat_only = coat.coat_albedo(theta.cos());
                        assert!(
                            (e - coat_only).abs() < 0.01 + 4.0 * se,
                            "{e} vs {coat_only}"
                        );
                    }
                }
            }
        }
    }
}

/// ∫ D(m) m_z dω_m = 1 (the projected microfacet area is the macro-surface's), dense enough
/// for the sharpest α tested (1e-4).
#[test]
fn the_distribution_is_normalised() {
    for (d, alpha) in DISTRIBUTIONS
        .into_iter()
        .flat_map(|d| [[0.05, 0.05], [0.3, 0.3], [1.0, 1.0], [0.1, 0.6]].map(|a| (d, a)))
    {
        let microsurface = Microsurface::rough(d, alpha).unwrap();
        let integral = quadrature::hemisphere(20_000, 256, |m| microsurface.d(m) * m.z);
        assert!(
            (integral - 1.0).abs() < 1e-4,
            "{d:?} α {alpha:?}: ∫D cos = {integral}"
        );
    }
}

/// ∫ D_ωo(m) dω_m = 1: G₁ is the normalisation of the visible normals, Λ and D agree (2e-3:
/// the visible density has a kink where ωo·m = 0, which the grid resolves to that).
#[test]
fn visible_normals_are_normalised() {
    for (d, alpha) in DISTRIBUTIONS
        .into_iter()
        .flat_map(|d| [(d, 0.1), (d, 0.5), (d, 1.0)])
    {
        let microsurface = Microsurface::isotropic(d, alpha);
        for theta in [0.0f64, 0.7, 1.3] {
            let wo = at(theta);
            let integral = quadrature::hemisphere(8_000, 512, |m| microsurface.visible_d(wo, m));
            assert!(
                (integral - 1.0).abs() < 2e-3,
                "{d:?} α {alpha}, θo {theta}: ∫D_wo = {integral}"
            );
        }
    }
}

/// The photon mapper reads a plastic's diffuse lobe from its photon map and samples the rest:
/// the diffuse lobe is exactly exit(ωo)·entry(ωi), and eval minus it is what the coat-only
/// sampler samples — each sample's weight equals that remainder·cos/pdf (to rounding, 1e-9),
/// and the mean weight (0 where the play is lost) is the coat's directional albedo E(μo),
/// the quantity the coat's table holds (independent quadrature), within 4 standard errors.
#[test]
fn a_plastics_lobes_split_into_a_diffuse_part_and_a_sampled_coat() {
    let n = DVec3::Z;
    for alpha in [0.05, 0.3] {
        let coat = Coat::new(1.5, Microsurface::ggx(alpha));
        let bsdf = Bsdf::Plastic {
            albedo: Rgb::new(0.8, 0.4, 0.2),
            coat: &coat,
        };
        let mut rng = Pcg64Mcg::seed_from_u64(5);
        for theta in [0.1f64, 0.8, 1.4] {
            let wo = at(theta);
            let samples = 200_000;
            let (mut sum, mut sum2) = (0.0, 0.0);
            for _ in 0..samples {
                let w = match bsdf.sample_beyond_diffuse(wo, n, uvw(&mut rng)) {
                    Some(s) => {
                        let diffuse = bsdf.diffuse_exit(wo, n) * bsdf.diffuse_entry(s.wi, n);
                        let coat_f = bsdf.eval(wo, s.wi, n) - diffuse;
                        let expect = coat_f.x * s.wi.z / s.pdf;
                        assert!(
                            (s.weight.x - expect).abs() <= 1e-9 * expect.max(1.0),
                            "α {alpha} θ {theta}: weight {} against f·cos/pdf {expect}",
                            s.weight.x
                        );
                        s.weight.x
                    }
                    None => 0.0,
                };
                sum += w;
                sum2 += w * w;
            }
            let mean = sum / samples as f64;
            let se = ((sum2 / samples as f64 - mean * mean) / samples as f64).sqrt();
            let e = coat.coat_albedo(theta.cos());
            assert!(
                (mean - e).abs() < 4.0 * se,
                "α {alpha} θ {theta}: mean weight {mean} ± {se} against E(μo) {e}"
            );
            // The factorisation, at a few directions in.
            for theta_i in [0.0f64, 0.6, 1.2] {
                let wi = DVec3::new(-theta_i.sin(), 0.0, theta_i.cos());
                let split = bsdf.diffuse_exit(wo, n) * bsdf.diffuse_entry(wi, n);
                let lambert = Bsdf::Lambert {
                    albedo: Rgb::new(0.8, 0.4, 0.2),
                };
                assert_eq!(
                    lambert.diffuse_exit(wo, n) * lambert.diffuse_entry(wi, n),
                    lambert.eval(wo, wi, n)
                );
                assert!(split.x > 0.0 && split.x < bsdf.eval(wo, wi, n).x);
            }
        }
    }
}
