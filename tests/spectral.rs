//! Wavelength as a physical quantity: dispersive media in scenes, photons that carry a
//! wavelength, receivers that measure bands — checked against Descartes' rainbow and a GRIN
//! rod's paraxial pitch per wavelength.

use glam::DVec3;
use grinlight::curve::{march_with, Bounds, MarchLimits, RayState, StepControl, StepperKind};
use grinlight::scene::load::parse_scene;
use grinlight::scene::load_scene;
use grinlight::spectrum::Dispersion;
use std::path::Path;

/// The minimum-deviation ray of a unit sphere of index `n` lit along −z (
/// cos² i = (n² − 1)/3), traced exactly (straight chords, Snell, one internal reflection): its
/// exit point and exit direction.
fn descartes_ray(n: f64) -> (DVec3, DVec3) {
    let far_hit = |o: DVec3, d: DVec3| {
        let (b, c) = (o.dot(d), o.length_squared() - 1.0);
        let s = (b * b - c).sqrt();
        o + d * if -b - s > 1e-9 { -b - s } else { -b + s }
    };
    let refract = |d: DVec3, normal: DVec3, eta: f64| {
        let c = -normal.dot(d);
        eta * d + (eta * c - (1.0 - eta * eta * (1.0 - c * c)).sqrt()) * normal
    };
    let i = ((n * n - 1.0) / 3.0).sqrt().acos();
    let mut d = -DVec3::Z;
    let mut p = far_hit(DVec3::new(i.sin(), 0.0, 2.0), d);
    d = refract(d, p, 1.0 / n);
    p = far_hit(p, d);
    d -= 2.0 * d.dot(p) * p;
    p = far_hit(p, d);
    (p, refract(d, -p, n))
}

/// Descartes' closed form: the exit direction of the traced minimum-deviation ray makes the
/// angle π − D with the antisolar direction +z, D = π + 2i − 4 asin(sin i / n), to rounding
/// (1e-11 rad: chord intersections round to ~1e-13, amplified by acos and asin); and water's bow is 42.08° at n = 1.333.
#[test]
fn the_descartes_ray_leaves_at_the_rainbow_angle() {
    for n in [1.333f64, 1.34, 1.517] {
        let i = ((n * n - 1.0) / 3.0).sqrt().acos();
        let d_min = std::f64::consts::PI + 2.0 * i - 4.0 * (i.sin() / n).asin();
        let (_, dir) = descartes_ray(n);
        let angle = dir.z.acos();
        assert!(
            (angle - (std::f64::consts::PI - d_min)).abs() < 1e-11,
            "{n}"
        );
        if n == 1.333 {
            assert!(
                (angle.to_degrees() - 42.08).abs() < 0.005,
                "{}",
                angle.to_degrees()
            );
        }
    }
}

/// `scenes/rainbow.toml`: each band's bow on the receiver is where the minimum-deviation ray
/// of the band's centre wavelength lands, within one ring (0.1 units: the bins' width; the
/// bow's edge is a caustic, so its brightest ring is the one it falls in or the one just
/// inside) plus half the spread of the band's own bow across its 40 nm; red outside blue;
/// and the energy budget booked band by band.
#[test]
fn the_rainbow_bands_land_where_descartes_says() {
    let (scene, mut settings) = load_scene(Path::new("scenes/rainbow.toml")).unwrap();
    settings.receiver_photons = 2_000_000;
    let (m, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let rec = &scene.receivers[0];
    // The energy budget per band: each band's fates add up to its emission, which is the
    // band's share of the equal-energy spectrum (40 of 470 nm: each photon's power is the same,
    // so the count in a band is binomial; within 5 of its standard deviations).
    assert_eq!(budget.bands.len(), rec.bands.len());
    for ((lo, hi), b) in &budget.bands {
        assert!(
            (b.booked() / b.emitted - 1.0).abs() < 1e-9,
            "{lo}–{hi}: {b:?}"
        );
        let p = 40.0 / 470.0;
        let sd = (p * (1.0 - p) / settings.receiver_photons as f64).sqrt();
        assert!(
            (b.emitted / budget.emitted - p).abs() < 5.0 * sd,
            "{lo}–{hi}: {b:?}"
        );
    }
    let water = Dispersion::named("water").unwrap();
    let z = rec.center.z;
    let land = |nm: f64| {
        let (p, d) = descartes_ray(water.at(nm));
        let q = p + d * (z - p.z) / d.z;
        q.truncate().length()
    };
    let width = 0.1;
    let mut peaks = Vec::new();
    for (&(lo, hi), band) in rec.bands.iter().zip(&m[0].bands) {
        // Rings by bin-centre radius; the incoming beam (r < 1.2) and the corners are left out.
        let mut rings = vec![(0.0, 0usize); 120];
        for (k, e) in band.irradiance.iter().enumerate() {
            let (x, y) = rec.bin_center(k);
            let ring = ((x * x + y * y).sqrt() / width) as usize;
            if (12..120).contains(&ring) {
                rings[ring].0 += e;
                rings[ring].1 += 1;
            }
        }
        let peak = (12..120)
            .max_by(|&a, &b| {
                let mean = |r: usize| rings[r].0 / rings[r].1.max(1) as f64;
                mean(a).total_cmp(&mean(b))
            })
            .unwrap();
        let measured = (peak as f64 + 0.5) * width;
        let expected = land(0.5 * (lo + hi));
        let spread = 0.5 * (land(hi) - land(lo));
        assert!(
            (measured - expected).abs() <= width + spread,
            "band {lo}–{hi} nm: bow at r = {measured}, Descartes {expected} ± {spread}"
        );
        peaks.push(measured);
    }
    assert!(
        peaks.windows(2).all(|w| w[1] > w[0]),
        "red outside blue: {peaks:?}"
    );
    // Each band holds its share of an equal-energy spectrum: 40 of 470 nm of the total flux,
    // within 5 standard errors.
    for band in &m[0].bands {
        let share = m[0].flux.0 * 40.0 / 470.0;
        assert!((band.flux.0 - share).abs() < 5.0 * band.flux.1, "{band:?}");
    }
}

/// A GRIN rod n = n0(1 − g²r²/2) with a catalogue-style g(λ): a paraxial ray entering
/// parallel to the axis at r0 crosses it at a quarter pitch, z = π/(2 g(λ)), for each
/// wavelength. The paraxial error is O(g² r0²) = 1e-7 relative at r0 = 1e-3 (measured:
/// 3.1–3.4e-8 at the four wavelengths), which is the tolerance.
#[test]
fn a_grin_rod_focuses_each_wavelength_at_its_own_quarter_pitch() {
    let text = r#"
[[medium]]
name = "rod"
profile = "parabolic"
n0 = "F2"
g = { table = [[400.0, 0.33], [550.0, 0.32], [700.0, 0.31]] }
"#;
    let (scene, _) = parse_scene(Path::new("rod.toml"), text.to_string()).unwrap();
    let media = scene.media();
    let rod = media.index("rod").unwrap();
    assert!(media.is_dispersive(rod));
    let table = Dispersion::Table(
        grinlight::media::MonotoneCubic::new(
            vec![400.0, 550.0, 700.0],
            vec![0.33, 0.32, 0.31],
            false,
            ("nm", "g"),
        )
        .unwrap(),
    );
    let mut foci = Vec::new();
    for nm in [420.0, 486.1327, 587.5618, 656.2725] {
        let medium = media.at_wavelength(rod, nm).unwrap();
        let g = table.at(nm);
        let start =
            RayState::new(medium.as_medium(), DVec3::new(1e-3, 0.0, 0.0), DVec3::Z).unwrap();
        let limits = MarchLimits {
            length: 2.0 * std::f64::consts::PI / g,
            max_steps: 1_000_000,
            bounds: Bounds::Unbounded,
        };
        let mut crossing = None;
        let mut last = start.position;
        march_with(
            StepperKind::Rk4,
            medium.as_medium(),
            StepControl::Fixed { step: 0.005 },
            start,
            &limits,
            |_, step| {
                let p = step.state.position;
                if crossing.is_none() && last.x > 0.0 && p.x <= 0.0 {
                    crossing = Some(last.z + (p.z - last.z) * last.x / (last.x - p.x));
                }
                last = p;
                std::ops::ControlFlow::Continue(())
            },
        );
        // The crossing is interpolated linearly between RK4 points 0.005 apart: near the
        // crossing x is odd about it (x'' = −g²x = 0 there), so the chord's error is
        // O(g²h³) ≈ 1e-8, and RK4's own O((gh)⁴) per step is smaller still.
        let z = crossing.expect("the ray crosses the axis");
        let want = std::f64::consts::FRAC_PI_2 / g;
        assert!((z / want - 1.0).abs() < 1e-7, "{nm} nm: {z} vs {want}");
        foci.push(z);
    }
    // Blue focuses first: g falls with wavelength.
    assert!(foci.windows(2).all(|w| w[1] > w[0]), "{foci:?}");
}

/// Every form of a dispersive index reads; a wrong one (among them a Sellmeier pole at
/// 500.5 nm too weak to show at whole nanometres) is an error at its file:line:col.
#[test]
fn dispersive_indices_read_and_wrong_ones_are_located() {
    let ok = [
        "ior = 1.5",
        "ior = \"BK7\"",
        "ior = { sellmeier = [1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653] }",
        "ior = { cauchy = [1.5046, 0.0042] }",
        "ior = { abbe = [1.5168, 64.17] }",
        "ior = { table = [[400.0, 1.53], [700.0, 1.51]] }",
    ];
    for line in ok {
        let text = format!("[[material]]\nname = \"g\"\ntype = \"dielectric\"\n{line}\n");
        let (scene, _) = parse_scene(Path::new("s.toml"), text).unwrap();
        let media = scene.media();
        assert_eq!(
            media.is_dispersive(grinlight::ids::MediumId::new(0)),
            line != "ior = 1.5",
            "{line}"
        );
        let n = media
            .at(grinlight::ids::MediumId::new(0))
            .sample(DVec3::ZERO)
            .unwrap()
            .n;
        assert!((n - 1.517).abs() < 0.02, "{line}: n_d = {n}");
    }
    let bad = [
        ("ior = \"unobtainium\"", "unknown material"),
        ("ior = { abbe = [0.9, 10.0] }", "abbe takes"),
        ("ior = { sellmeier = [1.0, 2.0, 3.0] }", "sellmeier takes"),
        ("ior = { sellmeier = [1e-6, 0.2505] }", "puts a pole of n"),
        ("ior = { fresnel = [1.0] }", "unknown dispersion model"),
        ("ior = { cauchy = [-1.0] }", "must be > 0"),
        ("ior = [1.5]", "expected a number"),
    ];
    for (line, says) in bad {
        let text = format!("[[material]]\nname = \"g\"\ntype = \"dielectric\"\n{line}\n");
        let err = parse_scene(Path::new("s.toml"), text)
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains("s.toml:4:") && err.contains(says),
            "{line}: {err}"
        );
    }
}

/// `scenes/grin_lens_chromatic.toml` with its bundle narrowed to the central 0.1 mm of the rod:
/// each band's focus — the plane of least mean-square radius, the minimum of the parabola
/// fitted to the 17 receivers' ⟨r²⟩ (exactly quadratic in z for straight rays) — lies where
/// paraxial optics puts the image of the band's centre wavelength, the rod's ABCD matrix
/// [[cos gL, sin gL/(n0 g)], [−n0 g sin gL, cos gL]] between the free stretches, with n0(λ)
/// of F2 and g(λ) of the scene. Tolerance 0.004 mm: the residual aberration of the bundle and
/// the photon noise gave offsets of +0.0002 to +0.0020 mm over four seeds (2·10⁵ photons);
/// the blue-to-red shift being measured is 0.233 mm.
#[test]
fn a_grin_rod_lens_focuses_each_band_at_its_paraxial_image() {
    let path = Path::new("scenes/grin_lens_chromatic.toml");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("cone_deg = 1.72", "cone_deg = 0.57");
    let (scene, mut settings) = parse_scene(path, text).unwrap();
    settings.receiver_photons = 200_000;
    let (m, _, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let (f2, s0, length) = (Dispersion::named("F2").unwrap(), 10.0, 4.0);
    let g = |nm: f64| 0.33 - (nm - 400.0) / 300.0 * 0.02; // the scene's table is linear
    let paraxial = |nm: f64| {
        let (n0, g) = (f2.at(nm), g(nm));
        let (c, s) = ((g * length).cos(), (g * length).sin());
        let (a, b, cc, d) = (c, s / (n0 * g), -n0 * g * s, c);
        -(a * s0 + b) / (cc * s0 + d)
    };
    let behind: Vec<f64> = scene
        .receivers
        .iter()
        .map(|r| r.center.z - length)
        .collect();
    let mut foci = Vec::new();
    for (k, &(lo, hi)) in scene.receivers[0].bands.iter().enumerate() {
        let r2: Vec<f64> = scene
            .receivers
            .iter()
            .zip(&m)
            .map(|(rec, meas)| meas.bands[k].mean_square_radius(rec))
            .collect();
        let focus = vertex_of_fitted_parabola(&behind, &r2);
        let want = paraxial(0.5 * (lo + hi));
        assert!(
            (focus - want).abs() < 0.004,
            "band {lo}–{hi} nm: focus {focus} mm behind the rod, paraxial {want}"
        );
        foci.push(focus);
    }
    assert!(foci.windows(2).all(|w| w[1] > w[0]), "blue first: {foci:?}");
    let shift = foci[2] - foci[0];
    assert!(
        (shift - (paraxial(640.0) - paraxial(420.0))).abs() < 0.004,
        "{shift}"
    );
}

/// The z of the least-squares parabola v ≈ c0 + c1 z + c2 z² through the points.
fn vertex_of_fitted_parabola(z: &[f64], v: &[f64]) -> f64 {
    let sum = |f: &dyn Fn(f64, f64) -> f64| z.iter().zip(v).map(|(&z, &v)| f(z, v)).sum::<f64>();
    let s: Vec<f64> = (0..5).map(|k| sum(&|z, _| z.powi(k))).collect();
    let t: Vec<f64> = (0..3).map(|k| sum(&|z, v| v * z.powi(k))).collect();
    // Normal equations by Cramer's rule.
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let a = [[s[0], s[1], s[2]], [s[1], s[2], s[3]], [s[2], s[3], s[4]]];
    let with = |col: usize| {
        let mut m = a;
        for (row, t) in m.iter_mut().zip(&t) {
            row[col] = *t;
        }
        det3(m)
    };
    -with(1) / (2.0 * with(2))
}

/// The mean of each channel of layer `name`, and its standard error from the pixels' spread.
fn channel_means(film: &grinlight::film::Film, name: &str) -> [(f64, f64); 3] {
    let pixels = film.layer(name).unwrap();
    let n = pixels.len() as f64;
    [0, 1, 2].map(|c| {
        let mean = pixels.iter().map(|p| p[c] as f64).sum::<f64>() / n;
        let var = pixels
            .iter()
            .map(|p| (p[c] as f64 - mean).powi(2))
            .sum::<f64>()
            / (n - 1.0);
        (mean, (var / n).sqrt())
    })
}

/// The white furnace in spectral mode: the closed grey sphere of `tests/render.rs` (albedo a,
/// a point light of intensity I at its centre, camera at the centre: L = (a/π)(I/R²)/(1 − a)
/// everywhere), but filled with dispersive water, so every camera path takes its hero
/// wavelength where it starts and every photon takes one on where it is launched. Each channel of the image is the
/// white total within 4 standard errors of the pixels' spread (the wavelength noise is in
/// it) plus the photon mapper's 1 % (its k-nearest estimate of a uniform irradiance, measured
/// in RGB mode by the test there).
#[test]
fn the_white_furnace_stays_white_in_spectral_mode() {
    let (a, i, r) = (0.5f64, 3.0f64, 2.0f64);
    let text = format!(
        "ambient = \"water\"\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov_y_deg = 60\nwidth = 16\nheight = 16\n\
         [render]\nspp = 256\ngather = 4\nphotons = 200000\n\
         [[medium]]\nname = \"water\"\nprofile = \"uniform\"\nn = \"water\"\n\
         [[material]]\nname = \"grey\"\ntype = \"diffuse\"\nalbedo = [{a}, {a}, {a}]\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = {r}\nmaterial = \"grey\"\n\
         [[light]]\ntype = \"point\"\nposition = [0, 0, 0.0]\nintensity = {i}\n"
    );
    let (scene, settings) = parse_scene(Path::new("furnace.toml"), text).unwrap();
    assert!(scene.is_dispersive());
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    let want = a * i / (r * r) / std::f64::consts::PI / (1.0 - a);
    for (c, (mean, se)) in channel_means(&film, "beauty").into_iter().enumerate() {
        println!("channel {c}: {mean:.5} ± {se:.5} (white {want:.5})");
        assert!(
            (mean - want).abs() < 4.0 * se + 0.01 * want,
            "channel {c}: {mean} ± {se} vs {want}"
        );
    }
}

/// A grey Cornell box with a glass ball (`scenes/cornell_caustic.toml` with grey walls, 48 ×
/// 48) in spectral mode — the ball's glass given by an Abbe number so large (V = 10⁹) that
/// every wavelength takes the same path to 1e-10, so that the scene is dispersive but its
/// picture is not — matches its RGB render: camera paths through the ball take a hero
/// wavelength and photons through it take on one, and the expectation over wavelengths is
/// the RGB one.
/// Both are rendered with 8 seeds; the seeds' spread of the difference of the image means
/// gives its standard error (the photon maps' noise is correlated across pixels, so the
/// pixels' spread would understate it). Each channel of the beauty and of the caustic layer
/// (the light through the ball): the mean difference within 4 standard errors; the beauty's
/// also within 1 % of its mean.
#[test]
fn a_grey_cornell_box_renders_alike_in_spectral_and_rgb_mode() {
    let base = std::fs::read_to_string("scenes/cornell_caustic.toml")
        .unwrap()
        .replace("[0.75, 0.15, 0.15]", "[0.75, 0.75, 0.75]")
        .replace("[0.15, 0.75, 0.15]", "[0.75, 0.75, 0.75]")
        .replace("width = 256", "width = 48")
        .replace("height = 256", "height = 48")
        .replace("spp = 16", "spp = 8");
    let means = |text: &str, seed: u32| {
        let text = text.replace("passes = 4", &format!("passes = 1\nseed = {seed}"));
        let (scene, settings) = parse_scene(Path::new("cornell_caustic.toml"), text).unwrap();
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        let mean = |layer: &str| {
            let pixels = film.layer(layer).unwrap();
            let n = pixels.len() as f64;
            [0, 1, 2].map(|c| pixels.iter().map(|p| p[c] as f64).sum::<f64>() / n)
        };
        (scene.is_dispersive(), [mean("beauty"), mean("caustic")])
    };
    let spectral_text = base.replace("ior = 1.5", "ior = { abbe = [1.5, 1e9] }");
    let seeds = 8;
    let mut diffs = vec![[[0.0; 3]; 2]; seeds];
    let mut level = [[0.0; 3]; 2];
    for (k, d) in diffs.iter_mut().enumerate() {
        let (rgb_mode, a) = means(&base, k as u32 + 1);
        let (spectral_mode, b) = means(&spectral_text, k as u32 + 1);
        assert!(!rgb_mode && spectral_mode);
        for l in 0..2 {
            for c in 0..3 {
                d[l][c] = b[l][c] - a[l][c];
                level[l][c] += a[l][c] / seeds as f64;
            }
        }
    }
    for (l, layer) in ["beauty", "caustic"].iter().enumerate() {
        for c in 0..3 {
            let x: Vec<f64> = diffs.iter().map(|d| d[l][c]).collect();
            let n = x.len() as f64;
            let mean = x.iter().sum::<f64>() / n;
            let se = (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
            let level = level[l][c];
            println!("{layer} channel {c}: spectral − RGB = {mean:.6} ± {se:.6} (RGB {level:.5})");
            assert!(mean.abs() < 4.0 * se, "{layer} channel {c}: {mean} ± {se}");
            if l == 0 {
                assert!(
                    mean.abs() < 0.01 * level,
                    "{layer} channel {c}: {mean} vs {level}"
                );
            }
        }
    }
}

/// A camera path that carries one wavelength reads a light with a spectrum at that wavelength
/// from the spectrum itself: an orange quad (albedo [0.8, 0.3, 0.1]) under the sun of a 600 nm
/// line (FWHM 20, irradiance 1), seen from a dispersive ambient medium of index ≈ 1 (every camera
/// path carries its hero wavelength from the camera on), reads (1/π)∫ r̄(λ)·ρ(λ)·S(λ) dλ per
/// channel — ρ the albedo's reflectance spectrum, S the line's normalised density, by 0.01 nm
/// midpoint sums — within 4 standard errors of the pixels' spread plus 2·10⁻⁴ (n² of the
/// medium, 1.0002, and the observer's 1 nm table), both integrators. Such a path used to read
/// the reflectance spectrum of the light's sRGB colour times D65 instead, a broad spectrum of
/// the same colour: its red read 1.8334 against the line's 1.5123, 21 % too bright.
#[test]
fn a_camera_path_at_one_wavelength_reads_a_lights_own_spectrum() {
    let albedo = [0.8, 0.3, 0.1];
    let text = format!(
        "ambient = \"air\"\n\
         [camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\nfov_y_deg = 20\n\
         width = 16\nheight = 16\n\
         [render]\nspp = 256\n\
         [[medium]]\nname = \"air\"\nprofile = \"uniform\"\nn = {{ abbe = [1.0001, 50] }}\n\
         [[material]]\nname = \"orange\"\ntype = \"diffuse\"\nalbedo = {albedo:?}\n\
         [[shape]]\ntype = \"quad\"\n\
         vertices = [[-10, -10, 0], [10, -10, 0], [10, 10, 0], [-10, 10, 0]]\nmaterial = \"orange\"\n\
         [[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nirradiance = 1\n\
         spectrum = {{ gaussian = [600, 20] }}\n"
    );
    let (scene, settings) = parse_scene(Path::new("line.toml"), text).unwrap();
    assert!(scene.is_dispersive());
    let sigma = 20.0 / (8.0 * std::f64::consts::LN_2).sqrt();
    let (mut mass, mut sum) = (0.0, DVec3::ZERO);
    for k in 0..47_000 {
        let nm = 360.0 + 0.01 * (k as f64 + 0.5);
        let s = (-0.5 * ((nm - 600.0) / sigma).powi(2)).exp();
        let rho = grinlight::spectrum::colour::reflectance(
            grinlight::color::Rgb(DVec3::from_array(albedo)),
            nm,
        );
        mass += s;
        sum += grinlight::spectrum::colour::sensor(nm).0 * (rho * s);
    }
    let want = sum / mass / std::f64::consts::PI;
    for integrator in grinlight::settings::IntegratorKind::ALL {
        let settings = grinlight::settings::Settings {
            integrator,
            ..settings.clone()
        };
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        for (c, (mean, se)) in channel_means(&film, "beauty").into_iter().enumerate() {
            println!(
                "{integrator:?} channel {c}: {mean:.5} ± {se:.5} against {:.5}",
                want[c]
            );
            assert!(
                (mean - want[c]).abs() < 4.0 * se + 2e-4 * want[c].abs(),
                "{integrator:?} channel {c}: {mean} ± {se} against {}",
                want[c]
            );
        }
    }
}
