//! A render never destroys a user's file: outputs that name an input or a foreign file are
//! refused before any work, every output is written atomically, an interrupt leaves a valid
//! partial result, and absurd requests are refused at once.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn grinlight(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run grinlight")
}

/// A fresh directory holding a copy of `scenes/cornell_caustic.toml` as `s.toml`, a tiny OBJ
/// and a scene `m.toml` that reads it and an environment image `sky.exr`.
fn workspace(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("grinlight-safety-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy("scenes/cornell_caustic.toml", dir.join("s.toml")).unwrap();
    std::fs::write(dir.join("m.obj"), "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    exr::prelude::write_rgb_file(dir.join("sky.exr"), 4, 2, |_, _| (1.0f32, 1.0f32, 1.0f32))
        .unwrap();
    std::fs::write(
        dir.join("m.toml"),
        "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov_y_deg = 40\nwidth = 8\nheight = 8\n\
         [render]\nspp = 1\nphotons = 1000\ngather = 1\n\
         [[material]]\nname = \"w\"\ntype = \"diffuse\"\nalbedo = 0.5\n\
         [[shape]]\ntype = \"mesh\"\nfile = \"m.obj\"\nmaterial = \"w\"\n\
         [[light]]\ntype = \"environment\"\nfile = \"sky.exr\"\n",
    )
    .unwrap();
    dir
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Every way an output can name an input or a foreign file is refused, and the files are
/// byte-for-byte unchanged.
#[test]
fn outputs_never_overwrite_inputs_or_foreign_files() {
    let dir = workspace("inputs");
    let before: Vec<(String, Vec<u8>)> = ["s.toml", "m.toml", "m.obj", "sky.exr"]
        .iter()
        .map(|f| (f.to_string(), std::fs::read(dir.join(f)).unwrap()))
        .collect();
    std::fs::write(dir.join("notes.csv"), "my measurements: keep\n").unwrap();
    std::fs::write(dir.join("o.toml"), "[output]\npath = \"s.toml\"\n").unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["render", "s.toml", "-o", "s.toml"], "must end in .exr"),
        (
            &["render", "m.toml", "-o", "sky.exr"],
            "is an input of this run",
        ),
        (&["render", "m.toml", "-o", "m.obj"], "must end in .exr"),
        (&["render", "s.toml", "-o", "out.png"], "must end in .exr"),
        (&["render", "o.toml"], "must name an EXR"),
        (
            &[
                "trace",
                "s.toml",
                "--medium",
                "glass (ior 1.5)",
                "--from",
                "0,0,0",
                "--dir",
                "1,0,0",
                "--length",
                "1",
                "--csv",
                "s.toml",
            ],
            "is an input of this run",
        ),
        (
            &[
                "trace",
                "s.toml",
                "--medium",
                "glass (ior 1.5)",
                "--from",
                "0,0,0",
                "--dir",
                "1,0,0",
                "--length",
                "1",
                "--csv",
                "notes.csv",
            ],
            "is not a CSV table grinlight wrote",
        ),
    ];
    // The medium's name in the scene (an anonymous uniform medium of the glass's ior).
    let (scene, _) = grinlight::scene::load_scene(&dir.join("s.toml")).unwrap();
    let glass = scene.medium_names().next().unwrap().to_string();
    for (args, needle) in cases {
        let args: Vec<&str> = args
            .iter()
            .map(|a| {
                if *a == "glass (ior 1.5)" {
                    glass.as_str()
                } else {
                    a
                }
            })
            .collect();
        let out = grinlight(&dir, &args);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr(&out).contains(needle), "{args:?}: {}", stderr(&out));
    }
    for (name, bytes) in &before {
        assert_eq!(
            &std::fs::read(dir.join(name)).unwrap(),
            bytes,
            "{name} changed"
        );
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.csv")).unwrap(),
        "my measurements: keep\n"
    );
    // The render itself works there and writes only its own files.
    let out = grinlight(&dir, &["render", "m.toml", "-o", "r.exr"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(dir.join("r.exr").is_file() && dir.join("r.png").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A user's own file at a path a render derives from its output, or at the output itself, is
/// never replaced — an image beside the EXR (`photo.png` for `-o photo.exr`), an EXR another
/// program wrote, a CSV of the user's at a receiver's CSV path (a header line of names, or a
/// single lower-case word) — each refused naming it, and left byte for byte; the files a
/// render wrote are replaced by the next render.
#[test]
fn a_users_files_on_derived_paths_are_refused() {
    let dir = workspace("derived");
    std::fs::copy("scenes/fiber_led.toml", dir.join("fiber.toml")).unwrap();
    // A PNG and an EXR that grinlight did not write (another program's: no signature).
    let mut png = Vec::new();
    image::RgbImage::new(2, 2)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let exr = std::fs::read(dir.join("sky.exr")).unwrap();
    let cases: Vec<(&str, Vec<u8>, Vec<&str>)> = vec![
        (
            "photo.png",
            png.clone(),
            vec!["render", "m.toml", "-o", "photo.exr"],
        ),
        (
            "theirs.exr",
            exr,
            vec!["render", "m.toml", "-o", "theirs.exr"],
        ),
        (
            "f.exit.csv",
            b"x,y\n1,2\n".to_vec(),
            vec![
                "render",
                "fiber.toml",
                "-o",
                "f.exr",
                "--receiver-photons",
                "1000",
            ],
        ),
        (
            "g.exit.radial.csv",
            b"hello\n".to_vec(),
            vec![
                "render",
                "fiber.toml",
                "-o",
                "g.exr",
                "--receiver-photons",
                "1000",
            ],
        ),
    ];
    for (file, bytes, args) in &cases {
        std::fs::write(dir.join(file), bytes).unwrap();
        let out = grinlight(&dir, args);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(
            stderr(&out).contains(&format!("{file}: exists and is not")),
            "{args:?}: {}",
            stderr(&out)
        );
        assert_eq!(
            &std::fs::read(dir.join(file)).unwrap(),
            bytes,
            "{file} changed"
        );
        std::fs::remove_file(dir.join(file)).unwrap();
    }
    // What grinlight wrote, it replaces.
    for _ in 0..2 {
        let out = grinlight(
            &dir,
            &[
                "render",
                "fiber.toml",
                "-o",
                "f.exr",
                "--receiver-photons",
                "1000",
            ],
        );
        assert!(out.status.success(), "{}", stderr(&out));
        let out = grinlight(&dir, &["render", "m.toml", "-o", "photo.exr"]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A write that fails half-way leaves the previous file as it was and no temporary file.
#[test]
fn a_failed_write_leaves_the_previous_file_intact() {
    let dir = workspace("atomic");
    let path = dir.join("result.csv");
    std::fs::write(&path, "x,y\n1,2\n").unwrap();
    let err = grinlight::output::write_atomic(&path, |tmp| {
        std::fs::write(tmp, "x,y\n3,").unwrap();
        Err(grinlight::error::Error::Usage(
            "disk full (simulated)".into(),
        ))
    });
    assert!(err.is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "x,y\n1,2\n");
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.ends_with(".tmp")), "{names:?}");
    // A write that succeeds replaces it whole.
    grinlight::output::write_text(&path, "x,y\n5,6\n").unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "x,y\n5,6\n");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Starts a long progressive render of the caustic Cornell box writing `out` after every pass.
fn long_render(dir: &Path, out: &str) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_grinlight"))
        .args([
            "render",
            "s.toml",
            "-o",
            out,
            "--width",
            "64",
            "--height",
            "64",
            "--spp",
            "1",
            "--photons",
            "20000",
            "--caustic-photons",
            "20000",
            "--passes",
            "100000",
            "--checkpoint",
            "1",
            "--threads",
            "1",
        ])
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Waits (at most 60 s) until `path` exists.
fn wait_for(path: &Path) {
    let start = Instant::now();
    while !path.exists() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{} never appeared",
            path.display()
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Every layer of the EXR at `path` reads back whole.
fn readable(path: &Path) -> bool {
    [
        "beauty",
        "direct",
        "caustic",
        "secondary",
        "emitted",
        "albedo",
        "normal",
    ]
    .iter()
    .all(
        |l| match grinlight::compare::read_exr_layer(path, Some(l)) {
            Ok(plane) => plane.width == 64 && plane.height == 64,
            // A layer nothing wrote is left out of the file; beauty never is.
            Err(e) => *l != "beauty" && e.to_string().contains("no layer"),
        },
    )
}

/// SIGINT during a many-pass render: the EXR is written with the passes done, the report
/// says the result is partial and how many passes it holds, and the exit code is 130.
#[test]
fn an_interrupt_writes_the_passes_done_and_says_so() {
    let dir = workspace("sigint");
    let child = long_render(&dir, "c.exr");
    wait_for(&dir.join("c.exr"));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(130), "{stdout}\n{}", stderr(&out));
    assert!(stdout.contains("PARTIAL (interrupted)"), "{stdout}");
    assert!(stdout.contains("of 100000 passes"), "{stdout}");
    assert!(stdout.contains("wrote c.exr"), "{stdout}");
    assert!(readable(&dir.join("c.exr")));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// SIGKILL while a render rewrites its EXR after every pass, at several moments: the file
/// on disk is always a whole EXR (before the atomic writes, 5 kills in 8 left a truncated
/// one). Readers during the render see whole files too.
#[test]
fn a_kill_never_leaves_a_truncated_output() {
    let dir = workspace("sigkill");
    for (k, delay_ms) in [0u64, 37, 91, 150, 233].iter().enumerate() {
        let out = format!("k{k}.exr");
        let mut child = long_render(&dir, &out);
        wait_for(&dir.join(&out));
        for _ in 0..3 {
            assert!(
                readable(&dir.join(&out)),
                "kill {k}: unreadable while rendering"
            );
        }
        std::thread::sleep(Duration::from_millis(*delay_ms));
        child.kill().unwrap();
        child.wait().unwrap();
        assert!(readable(&dir.join(&out)), "kill {k} after {delay_ms} ms");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Requests that cannot be met are refused before any work: an output directory that does
/// not exist or cannot be written, a film of 65536² pixels, 10⁵ threads. Each render would
/// take minutes to hours; the refusal comes in milliseconds (bound 5 s, for a loaded CI
/// machine).
#[test]
fn impossible_requests_are_refused_at_once() {
    let dir = workspace("refuse");
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "render",
                "s.toml",
                "--passes",
                "1000",
                "-o",
                "missing/c.exr",
            ],
            "does not exist",
        ),
        (
            &["render", "s.toml", "--passes", "1000", "-o", "/proc/c.exr"],
            "cannot write",
        ),
        (
            &["render", "s.toml", "--width", "65536", "--height", "65536"],
            "of memory",
        ),
        (&["render", "s.toml", "--threads", "100000"], "per core"),
        (
            &["validate", "fiber.toml", "--plot", "missing/v.png"],
            "does not exist",
        ),
    ];
    std::fs::copy("scenes/fiber_led.toml", dir.join("fiber.toml")).unwrap();
    for (args, needle) in cases {
        let start = Instant::now();
        let out = grinlight(&dir, args);
        let took = start.elapsed();
        assert!(!out.status.success(), "{args:?}");
        assert!(stderr(&out).contains(needle), "{args:?}: {}", stderr(&out));
        assert!(took < Duration::from_secs(5), "{args:?} took {took:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
