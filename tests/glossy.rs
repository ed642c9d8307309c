//! Glossy surfaces through the whole renderer: a white furnace of rough perfect conductors
//! against an independent quadrature of GGX's directional albedo, and the photon mapper
//! against the path tracer on a Cornell box of rough metal, frosted glass and plastic walls.

use glam::DVec3;
use grinlight::bsdf::{Bsdf, Microsurface, Reflectance};
use grinlight::color::Rgb;
use grinlight::scene::load::parse_scene;
use grinlight::settings::{IntegratorKind, Settings};
use std::path::Path;

use crate::common::quadrature;

/// The directional albedo E(μ) of single-scattering GGX with F = 1: ∫ f cos θi dωi by a
/// product quadrature over microfacet normals (dωi = 4 (ωo·m) dωm, cos θm = 1 − t²),
/// independent of the renderer's samplers.
fn ggx_albedo(alpha: f64, mu: f64) -> f64 {
    let bsdf = Bsdf::Conductor {
        fresnel: Reflectance::Constant(Rgb::ONE),
        microsurface: Some(Microsurface::ggx(alpha)),
    };
    let wo = DVec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    quadrature::reflected_fraction(1500, 360, wo, |wi| bsdf.eval(wo, wi, DVec3::Z).0.x)
}

/// A sphere of `metal = "perfect"` with roughness α under a uniform white sky, seen from far
/// away (50 radii, so every pixel looks along −z to 1 %): a convex mirror reflects each ray
/// once, so a camera ray shows E(μ) at its μ = cos of the angle between the view and the
/// normal. Over the pixels with μ ≥ 0.95 and those with 0.45 ≤ μ ≤ 0.55 the render's mean
/// equals the mean of E(μ) over the pixels' footprints (8 × 8 points a pixel, as the box
/// filter weighs them), for the photon mapper and the path tracer alike, within four
/// standard errors of the render (its passes' spread) plus 5·10⁻⁵ E for the quadrature and
/// the footprint's points (measured: E(μ) moves by ≤ 6·10⁻⁶ E between 1500 × 360 and
/// 3000 × 720 nodes, the region means by ≤ 1·10⁻⁵ between 8 × 8 and 16 × 16 points). The
/// regions' standard errors are 2–14·10⁻⁵; measured deviations lie within 1.5 of them. The
/// pixel's footprint matters: E at the pixels' centres is 1.2·10⁻³ off at α = 1, μ ≈ 0.5.
#[test]
fn a_rough_perfect_conductor_in_a_white_furnace_reflects_ggx_albedo() {
    let (size, distance) = (48u32, 50.0f64);
    let half_angle = (1.02f64 / distance).atan();
    for alpha in [0.1, 0.25, 0.5, 1.0] {
        let text = format!(
            "[camera]\nposition = [0, 0, {distance}]\nlook_at = [0, 0, 0]\n\
             fov_y_deg = {}\nwidth = {size}\nheight = {size}\n\
             [render]\nspp = 128\npasses = 8\ngather = 0\nphotons = 0\ncaustic_photons = 0\n\
             [[material]]\nname = \"m\"\ntype = \"conductor\"\nmetal = \"perfect\"\n\
             roughness = {alpha}\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n\
             [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n",
            2.0 * half_angle.to_degrees()
        );
        let (scene, settings) = parse_scene(Path::new("furnace.toml"), text).unwrap();
        // μ at a film point (in pixels), from the camera's ray and the unit sphere.
        let eye = DVec3::new(0.0, 0.0, distance);
        let tan = half_angle.tan();
        let mu_at = |fx: f64, fy: f64| -> Option<f64> {
            let x = (2.0 * fx / size as f64 - 1.0) * tan;
            let y = (1.0 - 2.0 * fy / size as f64) * tan;
            let d = DVec3::new(x, y, -1.0).normalize();
            let b = eye.dot(d);
            let disc = b * b - (eye.length_squared() - 1.0);
            (disc > 0.0).then(|| {
                let p = eye + (-b - disc.sqrt()) * d;
                -d.dot(p.normalize())
            })
        };
        // E(μ) on a grid of μ 0.005 apart, interpolated (its error is 3·10⁻⁶ E'').
        let grid: Vec<f64> = (0..=200)
            .map(|k| ggx_albedo(alpha, k as f64 * 0.005))
            .collect();
        let albedo = |mu: f64| {
            let at = (mu / 0.005).min(199.999);
            let k = at.floor();
            grid[k as usize] + (grid[k as usize + 1] - grid[k as usize]) * (at - k)
        };
        // The mean of E over pixel (px, py)'s footprint; None where any of it misses.
        const POINTS: u32 = 8;
        let footprint = |px: u32, py: u32| -> Option<f64> {
            let mut sum = 0.0;
            for i in 0..POINTS * POINTS {
                let fx = px as f64 + ((i % POINTS) as f64 + 0.5) / POINTS as f64;
                let fy = py as f64 + ((i / POINTS) as f64 + 0.5) / POINTS as f64;
                sum += albedo(mu_at(fx, fy)?);
            }
            Some(sum / (POINTS * POINTS) as f64)
        };
        for integrator in [IntegratorKind::PhotonMap, IntegratorKind::Path] {
            let settings = Settings {
                integrator,
                ..settings.clone()
            };
            let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
            let error = film.error().expect("eight passes");
            for (lo, hi) in [(0.95, 1.0), (0.45, 0.55)] {
                let (mut rendered, mut expected, mut variance, mut n) = (0.0, 0.0, 0.0, 0);
                for py in 0..size {
                    for px in 0..size {
                        let centre = mu_at(px as f64 + 0.5, py as f64 + 0.5);
                        if !centre.is_some_and(|m| (lo..=hi).contains(&m)) {
                            continue;
                        }
                        let i = (py * size + px) as usize;
                        expected += footprint(px, py).expect("the pixel is on the sphere");
                        rendered += error.mean(i)[0];
                        variance += error.variance(i)[0];
                        n += 1;
                    }
                }
                let n = n as f64;
                let (rendered, expected, sigma) = (rendered / n, expected / n, variance.sqrt() / n);
                println!(
                    "α {alpha}, {integrator:?}, μ in [{lo}, {hi}] ({n} pixels): rendered \
                     {rendered:.5} ± {sigma:.5}, quadrature {expected:.5}: {:.1} σ",
                    (rendered - expected) / sigma
                );
                assert!(
                    (rendered - expected).abs() < 4.0 * sigma + 5e-5 * expected,
                    "α {alpha}, {integrator:?}, μ in [{lo}, {hi}]: {rendered} vs {expected}"
                );
            }
        }
    }
}

/// The smooth limit: a glass ball of roughness 0.01 renders as the smooth ball, and a metal
/// ball of roughness 0.01 as the smooth one — rough interfaces crossed twice, total internal
/// reflection among rough facets, rough transmission's (n₁/n₂)² and the caustics through and
/// off them included. The Cornell caustic box at 128 × 128, 4 passes: the image means within
/// 0.5 %, and the RMS over 16 × 16 blocks of the relative difference rough − smooth (seeds 1
/// and 0) within 1.5× what the two renders' own noise gives a difference of independent
/// renders, √((ρ_rough² + ρ_smooth²)/2), each ρ the block RMS between two seeds of one
/// material (measured: glass 0.95, conductor 1.35 of it — α = 0.01 blurs the conductor's
/// caustic a little). The renders of a pair have different seeds: with the same seed a rough
/// path draws its next numbers from other Sobol dimensions than the smooth one at the same
/// place, and the two are no longer alike in their noise.
#[test]
fn roughness_zero_is_the_smooth_limit() {
    use grinlight::compare::{mean_ratios, MeanRatios};
    let base = std::fs::read_to_string("scenes/cornell_caustic.toml").unwrap();
    let base = base
        .replace("width = 256", "width = 128")
        .replace("height = 256", "height = 128");
    let render = |text: String, seed: u64| {
        let (scene, settings) = parse_scene(Path::new("scenes/limit.toml"), text).unwrap();
        let settings = Settings { seed, ..settings };
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        film.layer("beauty").unwrap()
    };
    let rms = |a: &[[f32; 3]], b: &[[f32; 3]]| {
        let MeanRatios {
            overall: mean,
            blocks,
        } = mean_ratios(a, b, 128, 16);
        let rms =
            (blocks.iter().map(|r| (r - 1.0).powi(2)).sum::<f64>() / blocks.len() as f64).sqrt();
        (mean, rms)
    };
    let glass = "type = \"dielectric\"\nior = 1.5\n";
    let mirror = "type = \"conductor\"\neta = [0.2, 0.4, 1.4]\nk = [3.9, 2.4, 1.6]\n";
    for (name, material) in [("glass", glass), ("conductor", mirror)] {
        let smooth_text = base.replace("type = \"dielectric\"\nior = 1.5\n", material);
        let rough_text = smooth_text.replace(material, &format!("{material}roughness = 0.01\n"));
        let smooth = [render(smooth_text.clone(), 0), render(smooth_text, 1)];
        let rough = [render(rough_text.clone(), 0), render(rough_text, 1)];
        let (mean, spread) = rms(&rough[1], &smooth[0]);
        let (_, smooth_noise) = rms(&smooth[1], &smooth[0]);
        let (_, rough_noise) = rms(&rough[1], &rough[0]);
        let noise = ((rough_noise.powi(2) + smooth_noise.powi(2)) / 2.0).sqrt();
        println!(
            "{name}: rough/smooth mean {mean:.4}, block RMS {spread:.4} against {noise:.4} \
             (seed noise rough {rough_noise:.4}, smooth {smooth_noise:.4}): {:.2}",
            spread / noise
        );
        assert!((mean - 1.0).abs() < 0.005, "{name}: mean ratio {mean}");
        assert!(
            spread < 1.5 * noise,
            "{name}: block RMS {spread} vs noise {noise}"
        );
    }
}

/// What a material says its lobes are (read before any ray is traced: the photon plan, the
/// caustic photons' aim) is what the BSDF it makes at a hit has (what decides a vertex).
#[test]
fn a_materials_lobes_are_its_bsdfs() {
    use grinlight::transport::{Stats, Tracer};
    let materials = [
        "type = \"diffuse\"\nalbedo = 0.5\n",
        "type = \"mirror\"\n",
        "type = \"conductor\"\nmetal = \"Cu\"\nroughness = 0.3\n",
        "type = \"conductor\"\nmetal = \"perfect\"\nroughness = 0.0005\n",
        "type = \"dielectric\"\nior = 1.5\n",
        "type = \"dielectric\"\nior = 1.5\nroughness = 0.2\n",
        "type = \"plastic\"\nalbedo = 0.5\n",
    ];
    for m in materials {
        let text = format!(
            "[[material]]\nname = \"m\"\n{m}\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n"
        );
        let (scene, settings) = parse_scene(Path::new("lobes.toml"), text).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        let hit = tracer
            .next_event(
                DVec3::new(0.0, 0.0, 3.0),
                -DVec3::Z,
                None,
                &mut Stats::default(),
            )
            .surface_hit()
            .expect("the ray meets the sphere");
        let surface = scene.surface(hit.prim);
        let vertex = tracer.vertex(hit, surface, None).unwrap();
        let material = scene.material(surface).unwrap().lobes();
        assert_eq!(vertex.lobes(), material, "{m}");
    }
}

/// A conductor's `eta` and `k` given as forms over wavelength: gold's measured nodes given as
/// `{ table = ... }` render the very picture `metal = "Au"` does (a monotone cubic through
/// the nodes, sampled at them, is the table itself), smooth and rough, in RGB and at hero
/// wavelengths (a dispersive glass ball in the scene makes camera samples draw one).
#[test]
fn a_metal_given_over_wavelength_is_the_named_one() {
    let au = grinlight::bsdf::metal("Au").unwrap();
    let table = |v: &[f64]| {
        let rows: Vec<String> = grinlight::bsdf::WAVELENGTHS
            .iter()
            .zip(v)
            .map(|(nm, x)| format!("[{nm}, {x}]"))
            .collect();
        format!("{{ table = [{}] }}", rows.join(", "))
    };
    for (roughness, glass) in [(0.0, ""), (0.2, ""), (0.2, "ior = \"F2\"")] {
        let scene = |index: &str| {
            format!(
                "[camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\n\
                 width = 24\nheight = 24\n[render]\nspp = 4\nintegrator = \"path\"\n\
                 [[material]]\nname = \"m\"\ntype = \"conductor\"\n{index}\n\
                 roughness = {roughness}\n\
                 [[material]]\nname = \"g\"\ntype = \"dielectric\"\n{}\n\
                 [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n\
                 [[shape]]\ntype = \"sphere\"\ncenter = [1.2, 1.2, 1]\nradius = 0.3\n\
                 material = \"g\"\n\
                 [[light]]\ntype = \"environment\"\nsky = \"uniform\"\nradiance = [1, 0.8, 0.6]\n",
                if glass.is_empty() { "ior = 1.5" } else { glass }
            )
        };
        let given = format!("eta = {}\nk = {}", table(&au.eta), table(&au.k));
        let render = |text: String| {
            let (scene, settings) = parse_scene(Path::new("metal.toml"), text).unwrap();
            grinlight::render::render(&scene, &settings, &()).unwrap().0
        };
        let named = render(scene("metal = \"Au\""));
        let tabled = render(scene(&given));
        assert_eq!(
            named.layer("beauty").unwrap(),
            tabled.layer("beauty").unwrap(),
            "roughness {roughness}, {glass}"
        );
    }
}

/// The photon mapper reads a plastic's diffuse lobe from its photon map (the irradiance that
/// passes the coat) and follows its final gathers on through the coat's lobe; the path
/// tracer samples the whole BSDF. The glossy Cornell box with every wall plastic too (so that
/// nearly every gather ends on a plastic), 64 × 64: the photon mapper at 8 passes against
/// the path tracer at 512 spp — the image's and the plastic back wall's means within four
/// standard errors of their difference (each render's from its passes' spread) plus 0.3 %
/// for the photon mapper's kernel bias. That bias is measured and shrinks as the photons
/// grow: the image's ratio is 0.9973, 0.9980, 0.9984 at 1, 4 and 16 times the scene's
/// photons (standard error of the ratio 0.09 %); the back wall's 0.9961, 0.9966, 0.9973
/// (0.3 %).
#[test]
fn the_photon_mapper_reads_plastic_as_the_path_tracer_sees_it() {
    let text = std::fs::read_to_string("scenes/cornell_glossy.toml")
        .unwrap()
        .replace("width = 256", "width = 64")
        .replace("height = 256", "height = 64")
        .replace(
            "name = \"white\"\ntype = \"diffuse\"\nalbedo = [0.75, 0.75, 0.75]",
            "name = \"white\"\ntype = \"plastic\"\nalbedo = [0.75, 0.75, 0.75]\nior = 1.5\nroughness = 0.2",
        );
    assert!(
        text.contains("roughness = 0.2\n"),
        "the walls became plastic"
    );
    let render = |kind: IntegratorKind, passes: u32, spp: u32| {
        let (scene, settings) =
            parse_scene(Path::new("scenes/plastic_box.toml"), text.clone()).unwrap();
        let mut settings = Settings {
            integrator: kind,
            passes,
            spp,
            ..settings
        };
        settings.seed = 3;
        grinlight::render::render(&scene, &settings, &()).unwrap().0
    };
    let pm = render(IntegratorKind::PhotonMap, 8, 16);
    let pt = render(IntegratorKind::Path, 32, 16);
    // A region's mean over its pixels and channels, and that mean's standard error.
    let region = |film: &grinlight::film::Film,
                  rows: std::ops::Range<usize>,
                  cols: std::ops::Range<usize>| {
        let error = film.error().expect("several passes");
        let (mut sum, mut variance, mut n) = (0.0, 0.0, 0.0);
        for y in rows {
            for x in cols.clone() {
                sum += error.mean(y * 64 + x).iter().sum::<f64>();
                variance += error.variance(y * 64 + x).iter().sum::<f64>();
                n += 3.0;
            }
        }
        (sum / n, variance.sqrt() / n)
    };
    for (name, rows, cols) in [("image", 0..64, 0..64), ("back wall", 12..24, 24..40)] {
        let (a, sa) = region(&pm, rows.clone(), cols.clone());
        let (b, sb) = region(&pt, rows, cols);
        let sigma = sa.hypot(sb);
        println!(
            "{name}: photon map {a:.5} ± {sa:.5}, path {b:.5} ± {sb:.5}: ratio {:.4}, {:.1} σ",
            a / b,
            (a - b) / sigma
        );
        assert!(
            (a - b).abs() < 4.0 * sigma + 0.003 * b,
            "{name}: photon map {a} ± {sa}, path {b} ± {sb}"
        );
    }
}

/// On a smooth mesh a light sample and a BSDF sample estimate the same integral: the light
/// sample's f·cos (`Vertex::eval` times `Vertex::cos`) and the BSDF sample's weight f·|cos|/pdf
/// take the cosine at the same normal — the shading normal a glossy or coated lobe is
/// evaluated about — so that multiple importance sampling weighs two estimates of one thing.
/// At a point of a coarse sphere mesh whose shading normal turns 5.2° from its facet's,
/// ∫ f cos g dω for g(ω) = 1 + ½ω·x + ¼ω·y is estimated both ways (2·10⁵ BSDF samples, 2·10⁶
/// uniform directions), for a rough conductor and a rough plastic; they agree within 4
/// standard errors. With the cosine at the facet's normal on the light-sample side the
/// conductor's read 5 % apart (z 28).
#[test]
fn light_and_bsdf_samples_take_the_same_cosine_on_a_smooth_mesh() {
    use grinlight::transport::{Stats, Tracer, Vertex};
    use rand::{Rng, SeedableRng};
    let dir = std::env::temp_dir().join(format!("grinlight-smooth-cos-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("ball.obj"), crate::common::sphere_obj(2, true)).unwrap();
    for material in [
        "type = \"conductor\"\nmetal = \"Cu\"\nroughness = 0.3\n",
        "type = \"plastic\"\nalbedo = 0.5\nroughness = 0.2\n",
    ] {
        let text = format!(
            "[[material]]\nname = \"m\"\n{material}\
             [[shape]]\ntype = \"mesh\"\nfile = \"ball.obj\"\nmaterial = \"m\"\n"
        );
        let (scene, settings) = parse_scene(&dir.join("s.toml"), text).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        let (origin, direction) = (DVec3::new(0.31, 0.22, 3.0), -DVec3::Z);
        let hit = tracer
            .next_event(origin, direction, None, &mut Stats::default())
            .surface_hit()
            .expect("the ray meets the ball");
        let v = tracer.vertex(hit, scene.surface(hit.prim), None).unwrap();
        let turn = v.shading.angle_between(v.normal).to_degrees();
        assert!(turn > 5.0, "{material}: the shading normal turns {turn}°");
        let g = |w: DVec3| 1.0 + 0.5 * w.x + 0.25 * w.y;
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(7);
        let stats = |xs: &[f64]| {
            let n = xs.len() as f64;
            let mean = xs.iter().sum::<f64>() / n;
            let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, (var / n).sqrt())
        };
        let by_bsdf: Vec<f64> = (0..200_000)
            .map(|_| {
                v.scatter((rng.gen(), rng.gen(), rng.gen()))
                    .map_or(0.0, |s| s.sample.weight.0.x * g(s.sample.wi))
            })
            .collect();
        let vertex = Vertex::Surface(v);
        let by_light: Vec<f64> = (0..2_000_000)
            .map(|_| {
                let z: f64 = 2.0 * rng.gen::<f64>() - 1.0;
                let phi = std::f64::consts::TAU * rng.gen::<f64>();
                let r = (1.0 - z * z).sqrt();
                let wi = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                let cos = vertex.cos(wi).max(0.0);
                vertex.eval(wi).0.x * cos * g(wi) * 4.0 * std::f64::consts::PI
            })
            .collect();
        let ((a, sa), (b, sb)) = (stats(&by_bsdf), stats(&by_light));
        let z = (a - b).abs() / (sa * sa + sb * sb).sqrt();
        println!("{material}: turn {turn:.1}°, BSDF samples {a:.5} ± {sa:.5}, light samples {b:.5} ± {sb:.5}, z {z:.2}");
        assert!(
            z < 4.0,
            "{material}: {a} ± {sa} against {b} ± {sb} (z {z:.1})"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
