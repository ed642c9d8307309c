//! Plastic's polarization: its coat's reflection, and its base's light refracted into the coat,
//! depolarized and refracted out (Baek et al. 2018; Mitsuba 3's `pplastic`). The base's light
//! is held to the smooth coat's Fresnel transmittances written out here from Born and Wolf's
//! amplitudes: it leaves partly p-polarized, by (T_p − T_s)/(T_p + T_s) of the angle it leaves
//! at, and takes s and p light in the ratio T_s/T_p of the angle it arrives at — with the light
//! (photons on receivers) and against it (camera paths, both integrators).

use glam::{DMat4, DVec3};
use grinlight::bsdf::{Bsdf, Coat, Microsurface};
use grinlight::color::Rgb;
use grinlight::polarization::Sense;
use grinlight::receiver::Measurement;

/// The coat's index in every scene here.
const ETA: f64 = 1.5;

/// (T_s − T_p)/(T_s + T_p) of light crossing the smooth coat at cos θ = `cos` on the outer side:
/// t_s = 2c/(c + η c_t), t_p = 2c/(η c + c_t) (Born and Wolf), T ∝ |t|² with one factor for
/// both, which the ratio drops.
fn s_minus_p(cos: f64) -> f64 {
    let ct = (1.0 - (1.0 - cos * cos) / (ETA * ETA)).sqrt();
    let ts = 2.0 * cos / (cos + ETA * ct);
    let tp = 2.0 * cos / (ETA * cos + ct);
    (ts * ts - tp * tp) / (ts * ts + tp * tp)
}

/// A unit direction at `theta` (radians) from +z, turned by `phi` about it.
fn direction(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// The plastic's Mueller matrix holds its f as its first element (per channel), the same
/// matrix both ways along a path for the same light (a camera path's, against the light, and
/// a photon's, with it), and Helmholtz reciprocity for polarized light: the light going the
/// other way meets Q Mᵀ Q, Q = diag(1, 1, −1, 1) (a basis's second axis turns over with the
/// light's direction) — which holds only where the entry's and the exit's bases are turned
/// alike. 1e-12 of f: rounding.
#[test]
fn a_plastics_matrix_is_its_f_and_reciprocal() {
    let coat = Coat::new(ETA, Microsurface::ggx(0.3));
    let bsdf = Bsdf::Plastic {
        albedo: Rgb::new(0.2, 0.5, 0.9),
        coat: &coat,
    };
    let n = DVec3::Z;
    let q = DMat4::from_diagonal(glam::DVec4::new(1.0, 1.0, -1.0, 1.0));
    let mut polarizing = 0.0f64;
    for theta_from in [0.0f64, 10.0, 40.0, 70.0, 89.0] {
        for theta_to in [0.0f64, 20.0, 55.0, 80.0] {
            for phi in [0.0f64, 1.0, 2.5, std::f64::consts::PI] {
                let from = direction(theta_from.to_radians(), 0.3);
                let to = direction(theta_to.to_radians(), 0.3 + phi);
                let camera = bsdf.mueller(to, from, n, Sense::AgainstLight).unwrap();
                let photon = bsdf.mueller(from, to, n, Sense::WithLight).unwrap();
                let back = bsdf.mueller(from, to, n, Sense::AgainstLight).unwrap();
                let f = bsdf.eval(to, from, n);
                for c in 0..3 {
                    let m = camera.mueller[c];
                    let scale = f.0[c];
                    assert!(
                        (m.col(0).x - scale).abs() < 1e-12 * scale,
                        "{m} against {f:?}"
                    );
                    assert_eq!(m, photon.mueller[c]);
                    let reciprocal = q * m.transpose() * q;
                    let gap = (back.mueller[c] - reciprocal).abs().to_cols_array();
                    let gap = gap.into_iter().fold(0.0, f64::max);
                    assert!(
                        gap < 1e-12 * scale,
                        "{theta_from}°, {theta_to}°, {phi}: {} against {reciprocal}",
                        back.mueller[c]
                    );
                    polarizing = polarizing.max(m.col(0).y.hypot(m.col(0).z) / scale);
                }
                assert_eq!(camera.x, camera.x_leaving);
            }
        }
    }
    // A case that tells a polarizing matrix from a depolarizer.
    assert!(polarizing > 0.1, "{polarizing}");
    assert!(bsdf
        .mueller(DVec3::Z, -DVec3::Z, n, Sense::AgainstLight)
        .is_none());
}

/// The sun straight above a white plastic (its coat as smooth as allowed, α = 0.001), seen by
/// an orthographic Stokes camera at 40° and 70° from the normal whose image's up is turned 30°
/// (and 0°) off the plane of incidence: the base's light leaves p-polarized by
/// (T_p − T_s)/(T_p + T_s) at θ, so that in the camera's basis S1/S0 = D cos 2φ and S2/S0 =
/// D sin 2φ, φ the p direction's angle from the basis's first axis toward its second. Each
/// pixel's paths alike (a delta light, nothing else in view), so the tolerance is what the
/// coat's reflection adds: its f toward the camera is below 10⁻⁶ of the base's at α = 0.001
/// (the half vector 20° or 35° off the normal), and 2·10⁻⁶ covers it and the f32 layers.
#[test]
fn a_plastics_base_sends_its_light_p_polarized_as_fresnel_transmission_says() {
    for integrator in ["path", "photon_map"] {
        for (deg, turn_deg) in [(40.0f64, 30.0f64), (70.0, 30.0), (70.0, 0.0)] {
            let theta = deg.to_radians();
            // The camera looks along d, in the plane y = 0.
            let d = DVec3::new(theta.sin(), 0.0, -theta.cos());
            let s = DVec3::Y;
            let image_up = (d.cross(s).normalize() * turn_deg.to_radians().cos()
                + s * turn_deg.to_radians().sin())
            .normalize();
            let eye = -3.0 * d;
            let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
            let text = format!(
                "[camera]\nprojection = \"orthographic\"\nview_height = 0.5\nposition = {}\n\
                 look_at = [0, 0, 0]\nup = {}\nwidth = 4\nheight = 4\n\
                 [render]\nintegrator = \"{integrator}\"\nstokes = true\nspp = 4\n\
                 photons = 2000\ncaustic_photons = 2000\n\
                 [[material]]\nname = \"plastic\"\ntype = \"plastic\"\nalbedo = 0.8\nior = {ETA}\n\
                 roughness = 0.001\n\
                 [[shape]]\ntype = \"quad\"\nmaterial = \"plastic\"\n\
                 vertices = [[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]]\n\
                 [[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nirradiance = [1, 1, 1]\n",
                v(eye),
                v(image_up)
            );
            let (scene, settings) =
                grinlight::scene::load::parse_scene(std::path::Path::new("plastic.toml"), text)
                    .unwrap();
            let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
            // The basis: x = d × up, y = −d × x; the light travels along −d.
            let x = d.cross(image_up).normalize();
            let y = -d.cross(x);
            let p = DVec3::Z - DVec3::Z.dot(d) * d;
            let phi = p.dot(y).atan2(p.dot(x));
            let degree = -s_minus_p(theta.cos());
            let want = [degree * (2.0 * phi).cos(), degree * (2.0 * phi).sin()];
            let layers = ["S0", "S1", "S2", "S3"].map(|name| film.layer(name).unwrap());
            let [l0, l1, l2, l3] = &layers;
            let pixels = l0.iter().zip(l1.iter()).zip(l2.iter()).zip(l3.iter());
            for (i, (((p0, p1), p2), p3)) in pixels.enumerate() {
                let [s0, s1, s2, s3] = [p0, p1, p2, p3].map(|p| f64::from(p[1]));
                assert!(s0 > 0.0);
                let got = [s1 / s0, s2 / s0];
                if i == 0 {
                    println!("{integrator}, {deg}°, turned {turn_deg}°: {got:?} against {want:?}");
                }
                assert!(
                    (got[0] - want[0]).abs() < 2e-6 && (got[1] - want[1]).abs() < 2e-6,
                    "{integrator}, {deg}°, turned {turn_deg}°, pixel {i}: {got:?} against {want:?}"
                );
                assert!(s3.abs() <= 1e-6 * s0, "{s3}");
            }
        }
    }
}

/// The receivers' measurements of scene `text` with `photons` receiver photons.
fn measured(text: &str, photons: u64) -> Vec<Measurement> {
    let (scene, mut settings) =
        grinlight::scene::load::parse_scene(std::path::Path::new("plastic.toml"), text.into())
            .unwrap();
    settings.receiver_photons = photons;
    grinlight::render::measure(&scene, &settings, 0, &())
        .unwrap()
        .0
}

/// Photons, with the light: a narrow spot straight down onto a white plastic (α = 0.001), a
/// receiver of side 0.4 at distance 10 at 60° from the normal, its width axis across the plane
/// of incidence (s): the base's light arrives there p-polarized, S1/S0 = (T_s − T_p)/(T_s + T_p)
/// at 60°, within what the receiver's spread of angles (±1.2°) moves it, 2·10⁻³. Then the spot
/// at 60° through a polarizer sheet across its beam and a receiver of side 3 at height 1.5
/// above the spot's point: with the sheet's axis along s it reads T_s/T_p of its flux along p,
/// within 4 standard errors — whatever way the light leaves, as the base depolarizes it.
/// (Against the light, a camera path takes the light a plastic's base receives through the
/// matrix's first row, which the reciprocity above ties to this entry.)
#[test]
fn photons_leave_and_enter_a_plastics_base_as_fresnel_transmission_says() {
    let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
    let plastic = format!(
        "[render]\npolarized = true\n\
         [[material]]\nname = \"plastic\"\ntype = \"plastic\"\nalbedo = 0.8\nior = {ETA}\n\
         roughness = 0.001\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"plastic\"\n\
         vertices = [[-5, -5, 0], [5, -5, 0], [5, 5, 0], [-5, 5, 0]]\n"
    );
    let theta = 60f64.to_radians();
    let r = direction(theta, 0.0);
    let leaving = format!(
        "{plastic}[[light]]\ntype = \"spot\"\nposition = [0, 0, 3]\ndirection = [0, 0, -1]\n\
         intensity = [1, 1, 1]\ncone_deg = 0.5\n\
         [[receiver]]\nname = \"r\"\ncenter = {}\nnormal = {}\nup = {}\nsize = [0.4, 0.4]\n\
         bins = [1, 1]\n",
        v(10.0 * r),
        v(r),
        v(r.cross(DVec3::Y))
    );
    let m = &measured(&leaving, 1_000_000)[0];
    let s1 = m.stokes[0].flux.0 / m.flux.0;
    let want = s_minus_p(theta.cos());
    println!("leaving at 60°: S1/S0 {s1:.5} against {want:.5}");
    assert!((s1 - want).abs() < 2e-3, "{s1} against {want}");
    assert!(want < -0.05, "{want}: a case that tells s from p");

    let k = -r;
    let entering = |axis: DVec3| {
        let c = 2.0 * r;
        let (a, b) = (0.3 * DVec3::Y, 0.3 * k.cross(DVec3::Y));
        format!(
            "{plastic}[[light]]\ntype = \"spot\"\nposition = {}\ndirection = {}\n\
             intensity = [1, 1, 1]\ncone_deg = 0.5\n\
             [[material]]\nname = \"sheet\"\ntype = \"polarizer\"\naxis = {}\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"sheet\"\nvertices = [{}, {}, {}, {}]\n\
             [[receiver]]\nname = \"r\"\ncenter = [0, 0, 1.5]\nnormal = [0, 0, 1]\n\
             up = [0, 1, 0]\nsize = [3, 3]\nbins = [1, 1]\n",
            v(3.0 * r),
            v(k),
            v(axis),
            v(c - a - b),
            v(c + a - b),
            v(c + a + b),
            v(c - a + b)
        )
    };
    let s = &measured(&entering(DVec3::Y), 1_000_000)[0];
    let p = &measured(&entering(k.cross(DVec3::Y)), 1_000_000)[0];
    let ratio = s.flux.0 / p.flux.0;
    let spread = ratio * (s.flux.1 / s.flux.0).hypot(p.flux.1 / p.flux.0);
    let want = (1.0 + s_minus_p(theta.cos())) / (1.0 - s_minus_p(theta.cos()));
    println!("entering at 60°: s/p {ratio:.5} ± {spread:.5} against T_s/T_p {want:.5}");
    assert!(
        (ratio - want).abs() < 4.0 * spread,
        "{ratio} ± {spread} against {want}"
    );
    assert!(
        want < 1.0 - 8.0 * spread,
        "{want}: a case that tells s from p"
    );
}

/// A plastic floor lit only by way of a side wall (the light faces the wall), seen at 71° from
/// its normal by a Stokes camera, its light polarized by the floor's coat and base. A mirror
/// wall casts a caustic, the photon mapper's caustic map; a white wall's light is its final
/// gather over the global map. The maps' photons keep no Stokes vector (the light from either
/// wall arrives unpolarized: a perfect mirror keeps unpolarized light unpolarized), and each
/// photon or gather ray reaches the camera through the floor's Mueller matrix for its
/// direction; the path tracer follows the same light by sampling the floor's BSDF. The near
/// half of the image over 4 seeds each, S1/S0 in one run: mirror 0.5751 ± 0.0032 (path) and
/// 0.5753 ± 0.0016 (photon map); white wall 0.4553 ± 0.0013 and 0.4549 ± 0.0006 (standard
/// errors of the seeds' mean); the tolerance is 4 combined standard errors. Read as
/// depolarized at the floor, the photon mapper's light gives −0.004 (mirror) and 0 (wall).
#[test]
fn a_plastic_polarizes_the_light_the_maps_bring_alike_in_both_integrators() {
    for wall in ["mirror", "white"] {
        let room = |integrator: &str, seed: u32| {
            format!(
                "[camera]\nposition = [3, 1.2, 0]\nlook_at = [-0.5, 0, 0]\nup = [0, 1, 0]\n\
                 fov_y_deg = 20\nwidth = 32\nheight = 32\n\
                 [render]\nintegrator = \"{integrator}\"\nstokes = true\nspp = 64\nseed = {seed}\n\
                 photons = 200000\ncaustic_photons = 200000\n\
                 [[material]]\nname = \"plastic\"\ntype = \"plastic\"\nalbedo = 0.5\nior = {ETA}\n\
                 roughness = 0.3\n\
                 [[material]]\nname = \"mirror\"\ntype = \"mirror\"\n\
                 [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = 0.8\n\
                 [[shape]]\ntype = \"quad\"\nmaterial = \"plastic\"\n\
                 vertices = [[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]\n\
                 [[shape]]\ntype = \"quad\"\nmaterial = \"{wall}\"\n\
                 vertices = [[-2, 0, -2], [-2, 2, -2], [-2, 2, 2], [-2, 0, 2]]\n\
                 [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                 vertices = [[-2, 0, -2], [2, 0, -2], [2, 2, -2], [-2, 2, -2]]\n\
                 [[light]]\ntype = \"quad\"\nradiance = [5, 5, 5]\n\
                 vertices = [[-1, 1.5, -0.5], [-1, 1.5, 0.5], [-1, 2.0, 0.5], [-1, 2.0, -0.5]]\n"
            )
        };
        let degree = |integrator: &str| {
            let ratios: Vec<f64> = (1..=4)
                .map(|seed| {
                    let text = room(integrator, seed);
                    let film = rendered(text);
                    near_half(&film, "S1") / near_half(&film, "S0")
                })
                .collect();
            let mean = ratios.iter().sum::<f64>() / 4.0;
            let var = ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / 3.0;
            (mean, (var / 4.0).sqrt())
        };
        let (path, photon_map) = (degree("path"), degree("photon_map"));
        println!("{wall} wall: S1/S0 path {path:?}, photon map {photon_map:?}");
        assert!(
            (path.0 - photon_map.0).abs() < 4.0 * path.1.hypot(photon_map.1),
            "{wall} wall: {path:?} against {photon_map:?}"
        );
        assert!(path.0 > 0.3, "{path:?}: a case that tells polarized light");
    }
}

/// A polarized caustic on a plastic: a quad light shining down through a polarizer sheet onto
/// a plastic floor, seen at 71° from its normal by a Stokes camera, the sheet's axis across
/// (x) or along (z) the view. The light through the sheet is the photon mapper's caustic map,
/// whose photons keep their Stokes vectors and reach the camera through the floor's Mueller
/// matrix for each one's polarization; the path tracer finds the light through the sheet by
/// sampling the floor's BSDF. Over 3 seeds each, the near half of the image: S1/S0 along
/// either axis and the ratio of S0 between the two, path tracer against photon mapper within
/// 4 combined standard errors of the seeds' means plus 0.003 (the density estimate's blur of
/// a polarization that changes across the floor; measured gaps 0.0003, 0.0009 and 0.0010). Photons
/// read as unpolarized at the floor gave S1/S0 −0.046 along both axes (the path tracer −0.150
/// and +0.046) and the ratio 1 (0.863).
#[test]
fn a_polarized_caustic_on_a_plastic_reads_alike_in_both_integrators() {
    let room = |integrator: &str, axis: &str, seed: u32| {
        format!(
            "[camera]\nposition = [3, 1, 0]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\n\
             fov_y_deg = 20\nwidth = 32\nheight = 32\n\
             [render]\nintegrator = \"{integrator}\"\nstokes = true\nspp = 64\nseed = {seed}\n\
             photons = 10000\ncaustic_photons = 400000\n\
             [[material]]\nname = \"plastic\"\ntype = \"plastic\"\nalbedo = 0.5\nior = {ETA}\n\
             roughness = 0.2\n\
             [[material]]\nname = \"sheet\"\ntype = \"polarizer\"\naxis = {axis}\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"plastic\"\n\
             vertices = [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"sheet\"\n\
             vertices = [[-1.5, 1.5, -1.5], [1.5, 1.5, -1.5], [1.5, 1.5, 1.5], [-1.5, 1.5, 1.5]]\n\
             [[light]]\ntype = \"quad\"\nradiance = [5, 5, 5]\n\
             vertices = [[-0.5, 2, -0.5], [0.5, 2, -0.5], [0.5, 2, 0.5], [-0.5, 2, 0.5]]\n"
        )
    };
    // Per seed: S0 and S1/S0 of the near half along x and along z.
    let readings = |integrator: &str| -> Vec<[f64; 4]> {
        (1..=3)
            .map(|seed| {
                let [x, z] = ["[1, 0, 0]", "[0, 0, 1]"].map(|axis| {
                    let text = room(integrator, axis, seed);
                    let film = rendered(text);
                    let s0 = near_half(&film, "S0");
                    (s0, near_half(&film, "S1") / s0)
                });
                [x.1, z.1, x.0 / z.0, 0.0]
            })
            .collect()
    };
    let (path, photon_map) = (readings("path"), readings("photon_map"));
    for (k, name) in ["S1/S0 along x", "S1/S0 along z", "S0 along x over along z"]
        .iter()
        .enumerate()
    {
        let stats = |runs: &[[f64; 4]]| {
            let mean = runs.iter().map(|r| r[k]).sum::<f64>() / 3.0;
            let var = runs.iter().map(|r| (r[k] - mean).powi(2)).sum::<f64>() / 2.0;
            (mean, (var / 3.0).sqrt())
        };
        let (a, b) = (stats(&path), stats(&photon_map));
        println!("{name}: path {a:?}, photon map {b:?}");
        assert!(
            (a.0 - b.0).abs() < 4.0 * a.1.hypot(b.1) + 0.003,
            "{name}: {a:?} against {b:?}"
        );
    }
}

/// The film of scene `text` (a test's own, at a made-up path).
fn rendered(text: String) -> grinlight::film::Film {
    let (scene, settings) =
        grinlight::scene::load::parse_scene(std::path::Path::new("room.toml"), text).unwrap();
    grinlight::render::render(&scene, &settings, &()).unwrap().0
}

/// The green channel of layer `name` summed over the lower half of a 32 × 32 image (the
/// floor nearest the camera).
fn near_half(film: &grinlight::film::Film, name: &str) -> f64 {
    let layer = film.layer(name).unwrap();
    layer[16 * 32..].iter().map(|p| f64::from(p[1])).sum()
}
