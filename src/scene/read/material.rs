//! `[[material]]`: surfaces, and what fills a dielectric. Every key's unit and default is in `docs/scene-format.md`.

use crate::color::Rgb;
use crate::error::Result;
use crate::material::Material;
use crate::scene::table::TableReader;
use crate::spectrum::Dispersion;
use crate::texture::Texture;
use std::sync::Arc;

/// What fills a dielectric: a named medium or a uniform index.
#[derive(Clone, Debug)]
pub enum Interior {
    /// A `[[medium]]` by name.
    Medium(String),
    /// A uniform index, perhaps dispersive.
    Ior(Dispersion),
}

fn unit_color(t: &mut TableReader, key: &str, default: Option<Rgb>) -> Result<Rgb> {
    let c = t.rgb_or(key, default)?;
    t.check(
        key,
        c.max_element() <= 1.0,
        format!("a reflectance must be ≤ 1, got {c}"),
    )?;
    Ok(c)
}

/// A material and, for a dielectric, what fills it.
pub fn read_material(t: &mut TableReader) -> Result<(Material, Option<Interior>)> {
    let kind = t.string("type")?;
    Ok(match kind.as_str() {
        "diffuse" => {
            // An image over the surface's (u, v), multiplied by `albedo` (then 1 by default).
            let texture = match t.has("texture") {
                true => {
                    let path = t.input_file("texture")?;
                    let texture = Texture::load(&path).map_err(|e| t.error("texture", e))?;
                    Some(Arc::new(texture))
                }
                false => None,
            };
            let albedo = unit_color(t, "albedo", texture.as_ref().map(|_| Rgb::ONE))?;
            (Material::Diffuse { albedo, texture }, None)
        }
        "mirror" => (
            Material::Mirror {
                reflectance: unit_color(t, "reflectance", Some(Rgb::ONE))?,
            },
            None,
        ),
        "emissive" => (
            Material::Emissive {
                radiance: t.rgb_or("radiance", None)?,
            },
            None,
        ),
        "dielectric" => {
            let interior = match (t.has("ior"), t.has("interior")) {
                (true, false) => Interior::Ior(t.dispersion("ior")?),
                (false, true) => Interior::Medium(t.string("interior")?),
                _ => {
                    return Err(t.error(
                        "ior",
                        "give exactly one of `ior` and `interior` (a medium name)",
                    ))
                }
            };
            (Material::Dielectric, Some(interior))
        }
        other => {
            return Err(t.error(
                "type",
                format!("unknown material type '{other}' (diffuse, mirror, dielectric, emissive)"),
            ))
        }
    })
}
