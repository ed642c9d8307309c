//! Furnaces: scenes whose radiance is known exactly, for every kind of light and both
//! integrators — white objects (Lambertian, a plastic of white base, a rough dielectric
//! between equal indices) in conservative fog, open under a uniform sky (the fog reaching the
//! world sphere) and closed in a box of emitters, where every pixel reads the sky's or the
//! walls' radiance (n² of it inside an index n); a point, spot and LED light at the centre of
//! a white spherical room (an integrating sphere: the light the walls send after one bounce is
//! the same everywhere, ρΦ/(πA(1 − ρ)) in all), against its closed form pixel by pixel; and,
//! where no closed form exists — the sun in open fog, a lamp in a fogged room — the photon
//! mapper against the path tracer. Each within 1 % (and 4 standard errors over its pixels
//! where they compare two renders).

use glam::DVec3;
use grinlight::scene::load::parse_scene;
use grinlight::settings::{IntegratorKind, Settings};
use std::f64::consts::PI;
use std::path::Path;

/// The green channel of the beauty layer of `text` rendered by `integrator`, pixel by pixel.
fn pixels(text: &str, integrator: IntegratorKind) -> Vec<f64> {
    let (scene, settings) = parse_scene(Path::new("furnace.toml"), text.to_string()).unwrap();
    let settings = Settings {
        integrator,
        ..settings
    };
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    film.layer("beauty")
        .unwrap()
        .iter()
        .map(|p| p[1] as f64)
        .collect()
}

/// The mean of `values` and its standard error.
fn mean(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// The image mean of `text` rendered by `integrator`, and its standard error over the pixels.
fn render(text: &str, integrator: IntegratorKind) -> (f64, f64) {
    mean(&pixels(text, integrator))
}

const BOTH: [IntegratorKind; 2] = [IntegratorKind::Path, IntegratorKind::PhotonMap];

/// Both integrators render `text` (the case `name`) to an image mean within 1 % of `expected`.
fn both_integrators_read(name: &str, text: &str, expected: f64) {
    for integrator in BOTH {
        let (mean, se) = render(text, integrator);
        println!("{name}, {integrator:?}: {mean:.5} ± {se:.5} against {expected:.5}");
        assert!(
            (mean - expected).abs() <= 0.01 * expected,
            "{name}, {integrator:?}: {mean} ± {se} against {expected}"
        );
    }
}

/// A white Lambertian sphere, a box of white plastic (its coat nearly smooth: α = 0.001,
/// whose single scattering loses nothing measurable) and a rough sphere of the surrounding
/// index (`ior`), side by side.
fn white_objects(ior: f64) -> String {
    format!(
        "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [1, 1, 1]\n\
         [[material]]\nname = \"plastic\"\ntype = \"plastic\"\nalbedo = [1, 1, 1]\nroughness = 0.001\n\
         [[material]]\nname = \"clear\"\ntype = \"dielectric\"\nior = {ior}\nroughness = 0.4\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [-0.55, 0, 0]\nradius = 0.3\nmaterial = \"white\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-0.15, -0.3, -0.2]\nmax = [0.15, 0.3, 0.2]\nmaterial = \"plastic\"\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [0.55, 0, 0]\nradius = 0.3\nmaterial = \"clear\"\n"
    )
}

/// A camera at [0, 0.3, 2.6] looking at the origin, 32 × 24.
const CAMERA: &str = "[camera]\nposition = [0, 0.3, 2.6]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\n\
                      width = 32\nheight = 24\n";

/// Six quad lights of radiance 1 facing into the box [−1.5, 1.5] × [−1.5, 1.5] × [−1.5, 3].
fn emitting_box() -> String {
    let (a, b, z0, z1) = (-1.5, 1.5, -1.5, 3.0);
    let faces = [
        format!("[[{a},{a},{z0}],[{a},{b},{z0}],[{a},{b},{z1}],[{a},{a},{z1}]]"),
        format!("[[{b},{a},{z0}],[{b},{a},{z1}],[{b},{b},{z1}],[{b},{b},{z0}]]"),
        format!("[[{a},{a},{z0}],[{a},{a},{z1}],[{b},{a},{z1}],[{b},{a},{z0}]]"),
        format!("[[{a},{b},{z0}],[{b},{b},{z0}],[{b},{b},{z1}],[{a},{b},{z1}]]"),
        format!("[[{a},{a},{z0}],[{b},{a},{z0}],[{b},{b},{z0}],[{a},{b},{z0}]]"),
        format!("[[{a},{a},{z1}],[{a},{b},{z1}],[{b},{b},{z1}],[{b},{a},{z1}]]"),
    ];
    faces
        .iter()
        .map(|v| format!("[[light]]\ntype = \"quad\"\nradiance = [1, 1, 1]\nvertices = {v}\n"))
        .collect()
}

/// Conservative fog of index `n` (σs = `sigma`) filling all space outside the objects.
fn fog(n: f64, sigma: f64) -> String {
    format!(
        "ambient = \"fog\"\n[[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = {n}\n\
         scattering = {sigma}\nphase = {{ hg = 0.3 }}\n"
    )
}

/// Open fog under a uniform sky of radiance 1 — the fog reaching the default world sphere,
/// ten times the scene's size (an optical depth of 1.6 from the scene to it), and an index of 1
/// or 1.33 (the sky's radiance in vacuum is n² in the medium) — and the same objects in a
/// closed box of emitters: every pixel reads n², by both integrators (the photon mapper's
/// light that the fog scattered outside the scene ball came from its shell; it lost 42 % of it
/// when its photons started upstream of the scene).
#[test]
fn white_objects_in_fog_read_the_radiance_around_them() {
    let render_keys = "[render]\nspp = 4\npasses = 8\nphotons = 50000\ncaustic_photons = 50000\n";
    let sky = "[[light]]\ntype = \"environment\"\nsky = \"uniform\"\n";
    let cases = [
        (
            "open, n = 1",
            format!(
                "{}{}{sky}{CAMERA}{render_keys}",
                fog(1.0, 0.05),
                white_objects(1.0)
            ),
            1.0,
        ),
        (
            "open, n = 1.33",
            format!(
                "{}{}{sky}{CAMERA}{render_keys}",
                fog(1.33, 0.05),
                white_objects(1.33)
            ),
            1.33 * 1.33,
        ),
        (
            "closed",
            format!(
                "{}{}{}{CAMERA}{render_keys}",
                fog(1.0, 0.3),
                white_objects(1.0),
                emitting_box()
            ),
            1.0,
        ),
    ];
    for (name, text, expected) in cases {
        both_integrators_read(name, &text, expected);
    }
}

/// An equal-area environment map of one radiance (an 8 × 8 EXR of 1) is the uniform sky: the
/// open furnace (white objects in fog of n = 1) renders pixel for pixel as under `sky =
/// "uniform"`, by both integrators — its lookup reads the map wherever a path leaves, and the
/// map's pixels hold 1 exactly.
#[test]
fn an_equal_area_map_of_one_radiance_is_the_uniform_sky() {
    let dir = std::env::temp_dir().join(format!("grinlight-equal-area-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    image::Rgb32FImage::from_pixel(8, 8, image::Rgb([1.0; 3]))
        .save(dir.join("sky.exr"))
        .unwrap();
    let render_keys = "[render]\nspp = 2\npasses = 2\nphotons = 20000\ncaustic_photons = 20000\n";
    let scene = |sky: &str| {
        format!(
            "{}{}[[light]]\ntype = \"environment\"\n{sky}{CAMERA}{render_keys}",
            fog(1.0, 0.05),
            white_objects(1.0)
        )
    };
    let uniform = scene("sky = \"uniform\"\n");
    let map = scene("file = \"sky.exr\"\nprojection = \"equal_area\"\n");
    for integrator in BOTH {
        let image = |text: &str| {
            let (scene, settings) = parse_scene(&dir.join("s.toml"), text.to_string()).unwrap();
            let settings = Settings {
                integrator,
                ..settings
            };
            let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
            film.layer("beauty").unwrap()
        };
        let (a, b) = (image(&uniform), image(&map));
        assert!(
            a.iter().any(|p| p[1] > 0.5),
            "{integrator:?}: the sky lights the view"
        );
        assert_eq!(a, b, "{integrator:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A fog that absorbs, scatters and emits basic radiance 1, open under a sky of radiance 1,
/// around white objects: in equilibrium every pixel reads n² (1 for n = 1, 1.33² for n =
/// 1.33), whatever σa and σs — the path tracer gathers the fog's emission along every stretch
/// of every path. The photon mapper sends no photons from a medium, and says so.
#[test]
fn white_objects_in_emitting_fog_under_a_sky_of_its_radiance_read_it() {
    let render_keys = "[render]\nspp = 4\npasses = 8\n";
    let sky = "[[light]]\ntype = \"environment\"\nsky = \"uniform\"\n";
    for n in [1.0, 1.33] {
        let glowing = fog(n, 0.2) + "absorption = 0.1\nemission = 1\n";
        let text = format!("{glowing}{}{sky}{CAMERA}{render_keys}", white_objects(n));
        let (mean, se) = render(&text, IntegratorKind::Path);
        println!(
            "emitting fog, n = {n}: {mean:.5} ± {se:.5} against {:.5}",
            n * n
        );
        assert!(
            (mean - n * n).abs() <= 0.01 * n * n,
            "emitting fog, n = {n}: {mean} ± {se}"
        );
        let (scene, settings) = parse_scene(Path::new("furnace.toml"), text).unwrap();
        let refused = grinlight::render::render(&scene, &settings, &()).unwrap_err();
        assert!(
            refused.to_string().contains("integrator = \"path\""),
            "{refused}"
        );
    }
}

/// The sun in open fog and a lamp in a fogged closed room have no closed form: the photon
/// mapper's image mean is the path tracer's within 1 % and 4 standard errors of their
/// pixel-by-pixel difference (the noise of the two, not the image's own variation).
#[test]
fn the_photon_mapper_reads_the_sun_and_a_lamp_in_fog_as_the_path_tracer_does() {
    let sun =
        "[[light]]\ntype = \"directional\"\ndirection = [0.3, -1, -0.4]\nirradiance = [2, 2, 2]\n";
    let lamp = "[[light]]\ntype = \"point\"\nposition = [0.2, 1.0, 0.6]\nintensity = [1, 1, 1]\n";
    let room = "[[material]]\nname = \"wall\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
                [[shape]]\ntype = \"box\"\nmin = [-1.5, -1.5, -1.5]\nmax = [1.5, 1.5, 3]\nmaterial = \"wall\"\n";
    let cases = [
        (
            "sun in open fog",
            format!(
                "{}{}{sun}{CAMERA}[render]\nspp = 16\npasses = 16\nphotons = 100000\ncaustic_photons = 100000\n",
                fog(1.0, 0.05),
                white_objects(1.0)
            ),
        ),
        (
            "lamp in a fogged room",
            format!(
                "{}{}{room}{lamp}{CAMERA}[render]\nspp = 16\npasses = 16\nphotons = 100000\ncaustic_photons = 100000\n",
                fog(1.0, 0.2),
                white_objects(1.0)
            ),
        ),
    ];
    for (name, text) in cases {
        let [path, photon_map] = BOTH.map(|k| pixels(&text, k));
        let (a, _) = mean(&path);
        let difference: Vec<f64> = photon_map.iter().zip(&path).map(|(b, a)| b - a).collect();
        let (d, sd) = mean(&difference);
        println!("{name}: path {a:.5}, photon map − path {d:.5} ± {sd:.5}");
        assert!(
            d.abs() <= 0.01 * a + 4.0 * sd,
            "{name}: path {a}, photon map − path {d} ± {sd}"
        );
    }
}

/// A white room of albedo ρ = 0.5, a sphere of radius 1 (area A = 4π), lit by a light at its
/// centre: the camera, also at the centre, sees each wall point at distance 1 square on, lit
/// directly by the light's intensity I(ω) toward it and by the walls' first bounce, the same
/// everywhere in a sphere, and the bounces after it: L(ω) = (ρ/π) (I(ω) + ρΦ/(A(1 − ρ))), Φ
/// the light's power. A point light (I = 1), a spot (cone 60°, falloff from 40°) and an LED
/// (I₀ cos² θ) — against the closed form at each pixel's centre, image means within 1 %.
#[test]
fn lights_in_a_white_spherical_room_light_it_as_an_integrating_sphere_does() {
    let rho = 0.5;
    let room = crate::common::white_spherical_room(rho, [0.0, -0.3, -1.0]);
    let (cos_in, cos_out) = (40f64.to_radians().cos(), 60f64.to_radians().cos());
    let smooth = move |c: f64| {
        let t = ((c - cos_out) / (cos_in - cos_out)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    let down = DVec3::new(0.0, -1.0, 0.0);
    let led_axis = DVec3::new(0.0, -0.3, -1.0).normalize();
    // The power by quadrature over cos θ (a million midpoints).
    let power = |f: &dyn Fn(f64) -> f64| {
        let n = 1_000_000;
        2.0 * PI
            * (0..n)
                .map(|i| f(-1.0 + 2.0 * (i as f64 + 0.5) / n as f64))
                .sum::<f64>()
            * 2.0
            / n as f64
    };
    type Intensity = Box<dyn Fn(DVec3) -> f64>;
    let cases: [(&str, String, Intensity, f64); 3] = [
        (
            "point",
            "[[light]]\ntype = \"point\"\nposition = [0, 0, 0]\nintensity = [1, 1, 1]\n".into(),
            Box::new(|_| 1.0),
            4.0 * PI,
        ),
        (
            "spot",
            "[[light]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, -1, 0]\n\
             intensity = [1, 1, 1]\ncone_deg = 60\nfalloff_deg = 40\n"
                .into(),
            Box::new(move |w: DVec3| smooth(w.dot(down))),
            power(&smooth),
        ),
        (
            "led",
            format!(
                "[[light]]\ntype = \"led\"\ncenter = [0, 0, 0]\nnormal = [{}, {}, {}]\n\
                 radius = 1e-4\npower = 2.0943951023931953\nm = 2\n",
                led_axis.x, led_axis.y, led_axis.z
            ),
            // I₀ = P (m + 1)/(2π) = 1 for P = 2π/3.
            Box::new(move |w: DVec3| w.dot(led_axis).max(0.0).powi(2)),
            2.0 * PI / 3.0,
        ),
    ];
    let (scene, _) = parse_scene(Path::new("room.toml"), format!("{room}{}", cases[0].1)).unwrap();
    let camera = scene.camera.as_ref().unwrap();
    for (name, light, intensity, phi) in &cases {
        let text = format!("{room}{light}");
        let bounced = rho * phi / (4.0 * PI * (1.0 - rho));
        let (w, h) = (camera.width as usize, camera.height as usize);
        let expected: f64 = (0..w * h)
            .map(|i| {
                let d = camera.direction((i % w) as u32, (i / w) as u32, 0.5, 0.5);
                rho / PI * (intensity(d) + bounced)
            })
            .sum::<f64>()
            / (w * h) as f64;
        both_integrators_read(name, &text, expected);
    }
}

/// Sixteen point lights of intensities 0.02 to 1 W/sr scattered through the white spherical
/// room (radius 1, albedo ρ = 0.5): the camera at its centre sees a wall point x (unit normal
/// −x) lit directly by Σ I_l cos θ_l / d_l² and by the walls' bounces, ρΦ/(A(1 − ρ)) for the
/// lights' total power Φ = 4π Σ I_l wherever they are — each vertex's light sample goes to one
/// light drawn by its irradiance bound, so this is the light sampler's unbiasedness, pixel by
/// pixel against the closed form, image mean within 1 %.
#[test]
fn many_lights_in_a_white_spherical_room_light_it_as_an_integrating_sphere_does() {
    let rho = 0.5;
    let lights: Vec<(DVec3, f64)> = (0..16)
        .map(|k| {
            let t = k as f64;
            // Scattered directions, 0.2 to 0.65 from the centre: inside the room.
            let p = DVec3::new(
                (2.4 * t).sin(),
                (1.7 * t + 0.5).cos(),
                (0.9 * t + 1.0).sin(),
            )
            .normalize()
                * (0.2 + 0.03 * t);
            (p, 0.02 * 50f64.powf(((k * 7) % 16) as f64 / 15.0))
        })
        .collect();
    let mut text = crate::common::white_spherical_room(rho, [0.0, -0.3, -1.0]);
    for (p, i) in &lights {
        text += &format!(
            "[[light]]\ntype = \"point\"\nposition = [{}, {}, {}]\nintensity = [{i}, {i}, {i}]\n",
            p.x, p.y, p.z
        );
    }
    let (scene, _) = parse_scene(Path::new("room.toml"), text.clone()).unwrap();
    let camera = scene.camera.as_ref().unwrap();
    let phi: f64 = lights.iter().map(|(_, i)| 4.0 * PI * i).sum();
    let bounced = rho * phi / (4.0 * PI * (1.0 - rho));
    let (w, h) = (camera.width as usize, camera.height as usize);
    let expected: f64 = (0..w * h)
        .map(|k| {
            let x = camera.direction((k % w) as u32, (k / w) as u32, 0.5, 0.5);
            let direct: f64 = lights
                .iter()
                .map(|(q, i)| {
                    let to = *q - x;
                    i * to.dot(-x).max(0.0) / to.length().powi(3)
                })
                .sum();
            rho / PI * (direct + bounced)
        })
        .sum::<f64>()
        / (w * h) as f64;
    both_integrators_read("sixteen point lights", &text, expected);
}

/// A thin pane (a window of index 1.5, tilted 50° about x) filling the view under a uniform
/// sky: whatever it reflects or passes is the sky, so every path reads 1 — exactly (1e-6, f32
/// pixels) in vacuum, by both integrators — and in open conservative fog of index 1.33 around
/// it (the pane's index relative to the fog's 1.128) n² within 1 %. Light the pane lost or
/// made would show in every pixel.
#[test]
fn a_thin_pane_under_a_uniform_sky_keeps_its_radiance() {
    let (s, c) = 50f64.to_radians().sin_cos();
    let corner = |x: f64, y: f64| format!("[{x}, {}, {}]", y * c, 1.0 + y * s);
    let pane = format!(
        "[[material]]\nname = \"pane\"\ntype = \"thin_dielectric\"\nior = 1.5\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"pane\"\nvertices = [{}, {}, {}, {}]\n\
         [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n\
         [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, 1]\nfov_y_deg = 30\nwidth = 16\nheight = 16\n\
         [render]\nspp = 4\npasses = 2\nphotons = 20000\ncaustic_photons = 20000\n",
        corner(-2.0, -2.0),
        corner(2.0, -2.0),
        corner(2.0, 2.0),
        corner(-2.0, 2.0),
    );
    for integrator in BOTH {
        let values = pixels(&pane, integrator);
        let worst = values.iter().map(|v| (v - 1.0).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-6, "{integrator:?}: a pixel off by {worst}");
    }
    let foggy = pane.replace(
        "spp = 4\npasses = 2\nphotons = 20000",
        "spp = 16\npasses = 8\nphotons = 50000",
    );
    both_integrators_read(
        "pane in fog",
        &format!("{}{foggy}", fog(1.33, 0.05)),
        1.33 * 1.33,
    );
}
