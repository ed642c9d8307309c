//! Radiometry where indices differ along a path, against closed forms: radiance across a
//! flat interface and along a GRIN path (basic radiance L/n² is conserved), the environment
//! seen from inside a medium, absorption that varies along the path, a receiver that casts
//! no shadow, a trapped ray, Tessendorf's ξ keyed per ray, and the mirage's photon-free
//! direct light against a uniform ambient.

use glam::DVec3;
use grinlight::media::{IndexSample, Medium};
use grinlight::scene::load::{parse_description, parse_scene};
use grinlight::scene::{Description, Scene};
use grinlight::settings::Settings;
use grinlight::transport::{Event, Stats, Tracer};
use std::path::Path;

fn parse(text: &str) -> (Scene, Settings) {
    parse_scene(Path::new("radiometry.toml"), text.to_string()).unwrap()
}

/// The scene of `text` as `edit` changes its description (a medium of one's own added).
fn parse_edited(text: &str, edit: impl FnOnce(&mut Description)) -> (Scene, Settings) {
    let (mut description, settings) =
        parse_description(Path::new("radiometry.toml"), text.to_string()).unwrap();
    edit(&mut description);
    (description.build(), settings)
}

fn render(scene: &(Scene, Settings)) -> grinlight::film::Film {
    grinlight::render::render(&scene.0, &scene.1, &())
        .unwrap()
        .0
}

/// Mean and standard error of the first channel of a layer.
fn mean(film: &grinlight::film::Film, layer: &str) -> (f64, f64) {
    let px: Vec<f64> = film
        .layer(layer)
        .unwrap()
        .iter()
        .map(|p| p[0] as f64)
        .collect();
    let n = px.len() as f64;
    let m = px.iter().sum::<f64>() / n;
    let var = px.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (var / n).sqrt())
}

/// A camera 1 unit below the top face of a glass (or water) box, looking straight up through
/// it at an emitter of radiance 1 in air that fills the view; or the mirror case, the camera
/// in air looking down into the box at an emitter inside it.
fn interface_scene(n: f64, camera_inside: bool) -> String {
    let (camera, look, emitter_y, normal_down) = if camera_inside {
        ("[0, -1, 0]", "[0, 1, 0]", 2.0, true)
    } else {
        ("[0, 2, 0]", "[0, -1, 0]", -1.5, false)
    };
    // The emitter's normal must point at the camera: vertices ordered accordingly.
    let quad = if normal_down {
        format!(
            "[[-50, {y}, -50], [50, {y}, -50], [50, {y}, 50], [-50, {y}, 50]]",
            y = emitter_y
        )
    } else {
        format!(
            "[[-50, {y}, -50], [-50, {y}, 50], [50, {y}, 50], [50, {y}, -50]]",
            y = emitter_y
        )
    };
    format!(
        "[camera]\nposition = {camera}\nlook_at = {look}\nup = [0, 0, 1]\nfov_y_deg = 2\nwidth = 8\nheight = 8\n\
         [render]\nspp = 256\ngather = 0\nphotons = 0\ncaustic_photons = 0\n\
         [[material]]\nname = \"water\"\ntype = \"dielectric\"\nior = {n}\n\
         [[shape]]\ntype = \"box\"\nmin = [-100, -100, -100]\nmax = [100, 0, 100]\nmaterial = \"water\"\n\
         [[light]]\ntype = \"quad\"\nvertices = {quad}\nradiance = 1\n"
    )
}

/// Radiance seen through a flat interface at normal incidence: T·(n_camera/n_emitter)² L,
/// T = 1 − R, R = ((n − 1)/(n + 1))². Under water (n = 1.333) the emitter in air is
/// 1.777·T/(1 − R²) = 1.742 times as bright as in air (the 1/(1 − R²) of light reflected
/// back up by the box's far bottom face, +4e-4); seen from air, an emitter under water is
/// T/1.777 as bright. Before radiance was scaled across indices both came out T (the camera
/// path's weight was 1 through every refraction). The Fresnel choice is sampled, so each
/// sample is 0 or the full ratio; the mean of 16384 samples is within 4 standard errors.
#[test]
fn radiance_through_a_flat_interface_scales_with_the_index_ratio_squared() {
    let n = 1.333f64;
    let r = ((n - 1.0) / (n + 1.0)).powi(2);
    let t = 1.0 - r;
    for (inside, want) in [(true, t * n * n / (1.0 - r * r)), (false, t / (n * n))] {
        let scene = parse(&interface_scene(n, inside));
        let tracer = Tracer::new(&scene.0, &scene.1.trace);
        assert_eq!(
            tracer.camera_medium.is_some(),
            inside,
            "the camera's medium is found by point-in-shape"
        );
        let (m, se) = mean(&render(&scene), "emitted");
        println!("camera inside {inside}: {m:.5} ± {se:.5}, want {want:.5}");
        assert!((m - want).abs() < 4.0 * se, "{m} ± {se} vs {want}");
    }
}

/// A medium of one's own: n = n0 exp(g·y) (g may be 0).
struct Graded {
    n0: f64,
    g: f64,
}

impl Medium for Graded {
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let n = self.n0 * (self.g * p.y).exp();
        Some(IndexSample {
            n,
            grad: DVec3::new(0.0, self.g * n, 0.0),
        })
    }
    fn step_hint(&self, _p: DVec3, _dir: DVec3) -> f64 {
        f64::INFINITY
    }
    fn is_uniform(&self) -> bool {
        self.g == 0.0
    }
}

/// Along a curved path (camera looking straight up along ∇n in n = exp(0.2 y), so the ray
/// runs straight) the radiance of an emitter at height 3 reaches the camera at height 0 as
/// (n(0)/n(3))² L = e^{−1.2} L: basic radiance L/n² is invariant. Deterministic (no sampling
/// on the way); the film's f32 bounds the tolerance, 1e-6 relative.
#[test]
fn basic_radiance_is_invariant_along_a_grin_path() {
    let scene = parse_edited(
        "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 1, 0]\nup = [0, 0, 1]\nfov_y_deg = 0.5\nwidth = 4\nheight = 4\n\
         [render]\nspp = 1\ngather = 0\nphotons = 0\ncaustic_photons = 0\nworld_radius = 100\n\
         [[light]]\ntype = \"quad\"\nvertices = [[-5, 3, -5], [5, 3, -5], [5, 3, 5], [-5, 3, 5]]\nradiance = 2\n",
        |d| d.ambient = Some(d.media.add("graded", Box::new(Graded { n0: 1.0, g: 0.2 }))),
    );
    let film = render(&scene);
    let want = 2.0 * (-1.2f64).exp();
    for p in film.layer("emitted").unwrap() {
        assert!(
            (p[0] as f64 / want - 1.0).abs() < 1e-6,
            "{} vs {want}",
            p[0]
        );
    }
}

/// The environment is given as in vacuum: a camera in a uniform ambient of index 1.5 sees a
/// sky of radiance 1 as 1.5² = 2.25 (exact, no sampling).
#[test]
fn the_environment_seen_from_inside_a_medium_is_n_squared_brighter() {
    let dir = std::env::temp_dir().join(format!("grinlight-rad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    exr::prelude::write_rgb_file(dir.join("sky.exr"), 8, 4, |_, _| (1.0f32, 1.0f32, 1.0f32))
        .unwrap();
    let text = "ambient = \"glass\"\n\
                [camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\nfov_y_deg = 30\nwidth = 4\nheight = 4\n\
                [render]\nspp = 1\n\
                [[medium]]\nname = \"glass\"\nprofile = \"uniform\"\nn = 1.5\n\
                [[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\n";
    let scene = parse_scene(&dir.join("s.toml"), text.to_string()).unwrap();
    let film = render(&scene);
    for p in film.layer("emitted").unwrap() {
        assert!((p[0] as f64 - 2.25).abs() < 1e-6, "{}", p[0]);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Absorption is the integral of σa along the path, not σa at the origin times the length:
/// σa = 0.3 + 0.05 x, a density linear in x (trilinear interpolation reproduces it exactly).
/// Straight (uniform n = 1.2) to the world sphere of radius R = 5 along −x from x = 2:
/// ∫ (0.3 + 0.05 x) dx over [−3, 2] = 1.375, exact to rounding (1e-12). Curved
/// (n = exp(0.2 y)) to a wall at x = 2: against the integral along the exact arc (n's
/// log-gradient is constant, so the arc is the path), by a 20 000-point midpoint rule; the
/// depth is exact along each step's chord, which departs from the arc by κh²/8 (κ ≤ 0.2), so
/// σa's change across that gap, 0.05·κh²/8, stays far below 1e-3 of the depth for any step
/// h ≤ 1. (σa at the start times the length would give 0.4·5 = 2 instead of 1.375.) σa differs
/// by channel, (1, 2, 0.5) times the density: each channel's depth is its σa times the
/// density's integral.
#[test]
fn absorption_integrates_sigma_a_along_the_path() {
    use grinlight::media::Density;
    use grinlight::volume::{Absorption, Participating};
    // d(x) = 0.3 + 0.05 x on x ∈ [−4, 4] (0.1 to 0.5), constant across y and z.
    let density = Density::new(
        DVec3::new(-4.0, -6.0, -6.0),
        DVec3::new(4.0, 6.0, 6.0),
        [2, 2, 2],
        [0.1, 0.5].repeat(4),
    )
    .unwrap();
    let radiometry = Participating {
        absorption: Some(Absorption {
            sigma_a: grinlight::color::Rgb::new(1.0, 2.0, 0.5),
            density: Some(std::sync::Arc::new(density)),
        }),
        ..Participating::default()
    };
    let (mut straight, mut curved) = (None, None);
    let scene = parse_edited(
        "[render]\nworld_radius = 5\n\
         [[material]]\nname = \"wall\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[2, -50, -50], [2, 50, -50], [2, 50, 50], [2, -50, 50]]\nmaterial = \"wall\"\n",
        |d| {
            for (name, g, id) in [("straight", 0.0, &mut straight), ("curved", 0.2, &mut curved)] {
                let m = d.media.add(name, Box::new(Graded { n0: 1.2 - g, g }));
                d.media.set_participating(m, radiometry.clone());
                *id = Some(m);
            }
        },
    );
    let (straight, curved) = (straight.unwrap(), curved.unwrap());
    let tracer = Tracer::new(&scene.0, &scene.1.trace);
    let mut stats = Stats::default();
    // Straight, away from the wall, to the world sphere (centred at the wall's centre).
    let (o, d) = (DVec3::new(2.0 - 1e-6, 0.0, 0.0), DVec3::NEG_X);
    let Event::Escaped {
        distance,
        optical_depth,
        ..
    } = tracer.next_event(o, d, Some(straight), &mut stats)
    else {
        panic!("escapes")
    };
    let want = 0.3 * distance + 0.05 * (o.x * distance - 0.5 * distance * distance);
    for (c, sigma) in [1.0, 2.0, 0.5].into_iter().enumerate() {
        assert!(
            (optical_depth[c] - sigma * want).abs() < 1e-12,
            "channel {c}: {optical_depth} vs {want}"
        );
    }
    // Curved, toward the wall.
    let start = DVec3::new(0.0, 0.0, 0.0);
    let dir = DVec3::new(1.0, 0.3, 0.0).normalize();
    let Event::Surface {
        distance,
        optical_depth,
        ..
    } = tracer.next_event(start, dir, Some(curved), &mut stats)
    else {
        panic!("reaches the wall")
    };
    let seg = grinlight::curve::CurvedSegment::new(start, dir, DVec3::new(0.0, 0.2, 0.0));
    let steps = 20_000;
    let h = distance / steps as f64;
    let want: f64 = (0..steps)
        .map(|i| 0.3 + 0.05 * seg.at((i as f64 + 0.5) * h).position.x)
        .sum::<f64>()
        * h;
    println!("curved: {optical_depth} vs {want:.9} over {distance:.6}");
    for (c, sigma) in [1.0, 2.0, 0.5].into_iter().enumerate() {
        assert!(
            (optical_depth[c] - sigma * want).abs() < 1e-3 * sigma * want,
            "channel {c}: {optical_depth} vs {want}"
        );
    }
}

/// A receiver between a light and the floor is transparent to every query, the shadow rays
/// and the BSDF rays of the direct estimate included: the render is the same with and
/// without it (the same random numbers; only the rays continued past the detector from an
/// offset origin differ, in their last bits: 1e-4 relative allows that), where before the
/// direct layer had a black rectangle under it.
#[test]
fn a_receiver_casts_no_shadow() {
    let base = "[camera]\nposition = [0, 3, 3]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nwidth = 24\nheight = 24\n\
                [render]\nspp = 4\ngather = 2\nphotons = 5000\n\
                [[material]]\nname = \"floor\"\ntype = \"diffuse\"\nalbedo = 0.8\n\
                [[shape]]\ntype = \"quad\"\nvertices = [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]\nmaterial = \"floor\"\n\
                [[light]]\ntype = \"point\"\nposition = [0, 2, 0]\nintensity = 5\n\
                [[light]]\ntype = \"quad\"\nvertices = [[-0.5, 2.5, -0.5], [0.5, 2.5, -0.5], [0.5, 2.5, 0.5], [-0.5, 2.5, 0.5]]\nradiance = 3\n";
    let receiver = "[[receiver]]\nname = \"r\"\ncenter = [0, 1, 0]\nnormal = [0, 1, 0]\nup = [0, 0, 1]\nsize = [1.5, 1.5]\nbins = [4, 4]\n";
    let without = render(&parse(base));
    let with = render(&parse(&format!("{base}{receiver}")));
    let (m, _) = mean(&with, "direct");
    assert!(m > 0.0);
    for (a, b) in without
        .planes()
        .iter()
        .flatten()
        .zip(with.planes().iter().flatten())
    {
        for c in 0..3 {
            assert!(
                (a[c] - b[c]).abs() <= 1e-4 * a[c].abs() + 1e-7,
                "the receiver changes the render: {a:?} vs {b:?}"
            );
        }
    }
}

/// A ray that can never leave the world is lost, not escaped: it sees no environment, and a
/// photon on such a path is booked as lost. In a Maxwell fish-eye (n0 = 2, R = 1) every ray
/// from P = (0.5, 0, 0) is a circle through P and its conjugate P′ = −P R²/|P|² = (−2, 0, 0),
/// tangent to the ray at P: centre P + ρm (m ⊥ d toward P′, ρ = |P′ − P|²/(2 m·(P′ − P))),
/// farthest from the origin at |c| + ρ. Inside a world of radius 3, rays whose circle stays
/// within 2.9 must be lost and rays whose circle reaches 3.1 escaped (120 directions; the
/// thin band between is left out, where the path's numerical drift could decide). The
/// photons of a point light at P are booked lost or missed, in the same shares as their
/// directions' circles fit or not (binomial noise of 800 photons, 4σ).
#[test]
fn a_trapped_ray_is_lost_not_escaped() {
    let (scene, settings) = parse(
        "ambient = \"eye\"\n[[medium]]\nname = \"eye\"\nprofile = \"fisheye\"\nn0 = 2\nradius = 1\n\
         [render]\nworld_radius = 3\nreceiver_photons = 800\n\
         [[light]]\ntype = \"point\"\nposition = [0.5, 0, 0]\nintensity = 1\n\
         [[receiver]]\nname = \"small\"\ncenter = [0, 0, 0]\nsize = [1e-3, 1e-3]\nbins = [1, 1]\n",
    );
    let tracer = Tracer::new(&scene, &settings.trace);
    let (p, conjugate) = (DVec3::new(0.5, 0.0, 0.0), DVec3::new(-2.0, 0.0, 0.0));
    // The farthest distance from the origin of the ray from P along unit d (∞: a line).
    let reach = |d: DVec3| {
        let chord = conjugate - p;
        let m = (chord - chord.dot(d) * d).normalize_or_zero();
        let along = m.dot(chord);
        if along <= 1e-9 {
            return f64::INFINITY;
        }
        let rho = chord.length_squared() / (2.0 * along);
        (p + rho * m).length() + rho
    };
    let (mut trapped, mut checked) = (0, 0);
    for i in 0..120 {
        let d = grinlight::sampling::uniform_sphere((
            (i as f64 + 0.5) / 120.0,
            (i as f64 * 0.618_034) % 1.0,
        ));
        let r = reach(d);
        if (2.9..3.1).contains(&r) {
            continue;
        }
        let e = tracer.next_event(p, d, scene.ambient(), &mut Stats::default());
        if r < 2.9 {
            trapped += 1;
            assert_eq!(e, Event::Lost, "d {d}: circle within {r:.3}");
        } else {
            assert!(
                matches!(e, Event::Escaped { .. }),
                "d {d}: circle reaches {r:.3}: {e:?}"
            );
        }
        checked += 1;
    }
    println!("{trapped} of {checked} directions trapped");
    assert!(trapped > 20 && checked - trapped > 20);
    // Photons: the expected lost share is the fraction of the sphere of directions whose
    // circle fits (the band 2.9..3.1 counted as fitting for the upper bound, not for the lower).
    let fits = |limit: f64| {
        let n = 200_000;
        (0..n)
            .filter(|&i| {
                let u = (
                    (i as f64 + 0.5) / n as f64,
                    (i as f64 * 0.618_033_988_749_895) % 1.0,
                );
                reach(grinlight::sampling::uniform_sphere(u)) < limit
            })
            .count() as f64
            / n as f64
    };
    let (low, high) = (fits(2.9), fits(3.1));
    let (_, budget, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    println!("{budget:?}; fitting share {low:.4}..{high:.4}");
    assert!((budget.lost + budget.missed - budget.emitted).abs() <= 1e-9 * budget.emitted);
    let share = budget.lost / budget.emitted;
    let sigma = (high * (1.0 - high) / 800.0).sqrt();
    assert!(
        share > low - 4.0 * sigma && share < high + 4.0 * sigma,
        "lost share {share} outside {low}..{high} ± 4σ"
    );
}

/// Under the `tessendorf` control each ray draws its own ξ: two rays along +x in a medium
/// stratified along y (n = 1 + 0.5 y), one at z = 0 and one at z = 3, follow congruent paths,
/// so the same ξ would give the same steps; they take different step sequences. With the
/// seed fixed per march, as before, the two sequences were identical.
#[test]
fn tessendorf_draws_different_xi_for_different_rays() {
    let (scene, settings) = parse(
        "[[medium]]\nname = \"e\"\nprofile = \"linear\"\nn0 = 1\ngradient = [0, 0.5, 0]\n\
         [render]\ncontrol = \"tessendorf\"\nstep = 0.01\nt_max = 1e-4\nt_min = 1e-6\nworld_radius = 10\n",
    );
    let tracer = Tracer::new(&scene, &settings.trace);
    let steps = |z: f64| {
        let mut points = Vec::new();
        let mut stats = Stats::default();
        tracer.next_event_along(
            DVec3::new(0.0, 0.0, z),
            DVec3::X,
            Some(grinlight::ids::MediumId::new(0)),
            &mut stats,
            &mut |p| points.push(p.position.x),
        );
        points.windows(2).map(|w| w[1] - w[0]).collect::<Vec<f64>>()
    };
    let (a, b) = (steps(0.0), steps(3.0));
    assert!(a.len() > 5 && b.len() > 5);
    let same = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| (*x - *y).abs() < 1e-9)
        .count();
    assert!(
        same < a.len().min(b.len()) / 2,
        "{same} equal steps: {a:?} {b:?}"
    );
    // The same ray draws the same ξ every time.
    assert_eq!(steps(0.0), a);
}

/// The mirage's direct light comes from curved BSDF rays (the sky) and curved connections (a
/// sun), not the photon maps: with its layer of hot air reduced to a 1e-10 index drop (rays
/// straight for all purposes), its pillar — 3 m wide, 400 m away, 5 pixels of the view —
/// renders as with a uniform ambient (the sky by the same cosine-sampled integral, the sun by
/// a straight shadow ray), within 0.2 % at 8 spp and one pass: they differ by the rays'
/// bending, ~1e-10 rad, and by the secondary light's photons. (Were the direct layer zero in
/// a gradient ambient, the caustic map's k-nearest radius — capped at 5 % of the scene, ≈ 20 m
/// here — would spread the pillar's few photons over a disk ten times its width, and the
/// sun-lit pillar would come out 11× too dark after 8 passes: 0.019 against 0.213.)
#[test]
fn mirage_pillar_matches_a_uniform_ambient() {
    let text = std::fs::read_to_string("scenes/mirage.toml").unwrap();
    let start = text.find("n = [1.000193").unwrap();
    let end = start + text[start..].find('\n').unwrap();
    let nodes = [0.0, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0f64];
    let faint: Vec<String> = nodes
        .iter()
        .map(|h| format!("{:.15}", 1.000293 - 1e-10 * (-h / 0.25).exp()))
        .collect();
    // And a sun, reached from the pillar by curved connections in the graded air.
    let sun =
        "[[light]]\ntype = \"directional\"\ndirection = [0.3, -0.5, -0.8]\nirradiance = 0.5\n";
    let small = |t: &str| {
        t.replace("width = 480\nheight = 240", "width = 48\nheight = 24")
            .replace("spp = 4", "spp = 8\nphotons = 20000")
            + sun
    };
    let graded = small(&format!(
        "{}n = [{}]{}",
        &text[..start],
        faint.join(", "),
        &text[end..]
    ));
    let h_start = text.find("profile = \"height_table\"").unwrap();
    let uniform = small(&format!(
        "{}profile = \"uniform\"\nn = 1.000293{}",
        &text[..h_start],
        &text[end..]
    ));
    assert!(graded.contains("1.000292999900000") && uniform.contains("\"uniform\""));
    let pillar = |film: &grinlight::film::Film| {
        // The pillar (0.43° of the 4° view) spans columns 22..26, its red part rows 8..13.
        let beauty = film.layer("beauty").unwrap();
        let (mut sum, mut n) = (0.0, 0);
        for y in 8..13 {
            for x in 22..26 {
                sum += beauty[y * 48 + x][0] as f64;
                n += 1;
            }
        }
        sum / n as f64
    };
    let (a, b) = (
        pillar(&render(&parse(&graded))),
        pillar(&render(&parse(&uniform))),
    );
    println!("pillar red: gradient ≈ 0 {a:.5}, uniform {b:.5}");
    assert!(b > 0.05, "the pillar is lit: {b}");
    assert!((a / b - 1.0).abs() < 0.002, "{a} vs {b}");
}

/// Curved connections against independent answers.
/// - Parallel light (irradiance 1 at 40° from the vertical) through a hot-air layer (a
///   height table; n constant above 3 m): the power per horizontal area is the same at
///   every height of a layered medium, so the connection's irradiance on a horizontal
///   surface at 0.1 m must be cos 40° (Snell's law across the layers makes the bundle's
///   spread and the n² factor cancel). The spread is the derivative of a march's end with
///   respect to its launch (differenced over marches that replay one step sequence, so no
///   step-choice noise); where a step straddles one of the table's joins (C¹: n″ jumps) that
///   derivative errs by O(h²) per join rather than at the stepper's order, so the error
///   follows the tolerance, not the position's error. At the default (rkn 1e-6) the five
///   points here err by ≤ 1.8e-6, bar 3e-6 (3.0e-6 was the worst of 20 points at heights
///   0.1–1.05 m); at rkn 1e-10 by ≤ 5.4e-8, bar 1e-7: the answer is
///   approached as the steps shrink.
/// - A point light (intensity 1) 3 units above a horizontal receiver in n = exp(0.3 y),
///   whose rays curve strongly: the connection's irradiance, averaged over each bin by a
///   4 × 4 midpoint rule, against the receiver's photon count (6·10⁴ photons, independent
///   code: photons traced from the light): χ²/dof ≤ 1.5 over the 36 bins (≈ 1 ± 0.24 for
///   agreement within noise) and every |z| < 4.5; the straight 1/d² law is far off (it fails
///   both bars).
#[test]
fn curved_connections_match_independent_answers() {
    use grinlight::lights::Anchor;
    use grinlight::transport::connect::connect;
    // Parallel light through a layer, at the default control and a tight one.
    for (control, bar) in [("", 3e-6), ("stepper = \"rkn\"\ntolerance = 1e-10\n", 1e-7)] {
        let (scene, settings) = parse(&format!(
            "ambient = \"air\"\n[[medium]]\nname = \"air\"\nprofile = \"height_table\"\n\
             h = [0.0, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0]\n\
             n = [1.000193, 1.000226, 1.000248, 1.000268, 1.000279, 1.000288, 1.000291, 1.000293, 1.000293, 1.000293]\n\
             [render]\nworld_radius = 50\n{control}",
        ));
        let tracer = Tracer::new(&scene, &settings.trace);
        let theta = 40f64.to_radians();
        let anchor = Anchor::Direction {
            toward: DVec3::new(theta.sin(), theta.cos(), 0.0),
            irradiance: grinlight::color::Rgb::ONE,
        };
        for (x, y) in [
            (-2.0, 0.1),
            (0.0, 0.1),
            (3.0, 0.1),
            (1.0, 0.45),
            (-1.0, 0.8),
        ] {
            let mut stats = Stats::default();
            let link = connect(
                &tracer,
                DVec3::new(x, y, 1.0),
                grinlight::ids::MediumId::new(0),
                &anchor,
                &mut stats,
            )
            .expect("parallel light reaches the layer");
            let e = link.irradiance(&anchor, grinlight::color::Rgb::ZERO).x * link.direction.y;
            println!(
                "layer {control:?}: horizontal irradiance {e:.9} vs {:.9}",
                theta.cos()
            );
            assert!((e - theta.cos()).abs() < bar, "{e} vs {}", theta.cos());
        }
    }
    // A point light above a receiver in an exponential medium.
    let (scene, settings) = parse(
        "ambient = \"e\"\n[[medium]]\nname = \"e\"\nprofile = \"exponential\"\nn0 = 1\ngradient = [0, 0.3, 0]\n\
         [render]\nreceiver_photons = 60000\nworld_radius = 8\n\
         [[light]]\ntype = \"point\"\nposition = [0, 3, 0]\nintensity = 1\n\
         [[receiver]]\nname = \"floor\"\ncenter = [0, 0, 0]\nnormal = [0, 1, 0]\nup = [0, 0, -1]\nsize = [3, 3]\nbins = [6, 6]\n",
    );
    let (measured, _, _) = grinlight::render::measure(&scene, &settings, 0, &()).unwrap();
    let m = &measured[0];
    let rec = &scene.receivers[0];
    let tracer = Tracer::new(&scene, &settings.trace);
    let anchor = Anchor::Point(DVec3::new(0.0, 3.0, 0.0));
    let light = &scene.lights[0];
    let mut stats = Stats::default();
    let (mut chi2, mut worst, mut chi2_straight) = (0.0, 0.0f64, 0.0);
    for k in 0..36 {
        let (cu, cv) = rec.bin_center(k);
        let (mut sum, mut straight) = (0.0, 0.0);
        for i in 0..4 {
            for j in 0..4 {
                let du = (i as f64 + 0.5) / 4.0 - 0.5;
                let dv = (j as f64 + 0.5) / 4.0 - 0.5;
                let p = rec.center + rec.u * (cu + 0.5 * du) + rec.v * (cv + 0.5 * dv);
                let link = connect(
                    &tracer,
                    p,
                    grinlight::ids::MediumId::new(0),
                    &anchor,
                    &mut stats,
                )
                .expect("the light is reached");
                let e = link.irradiance(&anchor, light.intensity(-link.arrival)).x;
                sum += e * link.direction.y / 16.0;
                let d = DVec3::new(0.0, 3.0, 0.0) - p;
                straight += d.y / d.length().powi(3) / 16.0;
            }
        }
        let (got, se) = (m.irradiance[k], m.stderr[k]);
        let z = (got - sum) / se;
        chi2 += z * z;
        chi2_straight += ((got - straight) / se).powi(2);
        worst = worst.max(z.abs());
    }
    println!(
        "point light: χ²/dof {:.3} (straight 1/d²: {:.1}), worst |z| {worst:.2}; {:?}",
        chi2 / 36.0,
        chi2_straight / 36.0,
        stats.connections
    );
    assert!(chi2 / 36.0 < 1.5 && worst < 4.5);
    assert!(chi2_straight / 36.0 > 1.5);
}

/// Surface hits on curved paths against a fine reference march: rays in a sech fiber medium
/// (n0 1.5, g 0.8 about the z axis; they turn through ~1 rad) meet a sphere, a quad and a disk
/// after 1–4 units. Each stepper at its default control (the arc chain finds hits on its own
/// arcs; RK steps on their quintic Hermite path, `curve::HermitePath`) must put the hit point
/// where RKN at tolerance 1e-13 does, within 10·tol·L of the default position bound
/// (`tests/validation.rs`), and on the same primitive.
#[test]
fn curved_paths_meet_surfaces_where_a_fine_march_does() {
    use grinlight::curve::StepperKind;
    let scene_with = |stepper: &str, tolerance: f64| {
        parse(&format!(
            "ambient = \"g\"\n[[medium]]\nname = \"g\"\nprofile = \"sech\"\nn0 = 1.5\ng = 0.8\n\
             [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0.3, 0.2, 2.5]\nradius = 0.4\nmaterial = \"white\"\n\
             [[shape]]\ntype = \"quad\"\nvertices = [[-2, -2, 4], [2, -2, 4], [2, 2, 4], [-2, 2, 4]]\nmaterial = \"white\"\n\
             [[shape]]\ntype = \"disk\"\ncenter = [-0.8, 0.0, 1.5]\nnormal = [1, 0, 0]\nradius = 0.6\nmaterial = \"white\"\n\
             [render]\nworld_radius = 20\nstepper = \"{stepper}\"\ntolerance = {tolerance:e}\n"
        ))
    };
    let rays: Vec<(DVec3, DVec3)> = (0..24)
        .map(|i| {
            let a = i as f64 * 0.37;
            let origin = DVec3::new(0.6 * a.cos(), 0.6 * a.sin(), 0.0);
            (
                origin,
                DVec3::new(0.3 * (2.0 * a).sin(), 0.2 * a.cos(), 1.0),
            )
        })
        .collect();
    let hits = |scene: &(Scene, Settings)| -> Vec<Option<(grinlight::ids::PrimId, DVec3, f64)>> {
        let tracer = Tracer::new(&scene.0, &scene.1.trace);
        rays.iter()
            .map(|&(o, d)| {
                match tracer.next_event(o, d, scene.0.ambient(), &mut Stats::default()) {
                    Event::Surface { hit, distance, .. } => {
                        Some((hit.prim, hit.position, distance))
                    }
                    _ => None,
                }
            })
            .collect()
    };
    let reference = hits(&scene_with("rkn", 1e-13));
    assert!(reference.iter().flatten().count() >= 20, "{reference:?}");
    for kind in [StepperKind::Arc, StepperKind::Rk4, StepperKind::Rkn] {
        let tol = kind.default_tolerance();
        let got = hits(&scene_with(kind.name(), tol));
        let mut worst = 0.0f64;
        for (g, r) in got.iter().zip(&reference) {
            let (Some((gp, gx, _)), Some((rp, rx, dist))) = (g, r) else {
                assert_eq!(g.is_some(), r.is_some(), "{kind:?}");
                continue;
            };
            assert_eq!(gp, rp, "{kind:?}: another surface");
            let err = (*gx - *rx).length();
            worst = worst.max(err / dist);
            assert!(err <= 10.0 * tol * dist, "{kind:?}: {err:e} over {dist}");
        }
        println!("{kind:?}: worst hit error {worst:.2e} per unit length (tolerance {tol:e})");
    }
}

/// A medium emitting basic radiance Le at the rate σa shows Le·(1 − e^(−σa L)) through a
/// stretch of length L: a box of index 1 (a dielectric of the ambient's index passes light
/// straight) L = 0.5 thick, σa L = 0.05, 0.5 and 5 — in every channel, and one σa per channel
/// — seen square on (a field of view of 0.001°: the rays' paths are L to 1e-10) in front of
/// nothing: every pixel that closed form, exactly (no sampling on the way: the interface
/// reflects nothing); f32 film, 1e-6 relative.
#[test]
fn an_emitting_slab_shows_its_closed_form() {
    for sigma_a in [[0.1; 3], [1.0; 3], [10.0; 3], [0.1, 1.0, 10.0]] {
        let scene = parse(&format!(
            "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov_y_deg = 0.001\nwidth = 4\nheight = 4\n\
             [render]\nintegrator = \"path\"\nspp = 1\n\
             [[medium]]\nname = \"glow\"\nprofile = \"uniform\"\nn = 1\nabsorption = {sigma_a:?}\nemission = [2, 1, 0.5]\n\
             [[material]]\nname = \"clear\"\ntype = \"dielectric\"\ninterior = \"glow\"\n\
             [[shape]]\ntype = \"box\"\nmin = [-5, -5, -0.25]\nmax = [5, 5, 0.25]\nmaterial = \"clear\"\n"
        ));
        let film = render(&scene);
        for p in film.layer("emitted").unwrap() {
            for (c, le) in [2.0, 1.0, 0.5].into_iter().enumerate() {
                let want = le * (1.0 - (-sigma_a[c] * 0.5f64).exp());
                assert!(
                    (p[c] as f64 / want - 1.0).abs() < 1e-6,
                    "σa {sigma_a:?}, channel {c}: {} vs {want}",
                    p[c]
                );
            }
        }
    }
}

/// Emission in a GRIN field: the ambient n = exp(0.2 y) emits Le = 1 at σa = 0.5, and the
/// camera at height 1 (n = e^0.2) looks along (1, 0.3, 0) at a black wall at x = 3. The ray is
/// the exact arc of constant ∇ln n ([`grinlight::curve::CurvedSegment`]); it reaches the wall
/// after arclength s, found here by bisection on the arc, and the camera sees
/// n² Le (1 − e^(−σa s)) (basic radiance Le/n² is what the medium emits and what is conserved).
/// The march's arclength is good to ~1e-9 and the field of view is 0.001°, so the pixels'
/// rays differ by 1e-5 rad (≤ 2e-6 of the reading): 1e-5 relative.
#[test]
fn emission_along_a_curved_path_shows_its_closed_form() {
    use grinlight::volume::{Absorption, Emission, Participating};
    let scene = parse_edited(
        "[camera]\nposition = [0, 1, 0]\nlook_at = [1, 1.3, 0]\nup = [0, 0, 1]\nfov_y_deg = 0.001\nwidth = 2\nheight = 2\n\
         [render]\nintegrator = \"path\"\nspp = 1\nworld_radius = 100\n\
         [[material]]\nname = \"black\"\ntype = \"diffuse\"\nalbedo = 0\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[3, -50, -50], [3, 50, -50], [3, 50, 50], [3, -50, 50]]\nmaterial = \"black\"\n",
        |d| {
            let m = d.media.add("graded", Box::new(Graded { n0: 1.0, g: 0.2 }));
            d.media.set_participating(
                m,
                Participating {
                    absorption: Some(Absorption {
                        sigma_a: grinlight::color::Rgb::splat(0.5),
                        density: None,
                    }),
                    emission: Some(Emission {
                        radiance: grinlight::color::Rgb::ONE,
                    }),
                    ..Participating::default()
                },
            );
            d.ambient = Some(m);
        },
    );
    let film = render(&scene);
    let start = DVec3::new(0.0, 1.0, 0.0);
    let arc = grinlight::curve::CurvedSegment::new(
        start,
        DVec3::new(1.0, 0.3, 0.0).normalize(),
        DVec3::new(0.0, 0.2, 0.0),
    );
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        match arc.at(mid).position.x < 3.0 {
            true => lo = mid,
            false => hi = mid,
        }
    }
    let s = 0.5 * (lo + hi);
    let n2 = (0.4f64).exp();
    let want = n2 * (1.0 - (-0.5 * s).exp());
    for p in film.layer("emitted").unwrap() {
        assert!(
            (p[1] as f64 / want - 1.0).abs() < 1e-5,
            "{} vs {want} (s = {s})",
            p[1]
        );
    }
}

/// A slab 0.5 thick absorbing σa = (0.2, 1, 3) a unit over a white floor (albedo 0.5) under
/// the sun straight down (irradiance 1), the camera between them looking down. Bounded by an
/// index-matched interface, the slab lets each channel through as e^(−σa·0.5): both
/// integrators' direct light at the floor is ρ/π times that, exactly (light samples of the
/// sun through the slab; f32 film, 1e-6). Of glass (n = 1.5), the light reaches the floor
/// only through the caustic photons, each channel (1 − R)²t / (1 − R²t²) of it (every
/// reflection inside the slab included; R = 0.04, t = e^(−σa·0.5)), which the photons carry
/// by Russian roulette on their largest channel: the caustic layer's mean over the view within
/// 4 standard errors of eight seeds (each seed's reads ±2.6 %: some 1500 photons in view; the
/// irradiance is uniform, so the estimate has no kernel bias), and the channels' ratios —
/// which every photon carries alike, so they hardly vary — within 2·10⁻³.
#[test]
fn a_coloured_absorbing_slab_passes_each_channels_closed_form() {
    let sigma_a = [0.2, 1.0, 3.0];
    let albedo = 0.5;
    let text = |material: &str, medium: &str, integrator: &str, seed: u32| {
        format!(
            "[camera]\nposition = [0, 0.9, 0]\nlook_at = [0, 0, 0]\nup = [0, 0, -1]\nfov_y_deg = 20\n\
             width = 8\nheight = 8\n\
             [render]\nintegrator = \"{integrator}\"\nspp = 4\nseed = {seed}\n\
             caustic_photons = 400000\nphotons = 10000\n\
             [[medium]]\nname = \"tint\"\nprofile = \"uniform\"\n{medium}\nabsorption = {sigma_a:?}\n\
             [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = {albedo}\n\
             [[material]]\nname = \"slab\"\ntype = \"dielectric\"\n{material}\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
             vertices = [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]\n\
             [[shape]]\ntype = \"box\"\nmin = [-2, 1, -2]\nmax = [2, 1.5, 2]\nmaterial = \"slab\"\n\
             [[light]]\ntype = \"directional\"\ndirection = [0, -1, 0]\nirradiance = [1, 1, 1]\n"
        )
    };
    let t = sigma_a.map(|s: f64| (-s * 0.5).exp());
    for integrator in ["path", "photon_map"] {
        let film = render(&parse(&text("interior = \"tint\"", "n = 1", integrator, 1)));
        for p in film.layer("direct").unwrap() {
            for c in 0..3 {
                let want = albedo / std::f64::consts::PI * t[c];
                assert!(
                    (p[c] as f64 / want - 1.0).abs() < 1e-6,
                    "{integrator}, channel {c}: {} vs {want}",
                    p[c]
                );
            }
        }
    }
    let r: f64 = 0.04;
    let want =
        t.map(|t| albedo / std::f64::consts::PI * (1.0 - r).powi(2) * t / (1.0 - r * r * t * t));
    let seeds: Vec<[f64; 3]> = (1..=8)
        .map(|seed| {
            let film = render(&parse(&text(
                "interior = \"tint\"",
                "n = 1.5",
                "photon_map",
                seed,
            )));
            let caustic = film.layer("caustic").unwrap();
            let n = caustic.len() as f64;
            std::array::from_fn(|c| caustic.iter().map(|p| p[c] as f64).sum::<f64>() / n)
        })
        .collect();
    let n = seeds.len() as f64;
    let mean: [f64; 3] = std::array::from_fn(|c| seeds.iter().map(|s| s[c]).sum::<f64>() / n);
    for c in 0..3 {
        let var = seeds.iter().map(|s| (s[c] - mean[c]).powi(2)).sum::<f64>() / (n - 1.0);
        let se = (var / n).sqrt();
        let ratio = (mean[c] / mean[0]) / (want[c] / want[0]);
        println!(
            "channel {c}: caustic {:.6} ± {se:.6} vs {:.6}; to channel 0, {ratio:.6} of the closed form's",
            mean[c], want[c]
        );
        assert!(
            (mean[c] - want[c]).abs() < 4.0 * se,
            "channel {c}: {} ± {se} vs {}",
            mean[c],
            want[c]
        );
        assert!((ratio - 1.0).abs() < 2e-3, "channel {c}: ratio {ratio}");
    }
}
