//! pbrt-v4 scenes converted to grinlight's scene schema: each directive and parameter either
//! converted exactly, approximated (only when asked, each approximation listed), or refused
//! naming its file, line and column. `docs/import.md` lists every conversion and its
//! conventions; the numbers pbrt-v4 uses (its defaults, its light normalisation, its
//! roughness remapping) are read from its source, `src/pbrt/{lights,materials,cameras,
//! film}.cpp`.
//!
//! pbrt's camera is left-handed (the image's right is the camera's +x, with +y up and +z
//! forward): a camera whose frame is a rotation sees the world mirrored, as grinlight's never
//! does. Such a scene is converted with x negated throughout (a point (x, y, z) of the file is
//! at (−x, y, z) in grinlight's scene), which renders the image pbrt renders; a scene whose
//! camera transform mirrors (the usual `Scale -1 1 1` before `LookAt`) keeps its coordinates.

mod illuminant;
mod index;
pub mod parse;
mod texture;

use super::geometry::{
    axis_scales, emitting_side, linear, local_frame, look_at, normal_turn, parallelogram,
    similarity, triangle_area, Facing, FACES_TOLERANCE,
};
use super::table::{
    absorption, affine_rows, free_name, pixel_filter_keys, string, table, vec3, with_uv_frame,
    AreaEmitter, Lists,
};
use super::{Imported, Place, Told};
use crate::error::{cut, Result};
use crate::pixel_filter::PixelFilter;
use crate::spectrum::emission::Shape;
use glam::{DMat3, DMat4, DVec3};
use index::Eta;
use parse::{Params, Scene, Statement};
use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;
use toml::{Table, Value as Toml};

/// pbrt-v4's tabulated metals that grinlight has measured data for (`metal-X-eta`,
/// `metal-X-k`).
const METALS: [&str; 4] = ["Ag", "Al", "Au", "Cu"];

/// Converts the statements of `scene`; `approximate` lets what converts only approximately
/// through (each one listed).
pub fn convert(scene: &Scene, approximate: bool) -> Result<Imported> {
    let mut c = Converter {
        scene,
        told: Told::new(approximate),
        lists: Lists::default(),
        graphics: Graphics::default(),
        defining: None,
        instances: HashMap::new(),
        instance_uses: Vec::new(),
        plys: HashMap::new(),
        stack: Vec::new(),
        named_frames: HashMap::new(),
        camera_at: None,
        camera: None,
        film: None,
        sampler: None,
        filter: PixelFilter::pbrt_gaussian(0.5, 1.5),
        render: Table::new(),
        mirror: false,
        world: false,
        named_materials: HashMap::new(),
        textures: HashMap::new(),
        used_textures: HashSet::new(),
        converted_materials: HashMap::new(),
        used_materials: HashSet::new(),
        default_material: None,
        index_matched: None,
        named_media: HashMap::new(),
        medium_tables: HashMap::new(),
        ambient: None,
        ambient_pbrt: None,
        environment: None,
    };
    c.render.insert("integrator".into(), string("path"));
    // pbrt-v4's default integrator, volpath, with its default depth; its default seed.
    c.render.insert("max_depth".into(), Toml::Integer(5));
    c.render.insert("seed".into(), Toml::Integer(0));
    for s in &scene.statements {
        c.statement(s)?;
    }
    if let Some(open) = &c.defining {
        return Err(open.place.error(format!(
            "ObjectBegin \"{}\" is never ended (ObjectEnd)",
            cut(&open.name)
        )));
    }
    c.place_instances()?;
    if !c.world {
        let place = scene
            .statements
            .last()
            .map(|s| s.place.clone())
            .unwrap_or_else(|| Place {
                file: std::rc::Rc::new(scene.files[0].clone()),
                line: 1,
                col: 1,
            });
        return Err(place.error("the scene has no WorldBegin: nothing to render"));
    }
    for s in &scene.statements {
        let unused = match s.directive.as_str() {
            "Material" | "MakeNamedMaterial" => {
                !c.used_materials.contains(&(s as *const Statement))
            }
            "Texture" => !c.used_textures.contains(s.text(0)),
            _ => false,
        };
        if unused {
            c.told.note(
                &s.place,
                format!("{} is used by no shape: left out", s.what()),
            );
        }
    }
    let mut table = Table::new();
    table.insert(
        "camera".into(),
        Toml::Table(c.camera.take().expect("made at WorldBegin")),
    );
    if let Some(env) = c.environment.take() {
        c.lists.lights.push(env);
    }
    if let Some(ambient) = &c.ambient {
        table.insert("ambient".into(), string(ambient));
    }
    table.insert("render".into(), Toml::Table(std::mem::take(&mut c.render)));
    std::mem::take(&mut c.lists).insert_into(&mut table);
    Ok(c.told.into_imported(table, scene.files.clone()))
}

/// An object's definition (`ObjectBegin` … `ObjectEnd`): its shapes, each with the graphics
/// state it was given in. An `ObjectInstance` places each shape with the transform current
/// there composed with its own, CTM_instance · CTM_shape, as pbrt-v4's render-from-instance
/// times its render-from-object (a flattening: every instance converts to shapes of its own).
struct Definition<'s> {
    name: String,
    place: Place,
    shapes: Vec<(&'s Statement, Graphics<'s>)>,
    /// The graphics states saved when it began, its own included.
    depth: usize,
}

/// pbrt's graphics state: what `AttributeBegin` saves and `AttributeEnd` restores.
#[derive(Clone)]
struct Graphics<'s> {
    /// The current transform (object to world), f64.
    ctm: DMat4,
    /// `ReverseOrientation` toggled an odd number of times.
    reverse: bool,
    /// The statement of the current material (None: pbrt's default, diffuse of reflectance
    /// 0.5), converted when a shape first uses it.
    material: Option<&'s Statement>,
    /// The current area light.
    area: Option<AreaLight>,
    /// `MediumInterface`: the media inside and outside the shapes that follow.
    inside: Option<String>,
    outside: Option<String>,
}

impl Default for Graphics<'_> {
    fn default() -> Self {
        Graphics {
            ctm: DMat4::IDENTITY,
            reverse: false,
            material: None,
            area: None,
            inside: None,
            outside: None,
        }
    }
}

/// What a material became.
#[derive(Clone)]
enum Surface {
    /// A grinlight material, its name; a dielectric's relative index; whether a texture
    /// colours it (looked up at the shape's (u, v), which must then be pbrt's).
    Material {
        name: String,
        ior: Option<Eta>,
        textured: bool,
    },
    /// pbrt's `interface`: no surface, a medium's boundary only.
    Interface,
}

/// `AreaLightSource "diffuse"`: the radiance of the shapes that follow.
#[derive(Clone)]
struct AreaLight {
    /// L × scale.
    radiance: Emission,
    /// `power`, if given: the radiance is then scaled to emit it from each shape.
    power: Option<f64>,
    place: Place,
}

struct Converter<'s> {
    scene: &'s Scene,
    told: Told,
    /// The scene's arrays of tables, as made.
    lists: Lists,
    graphics: Graphics<'s>,
    /// The object being defined (`ObjectBegin` … `ObjectEnd`).
    defining: Option<Definition<'s>>,
    /// The objects defined, by name.
    instances: HashMap<String, Definition<'s>>,
    /// Each `ObjectInstance` and the transform current there, placed once every object is
    /// defined (pbrt-v4 lets an instance come before its definition).
    instance_uses: Vec<(&'s Statement, DMat4)>,
    /// The PLY files read at conversion (to measure their normals), by statement.
    plys: HashMap<*const Statement, std::rc::Rc<crate::scene::mesh::ObjTriangles>>,
    stack: Vec<Graphics<'s>>,
    /// `CoordinateSystem` names (and `camera`).
    named_frames: HashMap<String, DMat4>,
    /// The `Camera` statement, its world-from-camera map and the medium it is in.
    camera_at: Option<(&'s Statement, DMat4, Option<String>)>,
    /// The `[camera]` table, made at `WorldBegin`.
    camera: Option<Table>,
    /// `Film`, `Sampler` as read (converted at `WorldBegin`, when the camera is).
    film: Option<Film>,
    sampler: Option<i64>,
    /// The pixel filter (pbrt's default until a `PixelFilter` says otherwise).
    filter: PixelFilter,
    render: Table,
    /// Whether x is negated (pbrt's camera frame is a rotation).
    mirror: bool,
    /// After `WorldBegin`.
    world: bool,
    /// `MakeNamedMaterial` statements by name.
    named_materials: HashMap<String, &'s Statement>,
    /// `Texture` statements by name, and the names a material used.
    textures: HashMap<String, &'s Statement>,
    used_textures: HashSet<String>,
    /// Each material statement converted, by address (one material however often used).
    converted_materials: HashMap<*const Statement, Surface>,
    /// The material statements a shape or an area light's shape used.
    used_materials: HashSet<*const Statement>,
    default_material: Option<String>,
    index_matched: Option<String>,
    /// `MakeNamedMedium` statements by name.
    named_media: HashMap<String, NamedMedium<'s>>,
    /// Each medium converted at an index (its bits, [`Eta::key`]), by name.
    medium_tables: HashMap<(String, Vec<u64>), String>,
    /// The grinlight medium around the camera, and its pbrt name.
    ambient: Option<String>,
    ambient_pbrt: Option<String>,
    environment: Option<Table>,
}

/// The reflection x ↦ −x, or the identity.
/// A `MakeNamedMedium` statement and the transform current where it was written (the
/// medium's space: a grid medium's lies in it).
#[derive(Clone, Copy)]
struct NamedMedium<'s> {
    statement: &'s Statement,
    ctm: DMat4,
}

fn mirror_map(mirror: bool) -> DMat4 {
    match mirror {
        true => DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0)),
        false => DMat4::IDENTITY,
    }
}

/// The frame of an image laid over directions (an equal-area map), `axes` its x, y and z
/// (orthonormal) in grinlight's world, as a rotation and whether the image's rows are read
/// flipped (its y negated) for it to be one: pbrt's frames may be mirrored against grinlight's
/// (the scene's x negated, a goniometric light's y and z swapped).
fn map_rotation(axes: DMat3) -> (DMat3, bool) {
    match axes.determinant() < 0.0 {
        true => (
            axes * DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0)),
            true,
        ),
        false => (axes, false),
    }
}

/// What a pbrt light emits. pbrt scales an RGB emission by its illuminant's luminance, so the
/// RGB given is the RGB seen, and a spectrum (a blackbody, a named illuminant, pairs of
/// wavelength and power) to unit luminance, so its luminance is its scale (`power` and
/// `illuminance` then scale either).
#[derive(Clone, Debug)]
enum Emission {
    /// Linear sRGB.
    Rgb(DVec3),
    /// A spectrum over wavelength.
    Spectral(Spectral),
}

/// CIE standard illuminant A as a temperature: the CIE defines it as Planck's law at 2848 K
/// with c₂ = 1.435·10⁻² m·K (CIE 15:2004), the same spectrum as at 2848 · c₂/1.435·10⁻² K with
/// c₂ = hc/k = 1.438777·10⁻² m·K (Planck's law depends on c₂/T alone, up to its scale).
const ILLUMINANT_A_KELVIN: f64 = 2848.0 * 1.438_776_877e-2 / 1.435e-2;

/// A spectrum's `shape`, of luminance `luminance` relative to unit-power D65's (a white of
/// luminance 1 is (1, 1, 1)), written at `place`.
#[derive(Clone, Debug)]
struct Spectral {
    shape: Shape,
    luminance: f64,
    place: Place,
}

impl Spectral {
    /// A spectrum of `shape` at unit luminance, written at `place`.
    fn unit(shape: Shape, place: &Place) -> Self {
        Self {
            shape,
            luminance: 1.0,
            place: place.clone(),
        }
    }

    /// grinlight's spectrum of it, and the power (in units of that spectrum, one of which has
    /// luminance `Spectrum::luminance`) that has its luminance.
    fn spectrum_and_power(&self) -> Result<(crate::spectrum::Spectrum, f64)> {
        let spectrum = crate::spectrum::Spectrum::new(self.shape.clone())
            .map_err(|e| self.place.error(format!("the light's spectrum: {e}")))?;
        let power = self.luminance / spectrum.luminance();
        Ok((spectrum, power))
    }

    /// Its shape as a light's `spectrum` key.
    fn toml(&self) -> Toml {
        match &self.shape {
            Shape::D65 => Toml::String("D65".into()),
            Shape::Equal => Toml::String("E".into()),
            Shape::Gaussian { peak, fwhm } => Toml::Table(table([(
                "gaussian",
                Toml::Array(vec![Toml::Float(*peak), Toml::Float(*fwhm)]),
            )])),
            Shape::Blackbody { kelvin } => {
                Toml::Table(table([("blackbody", Toml::Float(*kelvin))]))
            }
            Shape::Table(nodes) => Toml::Table(table([(
                "table",
                Toml::Array(
                    nodes
                        .iter()
                        .map(|&(nm, power)| Toml::Array(vec![Toml::Float(nm), Toml::Float(power)]))
                        .collect(),
                ),
            )])),
        }
    }
}

impl Emission {
    /// The emission scaled by `k`.
    fn times(self, k: f64) -> Emission {
        match self {
            Emission::Rgb(c) => Emission::Rgb(c * k),
            Emission::Spectral(b) => Emission::Spectral(Spectral {
                luminance: b.luminance * k,
                ..b
            }),
        }
    }

    /// Writes the emission as the light's `key`: an RGB, or one number (the power of the
    /// `spectrum` written beside it).
    fn put(&self, light: &mut Table, key: &str) -> Result<()> {
        match self {
            Emission::Rgb(c) => {
                light.insert(key.into(), vec3(*c));
            }
            Emission::Spectral(b) => {
                let (_, power) = b.spectrum_and_power()?;
                light.insert(key.into(), Toml::Float(power));
                light.insert("spectrum".into(), b.toml());
            }
        }
        Ok(())
    }

    /// Its linear sRGB.
    fn rgb(&self) -> Result<DVec3> {
        match self {
            Emission::Rgb(c) => Ok(*c),
            Emission::Spectral(b) => {
                let (spectrum, power) = b.spectrum_and_power()?;
                Ok(spectrum.colour().0 * power)
            }
        }
    }
}

/// pbrt-v4's microfacet α of a roughness: √r when remapped (its default), else r.
fn alpha(p: &Params, place: &Place) -> Result<f64> {
    let r = p.float("roughness", 0.0)?;
    let u = p.float("uroughness", r)?;
    let v = p.float("vroughness", r)?;
    if u != v {
        return Err(place.error(format!(
            "an anisotropic roughness (uroughness {u} ≠ vroughness {v}) is not supported"
        )));
    }
    let a = match p.boolean("remaproughness", true)? {
        true => u.max(0.0).sqrt(),
        false => u,
    };
    if !(0.0..=1.0).contains(&a) {
        return Err(place.error(format!(
            "the roughness gives α = {a}, outside grinlight's [0, 1]"
        )));
    }
    Ok(a)
}

impl<'s> Converter<'s> {
    /// An RGB colour parameter (`rgb`; `default` when absent); spectra, blackbodies and
    /// textures are refused by name.
    fn rgb(&self, p: &Params, name: &str, default: DVec3, owner: &str) -> Result<DVec3> {
        let Some(param) = p.take(name) else {
            return Ok(default);
        };
        match param.ty.as_str() {
            "rgb" => match p.numbers(name, &["rgb"])?.expect("taken").0[..] {
                [r, g, b] => Ok(DVec3::new(r, g, b)),
                ref v => Err(param.place.error(format!(
                    "{}: expected 3 numbers, got {}",
                    param.what(),
                    v.len()
                ))),
            },
            other => Err(param.place.error(format!(
                "{owner}: {} — a {} is not supported by grinlight's import (give an rgb)",
                param.what(),
                cut(other)
            ))),
        }
    }

    /// An emission parameter (`default` white when absent): an `rgb`, a `blackbody`
    /// temperature, or a `spectrum` — pbrt's named illuminants D65 and A, or pairs of
    /// wavelength and power; other named spectra and textures are refused by name.
    fn emission(&self, p: &Params, name: &str, owner: &str) -> Result<Emission> {
        match p.take(name) {
            Some(param) if param.ty == "blackbody" => {
                match p.numbers(name, &["blackbody"])?.expect("taken").0[..] {
                    [kelvin] if kelvin > 0.0 => Ok(Emission::Spectral(Spectral::unit(
                        Shape::Blackbody { kelvin },
                        &param.place,
                    ))),
                    _ => Err(param.place.error(format!(
                        "{owner}: {}: expected one temperature in kelvin, > 0",
                        param.what()
                    ))),
                }
            }
            Some(param) if param.ty == "spectrum" => match &param.values[..] {
                // pbrt scales a light's spectrum to unit luminance, as it does an RGB one's
                // illuminant: D65 is the RGB white, and CIE illuminant A Planck's spectrum at
                // 2848 K with the CIE's c₂ = 1.435·10⁻² m·K, 2855.50 K with today's
                // (c₂ = hc/k = 1.438777·10⁻² m·K).
                [parse::Value::Text(n)] if n == "stdillum-D65" => Ok(Emission::Rgb(DVec3::ONE)),
                [parse::Value::Text(n)] if n == "stdillum-A" => {
                    Ok(Emission::Spectral(Spectral::unit(
                        Shape::Blackbody {
                            kelvin: ILLUMINANT_A_KELVIN,
                        },
                        &param.place,
                    )))
                }
                [parse::Value::Text(n)] => match illuminant::rows(n) {
                    Some(rows) => Ok(Emission::Spectral(Spectral::unit(
                        Shape::Table(rows.into()),
                        &param.place,
                    ))),
                    None => Err(param.place.error(format!(
                        "{owner}: the spectrum \"{}\": grinlight's import reads pbrt-v4's named \
                         illuminants ({}), and pairs of wavelength and power (or give an rgb or \
                         a blackbody)",
                        cut(n),
                        ["stdillum-A", "stdillum-D65"]
                            .into_iter()
                            .chain(illuminant::names())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ))),
                },
                // Pairs λ, power: pbrt-v4's piecewise-linear spectrum, 0 beyond its ends.
                values => {
                    let numbers = p.numbers(name, &["spectrum"])?.expect("taken").0;
                    let nodes: Vec<(f64, f64)> =
                        numbers.chunks_exact(2).map(|w| (w[0], w[1])).collect();
                    let rising = nodes.windows(2).all(|w| w[0].0 < w[1].0);
                    let valid = values.len() % 2 == 0
                        && nodes.len() >= 2
                        && rising
                        && nodes.iter().all(|&(nm, power)| nm > 0.0 && power >= 0.0);
                    match valid {
                        true => Ok(Emission::Spectral(Spectral::unit(
                            Shape::Table(nodes.into()),
                            &param.place,
                        ))),
                        false => Err(param.place.error(format!(
                            "{owner}: {}: expected pairs of wavelength (nm, rising, > 0) and \
                             power (≥ 0), two or more",
                            param.what()
                        ))),
                    }
                }
            },
            _ => Ok(Emission::Rgb(self.rgb(p, name, DVec3::ONE, owner)?)),
        }
    }

    /// A light's `from` (the origin) and its unit direction toward `to` (+z), both in
    /// grinlight's world (`from` still in the light's frame `m`: place it with `self.point`).
    fn aim(&self, s: &Statement, m: &DMat4) -> Result<(DVec3, DVec3)> {
        let from = point_param(&s.params, "from", DVec3::ZERO)?;
        let to = point_param(&s.params, "to", DVec3::Z)?;
        let direction = self.vector(m, to - from).try_normalize().ok_or_else(|| {
            s.place
                .error(format!("{}: from and to are the same point", s.what()))
        })?;
        Ok((from, direction))
    }

    /// A point of the file in grinlight's world.
    fn point(&self, m: &DMat4, p: DVec3) -> DVec3 {
        (mirror_map(self.mirror) * *m).transform_point3(p)
    }

    /// A direction of the file in grinlight's world (not normalised).
    fn vector(&self, m: &DMat4, v: DVec3) -> DVec3 {
        (mirror_map(self.mirror) * *m).transform_vector3(v)
    }

    /// A normal of the file (object space) in grinlight's world, unit.
    fn normal(&self, m: &DMat4, n: DVec3) -> DVec3 {
        let l = linear(&(mirror_map(self.mirror) * *m));
        (l.inverse().transpose() * n).normalize()
    }

    fn statement(&mut self, s: &'s Statement) -> Result<()> {
        let p = &s.params;
        let numbers = s.numbers();
        let before_world = |what: &str| -> Result<()> {
            match self.world {
                false => Ok(()),
                true => Err(s.place.error(format!("{what} belongs before WorldBegin"))),
            }
        };
        match s.directive.as_str() {
            "Identity" => self.graphics.ctm = DMat4::IDENTITY,
            "Translate" => {
                self.graphics.ctm *= DMat4::from_translation(DVec3::from_slice(&numbers))
            }
            "Scale" => self.graphics.ctm *= DMat4::from_scale(DVec3::from_slice(&numbers)),
            "Rotate" => {
                let axis = DVec3::from_slice(&numbers[1..]);
                let axis = axis
                    .try_normalize()
                    .ok_or_else(|| s.place.error("Rotate: the axis has no length"))?;
                self.graphics.ctm *= DMat4::from_axis_angle(axis, numbers[0].to_radians());
            }
            "LookAt" => {
                let [ex, ey, ez, lx, ly, lz, ux, uy, uz] = numbers[..] else {
                    unreachable!("the parser reads 9 numbers")
                };
                // pbrt's LookAt is camera-from-world: the look-at frame inverted.
                let frame = look_at(
                    DVec3::new(ex, ey, ez),
                    DVec3::new(lx, ly, lz),
                    DVec3::new(ux, uy, uz),
                );
                self.graphics.ctm *= frame.map(|f| f.inverse()).ok_or_else(|| {
                    s.place
                        .error("LookAt: the eye is at the target, or up is along the view")
                })?;
            }
            // pbrt reads a matrix column by column.
            "Transform" => self.graphics.ctm = DMat4::from_cols_slice(&numbers),
            "ConcatTransform" => self.graphics.ctm *= DMat4::from_cols_slice(&numbers),
            "CoordinateSystem" => {
                self.named_frames
                    .insert(s.text(0).to_string(), self.graphics.ctm);
            }
            "CoordSysTransform" => {
                self.graphics.ctm = *self.named_frames.get(s.text(0)).ok_or_else(|| {
                    s.place.error(format!(
                        "no coordinate system is named \"{}\"",
                        cut(s.text(0))
                    ))
                })?
            }
            "ReverseOrientation" => self.graphics.reverse = !self.graphics.reverse,
            "AttributeBegin" => self.stack.push(self.graphics.clone()),
            "AttributeEnd" => {
                self.graphics = self
                    .stack
                    .pop()
                    .ok_or_else(|| s.place.error("AttributeEnd without AttributeBegin"))?
            }
            // pbrt-v4 still reads these (deprecated): they save and restore the transform.
            "TransformBegin" => self.stack.push(self.graphics.clone()),
            "TransformEnd" => {
                let saved = self
                    .stack
                    .pop()
                    .ok_or_else(|| s.place.error("TransformEnd without TransformBegin"))?;
                self.graphics.ctm = saved.ctm;
            }
            "Camera" => {
                before_world("Camera")?;
                if let Some((first, ..)) = &self.camera_at {
                    return Err(s.place.error(format!(
                        "a second Camera (the first at {}): grinlight renders one camera's view",
                        first.place
                    )));
                }
                self.camera_statement(s)?;
            }
            "Film" => {
                before_world("Film")?;
                self.film = Some(film(s)?);
            }
            "Sampler" => {
                before_world("Sampler")?;
                self.sampler = Some(sampler(s)?);
            }
            "PixelFilter" => {
                before_world("PixelFilter")?;
                self.filter = self.pixel_filter(s)?;
            }
            "Integrator" => {
                before_world("Integrator")?;
                self.integrator(s)?;
            }
            // The acceleration structure changes the speed, not the image.
            "Accelerator" => {
                for name in [
                    "maxnodeprims",
                    "splitmethod",
                    "intersectcost",
                    "traversalcost",
                ] {
                    p.ignore(name);
                }
                p.finish(&s.what())?;
            }
            "ColorSpace" => {
                if s.text(0) != "srgb" {
                    return Err(s.place.error(format!(
                        "the colour space \"{}\": grinlight's RGB is sRGB's (\"srgb\")",
                        cut(s.text(0))
                    )));
                }
            }
            "Option" => {
                // The seed of pbrt's samplers; the coordinates pbrt renders in change no pixel.
                if p.has("seed") {
                    let seed = p.integer("seed", 0)?.max(0);
                    self.render.insert("seed".into(), Toml::Integer(seed));
                }
                p.ignore("rendercoordsys");
                p.finish("Option")?;
            }
            "WorldBegin" => {
                if self.world {
                    return Err(s.place.error("a second WorldBegin"));
                }
                self.world_begin(s)?;
            }
            "Material" => {
                supported_material(s)?;
                self.graphics.material = Some(s);
            }
            "MakeNamedMaterial" => {
                supported_material(s)?;
                self.named_materials.insert(s.text(0).to_string(), s);
            }
            "NamedMaterial" => {
                let made = self.named_materials.get(s.text(0)).ok_or_else(|| {
                    s.place
                        .error(format!("no material is named \"{}\"", cut(s.text(0))))
                })?;
                self.graphics.material = Some(made);
            }
            "MakeNamedMedium" => {
                let medium = NamedMedium {
                    statement: s,
                    ctm: self.graphics.ctm,
                };
                self.named_media.insert(s.text(0).to_string(), medium);
            }
            "MediumInterface" => {
                let name = |t: &str| -> Result<Option<String>> {
                    match t {
                        "" => Ok(None),
                        t if self.named_media.contains_key(t) => Ok(Some(t.to_string())),
                        t => Err(s.place.error(format!("no medium is named \"{}\"", cut(t)))),
                    }
                };
                let inside = name(s.text(0))?;
                let outside = match s.args.len() {
                    1 => inside.clone(),
                    _ => name(s.text(1))?,
                };
                self.graphics.inside = inside;
                self.graphics.outside = outside;
            }
            "AreaLightSource" => self.area_light(s)?,
            "LightSource" => self.light(s)?,
            "Shape" => {
                if !self.world {
                    return Err(s.place.error("Shape belongs after WorldBegin"));
                }
                if let Some(definition) = &mut self.defining {
                    if self.graphics.area.is_some() {
                        return Err(s.place.error(format!(
                            "{}: an area light in an object's definition (pbrt-v4 leaves its \
                             light out with a warning; give the light outside the object)",
                            s.what()
                        )));
                    }
                    definition.shapes.push((s, self.graphics.clone()));
                    return Ok(());
                }
                self.shape(s)?;
            }
            "Texture" => {
                let name = s.text(0).to_string();
                if self.textures.insert(name.clone(), s).is_some() {
                    return Err(s.place.error(format!(
                        "Texture \"{}\" redefined (pbrt-v4 refuses it too)",
                        cut(&name)
                    )));
                }
            }
            "ObjectBegin" => {
                if !self.world {
                    return Err(s.place.error("ObjectBegin belongs after WorldBegin"));
                }
                if let Some(open) = &self.defining {
                    return Err(s.place.error(format!(
                        "ObjectBegin inside the definition of \"{}\" (begun at {})",
                        cut(&open.name),
                        open.place
                    )));
                }
                let name = s.text(0).to_string();
                if let Some(earlier) = self.instances.get(&name) {
                    return Err(s.place.error(format!(
                        "the object \"{}\" is defined again (first at {})",
                        cut(&name),
                        earlier.place
                    )));
                }
                self.stack.push(self.graphics.clone());
                self.defining = Some(Definition {
                    name,
                    place: s.place.clone(),
                    shapes: Vec::new(),
                    depth: self.stack.len(),
                });
            }
            "ObjectEnd" => {
                let definition = self
                    .defining
                    .take()
                    .ok_or_else(|| s.place.error("ObjectEnd without ObjectBegin"))?;
                if self.stack.len() != definition.depth {
                    return Err(s.place.error(format!(
                        "ObjectEnd with an AttributeBegin inside \"{}\" not ended",
                        cut(&definition.name)
                    )));
                }
                self.graphics = self
                    .stack
                    .pop()
                    .ok_or_else(|| s.place.error("ObjectEnd without ObjectBegin"))?;
                self.instances.insert(definition.name.clone(), definition);
            }
            "ObjectInstance" => {
                if let Some(open) = &self.defining {
                    return Err(s.place.error(format!(
                        "ObjectInstance inside the definition of \"{}\" (begun at {})",
                        cut(&open.name),
                        open.place
                    )));
                }
                self.instance_uses.push((s, self.graphics.ctm));
            }
            "Attribute" => {
                return Err(s.place.error(
                    "Attribute (default parameters for what follows) is not supported by \
                     grinlight's import: give the parameters where they are used",
                ))
            }
            "ActiveTransform" | "TransformTimes" => {
                return Err(s.place.error(format!(
                    "{}: moving geometry (motion blur) is not supported",
                    s.directive
                )))
            }
            "WorldEnd" => {
                return Err(s.place.error(
                    "WorldEnd is pbrt-v3's: grinlight reads pbrt-v4 scenes (pbrt --upgrade \
                     converts a v3 scene)",
                ))
            }
            other => unreachable!("the parser admits only pbrt-v4's directives, not {other}"),
        }
        Ok(())
    }

    /// A `PixelFilter`: a box of radius ½ (one pixel) or a Gaussian exactly (pbrt draws its
    /// film points from the filter, beyond the image's edges too); others as a box of one
    /// pixel, approximately.
    fn pixel_filter(&mut self, s: &Statement) -> Result<PixelFilter> {
        let p = &s.params;
        let filter = match s.text(0) {
            "box" if p.float("xradius", 0.5)? == 0.5 && p.float("yradius", 0.5)? == 0.5 => {
                PixelFilter::Box
            }
            "gaussian" => {
                let (x, y) = (p.float("xradius", 1.5)?, p.float("yradius", 1.5)?);
                let sigma = p.float("sigma", 0.5)?;
                if x != y {
                    return Err(s.place.error(format!(
                        "{}: xradius {x} ≠ yradius {y}: grinlight's Gaussian is the same along x and y",
                        s.what()
                    )));
                }
                if !(sigma > 0.0 && sigma <= 8.0 && x > 0.0 && x <= 32.0) {
                    return Err(s.place.error(format!(
                        "{}: sigma {sigma}, radius {x}: grinlight's Gaussian takes σ in (0, 8] and r in (0, 32] pixels",
                        s.what()
                    )));
                }
                PixelFilter::pbrt_gaussian(sigma, x)
            }
            _ => {
                for name in ["xradius", "yradius", "sigma", "alpha", "B", "C", "tau"] {
                    p.ignore(name);
                }
                self.told.approximate(
                    &s.place,
                    format!(
                        "{}: taken as a box of one pixel (each sample in its own pixel)",
                        s.what()
                    ),
                )?;
                PixelFilter::Box
            }
        };
        p.finish(&s.what())?;
        Ok(filter)
    }

    fn camera_statement(&mut self, s: &'s Statement) -> Result<()> {
        if s.text(0) != "perspective" {
            return Err(s.place.error(format!(
                "the camera \"{}\" is not supported (perspective is)",
                cut(s.text(0))
            )));
        }
        let world_from_camera = self.graphics.ctm.inverse();
        if !world_from_camera.is_finite() {
            return Err(s.place.error("the camera's transform has no inverse"));
        }
        self.named_frames.insert("camera".into(), world_from_camera);
        self.camera_at = Some((s, world_from_camera, self.graphics.outside.clone()));
        Ok(())
    }
}

/// The material types the import converts.
const MATERIALS: [&str; 8] = [
    "diffuse",
    "dielectric",
    "thindielectric",
    "conductor",
    "coateddiffuse",
    "interface",
    // pbrt-v4 reads these as `interface` (deprecated names).
    "none",
    "",
];

/// Refuses a material statement of a type the import does not convert, where it is written
/// (it is converted where a shape first uses it).
fn supported_material(s: &Statement) -> Result<()> {
    let kind = match s.directive.as_str() {
        "Material" => s.text(0).to_string(),
        _ => s.params.string("type")?.ok_or_else(|| {
            s.place
                .error(format!("{}: \"string type\" is missing", s.what()))
        })?,
    };
    match MATERIALS.contains(&kind.as_str()) {
        true => Ok(()),
        false => Err(s.place.error(format!(
            "the material \"{}\" is not supported by grinlight's import ({} are)",
            cut(&kind),
            MATERIALS.join(", ")
        ))),
    }
}

/// Whether a material scatters light about the surface's normal over a hemisphere (diffuse,
/// coated diffuse, rough dielectrics and conductors), rather than only into mirror and
/// refraction directions.
fn scatters_about_the_normal(s: &Statement) -> bool {
    let rough = |name| s.params.float(name, 0.0).is_ok_and(|r| r > 0.0);
    match Converter::material_kind(s).0.as_str() {
        "dielectric" | "conductor" => {
            rough("roughness") || rough("uroughness") || rough("vroughness")
        }
        "thindielectric" | "interface" | "none" | "" => false,
        _ => true,
    }
}

/// A `Film`: its size, and the window of it rendered.
#[derive(Clone, Copy, Debug)]
struct Film {
    width: i64,
    height: i64,
    /// `[x, y, width, height]` in pixels from the top-left, where it is not the whole image.
    window: Option<[i64; 4]>,
}

/// `Film "rgb"` (or `"gbuffer"`): its size and the window `cropwindow` or `pixelbounds` gives,
/// as pbrt-v4's film computes it (`film.cpp`): a crop window [x0, x1, y0, y1] of the unit
/// square, each pair ordered and clamped to [0, 1], is the pixels from ⌈x0·width⌉ to
/// ⌈x1·width⌉ (and likewise in y, from the top), the end excluded, and wins over pixel bounds
/// [x0, x1, y0, y1], which are clamped to the image. A window that is empty is refused, as
/// pbrt refuses it.
fn film(s: &Statement) -> Result<Film> {
    let p = &s.params;
    if !matches!(s.text(0), "rgb" | "gbuffer") {
        return Err(s.place.error(format!(
            "the film \"{}\" is not supported (rgb and gbuffer are)",
            cut(s.text(0))
        )));
    }
    let (w, h) = (
        p.integer("xresolution", 1280)?,
        p.integer("yresolution", 720)?,
    );
    if w < 1 || h < 1 {
        return Err(s.place.error("the resolution must be at least 1 × 1"));
    }
    let bounds = match (
        p.numbers("cropwindow", &["float"])?,
        p.numbers("pixelbounds", &["integer"])?,
    ) {
        (Some((c, param)), _) => {
            let [a, b, c0, d] = c[..] else {
                return Err(param.place.error(format!(
                    "{}: expected 4 numbers, found {}",
                    param.what(),
                    c.len()
                )));
            };
            let edge = |t: f64, n: i64| (n as f64 * t.clamp(0.0, 1.0)).ceil() as i64;
            [
                edge(a.min(b), w),
                edge(a.max(b), w),
                edge(c0.min(d), h),
                edge(c0.max(d), h),
            ]
        }
        (None, Some((b, param))) => {
            let [x0, x1, y0, y1] = b[..] else {
                return Err(param.place.error(format!(
                    "{}: expected 4 numbers, found {}",
                    param.what(),
                    b.len()
                )));
            };
            let clamp = |v: f64, n: i64| (v as i64).clamp(0, n);
            [clamp(x0, w), clamp(x1, w), clamp(y0, h), clamp(y1, h)]
        }
        (None, None) => [0, w, 0, h],
    };
    let [x0, x1, y0, y1] = bounds;
    if x1 <= x0 || y1 <= y0 {
        return Err(s.place.error(format!(
            "the film's window (pixels {x0}–{x1} across, {y0}–{y1} down) is empty"
        )));
    }
    // What pbrt writes where changes no pixel.
    for name in ["filename", "savefp16", "diagonal", "writefp16"] {
        p.ignore(name);
    }
    // pbrt's pass-through sensor: its imaging ratio is 1 at ISO 100, no white balance.
    if p.float("iso", 100.0)? != 100.0 {
        return Err(s
            .place
            .error("iso ≠ 100 scales pbrt's pixels: not supported"));
    }
    if p.float("whitebalance", 0.0)? != 0.0 {
        return Err(s.place.error("a white balance is not supported"));
    }
    if p.string("sensor")?.is_some_and(|n| n != "cie1931") {
        return Err(s
            .place
            .error("a camera sensor other than cie1931 is not supported"));
    }
    if p.float("maxcomponentvalue", f64::INFINITY)? != f64::INFINITY {
        return Err(s
            .place
            .error("maxcomponentvalue clamps pbrt's samples (a biased estimate): not supported"));
    }
    p.finish(&s.what())?;
    Ok(Film {
        width: w,
        height: h,
        window: (bounds != [0, w, 0, h]).then_some([x0, y0, x1 - x0, y1 - y0]),
    })
}

/// A `Sampler`'s samples a pixel (pbrt-v4's default 16; `stratified`: xsamples × ysamples).
fn sampler(s: &Statement) -> Result<i64> {
    let p = &s.params;
    // The pattern of the points changes the noise, not what they estimate.
    for name in ["randomization", "jitter", "seed"] {
        p.ignore(name);
    }
    let spp = match s.text(0) {
        "stratified" => p.integer("xsamples", 4)? * p.integer("ysamples", 4)?,
        "halton" | "independent" | "sobol" | "paddedsobol" | "zsobol" | "pmj02bn" => {
            p.integer("pixelsamples", 16)?
        }
        other => {
            return Err(s
                .place
                .error(format!("the sampler \"{}\" is not pbrt-v4's", cut(other))))
        }
    };
    if spp < 1 {
        return Err(s.place.error("the samples a pixel must be at least 1"));
    }
    p.finish(&s.what())?;
    Ok(spp)
}

/// A parameter's single point (`point3`, `point`), `default` when absent.
fn point_param(p: &Params, name: &str, default: DVec3) -> Result<DVec3> {
    match p.numbers(name, &["point3", "point"])? {
        None => Ok(default),
        Some((v, _)) if v.len() == 3 => Ok(DVec3::from_slice(&v)),
        Some((_, param)) => Err(param
            .place
            .error(format!("{}: expected one point (3 numbers)", param.what()))),
    }
}

/// Four corners ordered so that grinlight's quad normal, (v1 − v0) × (v3 − v0), points along
/// `normal`.
fn facing(v: [DVec3; 4], normal: DVec3) -> [DVec3; 4] {
    match (v[1] - v[0]).cross(v[3] - v[0]).dot(normal) >= 0.0 {
        true => v,
        false => [v[0], v[3], v[2], v[1]],
    }
}

/// A list of numbers as a TOML array.
fn floats(v: &[f64]) -> Toml {
    Toml::Array(v.iter().map(|&x| Toml::Float(x)).collect())
}

impl<'s> Converter<'s> {
    /// The camera, film, sampler and filter, converted now that all are known.
    fn world_begin(&mut self, s: &Statement) -> Result<()> {
        let film = self.film.unwrap_or(Film {
            width: 1280,
            height: 720,
            window: None,
        });
        let (w, h) = (film.width, film.height);
        self.render
            .insert("spp".into(), Toml::Integer(self.sampler.unwrap_or(16)));
        let (camera, world_from_camera, medium) = match self.camera_at.take() {
            Some((c, m, medium)) => (Some(c), m, medium),
            // pbrt's default camera: perspective, fov 90, at the origin looking along +z.
            None => (None, DMat4::IDENTITY, None),
        };
        let empty = Params::default();
        let p = camera.map(|c| &c.params).unwrap_or(&empty);
        let place = camera.map(|c| c.place.clone()).unwrap_or(s.place.clone());
        if similarity(&world_from_camera).is_none() {
            return Err(place.error(
                "the camera's transform scales unevenly or shears: a camera's frame is turned \
                 and moved only",
            ));
        }
        let l = linear(&world_from_camera);
        // pbrt's image right is the camera's +x; grinlight's is forward × up.
        self.mirror = l.x_axis.dot(l.z_axis.cross(l.y_axis)) < 0.0;
        if self.mirror {
            self.told.note(
                &place,
                "pbrt's camera sees the world mirrored (its frame is a rotation, and pbrt's \
                 camera is left-handed): x is negated throughout, a point (x, y, z) of the file \
                 is at (−x, y, z) in the converted scene",
            );
        }
        let origin = self.point(&world_from_camera, DVec3::ZERO);
        let forward = self.vector(&world_from_camera, DVec3::Z).normalize();
        let up = self.vector(&world_from_camera, DVec3::Y).normalize();
        let fov = p.float("fov", 90.0)?;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(place.error(format!("fov {fov}° is outside (0°, 180°)")));
        }
        // pbrt's fov spans the image's shorter side.
        let tan_x = (0.5 * fov.to_radians()).tan() * (w as f64 / h as f64).max(1.0);
        let mut table = table([
            ("position", vec3(origin)),
            ("look_at", vec3(origin + forward)),
            ("up", vec3(up)),
            ("width", Toml::Integer(w)),
            ("height", Toml::Integer(h)),
            ("fov_x_deg", Toml::Float(2.0 * tan_x.atan().to_degrees())),
        ]);
        let lens = p.float("lensradius", 0.0)?;
        let focus = p.float("focaldistance", 1e6)?;
        if lens > 0.0 {
            table.insert("aperture_radius".into(), Toml::Float(lens));
            table.insert("focus_distance".into(), Toml::Float(focus));
        }
        if let Some([x, y, width, height]) = film.window {
            let crop = [x, y, width, height].map(Toml::Integer);
            table.insert("crop".into(), Toml::Array(crop.to_vec()));
        }
        pixel_filter_keys(self.filter, &mut table);
        // The exposure scales pbrt's pixels: 1 (its default shutter) is grinlight's.
        let exposure = p.float("shutterclose", 1.0)? - p.float("shutteropen", 0.0)?;
        if exposure != 1.0 {
            return Err(place.error(format!(
                "an exposure (shutterclose − shutteropen) of {exposure} scales pbrt's pixels: \
                 grinlight's is 1"
            )));
        }
        if let Some(c) = camera {
            p.finish(&c.what())?;
        }
        if let Some(medium) = medium {
            let name = self.medium(&medium, &Eta::Constant(1.0))?;
            self.ambient = Some(name);
            self.ambient_pbrt = Some(medium);
        }
        self.camera = Some(table);
        self.world = true;
        self.graphics.ctm = DMat4::IDENTITY;
        self.named_frames.insert("world".into(), DMat4::IDENTITY);
        Ok(())
    }

    fn integrator(&mut self, s: &Statement) -> Result<()> {
        let p = &s.params;
        if !matches!(s.text(0), "path" | "volpath") {
            return Err(s.place.error(format!(
                "the integrator \"{}\" is not supported (path and volpath are, as grinlight's \
                 path tracer)",
                cut(s.text(0))
            )));
        }
        // pbrt's maxdepth counts scattering events, as grinlight's max_depth does.
        let depth = p.integer("maxdepth", 5)?;
        if depth < 1 {
            return Err(s.place.error(format!(
                "maxdepth {depth}: grinlight renders paths with at least one scattering"
            )));
        }
        self.render.insert("max_depth".into(), Toml::Integer(depth));
        // How lights are chosen changes the noise, not the estimate.
        p.ignore("lightsampler");
        if p.boolean("regularize", false)? {
            return Err(s
                .place
                .error("regularize = true roughens surfaces (a biased estimate): not supported"));
        }
        p.finish(&s.what())
    }

    /// pbrt's index of a dielectric: a `float eta` (1.5); a spectrum over wavelength refused.
    fn eta(&self, p: &Params, what: &str) -> Result<f64> {
        match p.take("eta") {
            None => Ok(1.5),
            Some(param) if param.ty == "float" => p.float("eta", 1.5),
            Some(param) => Err(param.place.error(format!(
                "{what}: {} — an index over wavelength (a dispersive glass) is not supported \
                 by grinlight's import; give a float eta",
                param.what()
            ))),
        }
    }

    /// pbrt's index of a `dielectric` ([`Eta`]): a `float eta` (1.5), or a `spectrum eta` — one of
    /// pbrt-v4's named glasses or inline pairs of wavelength (nm) and index; any other spectrum
    /// (a file, a blackbody, another named one) refused by name.
    fn dielectric_eta(&self, p: &Params, what: &str) -> Result<Eta> {
        let Some(param) = p.take("eta") else {
            return Ok(Eta::Constant(1.5));
        };
        if param.ty == "float" {
            return Ok(Eta::Constant(p.float("eta", 1.5)?));
        }
        let refuse = |why: String| {
            Err(param
                .place
                .error(format!("{what}: {}: {why}", param.what())))
        };
        if param.ty != "spectrum" {
            return refuse("expected a float or a spectrum".to_string());
        }
        let nodes: Vec<(f64, f64)> = match &param.values[..] {
            [parse::Value::Text(name)] => match index::glass(name) {
                Some(nodes) => nodes.to_vec(),
                None => {
                    return refuse(format!(
                        "\"{}\" is not one of pbrt-v4's glasses grinlight's import knows ({}; \
                         or give a float or pairs of wavelength and index)",
                        cut(name),
                        index::NAMES.join(", ")
                    ))
                }
            },
            values => {
                let numbers: Option<Vec<f64>> = values
                    .iter()
                    .map(|v| match v {
                        parse::Value::Number(x) => Some(*x),
                        parse::Value::Text(_) | parse::Value::Bool(_) => None,
                    })
                    .collect();
                let pairs = numbers
                    .filter(|n| n.len() >= 2 && n.len() % 2 == 0)
                    .map(|n| n.chunks(2).map(|c| (c[0], c[1])).collect::<Vec<_>>());
                match pairs {
                    Some(pairs)
                        if pairs.windows(2).all(|w| w[1].0 > w[0].0)
                            && pairs
                                .iter()
                                .all(|&(nm, n)| nm.is_finite() && n.is_finite() && n > 0.0) =>
                    {
                        pairs
                    }
                    _ => {
                        return refuse(
                            "give pairs of wavelength (nm, ascending) and index (> 0), or a \
                             named glass"
                                .to_string(),
                        )
                    }
                }
            }
        };
        Ok(Eta::Spectrum(nodes))
    }

    /// A diffuse base's `reflectance` (0.5 when absent) as a material's keys: its `albedo`,
    /// or a named texture's ([`texture::reflectance`], its approximation listed).
    fn reflectance(&mut self, p: &Params, what: &str) -> Result<Table> {
        let Some(param) = p.take("reflectance").filter(|r| r.ty == "texture") else {
            let r = self.rgb(p, "reflectance", DVec3::splat(0.5), what)?;
            return Ok(table([("albedo", vec3(r))]));
        };
        let name = p.string("reflectance")?.unwrap_or_default();
        let Some(&defined) = self.textures.get(&name) else {
            return Err(param.place.error(format!(
                "{what}: {} names no texture defined before it",
                param.what()
            )));
        };
        self.used_textures.insert(name);
        let converted = texture::reflectance(defined, |file, place| self.scene.find(file, place))?;
        self.told.approximate(&defined.place, converted.differs)?;
        Ok(converted.keys)
    }

    /// The grinlight material of a pbrt material of type `kind`, named `wanted` (or a free
    /// name near it).
    fn material(
        &mut self,
        kind: &str,
        p: &Params,
        what: &str,
        place: &Place,
        wanted: &str,
    ) -> Result<Surface> {
        let microsurface_note = |c: &mut Self| {
            c.told.note(
                place,
                format!(
                    "{what}: grinlight's microfacet model masks with correlated heights (pbrt: \
                     separable) and a rough dielectric scatters on its microsurface more than \
                     once (pbrt: once): grazing highlights differ by a few percent, light \
                     through a rough dielectric more (a frosted ball of fog lit from behind: \
                     Mitsuba 3.9.1's image, whose model is pbrt's, 0.86 of grinlight's)"
                ),
            )
        };
        let (grin_kind, mut m, ior) = match kind {
            "interface" | "none" | "" => {
                p.finish(what)?;
                return Ok(Surface::Interface);
            }
            "diffuse" => ("diffuse", self.reflectance(p, what)?, None),
            "dielectric" => {
                let eta = self.dielectric_eta(p, what)?;
                let a = alpha(p, place)?;
                let mut m = table([("ior", eta.toml())]);
                if a > 0.0 {
                    m.insert("roughness".into(), Toml::Float(a));
                    microsurface_note(self);
                }
                ("dielectric", m, Some(eta))
            }
            "thindielectric" => {
                let eta = self.eta(p, what)?;
                self.told.thin_pane(place, what, "pbrt");
                ("thin_dielectric", table([("ior", Toml::Float(eta))]), None)
            }
            "conductor" => {
                if let Some(param) = p.take("reflectance") {
                    return Err(param.place.error(format!(
                        "{what}: a conductor given by its reflectance is not supported (give \
                         eta and k)"
                    )));
                }
                let named = |name: &str| -> Result<Option<String>> {
                    match p.take(name) {
                        Some(param) if param.ty == "spectrum" => match &param.values[..] {
                            [parse::Value::Text(s)] => Ok(Some(s.clone())),
                            _ => Err(param.place.error(format!(
                                "{what}: {} over wavelength is not supported (give a named \
                                 metal's spectrum or an rgb)",
                                param.what()
                            ))),
                        },
                        _ => Ok(None),
                    }
                };
                let (eta_name, k_name) = (named("eta")?, named("k")?);
                let mut m = match (eta_name, k_name, p.has("eta") || p.has("k")) {
                    (None, None, false) => table([("metal", string("Cu"))]),
                    (Some(e), Some(k), _) => {
                        let metal = e
                            .strip_prefix("metal-")
                            .and_then(|r| r.strip_suffix("-eta"))
                            .filter(|m| METALS.contains(m) && k == format!("metal-{m}-k"))
                            .ok_or_else(|| {
                                place.error(format!(
                                    "{what}: eta \"{}\" and k \"{}\": grinlight has the \
                                     measured metals {} (metal-X-eta with metal-X-k)",
                                    cut(&e),
                                    cut(&k),
                                    METALS.join(", ")
                                ))
                            })?;
                        table([("metal", string(metal))])
                    }
                    (None, None, true) => table([
                        ("eta", vec3(self.rgb(p, "eta", DVec3::ONE, what)?)),
                        ("k", vec3(self.rgb(p, "k", DVec3::ZERO, what)?)),
                    ]),
                    _ => {
                        return Err(place.error(format!(
                            "{what}: give eta and k alike, both named metal spectra or both rgb"
                        )))
                    }
                };
                if m.contains_key("metal") {
                    self.told.note(
                        place,
                        format!(
                            "{what}: pbrt's tabulated metal taken as grinlight's measured one of \
                             the same name (Palik's data)"
                        ),
                    );
                }
                let a = alpha(p, place)?;
                if a > 0.0 {
                    m.insert("roughness".into(), Toml::Float(a));
                    microsurface_note(self);
                }
                ("conductor", m, None)
            }
            "coateddiffuse" => {
                let mut m = self.reflectance(p, what)?;
                let eta = self.eta(p, what)?;
                let a = alpha(p, place)?.max(1e-3);
                if self.rgb(p, "albedo", DVec3::ZERO, what)? != DVec3::ZERO {
                    return Err(place.error(format!(
                        "{what}: a coat that absorbs or scatters (albedo ≠ 0) is not supported"
                    )));
                }
                // With a clear coat the thickness changes nothing; the others set pbrt's
                // stochastic estimate of the layers.
                for name in ["thickness", "g", "maxdepth", "nsamples"] {
                    p.ignore(name);
                }
                self.told.approximate(
                    place,
                    format!(
                        "{what}: pbrt's stochastic layers taken as grinlight's plastic (a GGX coat \
                         over a diffuse base, the light between them summed in closed form)"
                    ),
                )?;
                m.insert("ior".into(), Toml::Float(eta));
                m.insert("roughness".into(), Toml::Float(a));
                ("plastic", m, None)
            }
            other => unreachable!("refused where it was defined: {other}"),
        };
        p.ignore("type");
        p.finish(what)?;
        let name = free_name(&self.lists.materials, wanted);
        m.insert("name".into(), string(&name));
        m.insert("type".into(), string(grin_kind));
        let textured = m.contains_key("texture") || m.contains_key("checkerboard");
        self.lists.materials.push(m);
        Ok(Surface::Material {
            name,
            ior,
            textured,
        })
    }

    /// The grinlight medium the pbrt medium `name` becomes at (relative) index `n`.
    fn medium(&mut self, name: &str, n: &Eta) -> Result<String> {
        let key = (name.to_string(), n.key());
        if let Some(made) = self.medium_tables.get(&key) {
            return Ok(made.clone());
        }
        let NamedMedium { statement: s, ctm } = self.named_media[name];
        let p = &s.params;
        let kind = p.string("type")?.unwrap_or_default();
        // pbrt-v4's defaults differ by medium (media.cpp).
        let (grid, sigma_a, sigma_s) = match kind.as_str() {
            "homogeneous" => (
                None,
                DVec3::new(0.0011, 0.0024, 0.014),
                DVec3::new(2.55, 3.21, 3.77),
            ),
            "uniformgrid" => (Some(self.uniform_grid(s, ctm)?), DVec3::ONE, DVec3::ONE),
            _ => {
                return Err(s.place.error(format!(
                    "the medium \"{}\" is not supported by grinlight's import (homogeneous and \
                     uniformgrid are)",
                    cut(&kind)
                )))
            }
        };
        let what = s.what();
        let scale = p.float("scale", 1.0)?;
        let sigma_a = self.rgb(p, "sigma_a", sigma_a, &what)? * scale;
        let sigma_s = self.rgb(p, "sigma_s", sigma_s, &what)? * scale;
        let g = p.float("g", 0.0)?;
        if self.rgb(p, "Le", DVec3::ZERO, &what)? != DVec3::ZERO {
            return Err(s.place.error(format!(
                "{what}: an emitting medium (Le) is not supported by grinlight's import"
            )));
        }
        p.ignore("Lescale");
        p.finish(&what)?;
        let mut m = table([("profile", string("uniform")), ("n", n.toml())]);
        m.extend(grid.unwrap_or_default());
        if sigma_a.max_element() > 0.0 {
            m.insert("absorption".into(), absorption(sigma_a));
        }
        if sigma_s.max_element() > 0.0 {
            m.insert("scattering".into(), vec3(sigma_s));
            if g != 0.0 {
                m.insert("phase".into(), Toml::Table(table([("hg", Toml::Float(g))])));
            }
        }
        let made = free_name(&self.lists.media, name);
        m.insert("name".into(), string(&made));
        self.lists.media.push(m);
        self.medium_tables.insert(key, made.clone());
        Ok(made)
    }

    /// A `uniformgrid` medium's density as a medium's density keys. pbrt-v4 (`SampledGrid`)
    /// holds nx × ny × nz values (x fastest) over the box [p0, p1] of the medium's space, value
    /// (i, j, k) at p0 + (p1 − p0)·((i, j, k) + ½)/(nx, ny, nz), trilinear between them and 0
    /// at the samples beyond them (so it falls to 0 half a cell past the outer values), and
    /// tracks the medium only within the box: grinlight's grid of the values ringed by zeros,
    /// placed by the transform where the medium was made, ending at the box (`density_end`).
    /// A transform that turns the grid is refused (grinlight's grids are axis-aligned); a
    /// mirroring one (the import's own mirror among them) reverses the values along that axis.
    fn uniform_grid(&self, s: &Statement, ctm: DMat4) -> Result<Table> {
        let p = &s.params;
        let what = s.what();
        if p.has("temperature") {
            return Err(s.place.error(format!(
                "{what}: an emitting medium (temperature) is not supported by grinlight's import"
            )));
        }
        for ignored in ["temperaturescale", "temperatureoffset", "temperaturecutoff"] {
            p.ignore(ignored);
        }
        let (density, param) = p
            .numbers("density", &["float"])?
            .ok_or_else(|| s.place.error(format!("{what}: no \"density\" values")))?;
        let dims = [
            p.integer("nx", 1)?,
            p.integer("ny", 1)?,
            p.integer("nz", 1)?,
        ];
        let count = dims.iter().try_fold(1i64, |n, &d| match d {
            1..=4096 => Some(n * d),
            _ => None,
        });
        if count != Some(density.len() as i64) {
            return Err(param.place.error(format!(
                "{what}: {} density values for nx, ny, nz = {dims:?} (each 1 to 4096, their \
                 product the number of values)",
                density.len()
            )));
        }
        if let Some(bad) = density.iter().find(|d| !(d.is_finite() && **d >= 0.0)) {
            return Err(param.place.error(format!(
                "{what}: a density {bad}: densities are finite and ≥ 0"
            )));
        }
        let (p0, p1) = (
            point_param(p, "p0", DVec3::ZERO)?,
            point_param(p, "p1", DVec3::ONE)?,
        );
        if !(p0.cmplt(p1).all() && p0.is_finite() && p1.is_finite()) {
            return Err(s.place.error(format!(
                "{what}: the box p0 {:?}, p1 {:?} is empty",
                p0.to_array(),
                p1.to_array()
            )));
        }
        let m = mirror_map(self.mirror) * ctm;
        let Some(diagonal) = axis_scales(&m) else {
            return Err(s.place.error(format!(
                "{what}: a transform that turns the grid: grinlight's grids are axis-aligned"
            )));
        };
        let n = dims.map(|d| d as usize);
        let padded = n.map(|d| d + 2);
        // The value at padded node (i, j, k): the file's, or 0 on the ring; read along an axis
        // the transform mirrors from its far end.
        let value = |node: [usize; 3]| {
            let mut at = [0; 3];
            for axis in 0..3 {
                let i = match diagonal[axis] < 0.0 {
                    true => padded[axis] - 1 - node[axis],
                    false => node[axis],
                };
                if i == 0 || i > n[axis] {
                    return 0.0;
                }
                at[axis] = i - 1;
            }
            density[(at[2] * n[1] + at[1]) * n[0] + at[0]]
        };
        let mut values = Vec::with_capacity(padded.iter().product());
        for k in 0..padded[2] {
            for j in 0..padded[1] {
                for i in 0..padded[0] {
                    values.push(Toml::Float(value([i, j, k])));
                }
            }
        }
        let cell = (p1 - p0) / DVec3::from(n.map(|d| d as f64));
        let corners = |a: DVec3, b: DVec3| {
            let (a, b) = (m.transform_point3(a), m.transform_point3(b));
            Toml::Array(vec![vec3(a.min(b)), vec3(a.max(b))])
        };
        Ok(table([
            ("density_bounds", corners(p0 - 0.5 * cell, p1 + 0.5 * cell)),
            (
                "density_dims",
                Toml::Array(padded.iter().map(|&d| Toml::Integer(d as i64)).collect()),
            ),
            ("density_values", Toml::Array(values)),
            ("density_end", corners(p0, p1)),
        ]))
    }

    fn area_light(&mut self, s: &Statement) -> Result<()> {
        let p = &s.params;
        let what = s.what();
        if s.text(0) != "diffuse" {
            return Err(s.place.error(format!(
                "the area light \"{}\" is not pbrt-v4's (diffuse is)",
                cut(s.text(0))
            )));
        }
        let radiance = self.emission(p, "L", &what)?.times(p.float("scale", 1.0)?);
        if p.boolean("twosided", false)? {
            return Err(s
                .place
                .error("a two-sided area light is not supported (grinlight's emit on one side)"));
        }
        let power = p.float("power", -1.0)?;
        p.finish(&what)?;
        self.graphics.area = Some(AreaLight {
            radiance,
            power: (power > 0.0).then_some(power),
            place: s.place.clone(),
        });
        Ok(())
    }

    fn light(&mut self, s: &Statement) -> Result<()> {
        let p = &s.params;
        let what = s.what();
        let m = self.graphics.ctm;
        let scale = p.float("scale", 1.0)?;
        let light = match s.text(0) {
            "point" => {
                let mut intensity = self.emission(p, "I", &what)?.times(scale);
                let power = p.float("power", -1.0)?;
                if power > 0.0 {
                    intensity = intensity.times(power / (4.0 * PI));
                }
                let from = point_param(p, "from", DVec3::ZERO)?;
                let mut t = table([
                    ("type", string("point")),
                    ("position", vec3(self.point(&m, from))),
                ]);
                intensity.put(&mut t, "intensity")?;
                t
            }
            "spot" => {
                if similarity(&m).is_none() {
                    return Err(s
                        .place
                        .error("the transform scales unevenly or shears the spot light's cone"));
                }
                let mut intensity = self.emission(p, "I", &what)?.times(scale);
                let cone = p.float("coneangle", 30.0)?;
                let delta = p.float("conedeltaangle", 5.0)?;
                if !(cone > 0.0 && cone <= 180.0 && delta >= 0.0 && delta <= cone) {
                    return Err(s.place.error(format!(
                        "coneangle {cone}° and conedeltaangle {delta}°: the cone must lie in \
                         (0°, 180°] and its falloff within it"
                    )));
                }
                let power = p.float("power", -1.0)?;
                if power > 0.0 {
                    let (end, start) = (cone.to_radians().cos(), (cone - delta).to_radians().cos());
                    intensity =
                        intensity.times(power / (2.0 * PI * ((1.0 - start) + 0.5 * (start - end))));
                }
                let (from, direction) = self.aim(s, &m)?;
                // pbrt's falloff: smoothstep in cos θ, grinlight's default.
                let mut t = table([
                    ("type", string("spot")),
                    ("position", vec3(self.point(&m, from))),
                    ("direction", vec3(direction)),
                    ("cone_deg", Toml::Float(cone)),
                    ("falloff_deg", Toml::Float(cone - delta)),
                    ("falloff_curve", string("smoothstep")),
                ]);
                intensity.put(&mut t, "intensity")?;
                t
            }
            "distant" => {
                let mut irradiance = self.emission(p, "L", &what)?.times(scale);
                let illuminance = p.float("illuminance", -1.0)?;
                if illuminance > 0.0 {
                    irradiance = irradiance.times(illuminance);
                }
                let (_, direction) = self.aim(s, &m)?;
                let mut t = table([
                    ("type", string("directional")),
                    ("direction", vec3(direction)),
                ]);
                irradiance.put(&mut t, "irradiance")?;
                t
            }
            "goniometric" => self.goniometric(s, &m, scale)?,
            "infinite" => {
                if let Some(name) = p.string("filename")? {
                    let environment = self.image_environment(s, &m, scale, &name)?;
                    p.finish(&what)?;
                    return self.set_environment(s, environment);
                }
                let mut radiance = self.emission(p, "L", &what)?.times(scale);
                let illuminance = p.float("illuminance", -1.0)?;
                if illuminance > 0.0 {
                    radiance = radiance.times(illuminance / PI);
                }
                p.finish(&what)?;
                // An environment has no spectrum of its own: its RGB.
                let environment = table([
                    ("type", string("environment")),
                    ("sky", string("uniform")),
                    ("radiance", vec3(radiance.rgb()?)),
                ]);
                return self.set_environment(s, environment);
            }
            other => {
                return Err(s.place.error(format!(
                    "the light \"{}\" is not supported by grinlight's import (point, spot, \
                     goniometric, distant, infinite are)",
                    cut(other)
                )))
            }
        };
        p.finish(&what)?;
        self.lists.lights.push(light);
        Ok(())
    }

    /// The scene's environment, `environment` from the infinite light `s` (grinlight has one).
    fn set_environment(&mut self, s: &Statement, environment: Table) -> Result<()> {
        if self.environment.is_some() {
            return Err(s
                .place
                .error("a second infinite light: grinlight has one environment"));
        }
        self.environment = Some(environment);
        Ok(())
    }

    /// An `infinite` light of an image (`filename`: RGB in the equal-area map, the light's frame
    /// its map's frame, read by nearest pixel): an `environment` of that image turned by the
    /// light's rotation — its rows read flipped where the rotation, with the scene's x negated
    /// or not, mirrors —, its radiance times `scale`, and with `illuminance` E times E/k,
    /// k the upper hemisphere's illuminance as pbrt-v4 computes it (each pixel's centre, cos θ
    /// and the sRGB luminance of its RGB, summed with weight 2π/N²).
    fn image_environment(&self, s: &Statement, m: &DMat4, scale: f64, name: &str) -> Result<Table> {
        let p = &s.params;
        for refused in ["L", "portal"] {
            if let Some(param) = p.take(refused) {
                return Err(param.place.error(format!(
                    "{}: an image's infinite light with {} is not supported",
                    s.what(),
                    param.what()
                )));
            }
        }
        let k = similarity(m).ok_or_else(|| {
            s.place.error(format!(
                "{}: the transform scales unevenly or shears the environment",
                s.what()
            ))
        })?;
        let path = self.scene.find(name, &s.place)?;
        let (turn, flip_v) = map_rotation(linear(&(mirror_map(self.mirror) * *m)) * (1.0 / k));
        let mut scale = scale;
        let illuminance = p.float("illuminance", -1.0)?;
        if illuminance > 0.0 {
            let image = crate::texture::open_image(&path)
                .map_err(|e| s.place.error(e))?
                .to_rgb32f();
            let n = image.width() as usize;
            let luminance = [0.212_639, 0.715_169, 0.072_192];
            let mut sum = 0.0;
            for (x, y, rgb) in image.enumerate_pixels() {
                let centre = glam::DVec2::new(
                    (f64::from(x) + 0.5) / n as f64,
                    (f64::from(y) + 0.5) / n as f64,
                );
                let w = crate::equal_area::square_to_sphere(centre);
                if w.z > 0.0 {
                    sum += (0..3)
                        .map(|c| f64::from(rgb.0[c]) * luminance[c])
                        .sum::<f64>()
                        * w.z;
                }
            }
            let k = sum * 2.0 * PI / (n * n) as f64;
            if !k.is_finite() || k <= 0.0 {
                return Err(s.place.error(format!(
                    "{}: illuminance {illuminance} asked of an image whose own above the \
                     horizon (pbrt's sum) is {k}",
                    s.what()
                )));
            }
            scale *= illuminance / k;
        }
        let file = std::fs::canonicalize(&path).unwrap_or(path);
        let rows = (0..3).flat_map(|r| (0..3).map(move |c| turn.col(c)[r]));
        let mut t = table([
            ("type", string("environment")),
            ("file", string(&file.to_string_lossy())),
            ("projection", string("equal_area")),
            ("matrix", Toml::Array(rows.map(Toml::Float).collect())),
            ("scale", Toml::Float(scale)),
        ]);
        if flip_v {
            t.insert("flip_v".into(), Toml::Boolean(true));
        }
        Ok(t)
    }

    /// A `goniometric` light: a point light whose intensity is its image's (`filename`, in
    /// the equal-area map; pbrt-v4 reads it with the light's y and z swapped, so the image's
    /// +z pole is the light's +y) times `I` and `scale`, or scaled to `power` (its luminous
    /// power, so with an RGB `I` of luminance 1 the power in grinlight's unit).
    fn goniometric(&self, s: &Statement, m: &DMat4, scale: f64) -> Result<Table> {
        let p = &s.params;
        let colour = match self.emission(p, "I", &s.what())? {
            Emission::Rgb(rgb) => rgb,
            Emission::Spectral(_) => {
                return Err(s.place.error(format!(
                    "{}: a spectrum I is not supported on a goniometric light (give rgb I)",
                    s.what()
                )))
            }
        };
        let name = p.string("filename")?.ok_or_else(|| {
            s.place.error(format!(
                "{}: \"string filename\" is missing (pbrt renders it black)",
                s.what()
            ))
        })?;
        if !similarity(m).is_some_and(|k| (k - 1.0).abs() < 1e-9) {
            return Err(s.place.error(format!(
                "{}: the transform scales or shears the light (pbrt looks its image up along \
                 directions no longer of unit length)",
                s.what()
            )));
        }
        // The image's axes in grinlight's world: pbrt's light frame with y and z swapped.
        // grinlight's image frame is (c0, c90, −nadir), c90 = −nadir × c0.
        let swap = DMat3::from_cols(DVec3::X, DVec3::Z, DVec3::Y);
        let (axes, flip_v) = map_rotation(linear(&(mirror_map(self.mirror) * *m)) * swap);
        let (nadir, c0) = (-axes.z_axis, axes.x_axis);
        let path = self.scene.find(&name, &s.place)?;
        let file = std::fs::canonicalize(&path).unwrap_or(path);
        let mut t = table([
            ("type", string("goniometric")),
            ("file", string(&file.to_string_lossy())),
            ("position", vec3(self.point(m, DVec3::ZERO))),
            ("direction", vec3(nadir)),
            ("c0", vec3(c0)),
            ("color", vec3(colour)),
        ]);
        if flip_v {
            t.insert("flip_v".into(), Toml::Boolean(true));
        }
        let power = p.float("power", -1.0)?;
        match power > 0.0 {
            true => t.insert("power".into(), Toml::Float(power * scale)),
            false => t.insert("scale".into(), Toml::Float(scale)),
        };
        Ok(t)
    }

    /// A material statement's type and the name its grinlight material is given.
    fn material_kind(s: &Statement) -> (String, &str) {
        match s.directive.as_str() {
            "Material" => (s.text(0).to_string(), "material"),
            _ => (
                s.params.string("type").ok().flatten().unwrap_or_default(),
                s.text(0),
            ),
        }
    }

    /// Whether the current material reflects nothing (a black diffuse one).
    fn is_black(&mut self) -> Result<bool> {
        let Some(s) = self.graphics.material else {
            return Ok(false);
        };
        self.used_materials.insert(s);
        let textured = (s.params.take("reflectance")).is_some_and(|r| r.ty == "texture");
        Ok(Self::material_kind(s).0 == "diffuse"
            && !textured
            && self.rgb(&s.params, "reflectance", DVec3::splat(0.5), &s.what())? == DVec3::ZERO)
    }

    /// The current material, converted the first time a shape uses it; pbrt's default
    /// (diffuse, reflectance 0.5) if none was set.
    fn surface(&mut self) -> Result<Surface> {
        if let Some(s) = self.graphics.material {
            let key = s as *const Statement;
            self.used_materials.insert(key);
            if let Some(made) = self.converted_materials.get(&key) {
                return Ok(made.clone());
            }
            let (kind, wanted) = Self::material_kind(s);
            let made = self.material(&kind, &s.params, &s.what(), &s.place, wanted)?;
            self.converted_materials.insert(key, made.clone());
            return Ok(made);
        }
        let name = match &self.default_material {
            Some(n) => n.clone(),
            None => {
                let name = free_name(&self.lists.materials, "default-diffuse");
                let mut t = table([
                    ("type", string("diffuse")),
                    ("albedo", vec3(DVec3::splat(0.5))),
                ]);
                t.insert("name".into(), string(&name));
                self.lists.materials.push(t);
                self.default_material = Some(name.clone());
                name
            }
        };
        Ok(Surface::Material {
            name,
            ior: None,
            textured: false,
        })
    }

    /// Places every `ObjectInstance`: each shape of its object's definition converted with
    /// the graphics state it was given in, its transform the instance's composed with its own.
    fn place_instances(&mut self) -> Result<()> {
        // Each use writes its object's shapes out again, a triangle mesh's numbers and all: a
        // small file may place an object millions of times. Refused up front where what would
        // be written (a converted number is about 64 bytes with its text) does not fit.
        let mut numbers: u64 = 0;
        for (use_, _) in &self.instance_uses {
            if let Some(d) = self.instances.get(use_.text(0)) {
                let each: usize = d.shapes.iter().map(|(s, _)| 16 + s.params.values()).sum();
                numbers = numbers.saturating_add(each as u64);
            }
        }
        let needed = numbers.saturating_mul(64);
        if let (Some((first, _)), Some(free)) = (
            self.instance_uses.first(),
            crate::resources::available_memory(),
        ) {
            if needed > free {
                return Err(first.place.error(format!(
                    "{} object instances write their objects' {numbers} numbers out, about \
                     {} of memory; this machine has {} available (place fewer instances or \
                     give the meshes as PLY files, which an instance refers to)",
                    self.instance_uses.len(),
                    crate::resources::human(needed),
                    crate::resources::human(free)
                )));
            }
        }
        let saved = self.graphics.clone();
        for (use_, ctm) in std::mem::take(&mut self.instance_uses) {
            let name = use_.text(0);
            let shapes = match self.instances.get(name) {
                Some(d) => d.shapes.clone(),
                None => {
                    return Err(use_
                        .place
                        .error(format!("no object is named \"{}\"", cut(name))))
                }
            };
            for (shape, graphics) in shapes {
                self.graphics = Graphics {
                    ctm: ctm * graphics.ctm,
                    ..graphics
                };
                self.shape(shape)?;
            }
        }
        self.graphics = saved;
        Ok(())
    }

    /// A dielectric of relative index 1: the boundary of a medium behind an `interface`.
    fn index_matched(&mut self) -> String {
        if let Some(n) = &self.index_matched {
            return n.clone();
        }
        let name = free_name(&self.lists.materials, "index-matched");
        let mut t = table([("type", string("dielectric")), ("ior", Toml::Float(1.0))]);
        t.insert("name".into(), string(&name));
        self.lists.materials.push(t);
        self.index_matched = Some(name.clone());
        name
    }
}

impl<'s> Converter<'s> {
    fn shape(&mut self, s: &'s Statement) -> Result<()> {
        let p = &s.params;
        let what = s.what();
        if p.float("alpha", 1.0)? != 1.0 {
            return Err(s
                .place
                .error(format!("{what}: an alpha cut-out is not supported")));
        }
        let g = self.graphics.clone();
        let interface = g.material.is_some_and(|m| {
            matches!(Self::material_kind(m).0.as_str(), "interface" | "none" | "")
        });
        match (&g.area, interface) {
            (Some(area), false) => return self.emitter(s, &g, area),
            (Some(area), true) => self.told.note(
                &area.place,
                format!(
                    "{what}: pbrt ignores an area light on an interface, and so does the import"
                ),
            ),
            (None, _) => {}
        }
        let surface = self.surface()?;
        let mut out = Table::new();
        // pbrt's shape changes the ray's medium only where its inside and outside differ.
        let transition = g.inside != g.outside;
        match (&surface, &g.inside) {
            (Surface::Interface, inside) if !transition || inside.is_none() => {
                self.told.note(
                    &s.place,
                    format!("{what} is an interface with no medium inside: invisible, left out"),
                );
                self.geometry(s, &g, false, false)?;
                return p.finish(&what);
            }
            (Surface::Interface, inside) => {
                let inside = inside.as_deref().expect("matched above");
                let name = self.medium(inside, &Eta::Constant(1.0))?;
                out.insert("material".into(), string(&self.index_matched()));
                out.insert("interior".into(), string(&name));
            }
            (Surface::Material { name, ior, .. }, inside) => {
                out.insert("material".into(), string(name));
                match (ior, inside) {
                    (_, _) if !transition => {}
                    (Some(eta), Some(inside)) => {
                        let name = self.medium(inside, eta)?;
                        out.insert("interior".into(), string(&name));
                    }
                    (None, Some(_)) => {
                        return Err(s.place.error(format!(
                            "{what} has a medium inside but its material lets no light in"
                        )))
                    }
                    (_, None) => {}
                }
            }
        }
        if transition && g.outside != self.ambient_pbrt {
            match &g.outside {
                Some(outside) => {
                    let name = self.medium(outside, &Eta::Constant(1.0))?;
                    out.insert("exterior".into(), string(&name));
                }
                None => {
                    let ambient = self.ambient.clone().unwrap_or_default();
                    self.told.approximate(
                        &s.place,
                        format!(
                            "{what} names no outside medium: pbrt's light leaves it in vacuum, \
                             grinlight's in '{ambient}', the camera's medium"
                        ),
                    )?;
                }
            }
        }
        let turn = match g.material.is_none_or(scatters_about_the_normal) {
            true => self.normal_turn(s, &g)?,
            false => 0.0,
        };
        if turn > FACES_TOLERANCE {
            self.told.approximate(
                &s.place,
                format!(
                    "{what}: pbrt evaluates its material about the mesh's interpolated \
                     normals N (cosines and hemisphere), which turn up to {:.2}° from its \
                     faces', grinlight a diffuse or rough surface's about each triangle's own \
                     (Mitsuba 3.9.1, which does as pbrt, against grinlight on an 80-face \
                     icosphere, 20°: blocks up to 1 % apart)",
                    turn.to_degrees()
                ),
            )?;
        }
        let dielectric = matches!(surface, Surface::Material { ior: Some(_), .. });
        let textured = matches!(surface, Surface::Material { textured: true, .. });
        if textured {
            self.has_pbrts_uv(s)?;
        }
        for (k, v) in self.geometry(s, &g, dielectric, textured)? {
            out.insert(k, v);
        }
        p.finish(&what)?;
        self.lists.shapes.push(out);
        Ok(())
    }

    /// A `plymesh`'s triangles, read once a statement however many instances place it.
    fn ply_mesh(
        &mut self,
        s: &'s Statement,
    ) -> Result<std::rc::Rc<crate::scene::mesh::ObjTriangles>> {
        if let Some(mesh) = self.plys.get(&(s as *const Statement)) {
            return Ok(mesh.clone());
        }
        let path = self.ply_file(s)?;
        let mesh =
            std::rc::Rc::new(crate::scene::ply::load_ply(&path).map_err(|e| s.place.error(e))?);
        self.plys.insert(s, mesh.clone());
        Ok(mesh)
    }

    /// How far the normals pbrt interpolates over shape `s` (placed by `g`) turn from its
    /// faces' ([`normal_turn`], radians): a mesh's `N` (a `trianglemesh`'s, a `plymesh`
    /// file's — read here for it); 0 for a mesh without them (pbrt then shades each triangle
    /// by its own normal) and for every other shape.
    fn normal_turn(&mut self, s: &'s Statement, g: &Graphics) -> Result<f64> {
        let (positions, triangles, normals): (Vec<DVec3>, Vec<[u32; 3]>, Option<Vec<DVec3>>) =
            match s.text(0) {
                "trianglemesh" => {
                    let mesh = TriangleMesh::read(s)?;
                    let vectors = |v: &[f64]| v.chunks_exact(3).map(DVec3::from_slice).collect();
                    let triangles = (mesh.indices.chunks_exact(3))
                        .map(|t| [t[0], t[1], t[2]])
                        .collect();
                    (
                        vectors(&mesh.points),
                        triangles,
                        mesh.normals.as_deref().map(vectors),
                    )
                }
                "plymesh" => {
                    let mesh = self.ply_mesh(s)?;
                    let vector = |v: &[f32; 3]| DVec3::from(v.map(f64::from));
                    (
                        mesh.positions.iter().map(vector).collect(),
                        mesh.triangles.clone(),
                        (mesh.normals.as_ref()).map(|n| n.iter().map(vector).collect()),
                    )
                }
                _ => return Ok(0.0),
            };
        let Some(normals) = normals else {
            return Ok(0.0);
        };
        let to_normal = linear(&g.ctm).inverse().transpose();
        let corner = |i: u32| g.ctm.transform_point3(positions[i as usize]);
        let normal = |i: u32| to_normal * normals[i as usize];
        Ok(normal_turn(&triangles, &corner, Some(&normal)))
    }

    /// Whether a mesh's triangles must be wound the other way for grinlight's normal
    /// (the winding's) to be pbrt's: its `ReverseOrientation`, a mirroring transform, and
    /// the scene's negated x each turn it over.
    fn turned(&self, g: &Graphics) -> bool {
        g.reverse ^ (linear(&g.ctm).determinant() < 0.0) ^ self.mirror
    }

    /// Refuses a textured shape whose (u, v) grinlight cannot read as pbrt-v4 does: a disk
    /// (pbrt's (φ/2π, (R − r)/(R − r_inner)) is no frame's), a triangle mesh without `uv` (pbrt
    /// gives each triangle's corners (0, 0), (1, 0), (1, 1); grinlight reads the corners'
    /// weights) and a bilinear patch given its own.
    fn has_pbrts_uv(&mut self, s: &'s Statement) -> Result<()> {
        let refuse = |why: &str| {
            Err(s
                .place
                .error(format!("{}: a texture on it: {why}", s.what())))
        };
        match s.text(0) {
            "disk" => {
                refuse("pbrt's disk (u, v) = (φ/2π, (R − r)/(R − r_inner)) is not grinlight's")
            }
            "trianglemesh" if TriangleMesh::read(s)?.uv.is_none() => refuse(
                "it gives no \"uv\" (pbrt's triangles then read (0, 0), (1, 0), (1, 1) at their \
                 corners, grinlight's the corners' weights)",
            ),
            "plymesh" if self.ply_mesh(s)?.texcoords.is_none() => refuse(
                "its file gives no texture coordinates (pbrt's triangles then read (0, 0), \
                 (1, 0), (1, 1) at their corners, grinlight's the corners' weights)",
            ),
            "bilinearmesh" if s.params.has("uv") => refuse("a patch's own \"uv\" is not read"),
            _ => Ok(()),
        }
    }

    /// A textured round shape's frame and `v_from_top`: pbrt's (u, v) are a sphere's and a
    /// cylinder's in their object space (φ from x toward y), which `m` places in pbrt's world
    /// and the scene's negated x in grinlight's.
    fn object_frame(&self, m: &DMat4, v_from_top: bool) -> ([DVec3; 3], bool) {
        let [x, y, z] = [DVec3::X, DVec3::Y, DVec3::Z].map(|a| self.vector(m, a));
        (local_frame(z, x, y), v_from_top)
    }

    /// The geometry keys of a shape; `oriented`: its inside and outside differ in grinlight
    /// (a dielectric), so its orientation must be kept; `textured`: a texture is looked up at
    /// its (u, v), which must then be pbrt's (a sphere's and a cylinder's in their object
    /// frame, `uv_frame`; a bilinear patch's corners in pbrt's order).
    fn geometry(
        &mut self,
        s: &Statement,
        g: &Graphics,
        oriented: bool,
        textured: bool,
    ) -> Result<Table> {
        let p = &s.params;
        let m = g.ctm;
        let uniform = |what: &str| -> Result<f64> {
            similarity(&m).ok_or_else(|| {
                s.place.error(format!(
                    "the transform scales unevenly or shears the {what}: not supported"
                ))
            })
        };
        let full = |name: &str, value: f64, default: f64| -> Result<()> {
            match value == default {
                true => Ok(()),
                false => Err(s.place.error(format!(
                    "{}: a partial shape ({name} {value}) is not supported",
                    s.what()
                ))),
            }
        };
        Ok(match s.text(0) {
            "sphere" => {
                let (center, radius) = self.sphere(s, g)?;
                // pbrt's v = (θ − θ(zmin))/(θ(zmax) − θ(zmin)) = 1 − θ/π of a whole sphere:
                // the frame's θ/π read from the top.
                with_uv_frame(
                    table([
                        ("type", string("sphere")),
                        ("center", vec3(center)),
                        ("radius", Toml::Float(radius)),
                    ]),
                    textured.then(|| self.object_frame(&m, true)),
                )
            }
            "disk" => {
                let (height, radius) = (p.float("height", 0.0)?, p.float("radius", 1.0)?);
                let inner = p.float("innerradius", 0.0)?;
                full("phimax", p.float("phimax", 360.0)?, 360.0)?;
                let k = uniform("disk")?;
                let mut t = table([
                    ("type", string("disk")),
                    ("center", vec3(self.point(&m, DVec3::new(0.0, 0.0, height)))),
                    ("normal", vec3(self.normal(&m, DVec3::Z))),
                    ("radius", Toml::Float(radius * k)),
                ]);
                if inner > 0.0 {
                    t.insert("inner_radius".into(), Toml::Float(inner * k));
                }
                t
            }
            "cylinder" => {
                let radius = p.float("radius", 1.0)?;
                let (zmin, zmax) = (p.float("zmin", -1.0)?, p.float("zmax", 1.0)?);
                full("phimax", p.float("phimax", 360.0)?, 360.0)?;
                let k = uniform("cylinder")?;
                let (lo, hi) = (zmin.min(zmax), zmin.max(zmax));
                if hi <= lo {
                    return Err(s.place.error("the cylinder has no height (zmin = zmax)"));
                }
                let axis = self.vector(&m, DVec3::Z).normalize();
                // pbrt's v = (z − zmin)/(zmax − zmin): the height from the base.
                with_uv_frame(
                    table([
                        ("type", string("cylinder")),
                        ("base", vec3(self.point(&m, DVec3::new(0.0, 0.0, lo)))),
                        ("axis", vec3(axis)),
                        ("radius", Toml::Float(radius * k)),
                        ("height", Toml::Float((hi - lo) * k)),
                        // pbrt's cylinder is open.
                        ("capped", Toml::Boolean(false)),
                    ]),
                    textured.then(|| self.object_frame(&m, false)),
                )
            }
            "trianglemesh" => {
                let mesh = TriangleMesh::read(s)?;
                let mut indices = mesh.indices.clone();
                if self.turned(g) {
                    for t in indices.chunks_exact_mut(3) {
                        t.swap(1, 2);
                    }
                }
                let placed = mirror_map(self.mirror) * m;
                let mut t = table([
                    ("type", string("mesh")),
                    ("points", floats(&mesh.points)),
                    (
                        "indices",
                        Toml::Array(indices.iter().map(|&i| Toml::Integer(i as i64)).collect()),
                    ),
                    ("matrix", affine_rows(&placed)),
                    ("smooth", Toml::Boolean(mesh.normals.is_some())),
                ]);
                if let Some(n) = &mesh.normals {
                    t.insert("normals".into(), floats(n));
                }
                if let Some(uv) = &mesh.uv {
                    t.insert("uv".into(), floats(uv));
                }
                t
            }
            "plymesh" => {
                let path = self.ply_file(s)?;
                if oriented && self.turned(g) {
                    return Err(s.place.error(
                        "a glass PLY mesh turned inside out (ReverseOrientation, a mirroring \
                         transform or the scene's negated x): grinlight takes a mesh's inside \
                         from its file's winding",
                    ));
                }
                let file = std::fs::canonicalize(&path).unwrap_or(path);
                table([
                    ("type", string("mesh")),
                    ("file", string(&file.to_string_lossy())),
                    ("matrix", affine_rows(&(mirror_map(self.mirror) * m))),
                ])
            }
            "bilinearmesh" => {
                let (corners, _) = self.bilinear_quad(s, g, !textured)?;
                table([
                    ("type", string("quad")),
                    (
                        "vertices",
                        Toml::Array(corners.into_iter().map(vec3).collect()),
                    ),
                ])
            }
            other => {
                return Err(s.place.error(format!(
                    "the shape \"{}\" is not supported by grinlight's import (sphere, disk, \
                     cylinder, trianglemesh, plymesh, bilinearmesh are)",
                    cut(other)
                )))
            }
        })
    }

    /// The file a `plymesh` names, found as the scene finds its files.
    fn ply_file(&self, s: &Statement) -> Result<std::path::PathBuf> {
        let name = s.params.string("filename")?.ok_or_else(|| {
            s.place
                .error(format!("{}: \"string filename\" is missing", s.what()))
        })?;
        self.scene.find(&name, &s.place)
    }

    /// A whole `sphere` (`radius` 1) in grinlight's world: its centre and radius.
    fn sphere(&self, s: &Statement, g: &Graphics) -> Result<(DVec3, f64)> {
        let p = &s.params;
        let radius = p.float("radius", 1.0)?;
        for (name, value, whole) in [
            ("zmin", p.float("zmin", -radius)?, -radius),
            ("zmax", p.float("zmax", radius)?, radius),
            ("phimax", p.float("phimax", 360.0)?, 360.0),
        ] {
            if value != whole {
                return Err(s.place.error(format!(
                    "{}: a partial shape ({name} {value}) is not supported",
                    s.what()
                )));
            }
        }
        let k = similarity(&g.ctm).ok_or_else(|| {
            s.place
                .error("the transform scales unevenly or shears the sphere: not supported")
        })?;
        Ok((self.point(&g.ctm, DVec3::ZERO), radius * k))
    }

    /// A `bilinearmesh` of one flat parallelogram patch: its corners in grinlight's world,
    /// ordered to face pbrt's normal, and that normal.
    fn bilinear_quad(
        &self,
        s: &Statement,
        g: &Graphics,
        facing_normal: bool,
    ) -> Result<([DVec3; 4], DVec3)> {
        let p = &s.params;
        let points = p
            .numbers("P", &["point3", "point"])?
            .map(|(v, _)| v)
            .unwrap_or_default();
        let indices = match p.numbers("indices", &["integer"])? {
            Some((v, _)) => v,
            None => vec![0.0, 1.0, 2.0, 3.0],
        };
        if points.len() != 12 || indices != [0.0, 1.0, 2.0, 3.0] {
            return Err(s.place.error(
                "a bilinear mesh of more than one patch is not supported (one patch of 4 \
                 points)",
            ));
        }
        let at = |i: usize| self.point(&g.ctm, DVec3::from_slice(&points[3 * i..3 * i + 3]));
        // pbrt's patch: p00, p10, p01, p11.
        let (p00, p10, p01, p11) = (at(0), at(1), at(2), at(3));
        let size = (p10 - p00).length() + (p01 - p00).length();
        if (p10 + p01 - p00 - p11).length() > 1e-9 * size {
            return Err(s
                .place
                .error("the bilinear patch is not a flat parallelogram (grinlight's quads are)"));
        }
        // pbrt's normal ∂p/∂u × ∂p/∂v in its world, turned by ReverseOrientation and a
        // mirroring transform; in grinlight's world it is turned again by the negated x.
        let at_pbrt = |i: usize| {
            g.ctm
                .transform_point3(DVec3::from_slice(&points[3 * i..3 * i + 3]))
        };
        let mut n = (at_pbrt(1) - at_pbrt(0)).cross(at_pbrt(2) - at_pbrt(0));
        if g.reverse ^ (linear(&g.ctm).determinant() < 0.0) {
            n = -n;
        }
        let normal = (linear(&mirror_map(self.mirror)) * n).normalize();
        if !normal.is_finite() {
            return Err(s.place.error("the bilinear patch has no area"));
        }
        let corners = [p00, p10, p11, p01];
        match facing_normal {
            true => Ok((facing(corners, normal), normal)),
            false => Ok((corners, normal)),
        }
    }

    /// A `trianglemesh` of two triangles forming a parallelogram, in grinlight's world and
    /// ordered to face pbrt's normal: the first triangle's winding, turned by
    /// ReverseOrientation and a mirroring transform, or toward the shading normal where one is
    /// given. None for any other mesh.
    fn two_triangle_quad(&self, mesh: &TriangleMesh, g: &Graphics) -> Option<[DVec3; 4]> {
        let corner = |i: u32| {
            let i = i as usize;
            g.ctm
                .transform_point3(DVec3::from_slice(&mesh.points[3 * i..3 * i + 3]))
        };
        let tri = |t: usize| [0, 1, 2].map(|k| corner(mesh.indices[3 * t + k]));
        let quad = match mesh.indices.len() {
            6 => parallelogram([tri(0), tri(1)], false),
            _ => None,
        }?;
        let [a, b, c] = tri(0);
        let mut n = (b - a).cross(c - a);
        match &mesh.normals {
            Some(normals) => {
                let i = 3 * mesh.indices[0] as usize;
                let ns =
                    linear(&g.ctm).inverse().transpose() * DVec3::from_slice(&normals[i..i + 3]);
                if n.dot(ns) < 0.0 {
                    n = -n;
                }
            }
            None if g.reverse ^ (linear(&g.ctm).determinant() < 0.0) => n = -n,
            None => {}
        }
        let r = linear(&mirror_map(self.mirror));
        let normal = (r * n).normalize();
        let corners = quad.map(|v| r * v);
        Some(facing(corners, normal))
    }

    /// An emitting mesh under `g` whose triangles `file` gives in pbrt's object space, and
    /// `keys`, the light's keys saying where they come from: placed by its matrix, emitting
    /// on the side pbrt's does — each triangle's winding in pbrt's world turned by
    /// ReverseOrientation and a mirroring transform, or the side its shading normals point
    /// to where the mesh has them. `power` (pbrt's per triangle: each its own light) is
    /// refused unless the triangles' areas are equal.
    fn emitting_mesh(
        &self,
        s: &Statement,
        g: &Graphics,
        file: &FileMesh,
        mut keys: Table,
        power: Option<f64>,
    ) -> Result<AreaEmitter> {
        let corner = |i: u32| self.point(&g.ctm, file.positions[i as usize]);
        let world: Vec<[DVec3; 3]> = file.triangles.iter().map(|t| t.map(corner)).collect();
        let turned = g.reverse ^ (linear(&g.ctm).determinant() < 0.0);
        let to_grinlight = linear(&mirror_map(self.mirror));
        // pbrt's normal of triangle i at each corner, in grinlight's world.
        let normal = |i: usize| -> [DVec3; 3] {
            let t = file.triangles[i];
            match &file.normals {
                Some(n) => t.map(|k| self.normal(&g.ctm, n[k as usize])),
                None => {
                    let [a, b, c] = t.map(|k| g.ctm.transform_point3(file.positions[k as usize]));
                    let w = (b - a).cross(c - a);
                    [to_grinlight * if turned { -w } else { w }; 3]
                }
            }
        };
        match emitting_side(world.iter().copied(), Some(&normal), false) {
            Facing::Winding => {}
            Facing::Against => {
                keys.insert("flip".into(), Toml::Boolean(true));
            }
            Facing::Mixed { against, split, of } => {
                return Err(s.place.error(format!(
                    "an area light on a mesh whose triangles emit on different sides of their \
                     winding ({against} of {of} one way, {split} with normals on both sides): \
                     grinlight's mesh lights emit on one side of every triangle's winding"
                )))
            }
        }
        let areas: Vec<f64> = world.iter().map(triangle_area).collect();
        let (least, most) = (areas.iter()).fold((f64::INFINITY, 0.0f64), |(lo, hi), &a| {
            (lo.min(a), hi.max(a))
        });
        if power.is_some() && most - least > 1e-9 * most {
            return Err(s.place.error(format!(
                "`power` on a mesh of triangles of different areas ({least:e} to {most:e}): \
                 pbrt makes each triangle a light emitting that power, so their radiances \
                 differ; grinlight's mesh light has one radiance (give L)"
            )));
        }
        keys.insert(
            "matrix".into(),
            affine_rows(&(mirror_map(self.mirror) * g.ctm)),
        );
        Ok(AreaEmitter::Mesh {
            keys,
            area: areas.iter().sum(),
        })
    }

    /// A shape under an `AreaLightSource`: a quad or disk light.
    fn emitter(&mut self, s: &Statement, g: &Graphics, area: &AreaLight) -> Result<()> {
        let p = &s.params;
        let what = s.what();
        // The surface, and how many lights pbrt makes of it (one per triangle).
        let (emitter, lights) = match s.text(0) {
            "trianglemesh" => {
                let mesh = TriangleMesh::read(s)?;
                match self.two_triangle_quad(&mesh, g) {
                    Some(quad) => (AreaEmitter::Quad(quad), 2.0),
                    None => {
                        let keys = table([
                            ("type", string("mesh")),
                            ("points", floats(&mesh.points)),
                            (
                                "indices",
                                Toml::Array(
                                    (mesh.indices.iter())
                                        .map(|&i| Toml::Integer(i as i64))
                                        .collect(),
                                ),
                            ),
                        ]);
                        let file = FileMesh {
                            positions: mesh.points.chunks_exact(3).map(DVec3::from_slice).collect(),
                            triangles: (mesh.indices.chunks_exact(3))
                                .map(|t| [t[0], t[1], t[2]])
                                .collect(),
                            normals: (mesh.normals.as_ref())
                                .map(|n| n.chunks_exact(3).map(DVec3::from_slice).collect()),
                        };
                        let emitter = self.emitting_mesh(s, g, &file, keys, area.power)?;
                        (emitter, file.triangles.len() as f64)
                    }
                }
            }
            "plymesh" => {
                let path = self.ply_file(s)?;
                let ply = crate::scene::ply::load_ply(&path).map_err(|e| s.place.error(e))?;
                let f64s = |v: &[f32; 3]| DVec3::from_array(v.map(f64::from));
                let file = FileMesh {
                    positions: ply.positions.iter().map(f64s).collect(),
                    triangles: ply.triangles,
                    normals: ply.normals.map(|n| n.iter().map(f64s).collect()),
                };
                let path = std::fs::canonicalize(&path).unwrap_or(path);
                let keys = table([
                    ("type", string("mesh")),
                    ("file", string(&path.to_string_lossy())),
                ]);
                let emitter = self.emitting_mesh(s, g, &file, keys, area.power)?;
                (emitter, file.triangles.len() as f64)
            }
            "bilinearmesh" => (AreaEmitter::Quad(self.bilinear_quad(s, g, true)?.0), 1.0),
            "sphere" => {
                if g.reverse || linear(&g.ctm).determinant() < 0.0 {
                    return Err(s.place.error(
                        "a sphere light turned inside out (ReverseOrientation or a mirroring \
                         transform): grinlight's sphere lights emit outward",
                    ));
                }
                let (center, radius) = self.sphere(s, g)?;
                (AreaEmitter::Sphere { center, radius }, 1.0)
            }
            "disk" => {
                if linear(&g.ctm).determinant() < 0.0 {
                    return Err(s.place.error(
                        "a disk light under a mirroring transform: pbrt-v4 emits it on one side \
                         when hit and samples it on the other",
                    ));
                }
                let (height, radius) = (p.float("height", 0.0)?, p.float("radius", 1.0)?);
                if p.float("innerradius", 0.0)? != 0.0 || p.float("phimax", 360.0)? != 360.0 {
                    return Err(s.place.error("a disk light must be a whole disk"));
                }
                let k = similarity(&g.ctm).ok_or_else(|| {
                    s.place
                        .error("the transform scales unevenly or shears the disk light")
                })?;
                let mut normal = self.normal(&g.ctm, DVec3::Z);
                if g.reverse {
                    normal = -normal;
                }
                let center = self.point(&g.ctm, DVec3::new(0.0, 0.0, height));
                (
                    AreaEmitter::Disk {
                        center,
                        normal,
                        radius: radius * k,
                    },
                    1.0,
                )
            }
            other => {
                return Err(s.place.error(format!(
                    "an area light on a \"{}\": grinlight's area lights are triangle meshes \
                     (PLY or not), bilinear patches, disks and spheres",
                    cut(other)
                )))
            }
        };
        p.finish(&what)?;
        if !self.is_black()? {
            self.told.approximate(
                &area.place,
                format!(
                    "{what}'s surface reflects light in pbrt; grinlight's area lights reflect \
                     nothing (exact for a black diffuse material)"
                ),
            )?;
        }
        // pbrt's `power` is the flux of each light it makes: one per triangle, patch, disk or
        // sphere, L = Φ/(π A) with A that one's area.
        let radiance = match area.power {
            Some(power) => area
                .radiance
                .clone()
                .times(power / (PI * emitter.area() / lights)),
            None => area.radiance.clone(),
        };
        let mut light = emitter.light();
        radiance.put(&mut light, "radiance")?;
        self.lists.lights.push(light);
        Ok(())
    }
}

/// A mesh as its statement or file gives it, in pbrt's object space.
struct FileMesh {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// One normal a position, if given.
    normals: Option<Vec<DVec3>>,
}

/// A `trianglemesh`'s lists as written.
struct TriangleMesh {
    /// `P`, 3 numbers a vertex.
    points: Vec<f64>,
    /// `indices`, 3 a triangle.
    indices: Vec<u32>,
    /// `N`, 3 numbers a vertex.
    normals: Option<Vec<f64>>,
    /// `uv`, 2 numbers a vertex.
    uv: Option<Vec<f64>>,
}

impl TriangleMesh {
    fn read(s: &Statement) -> Result<TriangleMesh> {
        let p = &s.params;
        let what = s.what();
        let (points, _) = p
            .numbers("P", &["point3", "point"])?
            .ok_or_else(|| s.place.error(format!("{what}: \"point3 P\" is missing")))?;
        if points.is_empty() || points.len() % 3 != 0 {
            return Err(s
                .place
                .error(format!("{what}: P must hold 3 numbers a vertex")));
        }
        let vertices = points.len() / 3;
        let indices = match p.numbers("indices", &["integer"])? {
            Some((v, _)) => v,
            None if vertices == 3 => vec![0.0, 1.0, 2.0],
            None => {
                return Err(s.place.error(format!(
                    "{what}: \"integer indices\" is missing (only a single triangle may leave \
                     it out)"
                )))
            }
        };
        if indices.is_empty()
            || indices.len() % 3 != 0
            || indices
                .iter()
                .any(|&i| i < 0.0 || i.fract() != 0.0 || i >= vertices as f64)
        {
            return Err(s.place.error(format!(
                "{what}: indices must be 3 a triangle, whole numbers from 0 to {}",
                vertices - 1
            )));
        }
        let per_vertex = |name: &str, types: &[&str], n: usize| -> Result<Option<Vec<f64>>> {
            match p.numbers(name, types)? {
                None => Ok(None),
                Some((v, _)) if v.len() == n * vertices => Ok(Some(v)),
                Some((_, param)) => Err(param.place.error(format!(
                    "{}: expected {n} numbers for each of the {vertices} vertices",
                    param.what()
                ))),
            }
        };
        let normals = per_vertex("N", &["normal", "normal3"], 3)?;
        let uv = per_vertex("uv", &["point2", "float"], 2)?;
        Ok(TriangleMesh {
            points,
            indices: indices.into_iter().map(|i| i as u32).collect(),
            normals,
            uv,
        })
    }
}
