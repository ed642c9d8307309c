//! `[[light]]`: lights, their spectra, and the environment. Every key's unit and default is in `docs/scene-format.md`.

use super::shape::{parallelogram, read_mesh};
use crate::color::Rgb;
use crate::environment::{Environment, ImageFilter, Sky, Turn};
use crate::equal_area::Grid;
use crate::error::Result;
use crate::lights::{Emitter, Falloff, Light, Luminaire};
use crate::math::Ball;
use crate::photometry::image::IntensityImage;
use crate::photometry::IntensityMap;
use crate::scene::table::TableReader;
use crate::shapes::{Disk, Quad, SampledMesh};
use crate::spectrum::Spectrum;
use glam::{DMat3, DVec3};
use std::sync::Arc;

/// A light's optional `spectrum` (None: not given — the light is D65 in bands and its RGB in
/// images): the shape of its emission over wavelength, `"D65"`, `"E"` (equal energy),
/// `{ blackbody = kelvin }` or `{ gaussian = [peak_nm, fwhm_nm] }` (an LED).
pub fn read_spectrum(t: &mut TableReader) -> Result<Option<Spectrum>> {
    t.spectrum_opt("spectrum")
}

/// A light and the spectrum it emits. With a `spectrum`, its power key (one number, or equal
/// RGB: the power in W, intensity, radiance or irradiance as the light's type says) scales the
/// spectrum, and the light appears in images in the spectrum's colour, ∫ Φ r̄ dλ
/// ([`Spectrum::colour`]; channels outside sRGB's gamut clipped to zero). Without one, its RGB
/// is its colour and it emits D65 in receiver bands.
pub fn read_light_and_spectrum(
    t: &mut TableReader,
    kind: &str,
) -> Result<(Light, Option<Spectrum>)> {
    let mut light = read_light(t, kind)?;
    let Some(spectrum) = read_spectrum(t)? else {
        return Ok((light, None));
    };
    let value = light.colour_mut();
    t.check(
        "spectrum",
        value.x == value.y && value.y == value.z,
        "a light with a spectrum gives its power as one number (or equal RGB); the spectrum gives its colour",
    )?;
    let colour = spectrum.colour().0.max(DVec3::ZERO);
    t.check(
        "spectrum",
        colour.max_element() > 0.0,
        "the spectrum is invisible: no sRGB colour between 380 and 780 nm",
    )?;
    *value = Rgb(value.0 * colour);
    Ok((light, Some(spectrum)))
}

/// A light of type `kind` (not `environment`).
pub fn read_light(t: &mut TableReader, kind: &str) -> Result<Light> {
    let area = |t: &mut TableReader, emitter: Emitter| -> Result<Light> {
        let radiance = t.rgb_or("radiance", None)?;
        Ok(Light::Area { emitter, radiance })
    };
    Ok(match kind {
        "point" => Light::Point { position: t.vec3("position")?, intensity: t.rgb_or("intensity", None)? },
        "spot" => {
            let position = t.vec3("position")?;
            let direction = t.direction_or("direction", -DVec3::Y)?;
            let intensity = t.rgb_or("intensity", None)?;
            let cone = t.f64("cone_deg")?;
            t.check("cone_deg", cone > 0.0 && cone <= 180.0, "must be in (0°, 180°]")?;
            let falloff = t.f64_or("falloff_deg", cone)?;
            t.check("falloff_deg", (0.0..=cone).contains(&falloff), "must be in [0°, cone_deg]")?;
            let curve = t.choice(
                "falloff_curve",
                &[("smoothstep", Falloff::SmoothStep), ("linear", Falloff::LinearInAngle)],
            )?;
            Light::Spot {
                position,
                direction,
                intensity,
                cos_inner: falloff.to_radians().cos(),
                cos_outer: cone.to_radians().cos(),
                falloff: curve,
            }
        }
        "quad" => {
            let (origin, e1, e2) = parallelogram(t, "vertices")?;
            area(t, Emitter::Quad(Quad { origin, e1, e2 }))?
        }
        "disk" => {
            let emitter = Emitter::Disk(Disk::full(
                t.vec3("center")?,
                t.direction_or("normal", -DVec3::Y)?,
                t.positive("radius")?,
            ));
            area(t, emitter)?
        }
        "sphere" => {
            let emitter = Emitter::Sphere(Ball {
                center: t.vec3("center")?,
                radius: t.positive("radius")?,
            });
            area(t, emitter)?
        }
        "mesh" => {
            let mesh = read_mesh(t)?;
            // `flip`: each triangle emits from the side of (c − a) × (b − a) instead.
            let mesh = match t.bool_or("flip", false)? {
                true => mesh.turned_over(),
                false => mesh,
            };
            let key = match t.has("points") {
                true => "points",
                false => "file",
            };
            let surface = SampledMesh::new(Arc::new(mesh))
                .ok_or_else(|| t.error(key, "the mesh's area is not a finite number"))?;
            area(t, Emitter::Mesh(Arc::new(surface)))?
        }
        "led" => {
            let disk = Disk::full(
                t.vec3("center")?,
                t.direction_or("normal", DVec3::Z)?,
                t.positive("radius")?,
            );
            let power = t.positive("power")?;
            let m = t.f64_or("m", 1.0)?;
            t.check("m", m >= 0.0, "must be ≥ 0")?;
            let color = t.rgb_or("color", Some(Rgb::ONE))?;
            let peak_intensity = color * (power * (m + 1.0) / std::f64::consts::TAU);
            Light::Led { disk, peak_intensity, m }
        }
        "goniometric" => {
            let path = t.input_file("file")?;
            let map = read_intensity_map(&path).map_err(|e| t.error("file", e))?;
            t.check(
                "file",
                map.power() > 0.0 && map.power().is_finite(),
                format!("the luminaire must send a finite power > 0, got {}", map.power()),
            )?;
            let nadir = t.direction_or("direction", -DVec3::Y)?;
            let fallback = match nadir.cross(DVec3::X).length() > 1e-6 {
                true => DVec3::X,
                false => DVec3::Z,
            };
            let c0 = t.direction_or("c0", fallback)?;
            t.check(
                "c0",
                nadir.cross(c0).length() > 1e-9,
                "must not be parallel to `direction` (the luminaire's nadir)",
            )?;
            let map = match map {
                IntensityMap::Image(image) => IntensityMap::Image(image.with_flip_v(t.bool_or("flip_v", false)?)),
                IntensityMap::Table(table) => {
                    t.check("flip_v", !t.has("flip_v"), "is an intensity image's: this file is a table")?;
                    IntensityMap::Table(table)
                }
            };
            let scale = match (t.has("power"), t.has("scale")) {
                (true, true) => return Err(t.error("scale", "give `power` or `scale`, not both")),
                (true, false) => t.positive("power")? / map.power(),
                (false, _) => t.positive_or("scale", 1.0)?,
            };
            Light::Goniometric {
                position: t.vec3("position")?,
                aim: Luminaire::new(nadir, c0),
                colour: t.rgb_or("color", Some(Rgb::ONE))? * scale,
                map: std::sync::Arc::new(map),
            }
        }
        "directional" => Light::Directional { direction: t.direction_or("direction", -DVec3::Y)?, irradiance: t.rgb_or("irradiance", None)? },
        other => return Err(t.error("type", format!("unknown light type '{other}' (point, spot, quad, disk, sphere, mesh, led, goniometric, directional, environment)"))),
    })
}

/// A luminaire's intensity from its file, by the file's extension: an equal-area image
/// (`.exr`, `.hdr`; `.png` and `.jpg` are read to be refused by name), a EULUMDAT table
/// (`.ldt`) or an IES table (any other). The message of a file that does not read names it.
fn read_intensity_map(path: &std::path::Path) -> std::result::Result<IntensityMap, String> {
    use crate::photometry::{eulumdat, ies};
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let named = |e: String| format!("{}: {e}", path.display());
    if let "exr" | "hdr" | "png" | "jpg" | "jpeg" = extension.as_str() {
        let image = crate::texture::open_image(path)?;
        return Ok(IntensityMap::Image(
            IntensityImage::from_image(&image).map_err(named)?,
        ));
    }
    let text =
        crate::input::read_text(path, 64 << 20, "photometric file").map_err(|e| e.to_string())?;
    let table = match extension.as_str() {
        "ldt" => eulumdat::parse(&text),
        _ => ies::parse(&text),
    };
    Ok(IntensityMap::Table(table.map_err(named)?))
}

/// A `[[light]]` of type `environment`; image files are relative to `dir`.
pub fn read_environment(t: &mut TableReader) -> Result<Environment> {
    let sky = match (t.has("file"), t.string_opt("sky")?) {
        (true, None) => {
            let path = t.input_file("file")?;
            let decoded = crate::texture::open_image(&path).map_err(|e| t.error("file", e))?;
            let img = decoded.to_rgb32f();
            let bad = img
                .pixels()
                .filter(|p| !p.0.iter().all(|c| c.is_finite() && *c >= 0.0));
            if let Some(first) = img
                .enumerate_pixels()
                .find(|(_, _, p)| !p.0.iter().all(|c| c.is_finite() && *c >= 0.0))
            {
                return Err(t.error(
                    "file",
                    format!(
                        "{}: {} pixel(s) are not finite non-negative radiances, the first at \
                         (x {}, y {}): {:?} (fix or clamp them in the image)",
                        path.display(),
                        bad.count(),
                        first.0,
                        first.1,
                        first.2 .0
                    ),
                ));
            }
            match t.choice("projection", &[("latlong", false), ("equal_area", true)])? {
                false => {
                    t.check(
                        "flip_v",
                        !t.has("flip_v"),
                        "is an equal-area map's: give projection = \"equal_area\"",
                    )?;
                    let filter = t.choice(
                        "filter",
                        &[
                            ("nearest", ImageFilter::Nearest),
                            ("bilinear", ImageFilter::Bilinear),
                        ],
                    )?;
                    Sky::Image {
                        width: img.width() as usize,
                        height: img.height() as usize,
                        pixels: img.pixels().map(|p| p.0).collect(),
                        filter,
                    }
                }
                true => {
                    t.check(
                        "filter",
                        !t.has("filter"),
                        "an equal-area map is read by nearest pixel: leave `filter` out",
                    )?;
                    let (size, pixels) = crate::equal_area::square_pixels(&decoded)
                        .map_err(|e| t.error("file", format!("{}: {e}", path.display())))?;
                    Sky::EqualArea {
                        grid: Grid {
                            size,
                            flip_v: t.bool_or("flip_v", false)?,
                        },
                        pixels,
                    }
                }
            }
        }
        (false, Some(sky)) => match sky.as_str() {
            "starfield" => Sky::Starfield {
                seed: t.natural_or("seed", 1)?,
            },
            "checker" => Sky::Checker {
                squares: t.count_or("squares", 24)?.min(1 << 20) as u32,
            },
            "uniform" => Sky::Uniform {
                radiance: t.rgb_or("radiance", Some(crate::color::Rgb::ONE))?,
            },
            other => {
                return Err(t.error(
                    "sky",
                    format!("unknown sky '{other}' (starfield, checker, uniform)"),
                ))
            }
        },
        _ => {
            return Err(t.error(
                "file",
                "give exactly one of `file` (a lat-long EXR or HDR) and `sky`",
            ))
        }
    };
    let scale = t.f64_or("scale", 1.0)?;
    t.check("scale", scale >= 0.0, "must be ≥ 0")?;
    let turn = match t.f64_list_opt("matrix")? {
        Some(m) => {
            t.check(
                "rotation_deg",
                !t.has("rotation_deg"),
                "give either `matrix` or `rotation_deg`",
            )?;
            t.check(
                "matrix",
                m.len() == 9,
                format!("expected the 9 numbers of 3 rows, got {}", m.len()),
            )?;
            let turn = DMat3::from_cols_slice(&m).transpose();
            let orthonormal = (turn.transpose() * turn - DMat3::IDENTITY)
                .to_cols_array()
                .iter()
                .all(|x| x.abs() < 1e-9);
            t.check(
                "matrix",
                orthonormal && turn.determinant() > 0.0,
                "must be a rotation (orthonormal rows, determinant 1)",
            )?;
            Turn::Rotation(turn)
        }
        None => Turn::AboutY(t.f64_or("rotation_deg", 0.0)?.to_radians()),
    };
    Ok(Environment { sky, turn, scale })
}
