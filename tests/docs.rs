//! The documentation stays true to the program: the README short, every link and picture in
//! the documents there, the command-line reference the program's own help, and the documents
//! and code speaking of the product, citing published works (docs/references.md).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The command-line reference as the program's help gives it.
fn cli_reference() -> String {
    let help = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_grinlight"))
            .args(args)
            .output()
            .expect("run grinlight");
        assert!(out.status.success(), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let mut doc = String::from(
        "# Command-line reference\n\nGenerated from `grinlight help` (a test checks it is current; \
         `GRINLIGHT_WRITE_DOCS=1 cargo test --release --test tests docs::` rewrites it). The scene keys \
         these options override are in [scene-format.md](scene-format.md); how to use them, in \
         [guide.md](guide.md).\n\n## grinlight\n\n```\n",
    );
    doc += &help(&["--help"]);
    doc += "```\n";
    for command in ["render", "merge", "validate", "trace"] {
        doc += &format!(
            "\n## grinlight {command}\n\n```\n{}```\n",
            help(&["help", command])
        );
    }
    doc
}

#[test]
fn the_cli_reference_is_the_programs_help() {
    let path = Path::new("docs/cli.md");
    let current = cli_reference();
    if std::env::var_os("GRINLIGHT_WRITE_DOCS").is_some() {
        std::fs::write(path, &current).unwrap();
    }
    assert!(
        std::fs::read_to_string(path).is_ok_and(|t| t == current),
        "docs/cli.md is stale: GRINLIGHT_WRITE_DOCS=1 cargo test --release --test tests docs::"
    );
}

#[test]
fn the_readme_is_short() {
    let lines = std::fs::read_to_string("README.md")
        .unwrap()
        .lines()
        .count();
    assert!(
        lines <= 200,
        "README.md has {lines} lines: the rest belongs in docs/"
    );
}

/// README.md, CHANGELOG.md and every document in docs/.
fn documents() -> Vec<PathBuf> {
    let mut all = vec![PathBuf::from("README.md"), PathBuf::from("CHANGELOG.md")];
    for entry in std::fs::read_dir("docs").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            all.push(path);
        }
    }
    all
}

/// Every `](target)` of a Markdown text that is not a web address or an anchor.
fn local_links(text: &str) -> Vec<String> {
    text.split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .map(|t| t.split('#').next().unwrap_or_default().trim().to_string())
        .filter(|t| !t.is_empty() && !t.contains("://") && !t.starts_with("mailto:"))
        .collect()
}

#[test]
fn every_link_and_picture_in_the_documents_is_there() {
    let mut missing = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        let dir = doc.parent().unwrap();
        for link in local_links(&text) {
            if !dir.join(&link).exists() {
                missing.push(format!("{}: {link}", doc.display()));
            }
        }
    }
    assert!(missing.is_empty(), "{missing:#?}");
}

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| {
            ["rs", "toml", "md", "sh", "py", "sbatch"]
                .iter()
                .any(|x| e == *x)
        }) {
            out.push(path);
        }
    }
}

/// The repository speaks of the product: no words of how it was developed, and sources cited
/// as published works (docs/references.md), not by names of documents a reader cannot open.
/// CHANGELOG.md is the one place for history.
#[test]
fn the_repository_speaks_of_the_product() {
    let mut files = vec![PathBuf::from("README.md"), PathBuf::from("Cargo.toml")];
    for dir in [
        "src", "tests", "examples", "scenes", "docs", "cluster", "bench", "python",
    ] {
        if Path::new(dir).is_dir() {
            sources(Path::new(dir), &mut files);
        }
    }
    // Built from pieces, so this file does not match itself.
    let words = [
        ["seed", " 00"].concat(),
        ["DESIGN", ".md"].concat(),
        ["DESIGN", " §"].concat(),
        ["sess", "ion"].concat(),
        ["the ", "issue"].concat(),
        ["issue", "'s"].concat(),
        ["last ", "build"].concat(),
        ["this ", "build"].concat(),
    ];
    let mut found = Vec::new();
    for f in &files {
        let Ok(text) = std::fs::read_to_string(f) else {
            continue;
        };
        for (n, line) in text.lines().enumerate() {
            // A peer renderer's API name (pyluxcore's), not a word about development.
            let lower = line.to_lowercase().replace("rendersession", "");
            let word = words
                .iter()
                .find(|w| lower.contains(&w.to_lowercase()))
                .cloned()
                .or_else(|| numbered_work_item(&lower));
            if let Some(w) = word {
                found.push(format!("{}:{}: '{w}': {}", f.display(), n + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// A tracker's work item named by number (the word issue or evidence and a number), if `line`
/// (lower case) names one: the product's files cite what a reader can open, not a tracker.
fn numbered_work_item(line: &str) -> Option<String> {
    ["issue ", "issues ", "issue #", "evidence "]
        .iter()
        .find_map(|w| {
            line.match_indices(w).find_map(|(at, _)| {
                let after = &line[at + w.len()..];
                let before = line[..at].chars().next_back();
                let starts_word = before.is_none_or(|c| !c.is_alphanumeric());
                (starts_word && after.starts_with(|c: char| c.is_ascii_digit()))
                    .then(|| format!("{w}{}", &after[..1]))
            })
        })
}

#[test]
fn numbered_work_items_are_recognised() {
    // Built from pieces, so this file does not match itself.
    let named = |w: &str, n: &str| numbered_work_item(&format!("/// ({w}{n}'s): a file"));
    assert!(named("issue ", "15").is_some());
    assert!(named("evidence ", "3").is_some());
    assert!(named("issue #", "24").is_some());
    assert!(numbered_work_item("n = 1.5 (issue of glass), 4 passes").is_none());
    assert!(numbered_work_item("value #7 is not a number").is_none());
}

/// Every setting of the settings table (`grinlight::settings::KEYS`) has a row in the
/// scene-format reference that gives its range and its default, and the default the table
/// gives in words is the one the program starts from.
#[test]
fn the_scene_format_gives_each_settings_range_and_default() {
    use grinlight::settings::{Given, Settings, Target, KEYS};
    let doc = std::fs::read_to_string("docs/scene-format.md").unwrap();
    for key in KEYS {
        let name = format!("`{}`", key.name);
        let row = doc
            .lines()
            .find(|l| l.starts_with('|') && l.split('|').nth(1).is_some_and(|k| k.contains(&name)))
            .unwrap_or_else(|| panic!("docs/scene-format.md has no row for {name}"));
        assert!(
            row.contains(&key.range()) && row.contains(key.default),
            "docs/scene-format.md: {name} should give its range {} and default {}: {row}",
            key.range(),
            key.default
        );
        // A default in numbers or names is the program's own: setting it changes nothing.
        if let Ok(a) = key.read(&Given::from_text(key.default)) {
            let mut settings = Settings::default();
            let mut camera = grinlight::camera::Camera::new(
                glam::DVec3::ZERO,
                glam::DVec3::Z,
                glam::DVec3::Y,
                40.0,
                grinlight::camera::Camera::DEFAULT_WIDTH,
                grinlight::camera::Camera::DEFAULT_HEIGHT,
            )
            .unwrap();
            let before = (settings.clone(), camera.width, camera.height);
            a.apply(&mut Target {
                settings: &mut settings,
                camera: Some(&mut camera),
            });
            assert_eq!(
                (settings, camera.width, camera.height),
                before,
                "{name}: the table's default {} is not the program's",
                key.default
            );
        }
    }
}

/// The scene the README shows is a scene grinlight reads.
#[test]
fn the_readme_scene_loads() {
    let readme = std::fs::read_to_string("README.md").unwrap();
    let start = readme.find("```toml\n").expect("a TOML block") + 8;
    let end = start + readme[start..].find("```").unwrap();
    let (description, _) = grinlight::scene::load::parse_description(
        Path::new("readme.toml"),
        readme[start..end].to_string(),
    )
    .unwrap();
    assert!(description.camera.is_some() && description.shapes.len() == 2);
}

/// Every `$ grinlight trace …` example in docs/guide.md prints, run here, the lines the guide
/// shows under it.
#[test]
fn the_guides_trace_examples_print_what_it_shows() {
    let guide = std::fs::read_to_string("docs/guide.md").unwrap();
    let lines: Vec<&str> = guide.lines().collect();
    let mut checked = 0;
    for (i, line) in lines.iter().enumerate() {
        let Some(command) = line.strip_prefix("$ grinlight trace ") else {
            continue;
        };
        let args: Vec<&str> = std::iter::once("trace")
            .chain(command.split_whitespace())
            .collect();
        let out = Command::new(env!("CARGO_BIN_EXE_grinlight"))
            .args(&args)
            .output()
            .expect("run grinlight");
        assert!(out.status.success(), "{command}");
        let printed = String::from_utf8(out.stdout).unwrap();
        for (k, printed) in printed.trim_end().lines().enumerate() {
            assert_eq!(
                printed,
                lines[i + 1 + k],
                "docs/guide.md line {}",
                i + 2 + k
            );
        }
        checked += 1;
    }
    assert!(checked > 0, "no trace example in docs/guide.md");
}

/// Every recipe of docs/cookbook.md — a `## title` and the TOML block under it — is a scene
/// grinlight renders without a warning (at a few pixels and photons, here), writing its image
/// or its receivers' readings.
#[test]
fn every_cookbook_recipe_renders_without_a_warning() {
    let cookbook = std::fs::read_to_string("docs/cookbook.md").unwrap();
    let dir = std::env::temp_dir().join(format!("grinlight-cookbook-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut rendered = 0;
    for section in cookbook.split("\n## ").skip(1) {
        let title = section.lines().next().unwrap();
        let start = section.find("```toml\n").expect("a TOML block") + 8;
        let end = start + section[start..].find("```").unwrap();
        let slug: String = title
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() {
                    c.to_ascii_lowercase()
                } else {
                    '_'
                }
            })
            .collect();
        let scene = dir.join(format!("{slug}.toml"));
        std::fs::write(&scene, &section[start..end]).unwrap();
        let has_camera = section[start..end].contains("[camera]");
        let mut args: Vec<String> = ["render", scene.to_str().unwrap(), "-o"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        args.push(dir.join(format!("{slug}.exr")).to_str().unwrap().into());
        args.extend(
            [
                "--passes",
                "1",
                "--photons",
                "2000",
                "--caustic-photons",
                "2000",
                "--receiver-photons",
                "5000",
                "--threads",
                "2",
            ]
            .map(String::from),
        );
        if has_camera {
            args.extend(["--width", "16", "--height", "12", "--spp", "1"].map(String::from));
        }
        let out = Command::new(env!("CARGO_BIN_EXE_grinlight"))
            .args(&args)
            .output()
            .expect("run grinlight");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "recipe {title:?}: {stderr}");
        assert!(
            !stderr.to_lowercase().contains("warning"),
            "recipe {title:?} warns: {stderr}"
        );
        let written = if has_camera {
            dir.join(format!("{slug}.exr"))
        } else {
            dir.join(format!("{slug}.exit.csv"))
        };
        assert!(written.is_file(), "recipe {title:?} wrote no {written:?}");
        rendered += 1;
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(rendered, 8, "docs/cookbook.md's recipes");
}
