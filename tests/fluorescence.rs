//! Fluorescence: a dye that absorbs light and emits some of it again at longer wavelengths —
//! its quantum yield and Stokes shift in the energy budget, the share of its isotropic light a
//! slab guides by total internal reflection, and the emission spectrum as receivers read it.

use crate::common::agreement::{agreement, Agreement};
use grinlight::scene::load::parse_scene;
use std::path::Path;

/// Index of the slab.
const N: f64 = 1.5;
/// Quantum yield of the dye.
const YIELD: f64 = 0.8;
/// The slab's thickness.
const THICKNESS: f64 = 0.1;
/// The slab's half width.
const HALF: f64 = 50.0;
/// The largest number of events a photon meets.
const MAX_DEPTH: u32 = 64;
/// The receivers' bands over the emission line (nm).
const BANDS: [(f64, f64); 5] = [
    (500.0, 570.0),
    (570.0, 590.0),
    (590.0, 610.0),
    (610.0, 630.0),
    (630.0, 830.0),
];

/// A thin slab of index 1.5 (0.1 thick, 100 wide) holding a dye that absorbs 20 per unit below
/// 480 nm and nothing above 500, and emits a Gaussian line at 600 nm (FWHM 40: no overlap with
/// its absorption, so no re-absorption), lit at its centre by a spot of 400 nm light from
/// above; receivers just above and below the slab, as wide as it, read the light leaving its
/// faces in the bands of [`BANDS`].
fn slab() -> String {
    let bands: Vec<String> = BANDS
        .iter()
        .map(|(lo, hi)| format!("[{lo:.1}, {hi:.1}]"))
        .collect();
    let bands = bands.join(", ");
    let gap = 1e-3;
    format!(
        "[render]\nreceiver_photons = 1000000\nmax_depth = {MAX_DEPTH}\n\
         [[medium]]\nname = \"dyed\"\nprofile = \"uniform\"\nn = {N}\n\
         fluorescence = {{ absorption = {{ table = [[360, 20], [480, 20], [500, 0], [830, 0]] }}, \
         emission = {{ gaussian = [600, 40] }}, quantum_yield = {YIELD} }}\n\
         [[material]]\nname = \"slab\"\ntype = \"dielectric\"\ninterior = \"dyed\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-{HALF}, -{HALF}, 0]\nmax = [{HALF}, {HALF}, {THICKNESS}]\n\
         material = \"slab\"\n\
         [[light]]\ntype = \"spot\"\nposition = [0, 0, 1]\ndirection = [0, 0, -1]\n\
         intensity = 1\ncone_deg = 5\nspectrum = {{ gaussian = [400, 2] }}\n\
         [[receiver]]\nname = \"above\"\ncenter = [0, 0, {}]\nnormal = [0, 0, 1]\n\
         size = [{w}, {w}]\nbins = [1, 1]\nbands = [{bands}]\n\
         [[receiver]]\nname = \"below\"\ncenter = [0, 0, -{gap}]\nnormal = [0, 0, -1]\n\
         size = [{w}, {w}]\nbins = [1, 1]\nbands = [{bands}]\n",
        THICKNESS + gap,
        w = 2.0 * HALF,
    )
}

/// The unpolarized Fresnel reflectance from inside a medium of index `n` to vacuum at cosine
/// `mu` of the angle of incidence (1 beyond the critical angle).
fn fresnel_inside(n: f64, mu: f64) -> f64 {
    let sin_t2 = n * n * (1.0 - mu * mu);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - sin_t2).sqrt();
    let rs = (n * mu - ct) / (n * mu + ct);
    let rp = (mu - n * ct) / (mu + n * ct);
    0.5 * (rs * rs + rp * rp)
}

/// The share of isotropic light inside a slab of index `n` that leaves through its faces
/// within `hits` meetings with them: ∫₀¹ (1 − R(μ)^hits) dμ, μ = |cos| to the normal uniform
/// over [0, 1] for isotropic light, R = 1 beyond the critical angle (midpoint rule on 10⁶
/// nodes, converged to 1e-9).
fn leaving_through_faces(n: f64, hits: u32) -> f64 {
    let nodes = 1_000_000;
    (0..nodes)
        .map(|k| {
            let mu = (k as f64 + 0.5) / nodes as f64;
            1.0 - fresnel_inside(n, mu).powi(hits as i32)
        })
        .sum::<f64>()
        / nodes as f64
}

/// ∫ g(λ) ε(λ) dλ / ∫ ε(λ) dλ over a Gaussian line ε (peak, FWHM) on [lo, hi] nm (0.01 nm
/// midpoint sums).
fn over_line(peak: f64, fwhm: f64, lo: f64, hi: f64, g: impl Fn(f64) -> f64) -> f64 {
    let sigma = fwhm / (8.0 * std::f64::consts::LN_2).sqrt();
    let steps = ((hi - lo) / 0.01) as usize;
    let (mut mass, mut sum) = (0.0, 0.0);
    for k in 0..steps {
        let nm = lo + 0.01 * (k as f64 + 0.5);
        let e = (-0.5 * ((nm - peak) / sigma).powi(2)).exp();
        mass += e;
        sum += e * g(nm);
    }
    sum / mass
}

/// The dyed slab, measured once, checked four ways:
/// 1. **Quantum yield and Stokes shift.** The power the dye emitted over the power it
///    absorbed is q·E[λ]·E[1/λ′] (absorbed at the 400 nm line, emitted on the 600 nm line:
///    each photon emitted carries λ/λ′ of the energy absorbed), within 4 standard errors of
///    the absorbed photons' count; nothing re-absorbed.
/// 2. **The budget closes**: the fates add up to the power emitted to 1e-12, and the part of
///    the dye's light adds up to what the dye emitted.
/// 3. **Trapping.** Of the light the dye emitted, the share that leaves through the slab's
///    faces (the two receivers, emission bands only) is 1 − √(1 − 1/n²) = 0.2546 at n = 1.5:
///    the rest is guided by total internal reflection toward the edges. Light inside the
///    escape cone near the critical angle is reflected many times (R → 1 there), so within
///    the photon's last 62–63 meetings with the faces a share 1 − ∫(1 − R^k) stays in:
///    the expectation is that integral at k = 62 and 63 (they differ by 2e-6), within 4
///    standard errors (binomial in the emitted photons, times the spread of their powers).
/// 4. **Spectrum.** Each band's share of the light leaving the faces is the line's share of
///    emitted *power* there, ∫ε/λ′ over the band over ∫ε/λ′ (ε the photons' number spectrum),
///    within 4 of the band's standard errors.
#[test]
fn a_dyed_slab_emits_its_yield_guides_its_light_and_shows_its_line() {
    let (scene, settings) = parse_scene(Path::new("dyed_slab.toml"), slab()).unwrap();
    let photons = settings.receiver_photons as f64;
    let (m, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let dye = &budget.dyes[&0];
    println!("{}", budget.table(scene.accel.primitives(), &["dyed"]));

    // 1. Yield and Stokes shift.
    let per_photon = budget.emitted / photons;
    let absorbed = dye.absorbed / per_photon;
    let mean_inverse = over_line(600.0, 40.0, 360.0, 830.0, |nm| 1.0 / nm);
    let mean_inverse2 = over_line(600.0, 40.0, 360.0, 830.0, |nm| 1.0 / (nm * nm));
    let (excitation, excitation2) = (
        over_line(400.0, 2.0, 360.0, 830.0, |nm| nm),
        over_line(400.0, 2.0, 360.0, 830.0, |nm| nm * nm),
    );
    let expected = YIELD * excitation * mean_inverse;
    let second = YIELD * excitation2 * mean_inverse2;
    let sigma = ((second - expected * expected) / absorbed).sqrt();
    let measured = dye.emitted / dye.absorbed;
    println!(
        "emitted / absorbed {measured:.5} against q·E[λ/λ′] {expected:.5} ± {sigma:.5} \
         ({absorbed:.0} photons absorbed)"
    );
    assert!((measured - expected).abs() < 4.0 * sigma);
    assert_eq!(dye.reabsorbed, 0.0);

    // 2. The budget closes, and so does the dye's part.
    assert!((budget.booked() / budget.emitted - 1.0).abs() < 1e-12);
    let part = budget.fluoresced.as_deref().expect("the dye emitted");
    assert!((part.emitted / dye.emitted - 1.0).abs() < 1e-12);
    assert!((part.booked() / part.emitted - 1.0).abs() < 1e-12);

    // 3. Trapping.
    let faces: f64 = m
        .iter()
        .map(|r| r.bands.iter().map(|b| b.flux.0).sum::<f64>())
        .sum();
    let share = faces / dye.emitted;
    let (early, late) = (
        leaving_through_faces(N, MAX_DEPTH - 2),
        leaving_through_faces(N, MAX_DEPTH - 1),
    );
    let guided = (1.0 - 1.0 / (N * N)).sqrt();
    let expected = 0.5 * (early + late);
    let emitted_photons = dye.emitted / (per_photon * excitation * mean_inverse);
    let spread = excitation2 * mean_inverse2 / (excitation * mean_inverse).powi(2);
    let sigma = (expected * (1.0 - expected) / emitted_photons * spread).sqrt();
    println!(
        "leaving through the faces: {share:.5} against {expected:.5} ± {sigma:.5} \
         (1 − √(1 − 1/n²) = {:.5}; {emitted_photons:.0} photons emitted)",
        1.0 - guided
    );
    assert!((share - expected).abs() < 4.0 * sigma + 0.5 * (late - early).abs());
    assert!(
        (expected - (1.0 - guided)).abs() < 2e-3,
        "the cone's last reflections"
    );

    // 4. The line's shape, band by band.
    let power = |lo: f64, hi: f64| over_line(600.0, 40.0, lo, hi, |nm| 1.0 / nm);
    let line = |lo: f64, hi: f64| {
        let sigma = 40.0 / (8.0 * std::f64::consts::LN_2).sqrt();
        let mass = |a: f64, b: f64| {
            libm::erf((b - 600.0) / (sigma * 2f64.sqrt()))
                - libm::erf((a - 600.0) / (sigma * 2f64.sqrt()))
        };
        mass(lo, hi) * power(lo, hi)
    };
    let total: f64 = BANDS.iter().map(|&(lo, hi)| line(lo, hi)).sum();
    for (k, &(lo, hi)) in BANDS.iter().enumerate() {
        let flux: f64 = m.iter().map(|r| r.bands[k].flux.0).sum();
        let stderr = m
            .iter()
            .map(|r| r.bands[k].flux.1.powi(2))
            .sum::<f64>()
            .sqrt();
        let expected = faces * line(lo, hi) / total;
        println!("band {lo}–{hi} nm: {flux:.6e} W against {expected:.6e} ± {stderr:.1e}");
        assert!((flux - expected).abs() < 4.0 * stderr, "band {lo}–{hi}");
    }
}

/// `scenes/dyed_fiber.toml`, a dye-doped GRIN fiber lit at its middle from the side by a
/// 405 nm lamp (4·10⁴ photons): the dye's light is guided to both end faces, which read the same
/// flux in the dye's band (the fiber and its lighting are symmetric about the middle; within 4
/// standard errors of their difference) and next to none of the lamp's, which crosses the
/// fiber unguided (below 10⁻³ of the dye's; 8·10⁻⁵ at 2·10⁵ photons); the budget closes to 1e-12, and the dye emitted q·E[λ/λ′] of what it absorbed
/// (every photon it absorbed is the lamp's: nothing the dye emits is in its absorption band;
/// within 4 standard errors of the photons absorbed).
#[test]
fn a_dyed_fiber_guides_its_fluorescence_to_both_ends() {
    let (scene, mut settings) =
        grinlight::scene::load_scene(Path::new("scenes/dyed_fiber.toml")).unwrap();
    settings.receiver_photons = 40_000;
    let (m, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let (near, far) = (&m[0], &m[1]);
    let [(lamp_near, _), (dye_near, sd_near)] = [near.bands[0].flux, near.bands[1].flux];
    let [(lamp_far, _), (dye_far, sd_far)] = [far.bands[0].flux, far.bands[1].flux];
    println!("dye's band: near {dye_near:.4e} ± {sd_near:.1e}, far {dye_far:.4e} ± {sd_far:.1e}");
    assert!(dye_near > 0.0 && dye_far > 0.0);
    assert!((dye_near - dye_far).abs() < 4.0 * (sd_near.powi(2) + sd_far.powi(2)).sqrt());
    assert!(lamp_near < 1e-3 * dye_near && lamp_far < 1e-3 * dye_far);
    assert!((budget.booked() / budget.emitted - 1.0).abs() < 1e-12);
    let dye = &budget.dyes[&0];
    let q = 0.9;
    let stokes = over_line(405.0, 15.0, 360.0, 830.0, |nm| nm)
        * over_line(530.0, 40.0, 360.0, 830.0, |nm| 1.0 / nm);
    // Each photon absorbed carries the same power (all are the lamp's, none re-absorbed): the
    // ratio's spread is that of q·λ/λ′ over the photons absorbed.
    let absorbed = dye.absorbed / (budget.emitted / settings.receiver_photons as f64);
    let second = q
        * over_line(405.0, 15.0, 360.0, 830.0, |nm| nm * nm)
        * over_line(530.0, 40.0, 360.0, 830.0, |nm| 1.0 / (nm * nm));
    let sd = ((second - (q * stokes).powi(2)) / absorbed).sqrt();
    let ratio = dye.emitted / dye.absorbed;
    println!(
        "emitted / absorbed {ratio:.5} ± {sd:.5} against q·E[λ/λ′] {:.5}",
        q * stokes
    );
    assert!((ratio - q * stokes).abs() < 4.0 * sd);
}

/// A slab (thickness 0.5, 100 wide) of index 1 — its faces index-matched, no surface at all —
/// holding a dye that absorbs σf = 2 per unit below 480 nm and nothing above 500, emitting
/// a Gaussian line at 600 nm (FWHM 40: no overlap, nothing re-absorbed) with yield 0.7, under
/// the sun of a 400 nm line (FWHM 2, irradiance E = 1) from +z, seen from below against the
/// black sky by a camera of 1° field (16 × 16 pixels, all through the slab). Light of
/// wavelength λ reaching depth z below the top face is E·e^(−σf z); the dye emits
/// isotropically q·ε(λ′)/λ′·σf·λ·E·e^(−σf z)/(4π) per unit length, which crosses the slab
/// to the camera unabsorbed (σf(λ′) = 0), so its radiance in linear sRGB is
/// (q/4π)·K·E·(1 − e^(−σf d))·E[λ], K = ∫ r̄(λ′)·ε(λ′)/λ′ dλ′ as for a layer (0.01 nm sums,
/// independent of the renderer's tables) — channel by channel, both integrators (here the same
/// estimate: no surface scatters), within 4 standard errors of the pixels' spread plus 2·10⁻⁴
/// of it (the observer's 1 nm table against the quadrature, and the rays' obliquity:
/// 1/cos 0.7° − 1 = 7.5·10⁻⁵).
#[test]
fn a_camera_sees_a_dyed_slab_glow_with_the_light_it_absorbs() {
    let (sigma, q, d) = (2.0, 0.7, 0.5f64);
    let text = format!(
        "[render]\nspp = 4096\n\
         [camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\nfov_y_deg = 1\n\
         width = 16\nheight = 16\n\
         [[medium]]\nname = \"dyed\"\nprofile = \"uniform\"\nn = 1\n\
         fluorescence = {{ absorption = {{ table = [[360, {sigma}], [480, {sigma}], [500, 0], [830, 0]] }}, \
         emission = {{ gaussian = [600, 40] }}, quantum_yield = {q} }}\n\
         [[material]]\nname = \"slab\"\ntype = \"dielectric\"\ninterior = \"dyed\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-50, -50, 0]\nmax = [50, 50, {d}]\nmaterial = \"slab\"\n\
         [[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nirradiance = 1\n\
         spectrum = {{ gaussian = [400, 2] }}\n"
    );
    let (scene, settings) = parse_scene(Path::new("dyed_slab.toml"), text).unwrap();
    let colour = line_colour();
    let absorbed = (1.0 - (-sigma * d).exp()) * over_line(400.0, 2.0, 360.0, 830.0, |nm| nm);
    let expected = colour.map(|k| q * k * absorbed / (4.0 * std::f64::consts::PI));
    every_integrator_sees(&scene, &settings, &expected, 2e-4);
}

/// Bad dyes are errors at the file's line and column naming the key: a yield above 1 or
/// below 0, a negative absorption, a dye that absorbs nothing, an emission with no power in
/// 360–830 nm, a missing key, an unknown key, a dye with a density.
#[test]
fn bad_dyes_are_errors_at_their_key() {
    let cases = [
        ("quantum_yield = 0.8", "quantum_yield = 1.2", "`quantum_yield`: photons emitted per photon absorbed: must be in [0, 1], got 1.2"),
        ("quantum_yield = 0.8", "quantum_yield = -0.1", "must be in [0, 1], got -0.1"),
        ("[[360, 20], [480, 20], [500, 0], [830, 0]]", "[[360, -1], [830, -1]]", "`absorption`: table: every value must be a finite number ≥ 0"),
        ("[[360, 20], [480, 20], [500, 0], [830, 0]]", "[[360, 0], [830, 0]]", "it absorbs nothing from 360 to 830 nm"),
        ("{ table = [[360, 20], [480, 20], [500, 0], [830, 0]] }", "{ cauchy = [1, -1] }", "`absorption`: must be ≥ 0 and finite from 360 to 830 nm"),
        ("gaussian = [600, 40]", "gaussian = [1200, 10]", "`emission`: the spectrum has no power"),
        (", quantum_yield = 0.8", "", "`quantum_yield`: is missing"),
        ("quantum_yield = 0.8", "quantum_yield = 0.8, lifetime_ns = 3", "lifetime_ns"),
        ("n = 1.5\n", "n = 1.5\ndensity_values = [1, 1, 1, 1, 1, 1, 1, 1]\ndensity_bounds = [[-1, -1, -1], [1, 1, 1]]\ndensity_dims = [2, 2, 2]\n", "not with a density"),
    ];
    for (from, to, expected) in cases {
        let text = slab().replacen(from, to, 1);
        assert_ne!(text, slab(), "{from}");
        let line = 1 + text
            .lines()
            .position(|l| l.starts_with("fluorescence"))
            .unwrap();
        let err = parse_scene(Path::new("dyed_slab.toml"), text)
            .err()
            .unwrap_or_else(|| panic!("{to}: accepted"))
            .to_string();
        assert!(
            err.starts_with(&format!("dyed_slab.toml:{line}:")),
            "{to}: {err}"
        );
        assert!(err.contains(expected), "{to}: {err}");
    }
}

/// An independent random walk of photons through a dyed box slab [−half, half]² × [0, t] of
/// index `N`, lit as [`reabsorbing_slab`] lights it: Fresnel's unpolarized reflectance on
/// every face (total internal reflection beyond the critical angle), the dye absorbing at
/// 2·(600/λ)²⁰ per unit, emitting `YIELD` of its photons isotropically on a Gaussian line at
/// 600 nm (FWHM 40) with λ/λ′ of their energy. Returns, per photon of unit power, the mean
/// and the variance of the power leaving through the faces (z) and through the edges.
fn plane_parallel_walk(half: f64, photons: u32, seed: u64) -> [(f64, f64); 2] {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let sigma_f = |nm: f64| 2.0 * (600.0 / nm).powi(20);
    let gaussian = |rng: &mut rand_pcg::Pcg64Mcg, peak: f64, fwhm: f64| loop {
        let (u, v): (f64, f64) = (rng.gen(), rng.gen());
        let z = (-2.0 * (1.0 - u).ln()).sqrt() * (std::f64::consts::TAU * v).cos();
        let nm = peak + z * fwhm / (8.0 * std::f64::consts::LN_2).sqrt();
        if (360.0..830.0).contains(&nm) {
            break nm;
        }
    };
    let fresnel_outside = |mu: f64| {
        let st = (1.0 - mu * mu) / (N * N);
        let ct = (1.0 - st).sqrt();
        let rs = (mu - N * ct) / (mu + N * ct);
        let rp = (N * mu - ct) / (N * mu + ct);
        0.5 * (rs * rs + rp * rp)
    };
    let (lo, hi) = (
        glam::DVec3::new(-half, -half, 0.0),
        glam::DVec3::new(half, half, THICKNESS),
    );
    let mut sums = [(0.0, 0.0); 2];
    for _ in 0..photons {
        // The spot: uniform over its 5° cone, from (0, 0, 1) straight down.
        let cos = 1.0 - rng.gen::<f64>() * (1.0 - 5f64.to_radians().cos());
        let phi = std::f64::consts::TAU * rng.gen::<f64>();
        let sin = (1.0 - cos * cos).sqrt();
        let d = glam::DVec3::new(sin * phi.cos(), sin * phi.sin(), -cos);
        let mut p = glam::DVec3::new(0.0, 0.0, 1.0) + d * ((1.0 - THICKNESS) / cos);
        if rng.gen::<f64>() < fresnel_outside(cos) {
            continue;
        }
        let t = d.truncate() / N;
        let mut d = t.extend(-(1.0 - t.length_squared()).sqrt());
        let mut nm = gaussian(&mut rng, 400.0, 2.0);
        let mut power = 1.0;
        let mut tally = [0.0; 2];
        for _ in 0..MAX_EVENTS {
            let absorbed_at = -(1.0 - rng.gen::<f64>()).ln() / sigma_f(nm);
            // The face it meets first: the nearest exit along each axis.
            let (mut face_at, mut axis) = (f64::INFINITY, 0);
            for a in 0..3 {
                let bound = if d[a] > 0.0 { hi[a] } else { lo[a] };
                let s = (bound - p[a]) / d[a];
                if d[a] != 0.0 && s < face_at {
                    (face_at, axis) = (s.max(0.0), a);
                }
            }
            if absorbed_at < face_at {
                p += d * absorbed_at;
                if rng.gen::<f64>() >= YIELD {
                    break;
                }
                let out = gaussian(&mut rng, 600.0, 40.0);
                power *= nm / out;
                nm = out;
                let z = 2.0 * rng.gen::<f64>() - 1.0;
                let phi = std::f64::consts::TAU * rng.gen::<f64>();
                let r = (1.0 - z * z).sqrt();
                d = glam::DVec3::new(r * phi.cos(), r * phi.sin(), z);
                continue;
            }
            p += d * face_at;
            if rng.gen::<f64>() < fresnel_inside(N, d[axis].abs()) {
                d[axis] = -d[axis];
                continue;
            }
            tally[usize::from(axis != 2)] = power;
            break;
        }
        for (s, t) in sums.iter_mut().zip(tally) {
            s.0 += t;
            s.1 += t * t;
        }
    }
    let n = photons as f64;
    sums.map(|(s, q)| (s / n, q / n - (s / n).powi(2)))
}

/// The most events (face meetings and absorptions) a photon of the re-absorbing slab meets:
/// enough that almost none is cut (the photons trapped by total internal reflection on every
/// face are absorbed by the dye within a few units of path).
const MAX_EVENTS: u32 = 1000;

/// The dyed slab of [`slab`] whose dye also absorbs its own light: σf = 2·(600/λ)²⁰ per unit
/// (2 at the line's peak, 0.4 at 650 nm), `half` wide each way, lit from 1 above by a 5° spot
/// at 400 nm, every face plain (no receivers).
fn reabsorbing_slab(half: f64) -> String {
    format!(
        "[render]\nreceiver_photons = 200000\nmax_depth = {MAX_EVENTS}\n\
         [[medium]]\nname = \"dyed\"\nprofile = \"uniform\"\nn = {N}\n\
         fluorescence = {{ absorption = {{ angstrom = [2, 600, 20] }}, \
         emission = {{ gaussian = [600, 40] }}, quantum_yield = {YIELD} }}\n\
         [[material]]\nname = \"slab\"\ntype = \"dielectric\"\ninterior = \"dyed\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-{half}, -{half}, 0]\nmax = [{half}, {half}, {THICKNESS}]\n\
         material = \"slab\"\n\
         [[light]]\ntype = \"spot\"\nposition = [0, 0, 1]\ndirection = [0, 0, -1]\n\
         intensity = 1\ncone_deg = 5\nspectrum = {{ gaussian = [400, 2] }}\n\
         [[receiver]]\nname = \"far\"\ncenter = [0, 0, 10]\nsize = [1, 1]\nbins = [1, 1]\n"
    )
}

/// Re-absorption: where the dye's line overlaps its absorption, the light it guides to the
/// edges is absorbed again on the way (and partly emitted again, redder), so the edges'
/// share of the light falls as the slab grows. For half widths 0.5, 1 and 2, the power
/// leaving through the edges and through the faces, as shares of the light's power, against
/// an independent plane-parallel random walk of the same slab (400 000 photons; the
/// geometry, Fresnel, the dye's rates and line written out apart from the renderer), within 4
/// standard errors of their difference (from the walk's per-photon variance, for both).
#[test]
fn a_dye_that_absorbs_its_own_light_dims_the_edges_of_a_longer_slab() {
    let mut edges = Vec::new();
    for (k, half) in [0.5, 1.0, 2.0].into_iter().enumerate() {
        let (scene, settings) =
            parse_scene(Path::new("reabsorbing.toml"), reabsorbing_slab(half)).unwrap();
        let photons = settings.receiver_photons as f64;
        let (_, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
        let (mut faces, mut sides) = (0.0, 0.0);
        for (&p, &w) in &budget.out_through {
            let grinlight::shapes::Primitive::Quad(q) = &scene.accel.primitives()[p] else {
                panic!("a box is six quads");
            };
            match q.e1.cross(q.e2).normalize().z.abs() > 0.5 {
                true => faces += w / budget.emitted,
                false => sides += w / budget.emitted,
            }
        }
        let walked = 400_000;
        let [(face_mean, face_var), (side_mean, side_var)] =
            plane_parallel_walk(half, walked, 17 + k as u64);
        let dye = &budget.dyes[&0];
        println!(
            "half width {half}: edges {sides:.5} (walk {side_mean:.5}), faces {faces:.5} \
             (walk {face_mean:.5}); re-absorbed {:.3} of the dye's absorption; lost {:.1e}",
            dye.reabsorbed / dye.absorbed,
            budget.lost / budget.emitted
        );
        let sigma = |var: f64| (var / photons + var / walked as f64).sqrt();
        assert!(
            (sides - side_mean).abs() < 4.0 * sigma(side_var),
            "edges at {half}"
        );
        assert!(
            (faces - face_mean).abs() < 4.0 * sigma(face_var),
            "faces at {half}"
        );
        assert!(dye.reabsorbed > 0.0);
        assert!((budget.booked() / budget.emitted - 1.0).abs() < 1e-12);
        edges.push(sides);
    }
    assert!(edges.windows(2).all(|w| w[1] < w[0]), "{edges:?}");
}

/// A dye absorbs along the curved path light takes: a pencil of 400 nm light (a spot of a
/// 0.002° cone) sent from inside a sech fiber (n0 1.5, g 1) at x0 = 0.5 with slope 0.3 is
/// met by a receiver across it 5 units on, at the meridional ray's closed-form place
/// x(z) = asinh(sinh(g x0) cos gz + slope cosh(g x0) sin gz)/g; in the excitation's band the
/// receiver reads e^(−σf s) of the light's power, s the ray's arclength ∫ n/β dz (β = n cos θ,
/// the ray invariant; Simpson's rule on 10⁵ intervals) — 1.11 times the straight 5 units, so
/// a dye read along the chord would be 10 % off (24 standard errors). Within 4 standard errors
/// (every photon alike: binomial). The dye emits nothing (yield 0): only the pencil is traced.
#[test]
fn a_dye_absorbs_along_a_curved_ray() {
    let (n0, g, x0, slope, length, sigma) = (1.5f64, 1.0f64, 0.5f64, 0.3f64, 5.0f64, 0.2f64);
    let x_at = |z: f64| {
        ((g * x0).sinh() * (g * z).cos() + slope * (g * x0).cosh() * (g * z).sin()).asinh() / g
    };
    let beta = n0 / (g * x0).cosh() / (1.0 + slope * slope).sqrt();
    let intervals = 100_000;
    let h = length / intervals as f64;
    let f = |z: f64| n0 / (g * x_at(z)).cosh() / beta;
    let arclength = (0..intervals)
        .map(|k| {
            let z = k as f64 * h;
            h / 6.0 * (f(z) + 4.0 * f(z + 0.5 * h) + f(z + h))
        })
        .sum::<f64>();
    let text = format!(
        "[render]\nreceiver_photons = 200000\n\
         [[medium]]\nname = \"rod\"\nprofile = \"sech\"\nn0 = {n0}\ng = {g}\n\
         fluorescence = {{ absorption = {{ table = [[360, {sigma}], [480, {sigma}], [500, 0], [830, 0]] }}, \
         emission = {{ gaussian = [600, 40] }}, quantum_yield = 0 }}\n\
         [[material]]\nname = \"glass\"\ntype = \"dielectric\"\ninterior = \"rod\"\n\
         [[shape]]\ntype = \"cylinder\"\nbase = [0, 0, -1]\nradius = 3\nheight = 8\nmaterial = \"glass\"\n\
         [[light]]\ntype = \"spot\"\nposition = [{x0}, 0, 0]\ndirection = [{slope}, 0, 1]\n\
         intensity = 1\ncone_deg = 0.002\nspectrum = {{ gaussian = [400, 2] }}\n\
         [[receiver]]\nname = \"across\"\ncenter = [{}, 0, {length}]\nsize = [0.2, 0.2]\n\
         bins = [1, 1]\nbands = [[380, 420]]\n",
        x_at(length)
    );
    let (scene, settings) = parse_scene(Path::new("dyed_rod.toml"), text).unwrap();
    let (m, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let kept = m[0].bands[0].flux.0 / budget.emitted;
    let expected = (-sigma * arclength).exp();
    let n = settings.receiver_photons as f64;
    let sd = (expected * (1.0 - expected) / n).sqrt();
    println!(
        "kept {kept:.5} against e^(−σ s) {expected:.5} ± {sd:.5} (s = {arclength:.5}; \
         along the chord {:.5})",
        (-sigma * length).exp()
    );
    assert!((kept - expected).abs() < 4.0 * sd);
}

/// A black diffuse square of half width `half` about the origin in the plane z = 0, its
/// fluorescent layer absorbing the share `a` below 480 nm (nothing above 500) and emitting a
/// Gaussian line at 600 nm (FWHM 40) with yield `q`, under the sun of a 400 nm line (FWHM 2,
/// irradiance 1) from +z.
fn ink_square(a: f64, q: f64, half: f64) -> String {
    format!(
        "[[material]]\nname = \"ink\"\ntype = \"diffuse\"\nalbedo = 0\n\
         fluorescence = {{ excitation = {{ table = [[360, {a}], [480, {a}], [500, 0], [830, 0]] }}, \
         emission = {{ gaussian = [600, 40] }}, quantum_yield = {q} }}\n\
         [[shape]]\ntype = \"quad\"\n\
         vertices = [[-{half}, -{half}, 0], [{half}, -{half}, 0], [{half}, {half}, 0], [-{half}, {half}, 0]]\n\
         material = \"ink\"\n\
         [[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nirradiance = 1\n\
         spectrum = {{ gaussian = [400, 2] }}\n"
    )
}

/// A fluorescent layer on a black diffuse square (20 × 20) under the sun at 400 nm, its layer
/// absorbing a = 0.6 there and emitting a Gaussian line at 600 nm (FWHM 40) with yield 0.7:
/// the square is a Lambertian emitter of exitance M = E·a·q·E[λ/λ′], and a receiver (4 × 4)
/// 1 above its centre, in the line's band, reads M times the square's view factor averaged
/// over the receiver (a 40 × 40 grid of points; at each, the rectangle's factor from the
/// corner formula F(a, b) = (1/2π)[a/√(1+a²)·atan(b/√(1+a²)) + b/√(1+b²)·atan(a/√(1+b²))],
/// lengths over the height, odd in a and b) — within 4 standard errors. The budget books the
/// layer's absorption and emission (their ratio q·E[λ/λ′] within 4 standard errors) and its
/// heat as absorbed by surfaces.
#[test]
fn a_fluorescent_layer_glows_as_a_lambertian_emitter_of_its_absorbed_light() {
    let (a, q, half, height, side) = (0.6, 0.7, 10.0f64, 1.0f64, 4.0f64);
    let text = format!(
        "[render]\nreceiver_photons = 1000000\n{}\
         [[receiver]]\nname = \"above\"\ncenter = [0, 0, {height}]\nnormal = [0, 0, -1]\n\
         size = [{side}, {side}]\nbins = [1, 1]\nbands = [[500, 830]]\n",
        ink_square(a, q, half)
    );
    let (scene, settings) = parse_scene(Path::new("ink.toml"), text).unwrap();
    let (m, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let corner = |a: f64, b: f64| {
        let (ra, rb) = ((1.0 + a * a).sqrt(), (1.0 + b * b).sqrt());
        (a / ra * (b / ra).atan() + b / rb * (a / rb).atan()) / std::f64::consts::TAU
    };
    let points = 40;
    let view = (0..points * points)
        .map(|k| {
            let at = |i: usize| side * ((i as f64 + 0.5) / points as f64 - 0.5);
            let (x, y) = (at(k % points), at(k / points));
            let f = |u: f64, v: f64| corner((u - x) / height, (v - y) / height);
            f(half, half) - f(-half, half) - f(half, -half) + f(-half, -half)
        })
        .sum::<f64>()
        / (points * points) as f64;
    let stokes = over_line(400.0, 2.0, 360.0, 830.0, |nm| nm)
        * over_line(600.0, 40.0, 360.0, 830.0, |nm| 1.0 / nm);
    let exitance = a * q * stokes;
    let band = &m[0].bands[0];
    let irradiance = band.flux.0 / (side * side);
    let sd = band.flux.1 / (side * side);
    println!(
        "irradiance {irradiance:.5} ± {sd:.5} against M·F {:.5} (M {exitance:.5}, F {view:.5})",
        exitance * view
    );
    assert!((irradiance - exitance * view).abs() < 4.0 * sd);
    // The layer's emitted over absorbed power, within 4 standard errors of the photons it
    // absorbed (each of the same power).
    let layer = &budget.layers[&0];
    let absorbed = layer.absorbed / (budget.emitted / settings.receiver_photons as f64);
    let second = q
        * over_line(400.0, 2.0, 360.0, 830.0, |nm| nm * nm)
        * over_line(600.0, 40.0, 360.0, 830.0, |nm| 1.0 / (nm * nm));
    let sd_ratio = ((second - (q * stokes).powi(2)) / absorbed).sqrt();
    assert!((layer.emitted / layer.absorbed - q * stokes).abs() < 4.0 * sd_ratio);
    assert!((budget.booked() / budget.emitted - 1.0).abs() < 1e-12);
    assert!(budget.absorbed > 0.0 && budget.dyes.is_empty());
}

/// The ink square of the test above seen from above by a camera (32 × 32 pixels, all on the
/// square): its radiance in linear sRGB is (q/π)·K·E·a·E[λ], the layer's emitted line's colour
/// per absorbed photon's energy K = ∫ r̄(λ′)·ε(λ′)/λ′ dλ′ (ε the line's normalised density,
/// here by 0.01 nm midpoint sums of the Gaussian, independent of the renderer's 1 nm tables)
/// times the absorbed light's E·a·E[λ] over π — channel by channel (the line at 600 nm is
/// orange, its blue negative), both integrators, within 4 standard errors of the pixels'
/// spread (each pixel an independent estimate of the same radiance) plus 2·10⁻⁴ of it (the
/// observer's 1 nm table against the quadrature).
#[test]
fn a_camera_sees_a_fluorescent_layer_glow_with_the_light_it_absorbs() {
    let (a, q, half) = (0.6, 0.7, 10.0f64);
    let text = format!(
        "[render]\nspp = 64\n\
         [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\nfov_y_deg = 20\n\
         width = 32\nheight = 32\n{}",
        ink_square(a, q, half)
    );
    let (scene, settings) = parse_scene(Path::new("ink.toml"), text).unwrap();
    let colour = line_colour();
    let absorbed = a * over_line(400.0, 2.0, 360.0, 830.0, |nm| nm);
    let expected = colour.map(|k| q * k * absorbed / std::f64::consts::PI);
    every_integrator_sees(&scene, &settings, &expected, 2e-4);
}

/// The fluorescent Cornell box (`scenes/cornell_fluorescent.toml`: a brightened paper on the
/// back wall and a highlighter's ink on the box, under the ceiling's white light and a 405 nm
/// lamp) at 64 × 64: the photon mapper's render agrees with the path tracer's. Both go on
/// from a layer by path tracing; the light the layers send to the other walls reaches the
/// photon mapper's final gathers by the global map's photons, which changed their wavelength
/// where a layer emitted them again — the path tracer by its bounces. The image within 1 % and
/// 4 standard errors, every 16 × 16 block's channel within 4 standard errors (each film's
/// `error` layer, from the spread of its 16 passes).
#[test]
fn the_photon_mapper_renders_a_fluorescent_box_as_the_path_tracer_does() {
    the_photon_mapper_renders_as_the_path_tracer_does("scenes/cornell_fluorescent.toml");
}

/// The shipped scene at `path` rendered at 64 × 64 by the path tracer (128 samples a pixel a
/// pass) and the photon mapper (32), 16 passes each: the image within 1 % and 4 standard
/// errors, every 16 × 16 block's channel within 4 standard errors.
fn the_photon_mapper_renders_as_the_path_tracer_does(path: &str) {
    let load = |kind: grinlight::settings::IntegratorKind, spp: u32| {
        let (mut scene, mut settings) = grinlight::scene::load_scene(Path::new(path)).unwrap();
        let camera = scene.camera.as_mut().unwrap();
        (camera.width, camera.height) = (64, 64);
        settings.integrator = kind;
        (settings.spp, settings.passes) = (spp, 16);
        grinlight::render::render(&scene, &settings, &()).unwrap().0
    };
    let pt = load(grinlight::settings::IntegratorKind::Path, 128);
    let pm = load(grinlight::settings::IntegratorKind::PhotonMap, 32);
    let Agreement { ratio, z, worst } = agreement(&pt, &pm, 64, 16);
    println!("{path}: photon mapper / path tracer: image {ratio:.4} (z {z:.2}), worst block z {worst:.2}");
    assert!(
        (ratio - 1.0).abs() < 0.01 && z < 4.0,
        "image {ratio}, z {z}"
    );
    assert!(worst < 4.0, "worst block z {worst}");
}

/// A bad fluorescent layer is an error at the file's line naming the key: a share absorbed
/// above 1 or below 0, nothing absorbed, a yield above 1, a missing emission.
#[test]
fn bad_fluorescent_layers_are_errors_at_their_key() {
    let layer = |excitation: &str, rest: &str| {
        format!(
            "[[material]]\nname = \"ink\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
             fluorescence = {{ excitation = {excitation}{rest} }}\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"ink\"\n\
             [[receiver]]\nname = \"r\"\ncenter = [0, 0, 2]\nsize = [1, 1]\nbins = [1, 1]\n"
        )
    };
    let good = ", emission = { gaussian = [600, 40] }, quantum_yield = 0.5";
    let cases = [
        (
            layer("1.5", good),
            "`excitation`: must be the share of light the layer absorbs, in [0, 1], from 360 to 830 nm",
        ),
        (layer("-0.1", good), "in [0, 1], from 360 to 830 nm, got -0.1"),
        (layer("0", good), "it absorbs nothing"),
        (
            layer(
                "0.5",
                ", emission = { gaussian = [600, 40] }, quantum_yield = 2",
            ),
            "`quantum_yield`: photons emitted per photon absorbed",
        ),
        (
            layer("0.5", ", quantum_yield = 0.5"),
            "`emission`: is missing",
        ),
    ];
    for (text, expected) in cases {
        let err = parse_scene(Path::new("ink.toml"), text.clone())
            .err()
            .unwrap_or_else(|| panic!("{text}: accepted"))
            .to_string();
        assert!(err.starts_with("ink.toml:5:"), "{err}");
        assert!(err.contains(expected), "{err}");
    }
}

/// The dyed Cornell box (`scenes/cornell_dyed.toml`: a block of fluorescent acrylic, n = 1.49,
/// under the ceiling's white light and a 405 nm panel) at 64 × 64: the photon mapper's render
/// agrees with the path tracer's. Both path trace the light the dye absorbs from points along
/// every camera-side ray through the block; the dye's light reaches the walls the photon
/// mapper's final gathers read by the global map's photons, emitted again where the dye
/// absorbed them — the path tracer's by its bounces. The image within 1 % and 4 standard
/// errors, every 16 × 16 block's channel within 4 standard errors (each film's `error` layer,
/// from the spread of its 16 passes).
#[test]
fn the_photon_mapper_renders_a_dyed_block_as_the_path_tracer_does() {
    the_photon_mapper_renders_as_the_path_tracer_does("scenes/cornell_dyed.toml");
}

/// E₃(x) = ∫₀¹ μ·e^(−x/μ) dμ, the third exponential integral (10⁴-point midpoint sum).
fn e3(x: f64) -> f64 {
    let steps = 10_000;
    (0..steps)
        .map(|k| {
            let mu = (k as f64 + 0.5) / steps as f64;
            mu * (-x / mu).exp()
        })
        .sum::<f64>()
        / steps as f64
}

/// A dyed slab (thickness d = 0.5, 100 wide) of index 1 under a uniform white sky (radiance
/// L(λ): D65 of unit colour), seen from below by a camera of 1° field (16 × 16 pixels): its
/// dye absorbs σf(λ) = 2 per unit below 480 nm, nothing above 500, and emits a Gaussian line
/// at 600 nm (FWHM 40, nothing re-absorbed) with yield 0.7. Inside, the sky's light averaged
/// over the sphere at depth z is L·(E₂(σf z) + E₂(σf (d − z)))/2, so the dye's radiance seen
/// across the slab is q·ε(λ′)/λ′·∫ λ·L(λ)·(1/2 − E₃(σf(λ)·d)) dλ, and the sky shows through
/// it as L(λ′)·e^(−σf(λ′)·d): per sRGB channel ∫ r̄(λ′)·(both) dλ′ by 0.1 nm sums (σf read
/// from the scene's own table). Checked, both integrators, for the slab as a uniform medium
/// (its faces index-matched: no surface) and as a gradient medium n = 1 + 10⁻⁹·y, whose rays
/// are curved stretches (the dye's points found by marching them again, its light sampled
/// through faces that are specular surfaces), both integrators (the same estimate here) —
/// within 4 standard errors of the pixels' spread
/// plus 5·10⁻⁴ of it (the observer's 1 nm tables against the 0.1 nm quadrature, the rays'
/// obliquity 7.5·10⁻⁵, the slab's finite width e^(−100)).
#[test]
fn a_dyed_slab_glows_under_a_uniform_sky_uniform_or_graded() {
    let (q, d) = (0.7, 0.5f64);
    let sky = |nm: f64| grinlight::spectrum::colour::illuminant(grinlight::color::Rgb::ONE, nm);
    for profile in [
        "profile = \"uniform\"\nn = 1",
        "profile = \"linear\"\nn0 = 1\ngradient = [0, 1e-9, 0]",
    ] {
        let text = format!(
            "[render]\nspp = 2048\n\
             [camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\nfov_y_deg = 1\n\
             width = 16\nheight = 16\n\
             [[medium]]\nname = \"dyed\"\n{profile}\n\
             fluorescence = {{ absorption = {{ table = [[360, 2], [480, 2], [500, 0], [830, 0]] }}, \
             emission = {{ gaussian = [600, 40] }}, quantum_yield = {q} }}\n\
             [[material]]\nname = \"slab\"\ntype = \"dielectric\"\ninterior = \"dyed\"\n\
             [[shape]]\ntype = \"box\"\nmin = [-50, -50, 0]\nmax = [50, 50, {d}]\nmaterial = \"slab\"\n\
             [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n"
        );
        let (scene, settings) = parse_scene(Path::new("dyed_slab.toml"), text).unwrap();
        let dye = scene
            .media()
            .fluorescence(grinlight::ids::MediumId::new(0))
            .unwrap();
        let h = 0.1;
        let nms = || (0..4700).map(|k| 360.0 + h * (k as f64 + 0.5));
        let absorbed: f64 = nms()
            .map(|nm| nm * sky(nm) * (0.5 - e3(dye.sigma(nm) * d)) * h)
            .sum();
        let line = |nm: f64| {
            let sigma = 40.0 / (8.0 * std::f64::consts::LN_2).sqrt();
            (-0.5 * ((nm - 600.0) / sigma).powi(2)).exp() / (sigma * std::f64::consts::TAU.sqrt())
        };
        let expected: [f64; 3] = std::array::from_fn(|c| {
            nms()
                .map(|nm| {
                    let seen = sky(nm) * (-dye.sigma(nm) * d).exp() + q * line(nm) / nm * absorbed;
                    grinlight::spectrum::colour::sensor(nm).0[c] * seen * h
                })
                .sum()
        });
        println!("{profile:?}");
        every_integrator_sees(&scene, &settings, &expected, 5e-4);
    }
}

/// A camera view of a dye lit by a point, spot, LED, goniometric or parallel light warns that
/// the light such a source sends into the dye through a refracting surface is not in the
/// image (no sample of either integrator finds it); lit by area lights alone, it does not.
#[test]
fn a_dye_lit_by_a_point_light_warns_that_images_miss_its_light_through_surfaces() {
    let scene = |light: &str| {
        let text = format!(
            "[camera]\nposition = [0, 0, -5]\nlook_at = [0, 0, 0]\nfov_y_deg = 30\nwidth = 8\nheight = 8\n\
             [[medium]]\nname = \"dyed\"\nprofile = \"uniform\"\nn = 1.5\n\
             fluorescence = {{ absorption = 1, emission = {{ gaussian = [600, 40] }}, quantum_yield = 0.5 }}\n\
             [[material]]\nname = \"glass\"\ntype = \"dielectric\"\ninterior = \"dyed\"\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"glass\"\n{light}"
        );
        parse_scene(Path::new("dyed.toml"), text).unwrap().0
    };
    let point = scene("[[light]]\ntype = \"point\"\nposition = [0, 3, 0]\nintensity = 1\n");
    let warning = grinlight::render::dye_light_warning(&point).expect("a warning");
    assert!(warning.contains("medium 'dyed' holds a dye"), "{warning}");
    assert!(warning.contains("through a refracting"), "{warning}");
    let area = scene(
        "[[light]]\ntype = \"quad\"\nvertices = [[-1, 3, -1], [1, 3, -1], [1, 3, 1], [-1, 3, 1]]\nradiance = 1\n",
    );
    assert_eq!(grinlight::render::dye_light_warning(&area), None);
}

/// K = ∫ r̄(λ′)·ε(λ′)/λ′ dλ′ per sRGB channel for the Gaussian line at 600 nm (FWHM 40): the
/// line's colour per unit of λ′'s energy (0.01 nm sums, [`over_line`]).
fn line_colour() -> [f64; 3] {
    std::array::from_fn(|c| {
        over_line(600.0, 40.0, 360.0, 830.0, |nm| {
            grinlight::spectrum::colour::sensor(nm).0[c] / nm
        })
    })
}

/// Renders `scene` with every integrator and checks the mean of its beauty per channel against
/// `expected`: within 4 standard errors of the pixels' spread (each pixel an independent
/// estimate of the same radiance) plus `slack` of it.
fn every_integrator_sees(
    scene: &grinlight::scene::Scene,
    settings: &grinlight::settings::Settings,
    expected: &[f64; 3],
    slack: f64,
) {
    for integrator in grinlight::settings::IntegratorKind::ALL {
        let settings = grinlight::settings::Settings {
            integrator,
            ..settings.clone()
        };
        let film = grinlight::render::render(scene, &settings, &()).unwrap().0;
        let beauty = film.layer("beauty").unwrap();
        let n = beauty.len() as f64;
        for (c, &want) in expected.iter().enumerate() {
            let values: Vec<f64> = beauty.iter().map(|p| f64::from(p[c])).collect();
            let mean = values.iter().sum::<f64>() / n;
            let sd =
                (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
            println!("{integrator:?} channel {c}: {mean:.6} ± {sd:.6} against {want:.6}");
            assert!(
                (mean - want).abs() < 4.0 * sd + slack * want.abs(),
                "{integrator:?} channel {c}: {mean} ± {sd} against {want}"
            );
        }
    }
}
