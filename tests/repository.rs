//! A clone holds everything its tests, examples and docs need: nothing in it points outside
//! the repository (a user's clone has nothing beside it).

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
