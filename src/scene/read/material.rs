//! `[[material]]`: surfaces, and what fills a dielectric. Every key's unit and default is in `docs/scene-format.md`.

use crate::bsdf::Metal;
use crate::bsdf::{Coat, Distribution, Microsurface, SMOOTH_ALPHA};
use crate::color::Rgb;
use crate::error::{cut, Result};
use crate::material::{ConductorIndex, FluorescentLayer, Material};
use crate::polarization::Sheet;
use crate::scene::media::{absorbing_form, read_fluorophore};
use crate::scene::table::TableReader;
use crate::spectrum::Dispersion;
use crate::texture::{Filter, Pattern, Texture, UvMap, Wrap};
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

/// An optional texture over the surface's (u, v), multiplying the albedo: an image at
/// `texture` or a `checkerboard` of two colours, placed by `texture_uv` (6 numbers, the rows
/// of [`UvMap`]; `checkerboard_uv` is the same key for a checkerboard).
fn texture(t: &mut TableReader) -> Result<Option<Arc<Texture>>> {
    let pattern = match (t.has("checkerboard"), t.has("texture")) {
        (true, true) => return Err(t.error("texture", "give either `texture` or `checkerboard`")),
        (false, false) => return Ok(None),
        (true, false) => {
            let colours = t.vec3_list("checkerboard")?;
            t.check(
                "checkerboard",
                colours.len() == 2
                    && colours
                        .iter()
                        .all(|c| c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1.0),
                "expected two colours [[r, g, b], [r, g, b]], each in [0, 1]",
            )?;
            Pattern::Checkerboard {
                colours: [Rgb(colours[0]), Rgb(colours[1])],
            }
        }
        (false, true) => {
            let path = t.input_file("texture")?;
            let filter = t.choice(
                "texture_filter",
                &[("bilinear", Filter::Bilinear), ("nearest", Filter::Nearest)],
            )?;
            let wrap = t.choice(
                "texture_wrap",
                &[
                    ("repeat", Wrap::Repeat),
                    ("clamp", Wrap::Clamp),
                    ("mirror", Wrap::Mirror),
                ],
            )?;
            Texture::load(&path, filter, wrap)
                .map_err(|e| t.error("texture", e))?
                .pattern
        }
    };
    let key = match t.has("checkerboard_uv") {
        true => "checkerboard_uv",
        false => "texture_uv",
    };
    t.check(
        "texture_uv",
        !(t.has("checkerboard_uv") && t.has("texture_uv")),
        "give either `texture_uv` or `checkerboard_uv` (the same map)",
    )?;
    let to_uv = match t.f64_list_opt(key)? {
        None => UvMap::default(),
        Some(m) => {
            t.check(
                key,
                m.len() == 6 && m.iter().all(|x| x.is_finite()),
                format!("expected 6 numbers (2 rows [a, b, c]), each finite, got {m:?}"),
            )?;
            UvMap([[m[0], m[1], m[2]], [m[3], m[4], m[5]]])
        }
    };
    Ok(Some(Arc::new(Texture { pattern, to_uv })))
}

/// The microfacet α at `roughness` (`default` if absent), a number in [0, 1].
fn roughness(t: &mut TableReader, default: f64) -> Result<f64> {
    let alpha = t.f64_or("roughness", default)?;
    t.check(
        "roughness",
        (0.0..=1.0).contains(&alpha),
        format!("must be a microfacet α in [0, 1], got {alpha:?}"),
    )?;
    Ok(alpha)
}

/// The microfacet `distribution`: `"ggx"` (the default) or `"beckmann"`.
fn distribution(t: &mut TableReader) -> Result<Distribution> {
    let Some(name) = t.string_opt("distribution")? else {
        return Ok(Distribution::Ggx);
    };
    Distribution::named(&name).ok_or_else(|| {
        let names: Vec<&str> = Distribution::ALL.iter().map(|d| d.name()).collect();
        t.error(
            "distribution",
            format!(
                "unknown distribution '{}' (expected {})",
                cut(&name),
                names.join(" or ")
            ),
        )
    })
}

/// The microsurface of `roughness` (smooth if absent) and `distribution`: None, a smooth
/// surface, where α is below [`crate::bsdf::SMOOTH_ALPHA`] — the one place rough and smooth
/// are told apart.
fn microsurface(t: &mut TableReader) -> Result<Option<Microsurface>> {
    let alpha = roughness(t, 0.0)?;
    let distribution = distribution(t)?;
    Ok(Microsurface::rough(distribution, [alpha, alpha]))
}

/// A conductor's index: `metal` (a measured metal's symbol, or "perfect"), or `eta` and `k`
/// (each a number or RGB; or, if either is, forms over wavelength, as indices are given).
fn conductor_index(t: &mut TableReader) -> Result<ConductorIndex> {
    match (t.has("metal"), t.has("eta"), t.has("k")) {
        (true, false, false) => {
            let name = t.string("metal")?;
            if name == "perfect" {
                return Ok(ConductorIndex::Constant(Rgb::ONE));
            }
            match crate::bsdf::metal(&name) {
                Some(m) => Ok(ConductorIndex::Measured(Arc::new(m.clone()))),
                None => {
                    let known: Vec<&str> = crate::bsdf::METALS.iter().map(|m| m.symbol).collect();
                    Err(t.error(
                        "metal",
                        format!("unknown metal '{name}' ({}, perfect)", known.join(", ")),
                    ))
                }
            }
        }
        (false, true, true) if t.is_over_wavelength("eta") || t.is_over_wavelength("k") => {
            let eta = t.dispersion("eta")?;
            let k = t.over_wavelength("k")?;
            let least = k.min_visible();
            t.check(
                "k",
                least >= 0.0,
                format!("k must be ≥ 0 from 360 to 830 nm, got {least:?} there"),
            )?;
            let metal = Metal::sampled("eta/k", |nm| eta.at(nm), |nm| k.at(nm));
            Ok(ConductorIndex::Measured(Arc::new(metal)))
        }
        (false, true, true) => {
            let eta = t.rgb_or("eta", None)?;
            let k = t.rgb_or("k", None)?;
            t.check(
                "eta",
                eta.min_element() > 0.0,
                format!("η must be > 0, got {eta}"),
            )?;
            t.check(
                "k",
                k.min_element() >= 0.0,
                format!("k must be ≥ 0, got {k}"),
            )?;
            Ok(ConductorIndex::Rgb { eta, k })
        }
        (false, true, false) => Err(t.error("eta", "`eta` needs `k` (the extinction coefficient)")),
        (false, false, true) => Err(t.error("k", "`k` needs `eta` (the real part of the index)")),
        (true, ..) => Err(t.error("metal", "give `metal` or `eta` and `k`, not both")),
        (false, false, false) => Err(t.error(
            "metal",
            "a conductor needs `metal` (Ag, Al, Au, Cu or perfect) or `eta` and `k`",
        )),
    }
}

/// A diffuse material's `fluorescence = { excitation = a(λ), emission = spectrum,
/// quantum_yield = q }` ([`FluorescentLayer`]): a(λ) the share of the light the layer absorbs,
/// in [0, 1] (a number or a form over wavelength), somewhere above 0.
fn fluorescent_layer(t: &mut TableReader) -> Result<Option<FluorescentLayer>> {
    let Some(mut f) = t.nested("fluorescence")? else {
        return Ok(None);
    };
    let excitation = absorbing_form(
        &mut f,
        "excitation",
        1.0,
        "the share of light the layer absorbs, in [0, 1],",
    )?;
    let fluorophore = read_fluorophore(&mut f)?;
    f.finish()?;
    match FluorescentLayer::new(excitation, fluorophore) {
        Some(layer) => Ok(Some(layer)),
        None => Err(t.error(
            "fluorescence",
            "the layer absorbs nothing from 360 to 830 nm",
        )),
    }
}

/// A material and, for a dielectric, what fills it.
pub fn read_material(t: &mut TableReader) -> Result<(Material, Option<Interior>)> {
    let kind = t.string("type")?;
    Ok(match kind.as_str() {
        "diffuse" => {
            let texture = texture(t)?;
            let albedo = unit_color(t, "albedo", texture.as_ref().map(|_| Rgb::ONE))?;
            let fluorescence = fluorescent_layer(t)?.map(Arc::new);
            (
                Material::Diffuse {
                    albedo,
                    texture,
                    fluorescence,
                },
                None,
            )
        }
        "mirror" => (
            Material::Conductor {
                index: ConductorIndex::Constant(unit_color(t, "reflectance", Some(Rgb::ONE))?),
                microsurface: None,
            },
            None,
        ),
        "conductor" => (
            Material::Conductor {
                index: conductor_index(t)?,
                microsurface: microsurface(t)?,
            },
            None,
        ),
        "plastic" => {
            let texture = texture(t)?;
            let albedo = unit_color(t, "albedo", texture.as_ref().map(|_| Rgb::ONE))?;
            let ior = t.f64_or("ior", 1.5)?;
            t.check(
                "ior",
                ior > 1.0 && ior <= 4.0,
                format!(
                    "the coat's index relative to its surroundings must be in (1, 4], got {ior:?}"
                ),
            )?;
            let alpha = roughness(t, 0.1)?;
            let distribution = distribution(t)?;
            let Some(microsurface) = Microsurface::rough(distribution, [alpha, alpha]) else {
                return Err(t.error(
                    "roughness",
                    format!(
                        "a plastic's coat is rough: roughness must be at least {SMOOTH_ALPHA}, got {alpha:?}"
                    ),
                ));
            };
            let coat = Arc::new(Coat::new(ior, microsurface));
            (
                Material::Plastic {
                    albedo,
                    texture,
                    coat,
                },
                None,
            )
        }
        // A surface that emits is a light, sampled and a photon source; an emissive material
        // on a shape would be seen but light nothing: refused rather than rendered wrong.
        "emissive" => {
            return Err(t.error(
                "type",
                "an emissive material would light nothing; make the surface a [[light]] \
                 (quad or disk, with `radiance`)",
            ))
        }
        "thin_dielectric" => {
            let ior = t.f64("ior")?;
            t.check(
                "ior",
                ior > 0.0 && ior <= 10.0,
                format!("a pane's index must be in (0, 10], got {ior:?}"),
            )?;
            (Material::ThinDielectric { ior }, None)
        }
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
            let microsurface = microsurface(t)?;
            (Material::Dielectric { microsurface }, Some(interior))
        }
        "polarizer" => (
            Material::Sheet(Sheet::Polarizer {
                axis: t.direction("axis")?,
            }),
            None,
        ),
        "retarder" => {
            let fast_axis = t.direction("fast_axis")?;
            let Some(retardance) = t.turn_opt("retardance_deg")? else {
                return Err(t.error("retardance_deg", "a retarder needs `retardance_deg`"));
            };
            (
                Material::Sheet(Sheet::Retarder {
                    fast_axis,
                    retardance,
                }),
                None,
            )
        }
        other => {
            return Err(t.error(
                "type",
                format!(
                    "unknown material type '{other}' (diffuse, mirror, conductor, dielectric, \
                     thin_dielectric, plastic, polarizer, retarder, emissive)"
                ),
            ))
        }
    })
}
