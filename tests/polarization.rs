//! Polarization. The field carried along traced rays (Rytov's law): the geometric phase of a helical ray in
//! a parabolic-index fiber against its closed form, and a meridional ray's, which is none.

use glam::DVec3;
use grinlight::commands::{trace_ray, RayTrace, TraceControl};
use grinlight::curve::StepperKind;
use std::f64::consts::TAU;

/// The scenes/media.toml fiber `grin_rod`: n = n0 (1 − a r²/2) about the z axis.
const N0: f64 = 1.5;
const A: f64 = 0.1;

/// The geometric phase, the field and the direction at the end of the ray from `from` along
/// `dir` over `length` with the field starting along `field`.
fn traced(
    (from, dir, length): (DVec3, DVec3, f64),
    stepper: StepperKind,
    tolerance: f64,
    field: DVec3,
) -> (f64, DVec3, DVec3) {
    let (scene, _) =
        grinlight::scene::load_scene(std::path::Path::new("scenes/media.toml")).unwrap();
    let ray = RayTrace {
        medium: "grin_rod".into(),
        from,
        dir,
        length,
        wavelength: None,
        stepper,
        control: TraceControl::Adaptive {
            tolerance: Some(tolerance),
        },
        max_steps: RayTrace::MAX_STEPS,
        polarization: Some(field),
    };
    let t = trace_ray(&scene, &ray, &()).unwrap();
    let p = t.polarization.expect("asked for");
    (p.phase, p.field, t.outcome.state.direction)
}

/// A skew ray at radius ρ whose direction makes the angle θ with the axis, sin²θ = n0 a ρ²/n(ρ)
/// (the index's pull n0 a ρ balancing the helix's curvature n sin²θ/ρ), stays at ρ: a helix
/// whose direction turns about the axis on a circle, sweeping 2π(1 − cos θ) a turn (Tomita and
/// Chiao's phase). After 1 and 5 turns, RKN6(4) at tolerance 1e-12 and the arc chain at 1e-9
/// give it within 1e-12 rad (measured: 6e-15 and 5.2e-14; 6e-15 and 2.1e-13). The field ends
/// perpendicular to the ray.
#[test]
fn a_helical_ray_in_a_parabolic_fiber_turns_its_field_by_the_solid_angle_it_sweeps() {
    let rho = 1.0;
    let n = N0 * (1.0 - 0.5 * A * rho * rho);
    let sin_theta = (N0 * A * rho * rho / n).sqrt();
    let cos_theta = (1.0 - sin_theta * sin_theta).sqrt();
    let turn = TAU * rho / sin_theta;
    let from = DVec3::new(rho, 0.0, 0.0);
    let dir = DVec3::new(0.0, sin_theta, cos_theta);
    for (stepper, tolerance, within) in [
        (StepperKind::Rkn, 1e-12, 1e-12),
        (StepperKind::Arc, 1e-9, 1e-12),
    ] {
        for turns in [1.0, 5.0] {
            let (phase, field, end) =
                traced((from, dir, turns * turn), stepper, tolerance, DVec3::X);
            let want = turns * TAU * (1.0 - cos_theta);
            println!("{stepper:?} {turns} turns: Γ {phase:.15} against {want:.15}");
            assert!(
                (phase - want).abs() < within,
                "{stepper:?}, {turns} turns: {phase} against {want}"
            );
            assert!(field.dot(end).abs() < 1e-12);
            assert!((field.length() - 1.0).abs() < 1e-12);
        }
    }
}

/// A meridional ray (in a plane through the axis) sweeps no solid angle: Γ = 0 to 1e-12 and
/// the field perpendicular to that plane stays as it was, over three of its periods.
#[test]
fn a_meridional_ray_keeps_its_field() {
    let pitch = TAU / A.sqrt();
    let ray = (
        DVec3::new(0.5, 0.0, 0.0),
        DVec3::new(0.1, 0.0, 1.0),
        3.0 * pitch,
    );
    let (phase, field, _) = traced(ray, StepperKind::Rkn, 1e-10, DVec3::Y);
    assert!(phase.abs() < 1e-12, "{phase}");
    assert!((field - DVec3::Y).length() < 1e-12, "{field}");
}

/// The command line prints the field and the phase; a field along the ray is refused, naming
/// the option.
#[test]
fn the_command_line_reports_the_phase_and_refuses_a_field_along_the_ray() {
    let run = |field: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_grinlight"))
            .args([
                "trace",
                "scenes/media.toml",
                "--medium",
                "grin_rod",
                "--from",
                "0.5,0,0",
                "--dir",
                "0,0.2,1",
                "--length",
                "30",
                "--polarization",
                field,
            ])
            .output()
            .expect("run grinlight")
    };
    let out = run("1,0,0");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(text.contains("geometric phase"), "{text}");
    let out = run("0,0.4,2");
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        text.contains("polarization") && text.contains("parallel"),
        "{text}"
    );
}

// Polarized transport (`[render] polarized`, or a polarizer or retarder in the scene): photons
// carry Stokes vectors to receivers, camera paths a measurement row; each against its closed
// form.

use grinlight::receiver::Measurement;
use grinlight::settings::Settings;

/// Parses scene `text` (a test's own, at a made-up path).
fn scene(text: &str) -> (grinlight::scene::Scene, Settings) {
    grinlight::scene::load::parse_scene(std::path::Path::new("polarized.toml"), text.into())
        .unwrap()
}

/// The receivers' measurements of `text` with `photons` receiver photons.
fn measured(text: &str, photons: u64) -> Vec<Measurement> {
    let (scene, mut settings) = scene(text);
    settings.receiver_photons = photons;
    grinlight::render::measure(&scene, &settings, 0, &())
        .unwrap()
        .0
}

/// A square of side 2·`half` across the z axis at height `z`, of material `material`.
fn square(z: f64, half: f64, material: &str) -> String {
    let h = half;
    format!(
        "[[shape]]\ntype = \"quad\"\nmaterial = \"{material}\"\n\
         vertices = [[-{h}, -{h}, {z}], [{h}, -{h}, {z}], [{h}, {h}, {z}], [-{h}, {h}, {z}]]\n"
    )
}

/// A unit parallel beam along +z, sheets across it at z = 1, 2, ... (materials given), and a
/// receiver of one bin, 1 × 1, at z = 4 with u = x.
fn beam_through(materials: &[String]) -> String {
    let mut text = String::from(
        "[[light]]\ntype = \"directional\"\ndirection = [0, 0, 1]\nirradiance = [1, 1, 1]\n\
         [[receiver]]\nname = \"r\"\ncenter = [0, 0, 4]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\n\
         size = [1, 1]\nbins = [1, 1]\n",
    );
    for (i, m) in materials.iter().enumerate() {
        text += &format!("[[material]]\nname = \"m{i}\"\n{m}");
        text += &square(1.0 + i as f64, 2.0, &format!("m{i}"));
    }
    text
}

fn polarizer(deg: f64) -> String {
    let t = deg.to_radians();
    format!(
        "type = \"polarizer\"\naxis = [{}, {}, 0]\n",
        t.cos(),
        t.sin()
    )
}

/// The flux's gap from `want` in combined standard errors.
fn z(m: &Measurement, want: (f64, f64)) -> f64 {
    (m.flux.0 - want.0).abs() / m.flux.1.hypot(want.1)
}

/// Malus's law on a receiver: behind polarizers at 0° and θ a parallel beam keeps ½cos²θ of its
/// flux (within 4 standard errors of the open beam's flux, itself the closed form 1 W), and what
/// arrives is polarized along the second axis: S1/S0 = cos 2θ, S2/S0 = sin 2θ in the receiver's
/// basis (u = x; every photon alike, so exact to the f32 a detection keeps, 1e-6).
#[test]
fn malus_law_on_a_receiver_behind_two_polarizers() {
    let photons = 200_000;
    let open = &measured(&beam_through(&[]), photons)[0];
    assert!(z(open, (1.0, 0.0)) < 4.0, "open beam: {:?}", open.flux);
    assert!(
        open.stokes.is_empty(),
        "unpolarized transport measures no Stokes components"
    );
    for deg in [0.0, 30.0, 60.0, 90.0] {
        let m = &measured(&beam_through(&[polarizer(0.0), polarizer(deg)]), photons)[0];
        if deg == 90.0 {
            assert_eq!(m.flux.0, 0.0, "crossed polarizers pass nothing");
            continue;
        }
        let share = 0.5 * f64::to_radians(deg).cos().powi(2);
        let want = (share * open.flux.0, share * open.flux.1);
        assert!(z(m, want) < 4.0, "{deg}°: {:?} against {want:?}", m.flux);
        let [s1, s2, s3] = [0, 1, 2].map(|i| m.stokes[i].flux.0 / m.flux.0);
        let t = f64::to_radians(2.0 * deg);
        assert!((s1 - t.cos()).abs() < 1e-6, "{deg}°: S1/S0 {s1}");
        assert!((s2 - t.sin()).abs() < 1e-6, "{deg}°: S2/S0 {s2}");
        assert!(s3.abs() < 1e-6, "{deg}°: S3/S0 {s3}");
    }
}

/// A quarter-wave plate with its fast axis at 45° to a linear polarization makes it circular
/// (S3/S0 = +1, right-handed seen by the receiver in Mitsuba 3's convention; −1 with the axis
/// at −45°) and passes all of it; a
/// half-wave plate at 22.5° turns it to 45°.
#[test]
fn wave_plates_turn_linear_light_circular_and_rotate_it() {
    let retarder = |deg: f64, retardance: f64| {
        let t = deg.to_radians();
        format!(
            "type = \"retarder\"\nfast_axis = [{}, {}, 0]\nretardance_deg = {retardance}\n",
            t.cos(),
            t.sin()
        )
    };
    let photons = 50_000;
    let linear = &measured(&beam_through(&[polarizer(0.0)]), photons)[0];
    for (deg, retardance, want) in [
        (45.0, 90.0, [0.0, 0.0, 1.0]),
        (-45.0, 90.0, [0.0, 0.0, -1.0]),
        (22.5, 180.0, [0.0, 1.0, 0.0]),
    ] {
        let m = &measured(
            &beam_through(&[polarizer(0.0), retarder(deg, retardance)]),
            photons,
        )[0];
        // The plate absorbs nothing and draws no numbers: the same photons arrive.
        assert_eq!(m.flux, linear.flux, "{deg}°");
        for (i, (component, want)) in m.stokes.iter().zip(want).enumerate() {
            let s = component.flux.0 / m.flux.0;
            assert!(
                (s - want).abs() < 1e-6,
                "{deg}°, {retardance}°: S{} {s}",
                i + 1
            );
        }
    }
}

/// Light reflected by glass at Brewster's angle is wholly s polarized (S1/S0 = 1 in a basis
/// whose first axis is the normal to the plane of incidence: every photon alike, 1e-6) — what
/// is reflected inside the plate and leaves through its top is too, as the internal angle is
/// Brewster's as well; a polarizer across s then passes nothing, one along s all of it (within
/// 4 standard errors). A black shield keeps the falling beam off the receiver; it casts its
/// shadow on the plate far from where the receiver's light is reflected.
#[test]
fn brewsters_reflection_is_s_polarized_and_a_crossed_polarizer_removes_it() {
    let brewster = 1.5f64.atan();
    let (s, c) = brewster.sin_cos();
    // The beam comes down in the x–y plane onto the plate's top (y = 0); s is z.
    let down = DVec3::new(s, -c, 0.0);
    let reflected = DVec3::new(s, c, 0.0);
    let at = 2.0 * reflected;
    let up = reflected.cross(DVec3::Z);
    let quad = |centre: DVec3, e1: DVec3, e2: DVec3| {
        let v = [
            centre - e1 - e2,
            centre + e1 - e2,
            centre + e1 + e2,
            centre - e1 + e2,
        ];
        v.map(|q| format!("[{}, {}, {}]", q.x, q.y, q.z)).join(", ")
    };
    let shield = quad(at - down, 0.3 * down.cross(DVec3::Z), 0.3 * DVec3::Z);
    let scene = |polarizer_axis: Option<DVec3>| {
        let mut text = format!(
            "[[light]]\ntype = \"directional\"\ndirection = [{}, {}, 0]\nirradiance = [1, 1, 1]\n\
             [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\
             [[shape]]\ntype = \"box\"\nmin = [-3, -1, -3]\nmax = [3, 0, 3]\nmaterial = \"glass\"\n\
             [[material]]\nname = \"black\"\ntype = \"diffuse\"\nalbedo = [0, 0, 0]\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"black\"\nvertices = [{shield}]\n\
             [[receiver]]\nname = \"r\"\ncenter = [{}, {}, 0]\nnormal = [{s}, {c}, 0]\n\
             up = [{}, {}, {}]\nsize = [0.5, 0.5]\nbins = [1, 1]\n",
            down.x, down.y, at.x, at.y, up.x, up.y, up.z
        );
        match polarizer_axis {
            Some(a) => {
                text += &format!(
                    "[[material]]\nname = \"p\"\ntype = \"polarizer\"\naxis = [{}, {}, {}]\n\
                     [[shape]]\ntype = \"quad\"\nmaterial = \"p\"\nvertices = [{}]\n",
                    a.x,
                    a.y,
                    a.z,
                    quad(1.5 * reflected, 0.4 * up, 0.4 * DVec3::Z)
                );
            }
            None => text += "[render]\npolarized = true\n",
        }
        text
    };
    let photons = 400_000;
    let plain = &measured(&scene(None), photons)[0];
    assert!(
        plain.flux.0 > 10.0 * plain.flux.1,
        "enough light: {:?}",
        plain.flux
    );
    let [s1, s2, s3] = [0, 1, 2].map(|i| plain.stokes[i].flux.0 / plain.flux.0);
    assert!(
        (s1 - 1.0).abs() < 1e-6 && s2.abs() < 1e-6 && s3.abs() < 1e-6,
        "{s1} {s2} {s3}"
    );
    let crossed = &measured(&scene(Some(up)), photons)[0];
    assert_eq!(crossed.flux.0, 0.0);
    let along = &measured(&scene(Some(DVec3::Z)), photons)[0];
    assert!(
        z(along, plain.flux) < 4.0,
        "{:?} {:?}",
        along.flux,
        plain.flux
    );
}

/// Along a curved path the basis is carried by Rytov's law. A beam enters square on a slab whose
/// index rises along y and turns in the y–z plane; a polarizer in the slab 0.01 past its face
/// (where the beam has turned 5e-4 rad) polarizes it at 45° between x and y, and the field
/// turns with the beam (parallel transport in a plane), so on a receiver in the slab it arrives
/// polarized at 45° between x and k × x: S2/S0 = 1 (1e-6), though its direction turned by more
/// than 0.15 rad on the way. (A basis only projected across the new direction would read
/// S1/S0 = cos 2·atan(cos 0.15) = 0.011.) A black sheet in the slab beyond the
/// receiver takes the light before the far face can reflect it back across the receiver.
#[test]
fn a_bent_beam_carries_its_polarization_along_its_path() {
    let axis = std::f64::consts::FRAC_1_SQRT_2;
    let text = format!(
        "[[medium]]\nname = \"slab\"\nprofile = \"linear\"\nn0 = 1.5\ngradient = [0, 0.075, 0]\n\
         [[material]]\nname = \"wall\"\ntype = \"dielectric\"\ninterior = \"slab\"\n\
         [[shape]]\ntype = \"box\"\nmin = [-4, -4, 2]\nmax = [4, 4, 8]\nmaterial = \"wall\"\n\
         [[material]]\nname = \"black\"\ntype = \"diffuse\"\nalbedo = [0, 0, 0]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"black\"\n\
         vertices = [[-4, -4, 7], [4, -4, 7], [4, 4, 7], [-4, 4, 7]]\n\
         [[light]]\ntype = \"directional\"\ndirection = [0, 0, 1]\nirradiance = [1, 1, 1]\n\
         [[material]]\nname = \"p\"\ntype = \"polarizer\"\naxis = [{axis}, {axis}, 0]\n{}\
         [[receiver]]\nname = \"r\"\ncenter = [0, 0.8, 6]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\n\
         size = [1, 1]\nbins = [1, 1]\n",
        square(2.01, 3.9, "p")
    );
    let (scene, settings) = scene(&text);
    // How far a ray entering the slab at the receiver's x turns before it: the test is one of
    // transport, not of a straight beam.
    let tracer = grinlight::transport::Tracer::new(&scene, &settings.trace);
    let mut stats = grinlight::transport::Stats::default();
    let slab = Some(grinlight::ids::MediumId::new(0));
    let event = tracer.next_event(DVec3::new(0.0, 0.0, 2.02), DVec3::Z, slab, &mut stats);
    let turned = event.direction().unwrap().angle_between(DVec3::Z);
    assert!(turned > 0.15, "the beam turns {turned} rad");
    let m = &measured(&text, 100_000)[0];
    assert!(m.flux.0 > 10.0 * m.flux.1, "{:?}", m.flux);
    let [s1, s2, s3] = [0, 1, 2].map(|i| m.stokes[i].flux.0 / m.flux.0);
    assert!(
        s1.abs() < 1e-6 && (s2 - 1.0).abs() < 1e-6 && s3.abs() < 1e-6,
        "{s1} {s2} {s3}"
    );
}

/// `scene` with polarizers at `angles` (degrees from x) across the z axis at z = 1, 1.5, …,
/// squares of side 6 before a camera at the origin looking along z.
fn behind_polarizers(scene: &str, angles: &[f64]) -> String {
    let mut text = scene.to_string();
    for (i, deg) in angles.iter().enumerate() {
        text += &format!(
            "[[material]]\nname = \"p{i}\"\n{}{}",
            polarizer(*deg),
            square(1.0 + 0.5 * i as f64, 3.0, &format!("p{i}"))
        );
    }
    text
}

/// The beauty layer of `text` seen by a camera with keys `camera` rendered with `integrator` at
/// `spp` samples a pixel (32 × 32) in `passes` passes.
fn beauty(text: &str, camera: &str, integrator: &str, spp: u32, passes: u32) -> Vec<[f32; 3]> {
    let text = format!(
        "{text}[render]\nintegrator = \"{integrator}\"\nspp = {spp}\npasses = {passes}\n\
         caustic_photons = 1000000\nphotons = 20000\n[camera]\nwidth = 32\nheight = 32\n{camera}"
    );
    let (scene, settings) = scene(&text);
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    film.layer("beauty").unwrap()
}

/// The mean over the pixels of rows and columns `crop` of an image 32 wide, all channels.
fn mean(image: &[[f32; 3]], crop: std::ops::Range<usize>) -> f64 {
    mean_of(image, crop.clone(), crop)
}

/// The mean over the pixels of `rows` and `columns` of an image 32 wide, all channels.
fn mean_of(
    image: &[[f32; 3]],
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
) -> f64 {
    let pixels: Vec<f64> = rows
        .flat_map(|y| columns.clone().map(move |x| y * 32 + x))
        .map(|i| image[i].iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0)
        .collect();
    pixels.iter().sum::<f64>() / pixels.len() as f64
}

/// A white wall across the z axis at z = 4, lit by a point light before it.
const LIT_WALL: &str =
    "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\
    [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
    vertices = [[-4, -4, 4], [-4, 4, 4], [4, 4, 4], [4, -4, 4]]\n\
    [[light]]\ntype = \"point\"\nposition = [0, 0, 3]\nintensity = [1, 1, 1]\n";

/// A camera at the origin looking along +z (y up) with a 4° view.
const NARROW_VIEW: &str = "position = [0, 0, 0]\nlook_at = [0, 0, 4]\nfov_y_deg = 4\n";

/// Looking through two polarizers at a lit wall: a camera path carries the measurement row, so
/// polarizers at 0° and θ pass ½cos²θ of the view — exactly, as the sheets draw no random
/// numbers and the paths beyond them are the same (both integrators: ½ at 0°, 3/8 at 30°, 0
/// crossed; relative 1e-6 over the image). The view is 4° wide: the axes act projected across
/// each ray, and across a ray 20° off the sheets' normal two axes 30° apart make a smaller
/// angle (a 40° view reads 0.37498).
#[test]
fn a_view_through_two_polarizers_keeps_half_cos_squared_of_it() {
    let with = |angles: &[f64]| behind_polarizers(LIT_WALL, angles);
    for integrator in ["path", "photon_map"] {
        let open = beauty(&with(&[]), NARROW_VIEW, integrator, 4, 1);
        let whole = 0..32;
        let reference = mean(&open, whole.clone());
        assert!(reference > 0.0);
        for (deg, share) in [(0.0, 0.5), (30.0, 0.375), (90.0, 0.0)] {
            let seen = beauty(&with(&[0.0, deg]), NARROW_VIEW, integrator, 4, 1);
            let ratio = mean(&seen, whole.clone()) / reference;
            assert!(
                (ratio - share).abs() < 1e-6,
                "{integrator}, {deg}°: {ratio}"
            );
        }
    }
}

/// A camera's polarizer (`polarizer_deg`, from the image's right toward its up) is a polarizer
/// sheet square to the view in front of the lens: alone it passes half the view of an
/// unpolarized wall, behind a sheet at φ it passes ½cos²(θ − φ) of it, and behind sheets
/// (listed from the camera out) Malus's law from the farthest to the camera — exactly, as it draws no
/// random numbers (both integrators, relative 1e-6 over the image: see the test above for the
/// 4° view). The camera looks along +z with y up, so its right is −x: 30° on the image is the
/// axis (−cos 30°, sin 30°, 0), at 150° from x.
#[test]
fn a_camera_polarizer_is_a_sheet_in_front_of_the_lens() {
    let polarized = format!("{NARROW_VIEW}polarizer_deg = 30\n");
    let with = |angles: &[f64]| behind_polarizers(LIT_WALL, angles);
    for integrator in ["path", "photon_map"] {
        let reference = mean(&beauty(&with(&[]), NARROW_VIEW, integrator, 4, 1), 0..32);
        assert!(reference > 0.0);
        for (sheets, share) in [
            (&[][..], 0.5),
            (&[150.0][..], 0.5),
            (&[-30.0][..], 0.5),
            (&[60.0][..], 0.0),
            (&[0.0][..], 0.5 * 0.75),
            (&[150.0, 0.0][..], 0.5 * 0.75),
            (&[0.0, 150.0][..], 0.5 * 0.75 * 0.75),
            (&[0.0, 60.0][..], 0.5 * 0.25 * 0.75),
        ] {
            let seen = beauty(&with(sheets), &polarized, integrator, 4, 1);
            let ratio = mean(&seen, 0..32) / reference;
            assert!(
                (ratio - share).abs() < 1e-6,
                "{integrator}, sheets at {sheets:?}: {ratio}, want {share}"
            );
        }
    }
}

/// Light reaching a floor through polarizers at 0° and 30°: photons carry Stokes vectors into
/// the caustic map, path-traced camera paths carry the measurement row through the sheets to
/// the light, and both find 3/8 of the open floor's light (½cos²30°; light treated as
/// unpolarized at each sheet would give 1/4) on the floor under the light. Both within 5 %: over
/// seeds 1–3 the path tracer's ratio read 1.005, 0.996, 1.003 of 3/8, the photon mapper's (10⁶
/// caustic photons) over seeds 0–4 1.005, 0.990, 0.995, 1.015, 0.995.
#[test]
fn light_through_two_polarizers_lights_a_floor_alike_in_both_integrators() {
    let thirty = 30f64.to_radians();
    let room = "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\
                [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                vertices = [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]\n\
                [[light]]\ntype = \"quad\"\nradiance = [1, 1, 1]\n\
                vertices = [[-0.5, 3, -0.5], [0.5, 3, -0.5], [0.5, 3, 0.5], [-0.5, 3, 0.5]]\n";
    let sheets = format!(
        "[[material]]\nname = \"p0\"\ntype = \"polarizer\"\naxis = [1, 0, 0]\n\
         [[material]]\nname = \"p1\"\ntype = \"polarizer\"\naxis = [{}, 0, {}]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"p0\"\n\
         vertices = [[-3, 2.5, -3], [3, 2.5, -3], [3, 2.5, 3], [-3, 2.5, 3]]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"p1\"\n\
         vertices = [[-3, 2, -3], [3, 2, -3], [3, 2, 3], [-3, 2, 3]]\n",
        thirty.cos(),
        thirty.sin()
    );
    let camera = "position = [0, 1, -3]\nlook_at = [0, 0, 0]\nfov_y_deg = 30\n";
    let centre = 12..20;
    let mut through = Vec::new();
    for integrator in ["path", "photon_map"] {
        let open = mean(&beauty(room, camera, integrator, 1024, 1), centre.clone());
        let seen = mean(
            &beauty(&(room.to_string() + &sheets), camera, integrator, 1024, 1),
            centre.clone(),
        );
        let share = seen / open;
        assert!((share / 0.375 - 1.0).abs() < 0.05, "{integrator}: {share}");
        through.push(seen);
    }
    assert!((through[1] / through[0] - 1.0).abs() < 0.05, "{through:?}");
}

/// The geometric phase in a render: light polarized along x̂ sent along a helical ray of the
/// parabolic rod (n = n0(1 − a ρ²/2), n0 = 1.5, a = 0.1; at ρ = 1 the helix at sin²θ = n0 a ρ²/n
/// to the axis) by a spot light of a 0.001° cone and a polarizer, both inside the rod, comes
/// back to its start's direction after one turn turned by Γ = 2π(1 − cos θ) = 0.33989 rad about
/// it (Tomita & Chiao): on a receiver there, square to the ray with its u along x̂, S1/S0 =
/// cos 2Γ and S2/S0 = sin 2Γ (1e-5, for the cone's spread and the stepper's tolerance; measured
/// 1e-6: 0.777716 and 0.628616 against 0.777715 and 0.628617. The phase turns the field from x̂
/// toward k × x̂, as `grinlight trace --polarization` reports; a basis carried by the shortest
/// turn alone would read S1/S0 = 1).
#[test]
fn a_helical_ray_in_a_render_turns_its_polarization_by_the_geometric_phase() {
    let (n0, a, rho): (f64, f64, f64) = (1.5, 0.1, 1.0);
    let sin2 = n0 * a * rho * rho / (n0 * (1.0 - 0.5 * a * rho * rho));
    let (s, c) = (sin2.sqrt(), (1.0 - sin2).sqrt());
    let k = DVec3::new(0.0, s, c);
    let start = DVec3::new(rho, 0.0, 0.5);
    let turn = start + DVec3::Z * (TAU * rho * c / s);
    let up = k.cross(DVec3::X);
    let sheet = start + 0.05 * k;
    let (e1, e2) = (0.02 * DVec3::X, 0.02 * up);
    let v = [
        sheet - e1 - e2,
        sheet + e1 - e2,
        sheet + e1 + e2,
        sheet - e1 + e2,
    ]
    .map(|q| format!("[{}, {}, {}]", q.x, q.y, q.z))
    .join(", ");
    let text = format!(
        "[[medium]]\nname = \"rod\"\nprofile = \"parabolic\"\nn0 = {n0}\na = {a}\naxis = [0, 0, 1]\n\
         [[material]]\nname = \"wall\"\ntype = \"dielectric\"\ninterior = \"rod\"\n\
         [[shape]]\ntype = \"cylinder\"\nbase = [0, 0, 0]\naxis = [0, 0, 1]\nradius = 2\n\
         height = 20\nmaterial = \"wall\"\n\
         [[light]]\ntype = \"spot\"\nposition = [{}, {}, {}]\ndirection = [{}, {}, {}]\n\
         intensity = [1, 1, 1]\ncone_deg = 0.001\n\
         [[material]]\nname = \"p\"\ntype = \"polarizer\"\naxis = [1, 0, 0]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"p\"\nvertices = [{v}]\n\
         [[receiver]]\nname = \"r\"\ncenter = [{}, {}, {}]\nnormal = [{}, {}, {}]\n\
         up = [{}, {}, {}]\nsize = [0.05, 0.05]\nbins = [1, 1]\n",
        start.x, start.y, start.z, k.x, k.y, k.z, turn.x, turn.y, turn.z, k.x, k.y, k.z, up.x,
        up.y, up.z
    );
    let m = &measured(&text, 2000)[0];
    assert!(m.flux.0 > 0.0, "the helix reaches the receiver");
    let gamma = TAU * (1.0 - c);
    assert!((gamma - 0.339887).abs() < 1e-6);
    let [s1, s2, s3] = [0, 1, 2].map(|i| m.stokes[i].flux.0 / m.flux.0);
    let (want1, want2) = ((2.0 * gamma).cos(), (2.0 * gamma).sin());
    println!("helix after one turn: S1/S0 {s1:.6} (cos 2Γ {want1:.6}), S2/S0 {s2:.6} (sin 2Γ {want2:.6}), S3/S0 {s3:.1e}");
    assert!(
        (s1 - want1).abs() < 1e-5,
        "S1/S0 {s1} against cos 2Γ {want1}"
    );
    assert!(
        (s2 - want2).abs() < 1e-5,
        "S2/S0 {s2} against sin 2Γ {want2}"
    );
    assert!(s3.abs() < 1e-5, "S3/S0 {s3}");
}

/// The shipped `scenes/helical_fiber.toml` says what it shows: one, two and three turns along
/// the helix, its receivers read S1/S0 = cos 2nΓ and S2/S0 = sin 2nΓ, Γ = 2π(1 − cos θ)
/// (1e-5 a turn, as the render above).
#[test]
fn the_helical_fiber_scene_turns_its_light_by_the_geometric_phase_each_turn() {
    let (scene, settings) =
        grinlight::scene::load::load_scene(std::path::Path::new("scenes/helical_fiber.toml"))
            .unwrap();
    let measured = grinlight::render::measure(&scene, &settings, 0, &())
        .unwrap()
        .0;
    let sin2: f64 = 1.5 * 0.1 / (1.5 * (1.0 - 0.05));
    let gamma = TAU * (1.0 - (1.0 - sin2).sqrt());
    // The receivers in the scene's order.
    let names = ["one_turn", "two_turns", "three_turns"];
    assert_eq!(measured.len(), 3);
    for (k, (m, name)) in measured.iter().zip(names).enumerate() {
        let turns = (k + 1) as f64;
        assert!(m.flux.0 > 0.0, "{name}");
        let [s1, s2] = [0, 1].map(|i| m.stokes[i].flux.0 / m.flux.0);
        let (want1, want2) = ((2.0 * turns * gamma).cos(), (2.0 * turns * gamma).sin());
        println!("{name}: S1/S0 {s1:.6} ({want1:.6}), S2/S0 {s2:.6} ({want2:.6})");
        assert!(
            (s1 - want1).abs() < 1e-5 * turns && (s2 - want2).abs() < 1e-5 * turns,
            "{name}: {s1} {s2} against {want1} {want2}"
        );
    }
}

/// What a camera path gathers along its stretches — fog's in-scattered light (volume beams,
/// single scattering) and a medium's emission — is seen through the polarizers it crossed
/// before: behind crossed polarizers a box of lit, glowing fog (its boundary index-matched) is
/// black in both integrators (below 1e-6 of it; weighed by the chain's weight alone, without
/// the camera's row, 0.118 of the path tracer's mean came through), and behind parallel ones half as bright
/// as without them: exactly for the direct light and the glow, in expectation for the light
/// scattered more than once, whose Russian roulette on the halved throughput draws other numbers
/// (2 %: the path tracer read 0.4965, its direct and emitted layers 0.5 to 3e-8).
#[test]
fn fog_and_glow_behind_polarizers_are_seen_through_them() {
    // The glow only for the path tracer: the photon mapper refuses an emitting medium.
    let fog = |glow: &str| {
        format!("[[medium]]\nname = \"fog\"\nprofile = \"uniform\"\nn = 1.0\n\
               scattering = 0.3\nabsorption = 0.1\n{glow}\
               [[material]]\nname = \"boundary\"\ntype = \"dielectric\"\ninterior = \"fog\"\n\
               [[shape]]\ntype = \"box\"\nmin = [-4, -4, 2]\nmax = [4, 4, 6]\nmaterial = \"boundary\"\n\
               [[light]]\ntype = \"point\"\nposition = [0, 1, 4]\nintensity = [2, 2, 2]\n\
               [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
               [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
               vertices = [[-5, -5, 7], [-5, 5, 7], [5, 5, 7], [5, -5, 7]]\n")
    };
    let camera = "position = [0, 0, 0]\nlook_at = [0, 0, 4]\nfov_y_deg = 4\n";
    let with = |angles: &[f64], glow: &str| behind_polarizers(&fog(glow), angles);
    for (integrator, glow) in [("path", "emission = [0.2, 0.2, 0.2]\n"), ("photon_map", "")] {
        let open = mean(&beauty(&with(&[], glow), camera, integrator, 2, 1), 0..32);
        assert!(open > 0.0, "{integrator}");
        let crossed = mean(
            &beauty(&with(&[0.0, 90.0], glow), camera, integrator, 2, 1),
            0..32,
        );
        // Not exactly 0: across a ray 2° off the sheets' normal their axes' projections are
        // not quite square (the leak goes as the square of that, 1e-6 of the light at most).
        assert!(
            crossed / open < 1e-6,
            "{integrator}: crossed polarizers {}",
            crossed / open
        );
        let parallel = mean(
            &beauty(&with(&[0.0, 0.0], glow), camera, integrator, 2, 1),
            0..32,
        );
        println!(
            "{integrator}: behind parallel polarizers {:.5} of the open view",
            parallel / open
        );
        assert!(
            (parallel / open - 0.5).abs() < 0.02,
            "{integrator}: {}",
            parallel / open
        );
    }
}

/// In the open: the sky seen through polarizers, and the sun's light through them onto a
/// floor. A uniform sky behind polarizers at 0° and θ is ½cos²θ of itself (both
/// integrators, 1e-6: the sky is unpolarized and the chain escapes through the sheets); a floor
/// lit by the sun (a directional light) through a polarizer pair at 0° and 60° sees ½cos²60° =
/// 1/8 of its direct sunlight in the photon mapper (caustic photons, 8 passes of 10⁶)
/// (the sun's light through a specular surface reaches a diffuse floor only as photons, which
/// the path tracer cannot find: the photon mapper alone, 5 %; over seeds 0–4 it read 0.9997,
/// 0.985, 0.999, 0.994, 1.015 of 1/8).
#[test]
fn the_sky_and_the_sun_through_polarizers() {
    let sky = "[[light]]\ntype = \"environment\"\nsky = \"uniform\"\nradiance = [1, 1, 1]\n";
    let camera = "position = [0, 0, 0]\nlook_at = [0, 0, 4]\nfov_y_deg = 4\n";
    let with = |angles: &[f64]| behind_polarizers(sky, angles);
    for integrator in ["path", "photon_map"] {
        let open = mean(&beauty(&with(&[]), camera, integrator, 1, 1), 0..32);
        assert!((open - 1.0).abs() < 1e-6, "{integrator}: the sky {open}");
        for (deg, share) in [(0.0, 0.5), (60.0, 0.125)] {
            let seen = mean(&beauty(&with(&[0.0, deg]), camera, integrator, 1, 1), 0..32);
            assert!(
                (seen / open - share).abs() < 1e-6,
                "{integrator}, {deg}°: {}",
                seen / open
            );
        }
    }
    let sun = "[[light]]\ntype = \"directional\"\ndirection = [0, -1, 0]\nirradiance = [1, 1, 1]\n\
               [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\
               [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
               vertices = [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]\n";
    let sheets = format!(
        "[[material]]\nname = \"p0\"\ntype = \"polarizer\"\naxis = [1, 0, 0]\n\
         [[material]]\nname = \"p1\"\ntype = \"polarizer\"\naxis = [0.5, 0, {}]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"p0\"\n\
         vertices = [[-3, 2.5, -3], [3, 2.5, -3], [3, 2.5, 3], [-3, 2.5, 3]]\n\
         [[shape]]\ntype = \"quad\"\nmaterial = \"p1\"\n\
         vertices = [[-3, 2, -3], [3, 2, -3], [3, 2, 3], [-3, 2, 3]]\n",
        0.75f64.sqrt()
    );
    let floor = "position = [0, 1, -3]\nlook_at = [0, 0, 0]\nfov_y_deg = 30\n";
    // The floor under the sheets: the lower half of the view, its middle three quarters.
    let open = mean_of(&beauty(sun, floor, "photon_map", 1, 8), 16..30, 4..28);
    let through = beauty(&(sun.to_string() + &sheets), floor, "photon_map", 1, 8);
    let through = mean_of(&through, 16..30, 4..28);
    println!(
        "sun through polarizers at 0° and 60°: {:.4} of 1/8",
        through / open / 0.125
    );
    assert!(
        (through / open / 0.125 - 1.0).abs() < 0.05,
        "{}",
        through / open
    );
}

/// Against Mitsuba 3.9.1's polarized path tracer (`bench/mitsuba_polarized.py`: its `stokes`
/// integrator, 16 runs of 1024 spp): a glass ball and a metal ball (η 1.2 + 2i) on a floor under
/// a quad light and a sky, seen through a camera polarizer at 0°, 45°, 90° and 135° — the
/// polarization of reflection and refraction in every orientation across the image, and the
/// camera's convention (from the image's right toward its up, right-handed about the light).
/// Block means (8 × 8) within 5 standard errors (32 runs of ours: P(|t| > 5) ≈ 2e-5 a block,
/// as `import::the_mitsuba_scenes_render_as_mitsuba_renders_them` argues; measured largest 3.8)
/// and image means within 0.5 % (measured 0.9996–0.9998). The references differ from one another
/// by far more than that: polarization is what is tested.
#[test]
fn glass_and_metal_through_a_camera_polarizer_as_mitsuba_sees_them() {
    use super::import::{compare, dir, grinlight_blocks, reference, write};
    let text = std::fs::read_to_string("tests/data/mitsuba/polarized_spheres.toml").unwrap();
    let dir = dir("polarized-spheres");
    let (crossed, _) = compare(
        &reference("polarized_spheres_0"),
        &reference("polarized_spheres_90"),
    );
    assert!(
        crossed > 50.0,
        "the references at 0° and 90° differ by {crossed:.1} σ"
    );
    for angle in [0, 45, 90, 135] {
        let seen = text.replacen(
            "[camera]\n",
            &format!("[camera]\npolarizer_deg = {angle}\n"),
            1,
        );
        let path = write(&dir, &format!("polarizer_{angle}.toml"), &seen);
        let ours = grinlight_blocks(&path, &[], 32, 16);
        let (worst, ratio) = compare(&ours, &reference(&format!("polarized_spheres_{angle}")));
        eprintln!("{angle}°: largest block z {worst:.2}, mean ratio {ratio:.5}");
        assert!(
            worst < 5.0,
            "{angle}°: a block differs by {worst:.2} standard errors"
        );
        assert!((ratio - 1.0).abs() < 0.005, "{angle}°: mean ratio {ratio}");
    }
}

/// The camera's Stokes vector (`stokes`: layers S0–S3, in the basis of each pixel's ray d,
/// first axis d × up) of the same glass and metal balls against Mitsuba 3.9.1's `stokes`
/// integrator's S0–S3 (its basis; `bench/mitsuba_polarized.py`, 16 × 1024 spp): every 8 × 8
/// block within 5 standard errors (32 runs of 16 spp, as the test of the Mitsuba scenes), S0's
/// image mean within 0.5 % (measured: z 2.71, 2.59, 3.53, 2.25; S0 1.0006). S1–S3 average near
/// zero over the image (their blocks' signs differ), so what is tested is their blocks, S3's
/// sign among them: light the metal ball and the glass ball's total internal reflections turn
/// circular (Mitsuba's and grinlight's S3 agree once S3 > 0 is right-handed seen by the
/// receiver; with the sign the other way its blocks differed by 9.2 standard errors).
#[test]
fn glass_and_metal_have_mitsubas_stokes_vector() {
    stokes_like_mitsubas("polarized_spheres", "path", [64, 20, 20, 2]);
}

/// Two rough metal balls (GGX, α = 0.08 and 0.12) under the same light and sky, against
/// Mitsuba 3.9.1's `stokes` integrator as above, through both integrators: a camera path
/// carries its measurement through each microfacet's Fresnel matrix, to the light samples and
/// the bounce of the vertex (measured, largest block z for S0–S3: path tracer 3.10, 2.13, 3.50,
/// 3.64, S0's mean 1.0007; photon mapper 4.80, 2.65, 3.06, 2.76, S0 1.0008). Their masking differs (grinlight's correlated heights,
/// Mitsuba's separable G₁G₁, a percent apart at α = 0.3 toward grazing: the balls are smooth
/// enough for it to stay within the noise). A camera path that took a rough conductor as a
/// depolarizer (before 0.27.0) read S1–S3 as zero over the whole image.
#[test]
fn rough_metal_has_mitsubas_stokes_vector() {
    for integrator in ["path", "photon_map"] {
        stokes_like_mitsubas("polarized_rough", integrator, [64, 20, 20, 0]);
    }
}

/// The Stokes layers of tests/data/mitsuba/`name`.toml rendered by `integrator` against
/// Mitsuba's references beside it: every block within 5 standard errors, S0's image mean
/// within 0.5 %, and at least `known` blocks of each layer whose value the reference knows to
/// 10 standard errors (what is tested).
fn stokes_like_mitsubas(name: &str, integrator: &str, known: [usize; 4]) {
    use super::import::{compare, dir, grinlight_layer_blocks, reference, write};
    let text = std::fs::read_to_string(format!("tests/data/mitsuba/{name}.toml")).unwrap();
    // The photon mapper's density estimates blur the floor's light (most near the balls'
    // contacts): S0's blocks are its own tests' (its mean is tested here), and with a million
    // photons a pass what the balls reflect of it keeps S1–S3 within the tolerance.
    let blurred = integrator == "photon_map";
    let photons = match blurred {
        true => "photons = 1000000\ncaustic_photons = 1000000\n",
        false => "",
    };
    let text = text.replacen(
        "integrator = \"path\"\n",
        &format!("integrator = \"{integrator}\"\n{photons}"),
        1,
    );
    let scene = write(&dir(name), &format!("{integrator}.toml"), &text);
    let layers = ["S0", "S1", "S2", "S3"];
    let ours = grinlight_layer_blocks(&scene, &Default::default(), 32, 16, true, &layers);
    for (k, (ours, layer)) in ours.iter().zip(layers).enumerate() {
        let theirs = reference(&format!("{name}_{layer}"));
        let well_known = (theirs.mean.iter().zip(&theirs.se))
            .filter(|(m, s)| m[0].abs() > 10.0 * s[0])
            .count();
        let (worst, ratio) = compare(ours, &theirs);
        eprintln!(
            "{name}, {integrator}, {layer}: largest block z {worst:.2}, mean ratio {ratio:.5}, \
             {well_known} blocks known to 10 σ"
        );
        assert!(well_known >= known[k], "{layer}: {well_known} blocks");
        assert!(
            worst < 5.0 || (k == 0 && blurred),
            "{layer}: a block differs by {worst:.2} standard errors"
        );
        if k == 0 {
            assert!((ratio - 1.0).abs() < 0.005, "S0: mean ratio {ratio}");
        }
    }
}

/// A thin pane (`thin_dielectric`, index 1.5) tilted 60° across a parallel beam passes
/// ½(T_s + T_p) of it, each polarization's T = (1 − R)/(1 + R) with R its face's reflectance
/// (Born and Wolf's, written out here: the internal reflections summed apart for s and p) —
/// 0.8481 where the unpolarized sum 1 − 2R/(1 + R) would give 0.8362 (measured 0.8466 ± 0.0020
/// of the open beam's 0.9993 ± 0.0005) — within 4 standard errors;
/// square on, (1 − R)/(1 + R) = 12/13. What passes obliquely is partly p polarized:
/// S1/S0 = (T_s − T_p)/(T_s + T_p) with s along the receiver's u = x (every photon alike: 1e-6).
/// A pane of the surroundings' index passes the whole beam, unpolarized.
#[test]
fn a_tilted_pane_passes_and_polarizes_light_as_its_summed_reflections_say() {
    let photons = 2_000_000;
    let pane = |deg: f64, ior: f64| {
        let (s, c) = deg.to_radians().sin_cos();
        let corner = |x: f64, y: f64| format!("[{x}, {}, {}]", y * c, 2.0 + y * s);
        let mut text = beam_through(&[]);
        text += &format!(
            "[render]\npolarized = true\n[[material]]\nname = \"pane\"\ntype = \"thin_dielectric\"\n\
             ior = {ior}\n[[shape]]\ntype = \"quad\"\nmaterial = \"pane\"\nvertices = [{}, {}, {}, {}]\n",
            corner(-0.8, -1.2),
            corner(0.8, -1.2),
            corner(0.8, 1.2),
            corner(-0.8, 1.2)
        );
        text
    };
    let open = &measured(&beam_through(&[]), photons)[0];
    let eta: f64 = 1.5;
    for deg in [0.0f64, 60.0] {
        let (sin_i, cos_i) = deg.to_radians().sin_cos();
        let cos_t = (1.0 - (sin_i / eta).powi(2)).sqrt();
        let r_s = ((cos_i - eta * cos_t) / (cos_i + eta * cos_t)).powi(2);
        let r_p = ((eta * cos_i - cos_t) / (eta * cos_i + cos_t)).powi(2);
        let (t_s, t_p) = ((1.0 - r_s) / (1.0 + r_s), (1.0 - r_p) / (1.0 + r_p));
        let share = 0.5 * (t_s + t_p);
        let m = &measured(&pane(deg, eta), photons)[0];
        let want = (share * open.flux.0, share * open.flux.1);
        assert!(z(m, want) < 4.0, "{deg}°: {:?} against {want:?}", m.flux);
        let [s1, s2, s3] = [0, 1, 2].map(|i| m.stokes[i].flux.0 / m.flux.0);
        let polarized = (t_s - t_p) / (t_s + t_p);
        assert!(
            (s1 - polarized).abs() < 1e-6,
            "{deg}°: S1/S0 {s1}, want {polarized}"
        );
        assert!(s2.abs() < 1e-6 && s3.abs() < 1e-6, "{deg}°: {s2} {s3}");
    }
    let clear = &measured(&pane(60.0, 1.0), photons)[0];
    assert!(
        z(clear, open.flux) < 4.0,
        "a pane of the surroundings' index: {:?}",
        clear.flux
    );
    assert!(clear
        .stokes
        .iter()
        .all(|s| s.flux.0.abs() < 1e-6 * clear.flux.0));
}

/// A camera polarizer in front of a black hole: the deflection table, which stands in for
/// traced camera rays where nothing but one spherically symmetric medium is in view, carries no
/// measurement, so behind a polarizer every ray is traced — and the unpolarized sky, its rays
/// bent but its light unpolarized, comes through at half (exactly: the same rays as a render
/// that traces every ray without the polarizer; 1e-6). A table used behind it would read the
/// whole sky.
#[test]
fn a_black_hole_seen_through_a_camera_polarizer_is_half_as_bright() {
    let hole = "ambient = \"hole\"\n[[medium]]\nname = \"hole\"\nprofile = \"black_hole\"\n\
                center = [0, 0, 0]\nrs = 0.01\nq = 0.1\n\
                [[light]]\ntype = \"environment\"\nsky = \"checker\"\nsquares = 72\n";
    let view = |render: &str, camera: &str| {
        let text = format!(
            "{hole}[render]\nworld_radius = 50.0\nspp = 1\n{render}[camera]\nwidth = 32\n\
             height = 32\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfov_y_deg = 3\n{camera}"
        );
        let (scene, settings) = scene(&text);
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        mean(&film.layer("beauty").unwrap(), 0..32)
    };
    let open = view("deflection_table = false\n", "");
    let seen = view("", "polarizer_deg = 30\n");
    assert!(open > 0.0);
    assert!((seen / open - 0.5).abs() < 1e-6, "{}", seen / open);
}

/// A smooth conductor reflecting a uniform sky polarizes it as complex Fresnel says: each
/// pixel of the image's middle column, where the plane of incidence is the image's vertical
/// one and s its horizontal axis, reads S1/S0 = Σ(Rs − Rp)/Σ(Rs + Rp) over its rays (a 16 × 16
/// grid of them), S2 = 0 and S3 = 0 (one reflection of unpolarized light is not circular:
/// exactly) — within 1e-3 (measured 2.2e-4, both integrators) at angles of incidence below 78°
/// (nearer grazing the ratio turns too fast across a pixel for its 16 samples); the sky seen
/// directly is unpolarized (S1 = S2 = S3 = 0 exactly); and S0 is
/// `beauty`. Every Stokes vector is one light can have: S1² + S2² + S3² ≤ S0². Both
/// integrators.
#[test]
fn a_conductor_polarizes_the_sky_it_reflects_as_fresnel_says() {
    for integrator in ["path", "photon_map"] {
        a_conductor_reflects_the_sky(integrator, None);
    }
}

/// The same for a rough conductor of α = 0.002, whose microfacets turn by a tenth of a degree
/// about the mean normal: the camera path carries its measurement past the scattering vertex,
/// through the microfacet's Fresnel matrix to the sky its light samples and its bounce find,
/// S1/S0 within the same 1e-3 (measured 2.2e-4 and 6.0e-4; S2/S0 2.3e-4 and 4.0e-4, at 256
/// samples a pixel for the microfacets' turns). A camera path that took the
/// vertex as a depolarizer (before 0.27.0) read S1 = 0 there.
#[test]
fn a_rough_conductor_polarizes_the_sky_it_reflects_as_fresnel_says() {
    for integrator in ["path", "photon_map"] {
        a_conductor_reflects_the_sky(integrator, Some(0.002));
    }
}

/// [`a_conductor_polarizes_the_sky_it_reflects_as_fresnel_says`] through `integrator`, the
/// conductor smooth or of the `roughness` given.
fn a_conductor_reflects_the_sky(integrator: &str, roughness: Option<f64>) {
    let (eta, k) = (1.2, 2.0);
    let material = format!(
        "type = \"conductor\"\neta = [{eta}, {eta}, {eta}]\nk = [{k}, {k}, {k}]\n{}",
        roughness.map_or(String::new(), |a| format!("roughness = {a}\n"))
    );
    let fresnel = |cos: f64| grinlight::polarization::mueller::conductor_reflection(cos, eta, k);
    // A rough conductor's microfacets turn the plane of reflection a sample at a time: S2
    // averages out over more of them.
    let spp = match roughness {
        Some(_) => 256,
        None => 16,
    };
    a_surface_reflects_the_sky(integrator, &material, spp, 1e-3, fresnel);
}

/// A rough glass floor (α = 0.002, index 1.5) over a black one reflecting a uniform sky, as
/// [`a_conductor_polarizes_the_sky_it_reflects_as_fresnel_says`]: each microfacet reflects as
/// Fresnel's matrix for a dielectric, S1/S0 = Σ(R_s − R_p)/Σ(R_s + R_p) over each pixel's rays
/// and S2/S0 within 3e-3, both integrators (measured: S1/S0 2.2e-3 and 1.8e-3, S2/S0 2.0e-3 and
/// 1.2e-3). A path reflects with chance R, a tenth here: of a pixel's 4 096 samples some 400
/// reflect, and which of its rays they are varies with the choice's numbers (smooth glass
/// at 16 384 samples read within 1e-3). A rough dielectric taken as a depolarizer (before
/// 0.27.0) read S1 = 0.
#[test]
fn rough_glass_polarizes_the_sky_it_reflects_as_fresnel_says() {
    let material = "type = \"dielectric\"\nior = 1.5\nroughness = 0.002\n";
    let fresnel = |cos: f64| grinlight::polarization::mueller::dielectric_reflection(cos, 1.0, 1.5);
    // A path chooses between reflection and refraction: a tenth of its samples reflect.
    for integrator in ["path", "photon_map"] {
        a_surface_reflects_the_sky(integrator, material, 4096, 3e-3, fresnel);
    }
}

/// A floor of `material` (a TOML table's keys) over a black one, under a uniform sky, seen by
/// `integrator` measuring the Stokes vector at `spp`: the middle column's S1/S0 against
/// `fresnel`'s over each pixel's rays, and S2/S0, within `tolerance` (see
/// [`a_conductor_polarizes_the_sky_it_reflects_as_fresnel_says`]).
fn a_surface_reflects_the_sky(
    integrator: &str,
    material: &str,
    spp: u32,
    tolerance: f64,
    fresnel: impl Fn(f64) -> glam::DMat4,
) {
    let text = format!(
        "[camera]\nposition = [0, 1, 0]\nlook_at = [0, 0, 2]\nfov_y_deg = 60\nwidth = 9\nheight = 31\n\
         [render]\nintegrator = \"{integrator}\"\nspp = {spp}\nstokes = true\nphotons = 2000\ncaustic_photons = 2000\n\
         [[material]]\nname = \"floor\"\n{material}\
         [[material]]\nname = \"black\"\ntype = \"diffuse\"\nalbedo = 0\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[-50, 0, -50], [-50, 0, 50], [50, 0, 50], [50, 0, -50]]\nmaterial = \"floor\"\n\
         [[shape]]\ntype = \"quad\"\nvertices = [[-50, -1, -50], [-50, -1, 50], [50, -1, 50], [50, -1, -50]]\nmaterial = \"black\"\n\
         [[light]]\ntype = \"environment\"\nsky = \"uniform\"\nradiance = [1, 1, 1]\n"
    );
    let (scene, settings) =
        grinlight::scene::load::parse_scene(std::path::Path::new("c.toml"), text).unwrap();
    let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
    let layer = |name| film.layer(name).unwrap();
    let (beauty, s) = (layer("beauty"), ["S0", "S1", "S2", "S3"].map(layer));
    let camera = scene.camera.as_ref().unwrap();
    let (mut floor, mut sky, mut worst, mut worst_s2) = (0, 0, 0.0f64, 0.0f64);
    for (i, b) in beauty.iter().enumerate() {
        let v = [0, 1, 2, 3].map(|c| s[c][i][0] as f64);
        assert!(
            (v[0] - b[0] as f64).abs() <= 1e-6 * v[0],
            "pixel {i}: S0 {v:?}, beauty {b:?}"
        );
        assert!(
            v[1] * v[1] + v[2] * v[2] + v[3] * v[3] <= v[0] * v[0] * (1.0 + 1e-6),
            "{v:?}"
        );
        let (x, y) = (i % 9, i / 9);
        let d = camera.direction(x as u32, y as u32, 0.5, 0.5);
        if d.y >= 0.0 {
            sky += 1;
            assert_eq!(&v[1..], &[0.0; 3], "pixel {i} sees the sky directly");
        } else if x == 4 && -d.y > 0.2 {
            floor += 1;
            // Fresnel's S1 and S0 summed over the pixel's rays (each ray's s is the basis's
            // first axis: the camera's up is the floor's normal).
            let (mut s1, mut s0) = (0.0, 0.0);
            for k in 0..256 {
                let (u, w) = ((k % 16) as f64 + 0.5, (k / 16) as f64 + 0.5);
                let d = camera.direction(x as u32, y as u32, u / 16.0, w / 16.0);
                let m = fresnel(-d.y);
                (s1, s0) = (s1 + m.col(0).y, s0 + m.col(0).x);
            }
            let want = s1 / s0;
            worst = worst.max((v[1] / v[0] - want).abs());
            assert!(
                (v[1] / v[0] - want).abs() < tolerance,
                "pixel {i}: S1/S0 {} vs {want}",
                v[1] / v[0]
            );
            worst_s2 = worst_s2.max(v[2].abs() / v[0]);
            // Off the middle plane a ray's s turns from x: S2 averages out over the pixel.
            assert!(
                v[2].abs() < tolerance * v[0] && v[3] == 0.0,
                "pixel {i}: {v:?}"
            );
        }
    }
    println!(
        "{integrator}, {material:?}: middle column: {floor} pixels of the floor, S1/S0 within \
         {worst:.1e}, S2/S0 {worst_s2:.1e}; {sky} of the sky"
    );
    assert!(floor >= 10 && sky >= 10, "{floor} {sky}");
}

/// Light a medium emits or a dye re-emits toward a camera ray leaves it unpolarized, and the
/// camera records it through the measurement its path carries there: behind a polarizer
/// sheet whose axis stands at θ from x, glowing fog (path tracer; the photon mapper refuses
/// emitting media) and a dyed slab lit by ultraviolet parallel light (both integrators) read
/// S1/S0 = cos 2θ and S2/S0 = −sin 2θ over the image (the camera looks along +z, its basis's
/// first axis d × up = −x), and without the sheet S1 = S2 = 0. Every path's light crosses the
/// same sheet, so the ratios are exact but for the rays' obliquity in a 1° view (the axis
/// projected across a ray 0.7° off the normal turns by below 10⁻⁴ rad): 2·10⁻⁴ (measured
/// within 4.4·10⁻⁶). Before, the light was measured as S0 alone and such scenes refused.
#[test]
fn glowing_fog_and_a_dye_behind_a_polarizer_are_measured_whole() {
    let glow = "[[medium]]\nname = \"glow\"\nprofile = \"uniform\"\nn = 1\nabsorption = 0.5\n\
                emission = [1, 1, 1]\n\
                [[material]]\nname = \"boundary\"\ntype = \"dielectric\"\ninterior = \"glow\"\n\
                [[shape]]\ntype = \"box\"\nmin = [-4, -4, 2]\nmax = [4, 4, 6]\nmaterial = \"boundary\"\n";
    let dye = "[[medium]]\nname = \"dyed\"\nprofile = \"uniform\"\nn = 1\n\
               fluorescence = { absorption = { table = [[360, 2], [480, 2], [500, 0], [830, 0]] }, \
               emission = { gaussian = [600, 40] }, quantum_yield = 0.7 }\n\
               [[material]]\nname = \"slab\"\ntype = \"dielectric\"\ninterior = \"dyed\"\n\
               [[shape]]\ntype = \"box\"\nmin = [-50, -50, 2]\nmax = [50, 50, 2.5]\nmaterial = \"slab\"\n\
               [[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nirradiance = 1\n\
               spectrum = { gaussian = [400, 2] }\n";
    let camera = "position = [0, 0, 0]\nlook_at = [0, 0, 4]\nup = [0, 1, 0]\nfov_y_deg = 1\n";
    for (scene, integrators) in [(glow, &["path"][..]), (dye, &["path", "photon_map"][..])] {
        for integrator in integrators {
            for theta in [None, Some(30f64), Some(100.0)] {
                let mut text = behind_polarizers(scene, theta.as_slice());
                text += &format!(
                    "[render]\nintegrator = \"{integrator}\"\nstokes = true\nspp = 16\n\
                     photons = 20000\ncaustic_photons = 20000\n\
                     [camera]\nwidth = 8\nheight = 8\n{camera}"
                );
                let (scene, settings) =
                    grinlight::scene::load::parse_scene(std::path::Path::new("shining.toml"), text)
                        .unwrap();
                let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
                let sum = |name: &str| {
                    let layer = film.layer(name).unwrap();
                    layer.iter().map(|p| f64::from(p[1])).sum::<f64>()
                };
                let [s0, s1, s2, s3] = ["S0", "S1", "S2", "S3"].map(sum);
                let want = theta.map_or([0.0, 0.0], |t| {
                    let t = t.to_radians();
                    [(2.0 * t).cos(), -(2.0 * t).sin()]
                });
                println!(
                    "{integrator}, sheet at {theta:?}: S1/S0 {}, S2/S0 {} against {want:?}",
                    s1 / s0,
                    s2 / s0
                );
                assert!(s0 > 0.0, "{integrator}");
                assert!(
                    (s1 / s0 - want[0]).abs() < 2e-4 && (s2 / s0 - want[1]).abs() < 2e-4,
                    "{integrator}, {theta:?}: {} {} against {want:?}",
                    s1 / s0,
                    s2 / s0
                );
                assert!(s3.abs() < 1e-6 * s0, "{s3}");
            }
        }
    }
}

/// The photon mapper's volume photons keep their Stokes vectors, on which the light Rayleigh's
/// phase function scatters toward a camera depends: parallel light through a polarizer whose
/// axis stands at α from x into a ball of thin Rayleigh air (radius 1, σs 0.01: the light
/// scattered once), seen at 90° to the beam by an orthographic Stokes camera looking along +y
/// (its first axis x). The sheet makes the light a volume caustic, the photon map's alone.
/// The dipole driven along the axis radiates toward the camera its x part alone: S0 ∝ cos²α,
/// polarized along x (S1/S0 = 1) — the density estimate's blur, the same at every α, drops
/// out of the ratios. Tolerance 2 %: light scattered twice (τ = 0.02 across the ball).
/// Measured: 0.7501 at 30°, 0.0013 at 90°, S1/S0 0.9985 and 0.9979; photons read as
/// unpolarized (before 0.28.0 such views were refused) gave 1.0000 at both angles.
#[test]
fn the_photon_mappers_volume_photons_keep_their_polarization() {
    let view = |alpha: f64| {
        let a = alpha.to_radians();
        let text = format!(
            "[camera]\nprojection = \"orthographic\"\nview_height = 1\nposition = [0, -3, 0]\n\
             look_at = [0, 0, 0]\nup = [0, 0, 1]\nwidth = 8\nheight = 8\n\
             [render]\nintegrator = \"photon_map\"\nstokes = true\nspp = 16\npasses = 4\n\
             caustic_photons = 1000000\nphotons = 1000\n\
             [[medium]]\nname = \"air\"\nprofile = \"uniform\"\nn = 1\nscattering = 0.01\n\
             phase = \"rayleigh\"\n\
             [[material]]\nname = \"boundary\"\ntype = \"dielectric\"\ninterior = \"air\"\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"boundary\"\n\
             [[light]]\ntype = \"directional\"\ndirection = [0, 0, 1]\nirradiance = [1, 1, 1]\n\
             [[material]]\nname = \"sheet\"\ntype = \"polarizer\"\naxis = [{}, {}, 0]\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"sheet\"\n\
             vertices = [[-2, -2, -3], [2, -2, -3], [2, 2, -3], [-2, 2, -3]]\n",
            a.cos(),
            a.sin()
        );
        let (scene, settings) =
            grinlight::scene::load::parse_scene(std::path::Path::new("air.toml"), text).unwrap();
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        let mean = |name: &str| {
            let layer = film.layer(name).unwrap();
            layer.iter().map(|p| f64::from(p[1])).sum::<f64>() / layer.len() as f64
        };
        (mean("S0"), mean("S1") / mean("S0"))
    };
    let (open, s1) = view(0.0);
    println!("α = 0: S1/S0 {s1:.4}");
    assert!(s1 > 0.98, "{s1}");
    let (thirty, s1) = view(30.0);
    let (ninety, _) = view(90.0);
    println!(
        "S0 at 30° {:.4} and at 90° {:.4} of 0°'s; S1/S0 at 30° {s1:.4}",
        thirty / open,
        ninety / open
    );
    assert!((thirty / open - 0.75).abs() < 0.02, "{}", thirty / open);
    assert!(ninety / open < 0.02, "{}", ninety / open);
    assert!(s1 > 0.98, "{s1}");
}

/// Light scattered once by Rayleigh air is polarized across the scattering plane, its degree
/// sin²θ/(1 + cos²θ) at scattering angle θ: a sphere of air (radius 1, σs 0.002: light
/// scattered twice is a few tenths of a percent of it) under parallel light travelling down,
/// seen by an orthographic camera measuring the Stokes vector (path tracer) at θ = 90°, 60°
/// and 30° (DoLP 1, 0.6 and 0.143), reads S1/S0 = −DoLP — its first axis d × up, up = x,
/// lies in the plane — within 0.005 over the sphere's image, and S2, S3 zero. The camera path carries its
/// measurement into the single scattering along its stretch and through each phase
/// function's Mueller matrix to the light; isotropic air, a depolarizer, reads S1 = 0.
#[test]
fn rayleigh_air_polarizes_the_light_it_scatters_once_as_the_dipole_says() {
    for (deg, phase) in [
        (90.0, "rayleigh"),
        (60.0, "rayleigh"),
        (30.0, "rayleigh"),
        (60.0, "isotropic"),
    ] {
        let theta: f64 = f64::to_radians(deg);
        // Light travels along −y; the camera looks along d, the light leaves toward it along −d.
        let d = DVec3::new(0.0, theta.cos(), theta.sin());
        let eye = -3.0 * d;
        let text = format!(
            "[camera]\nprojection = \"orthographic\"\nview_height = 1\nposition = [{}, {}, {}]\n\
             look_at = [0, 0, 0]\nup = [1, 0, 0]\nwidth = 8\nheight = 8\n\
             [render]\nintegrator = \"path\"\nstokes = true\nspp = 64\n\
             [[medium]]\nname = \"air\"\nprofile = \"uniform\"\nn = 1\nscattering = 0.002\nphase = \"{phase}\"\n\
             [[material]]\nname = \"boundary\"\ntype = \"dielectric\"\ninterior = \"air\"\n\
             [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"boundary\"\n\
             [[light]]\ntype = \"directional\"\ndirection = [0, -1, 0]\nirradiance = [1, 1, 1]\n",
            eye.x, eye.y, eye.z
        );
        let (scene, settings) =
            grinlight::scene::load::parse_scene(std::path::Path::new("air.toml"), text).unwrap();
        let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
        let s = ["S0", "S1", "S2", "S3"].map(|name| film.layer(name).unwrap());
        let sum = |k: usize| s[k].iter().map(|p| p[1] as f64).sum::<f64>();
        let (s0, s1, s2, s3) = (sum(0), sum(1), sum(2), sum(3));
        let want = match phase {
            "rayleigh" => -theta.sin().powi(2) / (1.0 + theta.cos().powi(2)),
            _ => 0.0,
        };
        eprintln!(
            "{phase} at {deg}°: S1/S0 {} (want {want}), S2/S0 {}, S3/S0 {}",
            s1 / s0,
            s2 / s0,
            s3 / s0
        );
        assert!(s0 > 0.0);
        assert!(
            (s1 / s0 - want).abs() < 0.005,
            "{phase} at {deg}°: S1/S0 {} vs {want}",
            s1 / s0
        );
        assert!(
            (s2 / s0).abs() < 1e-3 && (s3 / s0).abs() < 1e-9,
            "{s2} {s3}"
        );
    }
}

/// A narrow beam (a spot of 0.1° along +z) through a small sphere of Rayleigh-scattering air
/// (radius `radius`, σs 20: about a third of the beam scatters), `sheets` across the beam, and square
/// receivers of side `side` at distance 2 from the sphere's centre along each of `directions`
/// (their width axis `u` given, their normal facing away from the sphere); polarized
/// transport, `max_depth` 2 (one scattering, then the receiver: no light scattered twice) and
/// one more for each of `sheets` the beam crosses on its way.
fn rayleigh_sphere(
    radius: f64,
    side: f64,
    receivers: &[(DVec3, DVec3)],
    sheets: &[String],
) -> String {
    let mut text = format!(
        "[render]\npolarized = true\nmax_depth = {}\n\
         [[medium]]\nname = \"air\"\nprofile = \"uniform\"\nn = 1\nscattering = 20\n\
         phase = \"rayleigh\"\n\
         [[material]]\nname = \"skin\"\ntype = \"dielectric\"\ninterior = \"air\"\n\
         [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = {radius}\n\
         material = \"skin\"\ninterior = \"air\"\n\
         [[light]]\ntype = \"spot\"\nposition = [0, 0, -3]\ndirection = [0, 0, 1]\n\
         intensity = 1\ncone_deg = 0.1\n{}",
        2 + sheets.len(),
        sheets.concat()
    );
    for (i, (k, u)) in receivers.iter().enumerate() {
        let (c, up) = (2.0 * *k, k.cross(*u));
        text += &format!(
            "[[receiver]]\nname = \"r{i}\"\ncenter = [{}, {}, {}]\nnormal = [{}, {}, {}]\n\
             up = [{}, {}, {}]\nsize = [{side}, {side}]\nbins = [1, 1]\n",
            c.x, c.y, c.z, k.x, k.y, k.z, up.x, up.y, up.z
        );
    }
    text
}

/// Points of a square of side `side` at distance 2 along unit `k` with width axis `u`, on a
/// grid of `n` × `n` cell centres, each with the cosine of its normal to the direction from
/// the sphere's centre: (unit direction, weight cos/r² × cell area).
fn directions_onto(k: DVec3, u: DVec3, side: f64, n: usize) -> Vec<(DVec3, f64)> {
    let v = k.cross(u);
    let cell = side / n as f64;
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (
                cell * (i as f64 + 0.5) - side / 2.0,
                cell * (j as f64 + 0.5) - side / 2.0,
            );
            let p = 2.0 * k + a * u + b * v;
            let d = p.normalize();
            out.push((d, d.dot(k) / p.length_squared() * cell * cell));
        }
    }
    out
}

/// Rayleigh scattering polarizes unpolarized light across the scattering plane, S1/S0 =
/// sin²θ/(1 + cos²θ) in its basis (wholly at 90°), and makes no circular light. Receivers at
/// θ = 30°, 60°, 90°, 120° and 150° from the beam, width axis across the scattering plane,
/// catch light scattered once (`max_depth` 2): their S1/S0 and S2/S0 against the closed form
/// integrated over the receiver (p(θ)·cos/r², each direction's Stokes vector turned into the
/// receiver's basis, S1 = dolp·cos 2ψ, S2 = dolp·sin 2ψ; a 64 × 64 midpoint rule, the sphere
/// taken as its centre). Bars: 4 standard errors of a mean over N photons whose values spread
/// as the closed form does over the receiver (N from the flux's relative error, every photon
/// carrying the same power), plus 3·10⁻⁴ for the sphere's size (its radius 0.005 of the
/// distance: a second-order shift of θ). S3 = 0 to 10⁻⁶.
#[test]
fn rayleigh_scattering_polarizes_light_across_the_scattering_plane() {
    let (radius, side) = (0.01, 0.05);
    let angles = [30.0f64, 60.0, 90.0, 120.0, 150.0];
    let receivers: Vec<(DVec3, DVec3)> = (angles.iter())
        .map(|deg| {
            let t = deg.to_radians();
            (DVec3::new(t.sin(), 0.0, t.cos()), DVec3::Y)
        })
        .collect();
    let measured = measured(&rayleigh_sphere(radius, side, &receivers, &[]), 4_000_000);
    for ((deg, (k, u)), m) in angles.iter().zip(&receivers).zip(&measured) {
        // The closed form in the receiver's basis for light along `d`: p, S1/S0, S2/S0.
        let stokes = |d: DVec3| {
            let cos = d.z;
            let dolp = (1.0 - cos * cos) / (1.0 + cos * cos);
            let s = DVec3::Z.cross(d).normalize();
            let x = (*u - u.dot(d) * d).normalize();
            let psi = d.cross(x).dot(s).atan2(x.dot(s));
            let p = 3.0 * (1.0 + cos * cos) / (16.0 * std::f64::consts::PI);
            (p, dolp * (2.0 * psi).cos(), dolp * (2.0 * psi).sin())
        };
        let cells: Vec<(f64, f64, f64)> = directions_onto(*k, *u, side, 64)
            .into_iter()
            .map(|(d, w)| {
                let (p, s1, s2) = stokes(d);
                (p * w, s1, s2)
            })
            .collect();
        let total: f64 = cells.iter().map(|c| c.0).sum();
        let want1 = cells.iter().map(|c| c.0 * c.1).sum::<f64>() / total;
        let want2 = cells.iter().map(|c| c.0 * c.2).sum::<f64>() / total;
        let spread = |f: fn(&(f64, f64, f64)) -> f64| {
            let v = cells.iter().map(f);
            v.clone().fold(f64::NEG_INFINITY, f64::max) - v.fold(f64::INFINITY, f64::min)
        };
        assert!(m.flux.0 > 0.0, "{deg}°: no light");
        let photons = (m.flux.0 / m.flux.1).powi(2);
        let bar = |spread: f64| 4.0 * spread / photons.sqrt() + 3e-4;
        let [r1, r2, r3] = [0, 1, 2].map(|i| m.stokes[i].flux.0 / m.flux.0);
        let (bar1, bar2) = (bar(spread(|c| c.1)), bar(spread(|c| c.2)));
        assert!(
            (r1 - want1).abs() < bar1,
            "{deg}°: S1/S0 {r1} against {want1} ± {bar1} ({photons:.0} photons)"
        );
        assert!(
            (r2 - want2).abs() < bar2,
            "{deg}°: S2/S0 {r2} against {want2} ± {bar2}"
        );
        assert!(r3.abs() < 1e-6, "{deg}°: S3/S0 {r3}");
        eprintln!("{deg}°: S1/S0 {r1:.5} against {want1:.5} ± {bar1:.5}, S2/S0 {r2:.5} against {want2:.5} ± {bar2:.5}, {photons:.0} photons");
    }
}

/// The dipole a field drives radiates nothing along the field and most across it: behind a
/// polarizer along x the beam's light scattered at 90° toward +x is nothing but what the
/// receiver's width lets in off the axis (at most its largest 1 − (d·x̂)² over the least
/// toward +y, 2.1 %), and toward +y it is as bright as the unpolarized beam's (the polarizer
/// passes ½, the dipole sends twice the unpolarized share across its axis: within 4 combined
/// standard errors) — the photon's Stokes vector from the polarizer reaches the scattering.
#[test]
fn scattered_light_follows_the_dipole_the_field_drives() {
    let (radius, side) = (0.01, 0.4);
    let receivers = [(DVec3::X, DVec3::Y), (DVec3::Y, DVec3::Z)];
    let sheet = format!(
        "[[material]]\nname = \"pol\"\n{}{}",
        polarizer(0.0),
        square(-2.0, 0.1, "pol")
    );
    let photons = 4_000_000;
    let open = measured(&rayleigh_sphere(radius, side, &receivers, &[]), photons);
    let behind = measured(
        &rayleigh_sphere(radius, side, &receivers, &[sheet]),
        photons,
    );
    let across = |k: DVec3, u: DVec3| {
        let d = directions_onto(k, u, side, 64);
        let s = d.iter().map(|(d, _)| 1.0 - d.x * d.x);
        (
            s.clone().fold(f64::INFINITY, f64::min),
            s.fold(0.0, f64::max),
        )
    };
    let (_, most_along) = across(DVec3::X, DVec3::Y);
    let (least_across, _) = across(DVec3::Y, DVec3::Z);
    let bound = most_along / least_across;
    assert!(bound < 0.025, "bound {bound}");
    let along = behind[0].flux.0 / behind[1].flux.0;
    assert!(
        along < bound,
        "toward the field {along} of across it, bound {bound}"
    );
    assert!(behind[1].flux.0 > 0.0 && open[1].flux.0 > 0.0);
    let z = (behind[1].flux.0 - open[1].flux.0).abs() / behind[1].flux.1.hypot(open[1].flux.1);
    assert!(
        z < 4.0,
        "across the field {:?}, unpolarized {:?}: z {z}",
        behind[1].flux,
        open[1].flux
    );
    eprintln!(
        "toward the field {along:.2e} (bound {bound:.4}); across it {:?} against {:?}, z {z:.2}",
        behind[1].flux, open[1].flux
    );
}

/// A rough conductor (α = 0.002, η + ik = 1.2 + 2i) reflects light as its microfacets' Fresnel
/// matrices say: a narrow beam (0.05°) at 60° through a polarizer across the plane of incidence
/// (s) or in it (p) keeps R_s or R_p of what the sheet passes (Born and Wolf's complex
/// amplitudes at 60°), their ratio within 4 standard errors plus 0.1 % (R_s/R_p moves by 2 % a
/// degree of incidence, and the beam's and the lobe's spread are a few hundredths of one);
/// unpolarized, the reflected light is partly s polarized, S1/S0 = (R_s − R_p)/(R_s + R_p) in a
/// basis along s, within 1e-3 (S1/S0 moves by 0.008 a degree). A rough conductor that took
/// its light as depolarized (before 0.26.0) read the ratio as 1 and S1 as 0.
#[test]
fn a_rough_conductor_reflects_s_and_p_light_as_its_microfacets_fresnel_matrices_say() {
    use grinlight::polarization::mueller::Amplitudes;
    let d = DVec3::new(60f64.to_radians().sin(), 0.0, -60f64.to_radians().cos());
    let r = DVec3::new(d.x, 0.0, -d.z);
    let up = r.cross(DVec3::Y);
    let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
    let sheet = |axis: DVec3| {
        let c = -2.5 * d;
        let (a, b) = (0.3 * DVec3::Y, 0.3 * d.cross(DVec3::Y));
        format!(
            "[[material]]\nname = \"sheet\"\ntype = \"polarizer\"\naxis = {}\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"sheet\"\nvertices = [{}, {}, {}, {}]\n",
            v(axis),
            v(c - a - b),
            v(c + a - b),
            v(c + a + b),
            v(c - a + b)
        )
    };
    let scene = |sheet: &str| {
        format!(
            "[render]\npolarized = true\n\
             [[material]]\nname = \"metal\"\ntype = \"conductor\"\neta = 1.2\nk = 2.0\n\
             roughness = 0.002\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"metal\"\n\
             vertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]\n\
             [[light]]\ntype = \"spot\"\nposition = {}\ndirection = {}\nintensity = [1, 1, 1]\n\
             cone_deg = 0.05\n\
             [[receiver]]\nname = \"r\"\ncenter = {}\nnormal = {}\nup = {}\nsize = [2, 2]\n\
             bins = [1, 1]\n{sheet}",
            v(-3.0 * d),
            v(d),
            v(2.0 * r),
            v(r),
            v(up)
        )
    };
    let photons = 400_000;
    let s_light = &measured(&scene(&sheet(DVec3::Y)), photons)[0];
    let p_light = &measured(&scene(&sheet(d.cross(DVec3::Y))), photons)[0];
    let open = &measured(&scene(""), photons)[0];
    let amplitudes = Amplitudes::new(0.5, num_complex::Complex64::new(1.2, 2.0));
    let [rs, rp] = amplitudes.reflected.map(|a| a.norm_sqr());
    let ratio = s_light.flux.0 / p_light.flux.0;
    let spread = ratio * (s_light.flux.1 / s_light.flux.0).hypot(p_light.flux.1 / p_light.flux.0);
    println!("R_s/R_p {ratio:.5} ± {spread:.5} against {:.5}", rs / rp);
    assert!(
        (ratio - rs / rp).abs() < 4.0 * spread + 1e-3 * rs / rp,
        "{ratio} ± {spread} against {}",
        rs / rp
    );
    assert!(rs / rp > 1.2, "{}: a case that tells s from p", rs / rp);
    let s1 = open.stokes[0].flux.0 / open.flux.0;
    let want = (rs - rp) / (rs + rp);
    println!("S1/S0 {s1:.5} against {want:.5}");
    assert!((s1 - want).abs() < 1e-3, "{s1} against {want}");
}

/// Light scattered many times by Rayleigh air, measured both ways: a sphere of air (radius 1,
/// σs 1: most of the light leaving it scattered more than once) lit by a spot from below,
/// seen at 90° to the beam by an orthographic camera measuring the Stokes vector (both
/// integrators: camera paths carry the measurement against the light, through each
/// scattering's Mueller matrix and the single scattering along each stretch) and by a receiver of side 3 at
/// distance 30 the same way (photons carry the light's Stokes vector with it, drawing each
/// direction with its polarization's factor), both bases' first axis 30° off the scattering
/// plane's normal, so that S1 and S2 both read the degree of polarization (and a basis turned
/// the wrong way, S2's sign). Their S1/S0 and S2/S0 agree within 4 combined standard errors
/// plus 0.005 for the receiver's size and distance: it sees the sphere over ±3° and from 1/30
/// of a radian around it, the camera along one direction — a second-order difference, which
/// at distance 10 (±6°, 1/10) read 0.017 (measured at 30: camera 0.3406 ± 0.0024 and
/// −0.5871 ± 0.0029 (path tracer), 0.3356 ± 0.0036 and −0.5825 ± 0.0025 (photon mapper),
/// receiver 0.3373 ± 0.0077 and −0.5751 ± 0.0111).
#[test]
fn light_scattered_many_times_by_rayleigh_air_reads_alike_against_and_with_the_light() {
    let (s, c) = 30f64.to_radians().sin_cos();
    let u = DVec3::new(0.0, c, s);
    let medium = "[[medium]]\nname = \"air\"\nprofile = \"uniform\"\nn = 1\nscattering = 1\nphase = \"rayleigh\"\n\
                  [[material]]\nname = \"skin\"\ntype = \"dielectric\"\ninterior = \"air\"\n\
                  [[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"skin\"\n\
                  [[light]]\ntype = \"spot\"\nposition = [0, 0, -3]\ndirection = [0, 0, 1]\nintensity = 1\ncone_deg = 25\n";
    // With the light: a receiver along +x, its width axis u.
    let up = DVec3::X.cross(u);
    let receiver = format!(
        "[render]\npolarized = true\n{medium}\
         [[receiver]]\nname = \"r\"\ncenter = [30, 0, 0]\nnormal = [1, 0, 0]\nup = [{}, {}, {}]\nsize = [3, 3]\nbins = [1, 1]\n",
        up.x, up.y, up.z
    );
    let m = &measured(&receiver, 24_000_000)[0];
    let ratio = |i: usize| {
        let (s, se) = m.stokes[i].flux;
        let r = s / m.flux.0;
        (r, (se / m.flux.0).hypot(r * m.flux.1 / m.flux.0))
    };
    // Against it: the camera looks along −x, d × up = u.
    let camera_up = DVec3::new(0.0, -s, c);
    for integrator in ["path", "photon_map"] {
        let view = format!(
        "[camera]\nprojection = \"orthographic\"\nview_height = 2.2\nposition = [3, 0, 0]\nlook_at = [0, 0, 0]\n\
         up = [{}, {}, {}]\nwidth = 16\nheight = 16\n\
         [render]\nintegrator = \"{integrator}\"\nstokes = true\nspp = 64\nphotons = 10000\n{medium}",
        camera_up.x, camera_up.y, camera_up.z
    );
        let (scene, mut settings) =
            grinlight::scene::load::parse_scene(std::path::Path::new("air.toml"), view).unwrap();
        // Four independent renders: their spread is the camera's error.
        let runs: Vec<[f64; 4]> = (0..4)
            .map(|seed| {
                settings.seed = seed;
                let film = grinlight::render::render(&scene, &settings, &()).unwrap().0;
                ["S0", "S1", "S2", "S3"].map(|name| {
                    let layer = film.layer(name).unwrap();
                    layer.iter().map(|p| p[1] as f64).sum::<f64>()
                })
            })
            .collect();
        let sums: [f64; 4] = std::array::from_fn(|k| runs.iter().map(|r| r[k]).sum::<f64>());
        for i in 0..2 {
            let (r, se) = ratio(i);
            let seen = sums[i + 1] / sums[0];
            let each: Vec<f64> = runs.iter().map(|run| run[i + 1] / run[0]).collect();
            let mean = each.iter().sum::<f64>() / 4.0;
            let camera_se = (each.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 12.0).sqrt();
            let bar = 4.0 * se.hypot(camera_se) + 0.005;
            eprintln!(
            "{integrator}: S{}/S0: camera {seen:.4} ± {camera_se:.4}, receiver {r:.4} ± {se:.4}",
            i + 1
        );
            assert!(
                (seen - r).abs() < bar,
                "{integrator}: S{}/S0: {seen} against {r} ± {bar}",
                i + 1
            );
        }
        // A depolarized reading would make S1 and S2 both small: the light is strongly polarized.
        assert!(sums[1].hypot(sums[2]) > 0.5 * sums[0], "{sums:?}");
        assert!(
            sums[3] == 0.0 && ratio(2).0 == 0.0,
            "no circular light: {sums:?}"
        );
    }
}

/// A rough interface between equal indices lets light straight through, its polarization
/// unchanged: the facet matrix of wi = −wo is the identity (to 1e-12) rather than none (a
/// depolarizer), and a pair between unequal indices keeps its Fresnel matrix.
#[test]
fn a_rough_interface_between_equal_indices_keeps_the_polarization() {
    use grinlight::bsdf::{Bsdf, Microsurface};
    use grinlight::polarization::Sense;
    let n = DVec3::Z;
    let wo = DVec3::new(0.3, -0.2, 0.9).normalize();
    let matched = Bsdf::Dielectric {
        n1: 1.5,
        n2: 1.5,
        microsurface: Some(Microsurface::ggx(0.3)),
    };
    let element = matched
        .mueller(wo, -wo, n, Sense::WithLight)
        .expect("a matrix, not a depolarizer");
    for m in element.mueller {
        let m = m / m.col(0).x;
        assert!(
            m.abs_diff_eq(glam::DMat4::IDENTITY, 1e-12),
            "between equal indices: {m}"
        );
    }
    let glass = Bsdf::Dielectric {
        n1: 1.0,
        n2: 1.5,
        microsurface: Some(Microsurface::ggx(0.3)),
    };
    let wi = DVec3::new(-0.1, 0.15, -0.98).normalize();
    let m = glass.mueller(wo, wi, n, Sense::WithLight).unwrap().mueller[0];
    assert!(m.col(0).y.abs() > 1e-3, "a refraction polarizes: {m}");
}
