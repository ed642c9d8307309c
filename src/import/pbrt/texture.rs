//! pbrt-v4's spectrum textures as a material's reflectance (`"texture reflectance" "name"`):
//! `imagemap` and `checkerboard` over a shape's (u, v) (`mapping "uv"`), as pbrt-v4's
//! `textures.cpp` and `textures.h` make them.
//!
//! **The map.** pbrt looks a texture up at s = su·u + du, t = sv·v + dv (`uscale`, `vscale`,
//! `udelta`, `vdelta`); an image at (s, 1 − t) from its top-left corner, as grinlight reads
//! (u, v) through `texture_uv`: x = su·u + du, y = sv·(1 − v) + 1 − sv − dv. pbrt's
//! checkerboard takes `tex1` where ⌊s⌋ + ⌊t⌋ is even, grinlight's (Mitsuba's) its first
//! colour where x and y lie in the same half of their unit cells: x = s/2, y = t/2 exactly.
//!
//! **What differs.** pbrt reads an image at a MIP level its ray differentials choose, and
//! filters the checkerboard over each sample's footprint; grinlight reads the full image and
//! the checkerboard at the point. Both agree where the texture is magnified and away from the
//! checkerboard's edges; each texture converts with that approximation named.

use super::super::table::{string, table, vec3};
use super::super::Place;
use super::parse::{Params, Statement};
use crate::error::{cut, Result};
use glam::DVec3;
use std::path::PathBuf;
use toml::{Table, Value as Toml};

/// A texture converted: the material keys it sets, and what pbrt does differently.
pub(super) struct Converted {
    /// `texture` (and its filter, wrap and map, and the `albedo` its scale sets) or
    /// `checkerboard` and its map.
    pub keys: Table,
    /// The approximation, as the conversion lists it.
    pub differs: String,
}

/// pbrt's `uv` mapping of a texture's parameters `p`: (su, sv, du, dv).
fn uv_mapping(p: &Params, place: &Place, what: &str) -> Result<[f64; 4]> {
    match p.string("mapping")?.as_deref() {
        None | Some("uv") => {}
        Some(other) => {
            return Err(place.error(format!(
                "{what}: the mapping \"{}\" is not supported (\"uv\" is)",
                cut(other)
            )))
        }
    }
    Ok([
        p.float("uscale", 1.0)?,
        p.float("vscale", 1.0)?,
        p.float("udelta", 0.0)?,
        p.float("vdelta", 0.0)?,
    ])
}

/// The rows of grinlight's `texture_uv` that read at `scale`·(s, t) for pbrt's (s, t) of the
/// map `[su, sv, du, dv]`, y counted down from the top: x = scale·s, and y = scale·(1 − t)
/// for an image (scale 1) or y = scale·t for a checkerboard (scale ½; the parity of ⌊t⌋,
/// not its direction, decides there).
fn rows([su, sv, du, dv]: [f64; 4], image: bool) -> Toml {
    let numbers = match image {
        true => [su, 0.0, du, 0.0, sv, 1.0 - sv - dv],
        false => [0.5 * su, 0.0, 0.5 * du, 0.0, -0.5 * sv, 0.5 * (sv + dv)],
    };
    Toml::Array(numbers.into_iter().map(Toml::Float).collect())
}

/// The texture `s` (`Texture "name" "spectrum" "class" …`) as a reflectance; `find` locates
/// its image as the scene locates its files.
pub(super) fn reflectance(
    s: &Statement,
    find: impl Fn(&str, &Place) -> Result<PathBuf>,
) -> Result<Converted> {
    let what = format!("Texture \"{}\"", cut(s.text(0)));
    let p = &s.params;
    if s.text(1) != "spectrum" {
        return Err(s.place.error(format!(
            "{what}: a \"{}\" texture as a reflectance (a \"spectrum\" texture is read)",
            cut(s.text(1))
        )));
    }
    let converted = match s.text(2) {
        "imagemap" => imagemap(s, &what, find)?,
        "checkerboard" => {
            if p.integer("dimension", 2)? != 2 {
                return Err(s
                    .place
                    .error(format!("{what}: a 3D checkerboard is not supported")));
            }
            let colour = |name: &str, default: f64| -> Result<DVec3> {
                let Some(param) = p.take(name) else {
                    return Ok(DVec3::splat(default));
                };
                match p.numbers(name, &["rgb"])?.map(|(v, _)| v).as_deref() {
                    Some([r, g, b]) if [r, g, b].iter().all(|c| (0.0..=1.0).contains(*c)) => {
                        Ok(DVec3::new(*r, *g, *b))
                    }
                    _ => Err(param.place.error(format!(
                        "{what}: {} — give an rgb of three numbers in [0, 1] (a reflectance)",
                        param.what()
                    ))),
                }
            };
            let colours = [colour("tex1", 1.0)?, colour("tex2", 0.0)?];
            let map = uv_mapping(p, &s.place, &what)?;
            Converted {
                keys: table([
                    (
                        "checkerboard",
                        Toml::Array(colours.into_iter().map(vec3).collect()),
                    ),
                    ("checkerboard_uv", rows(map, false)),
                ]),
                differs: format!(
                    "{what}: pbrt filters the checkerboard over each sample's footprint, \
                     grinlight reads it at the point (they differ at its edges)"
                ),
            }
        }
        other => {
            return Err(s.place.error(format!(
                "{what}: the texture \"{}\" is not supported (imagemap and checkerboard are)",
                cut(other)
            )))
        }
    };
    p.finish(&what)?;
    Ok(converted)
}

/// An `imagemap`: an 8-bit PNG or JPEG read as sRGB (pbrt's default `encoding` for a PNG;
/// a JPEG must say "sRGB"), `filter` point or bilinear, `wrap` repeat or clamp, `scale` as
/// the albedo it multiplies.
fn imagemap(
    s: &Statement,
    what: &str,
    find: impl Fn(&str, &Place) -> Result<PathBuf>,
) -> Result<Converted> {
    let p = &s.params;
    let name = p.string("filename")?.ok_or_else(|| {
        s.place
            .error(format!("{what}: \"string filename\" is missing"))
    })?;
    let path = find(&name, &s.place)?;
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let default_encoding = match extension.as_str() {
        "png" => "sRGB",
        _ => "linear",
    };
    match (
        extension.as_str(),
        p.string("encoding")?.as_deref().unwrap_or(default_encoding),
    ) {
        ("png" | "jpg" | "jpeg", "sRGB") => {}
        (_, encoding) => {
            return Err(s.place.error(format!(
                "{what}: \"{}\" with encoding \"{}\": grinlight reads 8-bit PNG and JPEG images \
                 as sRGB",
                cut(&name),
                cut(encoding)
            )))
        }
    }
    let filter = match p.string("filter")?.as_deref().unwrap_or("bilinear") {
        "point" => "nearest",
        "bilinear" | "trilinear" | "ewa" => "bilinear",
        other => {
            return Err(s.place.error(format!(
                "{what}: the filter \"{}\" is unknown to pbrt-v4",
                cut(other)
            )))
        }
    };
    p.ignore("maxanisotropy");
    let wrap = match p.string("wrap")?.as_deref().unwrap_or("repeat") {
        w @ ("repeat" | "clamp") => w.to_string(),
        other => {
            return Err(s.place.error(format!(
                "{what}: the wrap mode \"{}\" is not supported (repeat and clamp are)",
                cut(other)
            )))
        }
    };
    if p.boolean("invert", false)? {
        return Err(s.place.error(format!(
            "{what}: an inverted image (1 − its value) is not supported"
        )));
    }
    let scale = p.float("scale", 1.0)?;
    if !(0.0..=1.0).contains(&scale) {
        return Err(s.place.error(format!(
            "{what}: \"float scale\" {scale} — a reflectance's scale lies in [0, 1]"
        )));
    }
    let map = uv_mapping(p, &s.place, what)?;
    let file = std::fs::canonicalize(&path).unwrap_or(path);
    Ok(Converted {
        keys: table([
            ("texture", string(&file.to_string_lossy())),
            ("texture_filter", string(filter)),
            ("texture_wrap", Toml::String(wrap)),
            ("texture_uv", rows(map, true)),
            ("albedo", vec3(DVec3::splat(scale))),
        ]),
        differs: format!(
            "{what}: pbrt reads the image at a MIP level each sample's footprint chooses, \
             grinlight the full image, {filter} (the same where the image is magnified)"
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::UvMap;
    use glam::DVec2;

    fn uv_map(rows: &Toml) -> UvMap {
        let n: Vec<f64> = rows
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_float().unwrap())
            .collect();
        UvMap([[n[0], n[1], n[2]], [n[3], n[4], n[5]]])
    }

    /// grinlight's map of a converted texture reads where pbrt-v4 reads: an image at (s, 1 − t)
    /// from its top-left corner, and a checkerboard's colour by the parity of ⌊s⌋ + ⌊t⌋ (its
    /// first colour where even), for s = su·u + du, t = sv·v + dv (1e-12; 400 points, a map
    /// with negative and fractional scales and offsets).
    #[test]
    fn a_converted_map_reads_where_pbrt_reads() {
        let map = [2.5, -1.75, 0.3, 0.45];
        let (image, checker) = (uv_map(&rows(map, true)), uv_map(&rows(map, false)));
        let second_half = |x: f64| x - x.floor() > 0.5;
        for k in 0..400 {
            let uv = DVec2::new(
                (k as f64 * 0.618_034).fract(),
                (k as f64 * 0.414_214).fract(),
            );
            let (s, t) = (map[0] * uv.x + map[2], map[1] * uv.y + map[3]);
            let at = image.image_point(uv);
            assert!(
                (at - DVec2::new(s, 1.0 - t)).length() < 1e-12,
                "{at} against {s}, {}",
                1.0 - t
            );
            let c = checker.image_point(uv);
            let first = second_half(c.x) == second_half(c.y);
            let pbrt_first = (s.floor() + t.floor()).rem_euclid(2.0) == 0.0;
            assert_eq!(first, pbrt_first, "s {s}, t {t}");
        }
    }
}
