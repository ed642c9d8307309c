//! The repository itself: a clone holds everything its tests, examples and docs need (nothing
//! in it points outside the repository: a user's clone has nothing beside it), and the code
//! keeps the layering `docs/architecture.md` describes (each module imports only from the
//! floors below it; a folder's files import one another without a circle).

use std::path::Path;

fn files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, out);
        } else if path
            .extension()
            .is_some_and(|e| ["rs", "toml", "md"].iter().any(|x| e == *x))
        {
            out.push(path);
        }
    }
}

#[test]
fn nothing_reaches_outside_the_repository() {
    let mut all = vec![Path::new("README.md").to_path_buf()];
    for dir in ["src", "tests", "examples", "scenes", "docs", "refs"] {
        files(Path::new(dir), &mut all);
    }
    // Built from pieces, so this file does not match itself.
    let needle = format!("{}/{}", "..", "shared");
    let offenders: Vec<_> = all
        .iter()
        .filter(|p| std::fs::read_to_string(p).is_ok_and(|t| t.contains(&needle)))
        .collect();
    assert!(
        offenders.is_empty(),
        "{offenders:?} point outside the repository"
    );
    // The reference the render tests compare with is in the repository.
    assert!(Path::new("refs/cornell_diffuse.reference.exr").is_file());
}

/// The floors of `docs/architecture.md`'s layout table: module name → floor.
fn floors() -> std::collections::BTreeMap<String, u32> {
    let doc = std::fs::read_to_string("docs/architecture.md").unwrap();
    let start = doc
        .find("## Layout")
        .expect("docs/architecture.md has a Layout section");
    let block = doc[start..]
        .split("```")
        .nth(1)
        .expect("the Layout section has a table");
    let mut floors = std::collections::BTreeMap::new();
    let mut floor = None;
    for line in block.lines().filter(|l| l.len() > 3) {
        let (number, rest) = line.split_at(3);
        if let Ok(n) = number.trim().parse::<u32>() {
            floor = Some(n);
        } else if !number.trim().is_empty() || rest.starts_with(' ') {
            continue; // a description's continuation
        }
        let names = rest.split("  ").next().unwrap();
        for name in names.split(',') {
            let name = name.trim().trim_end_matches('/');
            let f = floor.unwrap_or_else(|| panic!("{name:?} is listed before any floor"));
            assert!(
                floors.insert(name.to_string(), f).is_none(),
                "{name} listed twice"
            );
        }
    }
    floors
}

/// The source of `path` without its comment lines (doc links name modules without using them).
fn code(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The names that follow `prefix` in `text` (`crate::` → the modules it reaches).
fn names_after<'t>(text: &'t str, prefix: &str) -> Vec<&'t str> {
    text.match_indices(prefix)
        .map(|(i, _)| {
            let rest = &text[i + prefix.len()..];
            let end = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            &rest[..end]
        })
        .filter(|n| !n.is_empty())
        .collect()
}

/// The library's modules: each top-level file or folder of `src/` but `lib.rs`, `bin/` and
/// the sources inside it.
fn modules() -> Vec<(String, Vec<std::path::PathBuf>)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir("src").unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if name == "lib" || name == "bin" {
            continue;
        }
        let mut sources = Vec::new();
        if path.is_dir() {
            files(&path, &mut sources);
            sources.retain(|p| p.extension().is_some_and(|e| e == "rs"));
        } else {
            sources.push(path);
        }
        out.push((name, sources));
    }
    out
}

#[test]
fn every_module_imports_only_from_floors_below_it() {
    let floors = floors();
    let mut wrong = Vec::new();
    for (module, sources) in modules() {
        let Some(&floor) = floors.get(&module) else {
            wrong.push(format!("{module} is on no floor of docs/architecture.md"));
            continue;
        };
        for source in &sources {
            for used in names_after(&code(source), "crate::") {
                if used == module {
                    continue;
                }
                match floors.get(used) {
                    Some(&f) if f < floor => {}
                    Some(&f) => wrong.push(format!(
                        "{} (floor {floor}) uses {used} (floor {f})",
                        source.display()
                    )),
                    None => wrong.push(format!("{} uses {used}, on no floor", source.display())),
                }
            }
        }
    }
    for listed in floors.keys() {
        let exists = Path::new("src").join(listed).is_dir()
            || Path::new("src").join(format!("{listed}.rs")).is_file();
        if !exists {
            wrong.push(format!(
                "docs/architecture.md lists {listed}, which src/ lacks"
            ));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn the_files_of_a_folder_import_one_another_without_a_circle() {
    for (module, sources) in modules() {
        // Each file's siblings it names through `super::` or `crate::module::`.
        let sibling = |p: &Path| {
            let stem = p.file_stem().unwrap().to_string_lossy().to_string();
            match stem.as_str() {
                "mod" => p.parent().unwrap().to_string_lossy().to_string(),
                _ => p.with_extension("").to_string_lossy().to_string(),
            }
        };
        let nodes: Vec<String> = sources.iter().map(|p| sibling(p)).collect();
        let mut edges = std::collections::BTreeMap::<String, Vec<String>>::new();
        for (source, node) in sources.iter().zip(&nodes) {
            let text = code(source);
            let folder = if source.file_stem().is_some_and(|s| s == "mod") {
                Path::new(node).parent().unwrap().to_path_buf()
            } else {
                source.parent().unwrap().to_path_buf()
            };
            let mut targets: Vec<String> = names_after(&text, "super::")
                .into_iter()
                .map(|n| folder.join(n).to_string_lossy().to_string())
                .collect();
            targets.extend(
                names_after(&text, &format!("crate::{module}::"))
                    .into_iter()
                    .map(|n| format!("src/{module}/{n}")),
            );
            targets.retain(|t| t != node && nodes.contains(t));
            // A folder's mod.rs that declares its files is above them; one of them reaching
            // back into mod.rs for a shared type is the only direction allowed.
            if source.file_stem().is_some_and(|s| s == "mod") {
                continue;
            }
            edges.insert(node.clone(), targets);
        }
        // Depth-first search for a back edge.
        fn visit(
            node: &str,
            edges: &std::collections::BTreeMap<String, Vec<String>>,
            path: &mut Vec<String>,
            done: &mut std::collections::BTreeSet<String>,
        ) {
            if let Some(i) = path.iter().position(|p| p == node) {
                panic!("a circle: {}", path[i..].join(" → ") + " → " + node);
            }
            if !done.insert(node.to_string()) {
                return;
            }
            path.push(node.to_string());
            for next in edges.get(node).into_iter().flatten() {
                visit(next, edges, path, done);
            }
            path.pop();
        }
        let mut done = std::collections::BTreeSet::new();
        for node in edges.keys() {
            visit(node, &edges, &mut Vec::new(), &mut done);
        }
    }
}
