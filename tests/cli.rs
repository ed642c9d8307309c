//! The `grinlight` binary: output files and error behaviour.

use std::process::Command;

fn grinlight(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args(args)
        .output()
        .expect("run grinlight")
}

fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("grinlight-cli-{}-{name}", std::process::id()))
}

#[test]
fn trace_writes_a_csv_from_start_to_end_and_a_png() {
    let csv = temp("path.csv");
    let png = temp("path.png");
    let out = grinlight(&[
        "trace",
        "scenes/media.toml",
        "--medium",
        "luneburg",
        "--from",
        "-0.8,0.6,0",
        "--dir",
        "2,0,0",
        "--length",
        "1.5",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        png.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("reason: length reached"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(2)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(text.starts_with("# grinlight "), "{text}");
    assert_eq!(text.lines().nth(1).unwrap(), "step,s,x,y,z,dx,dy,dz,n");
    let first = &rows[0];
    assert_eq!(&first[..8], &[0.0, 0.0, -0.8, 0.6, 0.0, 1.0, 0.0, 0.0]);
    let last = rows.last().unwrap();
    assert!((last[1] - 1.5).abs() < 1e-12, "last row at s = {}", last[1]);
    // The summary's step count is the CSV's rows minus the start row.
    let steps: usize = stdout
        .split("steps ")
        .nth(1)
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(rows.len(), steps + 1);
    // n in the CSV is the Luneburg index at the row's position.
    for r in &rows {
        let r2 = r[2] * r[2] + r[3] * r[3] + r[4] * r[4];
        let n = if r2 > 1.0 { 1.0 } else { (2.0 - r2).sqrt() };
        assert!((r[8] - n).abs() < 1e-12);
    }
    let png_bytes = std::fs::read(&png).unwrap();
    assert_eq!(&png_bytes[..8], b"\x89PNG\r\n\x1a\n");
    let _ = std::fs::remove_file(csv);
    let _ = std::fs::remove_file(png);
}

/// A trace command line: `trace SCENE --medium M --from F --dir D --length L` plus `extra`,
/// given as one whitespace-separated string.
fn trace_args(
    scene: &str,
    medium: &str,
    from: &str,
    dir: &str,
    length: &str,
    extra: &str,
) -> Vec<String> {
    let mut v: Vec<String> = [
        "trace", scene, "--medium", medium, "--from", from, "--dir", dir, "--length", length,
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    v.extend(extra.split_whitespace().map(str::to_string));
    v
}

#[test]
fn bad_input_fails_with_a_message_and_no_panic() {
    let media = "scenes/media.toml";
    let cases = [
        (
            trace_args(media, "nope", "0,0,0", "0,0,1", "1", ""),
            "no medium named 'nope'",
        ),
        (
            trace_args("scenes/missing.toml", "a", "0,0,0", "0,0,1", "1", ""),
            "scenes/missing.toml",
        ),
        (
            trace_args(media, "luneburg", "0,0", "0,0,1", "1", ""),
            "expected X,Y,Z",
        ),
        (
            trace_args(media, "luneburg", "0,0,0", "0,0,0", "1", ""),
            "--dir",
        ),
        (
            trace_args(media, "luneburg", "0,0,0", "0,0,1", "-1", ""),
            "--length",
        ),
        (
            trace_args(media, "luneburg", "0,0,0", "0,0,1", "1", "--control fixed"),
            "--step",
        ),
        (
            trace_args(media, "luneburg", "0,0,0", "0,0,1", "1", "--tol 0"),
            "--tol",
        ),
        (
            trace_args(
                media,
                "luneburg",
                "0,0,0",
                "0,0,1",
                "1",
                "--control tessendorf --tmax 1e-4 --tmin 1e-2",
            ),
            "--tmin",
        ),
        (
            trace_args(media, "black_hole", "0,0,0", "0,0,1", "1", ""),
            "captures rays",
        ),
        (
            trace_args(media, "luneburg", "nan,0,0", "0,0,1", "1", ""),
            "not finite",
        ),
        (
            trace_args(media, "luneburg", "0,0,0", "0,0,1", "1", "--stepper euler"),
            "unknown stepper",
        ),
        (
            trace_args(
                media,
                "grin_rod_chromatic",
                "0,0,0",
                "0,0,1",
                "1",
                "--wavelength 1000",
            ),
            "--wavelength must be from 360 to 830 nm, got 1000",
        ),
    ];
    for (args, needle) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = grinlight(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
        assert!(
            stderr.contains(needle),
            "{args:?}: '{stderr}' lacks '{needle}'"
        );
    }
}

/// `render --paths N` on the fiber writes the receiver files and the three-panel figure, whose
/// middle panel holds the drawn paths; the energy budget is printed; without a receiver, or
/// for more paths than a figure can hold, `--paths` is refused with a message.
#[test]
fn render_paths_draws_the_fiber_figure() {
    let exr = temp("fiber.exr");
    let out = grinlight(&[
        "render",
        "scenes/fiber_led.toml",
        "--receiver-photons",
        "3000",
        "--paths",
        "8",
        "-o",
        exr.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("8 photon paths"), "{stdout}");
    assert!(
        stdout.contains("energy budget: emitted 1.000000e-2 W, booked 1.000000e-2 W"),
        "{stdout}"
    );
    let stem = exr.with_extension("");
    let figure = std::path::PathBuf::from(format!("{}.paths.png", stem.display()));
    let img = image::open(&figure).unwrap().to_rgb8();
    // Path colours are saturated; the middle panel's shading, axes and text are grey. The
    // panel spans pixels x 400..1120, y 70..370 (margins 70, profile panel 260 wide).
    let coloured = img
        .enumerate_pixels()
        .filter(|(x, y, p)| {
            (400..1120).contains(x)
                && (70..370).contains(y)
                && p.0.iter().max().unwrap() - p.0.iter().min().unwrap() > 60
        })
        .count();
    assert!(coloured > 2000, "{coloured} coloured pixels");
    for ext in [
        "paths.png",
        "exit.csv",
        "exit.png",
        "exit.radial.csv",
        "exit.radial.png",
    ] {
        std::fs::remove_file(format!("{}.{ext}", stem.display())).unwrap();
    }
    let out = grinlight(&["render", "scenes/cornell_diffuse.toml", "--paths", "3"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no [[receiver]]"));
    let out = grinlight(&["render", "scenes/fiber_led.toml", "--paths", "100000"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("at most 10000 paths"));
}

/// `validate` on a fiber whose receiver measures wavelength bands compares each band apart:
/// a table row per band after the twin's row.
#[test]
fn validate_compares_each_band() {
    let scene = temp("fiber_bands.toml");
    let text = std::fs::read_to_string("scenes/fiber_led.toml")
        .unwrap()
        .replace(
            "bins = [64, 64]",
            "bins = [16, 16]\nbands = [[600.0, 625.0], [625.0, 650.0]]",
        );
    std::fs::write(&scene, text).unwrap();
    let plot = temp("fiber_bands.validate.png");
    let out = grinlight(&[
        "validate",
        scene.to_str().unwrap(),
        "--dn",
        "0.01",
        "--photons",
        "20000",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for band in ["| 0.01, band 600–625 nm |", "| 0.01, band 625–650 nm |"] {
        assert!(stdout.contains(band), "{band} missing:\n{stdout}");
    }
    let _ = std::fs::remove_file(scene);
    let _ = std::fs::remove_file(plot);
}

/// The scene file and the command line read each setting of the settings table
/// (`grinlight::settings::KEYS`) alike: a value it refuses (each side of a count's range, a
/// number ≤ 0, a word that is not a choice, a word that is not true or false) is refused by
/// both, before any work, in the same words.
#[test]
fn the_scene_file_and_the_command_line_refuse_the_same_values() {
    use grinlight::settings::{Given, Table, KEYS};
    let dir = temp("ranges");
    std::fs::create_dir_all(&dir).unwrap();
    let base = std::fs::read_to_string("scenes/cornell_diffuse.toml").unwrap();
    let bad = |key: &'static grinlight::settings::Key| -> Vec<Given> {
        let mut values: Vec<Given> = [
            Given::Integer(-1),
            Given::Integer(0),
            Given::Number(-1.5),
            Given::Text("nonsense".into()),
            Given::Integer(i128::from(u32::MAX) + 1),
            Given::Integer(70_000),
        ]
        .into_iter()
        .filter(|g| key.read(g).is_err())
        .collect();
        values.dedup();
        values
    };
    for key in KEYS {
        let values = bad(key);
        assert!(values.len() >= 2, "{}: too few refused values", key.name);
        for given in values {
            let why = key.read(&given).unwrap_err();
            let (toml, word) = match &given {
                Given::Integer(i) => (i.to_string(), i.to_string()),
                Given::Number(x) => (format!("{x:?}"), format!("{x}")),
                Given::Text(t) => (format!("\"{t}\""), t.clone()),
                other => panic!("no such test value {other:?}"),
            };
            let table = match key.table {
                Table::Render => "[render]",
                Table::Camera => "[camera]",
            };
            let own = format!("{} =", key.name);
            let text: String = base
                .lines()
                .filter(|l| !l.starts_with(&own))
                .map(|l| format!("{l}\n"))
                .collect();
            let text = text.replacen(table, &format!("{table}\n{own} {toml}"), 1);
            let scene = dir.join(format!("{}-{word}.toml", key.name));
            std::fs::write(&scene, text).unwrap();
            let by_file = grinlight(&["render", scene.to_str().unwrap()]);
            let by_flag = grinlight(&["render", "scenes/cornell_diffuse.toml", &key.flag(), &word]);
            for (how, out) in [("file", by_file), ("flag", by_flag)] {
                let stderr = String::from_utf8_lossy(&out.stderr);
                assert!(!out.status.success(), "{} = {word} by {how}", key.name);
                assert!(
                    stderr.contains(&why),
                    "{} = {word} by {how}: '{stderr}' lacks '{why}'",
                    key.name
                );
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A misspelt setting is refused by the scene file and the command line in the same words
/// ("unknown key `sppp` (expected one of: …)"); Python's are checked in
/// python/tests/test_errors.py.
#[test]
fn a_misspelt_setting_reads_alike_from_the_file_and_the_flag() {
    let dir = temp("misspelt");
    std::fs::create_dir_all(&dir).unwrap();
    let base = std::fs::read_to_string("scenes/cornell_diffuse.toml").unwrap();
    let scene = dir.join("sppp.toml");
    std::fs::write(&scene, base.replacen("[render]", "[render]\nsppp = 4", 1)).unwrap();
    let by_file = grinlight(&["render", scene.to_str().unwrap()]);
    let by_flag = grinlight(&["render", "scenes/cornell_diffuse.toml", "--sppp", "4"]);
    for (how, out) in [("file", by_file), ("flag", by_flag)] {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{how}");
        assert!(
            stderr.contains("unknown key `sppp` (expected one of: ") && stderr.contains("spp"),
            "{how}: {stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A trace that keeps every point (the library's `trace_ray`, Python's `trace`) is refused up
/// front when `max_steps` points cannot fit in memory, naming the setting; the command line's,
/// which streams its CSV and keeps a bounded plot, is stopped by an interrupt where it is
/// (reason: stopped), its CSV written up to there, the exit code 130.
#[test]
fn a_trace_holds_bounded_memory_and_stops_on_an_interrupt() {
    use grinlight::commands::{trace_ray, RayTrace, TraceControl};
    let (scene, _) =
        grinlight::scene::load_scene(std::path::Path::new("scenes/media.toml")).unwrap();
    let ray = RayTrace {
        medium: "luneburg".into(),
        from: glam::DVec3::ZERO,
        dir: glam::DVec3::X,
        length: 1.0,
        wavelength: None,
        stepper: RayTrace::STEPPER,
        control: TraceControl::Fixed { step: Some(1e-9) },
        max_steps: 1 << 40,
        polarization: None,
    };
    let e = trace_ray(&scene, &ray, &())
        .expect_err("refused")
        .to_string();
    assert!(e.contains("max_steps") && e.contains("memory"), "{e}");

    let csv = temp("interrupted.csv");
    let child = Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args([
            "trace",
            "scenes/media.toml",
            "--medium",
            "luneburg",
            "--from",
            "0,0,0",
            "--dir",
            "1,0,0",
            "--length",
            "1",
            "--control",
            "fixed",
            "--step",
            "1e-9",
            "--max-steps",
            "1000000000",
            "--csv",
            csv.to_str().unwrap(),
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(130), "{stdout}");
    assert!(stdout.contains("reason: stopped"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("# grinlight ") && text.lines().count() > 1000);
    std::fs::remove_file(&csv).unwrap();
}

#[test]
fn convert_writes_a_scene_replaces_only_its_own_and_render_reads_the_xml() {
    let dir = temp("convert");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("box.toml");
    let out_s = out.to_str().unwrap();
    let xml = "scenes/mitsuba/cornell_box.xml";
    let first = grinlight(&["convert", xml, "-o", out_s, "-D", "res=8"]);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("# Converted by grinlight "), "{text}");
    assert!(text.contains("width = 8"), "{text}");
    // Its own file it replaces; a file of the user's it leaves alone.
    let again = grinlight(&["convert", xml, "-o", out_s]);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    let mine = dir.join("mine.toml");
    std::fs::write(&mine, "# my scene\n").unwrap();
    let refused = grinlight(&["convert", xml, "-o", mine.to_str().unwrap()]);
    assert_eq!(refused.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&mine).unwrap(), "# my scene\n");
    // The XML renders as it is, its parameters from the command line.
    let exr = dir.join("box.exr");
    let render = grinlight(&[
        "render",
        xml,
        "-D",
        "res=8",
        "-D",
        "spp=1",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert!(
        render.status.success(),
        "{}",
        String::from_utf8_lossy(&render.stderr)
    );
    assert!(exr.exists());
}

/// With `stokes` the render writes `<stem>.polarization.png` beside its preview, hue the angle
/// of linear polarization and saturation its degree: a lit wall seen through a polarizer along
/// the image's right line is red (the light wholly polarized along the first axis, S1 = S0),
/// through one along its up cyan, and without the sheet grey; without `stokes` no such file.
#[test]
fn a_stokes_render_writes_a_false_colour_picture_of_its_polarization() {
    let wall = "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, 4]\nfov_y_deg = 4\nwidth = 8\n\
                height = 8\n[render]\nspp = 4\nintegrator = \"path\"\nstokes = true\n\
                [[material]]\nname = \"white\"\ntype = \"diffuse\"\nalbedo = [0.8, 0.8, 0.8]\n\
                [[shape]]\ntype = \"quad\"\nmaterial = \"white\"\n\
                vertices = [[-4, -4, 4], [-4, 4, 4], [4, 4, 4], [4, -4, 4]]\n\
                [[light]]\ntype = \"point\"\nposition = [0, 0, 3]\nintensity = [30, 30, 30]\n";
    let sheet = |axis: &str| {
        format!(
            "[[material]]\nname = \"sheet\"\ntype = \"polarizer\"\naxis = {axis}\n\
             [[shape]]\ntype = \"quad\"\nmaterial = \"sheet\"\n\
             vertices = [[-3, -3, 1], [3, -3, 1], [3, 3, 1], [-3, 3, 1]]\n"
        )
    };
    let centre = |text: &str, name: &str| -> Option<[u8; 3]> {
        let scene = temp(&format!("{name}.toml"));
        let exr = temp(&format!("{name}.exr"));
        std::fs::write(&scene, text).unwrap();
        let out = grinlight(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            exr.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let png = exr.with_extension("polarization.png");
        let pixel = png
            .exists()
            .then(|| image::open(&png).unwrap().to_rgb8().get_pixel(4, 4).0);
        for f in [scene, exr.clone(), exr.with_extension("png"), png] {
            let _ = std::fs::remove_file(f);
        }
        pixel
    };
    // The camera looks along +z with y up: its right is −x.
    let [r, g, b] = centre(&format!("{wall}{}", sheet("[1, 0, 0]")), "right").unwrap();
    assert!(
        r > 100 && g == 0 && b == 0,
        "along the right: {:?}",
        [r, g, b]
    );
    let [r, g, b] = centre(&format!("{wall}{}", sheet("[0, 1, 0]")), "up").unwrap();
    assert!(r == 0 && g > 100 && g == b, "along the up: {:?}", [r, g, b]);
    let [r, g, b] = centre(wall, "open").unwrap();
    assert!(r > 100 && r == g && g == b, "unpolarized: {:?}", [r, g, b]);
    let plain = wall.replace("stokes = true\n", "");
    assert_eq!(centre(&plain, "plain"), None);
}
