//! The values of a grinlight scene table as converters write them (docs/scene-format.md).

use glam::DVec3;
use toml::{Table, Value as Toml};

/// A name no table of `tables` has: `wanted` itself where it is free, else `wanted-1`,
/// `wanted-2`, ….
pub fn free_name(tables: &[Table], wanted: &str) -> String {
    let taken = |n: &str| {
        tables
            .iter()
            .any(|t| t.get("name").and_then(Toml::as_str) == Some(n))
    };
    std::iter::once(wanted.to_string())
        .chain((1..).map(|i| format!("{wanted}-{i}")))
        .find(|n| !taken(n))
        .expect("a free name")
}

/// A vector as a TOML array.
pub fn vec3(v: DVec3) -> Toml {
    Toml::Array(v.to_array().iter().map(|&x| Toml::Float(x)).collect())
}

/// A table from key–value pairs.
pub fn table<const N: usize>(pairs: [(&str, Toml); N]) -> Table {
    pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}

/// A string as a TOML value.
pub fn string(s: &str) -> Toml {
    Toml::String(s.to_string())
}
