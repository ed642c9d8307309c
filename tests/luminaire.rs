//! Measured luminaires (IES LM-63 and EULUMDAT files, equal-area intensity images): the table
//! read and its symmetry expanded, its power against the closed form of the distribution it
//! tabulates, its photons' directions drawn without bias, and a luminaire lighting the white
//! spherical room as an integrating sphere says it must, by both integrators.

use glam::DVec3;
use grinlight::lights::{Aim, Entry, Light, Luminaire};
use grinlight::math::Ball;
use grinlight::photometry::image::IntensityImage;
use grinlight::photometry::{ies, IntensityMap};
use grinlight::scene::load::parse_scene;
use std::f64::consts::PI;

/// An IES LM-63-2002 file of type C with `verticals` and `horizontals` (degrees) and the
/// candela of `intensity(γ, C)` (degrees) at each node, ten numbers a line.
fn ies_file(verticals: &[f64], horizontals: &[f64], intensity: impl Fn(f64, f64) -> f64) -> String {
    ies_file_of_type(1, verticals, horizontals, intensity)
}

/// An IES LM-63-2002 file of photometric type `kind` (1 C, 2 B, 3 A) with `verticals` and
/// `horizontals` (degrees) and the candela of `intensity(vertical, horizontal)` (degrees) at
/// each node, ten numbers a line.
fn ies_file_of_type(
    kind: u8,
    verticals: &[f64],
    horizontals: &[f64],
    intensity: impl Fn(f64, f64) -> f64,
) -> String {
    let mut numbers: Vec<String> = Vec::new();
    numbers.extend(verticals.iter().map(|v| format!("{v}")));
    numbers.extend(horizontals.iter().map(|h| format!("{h}")));
    for &c in horizontals {
        numbers.extend(verticals.iter().map(|&g| format!("{:.9}", intensity(g, c))));
    }
    let mut text = String::from("IESNA:LM-63-2002\n[TEST] grinlight\n[MANUFAC] none\nTILT=NONE\n");
    text += &format!(
        "1 -1 1 {} {} {kind} 2 0 0 0\n1 1 10\n",
        verticals.len(),
        horizontals.len()
    );
    for chunk in numbers.chunks(10) {
        text += &chunk.join(" ");
        text.push('\n');
    }
    text
}

fn degrees(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).round() as usize;
    (0..=n).map(|k| from + step * k as f64).collect()
}

/// A Lambertian downlight I = 100 cos γ tabulated at 1° (one plane: rotationally symmetric):
/// its nodes read back exactly, its power is π·100 (the bilinear table errs by ≤ Δγ²/8 ≈
/// 4e-5 of it: 1e-4), nothing goes upward; and quadrant (0–90°) and bilateral (0–180°) files
/// of I = 100 + 50 cos 2C and 100 + 50 cos C read the same as the full distribution at
/// mirrored angles (1e-9).
#[test]
fn an_ies_table_reads_back_with_its_symmetry() {
    let lambert = ies::parse(&ies_file(&degrees(0.0, 90.0, 1.0), &[0.0], |g, _| {
        100.0 * g.to_radians().cos()
    }))
    .unwrap();
    for g in [0.0f64, 17.0, 45.0, 89.0] {
        let want = 100.0 * g.to_radians().cos();
        assert!((lambert.intensity(g.to_radians(), 1.234) - want).abs() < 1e-9 * 100.0);
    }
    assert_eq!(lambert.intensity(100f64.to_radians(), 0.0), 0.0);
    assert!(
        (lambert.power() / (100.0 * PI) - 1.0).abs() < 1e-4,
        "{}",
        lambert.power()
    );
    let quadrants = Symmetric {
        horizontals: &[0.0, 30.0, 60.0, 90.0],
        intensity: |c| 100.0 + 50.0 * (2.0 * c).to_radians().cos(),
        mirrors: |c| vec![c, 180.0 - c, 180.0 + c, 360.0 - c],
    };
    let bilateral = Symmetric {
        horizontals: &[0.0, 45.0, 90.0, 135.0, 180.0],
        intensity: |c| 100.0 + 50.0 * c.to_radians().cos(),
        mirrors: |c| vec![c, 360.0 - c],
    };
    for case in [quadrants, bilateral] {
        let text = ies_file(&degrees(0.0, 180.0, 10.0), case.horizontals, |_, c| {
            (case.intensity)(c)
        });
        let table = ies::parse(&text).unwrap();
        for &c in case.horizontals {
            for mirrored in (case.mirrors)(c) {
                let got = table.intensity(1.0, mirrored.to_radians());
                let want = (case.intensity)(c);
                assert!(
                    (got - want).abs() < 1e-9,
                    "C = {mirrored}: {got} against {want}"
                );
            }
        }
    }
}

/// An LM-63-2019 file reads as its 2002 twin: the same table once its first line names the
/// 2019 edition and the field 2002 left for future use holds 2019's file-generation type (here
/// 1.10000), which says how the file was made, not what it measures.
#[test]
fn an_lm_63_2019_file_reads_as_its_2002_twin() {
    let old = ies_file(&degrees(0.0, 90.0, 5.0), &[0.0, 90.0], |g, c| {
        100.0 * g.to_radians().cos() + c * 0.1
    });
    let new = old
        .replacen("IESNA:LM-63-2002", "IES:LM-63-2019", 1)
        .replacen("\n1 1 10\n", "\n1 1.10000 10\n", 1);
    assert_ne!(new, old, "the 2019 header and field were written");
    assert_eq!(ies::parse(&new).unwrap(), ies::parse(&old).unwrap());
}

/// A file's horizontal symmetry: the planes it gives, the intensity over C it tabulates and
/// the angles (degrees) where each given plane's intensity recurs.
struct Symmetric {
    horizontals: &'static [f64],
    intensity: fn(f64) -> f64,
    mirrors: fn(f64) -> Vec<f64>,
}

/// Unreadable tables are refused with the reason: a photometric type that is none of A, B and
/// C, type B horizontal angles that are neither −90–90 nor 0–90, a tilt file of its own,
/// too few numbers, descending angles, a negative candela value.
#[test]
fn a_bad_ies_file_is_refused_with_its_reason() {
    let good = ies_file(&[0.0, 90.0], &[0.0], |_, _| 1.0);
    let cases = [
        (
            good.replace("1 -1 1 2 1 1 2", "1 -1 1 2 1 4 2"),
            "2 (type B)",
        ),
        (
            ies_file_of_type(2, &[-90.0, 90.0], &[-45.0, 90.0], |_, _| 1.0),
            "−90 to 90, or 0 to 90",
        ),
        (good.replace("TILT=NONE", "TILT=lamp.tlt"), "tilt file"),
        (
            good.lines().take(6).collect::<Vec<_>>().join("\n"),
            "ends before",
        ),
        (
            ies_file(&[90.0, 0.0], &[0.0], |_, _| 1.0),
            "vertical angles must rise",
        ),
        (ies_file(&[0.0, 90.0], &[0.0], |_, _| -1.0), "≥ 0"),
        ("no such thing\n".to_string(), "TILT="),
    ];
    for (text, needle) in cases {
        let e = ies::parse(&text).unwrap_err();
        assert!(e.contains(needle), "{e:?} lacks {needle:?}");
    }
}

/// Photons from a luminaire carry its power without bias: over 2·10⁵ photons of the
/// cos γ downlight turned to nadir −y, the mean photon power is its power (4 standard
/// errors) and no photon leaves upward.
#[test]
fn a_luminaires_photons_carry_its_power() {
    let table = ies::parse(&ies_file(&degrees(0.0, 90.0, 5.0), &[0.0], |g, _| {
        100.0 * g.to_radians().cos()
    }))
    .unwrap();
    let power = table.power();
    let light = Light::Goniometric {
        position: DVec3::ZERO,
        aim: Luminaire::new(-DVec3::Y, DVec3::X),
        colour: grinlight::color::Rgb::ONE,
        map: std::sync::Arc::new(IntensityMap::Table(table)),
    };
    let aim = Aim::whole(
        Ball {
            center: DVec3::ZERO,
            radius: 1.0,
        },
        Entry::Upstream,
    );
    let n = 200_000;
    let (mut sum, mut sum2) = (0.0, 0.0);
    for k in 0..n {
        let u = |a: u64| grinlight::sampling::mix(k * 4 + a) as f64 / u64::MAX as f64;
        let Some(e) = light.emit([u(0), u(1), u(2), u(3)], aim) else {
            continue;
        };
        assert!(e.direction.y <= 1e-12, "upward: {}", e.direction);
        let p = e.power.0.x;
        sum += p;
        sum2 += p * p;
    }
    let mean = sum / n as f64;
    let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
    assert!(
        (mean - power).abs() <= 4.0 * se + 1e-12,
        "{mean} ± {se} against {power}"
    );
}

/// The unit direction of horizontal angle `h` and vertical angle `v` (degrees) of type B
/// (`kind` 2) or A (3) photometry in the luminaire's frame (x along C = 0, y along C = 90°, z
/// the nadir), as IES LM-63 places their webs: B's polar axis the luminaire's width y, A's
/// its length x, the photometric axis (0°, 0°) the nadir.
fn lateral_direction(kind: u8, h: f64, v: f64) -> DVec3 {
    let (h, v) = (h.to_radians(), v.to_radians());
    match kind {
        2 => DVec3::new(h.cos() * v.sin(), h.sin(), h.cos() * v.cos()),
        3 => DVec3::new(v.sin(), v.cos() * h.sin(), v.cos() * h.cos()),
        other => panic!("photometric type {other} has no lateral angles"),
    }
}

/// A goniometric light of `table` at the origin, its nadir −y and its C = 0 direction x.
fn luminaire_of(table: grinlight::photometry::Goniogram) -> Light {
    Light::Goniometric {
        position: DVec3::ZERO,
        aim: Luminaire::new(-DVec3::Y, DVec3::X),
        colour: grinlight::color::Rgb::ONE,
        map: std::sync::Arc::new(IntensityMap::Table(table)),
    }
}

/// The world direction of `local` (the luminaire's frame) for [`luminaire_of`]'s light.
fn world_of(local: DVec3) -> DVec3 {
    let aim = Luminaire::new(-DVec3::Y, DVec3::X);
    aim.c0 * local.x + aim.c90 * local.y + aim.nadir * local.z
}

/// Type B and A tables lie on the luminaire as IES LM-63 places their webs: for I = 200 + H +
/// V/2 (degrees), linear in the web's angles so that bilinear interpolation between nodes 15°
/// apart in H and 10° in V is exact, the light's intensity toward 120 directions between the
/// nodes is the formula's (1e-9 relative) — a transposed or mirrored web misses by up to 90
/// cd — and nothing leaves behind the luminaire. A laterally symmetric file (H from 0° to 90°)
/// reads I(−H) = I(H).
#[test]
fn type_b_and_a_tables_lie_on_the_luminaire_as_lm_63_places_them() {
    let formula = |v: f64, h: f64| 200.0 + h + 0.5 * v;
    let symmetric = |v: f64, h: f64| 200.0 + h.abs() + 0.5 * v;
    for kind in [2u8, 3] {
        let full = ies_file_of_type(
            kind,
            &degrees(-90.0, 90.0, 10.0),
            &degrees(-90.0, 90.0, 15.0),
            formula,
        );
        let half = ies_file_of_type(
            kind,
            &degrees(-90.0, 90.0, 10.0),
            &degrees(0.0, 90.0, 15.0),
            symmetric,
        );
        for (text, want) in [
            (full, &formula as &dyn Fn(f64, f64) -> f64),
            (half, &symmetric),
        ] {
            let light = luminaire_of(ies::parse(&text).unwrap());
            for k in 0..12 {
                for m in 0..10 {
                    let (h, v) = (-86.0 + 15.1 * k as f64, -84.0 + 17.9 * m as f64);
                    let dir = world_of(lateral_direction(kind, h, v));
                    let got = light.intensity(dir).0.x;
                    let expected = want(v, h);
                    assert!(
                        (got - expected).abs() < 1e-9 * expected,
                        "type {kind}, H {h}, V {v}: {got} against {expected}"
                    );
                }
            }
            assert_eq!(
                light.intensity(world_of(-DVec3::Z)).0.x,
                0.0,
                "type {kind} behind"
            );
        }
    }
}

/// A type B or A luminaire's power and photons: I = 110 + d·(30, 20, 100) in the luminaire's
/// frame, over the front half (d·nadir ≥ 0), tabulated at 1° in H and V. Its power is
/// 110·2π + 100·π (the bilinear table errs by O(Δ²) ≈ 1e-4 of it: 3e-4), and the photons'
/// power through a cap of half-angle 8° about five of the file's directions, over the cap's
/// solid angle, is the mean intensity over the cap, 110 + b·d(1 + cos 8°)/2 exactly for an
/// affine I — the far-field intensity a receiver sphere measures. 10⁷ photons, 4 standard
/// errors (each about 0.3 %).
#[test]
fn type_b_and_a_luminaires_send_their_tables_power_and_intensity() {
    let b = DVec3::new(30.0, 20.0, 100.0);
    let alpha = 8f64.to_radians();
    let cap = std::f64::consts::TAU * (1.0 - alpha.cos());
    let nodes = [
        (0.0, 0.0),
        (40.0, -20.0),
        (-55.0, 10.0),
        (20.0, 60.0),
        (-30.0, -50.0),
    ];
    for kind in [2u8, 3] {
        let text = ies_file_of_type(
            kind,
            &degrees(-90.0, 90.0, 1.0),
            &degrees(-90.0, 90.0, 1.0),
            |v, h| 110.0 + b.dot(lateral_direction(kind, h, v)),
        );
        let table = ies::parse(&text).unwrap();
        let power = 110.0 * 2.0 * PI + 100.0 * PI;
        assert!(
            (table.power() / power - 1.0).abs() < 3e-4,
            "type {kind}: {} against {power}",
            table.power()
        );
        let light = luminaire_of(table);
        let aim = Aim::whole(
            Ball {
                center: DVec3::ZERO,
                radius: 1.0,
            },
            Entry::Upstream,
        );
        let axes: Vec<DVec3> = nodes
            .iter()
            .map(|&(h, v)| lateral_direction(kind, h, v))
            .collect();
        let n = 10_000_000u64;
        let mut sums = vec![(0.0, 0.0); axes.len()];
        for k in 0..n {
            let u = |a: u64| {
                grinlight::sampling::mix((k * 4 + a) ^ u64::from(kind) << 40) as f64
                    / u64::MAX as f64
            };
            let Some(e) = light.emit([u(0), u(1), u(2), u(3)], aim) else {
                continue;
            };
            let aim_frame = Luminaire::new(-DVec3::Y, DVec3::X);
            let local = DVec3::new(
                e.direction.dot(aim_frame.c0),
                e.direction.dot(aim_frame.c90),
                e.direction.dot(aim_frame.nadir),
            );
            for (axis, sum) in axes.iter().zip(sums.iter_mut()) {
                if local.dot(*axis) >= alpha.cos() {
                    let p = e.power.0.x;
                    sum.0 += p;
                    sum.1 += p * p;
                }
            }
        }
        for ((axis, &(sum, sum2)), node) in axes.iter().zip(&sums).zip(nodes) {
            let mean = sum / n as f64 / cap;
            let se = ((sum2 / n as f64 - (sum / n as f64).powi(2)) / n as f64).sqrt() / cap;
            let want = 110.0 + b.dot(*axis) * (1.0 + alpha.cos()) / 2.0;
            assert!(
                (mean - want).abs() <= 4.0 * se,
                "type {kind} at (H, V) = {node:?}: {mean} ± {se} against {want}"
            );
            assert!(
                se < 0.004 * want,
                "type {kind}: standard error {se} of {want}"
            );
        }
    }
}

/// The scene's `beauty` layer rendered by each integrator.
fn beauty_by_integrator(
    scene: &grinlight::scene::Scene,
    settings: &grinlight::settings::Settings,
) -> Vec<(grinlight::settings::IntegratorKind, Vec<[f32; 3]>)> {
    grinlight::settings::IntegratorKind::ALL
        .into_iter()
        .map(|integrator| {
            let settings = grinlight::settings::Settings {
                integrator,
                ..settings.clone()
            };
            let film = grinlight::render::render(scene, &settings, &()).unwrap().0;
            (integrator, film.layer("beauty").unwrap())
        })
        .collect()
}

/// The white spherical room of albedo ρ = 0.5 lit by a luminaire at its centre whose IES table
/// is I = I₀ cos γ downward (I₀ = 1, at 1°): each pixel reads (ρ/π)(I(ω) + ρΦ/(A(1 − ρ))),
/// Φ = π I₀, as for the other lights; both integrators, image mean within 1 %.
#[test]
fn a_luminaire_lights_a_white_spherical_room_as_an_integrating_sphere_does() {
    let dir = std::env::temp_dir().join(format!("grinlight-ies-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("down.ies"),
        ies_file(&degrees(0.0, 90.0, 1.0), &[0.0], |g, _| {
            g.to_radians().cos()
        }),
    )
    .unwrap();
    let rho = 0.5;
    let text = crate::common::white_spherical_room(rho, [0.0, -0.6, -1.0])
        + "[[light]]\ntype = \"goniometric\"\nfile = \"down.ies\"\nposition = [0, 0, 0]\n";
    let path = dir.join("room.toml");
    let (scene, settings) = parse_scene(&path, text).unwrap();
    let camera = scene.camera.as_ref().unwrap();
    let bounced = rho * PI / (4.0 * PI * (1.0 - rho));
    let (w, h) = (camera.width as usize, camera.height as usize);
    let expected: f64 = (0..w * h)
        .map(|i| {
            let d = camera.direction((i % w) as u32, (i / w) as u32, 0.5, 0.5);
            rho / PI * ((-d.y).max(0.0) + bounced)
        })
        .sum::<f64>()
        / (w * h) as f64;
    for (integrator, pixels) in beauty_by_integrator(&scene, &settings) {
        let mean = pixels.iter().map(|p| p[1] as f64).sum::<f64>() / pixels.len() as f64;
        println!("luminaire, {integrator:?}: {mean:.5} against {expected:.5}");
        assert!(
            (mean - expected).abs() <= 0.01 * expected,
            "{integrator:?}: {mean} against {expected}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An intensity over (γ, C) in degrees.
type Distribution = fn(f64, f64) -> f64;

/// A EULUMDAT file of Isym `symmetry` over `mc` C planes (every 360/mc degrees) and γ every
/// 10°, its stored planes (as the format counts them) holding `intensity(γ, C)` in cd/klm,
/// lamps of 2000 lm in all and a conversion factor of 1.5.
fn ldt_file(symmetry: usize, mc: usize, intensity: impl Fn(f64, f64) -> f64) -> String {
    let step = 360.0 / mc as f64;
    let gammas = degrees(0.0, 180.0, 10.0);
    let stored: Vec<f64> = match symmetry {
        0 => (0..mc).map(|i| i as f64 * step).collect(),
        1 => vec![0.0],
        2 => (0..=mc / 2).map(|i| i as f64 * step).collect(),
        3 => (0..=mc / 2)
            .map(|i| (270.0 + i as f64 * step) % 360.0)
            .collect(),
        _ => (0..=mc / 4).map(|i| i as f64 * step).collect(),
    };
    let mut lines: Vec<String> = vec![
        "grinlight test".into(),
        "1".into(),
        symmetry.to_string(),
        mc.to_string(),
        step.to_string(),
        gammas.len().to_string(),
        "10".into(),
    ];
    lines.extend(["r", "name", "no", "file.ldt", "today"].map(String::from));
    lines.extend(
        [
            "100", "100", "50", "90", "90", "0", "0", "0", "0", "100", "80",
        ]
        .map(String::from),
    );
    lines.extend(["1,5", "0", "2"].map(String::from));
    for field in [
        ["1", "1"],
        ["LED", "LED"],
        ["1200", "800"],
        ["3000K", "3000K"],
        ["80", "80"],
        ["20", "15"],
    ] {
        lines.extend(field.map(String::from));
    }
    lines.extend((0..10).map(|_| "0.5".to_string()));
    lines.extend((0..mc).map(|i| (i as f64 * step).to_string()));
    lines.extend(gammas.iter().map(|g| g.to_string()));
    for c in stored {
        lines.extend(gammas.iter().map(|&g| format!("{:.9}", intensity(g, c))));
    }
    lines.join("\r\n") + "\r\n"
}

/// EULUMDAT tables of each symmetry, holding a distribution with that symmetry, read back at
/// every plane of the full turn as the distribution itself (1e-9 of it): cd/klm times the lamp
/// sets' 2000 lm over 1000 times the conversion factor 1.5; and a table that stops short is
/// refused with the line it lacks.
#[test]
fn a_eulumdat_table_reads_back_with_its_symmetry() {
    use grinlight::photometry::eulumdat;
    let cases: [(usize, Distribution); 5] = [
        (0, |g, c| {
            100.0 + g + 30.0 * c.to_radians().cos() + 10.0 * c.to_radians().sin()
        }),
        (1, |g, _| 100.0 + g),
        (2, |g, c| 100.0 + g + 30.0 * c.to_radians().cos()),
        (3, |g, c| 100.0 + g + 30.0 * c.to_radians().sin()),
        (4, |g, c| 100.0 + g + 30.0 * (2.0 * c).to_radians().cos()),
    ];
    for (symmetry, f) in cases {
        let table = eulumdat::parse(&ldt_file(symmetry, 24, f)).unwrap();
        for i in 0..24 {
            let c = i as f64 * 15.0;
            for g in [0.0f64, 40.0, 170.0] {
                let got = table.intensity(g.to_radians(), c.to_radians());
                let want = f(g, c) * 2.0 * 1.5;
                assert!(
                    (got - want).abs() < 1e-9 * want,
                    "Isym {symmetry}, C {c}, γ {g}: {got} against {want}"
                );
            }
        }
    }
    let short: String = ldt_file(1, 24, |_, _| 1.0)
        .lines()
        .take(30)
        .collect::<Vec<_>>()
        .join("\n");
    let e = eulumdat::parse(&short).unwrap_err();
    assert!(e.contains("ends before"), "{e}");
}

/// An 8 × 8 intensity image whose pixel (x, y) holds 1 + x + 8y (a different value in each).
fn ramp_image() -> (usize, Vec<f64>) {
    (8, (0..64).map(|i| 1.0 + i as f64).collect())
}

/// An equal-area intensity image as a luminaire: toward each direction the intensity of the
/// pixel the direction lies in, in the luminaire's frame (the image's +z the zenith, opposite
/// the nadir; +x the C = 0 direction, +y C = 90°, or C = 270° with its rows flipped); its power
/// 4π/N² times the pixels' sum, exactly; and every photon it sends carries that power (1e-9)
/// along a direction in the pixel it was drawn from, the pixels drawn in proportion to their
/// intensity (χ² over 6.4·10⁵ photons below the 10⁻⁴ quantile for 63 degrees of freedom, 113.7).
#[test]
fn an_equal_area_image_sends_each_pixels_intensity_its_way() {
    use grinlight::equal_area::{pixel, sphere_to_square};
    let (n, values) = ramp_image();
    let sum: f64 = values.iter().sum();
    let power = 4.0 * PI * sum / (n * n) as f64;
    let aim = Luminaire::new(DVec3::new(0.0, 0.0, -1.0), DVec3::new(1.0, 1.0, 0.0));
    for flip_v in [false, true] {
        let image = IntensityImage::new(n, values.clone()).with_flip_v(flip_v);
        assert!((image.power() - power).abs() < 1e-12 * power);
        let light = Light::Goniometric {
            position: DVec3::ZERO,
            aim,
            colour: grinlight::color::Rgb::ONE,
            map: std::sync::Arc::new(IntensityMap::Image(image)),
        };
        // The frame: x along c0 = (1, 1, 0)/√2, y along c90 = zenith × c0, z the zenith +z.
        let (x, z) = (DVec3::new(1.0, 1.0, 0.0).normalize(), DVec3::Z);
        let y = z.cross(x) * if flip_v { -1.0 } else { 1.0 };
        let pixel_of = |w: DVec3| {
            let (i, j) = pixel(
                sphere_to_square(DVec3::new(w.dot(x), w.dot(y), w.dot(z))),
                n,
            );
            j * n + i
        };
        for k in 0..2000u64 {
            let h = grinlight::sampling::mix(k);
            let u = (
                (h >> 32) as f64 / 2f64.powi(32),
                (h & 0xffff_ffff) as f64 / 2f64.powi(32),
            );
            let w = grinlight::sampling::uniform_sphere(u);
            assert_eq!(light.intensity(w).0.x, values[pixel_of(w)], "{w}");
        }
        // Straight along the image's axes: the centre pixels' values at +z, the corners' at −z.
        let centre = light.intensity(z).0.x;
        assert!(
            [28.0, 29.0, 36.0, 37.0].map(|i| 1.0 + i).contains(&centre),
            "{centre}"
        );
        let aim_all = grinlight::lights::Aim::whole(
            Ball {
                center: DVec3::ZERO,
                radius: 1.0,
            },
            Entry::Upstream,
        );
        let draws = 640_000u64;
        let mut counts = vec![0u64; n * n];
        for k in 0..draws {
            let u = |a: u64| grinlight::sampling::mix(k * 4 + a) as f64 / u64::MAX as f64;
            let e = light
                .emit([u(0), u(1), u(2), u(3)], aim_all)
                .expect("a photon");
            assert!(
                (e.power.0.x - power).abs() < 1e-9 * power,
                "{}",
                e.power.0.x
            );
            counts[pixel_of(e.direction)] += 1;
        }
        let chi2: f64 = counts
            .iter()
            .zip(&values)
            .map(|(&c, v)| {
                let expected = draws as f64 * v / sum;
                (c as f64 - expected).powi(2) / expected
            })
            .sum();
        assert!(chi2 < 113.7, "flip_v {flip_v}: χ² {chi2}");
    }
}

/// The white spherical room of albedo ρ = 0.5 lit by an equal-area intensity image (an EXR, 8 ×
/// 8, pixel (x, y) holding 1 + x + 8y in R, G and B) at its centre, turned by `direction` and
/// `c0`: each pixel reads (ρ/π)(I(ω) + ρΦ/(A(1 − ρ))), I(ω) the image's pixel toward the
/// camera ray's direction (the camera at the centre too), Φ its power; both integrators, the
/// image's quadrants' means each within 1 % (a frame turned by a quarter turn or mirrored
/// puts them off by 2 % or more).
#[test]
fn an_intensity_image_lights_a_white_spherical_room_as_an_integrating_sphere_does() {
    use grinlight::equal_area::{pixel, sphere_to_square};
    let dir = std::env::temp_dir().join(format!("grinlight-gonio-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (n, values) = ramp_image();
    image::Rgb32FImage::from_fn(n as u32, n as u32, |x, y| {
        image::Rgb([values[(y * n as u32 + x) as usize] as f32; 3])
    })
    .save(dir.join("map.exr"))
    .unwrap();
    let rho = 0.5;
    let text = crate::common::white_spherical_room(rho, [0.0, -0.6, -1.0])
        + "[[light]]\ntype = \"goniometric\"\nfile = \"map.exr\"\nposition = [0, 0, 0]\n\
           direction = [0, 0, 1]\nc0 = [0, 1, 0]\nscale = 0.02\n";
    let path = dir.join("room.toml");
    let (scene, settings) = parse_scene(&path, text).unwrap();
    let camera = scene.camera.as_ref().unwrap();
    let sum: f64 = values.iter().sum();
    let power = 0.02 * 4.0 * PI * sum / (n * n) as f64;
    let bounced = rho * power / (4.0 * PI * (1.0 - rho));
    // The image's frame: x = c0 = +y, z = −direction = −z, y = z × x = +x.
    let (x, y, z) = (DVec3::Y, DVec3::X, -DVec3::Z);
    let (w, h) = (camera.width as usize, camera.height as usize);
    let quadrant = |i: usize| usize::from(i % w >= w / 2) + 2 * usize::from(i / w >= h / 2);
    let mut expected = [0.0; 4];
    for i in 0..w * h {
        let d = camera.direction((i % w) as u32, (i / w) as u32, 0.5, 0.5);
        let (a, b) = pixel(
            sphere_to_square(DVec3::new(d.dot(x), d.dot(y), d.dot(z))),
            n,
        );
        expected[quadrant(i)] +=
            rho / PI * (0.02 * values[b * n + a] + bounced) / (w * h / 4) as f64;
    }
    for (integrator, pixels) in beauty_by_integrator(&scene, &settings) {
        let mut mean = [0.0; 4];
        for (i, p) in pixels.iter().enumerate() {
            mean[quadrant(i)] += p[1] as f64 / (w * h / 4) as f64;
        }
        println!("intensity image, {integrator:?}: quadrants {mean:.5?} against {expected:.5?}");
        for (m, e) in mean.iter().zip(&expected) {
            assert!(
                (m - e).abs() <= 0.01 * e,
                "{integrator:?}: {mean:?} against {expected:?}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
