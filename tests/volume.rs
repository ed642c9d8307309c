//! Scattering media against exact results: the phase functions' normalisation and sampling;
//! a closed box of emitting walls filled with a conservative scattering medium (a white
//! furnace: the radiance everywhere is the walls' times n²), straight and in a Luneburg
//! index field, grey and coloured; and the light a semi-infinite isotropic medium reflects,
//! against Chandrasekhar's H-function.

use crate::common;

use glam::DVec3;
use grinlight::photon::{shoot, Batch, Photons, Sources};
use grinlight::scene::load::parse_scene;
use grinlight::settings::{IntegratorKind, Settings};
use grinlight::transport::Tracer;
use grinlight::volume::Phase;
use std::f64::consts::PI;
use std::path::Path;

/// The phase functions a medium may have, Henyey–Greenstein near and at its limits.
fn phases() -> Vec<Phase> {
    let mut p = vec![Phase::Isotropic, Phase::Rayleigh];
    for g in [-0.9, -0.3, 1e-9, 0.5, 0.95] {
        p.push(Phase::HenyeyGreenstein { g });
    }
    p
}

/// ∫ p dω = 2π ∫ p(μ) dμ = 1, by Gauss–Legendre quadrature in μ on [−1, 1] split at the
/// forward peak's scale (1e-9 relative); and Henyey–Greenstein's mean cosine is g (1e-9),
/// Rayleigh's 0, and its mean squared cosine 2/5 (∫ μ² · 3(1 + μ²)/8 dμ); Rayleigh's is its
/// Mueller matrix's first element (1e-15).
#[test]
fn phase_functions_are_normalised() {
    for phase in phases() {
        let (norm, mean) = common::quadrature::integrate_mu(|mu| {
            let p = 2.0 * PI * phase.eval(mu);
            (p, p * mu)
        });
        assert!((norm - 1.0).abs() < 1e-9, "{phase:?}: ∫p dω = {norm}");
        let g = match phase {
            Phase::Isotropic | Phase::Rayleigh => 0.0,
            Phase::HenyeyGreenstein { g } => g,
        };
        assert!((mean - g).abs() < 1e-9, "{phase:?}: mean cosine {mean}");
        if phase == Phase::Rayleigh {
            let (square, _) =
                common::quadrature::integrate_mu(|mu| (2.0 * PI * phase.eval(mu) * mu * mu, 0.0));
            assert!(
                (square - 0.4).abs() < 1e-9,
                "Rayleigh: mean squared cosine {square}"
            );
            for mu in [-1.0, -0.3, 0.0, 0.7, 1.0] {
                let m00 = grinlight::polarization::mueller::rayleigh(mu).col(0).x;
                assert!(
                    (m00 - phase.eval(mu)).abs() < 1e-15,
                    "Rayleigh: M00 {m00} at {mu}"
                );
            }
        }
    }
}

/// Directions drawn by [`Phase::sample`] are distributed as [`Phase::between`] says (χ² at
/// significance 1e-4), about a travel direction off every axis.
#[test]
fn phase_sampling_follows_its_density() {
    let before = DVec3::new(0.3, -0.5, 0.8).normalize();
    for phase in phases() {
        common::chi2::chi2(
            &format!("{phase:?}"),
            |rng| {
                use rand::Rng;
                Some(phase.sample(before, (rng.gen(), rng.gen())))
            },
            |after| phase.between(before, after),
        );
    }
}

/// Six quad lights of radiance `l` facing into the box [−1, 1]³.
fn emitting_box(l: f64) -> String {
    let faces = [
        "[[-1, -1, -1], [-1, 1, -1], [-1, 1, 1], [-1, -1, 1]]",
        "[[1, -1, -1], [1, -1, 1], [1, 1, 1], [1, 1, -1]]",
        "[[-1, -1, -1], [-1, -1, 1], [1, -1, 1], [1, -1, -1]]",
        "[[-1, 1, -1], [1, 1, -1], [1, 1, 1], [-1, 1, 1]]",
        "[[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1]]",
        "[[-1, -1, 1], [-1, 1, 1], [1, 1, 1], [1, -1, 1]]",
    ];
    faces
        .iter()
        .map(|v| {
            format!("[[light]]\ntype = \"quad\"\nradiance = [{l}, {l}, {l}]\nvertices = {v}\n")
        })
        .collect()
}

/// The mean of each channel of the beauty layer of `text` rendered by both integrators, with
/// its standard error over pixels.
fn furnace(text: &str) -> Vec<(IntegratorKind, [f64; 3], [f64; 3])> {
    let (scene, settings) = parse_scene(Path::new("furnace.toml"), text.to_string()).unwrap();
    [IntegratorKind::Path, IntegratorKind::PhotonMap]
        .into_iter()
        .map(|integrator| {
            let settings = Settings {
                integrator,
                ..settings.clone()
            };
            let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
            let beauty = film.layer("beauty").unwrap();
            let n = beauty.len() as f64;
            let mean: [f64; 3] =
                std::array::from_fn(|c| beauty.iter().map(|p| p[c] as f64).sum::<f64>() / n);
            let error: [f64; 3] = std::array::from_fn(|c| {
                let var = beauty
                    .iter()
                    .map(|p| (p[c] as f64 - mean[c]).powi(2))
                    .sum::<f64>();
                (var / (n * n)).sqrt()
            });
            (integrator, mean, error)
        })
        .collect()
}

/// A density lattice over the furnace, 21 nodes a side, rough (every node its own value, a
/// quarter of them 0: empty pockets, steep walls; drawn from a fixed seed; 20 cells a side,
/// so free flights are drawn under local majorants of 3³ blocks): the `density_*` keys of a
/// `[[medium]]` table.
fn rough_density() -> String {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(17);
    let values: Vec<String> = (0..21 * 21 * 21)
        .map(|_| match rng.gen::<f64>() {
            u if u < 0.25 => "0".to_string(),
            _ => format!("{:.3}", rng.gen::<f64>() * 2.0),
        })
        .collect();
    format!(
        "density_bounds = [[-1, -1, -1], [1, 1, 1]]\ndensity_dims = [21, 21, 21]\n\
         density_values = [{}]",
        values.join(", ")
    )
}

/// A camera in a closed box of walls emitting radiance 1, filled with a conservative
/// scattering medium (no absorption), sees radiance n² everywhere: 1 in a uniform medium of
/// n = 1 — with forward Henyey–Greenstein scattering, and with σs coloured (each channel its
/// own free flights: (0.3, 1, 3)), and over wavelength (Rayleigh's λ⁻⁴: every path at a hero
/// wavelength) — and 2 at the centre of a Luneburg index field
/// (n = √2 there), whose rays curve between scattering events — with isotropic and with
/// Rayleigh scattering. So too where a rough density
/// scales σs (free flights by delta tracking, shadow rays by the density's column; grey in a
/// uniform index, coloured in the Luneburg field). Both integrators; within four standard
/// errors of the pixel mean (0.5–1 % at these sample counts).
#[test]
fn a_scattering_furnace_shows_the_walls_radiance_times_n_squared() {
    let camera = "[camera]\nposition = [0, 0, 0]\nlook_at = [0.2, 0.1, -1]\nfov_y_deg = 60\n\
                  width = 12\nheight = 12\n[render]\nspp = 256\n";
    let cases = [
        (
            "profile = \"uniform\"\nn = 1\nscattering = 1\nphase = { hg = 0.6 }",
            1.0,
        ),
        (
            "profile = \"uniform\"\nn = 1\nscattering = [0.3, 1, 3]",
            1.0,
        ),
        (
            "profile = \"uniform\"\nn = 1\nscattering = { angstrom = [1, 550, 4] }",
            1.0,
        ),
        ("profile = \"luneburg\"\nradius = 0.9\nscattering = 1", 2.0),
        (
            "profile = \"luneburg\"\nradius = 0.9\nscattering = 1\nphase = \"rayleigh\"",
            2.0,
        ),
        (
            &format!(
                "profile = \"uniform\"\nn = 1\nscattering = 3\n{}",
                rough_density()
            ),
            1.0,
        ),
        (
            &format!(
                "profile = \"luneburg\"\nradius = 0.9\nscattering = [1, 2, 4]\n{}",
                rough_density()
            ),
            2.0,
        ),
    ];
    for (medium, expected) in cases {
        let text = format!(
            "ambient = \"fog\"\n{camera}[[medium]]\nname = \"fog\"\n{medium}\n{}",
            emitting_box(1.0)
        );
        for (integrator, mean, error) in furnace(&text) {
            let label = medium.split("\ndensity_values").next().unwrap_or(medium);
            println!("{label:?} {integrator:?}: {mean:?} ± {error:?} against {expected}");
            for (m, e) in mean.iter().zip(error) {
                assert!(
                    (m - expected).abs() < 4.0 * e,
                    "{label} with {integrator:?}: {mean:?} ± {error:?} against {expected}"
                );
            }
        }
    }
}

/// H(μ) of isotropic scattering of single-scattering albedo `albedo` (Chandrasekhar 1960,
/// ch. V): iterated on 1/H(μ) = √(1 − ϖ) + (ϖ/2) ∫₀¹ μ' H(μ') / (μ + μ') dμ' over 48
/// Gauss–Legendre nodes in μ', averaging each iterate with the last (the map sends a scaled H
/// to its reciprocal scale, so undamped it oscillates for ϖ = 1), evaluated at `mu`.
fn chandrasekhar_h(albedo: f64, mu: f64) -> f64 {
    let (nodes, weights) = common::quadrature::gauss_legendre_unit(48);
    let mut h = vec![1.0; nodes.len()];
    let at = |h: &[f64], x: f64| {
        let integral: f64 = nodes
            .iter()
            .zip(&weights)
            .zip(h)
            .map(|((m, w), hm)| w * m * hm / (x + m))
            .sum();
        1.0 / ((1.0 - albedo).sqrt() + 0.5 * albedo * integral)
    };
    for _ in 0..10_000 {
        let next: Vec<f64> = nodes
            .iter()
            .zip(&h)
            .map(|(&x, old)| 0.5 * (old + at(&h, x)))
            .collect();
        let change = next
            .iter()
            .zip(&h)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        h = next;
        if change < 1e-15 {
            break;
        }
    }
    at(&h, mu)
}

/// The H-function against Chandrasekhar's table for conservative isotropic scattering:
/// H(1) = 2.90781, H(0.5) = 2.01278, H(0) = 1 (Chandrasekhar 1960, table XI).
#[test]
fn the_h_function_matches_chandrasekhars_table() {
    for (mu, h) in [(1.0, 2.90781), (0.5, 2.01278), (0.0, 1.0)] {
        let got = chandrasekhar_h(1.0, mu);
        assert!((got - h).abs() < 2e-4, "H({mu}) = {got}, table {h}");
    }
}

/// A narrow beam falls straight down onto a thick slab (2000 × 200 × 2000 mean free paths)
/// of an isotropically scattering medium of albedo ϖ, bounded by an index-matched interface:
/// the power that leaves through its top face is the half-space's reflectance
/// R = 1 − √(1 − ϖ) H(1), within 0.5 % (the photon count's standard error is below 0.2 %).
#[test]
fn a_half_space_reflects_as_chandrasekhar_says() {
    for albedo in [0.5f64, 0.9, 0.99] {
        let sigma_a = (1.0 - albedo) / albedo;
        let text = format!(
            "[render]\nmax_depth = 100000000\n\
             [[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\n\
             absorption = {sigma_a}\n\
             [[material]]\nname = \"skin\"\ntype = \"dielectric\"\ninterior = \"fog\"\n\
             [[shape]]\ntype = \"box\"\nmin = [-1000, -200, -1000]\nmax = [1000, 0, 1000]\n\
             material = \"skin\"\ninterior = \"fog\"\n\
             [[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n\
             intensity = 1\ncone_deg = 0.5\n"
        );
        let (scene, settings) = parse_scene(Path::new("slab.toml"), text).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        let sources = Sources::new(&tracer);
        let count = 400_000;
        let photons = Photons::all(Batch::Receivers, 5, 0, count);
        let (sink, _) = shoot(&tracer, &sources, photons, &|| false);
        let budget = sink.budget.statement(1.0);
        let top = scene
            .accel
            .primitives()
            .iter()
            .position(|p| {
                let grinlight::math::Bounds3 { lo, hi } = p.bounds();
                lo.y > -1.0 && hi.y > -1.0
            })
            .unwrap();
        let reflected = budget.out_through.get(&top).copied().unwrap_or(0.0) / budget.emitted;
        let expected = 1.0 - (1.0 - albedo).sqrt() * chandrasekhar_h(albedo, 1.0);
        println!(
            "ϖ = {albedo}: reflected {reflected:.5}, H-function {expected:.5}, lost {:.2e}",
            budget.lost / budget.emitted
        );
        assert!(
            (reflected / expected - 1.0).abs() < 5e-3,
            "ϖ = {albedo}: reflected {reflected}, expected {expected}"
        );
    }
}

/// Extreme coefficients stay finite and bounded: a fog of σs = 10⁶ (a path scatters at every
/// micrometre and is cut at `max_depth`) and one of σs = 10⁻¹² (practically none), each with
/// σa alike, render every pixel finite and non-negative, the thin one showing the walls.
#[test]
fn extreme_scattering_coefficients_stay_finite() {
    for sigma in [1e6, 1e-12] {
        let text = format!(
            "ambient = \"fog\"\n[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\n\
             fov_y_deg = 60\nwidth = 8\nheight = 8\n[render]\nspp = 4\n\
             [[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\nscattering = {sigma}\n\
             absorption = {sigma}\n{}",
            emitting_box(1.0)
        );
        for (integrator, mean, _) in furnace(&text) {
            assert!(
                mean.iter().all(|m| m.is_finite() && *m >= 0.0),
                "σ = {sigma:e} with {integrator:?}: {mean:?}"
            );
            if sigma < 1.0 {
                assert!((mean[0] - 1.0).abs() < 1e-6, "σ = {sigma:e}: {mean:?}");
            }
        }
    }
}

/// A glass ball in a fog-filled box under a small area light focuses a cone of light in the
/// fog (a volume caustic): the photon mapper — volume caustic photons read where camera paths
/// scatter, light scattered on its way to a surface in the caustic map — against the path
/// tracer, which finds the cone by sampling the phase function through the ball to the
/// light (a broad one: through a small light its estimate is heavy-tailed). Image mean within
/// 1.5 % and the strip under the ball within 4 %: the path tracer's spread over four seeds
/// at 256 passes is ±0.3 % (image) and ±1.3 % (strip), and the photon mapper's 16 passes read
/// −0.2 % and +0.4 % from their mean.
#[test]
fn the_photon_mapper_renders_a_volume_caustic_as_the_path_tracer_does() {
    let text = "ambient = \"fog\"\n[camera]\nposition = [0, 1, 3.4]\nlook_at = [0, 0.9, 0]\n\
                fov_y_deg = 40\nwidth = 16\nheight = 16\n\
                [render]\nspp = 16\ncaustic_photons = 100000\nphotons = 100000\ngather = 4\n\
                [[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\nscattering = 0.15\n\
                phase = { hg = 0.3 }\n\
                [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.7, 0.7, 0.7]\n\
                [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\
                [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                vertices = [[-1.5, 0, -1.5], [-1.5, 0, 1.5], [1.5, 0, 1.5], [1.5, 0, -1.5]]\n\
                [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                vertices = [[-1.5, 0, -1.5], [1.5, 0, -1.5], [1.5, 3, -1.5], [-1.5, 3, -1.5]]\n\
                [[shape]]\ntype = \"sphere\"\ncenter = [0, 1.5, 0]\nradius = 0.45\n\
                material = \"glass\"\n\
                [[light]]\ntype = \"quad\"\nradiance = [5.4, 5.4, 5.4]\n\
                vertices = [[-0.5, 2.8, -0.5], [0.5, 2.8, -0.5], [0.5, 2.8, 0.5], \
                [-0.5, 2.8, 0.5]]\n";
    let (scene, settings) = parse_scene(Path::new("cone.toml"), text.to_string()).unwrap();
    let render = |integrator, passes| {
        let settings = Settings {
            integrator,
            passes,
            ..settings.clone()
        };
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        film.layer("beauty").unwrap()
    };
    let reference = render(IntegratorKind::Path, 512);
    let photon_map = render(IntegratorKind::PhotonMap, 16);
    let mean = |image: &[[f32; 3]], keep: &dyn Fn(usize, usize) -> bool| {
        let (mut sum, mut n) = (0.0, 0);
        for (i, p) in image.iter().enumerate() {
            if keep(i % 16, i / 16) {
                sum += p[0] as f64;
                n += 1;
            }
        }
        sum / n as f64
    };
    let whole = |_: usize, _: usize| true;
    let cone = |x: usize, y: usize| (6..10).contains(&x) && y >= 8;
    let ratio = mean(&photon_map, &whole) / mean(&reference, &whole);
    let in_cone = mean(&photon_map, &cone) / mean(&reference, &cone);
    println!("photon map / path tracer: image {ratio:.4}, under the ball {in_cone:.4}");
    assert!((ratio - 1.0).abs() < 0.015, "image {ratio}");
    assert!((in_cone - 1.0).abs() < 0.04, "under the ball {in_cone}");
}

/// Slabs of optical depth τ = 1 and 4 (albedo 0.9, isotropic, index-matched faces) under a
/// narrow normal beam: the power out through the top (R) and the bottom (T) against an
/// independent plane-parallel random walk written here (exponential free paths in optical
/// depth, isotropic directions; 1.6·10⁷ walks) with 4·10⁶ photons, within four combined
/// standard errors (0.2–0.6 % of R and T); and the slab of the same optical depth whose
/// density ramps across it (10⁶ photons, 0.3–1.1 %): R and T depend on optical depth alone.
#[test]
fn slabs_reflect_and_transmit_as_a_plane_parallel_random_walk() {
    use rand::{Rng, SeedableRng};
    let albedo = 0.9f64;
    for tau in [1.0f64, 4.0] {
        // The reference: depth z in optical units, direction cosine μ (down is +).
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let walks = 16_000_000;
        let (mut r, mut t) = (0u64, 0u64);
        for _ in 0..walks {
            let (mut z, mut mu) = (0.0f64, 1.0f64);
            loop {
                z += mu * -(1.0 - rng.gen::<f64>()).ln();
                if z < 0.0 {
                    r += 1;
                    break;
                }
                if z > tau {
                    t += 1;
                    break;
                }
                if rng.gen::<f64>() >= albedo {
                    break;
                }
                mu = 2.0 * rng.gen::<f64>() - 1.0;
            }
        }
        let share = |n: u64| n as f64 / walks as f64;
        let (r_ref, t_ref) = (share(r), share(t));
        // grinlight: σs = 1 and σa = (1 − ϖ)/ϖ, so σt = 1/ϖ and the thickness is ϖτ.
        let sigma_a = (1.0 - albedo) / albedo;
        let depth = albedo * tau;
        // The same slab, homogeneous, and with a density falling linearly from 1.75 at the
        // bottom to 0.25 at the top (mean 1): a plane-parallel medium's R and T depend on its
        // optical depth alone, and the density scales σa with σs, so ϖ stays 0.9. The ramp
        // has 41 nodes in depth (5 blocks of cells): free flights under local majorants.
        let values: Vec<String> = (0..2 * 41 * 2)
            .map(|i| format!("{}", 1.75 - 1.5 * ((i / 2) % 41) as f64 / 40.0))
            .collect();
        let ramp = format!(
            "density_bounds = [[-1000, -{depth}, -1000], [1000, 0, 1000]]\n\
             density_dims = [2, 41, 2]\n\
             density_values = [{}]\n",
            values.join(", ")
        );
        for (slab, density, count) in [
            ("homogeneous", "", 4_000_000),
            ("ramp", ramp.as_str(), 1_000_000),
        ] {
            let text = format!(
                "[render]\nmax_depth = 100000000\n\
                 [[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\n\
                 absorption = {sigma_a}\n{density}\
                 [[material]]\nname = \"skin\"\ntype = \"dielectric\"\ninterior = \"fog\"\n\
                 [[shape]]\ntype = \"box\"\nmin = [-1000, -{depth}, -1000]\n\
                 max = [1000, 0, 1000]\nmaterial = \"skin\"\ninterior = \"fog\"\n\
                 [[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n\
                 intensity = 1\ncone_deg = 0.5\n"
            );
            let (scene, settings) = parse_scene(Path::new("slab.toml"), text).unwrap();
            let tracer = Tracer::new(&scene, &settings.trace);
            let photons = Photons::all(Batch::Receivers, 5, 0, count);
            let (sink, _) = shoot(&tracer, &Sources::new(&tracer), photons, &|| false);
            let budget = sink.budget.statement(1.0);
            // The share of the power emitted that left `part` of the budget through the face
            // at height `face_y`.
            let through = |part: &grinlight::photon::Budget, face_y: f64| {
                let prim = scene.accel.primitives().iter().position(|p| {
                    let grinlight::math::Bounds3 { lo, hi } = p.bounds();
                    (lo.y - face_y).abs() < 1e-9 && (hi.y - face_y).abs() < 1e-9
                });
                prim.and_then(|p| part.out_through.get(&p).copied())
                    .unwrap_or(0.0)
                    / budget.emitted
            };
            let (r_got, t_got) = (through(&budget, 0.0), through(&budget, -depth));
            for (name, got, reference) in [("R", r_got, r_ref), ("T", t_got, t_ref)] {
                let se = (got * (1.0 - got) / count as f64
                    + reference * (1.0 - reference) / walks as f64)
                    .sqrt();
                println!(
                    "τ = {tau}, {slab}: {name} {got:.5} against {reference:.5} \
                     ({:+.2} %, 4σ = {:.2} %)",
                    100.0 * (got / reference - 1.0),
                    400.0 * se / reference
                );
                assert!(
                    (got - reference).abs() < 4.0 * se,
                    "τ = {tau}, {slab}: {name} {got} against {reference} ± {se}"
                );
            }
            // The energy budget: what neither face let out was absorbed in the fog (medium
            // 0), against the walk's 1 − R − T; a photon scatters at least once with
            // probability ϖ(1 − e^{−τ}) (its first collision within the slab is a scattering),
            // and those that did not either went straight through (e^{−τ}) or were absorbed.
            assert!((budget.booked() - budget.emitted).abs() < 1e-9 * budget.emitted);
            assert_eq!((budget.absorbed, budget.lost), (0.0, 0.0));
            let scattered = budget.scattered.as_deref().expect("the fog scattered");
            assert!((scattered.booked() - scattered.emitted).abs() < 1e-9 * scattered.emitted);
            let straight_through = t_got - through(scattered, -depth);
            let unscattered = (-tau).exp();
            for (name, got, want, walked) in [
                (
                    "absorbed",
                    budget.absorbed_in[&0] / budget.emitted,
                    1.0 - share(r) - share(t),
                    true,
                ),
                (
                    "scattered",
                    scattered.emitted / budget.emitted,
                    albedo * (1.0 - unscattered),
                    false,
                ),
                ("straight through", straight_through, unscattered, false),
            ] {
                let mut var = got * (1.0 - got) / count as f64;
                if walked {
                    var += want * (1.0 - want) / walks as f64;
                }
                let se = var.sqrt();
                println!("τ = {tau}, {slab}: {name} {got:.5} against {want:.5} ± {se:.5}");
                assert!(
                    (got - want).abs() < 4.0 * se,
                    "τ = {tau}, {slab}: {name} {got} against {want} ± {se}"
                );
            }
        }
    }
}

/// A slab of Rayleigh scatterers, σs = (550/λ)⁴ per unit length, lit at normal incidence by
/// narrow lines at 450 and 650 nm: the share of photons crossing it unscattered is
/// exp(−σs(λ) d) at each line's own wavelength (0.328 and 0.774 for d = 0.5), not at the
/// wavelength RGB paths see (587.6 nm: 0.681). 400 000 photons a line, within four binomial
/// standard errors (0.3 %).
#[test]
fn a_scattering_coefficient_over_wavelength_acts_at_each_wavelength() {
    let depth = 0.5;
    for line in [450.0f64, 650.0] {
        let text = format!(
            "[render]\nmax_depth = 100000\n\
             [[medium]]\nname = \"haze\"\nprofile = \"uniform\"\nn = 1\n\
             scattering = {{ angstrom = [1, 550, 4] }}\n\
             [[material]]\nname = \"skin\"\ntype = \"dielectric\"\ninterior = \"haze\"\n\
             [[shape]]\ntype = \"box\"\nmin = [-1000, -{depth}, -1000]\n\
             max = [1000, 0, 1000]\nmaterial = \"skin\"\ninterior = \"haze\"\n\
             [[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n\
             intensity = 1\ncone_deg = 0.5\nspectrum = {{ gaussian = [{line}, 0.01] }}\n"
        );
        let (scene, settings) = parse_scene(Path::new("rayleigh.toml"), text).unwrap();
        assert!(
            scene.is_dispersive(),
            "σs over wavelength makes paths spectral"
        );
        let tracer = Tracer::new(&scene, &settings.trace);
        let count = 400_000;
        let photons = Photons::all(Batch::Receivers, 5, 0, count);
        let (sink, _) = shoot(&tracer, &Sources::new(&tracer), photons, &|| false);
        let budget = sink.budget.statement(1.0);
        let bottom = scene
            .accel
            .primitives()
            .iter()
            .position(|p| {
                let grinlight::math::Bounds3 { lo, hi } = p.bounds();
                (lo.y + depth).abs() < 1e-9 && (hi.y + depth).abs() < 1e-9
            })
            .expect("the slab's bottom face");
        let out = |part: &grinlight::photon::Budget| {
            part.out_through.get(&bottom).copied().unwrap_or(0.0) / budget.emitted
        };
        let scattered = budget.scattered.as_deref().expect("the haze scattered");
        let got = out(&budget) - out(scattered);
        let want = (-(550.0 / line).powi(4) * depth).exp();
        let se = (want * (1.0 - want) / count as f64).sqrt();
        println!("{line} nm: unscattered {got:.5} against {want:.5} ± {se:.5}");
        assert!(
            (got - want).abs() < 4.0 * se,
            "{line} nm: unscattered {got} against {want} ± {se}"
        );
    }
}

/// A camera in an open conservative fog under a uniform sky of radiance 1 (no lights, the
/// fog filling the world sphere) sees 1 everywhere: the sky's single scattering is found by
/// the phase sample at each scattering point, multiple scattering by the paths that go on.
/// Isotropic and Rayleigh scattering, both integrators, within four standard errors of the
/// pixel mean.
#[test]
fn a_fog_under_a_uniform_sky_shows_the_sky() {
    for phase in ["\"isotropic\"", "\"rayleigh\""] {
        let text = format!(
            "ambient = \"fog\"\n[camera]\nposition = [0, 0, 0]\nlook_at = [0.2, 0.1, -1]\n\
             fov_y_deg = 60\nwidth = 12\nheight = 12\n[render]\nspp = 256\nworld_radius = 2\n\
             [[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\n\
             phase = {phase}\n[[light]]\ntype = \"environment\"\nsky = \"uniform\"\n"
        );
        for (integrator, mean, error) in furnace(&text) {
            println!("sky, {phase}: {integrator:?}: {mean:?} ± {error:?}");
            for (m, e) in mean.iter().zip(error) {
                assert!(
                    (m - 1.0).abs() < 4.0 * e.max(1e-3),
                    "{phase}, {integrator:?}: {mean:?} ± {error:?} against 1"
                );
            }
        }
    }
}

/// The energy budget closes over coloured surfaces: a spot light onto a floor of albedo
/// (0.9, 0.1, 0.1) (RGB photons: receivers without bands), every photon booked exactly once —
/// emitted equals the sum of the fates to rounding (1e-12) — and the floor absorbs
/// 1 − 0.3667 of the light, within 4 standard errors (the photons' escapes are Bernoulli
/// draws of the mean survival 0.9 weighed by the kept channels). Russian roulette keeps a
/// photon by its largest channel; before the loss of its other channels was booked, 9.9 % was
/// booked as absorbed, and the fates added up to 46.6 % of the power emitted.
#[test]
fn the_energy_budget_closes_over_a_coloured_floor() {
    let text = "[[material]]\nname = \"red\"\ntype = \"diffuse\"\nalbedo = [0.9, 0.1, 0.1]\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]\n\
                material = \"red\"\n\
                [[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, -1, 0]\n\
                intensity = [1, 1, 1]\ncone_deg = 20\n\
                [[receiver]]\nname = \"top\"\ncenter = [0, 0.5, 0]\nsize = [0.2, 0.2]\nbins = [2, 2]\n";
    let (scene, settings) = parse_scene(Path::new("budget.toml"), text.to_string()).unwrap();
    let tracer = Tracer::new(&scene, &settings.trace);
    let sources = Sources::new(&tracer);
    let count = 200_000;
    let (sink, _) = shoot(
        &tracer,
        &sources,
        Photons::all(Batch::Receivers, 3, 0, count),
        &|| false,
    );
    let b = sink.budget.statement(1.0);
    let booked = b.missed + b.absorbed + b.reflected + b.lost;
    assert!(
        (booked / b.emitted - 1.0).abs() < 1e-12,
        "booked {booked} of {}",
        b.emitted
    );
    let albedo = [0.9, 0.1, 0.1];
    let mean: f64 = albedo.iter().sum::<f64>() / 3.0;
    // A photon escapes with chance 0.9 carrying mean/0.9 of its power: the absorbed share's
    // variance is 0.9·(1 − 0.9)·(mean/0.9)² a photon.
    let se = (0.9 * 0.1 * (mean / 0.9).powi(2) / count as f64).sqrt();
    let absorbed = b.absorbed / b.emitted;
    println!("absorbed {absorbed:.5} against {:.5} ± {se:.5}", 1.0 - mean);
    assert!(
        (absorbed - (1.0 - mean)).abs() < 4.0 * se,
        "absorbed {absorbed}"
    );
}

/// Light scattered once by a slab under the sun, as each phase function says: a slab of
/// optical depth τ = 0.1 (index-matched, 100 wide) lit by the sun at 30° from its normal,
/// irradiance 1, seen from above along a few directions (a 2° view, straight down and 40° and
/// 60° off it: scattering angles 150°, 131.5°, 90°) with `max_depth` 1 (one scattering, the
/// sun's light at it): L = p(θ)·E·μ0·(1 − e^(−τ(1/μ0 + 1/μ)))/(μ + μ0), μ0 and μ the sun's and
/// the view's cosines with the normal — isotropic, Henyey–Greenstein and Rayleigh scattering,
/// both integrators, within 4 standard errors of the pixel mean plus 0.3 % (the view's width:
/// the closed form's spread over its rays).
#[test]
fn single_scattering_from_a_slab_follows_the_phase_function() {
    let (tau, mu0) = (0.1, f64::to_radians(30.0).cos());
    let sun = DVec3::new(0.5, -mu0, 0.0);
    for (phase_key, phase) in [
        ("\"isotropic\"", Phase::Isotropic),
        ("{ hg = -0.4 }", Phase::HenyeyGreenstein { g: -0.4 }),
        ("\"rayleigh\"", Phase::Rayleigh),
    ] {
        for (alpha, azimuth) in [(0.0f64, 0.0f64), (40.0, 90.0), (60.0, 0.0)] {
            let (a, f) = (alpha.to_radians(), azimuth.to_radians());
            // From the slab's top toward the camera.
            let out = DVec3::new(a.sin() * f.cos(), a.cos(), a.sin() * f.sin());
            let camera = 3.0 * out;
            let text = format!(
                "[camera]\nposition = [{}, {}, {}]\nlook_at = [0, 0, 0]\nup = [0, 0, 1]\n\
                 fov_y_deg = 2\nwidth = 8\nheight = 8\n[render]\nspp = 1024\nmax_depth = 1\n\
                 [[medium]]\nname = \"air\"\nprofile = \"uniform\"\nn = 1\nscattering = {tau}\n\
                 phase = {phase_key}\n\
                 [[material]]\nname = \"skin\"\ntype = \"dielectric\"\ninterior = \"air\"\n\
                 [[shape]]\ntype = \"box\"\nmin = [-50, -1, -50]\nmax = [50, 0, 50]\n\
                 material = \"skin\"\ninterior = \"air\"\n\
                 [[light]]\ntype = \"directional\"\ndirection = [{}, {}, 0]\nirradiance = 1\n",
                camera.x, camera.y, camera.z, sun.x, sun.y
            );
            let mu = out.y;
            let want =
                phase.eval(sun.dot(out)) * mu0 * (1.0 - (-tau * (1.0 / mu0 + 1.0 / mu)).exp())
                    / (mu + mu0);
            for (integrator, mean, error) in furnace(&text) {
                println!(
                    "{phase_key} at {alpha}°/{azimuth}°: {integrator:?} {:.5} ± {:.5} against {want:.5}",
                    mean[0], error[0]
                );
                for (m, e) in mean.iter().zip(error) {
                    assert!(
                        (m - want).abs() < 4.0 * e + 3e-3 * want,
                        "{phase_key} at {alpha}°, {azimuth}°: {integrator:?} {mean:?} ± {error:?} against {want}"
                    );
                }
            }
        }
    }
}
