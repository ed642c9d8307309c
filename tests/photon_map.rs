//! The photon map against a brute-force scan, on random and on coplanar photons, and its
//! density estimates against a known irradiance.

use glam::DVec3;
use grinlight::color::Rgb;
use grinlight::photon::{Photon, PhotonMap};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

fn photon(position: DVec3, normal: DVec3, power: f32) -> Photon {
    Photon {
        position,
        normal,
        power: [power; 3],
        from: normal.as_vec3().to_array(),
        base: 1.0,
    }
}

/// Photons uniform on the unit square of the plane z = 0, flux `total` in all.
fn uniform_square(n: usize, total: f64, rng: &mut Pcg64Mcg) -> Vec<Photon> {
    (0..n)
        .map(|_| {
            photon(
                DVec3::new(rng.gen(), rng.gen(), 0.0),
                DVec3::Z,
                (total / n as f64) as f32,
            )
        })
        .collect()
}

#[test]
fn radius_queries_match_a_brute_force_scan() {
    let mut rng = Pcg64Mcg::seed_from_u64(7);
    // Random photons in a box, half facing +z and half −z; and 5000 coplanar photons on an
    // axis-aligned wall x = 1 (the case that makes kiddo's mutable tree panic), many of them
    // at identical positions.
    let mut photons: Vec<Photon> = (0..20_000)
        .map(|i| {
            let n = if i % 2 == 0 { DVec3::Z } else { -DVec3::Z };
            photon(DVec3::new(rng.gen(), rng.gen(), rng.gen()), n, 1.0)
        })
        .collect();
    for i in 0..5000 {
        let (y, z) = if i % 5 == 0 {
            (0.5, 0.5)
        } else {
            (rng.gen(), rng.gen())
        };
        photons.push(photon(DVec3::new(1.0, y, z), -DVec3::X, 1.0));
    }
    let map = PhotonMap::new(photons.clone());
    assert_eq!(map.len(), photons.len());
    for q in 0..300 {
        let (p, n) = if q % 3 == 0 {
            (DVec3::new(1.0, rng.gen(), rng.gen()), -DVec3::X)
        } else {
            (DVec3::new(rng.gen(), rng.gen(), rng.gen()), DVec3::Z)
        };
        let r2: f64 = rng.gen_range(1e-4..0.05);
        // The tree keeps positions turned by a fixed rotation (distances equal to ~1e-16
        // relative), so a photon within 1e-12·r² of the sphere may fall either way.
        let mut got = 0;
        map.for_each_within(p, n, r2, |ph, d2| {
            assert!((d2 - (ph.position - p).length_squared()).abs() < 1e-12);
            assert!(ph.normal.dot(n) >= 0.9);
            got += 1;
        });
        let count = |r2: f64| {
            photons
                .iter()
                .filter(|ph| (ph.position - p).length_squared() <= r2 && ph.normal.dot(n) >= 0.9)
                .count()
        };
        let (inner, outer) = (count(r2 * (1.0 - 1e-12)), count(r2 * (1.0 + 1e-12)));
        assert!(
            (inner..=outer).contains(&got),
            "query {q} at {p} r² {r2}: {got} not in {inner}..={outer}"
        );
        // k-nearest radius: the k-th smallest distance among the same-side photons.
        let mut d: Vec<f64> = photons
            .iter()
            .filter(|ph| ph.normal.dot(n) >= 0.9)
            .map(|ph| (ph.position - p).length_squared())
            .collect();
        d.sort_by(f64::total_cmp);
        let k = 1 + q % 40;
        let want_r2 = if d[k - 1] <= 0.5 { d[k - 1] } else { 0.5 };
        let got_r2 = map.knn_radius2(p, n, k, 0.5);
        assert!(
            (got_r2 - want_r2).abs() <= 1e-12 * want_r2,
            "query {q}, k {k}: {got_r2} vs {want_r2}"
        );
    }
    // The coplanar cluster: 1000 photons at one point are all found.
    let mut at_point = 0;
    map.for_each_within(DVec3::new(1.0, 0.5, 0.5), -DVec3::X, 1e-20, |_, _| {
        at_point += 1
    });
    assert_eq!(at_point, 1000);
}

#[test]
fn an_empty_map_answers_zero() {
    let map = PhotonMap::new(Vec::new());
    assert!(map.is_empty());
    assert_eq!(map.irradiance(DVec3::ZERO, DVec3::Z, 1.0), (Rgb::ZERO, 0));
    assert_eq!(map.knn_irradiance(DVec3::ZERO, DVec3::Z, 8, 1.0), Rgb::ZERO);
    assert_eq!(map.knn_radius2(DVec3::ZERO, DVec3::Z, 8, 1.0), 1.0);
}

/// Uniform irradiance E = 1 W/m² on the unit square: the estimates averaged over many query
/// points must be unbiased. Standard error of the mean over 4000 queries of a k = 16
/// estimate (relative sd ≈ 1/√(k − 2) ≈ 0.27, but neighbouring queries share photons) is
/// below 1 %; the tolerance is 2 %.
#[test]
fn density_estimates_are_unbiased_on_a_uniform_plane() {
    let mut rng = Pcg64Mcg::seed_from_u64(3);
    let mut map = PhotonMap::new(uniform_square(200_000, 1.0, &mut rng));
    map.precompute_irradiance(16, 1.0);
    let (mut fixed, mut knn, mut lookup) = (0.0, 0.0, 0.0);
    let queries = 4000;
    for _ in 0..queries {
        // Away from the edges, so no disk leaves the square.
        let p = DVec3::new(rng.gen_range(0.1..0.9), rng.gen_range(0.1..0.9), 0.0);
        fixed += map.irradiance(p, DVec3::Z, 1e-4).0.x;
        knn += map.knn_irradiance(p, DVec3::Z, 16, 1.0).x;
        lookup += map.nearest_irradiance(p, DVec3::Z).x;
    }
    let q = queries as f64;
    println!(
        "fixed radius {:.4}, knn {:.4}, precomputed lookup {:.4}",
        fixed / q,
        knn / q,
        lookup / q
    );
    for (name, v) in [("fixed", fixed), ("knn", knn), ("lookup", lookup)] {
        assert!((v / q - 1.0).abs() < 0.02, "{name}: {}", v / q);
    }
}

/// Caustic photons are sent only through a ball holding the specular surfaces (projection
/// maps): on a 0.5-radius glass ball over an 8 × 8 floor, the caustic power stored on the
/// floor (in all, and within 0.6 of the point below the ball) is the same as with photons over
/// the whole scene — within 4 combined standard errors, ≈ 1–2 % here — while many times more
/// photons reach the ball: for the sun and a sky ((R/r)²-fold), and for a point light, a spot,
/// a quad light and an LED, each aimed over the ball's cone from where its photon starts. A
/// roof between the sun and the ball is not skipped: photons still start upstream of the
/// whole scene.
#[test]
fn caustic_photons_aimed_at_specular_surfaces_carry_the_same_power() {
    use grinlight::photon::{shoot, Batch, Photons, Sources};
    use grinlight::scene::load::parse_scene;
    use grinlight::transport::Tracer;
    let sun = "[[light]]\ntype = \"directional\"\ndirection = [0.2,-1,0.1]\nirradiance = 2\n";
    let sky = "[[light]]\ntype = \"environment\"\nsky = \"checker\"\nscale = 0.3\n";
    let scene = |lights: &str| {
        format!(
            "[[material]]\nname = \"floor\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
             [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\
             [[shape]]\ntype = \"quad\"\nvertices = [[-4,0,-4],[4,0,-4],[4,0,4],[-4,0,4]]\nmaterial = \"floor\"\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0,1,0]\nradius = 0.5\nmaterial = \"glass\"\n{lights}"
        )
    };
    // Total stored power and that within 0.6 of the focus, each with its standard error
    // (one photon stores at most once: Var = Σx² − (Σx)²/N).
    let measure = |text: String, aimed: bool, n: u64| {
        let (scene, settings) = parse_scene(std::path::Path::new("aim.toml"), text).unwrap();
        let tracer = Tracer::new(&scene, &settings.trace);
        let sources = match aimed {
            true => Sources::for_caustics(&tracer),
            false => Sources::new(&tracer),
        };
        let (sink, _) = shoot(
            &tracer,
            &sources,
            Photons::all(Batch::Caustic, 7, 0, n),
            &|| false,
        );
        // The ball's focus on the floor: below it, shifted along the sun's slant.
        let focus = DVec3::new(0.2, 0.0, 0.1);
        let sums = |near: bool| {
            let (mut s, mut q) = (0.0, 0.0);
            for p in sink.photons.photons() {
                let x = p.power.iter().map(|&c| c as f64).sum::<f64>() / 3.0;
                if !near || (p.position - focus).length() < 0.6 {
                    s += x;
                    q += x * x;
                }
            }
            (s, (q - s * s / n as f64).max(0.0).sqrt())
        };
        (
            sums(false),
            sums(true),
            sink.photons.photons().len() as f64 / n as f64,
        )
    };
    let local = "[[light]]\ntype = \"point\"\nposition = [1.5,3,0]\nintensity = 1\n\
                 [[light]]\ntype = \"spot\"\nposition = [-1,3,0.5]\nintensity = 2\ncone_deg = 40\nfalloff_deg = 20\n\
                 [[light]]\ntype = \"quad\"\nvertices = [[-0.3,3.5,-0.3],[0.3,3.5,-0.3],[0.3,3.5,0.3],[-0.3,3.5,0.3]]\nradiance = 2\n\
                 [[light]]\ntype = \"led\"\ncenter = [0,2.5,-1.5]\nnormal = [0,-0.8,0.6]\nradius = 0.05\npower = 3\nm = 4\n";
    for (lights, whole) in [
        (format!("{sun}{sky}"), 2_000_000),
        (local.to_string(), 1_000_000),
    ] {
        let (all_a, near_a, rate_a) = measure(scene(&lights), true, 200_000);
        let (all_w, near_w, rate_w) = measure(scene(&lights), false, whole);
        println!(
            "aimed: {:.4e} ± {:.1e} (focus {:.4e} ± {:.1e}), {rate_a:.4} stored per photon; whole: \
             {:.4e} ± {:.1e} (focus {:.4e} ± {:.1e}), {rate_w:.4}",
            all_a.0, all_a.1, near_a.0, near_a.1, all_w.0, all_w.1, near_w.0, near_w.1
        );
        for (a, w) in [(all_a, all_w), (near_a, near_w)] {
            assert!(
                (a.0 - w.0).abs() < 4.0 * (a.1 * a.1 + w.1 * w.1).sqrt(),
                "{a:?} vs {w:?}"
            );
            assert!(
                a.1 < 0.02 * a.0 && w.1 < 0.02 * w.0,
                "too noisy to compare: {a:?} {w:?}"
            );
        }
        assert!(rate_a > 10.0 * rate_w, "{rate_a} vs {rate_w}");
    }
    // A roof over the scene: no sun photon reaches the ball, aimed or not.
    let roof = "[[shape]]\ntype = \"quad\"\nvertices = [[-9,5,-9],[-9,5,9],[9,5,9],[9,5,-9]]\nmaterial = \"floor\"\n";
    let (covered, _, _) = measure(scene(&format!("{sun}{roof}")), true, 100_000);
    assert_eq!(covered.0, 0.0);
}
