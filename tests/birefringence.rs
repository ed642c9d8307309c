// Uniaxial crystals in the transport: a calcite plate doubles a beam by its walk-off (photons
// on receivers), is lossless under a uniform sky (both integrators' camera paths), doubles an
// edge seen through it (camera paths), and bad crystal input is refused by place.

use crate::common::agreement::{agreement, Agreement};
use crate::common::mean_and_error;
use grinlight::receiver::Measurement;
use grinlight::scene::load::parse_scene;
use grinlight::settings::{IntegratorKind, Settings};
use std::path::Path;

/// Calcite at 589 nm.
const NO: f64 = 1.6584;
const NE: f64 = 1.4864;

/// The walk-off of the extraordinary ray square on a plate whose optic axis stands at `deg` to
/// the normal: tan ρ = (n_o² − n_e²) tan θ / (n_e² + n_o² tan²θ) (Born and Wolf §15.3).
fn walk_off(deg: f64) -> f64 {
    let t = deg.to_radians().tan();
    (NO * NO - NE * NE) * t / (NE * NE + NO * NO * t * t)
}

/// A calcite medium of optic axis `axis`, and its material `crystal`.
fn calcite(axis: [f64; 3]) -> String {
    let [x, y, z] = axis;
    format!(
        "[[medium]]\nname = \"calcite\"\nprofile = \"uniaxial\"\nno = {NO}\nne = {NE}\n\
         optic_axis = [{x}, {y}, {z}]\n\
         [[material]]\nname = \"crystal\"\ntype = \"dielectric\"\ninterior = \"calcite\"\n"
    )
}

/// The optic axis `deg` from +z toward +x.
fn tilted(deg: f64) -> [f64; 3] {
    let t = deg.to_radians();
    [t.sin(), 0.0, t.cos()]
}

fn measured(text: &str, photons: u64) -> Vec<Measurement> {
    let (scene, mut settings) = parse_scene(Path::new("crystal.toml"), text.into()).unwrap();
    settings.receiver_photons = photons;
    grinlight::render::measure(&scene, &settings, 0, &())
        .unwrap()
        .0
}

/// A narrow beam square on a calcite plate 2 thick, its optic axis at 45°, leaves as two
/// beams: the ordinary one straight on, the extraordinary one beside it by t·tan ρ = 0.2181
/// (walked off away from the axis's tilt in this negative crystal), both parallel to the beam.
/// Each spot's centroid lies within half a bin (5e-4) of its closed-form place (the spots are
/// narrower than a bin); the two are polarized across each other — the ordinary one along y
/// (across the plane of the beam and the axis: S1/S0 = −1 with u = x), the extraordinary one
/// along x (S1/S0 = +1) — to 1e-6 (every photon alike); and the ordinary spot carries half of
/// the light the plate passes at n_o, ½(1 − R)/(1 + R) with R = ((n_o − 1)/(n_o + 1))² (its
/// reflections inside sum on the same spot), of the open beam's flux within 4 standard errors.
#[test]
fn a_calcite_plate_doubles_a_beam_by_its_walk_off() {
    let beam = "[[light]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, 0, 1]\n\
                intensity = [1, 1, 1]\ncone_deg = 0.002\n\
                [[receiver]]\nname = \"r\"\ncenter = [-0.0995, 0, 5]\nnormal = [0, 0, 1]\n\
                up = [0, 1, 0]\nsize = [0.4, 0.01]\nbins = [400, 1]\n";
    let plate = format!(
        "{beam}{}[[shape]]\ntype = \"box\"\nmin = [-3, -3, 1]\nmax = [3, 3, 3]\n\
         material = \"crystal\"\n",
        calcite(tilted(45.0))
    );
    let photons = 100_000;
    let open = &measured(beam, photons)[0];
    let (scene, _) = parse_scene(Path::new("crystal.toml"), plate.clone()).unwrap();
    let receiver = &scene.receivers[0];
    let m = &measured(&plate, photons)[0];
    let separation = 2.0 * walk_off(45.0);
    assert!((walk_off(45.0).atan().to_degrees() - 6.22).abs() < 0.01);
    // Each spot: its flux, centroid along u and Stokes sums, from the bins near it.
    let spot = |centre: f64| {
        let (mut flux, mut moment, mut s1) = (0.0, 0.0, 0.0);
        for (bin, e) in m.irradiance.iter().enumerate() {
            // The receiver's centre lies at x = −0.0995, its u along x.
            let u = receiver.bin_center(bin).0 - 0.0995;
            if (u - centre).abs() < 0.05 {
                flux += e;
                moment += e * u;
                s1 += m.stokes[0].irradiance[bin];
            }
        }
        (flux, moment / flux, s1 / flux)
    };
    let (ordinary, extraordinary) = (spot(0.0), spot(-separation));
    println!("ordinary spot {ordinary:?}, extraordinary {extraordinary:?}, t tan ρ {separation}");
    assert!(ordinary.1.abs() < 5e-4, "{ordinary:?}");
    assert!(
        (extraordinary.1 + separation).abs() < 5e-4,
        "{extraordinary:?} against −{separation}"
    );
    assert!((ordinary.2 + 1.0).abs() < 1e-6, "{ordinary:?}");
    assert!((extraordinary.2 - 1.0).abs() < 1e-6, "{extraordinary:?}");
    let total: f64 = m.irradiance.iter().sum();
    assert!(
        (ordinary.0 + extraordinary.0) > (1.0 - 1e-3) * total,
        "what arrives lies in the two spots"
    );
    let r = ((NO - 1.0) / (NO + 1.0)).powi(2);
    let share = 0.5 * (1.0 - r) / (1.0 + r);
    let got = m.flux.0 * ordinary.0 / total;
    let want = share * open.flux.0;
    let z = (got - want).abs() / (share * open.flux.1).hypot(m.flux.1);
    println!("ordinary flux {got} against {want} (z {z:.2})");
    assert!(z < 4.0, "{got} against {want}");
}

/// The image mean of `text`'s beauty (green channel) and its standard error over the pixels.
fn image_mean(text: &str, integrator: IntegratorKind) -> (f64, f64) {
    let (scene, settings) = parse_scene(Path::new("crystal.toml"), text.into()).unwrap();
    let settings = Settings {
        integrator,
        ..settings
    };
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    let values: Vec<f64> = (film.layer("beauty").unwrap().iter())
        .map(|p| p[1] as f64)
        .collect();
    mean_and_error(&values)
}

/// A furnace: a calcite block filling the view under a uniform sky of radiance 1 reads 1 —
/// a lossless crystal in light that is the same every way, however its faces split, reflect
/// and trap it — through both integrators, within 4 standard errors over the pixels (the
/// path's splits are drawn by power, so pixels scatter about 1). Its optic axis lies oblique
/// to every face.
#[test]
fn a_calcite_block_under_a_uniform_sky_reads_the_sky() {
    let text = format!(
        "{}[camera]\nposition = [0, 0, -3]\nlook_at = [0, 0, 0]\nfov_y_deg = 20\nwidth = 24\n\
         height = 24\n[render]\nspp = 64\nmax_depth = 200\n\
         [[shape]]\ntype = \"box\"\nmin = [-1, -1.2, -1]\nmax = [1, 1.2, 1]\n\
         material = \"crystal\"\n\
         [[light]]\ntype = \"environment\"\nsky = \"uniform\"\nradiance = [1, 1, 1]\n",
        calcite([0.3, 0.5, 0.8])
    );
    for integrator in [IntegratorKind::Path, IntegratorKind::PhotonMap] {
        let (mean, se) = image_mean(&text, integrator);
        println!("{integrator:?}: {mean:.5} ± {se:.5}");
        assert!(
            (mean - 1.0).abs() < 4.0 * se,
            "{integrator:?}: {mean} ± {se}"
        );
        assert!(se < 0.01, "{integrator:?}: a test of 1 %: {se}");
    }
}

/// An edge seen through the plate twice: a glowing half-plane (x > 0, radiance 1) under a
/// calcite plate 2 thick, its axis at 45°, seen square on by an orthographic camera (pixels
/// 0.01 wide along x). The ordinary image of the edge stands at x = 0, the extraordinary one
/// at x = −t·tan ρ (light from the page walks off as the beam above does): each found where
/// the image's row profile crosses half its step, within a pixel. Between the two edges only
/// the extraordinary light arrives, polarized along x (S1/S0 = 1 to 1e-6, every path alike);
/// beyond both, the ordinary light adds ½(1 − R)/(1 + R) of the page's radiance (camera paths
/// reciprocal to the beam's photons) within 4 standard errors, polarized along y.
#[test]
fn an_edge_seen_through_the_plate_is_doubled_by_the_walk_off() {
    let text = format!(
        "{}[camera]\nprojection = \"orthographic\"\nposition = [-0.1, 0, 5]\n\
         look_at = [-0.1, 0, 0]\nview_height = 0.1\nwidth = 100\nheight = 10\n\
         [render]\nspp = 256\nstokes = true\nintegrator = \"path\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-3, -3, 0.01]\nmax = [3, 3, 2.01]\n\
         material = \"crystal\"\n\
         [[light]]\ntype = \"quad\"\nvertices = [[0, -1, 0], [2, -1, 0], [2, 1, 0], [0, 1, 0]]\n\
         radiance = [1, 1, 1]\n",
        calcite(tilted(45.0))
    );
    let (scene, settings) = parse_scene(Path::new("crystal.toml"), text).unwrap();
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    let (width, height) = (100, 10);
    // Per column: the mean over the rows of S0 and S1, and the spread of S0 over them.
    let columns = |layer: &str| -> Vec<(f64, f64)> {
        let pixels = film.layer(layer).unwrap();
        (0..width)
            .map(|x| {
                let values: Vec<f64> = (0..height)
                    .map(|y| pixels[y * width + x][1] as f64)
                    .collect();
                mean_and_error(&values)
            })
            .collect()
    };
    let (s0, s1) = (columns("beauty"), columns("S1"));
    // Column c's centre lies at x = −0.6 + 0.01 (c + ½).
    let x = |c: usize| -0.6 + 0.01 * (c as f64 + 0.5);
    let separation = 2.0 * walk_off(45.0);
    let mean_over = |lo: f64, hi: f64, of: &[(f64, f64)]| {
        let picked: Vec<&(f64, f64)> = (0..width)
            .filter(|&c| x(c) > lo + 0.02 && x(c) < hi - 0.02)
            .map(|c| &of[c])
            .collect();
        let n = picked.len() as f64;
        let mean = picked.iter().map(|p| p.0).sum::<f64>() / n;
        let se = picked.iter().map(|p| p.1 * p.1).sum::<f64>().sqrt() / n;
        (mean, se)
    };
    let dark = mean_over(-0.6, -separation, &s0);
    let extraordinary = mean_over(-separation, 0.0, &s0);
    let both = mean_over(0.0, 0.4, &s0);
    println!("dark {dark:?}, extraordinary only {extraordinary:?}, both {both:?}");
    assert_eq!(
        dark.0, 0.0,
        "nothing reaches the camera from beyond both images"
    );
    // Where the profile crosses half of each step (linear between column centres).
    let crossing = |from: usize, level: f64| -> f64 {
        let c = (from..width - 1)
            .find(|&c| (s0[c].0 - level) * (s0[c + 1].0 - level) <= 0.0)
            .unwrap();
        let t = (level - s0[c].0) / (s0[c + 1].0 - s0[c].0);
        x(c) + 0.01 * t
    };
    let first = crossing(0, 0.5 * extraordinary.0);
    let second = crossing(
        ((-0.5 * separation + 0.6) / 0.01) as usize,
        0.5 * (extraordinary.0 + both.0),
    );
    println!(
        "edges at {first:.4} and {second:.4}: −t tan ρ = {:.4} and 0",
        -separation
    );
    assert!(
        (first + separation).abs() < 0.01,
        "{first} against −{separation}"
    );
    assert!(second.abs() < 0.01, "{second} against 0");
    let r = ((NO - 1.0) / (NO + 1.0)).powi(2);
    let ordinary = (both.0 - extraordinary.0, both.1.hypot(extraordinary.1));
    let want = 0.5 * (1.0 - r) / (1.0 + r);
    println!("ordinary light {ordinary:?} against {want}");
    assert!(
        (ordinary.0 - want).abs() < 4.0 * ordinary.1,
        "{ordinary:?} against {want}"
    );
    assert!(ordinary.1 < 0.01 * want, "a test of 1 %: {ordinary:?}");
    let polarized = mean_over(-separation, 0.0, &s1).0 / extraordinary.0;
    assert!((polarized - 1.0).abs() < 1e-6, "S1/S0 {polarized}");
    let both_s1 = mean_over(0.0, 0.4, &s1).0;
    let want_s1 = extraordinary.0 - ordinary.0;
    assert!(
        (both_s1 - want_s1).abs() < 4.0 * ordinary.1,
        "S1 {both_s1} against {want_s1}"
    );
}

/// Bad crystal input is refused by file, line and key: indices ≤ 0 or NaN, an optic axis of
/// zero length, a crystal that scatters, a rough or thin surface on one, a crystal around the
/// scene; and a camera inside a crystal by name when the render starts.
#[test]
fn bad_crystal_input_is_refused_by_place() {
    let medium =
        |keys: &str| format!("[[medium]]\nname = \"calcite\"\nprofile = \"uniaxial\"\n{keys}\n");
    let good = "no = 1.6584\nne = 1.4864\noptic_axis = [0, 0, 1]";
    let cases = [
        (
            medium("no = 1.6\nne = 0\noptic_axis = [0, 0, 1]"),
            "crystal.toml:5:",
            "ne",
        ),
        (
            medium("no = nan\nne = 1.5\noptic_axis = [0, 0, 1]"),
            "crystal.toml:4:",
            "no",
        ),
        (
            medium("no = 1.6\nne = 1.5\noptic_axis = [0, 0, 0]"),
            "crystal.toml:6:",
            "optic_axis",
        ),
        (
            medium(&format!("{good}\nscattering = 0.1")),
            "crystal.toml:7:",
            "scattering",
        ),
        (
            format!(
                "{}[[material]]\nname = \"m\"\ntype = \"dielectric\"\ninterior = \"calcite\"\n\
                 roughness = 0.1\n[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\n\
                 radius = 1\nmaterial = \"m\"\n",
                medium(good)
            ),
            "crystal.toml:16:",
            "smooth `dielectric`",
        ),
        (
            format!("ambient = \"calcite\"\n{}", medium(good)),
            "crystal.toml:1:",
            "uniaxial crystal",
        ),
    ];
    for (text, place, says) in cases {
        let error = parse_scene(Path::new("crystal.toml"), text.clone())
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"))
            .to_string();
        assert!(
            error.contains(place) && error.contains(says),
            "{text}\n→ {error}"
        );
    }
    let inside = format!(
        "{}[[material]]\nname = \"m\"\ntype = \"dielectric\"\ninterior = \"calcite\"\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n\
         [camera]\nposition = [0, 0, 0.5]\nlook_at = [0, 0, 0]\nfov_y_deg = 30\nwidth = 8\nheight = 8\n\
         [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n",
        medium(good)
    );
    let dir = std::env::temp_dir().join(format!("grinlight-crystal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("inside.toml");
    std::fs::write(&path, inside).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args(["render", path.to_str().unwrap(), "--output"])
        .arg(dir.join("inside.exr"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        said.contains("camera sits inside crystal 'calcite'"),
        "{said}"
    );
    assert!(!dir.join("inside.exr").exists(), "nothing written");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Calcite's indices by Ghosh's (1999) Sellmeier terms (n² = A + Σ Bᵢλ²/(λ² − Cᵢ), A's excess
/// over 1 written as a term of C = 0), as a scene gives them, and their values at `nm`.
const GHOSH: [(&str, [f64; 6]); 2] = [
    (
        "no",
        [
            0.73358749,
            0.96464345,
            1.82831454,
            0.0,
            1.94325203e-2,
            120.0,
        ],
    ),
    (
        "ne",
        [
            0.35859695,
            0.82427830,
            0.14429128,
            0.0,
            1.06689543e-2,
            120.0,
        ],
    ),
];

fn ghosh(terms: [f64; 6], nm: f64) -> f64 {
    let l2 = (nm * 1e-3).powi(2);
    (1.0 + (0..3)
        .map(|i| terms[i] * l2 / (l2 - terms[i + 3]))
        .sum::<f64>())
    .sqrt()
}

/// Dispersive calcite: its indices over wavelength (Ghosh's Sellmeier terms) part a narrow
/// beam's extraordinary spot by colour. A violet (400 nm) and a red (700 nm) line, each 0.5 nm
/// wide, through the plate of the first test: the ordinary spot stays at 0, the extraordinary
/// one lands at −t·tan ρ(λ) with ρ from n_o(λ), n_e(λ) — 0.2318 and 0.2149 from it (0.2181 at
/// 589 nm) — each within half a bin (5e-4).
#[test]
fn dispersive_calcite_parts_its_extraordinary_spot_by_colour() {
    let sellmeier = |(key, terms): (&str, [f64; 6])| {
        let list = terms.map(|x| x.to_string()).join(", ");
        format!("{key} = {{ sellmeier = [{list}] }}\n")
    };
    let medium = format!(
        "[[medium]]\nname = \"calcite\"\nprofile = \"uniaxial\"\n{}{}\
         optic_axis = [0.7071067811865476, 0, 0.7071067811865476]\n\
         [[material]]\nname = \"crystal\"\ntype = \"dielectric\"\ninterior = \"calcite\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-3, -3, 1]\nmax = [3, 3, 3]\nmaterial = \"crystal\"\n\
         [[receiver]]\nname = \"r\"\ncenter = [-0.0995, 0, 5]\nnormal = [0, 0, 1]\n\
         up = [0, 1, 0]\nsize = [0.4, 0.01]\nbins = [400, 1]\n",
        sellmeier(GHOSH[0]),
        sellmeier(GHOSH[1])
    );
    for nm in [400.0, 700.0] {
        let text = format!(
            "{medium}[[light]]\ntype = \"spot\"\nposition = [0, 0, 0]\ndirection = [0, 0, 1]\n\
             intensity = [1, 1, 1]\ncone_deg = 0.002\nspectrum = {{ gaussian = [{nm}, 0.5] }}\n"
        );
        let (scene, _) = parse_scene(Path::new("crystal.toml"), text.clone()).unwrap();
        let receiver = &scene.receivers[0];
        let m = &measured(&text, 20_000)[0];
        let (o, e) = (ghosh(GHOSH[0].1, nm), ghosh(GHOSH[1].1, nm));
        let separation = 2.0 * (o * o - e * e) / (e * e + o * o);
        let centroid = |centre: f64| {
            let (mut flux, mut moment) = (0.0, 0.0);
            for (bin, value) in m.irradiance.iter().enumerate() {
                let u = receiver.bin_center(bin).0 - 0.0995;
                if (u - centre).abs() < 0.008 {
                    flux += value;
                    moment += value * u;
                }
            }
            moment / flux
        };
        let (ordinary, extraordinary) = (centroid(0.0), centroid(-separation));
        println!(
            "{nm} nm: spots at {ordinary:.5} and {extraordinary:.5}, −t tan ρ {:.5}",
            -separation
        );
        assert!(ordinary.abs() < 5e-4, "{nm} nm: {ordinary}");
        assert!(
            (extraordinary + separation).abs() < 5e-4,
            "{nm} nm: {extraordinary} against −{separation}"
        );
    }
}

/// The photon mapper against the path tracer on a calcite block (axis oblique to every face)
/// on a white floor under a uniform sky: the sky's light through the crystal onto the floor
/// reaches the path tracer by bounces from the floor split at the crystal's faces, and the
/// photon mapper by photons split on their way down (its caustic map). The image and every
/// 16 × 16 block within 4 standard errors (each film's `error` layer, from the spread of its 8
/// passes). Under a small lamp the photon mapper blurs the edges of the block's caustic —
/// a plain glass block of n_o read a block 17.6 standard errors off there, the calcite 6.9 —
/// a bias of density estimation that the sky's broad caustic does not show.
#[test]
fn a_crystal_lights_a_floor_alike_in_both_integrators() {
    let text = format!(
        "{}[camera]\nposition = [0, 3, -3]\nlook_at = [0, 0.3, 0]\nfov_y_deg = 35\nwidth = 48\n\
         height = 48\n[render]\nphotons = 100000\ncaustic_photons = 200000\n\
         [[shape]]\ntype = \"box\"\nmin = [-0.6, 0.001, -0.6]\nmax = [0.6, 0.8, 0.6]\n\
         material = \"crystal\"\n\
         [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
         vertices = [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]\n\
         [[light]]\ntype = \"environment\"\nsky = \"uniform\"\n",
        calcite([0.3, 0.5, 0.8])
    );
    let film = |integrator: IntegratorKind, spp: u32| {
        let (scene, settings) = parse_scene(Path::new("crystal.toml"), text.clone()).unwrap();
        let settings = Settings {
            integrator,
            spp,
            passes: 8,
            ..settings
        };
        grinlight::render::render(&scene, &settings, &()).unwrap().0
    };
    let (pt, pm) = (
        film(IntegratorKind::Path, 64),
        film(IntegratorKind::PhotonMap, 16),
    );
    let Agreement { ratio, z, worst } = agreement(&pt, &pm, 48, 16);
    println!("crystal on a floor, photon mapper / path tracer: image {ratio:.4} (z {z:.2}), largest block z {worst:.2}");
    assert!(z < 4.0, "image {ratio}: {z:.2} standard errors");
    assert!(worst < 4.0, "a block differs by {worst:.2} standard errors");
}
