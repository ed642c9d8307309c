//! `[camera]`, `[render]`, `[output]`, `[[material]]`, `[[shape]]` and `[[light]]` tables.
//! Every key's unit and default is listed in `docs/scene-format.md`.

use super::table::{TableReader, MAX_MAGNITUDE};
use crate::camera::Camera;
use crate::color::Rgb;
use crate::curve::{StepControl, StepperKind};
use crate::environment::{Environment, Sky};
use crate::error::Result;
use crate::lights::{Emitter, Light};
use crate::material::Material;
use crate::receiver::Receiver;
use crate::settings::{OutputSettings, PhotonSettings, Settings, TraceSettings};
use crate::shapes::{Primitive, TriangleMesh};
use crate::spectrum::emission::Shape;
use crate::spectrum::{Dispersion, Spectrum, LAMBDA_MAX, LAMBDA_MIN};
use crate::texture::Texture;
use glam::{DMat3, DVec3};
use std::sync::Arc;

/// What fills a dielectric: a named medium or a uniform index.
#[derive(Clone, Debug)]
pub enum Interior {
    /// A `[[medium]]` by name.
    Medium(String),
    /// A uniform index, perhaps dispersive.
    Ior(Dispersion),
}

/// A shape before names are resolved.
pub struct ShapeDesc {
    /// Its primitives.
    pub primitives: Vec<Primitive>,
    /// Material name.
    pub material: String,
    /// Interior override.
    pub interior: Option<String>,
}

/// `[camera]`.
pub fn read_camera(t: &mut TableReader) -> Result<Camera> {
    let position = t.vec3("position")?;
    let look_at = t.vec3("look_at")?;
    let up = t.vec3_or("up", DVec3::Y)?;
    let width = t.count_or("width", 640)?;
    let height = t.count_or("height", 480)?;
    t.check("width", width <= 65_536, "must be at most 65536")?;
    t.check("height", height <= 65_536, "must be at most 65536")?;
    let (width, height) = (width as u32, height as u32);
    let fov_y = match (t.has("fov_y_deg"), t.has("fov_x_deg")) {
        (true, false) => t.f64("fov_y_deg")?,
        (false, true) => Camera::fov_y_from_x(t.f64("fov_x_deg")?, width, height),
        _ => {
            return Err(t.error(
                "fov_y_deg",
                "give exactly one of `fov_y_deg` and `fov_x_deg`",
            ))
        }
    };
    let key = if t.has("fov_y_deg") {
        "fov_y_deg"
    } else {
        "fov_x_deg"
    };
    t.check(
        key,
        fov_y > 0.0 && fov_y < 179.0,
        "the field of view must be in (0°, 179°)",
    )?;
    let mut camera = Camera::new(position, look_at, up, fov_y, width, height)
        .map_err(|e| t.error("look_at", e))?;
    let aperture = t.f64_or("aperture_radius", 0.0)?;
    t.check("aperture_radius", aperture >= 0.0, "must be ≥ 0")?;
    if aperture > 0.0 {
        let focus = t.positive("focus_distance")?;
        camera.lens = Some((aperture, focus));
    }
    Ok(camera)
}

/// `[render]`: every setting but the output's.
pub fn read_render(t: &mut TableReader) -> Result<Settings> {
    let stepper: StepperKind = t
        .string_opt("stepper")?
        .map_or(Ok(StepperKind::DEFAULT), |s| {
            s.parse().map_err(|e: String| t.error("stepper", e))
        })?;
    let control = match t.string_opt("control")?.as_deref().unwrap_or("adaptive") {
        "adaptive" => {
            let tolerance = t.f64_or("tolerance", stepper.default_tolerance())?;
            t.check("tolerance", tolerance > 0.0, "must be > 0")?;
            StepControl::Adaptive { tolerance }
        }
        "fixed" => StepControl::Fixed {
            step: t.positive("step")?,
        },
        "tessendorf" => {
            let (t_max, t_min) = (t.f64_or("t_max", 1e-2)?, t.f64_or("t_min", 1e-4)?);
            t.check(
                "t_max",
                t_min >= 0.0 && t_max > t_min,
                "need 0 ≤ t_min < t_max",
            )?;
            StepControl::Tessendorf {
                initial_step: t.positive("step")?,
                t_max,
                t_min,
                seed: 1,
            }
        }
        other => {
            return Err(t.error(
                "control",
                format!("unknown control '{other}' (adaptive, fixed, tessendorf)"),
            ))
        }
    };
    let world_radius = optional_positive(t, "world_radius")?;
    let radius = optional_positive(t, "radius")?;
    let time_budget = optional_positive(t, "time_budget")?;
    let d = Settings::default();
    let integrator = t.string_opt("integrator")?.map_or(Ok(d.integrator), |s| {
        s.parse().map_err(|e: String| t.error("integrator", e))
    })?;
    Ok(Settings {
        integrator,
        deflection_table: t.bool_or("deflection_table", d.deflection_table)?,
        spp: t.count_or("spp", d.spp as u64)?.min(u32::MAX as u64) as u32,
        seed: t.natural_or("seed", d.seed)?,
        threads: t.natural_or("threads", 0)? as usize,
        trace: TraceSettings {
            max_depth: t
                .count_or("max_depth", d.trace.max_depth as u64)?
                .min(u32::MAX as u64) as u32,
            stepper,
            control,
            max_steps: t.count_or("max_steps", d.trace.max_steps)?,
            world_radius,
        },
        photons: PhotonSettings {
            global: t.natural_or("photons", d.photons.global)?,
            caustic: t.natural_or("caustic_photons", d.photons.caustic)?,
            gather: t
                .natural_or("gather", d.photons.gather as u64)?
                .min(1 << 16) as u32,
            radius,
            knn: t.count_or("knn", d.photons.knn as u64)?.min(1 << 16) as u32,
        },
        passes: t.count_or("passes", d.passes as u64)?.min(u32::MAX as u64) as u32,
        time_budget,
        receiver_photons: t.count_or("receiver_photons", d.receiver_photons)?,
        output: d.output,
    })
}

/// A key that is either absent or a finite number > 0.
fn optional_positive(t: &mut TableReader, key: &str) -> Result<Option<f64>> {
    if t.has(key) {
        Ok(Some(t.positive(key)?))
    } else {
        Ok(None)
    }
}

/// `[output]`; relative paths are relative to the scene file's directory `dir`.
pub fn read_output(t: &mut TableReader) -> Result<OutputSettings> {
    let exposure = t.f64_or("exposure", 1.0)?;
    t.check("exposure", exposure > 0.0, "must be > 0")?;
    let path = t.output_file("path")?;
    t.check(
        "path",
        path.as_ref().is_none_or(|p| crate::output::is_exr(p)),
        "must name an EXR file (…/name.exr): the PNG preview and receiver files are written beside it",
    )?;
    Ok(OutputSettings {
        path,
        png: t.bool_or("png", true)?,
        exposure: exposure as f32,
    })
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

/// The parallelogram of four vertices v0..v3 (refs convention: triangles (v0,v1,v2), (v0,v2,v3)).
fn parallelogram(t: &mut TableReader, key: &str) -> Result<(DVec3, DVec3, DVec3)> {
    let v = t.vec3_list(key)?;
    t.check(
        key,
        v.len() == 4,
        format!("expected 4 vertices, got {}", v.len()),
    )?;
    let (e1, e2) = (v[1] - v[0], v[3] - v[0]);
    let scale = e1.length().max(e2.length());
    t.check(
        key,
        (v[0] + e1 + e2 - v[2]).length() <= 1e-9 * scale.max(1e-300),
        "the 4 vertices are not a parallelogram (v2 must be v1 + v3 − v0)",
    )?;
    t.check(key, e1.cross(e2).length() > 0.0, "the quad has zero area")?;
    Ok((v[0], e1, e2))
}

/// `[[shape]]`; mesh files are relative to `dir`.
pub fn read_shape(t: &mut TableReader) -> Result<ShapeDesc> {
    let kind = t.string("type")?;
    let primitives = match kind.as_str() {
        "sphere" => vec![Primitive::Sphere {
            center: t.vec3("center")?,
            radius: t.positive("radius")?,
        }],
        "cylinder" => {
            let base = t.vec3("base")?;
            let axis = t.direction_or("axis", DVec3::Z)?;
            let radius = t.positive("radius")?;
            let height = t.positive("height")?;
            let mut p = vec![Primitive::Tube {
                base,
                axis,
                radius,
                height,
            }];
            if t.bool_or("capped", true)? {
                p.push(Primitive::Disk {
                    center: base,
                    normal: -axis,
                    radius,
                    inner: 0.0,
                });
                p.push(Primitive::Disk {
                    center: base + axis * height,
                    normal: axis,
                    radius,
                    inner: 0.0,
                });
            }
            p
        }
        "box" => {
            let (lo, hi) = (t.vec3("min")?, t.vec3("max")?);
            t.check(
                "max",
                lo.cmplt(hi).all(),
                "every component of `max` must exceed `min`",
            )?;
            box_faces(lo, hi)
        }
        "quad" => {
            let (origin, e1, e2) = parallelogram(t, "vertices")?;
            vec![Primitive::Quad { origin, e1, e2 }]
        }
        "disk" => {
            let center = t.vec3("center")?;
            let normal = t.direction_or("normal", DVec3::Y)?;
            let radius = t.positive("radius")?;
            let inner = t.f64_or("inner_radius", 0.0)?;
            t.check(
                "inner_radius",
                (0.0..radius).contains(&inner),
                "must be in [0, radius)",
            )?;
            vec![Primitive::Disk {
                center,
                normal,
                radius,
                inner,
            }]
        }
        "mesh" => read_mesh(t)?,
        other => {
            return Err(t.error(
                "type",
                format!("unknown shape type '{other}' (sphere, cylinder, box, quad, disk, mesh)"),
            ))
        }
    };
    Ok(ShapeDesc {
        primitives,
        material: t.string("material")?,
        interior: t.string_opt("interior")?,
    })
}

/// The six outward-facing quads of an axis-aligned box.
fn box_faces(lo: DVec3, hi: DVec3) -> Vec<Primitive> {
    let d = hi - lo;
    let (x, y, z) = (DVec3::X * d.x, DVec3::Y * d.y, DVec3::Z * d.z);
    vec![
        Primitive::Quad {
            origin: lo,
            e1: y,
            e2: x,
        }, // −z
        Primitive::Quad {
            origin: lo + z,
            e1: x,
            e2: y,
        }, // +z
        Primitive::Quad {
            origin: lo,
            e1: z,
            e2: y,
        }, // −x
        Primitive::Quad {
            origin: lo + x,
            e1: y,
            e2: z,
        }, // +x
        Primitive::Quad {
            origin: lo,
            e1: x,
            e2: z,
        }, // −y
        Primitive::Quad {
            origin: lo + y,
            e1: z,
            e2: x,
        }, // +y
    ]
}

fn read_mesh(t: &mut TableReader) -> Result<Vec<Primitive>> {
    let path = t.input_file("file")?;
    let translate = t.vec3_or("translate", DVec3::ZERO)?;
    let scale = t.f64_or("scale", 1.0)?;
    t.check("scale", scale != 0.0, "must not be 0")?;
    let rot = t.vec3_or("rotate_deg", DVec3::ZERO)?;
    let m = DMat3::from_rotation_z(rot.z.to_radians())
        * DMat3::from_rotation_y(rot.y.to_radians())
        * DMat3::from_rotation_x(rot.x.to_radians());
    let obj = super::mesh::load_triangles(&path).map_err(|e| t.error("file", e))?;
    let smooth = t.bool_or("smooth", obj.normals.is_some())?;
    // Placed in f64, stored in f32: the stored vertices are the geometry.
    let mut vertices = obj.positions;
    for (i, v) in vertices.iter_mut().enumerate() {
        let given = DVec3::from(v.map(f64::from));
        t.check(
            "file",
            given.abs().max_element() <= MAX_MAGNITUDE,
            format!(
                "{}: vertex {} lies at {:?}, beyond ±{MAX_MAGNITUDE:e}",
                path.display(),
                i + 1,
                v
            ),
        )?;
        let p = translate + m * (scale * given);
        t.check(
            "scale",
            p.abs().max_element() <= MAX_MAGNITUDE,
            format!(
                "{}: scaled and moved, a vertex lies beyond ±{MAX_MAGNITUDE:e}",
                path.display()
            ),
        )?;
        *v = p.as_vec3().to_array();
    }
    let faces = obj.triangles.len();
    let at = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
    let mut triangles = obj.triangles;
    triangles.retain(|&[a, b, c]| (at(b) - at(a)).cross(at(c) - at(a)).length_squared() > 0.0);
    if triangles.is_empty() {
        // A file with an unusable line says so rather than "zero area" (read again: only here).
        let problem = std::fs::read(&path)
            .ok()
            .and_then(|b| super::mesh::diagnose(&b));
        return Err(match problem {
            Some(p) => t.error("file", format!("{}: {p}", path.display())),
            None => t.error(
                "scale",
                format!(
                    "{}: all {faces} triangles have zero area at this scale",
                    path.display()
                ),
            ),
        });
    }
    let duplicates = super::mesh::drop_duplicate_triangles(&vertices, &mut triangles);
    if duplicates > 0 {
        t.warn(
            "file",
            format!(
                "{}: {duplicates} triangle(s) repeat an earlier one's corners and were left out",
                path.display()
            ),
        );
    }
    triangles.shrink_to_fit();
    let normals = match (smooth, obj.normals) {
        (false, _) => None,
        // Normals transform by the inverse transpose: the rotation, and the sign of the scale.
        (true, Some(mut n)) => {
            for v in &mut n {
                let w = scale.signum() * (m * DVec3::from(v.map(f64::from)));
                *v = w.normalize_or_zero().as_vec3().to_array();
            }
            Some(n)
        }
        (true, None) => Some(vertex_normals(&vertices, &triangles)),
    };
    let mesh = TriangleMesh::new(vertices, triangles, normals, obj.texcoords)
        .map_err(|e| t.error("file", e))?;
    Ok(vec![Primitive::Mesh(std::sync::Arc::new(mesh))])
}

/// Vertex normals of a mesh without them, by Max's weights (J. Graphics Tools 4(2), 1999):
/// at each corner, e1 × e2 / (|e1|² |e2|²) with e1, e2 the corner's edges, summed over the
/// triangles that share the vertex (by index). Exact where the vertex and its neighbours lie on
/// a sphere, and so O(h²) on smooth surfaces, where area or angle weights err by O(h) on
/// irregular meshes. A vertex no triangle uses gets +z.
fn vertex_normals(vertices: &[[f32; 3]], triangles: &[[u32; 3]]) -> Vec<[f32; 3]> {
    let at = |i: u32| DVec3::from(vertices[i as usize].map(f64::from));
    let mut sum = vec![DVec3::ZERO; vertices.len()];
    for &[a, b, c] in triangles {
        for (v, next, prev) in [(a, b, c), (b, c, a), (c, a, b)] {
            let (e1, e2) = (at(next) - at(v), at(prev) - at(v));
            let w = e1.length_squared() * e2.length_squared();
            if w > 0.0 {
                sum[v as usize] += e1.cross(e2) / w;
            }
        }
    }
    sum.into_iter()
        .map(|n| n.try_normalize().unwrap_or(DVec3::Z).as_vec3().to_array())
        .collect()
}

/// A light's optional `spectrum` (None: not given — the light is D65 in bands and its RGB in
/// images): the shape of its emission over wavelength, `"D65"`, `"E"` (equal energy),
/// `{ blackbody = kelvin }` or `{ gaussian = [peak_nm, fwhm_nm] }` (an LED).
pub fn read_spectrum(t: &mut TableReader) -> Result<Option<Spectrum>> {
    let Some(value) = t.value_opt("spectrum") else {
        return Ok(None);
    };
    let bad = |why: &str| {
        t.error(
            "spectrum",
            format!("{why} (expected \"D65\", \"E\", {{ blackbody = kelvin }} or {{ gaussian = [peak_nm, fwhm_nm] }})"),
        )
    };
    let shape = match &value {
        toml::Value::String(s) if s == "D65" => Shape::D65,
        toml::Value::String(s) if s == "E" => Shape::Equal,
        toml::Value::Table(table) if table.len() == 1 => {
            let (model, v) = table.iter().next().expect("one entry");
            let numbers = t.numbers_in("spectrum", v)?;
            match (model.as_str(), &numbers[..]) {
                ("blackbody", &[k]) if k > 0.0 && k.is_finite() => Shape::Blackbody { kelvin: k },
                ("gaussian", &[peak, fwhm])
                    if fwhm > 0.0 && peak.is_finite() && fwhm.is_finite() =>
                {
                    Shape::Gaussian { peak, fwhm }
                }
                _ => return Err(bad(&format!("bad `{model}` spectrum"))),
            }
        }
        toml::Value::String(s) => return Err(bad(&format!("unknown spectrum '{s}'"))),
        _ => return Err(bad("not a spectrum")),
    };
    Spectrum::new(shape)
        .map(Some)
        .map_err(|e| t.error("spectrum", e))
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
            Light::Spot {
                position,
                direction,
                intensity,
                cos_inner: falloff.to_radians().cos(),
                cos_outer: cone.to_radians().cos(),
            }
        }
        "quad" => {
            let (origin, e1, e2) = parallelogram(t, "vertices")?;
            area(t, Emitter::Quad { origin, e1, e2 })?
        }
        "disk" => {
            let emitter = Emitter::Disk {
                center: t.vec3("center")?,
                normal: t.direction_or("normal", -DVec3::Y)?,
                radius: t.positive("radius")?,
            };
            area(t, emitter)?
        }
        "led" => {
            let emitter = Emitter::Disk {
                center: t.vec3("center")?,
                normal: t.direction_or("normal", DVec3::Z)?,
                radius: t.positive("radius")?,
            };
            let power = t.positive("power")?;
            let m = t.f64_or("m", 1.0)?;
            t.check("m", m >= 0.0, "must be ≥ 0")?;
            let color = t.rgb_or("color", Some(Rgb::ONE))?;
            let peak_intensity = color * (power * (m + 1.0) / std::f64::consts::TAU);
            Light::Led { emitter, peak_intensity, m }
        }
        "directional" => Light::Directional { direction: t.direction_or("direction", -DVec3::Y)?, irradiance: t.rgb_or("irradiance", None)? },
        other => return Err(t.error("type", format!("unknown light type '{other}' (point, spot, quad, disk, led, directional, environment)"))),
    })
}

/// A `[[light]]` of type `environment`; image files are relative to `dir`.
pub fn read_environment(t: &mut TableReader) -> Result<Environment> {
    let sky = match (t.has("file"), t.string_opt("sky")?) {
        (true, None) => {
            let path = t.input_file("file")?;
            let img = crate::texture::open_image(&path)
                .map_err(|e| t.error("file", e))?
                .to_rgb32f();
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
            Sky::Image {
                width: img.width() as usize,
                height: img.height() as usize,
                pixels: img.pixels().map(|p| p.0).collect(),
            }
        }
        (false, Some(sky)) => match sky.as_str() {
            "starfield" => Sky::Starfield {
                seed: t.natural_or("seed", 1)?,
            },
            "checker" => Sky::Checker {
                squares: t.count_or("squares", 24)?.min(1 << 20) as u32,
            },
            other => {
                return Err(t.error("sky", format!("unknown sky '{other}' (starfield, checker)")))
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
    Ok(Environment {
        sky,
        rotation: t.f64_or("rotation_deg", 0.0)?.to_radians(),
        scale,
    })
}

/// A `[[receiver]]` called `name`: a detector rectangle.
pub fn read_receiver(t: &mut TableReader, name: String) -> Result<Receiver> {
    let center = t.vec3("center")?;
    let normal = t.direction_or("normal", DVec3::Z)?;
    let up = t.direction_or("up", DVec3::Y)?;
    let u = up.cross(normal);
    t.check("up", u.length() > 1e-9, "must not be parallel to `normal`")?;
    let u = u.normalize();
    let size = t
        .f64_list_opt("size")?
        .ok_or_else(|| t.error("size", "is missing"))?;
    t.check(
        "size",
        size.len() == 2 && size.iter().all(|s| *s > 0.0 && s.is_finite()),
        "expected [width, height], both > 0",
    )?;
    let [nx, ny] = t.counts::<2>("bins")?;
    t.check(
        "bins",
        (1..=4096).contains(&nx) && (1..=4096).contains(&ny),
        "each must be in 1..=4096",
    )?;
    let bands = t.vec2_list_opt("bands")?.unwrap_or_default();
    t.check(
        "bands",
        bands
            .iter()
            .all(|&(lo, hi)| LAMBDA_MIN <= lo && lo < hi && hi <= LAMBDA_MAX),
        format!("each band is [lo_nm, hi_nm] with {LAMBDA_MIN} ≤ lo < hi ≤ {LAMBDA_MAX}"),
    )?;
    Ok(Receiver {
        bands,
        name,
        center,
        u,
        v: normal.cross(u),
        size: (size[0], size[1]),
        bins: (nx, ny),
    })
}
