//! The integrator seam: the path tracer as an independent reference for the photon mapper
//! (on the Cornell boxes against Mitsuba and on a GRIN scene), and passes rendered apart and
//! merged against the same passes rendered at once.

use crate::common::agreement::{agreement, Agreement};
use grinlight::compare::{mean_ratios, read_exr_layer, MeanRatios};
use grinlight::film::Film;
use grinlight::integrator::PhotonMapper;
use grinlight::render::{render_with, Passes};
use grinlight::scene::{load_scene, Scene};
use grinlight::settings::IntegratorKind as Kind;
use grinlight::settings::Settings;
use grinlight::transport::Tracer;
use std::path::Path;

fn render((scene, settings): &(Scene, Settings)) -> Film {
    grinlight::render::render(scene, settings, &()).unwrap().0
}

/// `scene` at `width` × `width` (square scenes only) with `kind`.
fn load(path: &str, width: u32, kind: Kind) -> (Scene, Settings) {
    let (mut scene, mut settings) = load_scene(Path::new(path)).unwrap();
    let camera = scene.camera.as_mut().unwrap();
    (camera.width, camera.height) = (width, width * camera.height / camera.width);
    settings.integrator = kind;
    (scene, settings)
}

/// The path tracer on `scenes/cornell_diffuse.toml` at 128 × 128, 128 spp, against the Mitsuba
/// reference (averaged 2 × 2): the same bars as the photon mapper's test — mean ratio within
/// 1 %, every 16 × 16 block within 3 % (its noise per block at 128 spp is ≈ 0.6 %, the worst
/// of 64 about 3σ) — and against the photon mapper's render of the same view, blocks within
/// 3 % (the photon mapper's k-nearest bias in the corners is ~2 %).
#[test]
fn path_tracer_matches_the_reference_and_the_photon_mapper_on_the_cornell_box() {
    let mut pt = load("scenes/cornell_diffuse.toml", 128, Kind::Path);
    pt.1.spp = 128;
    let film = render(&pt);
    let beauty = film.layer("beauty").unwrap();
    let reference = read_exr_layer(Path::new("refs/cornell_diffuse.reference.exr"), None).unwrap();
    let reference = reference.downsample(reference.width / 128).pixels;
    let MeanRatios { overall, blocks } = mean_ratios(&beauty, &reference, 128, 16);
    let worst = blocks.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    println!("path tracer vs Mitsuba: mean ratio {overall:.4}, worst block {worst:.4}");
    assert!((overall - 1.0).abs() < 0.01 && worst < 0.03);
    let mut pm = load("scenes/cornell_diffuse.toml", 128, Kind::PhotonMap);
    (pm.1.spp, pm.1.photons.global) = (16, 400_000);
    let pm_beauty = render(&pm).layer("beauty").unwrap();
    let MeanRatios { overall, blocks } = mean_ratios(&beauty, &pm_beauty, 128, 16);
    let worst = blocks.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    println!("path tracer vs photon mapper: mean ratio {overall:.4}, worst block {worst:.4}");
    assert!((overall - 1.0).abs() < 0.01 && worst < 0.03);
}

/// A GRIN scene both integrators render fully: `scenes/luneburg.toml` with its parallel beam
/// replaced by a large quad light behind the lens (the path tracer cannot find a delta
/// light's caustic), the wall moved 2 units behind the lens and the camera between them, so
/// the light the lens bends reaches the wall and floor the camera sees (80 × 60 pixels).
/// The path tracer (256 spp) is the reference: unbiased, with noise ≈ 0.3 % of the image
/// mean and ≈ 1 % of the floor's (its last 10 rows). The photon mapper's estimates are biased
/// by their kernels where light is concentrated or a surface ends (the lens' caustic light
/// on the floor near the camera, the floor's corner with the wall): measured at 2 passes,
/// image 0.988 and floor 0.974 of the path tracer with 4·10⁵ caustic photons per pass, image
/// 0.996 and floor 0.975 with 8·10⁶. Bars: the image within 1.5 % at 8·10⁶, the floor within
/// 5 % at both.
#[test]
fn photon_mapper_agrees_with_the_path_tracer_through_a_luneburg_lens() {
    let scene = |kind: Kind| {
        let text = std::fs::read_to_string("scenes/luneburg.toml").unwrap();
        let edited = [
            ("[[-2.0, -0.6, -0.55], [2.0, -0.6, -0.55], [2.0, 1.6, -0.55], [-2.0, 1.6, -0.55]]", "[[-2.0, -0.6, -2.0], [2.0, -0.6, -2.0], [2.0, 1.6, -2.0], [-2.0, 1.6, -2.0]]"),
            ("[[-2.0, -0.6, -0.55], [-2.0, -0.6, 3.0], [2.0, -0.6, 3.0], [2.0, -0.6, -0.55]]", "[[-2.0, -0.6, -2.0], [-2.0, -0.6, 3.0], [2.0, -0.6, 3.0], [2.0, -0.6, -2.0]]"),
            ("type = \"directional\"\ndirection = [0.0, -0.3, -1.0]\nirradiance = [3.0, 3.0, 3.0]", "type = \"quad\"\nvertices = [[-3, -1.5, 9], [-3, 1.5, 9], [3, 1.5, 9], [3, -1.5, 9]]\nradiance = [2.0, 2.0, 2.0]"),
            ("position = [1.2, 0.5, 2.4]\nlook_at = [0.0, 0.0, 0.0]\nfov_y_deg = 35.0\nwidth = 400\nheight = 300", "position = [0.3, 0.2, -0.8]\nlook_at = [0.0, 0.0, -2.0]\nfov_y_deg = 60.0\nwidth = 80\nheight = 60"),
        ]
        .iter()
        .fold(text, |t, (from, to)| {
            assert!(t.contains(from), "{from}");
            t.replace(from, to)
        });
        let (scene, mut settings) =
            grinlight::scene::load::parse_scene(Path::new("scenes/luneburg.toml"), edited).unwrap();
        settings.integrator = kind;
        (scene, settings)
    };
    let mut pt = scene(Kind::Path);
    pt.1.spp = 256;
    let reference = render(&pt).layer("beauty").unwrap();
    let means = |plane: &[[f32; 3]]| {
        let mean = |rows: std::ops::Range<usize>| {
            rows.clone()
                .flat_map(|y| plane[y * 80..(y + 1) * 80].iter())
                .map(|p| p.iter().map(|&c| c as f64).sum::<f64>())
                .sum::<f64>()
                / (rows.len() * 80) as f64
        };
        (mean(0..60), mean(50..60))
    };
    let (image, floor) = means(&reference);
    let mut ratios = Vec::new();
    for caustic in [400_000, 8_000_000] {
        let mut pm = scene(Kind::PhotonMap);
        (pm.1.spp, pm.1.passes) = (16, 2);
        (pm.1.photons.global, pm.1.photons.caustic) = (200_000, caustic);
        let (i, f) = means(&render(&pm).layer("beauty").unwrap());
        println!("{caustic} caustic photons per pass: photon mapper / path tracer: image {:.4}, floor {:.4}", i / image, f / floor);
        ratios.push((i / image, f / floor));
    }
    assert!((ratios[1].0 - 1.0).abs() < 0.015, "image {}", ratios[1].0);
    assert!(
        ratios.iter().all(|r| (r.1 - 1.0).abs() < 0.05),
        "floor {ratios:?}"
    );
}

/// Passes rendered apart and merged equal the same passes rendered at once: the photon
/// mapper's passes are independent (streams keyed by the pass, the caustic radius a schedule
/// of the pass index), and a film holds fixed-point sums and counts: the films are equal to
/// the bit (with f64 sums they agreed only to rounding, the sums added in another order).
#[test]
fn passes_rendered_apart_merge_into_the_same_film() {
    let (mut scene, mut settings) = load_scene(Path::new("scenes/cornell_caustic.toml")).unwrap();
    let camera = scene.camera.as_mut().unwrap();
    (camera.width, camera.height) = (40, 30);
    (
        settings.spp,
        settings.photons.global,
        settings.photons.caustic,
    ) = (2, 20_000, 20_000);
    let tracer = Tracer::new(&scene, &settings.trace);
    let integrator = PhotonMapper::new(&tracer, &settings);
    let run = |first, count| {
        render_with(
            &integrator,
            &tracer,
            &settings,
            Passes {
                first,
                count,
                earlier: None,
            },
            &(),
        )
        .unwrap()
        .0
    };
    let whole = run(0, 4);
    let mut merged = run(0, 1);
    merged.merge(&run(1, 2)).unwrap();
    merged.merge(&run(3, 1)).unwrap();
    assert!(whole.counts().iter().all(|&c| c == 8));
    // The film's sums are fixed-point: merged in any grouping they are the same to the bit.
    assert_eq!(whole, merged);
    // Films of another size or other layers are refused.
    let other = Film::new(4, 3, &whole.layers);
    assert!(merged.clone().merge(&other).is_err());
}

/// A caustic does not leak through a thin wall: a glass ball focuses a light onto the floor
/// beside a wall standing on it, and the floor on the wall's other side — which no light
/// reaches — reads no caustic light, although its estimate's radius (0.5) takes in the
/// focus 0.35 away behind the wall. Exactly zero: a photon read through the wall would make
/// it positive.
#[test]
fn a_caustic_does_not_leak_through_a_thin_wall() {
    let text = "[camera]\nposition = [0.3, 1.5, 0]\nlook_at = [0.3, 0, 0]\nup = [0, 0, -1]\n\
                fov_y_deg = 20\nwidth = 24\nheight = 24\n\
                [render]\nspp = 4\ngather = 0\nphotons = 0\ncaustic_photons = 200000\n\
                radius = 0.5\n\
                [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\
                [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\
                [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                vertices = [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]\n\
                [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                vertices = [[0, 0, -2], [0, 3, -2], [0, 3, 2], [0, 0, 2]]\n\
                [[shape]]\ntype = \"sphere\"\ncenter = [-0.35, 0.3, 0]\nradius = 0.25\n\
                material = \"glass\"\n\
                [[light]]\ntype = \"quad\"\nradiance = [50, 50, 50]\n\
                vertices = [[-0.45, 2, -0.1], [-0.25, 2, -0.1], [-0.25, 2, 0.1], [-0.45, 2, 0.1]]\n";
    let (scene, settings) =
        grinlight::scene::load::parse_scene(Path::new("wall.toml"), text.to_string()).unwrap();
    let film = render(&(scene, settings));
    let caustic = film.layer("caustic").unwrap();
    let brightest = caustic.iter().flatten().fold(0.0f32, |m, &v| m.max(v));
    assert_eq!(brightest, 0.0, "caustic light read through the wall");
}

/// Sphere lights (`scenes/mitsuba/sphere_lights.xml`: two emitting spheres over two diffuse
/// balls and a floor, 64 × 64) in both integrators: the light the surfaces send (the image
/// less the `emitted` layer, the spheres seen directly, which both integrators take from the
/// same camera ray and whose silhouettes' coverage noise — a radiance of 40 on a pixel's edge —
/// would dominate a block). The path tracer (512 spp) is the reference — itself held against
/// Mitsuba by `import.rs` — and the photon mapper's must agree within 1 % over the image and
/// 2 % on every 16 × 16 block (measured: 0.16 % and at worst 0.5 %; the path tracer's noise a
/// block is ≈ 0.3 %, and the photon mapper's kernels are biased by up to 2 % where light
/// changes fast, as in the Cornell box's corners).
#[test]
fn photon_mapper_agrees_with_the_path_tracer_under_sphere_lights() {
    let load = |kind: Kind| {
        let (description, mut settings) = grinlight::import::load_description(
            Path::new("scenes/mitsuba/sphere_lights.xml"),
            &Default::default(),
        )
        .unwrap();
        settings.integrator = kind;
        (description.build(), settings)
    };
    let reflected = |film: Film| -> Vec<[f32; 3]> {
        let (beauty, emitted) = (
            film.layer("beauty").unwrap(),
            film.layer("emitted").unwrap(),
        );
        beauty
            .iter()
            .zip(&emitted)
            .map(|(b, e)| [0, 1, 2].map(|c| b[c] - e[c]))
            .collect()
    };
    let mut pt = load(Kind::Path);
    pt.1.spp = 512;
    let reference = reflected(render(&pt));
    let mut pm = load(Kind::PhotonMap);
    (pm.1.spp, pm.1.passes) = (64, 4);
    let beauty = reflected(render(&pm));
    let MeanRatios { overall, blocks } = mean_ratios(&beauty, &reference, 64, 16);
    let worst = blocks.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    println!(
        "sphere lights, photon mapper / path tracer: image {overall:.4}, worst block {worst:.4}"
    );
    assert!((overall - 1.0).abs() < 0.01, "image {overall}");
    assert!(worst < 0.02, "worst block {worst}");
}

/// A spot light behind a frosted glass ball (`scenes/mitsuba/frosted_spot.xml`: GGX α = 0.3,
/// n = 1.3, a fog inside that absorbs and scatters by colour) over a floor: its light reaches
/// the camera and the floor only through the rough glass. The path tracer finds it by light
/// samples from the glass's far side (a delta light no direction sample can hit) at the glass
/// and beyond it; the photon mapper by photons refracted through the glass (on the floor, and
/// in the fog: its volume caustic), and by the same light samples at the glass where no
/// volume photon stands for them. The image and every 16 × 16 block within 4 standard errors
/// (each film's `error` layer, from the spread of its 8 passes); 0.18.0's path tracer read 0
/// and its photon mapper counted the fog's light through the glass twice.
#[test]
fn a_spot_light_through_frosted_glass_lights_both_integrators_alike() {
    let load = |kind: Kind, spp: u32| {
        let (description, mut settings) = grinlight::import::load_description(
            Path::new("scenes/mitsuba/frosted_spot.xml"),
            &Default::default(),
        )
        .unwrap();
        settings.integrator = kind;
        (settings.spp, settings.passes) = (spp, 8);
        render(&(description.build(), settings))
    };
    let (pt, pm) = (load(Kind::Path, 64), load(Kind::PhotonMap, 16));
    let Agreement {
        ratio: overall,
        z,
        worst,
    } = agreement(&pt, &pm, 48, 16);
    println!(
        "frosted spot, photon mapper / path tracer: image {overall:.4} (z {z:.2}), largest block z {worst:.2}"
    );
    assert!(z < 4.0, "image {overall}: {z:.2} standard errors");
    assert!(worst < 4.0, "a block differs by {worst:.2} standard errors");
}

/// Point lights beyond frosted glass whose far side is a gradient medium, or seen from inside
/// one: a frosted ball (GGX α = 0.3) of index 1.3 holding a point light at its centre, a second
/// point light outside beside it, a floor. The ball's inside once of uniform index and once a
/// linear medium of gradient 10⁻⁶ (a curved medium to the renderer, straight to 10⁻⁶ along the
/// ball): the two images agree within 4 standard errors, as a whole and by 8 × 8 block, with
/// both integrators. A delta light is found by no direction sample; its light reaches the
/// glass by the light sample that connects to it through the glass — curved from the far side
/// into the gradient medium, straight out of it — which the light samples once left out
/// (0.20.0 rendered the gradient ball's glow, and the outer light through it, black).
#[test]
fn point_lights_through_frosted_glass_reach_into_and_out_of_a_gradient_medium() {
    let scene = |profile: &str| {
        format!(
            r#"
[camera]
position = [0.0, 0.4, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_y_deg = 40.0
width = 32
height = 32

[render]
max_depth = 16

[[medium]]
name = "inside"
{profile}

[[material]]
name = "frosted"
type = "dielectric"
interior = "inside"
roughness = 0.3

[[material]]
name = "floor"
type = "diffuse"
albedo = [0.7, 0.7, 0.7]

[[shape]]
type = "sphere"
center = [0.0, 0.0, 0.0]
radius = 0.5
material = "frosted"

[[shape]]
type = "quad"
vertices = [[-3.0, -0.5, -3.0], [-3.0, -0.5, 3.0], [3.0, -0.5, 3.0], [3.0, -0.5, -3.0]]
material = "floor"

[[light]]
type = "point"
position = [0.0, 0.0, 0.0]
intensity = 2.0

[[light]]
type = "point"
position = [-0.9, 0.3, -0.6]
intensity = 2.0
"#
        )
    };
    let uniform = scene("profile = \"uniform\"\nn = 1.3");
    let graded = scene("profile = \"linear\"\nn0 = 1.3\ngradient = [0.0, 1e-6, 0.0]");
    let path = Path::new("frosted_point_lights.toml");
    for kind in [Kind::Path, Kind::PhotonMap] {
        let film = |text: &str| {
            let (scene, mut settings) =
                grinlight::scene::load::parse_scene(path, text.to_string()).unwrap();
            settings.integrator = kind;
            (settings.spp, settings.passes) = (64, 8);
            (settings.photons.global, settings.photons.caustic) = (100_000, 100_000);
            render(&(scene, settings))
        };
        let Agreement { ratio, z, worst } = agreement(&film(&uniform), &film(&graded), 32, 8);
        println!(
            "{kind:?}: gradient / uniform ball {ratio:.4} (z {z:.2}), largest block z {worst:.2}"
        );
        assert!(z < 4.0, "{kind:?}: image {ratio}: {z:.2} standard errors");
        assert!(
            worst < 4.0,
            "{kind:?}: a block differs by {worst:.2} standard errors"
        );
    }
}

/// A BSDF or phase ray of the direct estimate whose straight line meets no area light is left
/// untraced where the tracer finds emission only along straight lines
/// (`Tracer::emission_on_lines`: no environment, no gradient medium). At 2000 points of the
/// fogged Cornell box's fog, some a few millimetres under its lamp, the direct light is the
/// same to the bit with and without the shortcut (same random numbers: the chain it skips
/// draws none), and most phase rays take the shortcut. A scene with a sky, a gradient medium
/// or 64 lights does not take it.
#[test]
fn a_direction_sample_left_untraced_changes_no_direct_light() {
    use glam::DVec3;
    use grinlight::transport::chain::{Carried, Ray};
    use grinlight::transport::lighting::{direct_light, may_find_emission, Radiance};
    use grinlight::transport::{MediumVertex, Stats, Vertex};
    use rand::{Rng, SeedableRng};
    let (scene, settings) = load_scene(Path::new("bench/cornell_fog.toml")).unwrap();
    let tracer = Tracer::new(&scene, &settings.trace);
    assert!(tracer.emission_on_lines);
    let mut traced = Tracer::new(&scene, &settings.trace);
    traced.emission_on_lines = false;
    let fog = scene.ambient().unwrap();
    let phase = tracer.scattering(fog).unwrap().phase;
    let mut draw = rand_pcg::Pcg64::seed_from_u64(7);
    let (mut lit, mut missed) = (0, 0);
    for i in 0..2000 {
        let mut p = DVec3::new(draw.gen(), draw.gen(), draw.gen()) * 1.98 - 0.99;
        if i % 4 == 0 {
            // Just under the lamp (x, z in [-0.25, 0.25] at y = 0.999).
            p = DVec3::new(0.6 * p.x, 0.995, 0.6 * p.z);
        }
        let wo = DVec3::new(draw.gen(), draw.gen(), draw.gen()) * 2.0 - 1.0;
        let vertex = Vertex::Medium(MediumVertex {
            position: p,
            wo: wo.normalize(),
            medium: Some(fog),
            phase,
        });
        let estimate = |t: &Tracer| {
            let mut rng = rand_pcg::Pcg64::seed_from_u64(i);
            let light = direct_light(
                Carried::on(t),
                &vertex,
                &Radiance,
                &mut rng,
                &mut Stats::default(),
            );
            (light, rng.gen::<u64>())
        };
        let (shortcut, full) = (estimate(&tracer), estimate(&traced));
        assert_eq!(
            shortcut.0 .0.to_array().map(f64::to_bits),
            full.0 .0.to_array().map(f64::to_bits),
            "point {p}"
        );
        assert_eq!(shortcut.1, full.1, "the random numbers drawn differ at {p}");
        lit += (shortcut.0 .0.max_element() > 0.0) as u32;
        let ray = Ray {
            origin: p,
            direction: phase.sample(-wo.normalize(), (draw.gen(), draw.gen())),
            medium: Some(fog),
        };
        missed += !may_find_emission(&tracer, &ray) as u32;
    }
    assert!(lit > 1000, "{lit} of 2000 points lit");
    assert!(missed > 1200, "{missed} of 2000 phase rays left untraced");
    for (path, why) in [
        ("scenes/heat_haze.toml", "a gradient medium and a sky"),
        ("scenes/luneburg.toml", "a gradient medium"),
        (
            "bench/many_lights.toml",
            "more lights than are looked through per sample",
        ),
    ] {
        let (scene, settings) = load_scene(Path::new(path)).unwrap();
        assert!(
            !Tracer::new(&scene, &settings.trace).emission_on_lines,
            "{path}: {why}"
        );
    }
}
