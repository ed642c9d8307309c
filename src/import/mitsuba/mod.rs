//! Mitsuba 3 scenes (XML, versions 2.x and 3.x) converted to grinlight's scene schema: each
//! plugin and parameter either converted exactly, approximated (only when asked, each
//! approximation listed), or refused naming its file, line and element. `docs/import.md`
//! lists every conversion and its conventions.

mod spectrum;
pub mod xml;

use super::geometry::{
    axis_scales, emitting_side, linear, local_frame, normal_turn, parallelogram, similarity,
    triangle_area, Facing, FACES_TOLERANCE,
};
use super::table::{
    absorption, affine_rows, free_name, pixel_filter_keys, string, table, vec3, with_uv_frame,
    AreaEmitter, Lists,
};
use super::{Imported, Place, Told};
use crate::bsdf::Distribution;
use crate::error::{cut, Result};
use crate::pixel_filter::PixelFilter;
use glam::{DMat3, DMat4, DVec3};
use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::rc::Rc;
use toml::{Table, Value as Toml};
use xml::{Document, Object};

/// Mitsuba's named indices of refraction (its `ior.h`, read back from Mitsuba 3.9.1).
const NAMED_IOR: [(&str, f64); 23] = [
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// Mitsuba's conductors whose measured η + ik grinlight has (from the same handbook data).
const METALS: [&str; 4] = ["Ag", "Al", "Au", "Cu"];

/// The 35 mm film diagonal Mitsuba turns a `focal_length` into a diagonal field of view with.
const FILM_DIAGONAL_MM: f64 = 43.266_615_305_567_87;

/// Converts the scene read from `doc`; `approximate` lets what converts only approximately
/// through (each one listed).
pub fn convert(doc: &Document, approximate: bool) -> Result<Imported> {
    let mut c = Converter {
        doc,
        told: Told::new(approximate),
        lists: Lists::default(),
        material_names: HashMap::new(),
        medium_names: HashMap::new(),
        environment: None,
        ambient: None,
        one_sided: Vec::new(),
        made: HashMap::new(),
        repeated_delta_lights: None,
        attached: HashSet::new(),
        hide_emitters: None,
        see_through: SeeThrough::default(),
        meshes: HashMap::new(),
    };
    let scene = doc.scene.clone();
    let mut table = Table::new();
    let sensors = scene.children("sensor");
    let sensor = match sensors.as_slice() {
        [one] => one,
        [] => {
            return Err(scene.error("the scene has no <sensor>: grinlight renders a camera's view"))
        }
        [_, second, ..] => {
            return Err(second
                .place
                .error("a second <sensor>: grinlight renders one camera's view"))
        }
    };
    let mut render = c.sensor(sensor.object(), &mut table)?;
    c.integrator(&scene, &mut render)?;
    let mut declared_areas = Vec::new();
    for child in scene.all_children() {
        Object::mark(child);
        match child.object().tag.as_str() {
            "shape" => c.shape(child.object())?,
            // Defined here for a <ref> in a shape, and converted there.
            "emitter" if child.object().kind == "area" && child.object().id.is_some() => {
                declared_areas.push(child);
            }
            "emitter" => c.emitter(child.object())?,
            // Converted where shapes, emitters and the sensor refer to them.
            "bsdf" | "texture" | "medium" | "phase" | "volume" | "sensor" | "integrator" => {}
            // Defined here for a <ref> in the sensor.
            "film" | "sampler" | "rfilter" if child.object().id.is_some() => {}
            "film" | "sampler" | "rfilter" => {
                return Err(child.place.error(format!(
                    "{} belongs inside the <sensor>",
                    child.object().what()
                )))
            }
            other => {
                return Err(child
                    .place
                    .error(format!("<{}> is not read at the top level", cut(other))))
            }
        }
    }
    if let Some(lone) =
        (declared_areas.iter()).find(|d| !c.attached.contains(&Rc::as_ptr(d.object())))
    {
        return Err(lone.place.error(format!(
            "{}: an area emitter no shape refers to: grinlight's area lights are shapes' (refer to it from one)",
            lone.object().what()
        )));
    }
    scene.finish()?;
    if !c.one_sided.is_empty() {
        let place = scene.place.clone();
        let list = c.one_sided.join(", ");
        c.told.note(
            &place,
            format!(
                "{list}: one-sided in Mitsuba (black from behind), two-sided in grinlight — \
                 the same wherever only their fronts are seen"
            ),
        );
    }
    c.hide_emitters(&mut table)?;
    if let Some(env) = c.environment.take() {
        c.lists.lights.push(env);
    }
    if let Some(ambient) = &c.ambient {
        table.insert("ambient".into(), Toml::String(ambient.clone()));
    }
    table.insert("render".into(), Toml::Table(render));
    std::mem::take(&mut c.lists).insert_into(&mut table);
    Ok(c.told.into_imported(table, doc.files.clone()))
}

/// How far the normals Mitsuba interpolates over `mesh` placed by `m` turn from its faces'
/// ([`normal_turn`]: the file's, or where it gives none Mitsuba's averages of the faces).
fn mesh_normal_turn(mesh: &crate::scene::mesh::ObjTriangles, m: &DMat4) -> f64 {
    let corner =
        |i: u32| m.transform_point3(DVec3::from(mesh.positions[i as usize].map(f64::from)));
    let to_normal = linear(m).inverse().transpose();
    let normal = mesh
        .normals
        .as_ref()
        .map(|n| move |k: u32| to_normal * DVec3::from(n[k as usize].map(f64::from)));
    normal_turn(
        &mesh.triangles,
        &corner,
        normal.as_ref().map(|f| f as &dyn Fn(u32) -> DVec3),
    )
}

/// Whether a BSDF scatters light about the surface's normal over a hemisphere (diffuse,
/// plastic and rough BSDFs), rather than only into mirror and refraction directions.
fn scatters_about_the_normal(bsdf: &Object) -> bool {
    match bsdf.kind.as_str() {
        "twosided" => bsdf
            .children("bsdf")
            .first()
            .is_some_and(|inner| scatters_about_the_normal(inner.object())),
        "conductor" | "dielectric" | "thindielectric" | "null" | "polarizer" => false,
        _ => true,
    }
}

/// The refusal of a spectrum `name` of `obj` whose colour is not a finite number.
fn not_finite(obj: &Object, name: &str) -> String {
    format!(
        "{}: '{name}': a spectrum whose colour is not a finite number (its values overflow)",
        obj.what()
    )
}

/// What a shape's BSDF became.
#[derive(Clone)]
enum Surface {
    /// A grinlight material; a dielectric's relative index inside; whether an image
    /// texture colours it (Mitsuba's (u, v) must then be the shape's in grinlight).
    Material {
        name: String,
        ior: Option<f64>,
        textured: bool,
    },
    /// Mitsuba's `null`: no surface (a medium's boundary only).
    Null,
}

/// A sensor's film as grinlight's camera takes it.
struct SensorFilm {
    /// The `<film>` (None: Mitsuba's default film).
    object: Option<Rc<Object>>,
    /// Pixels across.
    width: i64,
    /// Pixels down.
    height: i64,
    /// Its pixel filter.
    filter: PixelFilter,
    /// Its crop window, `[x, y, width, height]` (None: the whole film).
    crop: Option<[i64; 4]>,
}

/// A rough surface's microsurface as a grinlight material's keys.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Roughness {
    /// Its α.
    alpha: f64,
    /// Its distribution of normals.
    distribution: Distribution,
}

impl Roughness {
    /// Writes `roughness` (and `distribution`, where it is not GGX, the default) into `m`.
    fn write(self, m: &mut Table) {
        m.insert("roughness".into(), Toml::Float(self.alpha));
        if self.distribution != Distribution::Ggx {
            m.insert("distribution".into(), string(self.distribution.name()));
        }
    }
}

struct Converter<'d> {
    doc: &'d Document,
    told: Told,
    /// The scene's arrays of tables, as made.
    lists: Lists,
    /// Each BSDF object converted, by address (one material however often it is used).
    material_names: HashMap<*const Object, Surface>,
    /// Each medium converted at an index (bits of n), by address.
    medium_names: HashMap<(*const Object, u64), String>,
    environment: Option<Table>,
    ambient: Option<String>,
    /// The BSDFs that are one-sided in Mitsuba (black from behind), two-sided here.
    one_sided: Vec<String>,
    /// The materials the import made itself, by their names.
    made: HashMap<Made, String>,
    /// Where a `direct` integrator takes more than one emitter sample, and how many: Mitsuba
    /// counts a delta light (point, spot, directional) that many times ([`Converter::emitter`]).
    repeated_delta_lights: Option<(Place, i64)>,
    /// The area emitters shapes carry, by address (a top-level one must be one of them).
    attached: HashSet<*const Object>,
    /// Where the integrator hides the emitters it sees directly, and its kind.
    hide_emitters: Option<(Place, String)>,
    /// The `null` BSDFs and the `thindielectric`s converted: where Mitsuba's integrators
    /// disagree on whether emitters seen through them are seen directly.
    see_through: SeeThrough,
    /// The mesh files read at conversion (to measure their normals, or an emitting mesh's
    /// side), by shape.
    meshes: HashMap<*const Object, Rc<crate::scene::mesh::ObjTriangles>>,
}

/// BSDFs a camera ray passes straight through, by kind ([`Converter::hide_emitters`]).
#[derive(Default)]
struct SeeThrough {
    /// `null` BSDFs: Mitsuba's `volpath` sees through them as through nothing (an emitter
    /// behind one is hidden), its `path` shows an area emitter behind one.
    null: Vec<String>,
    /// `thindielectric`s: Mitsuba's `path` shows an emitter behind one, its `volpath` hides it.
    thin: Vec<String>,
}

/// A material the import makes itself, not from a BSDF of the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Made {
    /// Mitsuba's default BSDF, for a shape without one.
    DefaultDiffuse,
    /// The index-matched boundary of a medium behind a `null` BSDF.
    IndexMatched,
}

impl Converter<'_> {
    /// A colour parameter: an `<rgb>`, a `<float>` or a `<spectrum>` of one value or of
    /// wavelength:value pairs, as Mitsuba's RGB variants read them ([`spectrum`]); a texture
    /// or a spectrum in a file is refused.
    fn colour(&mut self, obj: &Object, name: &str, default: f64) -> Result<DVec3> {
        if let Some(child) = obj.named_child(name) {
            return Err(child.place.error(format!(
                "{}: a {} as '{name}' is not supported by grinlight's import (give an rgb)",
                obj.what(),
                child.object().what()
            )));
        }
        let Some(p) = obj.property(name) else {
            return Ok(DVec3::splat(default));
        };
        let role = spectrum::Role::of(&obj.tag, name);
        match &p.value {
            xml::Value::Rgb(v) => Ok(*v),
            xml::Value::Float(x) => Ok(DVec3::splat(*x)),
            xml::Value::UniformSpectrum(x) => {
                spectrum::uniform(*x, role).ok_or_else(|| p.place.error(not_finite(obj, name)))
            }
            xml::Value::Integer(i) => Ok(DVec3::splat(*i as f64)),
            xml::Value::SampledSpectrum(s) => match spectrum::pairs(s) {
                Ok(pairs) => spectrum::sampled(&pairs, role)
                    .ok_or_else(|| p.place.error(not_finite(obj, name))),
                Err(why) => Err(p.place.error(format!("{}: '{name}': {why}", obj.what()))),
            },
            xml::Value::SpectrumFile(f) => Err(p.place.error(format!(
                "{}: '{name}' is a spectrum in a file (\"{}\"); grinlight's import reads an rgb, \
                 one number or wavelength:value pairs",
                obj.what(),
                cut(f)
            ))),
            other => Err(p.place.error(format!(
                "{}: '{name}' should be an rgb, a float or a spectrum, got {other:?}",
                obj.what()
            ))),
        }
    }

    /// A diffuse colour: `albedo` from an RGB (Mitsuba's default 0.5), or `texture` from a
    /// `bitmap` (an sRGB PNG or JPEG, bilinear and repeating as grinlight's textures are).
    fn albedo(&mut self, b: &Object, name: &str) -> Result<Table> {
        let Some(child) = b.named_child(name) else {
            return Ok(table([("albedo", vec3(self.colour(b, name, 0.5)?))]));
        };
        let tex = child.object().clone();
        if tex.tag == "texture" && tex.kind == "checkerboard" {
            let colours = [
                self.colour(&tex, "color0", 0.4)?,
                self.colour(&tex, "color1", 0.2)?,
            ];
            let mut t = table([(
                "checkerboard",
                Toml::Array(colours.into_iter().map(vec3).collect()),
            )]);
            t.extend(texture_uv(&tex)?);
            tex.finish()?;
            return Ok(t);
        }
        if tex.tag != "texture" || tex.kind != "bitmap" {
            return Err(tex.error(format!(
                "as '{name}': grinlight's import reads an rgb, a bitmap or a checkerboard \
                 texture"
            )));
        }
        let file = tex
            .string("filename")?
            .ok_or_else(|| tex.error("has no filename"))?
            .to_string();
        let ext = std::path::Path::new(&file)
            .extension()
            .map(|x| x.to_string_lossy().to_ascii_lowercase());
        if !matches!(ext.as_deref(), Some("png") | Some("jpg") | Some("jpeg")) {
            return Err(tex.error(format!(
                "'{}': grinlight's textures are sRGB PNG or JPEG images",
                cut(&file)
            )));
        }
        let path = self.doc.find(&file, &tex.place)?;
        let path = std::fs::canonicalize(&path).unwrap_or(path);
        if tex.boolean_or("raw", false)? {
            return Err(tex.error("raw = true: grinlight decodes a texture's sRGB"));
        }
        let filter = tex.string("filter_type")?.unwrap_or("bilinear").to_string();
        let wrap = tex.string("wrap_mode")?.unwrap_or("repeat").to_string();
        let known = ["bilinear", "nearest"].contains(&filter.as_str())
            && ["repeat", "clamp", "mirror"].contains(&wrap.as_str());
        if !known {
            return Err(tex.error(format!(
                "filter_type '{}' and wrap_mode '{}': Mitsuba's are bilinear or nearest, and \
                 repeat, clamp or mirror",
                cut(&filter),
                cut(&wrap)
            )));
        }
        let mut t = table([("texture", string(&path.to_string_lossy()))]);
        if filter != "bilinear" {
            t.insert("texture_filter".into(), string(&filter));
        }
        if wrap != "repeat" {
            t.insert("texture_wrap".into(), string(&wrap));
        }
        t.extend(texture_uv(&tex)?);
        tex.finish()?;
        Ok(t)
    }

    /// A colour parameter that must be 1 (Mitsuba's specular reflectance and transmittance
    /// factors, which no physical surface has).
    fn unit_factor(&mut self, obj: &Object, name: &str) -> Result<()> {
        let f = self.colour(obj, name, 1.0)?;
        if f != DVec3::ONE {
            let place = obj
                .property(name)
                .map_or(obj.place.clone(), |p| p.place.clone());
            return Err(place.error(format!(
                "{}: '{name}' = {:?}: grinlight's surfaces have no such factor (only 1 is read)",
                obj.what(),
                f.to_array()
            )));
        }
        Ok(())
    }

    /// An index of refraction: a number or one of Mitsuba's names.
    fn ior(&mut self, obj: &Object, name: &str, default: &str) -> Result<f64> {
        if let Some(x) = obj.float(name).ok().flatten() {
            return Ok(x);
        }
        let given = obj.string(name)?.unwrap_or(default).to_string();
        let named = NAMED_IOR
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(&given))
            .map(|&(_, n)| n);
        named.ok_or_else(|| {
            let names: Vec<&str> = NAMED_IOR.iter().map(|(n, _)| *n).collect();
            obj.error(format!(
                "'{name}' = \"{}\" is none of Mitsuba's named indices ({})",
                cut(&given),
                names.join(", ")
            ))
        })
    }

    /// The microsurface: α from `alpha` (or equal `alpha_u`, `alpha_v`), `distribution` GGX or
    /// Beckmann (Mitsuba's default). The masking differs by model, said in a note: Mitsuba's
    /// is the separable Smith G₁(ωi)G₁(ωo) (for Beckmann its rational fit to G₁, within
    /// 0.35 %), grinlight's the height-correlated one (and its rough dielectric keeps every
    /// order of scattering on the microsurface).
    fn roughness(&mut self, obj: &Object) -> Result<Roughness> {
        let place = obj.place.clone();
        self.told.note(
            &place,
            format!(
                "{}: grinlight's microfacet model masks with correlated heights (Mitsuba: \
                 separable) and a rough dielectric scatters on its microsurface more than once \
                 (Mitsuba: once): grazing highlights differ by a few percent, light through a \
                 rough dielectric more (a frosted ball of fog lit from behind: Mitsuba 3.9.1's \
                 image 0.86 of grinlight's)",
                obj.what()
            ),
        );
        let distribution = obj
            .string("distribution")?
            .unwrap_or("beckmann")
            .to_string();
        obj.ignore("sample_visible");
        let alpha = match (obj.float("alpha_u")?, obj.float("alpha_v")?) {
            (Some(u), Some(v)) if u == v => u,
            (Some(_), Some(_)) => {
                return Err(
                    obj.error("an anisotropic roughness (alpha_u ≠ alpha_v) is not supported")
                )
            }
            _ => obj.float_or("alpha", 0.1)?,
        };
        let Some(distribution) = Distribution::named(&distribution) else {
            return Err(obj.error(format!("unknown distribution '{}'", cut(&distribution))));
        };
        if !(0.0..=1.0).contains(&alpha) {
            return Err(obj.error(format!("alpha = {alpha} is outside grinlight's [0, 1]")));
        }
        Ok(Roughness {
            alpha,
            distribution,
        })
    }

    /// The material a BSDF becomes (each BSDF object once).
    fn bsdf(&mut self, bsdf: &Rc<Object>) -> Result<Surface> {
        let key = Rc::as_ptr(bsdf);
        if let Some(s) = self.material_names.get(&key) {
            return Ok(s.clone());
        }
        let (two_sided, inner) =
            match bsdf.kind.as_str() {
                "twosided" => {
                    let inner = bsdf.children("bsdf");
                    match inner.as_slice() {
                        [one] => (true, one.object().clone()),
                        _ => return Err(bsdf.error(
                            "a twosided BSDF with two different sides is not supported (give one \
                             nested BSDF)",
                        )),
                    }
                }
                _ => (false, bsdf.clone()),
            };
        if two_sided {
            bsdf.finish()?;
        }
        let surface = self.material(&inner, two_sided, bsdf.id.as_deref())?;
        self.material_names.insert(key, surface.clone());
        Ok(surface)
    }

    fn material(&mut self, b: &Object, two_sided: bool, id: Option<&str>) -> Result<Surface> {
        let one_sided = |c: &mut Self| {
            if !two_sided {
                c.one_sided.push(b.what());
            }
        };
        let (kind, mut m, ior) = match b.kind.as_str() {
            "null" => {
                b.finish()?;
                self.see_through.null.push(b.what());
                return Ok(Surface::Null);
            }
            "diffuse" => {
                one_sided(self);
                ("diffuse", self.albedo(b, "reflectance")?, None)
            }
            "dielectric" | "roughdielectric" => {
                let eta = self.ior(b, "int_ior", "bk7")? / self.ior(b, "ext_ior", "air")?;
                self.unit_factor(b, "specular_reflectance")?;
                self.unit_factor(b, "specular_transmittance")?;
                let mut m = table([("ior", Toml::Float(eta))]);
                if b.kind == "roughdielectric" {
                    self.roughness(b)?.write(&mut m);
                }
                ("dielectric", m, Some(eta))
            }
            "thindielectric" => {
                let eta = self.ior(b, "int_ior", "bk7")? / self.ior(b, "ext_ior", "air")?;
                self.unit_factor(b, "specular_reflectance")?;
                self.unit_factor(b, "specular_transmittance")?;
                let place = b.place.clone();
                self.told.thin_pane(&place, &b.what(), "Mitsuba");
                self.see_through.thin.push(b.what());
                ("thin_dielectric", table([("ior", Toml::Float(eta))]), None)
            }
            "conductor" | "roughconductor" => {
                one_sided(self);
                self.unit_factor(b, "specular_reflectance")?;
                let mut m = match (b.has("eta"), b.has("k")) {
                    (true, true) => table([
                        ("eta", vec3(self.colour(b, "eta", 0.0)?)),
                        ("k", vec3(self.colour(b, "k", 0.0)?)),
                    ]),
                    (false, false) => {
                        let name = b.string("material")?.unwrap_or("none").to_string();
                        let metal = match name.as_str() {
                            "none" => "perfect",
                            n if METALS.contains(&n) => n,
                            other => {
                                return Err(b.error(format!(
                                    "material '{}': grinlight has the measured metals {} (and \
                                     'none', a perfect mirror); give eta and k",
                                    cut(other),
                                    METALS.join(", ")
                                )))
                            }
                        };
                        table([("metal", string(metal))])
                    }
                    _ => return Err(b.error("give both eta and k, or neither")),
                };
                if b.kind == "roughconductor" {
                    self.roughness(b)?.write(&mut m);
                }
                ("conductor", m, None)
            }
            "plastic" | "roughplastic" => {
                one_sided(self);
                let mut base = self.albedo(b, "diffuse_reflectance")?;
                self.unit_factor(b, "specular_reflectance")?;
                let eta =
                    self.ior(b, "int_ior", "polypropylene")? / self.ior(b, "ext_ior", "air")?;
                // grinlight's plastic keeps the light scattered between the base and the
                // coat's inner side, ρ/(1 − ρ F̄ᵢ): Mitsuba's `nonlinear = true`.
                if !b.boolean_or("nonlinear", false)? {
                    let place = b.place.clone();
                    self.told.approximate(
                        &place,
                        format!(
                            "{}: Mitsuba's linear base (nonlinear = false, its default) taken as \
                             grinlight's, which keeps the light scattered between base and \
                             coat (as nonlinear = true)",
                            b.what()
                        ),
                    )?;
                }
                let roughness = match b.kind.as_str() {
                    "roughplastic" => {
                        let rough = self.roughness(b)?;
                        Roughness {
                            alpha: rough.alpha.max(1e-3),
                            ..rough
                        }
                    }
                    _ => {
                        let place = b.place.clone();
                        self.told.approximate(
                            &place,
                            format!(
                                "{}: a smooth coat taken as GGX α = 0.001, grinlight's smoothest",
                                b.what()
                            ),
                        )?;
                        Roughness {
                            alpha: 1e-3,
                            distribution: Distribution::Ggx,
                        }
                    }
                };
                base.insert("ior".into(), Toml::Float(eta));
                roughness.write(&mut base);
                let place = b.place.clone();
                self.told.note(
                    &place,
                    format!(
                        "{}: Mitsuba's rough plastic loses diffuse light its coat sends back \
                         to the base (its internal reflectance is the coat's single scattering: \
                         the diffuse light 6 % darker square on, up to 25 % at grazing, than \
                         the layer simulated ray by ray — docs/validation.md); grinlight's \
                         keeps it, so its plastic reads brighter",
                        b.what()
                    ),
                );
                ("plastic", base, None)
            }
            other => {
                return Err(b.error(format!(
                    "the BSDF '{}' is not supported by grinlight's import (diffuse, \
                     dielectric, roughdielectric, thindielectric, conductor, roughconductor, \
                     plastic, roughplastic, twosided, null are)",
                    cut(other)
                )))
            }
        };
        b.finish()?;
        let textured = m.contains_key("texture") || m.contains_key("checkerboard");
        let name = free_name(
            &self.lists.materials,
            id.or(b.id.as_deref()).unwrap_or("bsdf"),
        );
        m.insert("name".into(), string(&name));
        m.insert("type".into(), string(kind));
        self.lists.materials.push(m);
        Ok(Surface::Material {
            name,
            ior,
            textured,
        })
    }

    /// The grinlight medium a Mitsuba medium becomes at (relative) index `n`.
    fn medium(&mut self, medium: &Rc<Object>, n: f64) -> Result<String> {
        let key = (Rc::as_ptr(medium), n.to_bits());
        if let Some(name) = self.medium_names.get(&key) {
            return Ok(name.clone());
        }
        // A heterogeneous medium's σt is a grid of densities times `scale` (or a constant,
        // as a homogeneous one's).
        let grid = match medium.kind.as_str() {
            "homogeneous" => None,
            "heterogeneous" => {
                for tuning in ["majorant_resolution_factor", "majorant_factor"] {
                    medium.ignore(tuning);
                }
                // Mitsuba bounds a heterogeneous medium by its σt volume's box: a constant's
                // is not the shape's.
                let child = medium.named_child("sigma_t").ok_or_else(|| {
                    medium.error(
                        "a heterogeneous medium whose sigma_t is no gridvolume: grinlight's \
                         import reads a gridvolume here (a constant σt is a homogeneous medium)",
                    )
                })?;
                Some(self.density_grid(child)?)
            }
            other => {
                return Err(medium.error(format!(
                    "the medium '{}' is not supported by grinlight's import (homogeneous and \
                     heterogeneous are)",
                    cut(other)
                )))
            }
        };
        let scale = medium.float_or("scale", 1.0)?;
        let sigma_t = match grid {
            Some(_) => DVec3::splat(scale),
            None => self.colour(medium, "sigma_t", 1.0)? * scale,
        };
        let albedo = self.colour(medium, "albedo", 0.75)?;
        medium.ignore("sample_emitters");
        let sigma_a = sigma_t * (DVec3::ONE - albedo);
        let sigma_s = sigma_t * albedo;
        let mut m = table([("profile", string("uniform")), ("n", Toml::Float(n))]);
        m.extend(grid.unwrap_or_default());
        if sigma_a.max_element() > 0.0 {
            m.insert("absorption".into(), absorption(sigma_a));
        }
        if sigma_s.max_element() > 0.0 {
            m.insert("scattering".into(), vec3(sigma_s));
            if let Some(phase) = medium.child("phase")? {
                let p = &phase.object();
                match p.kind.as_str() {
                    "isotropic" => {}
                    "rayleigh" => {
                        m.insert("phase".into(), string("rayleigh"));
                    }
                    "hg" => {
                        let g = p.float_or("g", 0.8)?;
                        m.insert("phase".into(), Toml::Table(table([("hg", Toml::Float(g))])));
                    }
                    other => {
                        return Err(p.error(format!(
                        "the phase function '{}' is not supported (isotropic, hg and rayleigh are)",
                        cut(other)
                    )))
                    }
                }
                p.finish()?;
            }
        } else {
            medium.children("phase");
        }
        medium.finish()?;
        let name = free_name(&self.lists.media, medium.id.as_deref().unwrap_or("medium"));
        m.insert("name".into(), string(&name));
        self.lists.media.push(m);
        self.medium_names.insert(key, name.clone());
        Ok(name)
    }

    /// A heterogeneous medium's σt grid (a `gridvolume`) as a medium's density keys: the
    /// file's values at their nodes. Mitsuba 3 reads a grid of resolution r over the unit cube
    /// that `to_world` places, node i at (i + ½)/r, trilinear between nodes and clamped
    /// beyond the outer ones (checked against Mitsuba 3.9.1's own lookups,
    /// `bench/mitsuba_gridvolume.py`) — grinlight's density grid between its first and last
    /// nodes, clamped beyond them, which `density_bounds` places there. Its medium ends at
    /// the placed cube (heterogeneous.cpp tracks only within the grid's box): `density_end`.
    fn density_grid(&mut self, child: &xml::Child) -> Result<Table> {
        let grid = child.object().clone();
        if grid.tag != "volume" || grid.kind != "gridvolume" {
            return Err(grid.error(
                "as 'sigma_t': grinlight's import reads a gridvolume here (a constant σt is a \
                 homogeneous medium)",
            ));
        }
        let file = grid
            .string("filename")?
            .ok_or_else(|| grid.error("has no filename"))?
            .to_string();
        let path = self.doc.find(&file, &grid.place)?;
        let path = std::fs::canonicalize(&path).unwrap_or(path);
        let header = crate::scene::vol::header(&path)
            .map_err(|e| grid.error(format!("{}: {e}", path.display())))?;
        if header.channels != 1 {
            return Err(grid.error(format!(
                "{} channels: grinlight's σt grid is one density a node, times an rgb albedo",
                header.channels
            )));
        }
        if let Some(axis) = header.dims.iter().position(|&n| n < 2) {
            return Err(grid.error(format!(
                "{} value(s) along {}: grinlight's grids hold at least 2 a side",
                header.dims[axis],
                ["x", "y", "z"][axis]
            )));
        }
        let filter = grid
            .string("filter_type")?
            .unwrap_or("trilinear")
            .to_string();
        let wrap = grid.string("wrap_mode")?.unwrap_or("clamp").to_string();
        if filter != "trilinear" || wrap != "clamp" {
            return Err(grid.error(format!(
                "filter_type '{}' and wrap_mode '{}': grinlight's density grids are trilinear \
                 and clamped",
                cut(&filter),
                cut(&wrap)
            )));
        }
        if grid.boolean_or("use_grid_bbox", false)? {
            return Err(grid.error(
                "use_grid_bbox = true: grinlight places a grid by its to_world, as Mitsuba's \
                 default does",
            ));
        }
        let m = grid.transform("to_world")?;
        if !axis_scales(&m).is_some_and(|d| d.min_element() > 0.0) {
            return Err(grid.error(
                "a to_world that turns or mirrors the grid: grinlight's grids are axis-aligned",
            ));
        }
        grid.finish()?;
        let res = DVec3::from(header.dims.map(|n| n as f64));
        let first = m.transform_point3(0.5 / res);
        let last = m.transform_point3(DVec3::ONE - 0.5 / res);
        let (lo, hi) = (
            m.transform_point3(DVec3::ZERO),
            m.transform_point3(DVec3::ONE),
        );
        Ok(table([
            ("density_file", string(&path.to_string_lossy())),
            ("density_bounds", Toml::Array(vec![vec3(first), vec3(last)])),
            ("density_end", Toml::Array(vec![vec3(lo), vec3(hi)])),
        ]))
    }

    /// The camera (`[camera]` into `out`) and the sampler's settings (the `[render]` table
    /// returned).
    fn sensor(&mut self, s: &Object, out: &mut Table) -> Result<Table> {
        let thin_lens = match s.kind.as_str() {
            "perspective" => false,
            "thinlens" => true,
            "orthographic" => return self.orthographic_sensor(s, out),
            other => {
                return Err(s.error(format!(
                    "the sensor '{}' is not supported (perspective, thinlens and orthographic \
                     are)",
                    cut(other)
                )))
            }
        };
        let m = s.transform("to_world")?;
        let origin = m.transform_point3(DVec3::ZERO);
        let l = linear(&m);
        let (left, up, dir) = (l.x_axis, l.y_axis, l.z_axis);
        let Some(_) = similarity(&m) else {
            return Err(s.error(
                "to_world scales unevenly or shears: a camera's frame is turned and moved only",
            ));
        };
        let film = self.sensor_film(s, [left, up, dir])?;
        let (width, height) = (film.width, film.height);
        let (w, h) = (width as f64, height as f64);
        // Mitsuba's field of view on its axis, turned into the horizontal one.
        let tan_half_x = |fov_deg: f64, axis: &str| -> Option<f64> {
            let t = (0.5 * fov_deg.to_radians()).tan();
            match axis {
                "x" => Some(t),
                "y" => Some(t * w / h),
                "diagonal" => Some(t * w / (w * w + h * h).sqrt()),
                "smaller" => Some(if w <= h { t } else { t * w / h }),
                "larger" => Some(if w >= h { t } else { t * w / h }),
                _ => None,
            }
        };
        let axis = s.string("fov_axis")?.unwrap_or("x").to_string();
        let tan_x = match (s.float("fov")?, s.string("focal_length")?) {
            (Some(_), Some(_)) => return Err(s.error("give fov or focal_length, not both")),
            (Some(fov), None) => tan_half_x(fov, &axis),
            (None, focal) => {
                let text = focal.unwrap_or("50mm");
                let mm = text
                    .trim()
                    .trim_end_matches("mm")
                    .trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|f| *f > 0.0 && f.is_finite())
                    .ok_or_else(|| {
                        s.error(format!(
                            "focal_length \"{}\" is not a length in mm",
                            cut(text)
                        ))
                    })?;
                let diagonal = 2.0 * (FILM_DIAGONAL_MM / (2.0 * mm)).atan().to_degrees();
                tan_half_x(diagonal, "diagonal")
            }
        }
        .ok_or_else(|| {
            s.error(format!(
                "fov_axis '{}' is none of x, y, diagonal, smaller, larger",
                cut(&axis)
            ))
        })?;
        let fov_x = 2.0 * tan_x.atan().to_degrees();
        // A pinhole's focus distance changes nothing.
        if !thin_lens {
            s.ignore("focus_distance");
        }
        for clip in ["near_clip", "far_clip"] {
            if s.float(clip)?.is_some() {
                let place = s.place.clone();
                self.told
                    .note(&place, format!("{clip} read past: grinlight does not clip"));
            }
        }
        let mut camera = table([
            ("position", vec3(origin)),
            ("look_at", vec3(origin + dir.normalize())),
            ("up", vec3(up.normalize())),
            ("width", Toml::Integer(width)),
            ("height", Toml::Integer(height)),
            ("fov_x_deg", Toml::Float(fov_x)),
        ]);
        if thin_lens {
            camera.insert(
                "aperture_radius".into(),
                Toml::Float(s.float_or("aperture_radius", 0.03)?),
            );
            camera.insert(
                "focus_distance".into(),
                Toml::Float(s.float_or("focus_distance", 0.0)?),
            );
        }
        self.sensor_rest(s, film, camera, out)
    }

    /// An `orthographic` sensor: Mitsuba 3 sends parallel rays along `to_world`'s z from the
    /// near plane (`near_clip`, 0.01) over x ∈ [−1, 1], y ∈ [−1/aspect, 1/aspect] of its
    /// frame (`orthographic_projection` in sensor.h), which `to_world` scales, turns and moves:
    /// grinlight's orthographic camera at that plane's centre, `view_height` = 2|y axis|/aspect.
    /// A `to_world` that shears, mirrors or scales x and y apart (non-square pixels) is refused.
    fn orthographic_sensor(&mut self, s: &Object, out: &mut Table) -> Result<Table> {
        let m = s.transform("to_world")?;
        let l = linear(&m);
        let (left, up, dir) = (l.x_axis, l.y_axis, l.z_axis);
        let scale = left.length();
        let square = left.dot(up).abs() + up.dot(dir).abs() + left.dot(dir).abs()
            <= 1e-9 * scale * (scale + dir.length());
        if !square || (up.length() - scale).abs() > 1e-9 * scale || dir.length() == 0.0 {
            return Err(s.error(
                "to_world shears or scales x and y apart: grinlight's orthographic pixels are \
                 square",
            ));
        }
        let film = self.sensor_film(s, [left, up, dir])?;
        let (width, height) = (film.width, film.height);
        let aspect = width as f64 / height as f64;
        let position = m.transform_point3(DVec3::new(0.0, 0.0, s.float_or("near_clip", 0.01)?));
        if s.float("far_clip")?.is_some() {
            let place = s.place.clone();
            self.told.note(
                &place,
                "far_clip read past: grinlight does not clip".to_string(),
            );
        }
        let camera = table([
            ("projection", string("orthographic")),
            ("position", vec3(position)),
            ("look_at", vec3(position + dir.normalize())),
            ("up", vec3(up.normalize())),
            ("width", Toml::Integer(width)),
            ("height", Toml::Integer(height)),
            ("view_height", Toml::Float(2.0 * up.length() / aspect)),
        ]);
        self.sensor_rest(s, film, camera, out)
    }

    /// A sensor's film: its size in pixels and pixel filter (Mitsuba's 768 × 576 and Gaussian
    /// without one), once its frame `axes` (to_world's x, y and z) are known not to mirror the
    /// image.
    fn sensor_film(&mut self, s: &Object, axes: [DVec3; 3]) -> Result<SensorFilm> {
        let [left, up, dir] = axes;
        if left.dot(up.cross(dir)) <= 0.0 {
            return Err(s.error("to_world mirrors the camera (its x axis is not up × forward): grinlight does not render mirrored images"));
        }
        match s.child("film")?.map(|c| c.object().clone()) {
            Some(f) => self.film(f),
            None => Ok(SensorFilm {
                object: None,
                width: 768,
                height: 576,
                filter: PixelFilter::mitsuba_gaussian(0.5),
                crop: None,
            }),
        }
    }

    /// What every sensor has besides its projection: its medium, its sampler's settings
    /// (the `[render]` table returned) and its film's; `camera` goes into `out`.
    fn sensor_rest(
        &mut self,
        s: &Object,
        film: SensorFilm,
        mut camera: Table,
        out: &mut Table,
    ) -> Result<Table> {
        pixel_filter_keys(film.filter, &mut camera);
        if let Some(crop) = film.crop {
            camera.insert(
                "crop".into(),
                Toml::Array(crop.iter().map(|&n| Toml::Integer(n)).collect()),
            );
        }
        if let Some(medium) = s.named_child("medium").or(s.child("medium")?) {
            // The camera's medium: grinlight finds it from the camera's position; a medium no
            // shape holds fills the space around them.
            let name = self.medium(&medium.object().clone(), 1.0)?;
            self.ambient = Some(name);
        }
        let mut render = Table::new();
        if let Some(sampler) = s.child("sampler")? {
            let sampler = &sampler.object();
            let spp = sampler.integer_or("sample_count", 4)?;
            if spp < 1 {
                return Err(sampler.error("sample_count must be ≥ 1"));
            }
            render.insert("spp".into(), Toml::Integer(spp));
            render.insert(
                "seed".into(),
                Toml::Integer(sampler.integer_or("seed", 0)?.max(0)),
            );
            // The pattern of the points changes the noise, not what they estimate.
            for name in ["jitter", "scramble_seed"] {
                sampler.ignore(name);
            }
            sampler.finish()?;
        } else {
            render.insert("spp".into(), Toml::Integer(4));
        }
        if let Some(f) = &film.object {
            f.finish()?;
        }
        s.finish()?;
        out.insert("camera".into(), Toml::Table(camera));
        Ok(render)
    }

    /// The film's size and pixel filter: a box or a Gaussian exactly, others only
    /// approximately (as a box).
    fn film(&mut self, f: Rc<Object>) -> Result<SensorFilm> {
        if f.kind != "hdrfilm" {
            return Err(f.error(format!(
                "the film '{}' is not supported (hdrfilm is)",
                cut(&f.kind)
            )));
        }
        let width = f.integer_or("width", 768)?;
        let height = f.integer_or("height", 576)?;
        if !(1..=65536).contains(&width) || !(1..=65536).contains(&height) {
            return Err(f.error(format!(
                "{width}×{height} pixels: each side must be 1…65536"
            )));
        }
        // How the image is stored, not what it holds.
        for name in ["pixel_format", "component_format", "file_format", "banner"] {
            f.ignore(name);
        }
        let filter = f.child("rfilter")?.map(|c| c.object().clone());
        let kind = filter
            .as_ref()
            .map_or("gaussian".to_string(), |r| r.kind.clone());
        let pixel_filter = match kind.as_str() {
            "box" => PixelFilter::Box,
            "gaussian" => {
                let stddev = filter
                    .as_ref()
                    .map_or(Ok(0.5), |r| r.float_or("stddev", 0.5))?;
                if !(stddev > 0.0 && stddev <= 8.0) {
                    let at = filter.as_ref().unwrap_or(&f);
                    return Err(at.error(format!(
                        "stddev = {stddev}: grinlight's Gaussian pixel filter is (0, 8] pixels wide"
                    )));
                }
                PixelFilter::mitsuba_gaussian(stddev)
            }
            _ => {
                let place = filter.as_ref().map_or(f.place.clone(), |r| r.place.clone());
                self.told.approximate(
                    &place,
                    format!(
                        "the pixel filter '{kind}' taken as a box (grinlight's pixels are \
                         box- or Gaussian-filtered: the image is a little sharper)"
                    ),
                )?;
                if let Some(r) = &filter {
                    for name in ["radius", "B", "C", "lobes"] {
                        r.ignore(name);
                    }
                }
                PixelFilter::Box
            }
        };
        if let Some(r) = &filter {
            r.finish()?;
        }
        // The crop window: Mitsuba renders it alone, its pixels as the whole film's, the
        // filter's support ending at its edges (its film's image block has no border).
        let crop = [
            f.integer_or("crop_offset_x", 0)?,
            f.integer_or("crop_offset_y", 0)?,
            f.integer_or("crop_width", width)?,
            f.integer_or("crop_height", height)?,
        ];
        let [x, y, w, h] = crop;
        if x < 0 || y < 0 || w < 1 || h < 1 || x + w > width || y + h > height {
            return Err(f.error(format!(
                "a crop of {w}×{h} pixels at ({x}, {y}) does not lie within the {width}×{height} film"
            )));
        }
        Ok(SensorFilm {
            object: Some(f),
            width,
            height,
            filter: pixel_filter,
            crop: (crop != [0, 0, width, height]).then_some(crop),
        })
    }

    /// `[render] integrator` and `max_depth` from the `<integrator>`.
    fn integrator(&mut self, scene: &Object, render: &mut Table) -> Result<()> {
        render.insert("integrator".into(), string("path"));
        let Some(child) = scene.child("integrator")? else {
            return Ok(());
        };
        let mut i = child.object().clone();
        while matches!(i.kind.as_str(), "moment" | "aov" | "stokes") {
            if i.kind == "aov" {
                i.ignore("aovs");
                let place = i.place.clone();
                self.told.note(&place, "<integrator type=\"aov\">: its AOVs are not written (grinlight writes albedo and normal layers)");
            }
            // Mitsuba's Stokes images, in its basis (first axis d × up): grinlight's S0–S3
            // layers (checked against Mitsuba 3.9.1: tests/polarization.rs).
            if i.kind == "stokes" {
                render.insert("stokes".into(), Toml::Boolean(true));
            }
            let inner = i.child("integrator")?.map(|c| c.object().clone());
            i.finish()?;
            i = inner.ok_or_else(|| i.error("holds no <integrator>"))?;
        }
        let depth = match i.kind.as_str() {
            "path" | "volpath" | "volpathmis" | "ptracer" => i.integer_or("max_depth", -1)?,
            // Direct light and the emitters seen: paths of two segments; its sample counts
            // split the same estimate differently (but see `repeated_delta_lights`).
            "direct" => {
                let shading = i.integer_or("shading_samples", 1)?;
                let emitter = i.integer_or("emitter_samples", shading)?;
                i.ignore("bsdf_samples");
                if emitter > 1 {
                    self.repeated_delta_lights = Some((i.place.clone(), emitter));
                }
                2
            }
            other => {
                return Err(i.error(format!(
                    "the integrator '{}' is not supported (path, volpath, volpathmis, \
                     ptracer and direct are, as grinlight's path tracer)",
                    cut(other)
                )))
            }
        };
        match depth {
            -1 => {}
            // Mitsuba counts a path's segments; grinlight the scattering events between.
            d if d >= 2 => {
                render.insert("max_depth".into(), Toml::Integer(d - 1));
            }
            d => {
                return Err(i.error(format!(
                    "max_depth = {d}: grinlight renders paths with at least one scattering \
                     (Mitsuba's max_depth ≥ 2, or -1)"
                )))
            }
        }
        // Russian roulette and a pass's size change the noise, not the estimate.
        for name in ["rr_depth", "samples_per_pass"] {
            i.ignore(name);
        }
        if i.boolean_or("hide_emitters", false)? {
            self.hide_emitters = Some((i.place.clone(), i.kind.clone()));
        }
        i.finish()?;
        Ok(())
    }

    /// `hide_emitters`: the camera's `hide_emitters`, which leaves out emitters and the sky
    /// its first chain meets before any specular surface — Mitsuba's, whose integrators see
    /// emitters at depth 0 only (checked against Mitsuba 3.9.1: `tests/import.rs`). Emitters
    /// behind a `null` BSDF or a `thindielectric` are where its integrators disagree (measured
    /// with Mitsuba 3.9.1: `path` shows an area emitter behind a `null` surface and behind a
    /// thin pane, `volpath` hides both; grinlight counts a thin pane's transmission as a
    /// specular surface and a `null` surface as none): an approximation where they differ.
    fn hide_emitters(&mut self, scene: &mut Table) -> Result<()> {
        let Some((place, kind)) = self.hide_emitters.take() else {
            return Ok(());
        };
        if let Some(Toml::Table(camera)) = scene.get_mut("camera") {
            camera.insert("hide_emitters".into(), Toml::Boolean(true));
        }
        let differ = match kind.as_str() {
            "volpath" | "volpathmis" => &self.see_through.thin,
            _ => &self.see_through.null,
        };
        if !differ.is_empty() {
            let list = differ.join(", ");
            self.told.approximate(
                &place,
                format!(
                    "hide_emitters = true with {list}: Mitsuba's `{}` decides otherwise than \
                     grinlight whether an emitter seen through them is seen directly",
                    cut(&kind)
                ),
            )?;
        }
        Ok(())
    }

    /// The emitter nested in a shape, if any.
    fn area_radiance(&mut self, shape: &Object) -> Result<Option<(DVec3, Place)>> {
        let Some(e) = shape.child("emitter")? else {
            return Ok(None);
        };
        let e = e.object().clone();
        if e.kind != "area" {
            return Err(e.error("a shape's emitter must be 'area'"));
        }
        self.attached.insert(Rc::as_ptr(&e));
        let radiance = self.colour(&e, "radiance", 1.0)?;
        e.finish()?;
        Ok(Some((radiance, e.place.clone())))
    }

    /// A top-level `<shape>`: a shape placed as it says, a `shapegroup`'s shapes where an
    /// `instance` places them (a group itself shows nothing), or an `instance`.
    fn shape(&mut self, shape: &Rc<Object>) -> Result<()> {
        match shape.kind.as_str() {
            "shapegroup" => {
                for member in shape.children("shape") {
                    let member = member.object();
                    if matches!(member.kind.as_str(), "shapegroup" | "instance") {
                        return Err(
                            member.error("inside a shapegroup: Mitsuba's groups hold plain shapes")
                        );
                    }
                    if let Some(e) = member.child("emitter")? {
                        return Err(e.place.error(format!(
                            "{}: an emitter on a shape in a shapegroup (Mitsuba's instances \
                             do not emit)",
                            member.what()
                        )));
                    }
                }
                Ok(())
            }
            "instance" => self.instance(shape),
            _ => self.placed_shape(shape, &DMat4::IDENTITY),
        }
    }

    /// An `instance`: each shape of the `shapegroup` it refers to, placed by the instance's
    /// `to_world` after its own (Mitsuba's instance-to-world times the shape's to_world) — a
    /// flattening: every instance converts to shapes of its own.
    fn instance(&mut self, instance: &Rc<Object>) -> Result<()> {
        let placement = instance.transform("to_world")?;
        let group = instance
            .child("shape")?
            .map(|c| c.object().clone())
            .ok_or_else(|| instance.error("refers to no shapegroup (<ref id=\"…\"/>)"))?;
        if group.kind != "shapegroup" {
            return Err(instance.error(format!("refers to {}, not a shapegroup", group.what())));
        }
        instance.finish()?;
        for member in group.children("shape") {
            self.placed_shape(member.object(), &placement)?;
        }
        Ok(())
    }

    /// The triangles of a mesh shape's file (OBJ, PLY or serialized).
    /// Read once a shape, however many instances place it.
    fn load_mesh(&mut self, shape: &Object) -> Result<Rc<crate::scene::mesh::ObjTriangles>> {
        if let Some(mesh) = self.meshes.get(&(shape as *const Object)) {
            return Ok(mesh.clone());
        }
        let path = self.mesh_file(shape)?;
        let mesh = match shape.kind.as_str() {
            "ply" => crate::scene::ply::load_ply(&path),
            "serialized" => crate::scene::serialized::load_serialized(&path, shape_index(shape)?),
            _ => crate::scene::mesh::load_triangles(&path),
        }
        .map_err(|e| shape.error(e))?;
        let mesh = Rc::new(mesh);
        self.meshes.insert(shape as *const Object, mesh.clone());
        Ok(mesh)
    }

    /// A shape placed by `placement` after its own `to_world`.
    fn placed_shape(&mut self, shape: &Rc<Object>, placement: &DMat4) -> Result<()> {
        let m = *placement * shape.transform("to_world")?;
        let flip = shape.boolean_or("flip_normals", false)?;
        let emitting = self.area_radiance(shape)?;
        let bsdf = shape.child("bsdf")?.map(|c| c.object().clone());
        let interior = Self::medium_child(shape, "interior")?;
        let exterior = Self::medium_child(shape, "exterior")?;
        if let Some((radiance, place)) = emitting {
            // grinlight's area lights reflect nothing: exact only for a black surface.
            let black = match &bsdf {
                None => false,
                Some(b) => {
                    let inner = match b.kind.as_str() {
                        "twosided" => b.children("bsdf").first().map(|c| c.object().clone()),
                        _ => Some(b.clone()),
                    };
                    inner.is_some_and(|i| {
                        i.kind == "diffuse"
                            && self.colour(&i, "reflectance", 0.5).ok() == Some(DVec3::ZERO)
                    })
                }
            };
            if !black {
                self.told.approximate(
                    &place,
                    format!(
                        "{}'s surface reflects light in Mitsuba; grinlight's area lights \
                         reflect nothing (exact for a black diffuse BSDF)",
                        shape.what()
                    ),
                )?;
            }
            let emitting = self.emitting_surface(shape, &m, flip)?;
            shape.finish()?;
            let mut light = emitting.light();
            light.insert("radiance".into(), vec3(radiance));
            self.lists.lights.push(light);
            return Ok(());
        }
        let surface = match &bsdf {
            Some(b) => self.bsdf(b)?,
            None => self.default_diffuse(),
        };
        let mut out = Table::new();
        match (&surface, &interior) {
            (Surface::Null, None) => {
                let place = shape.place.clone();
                self.told.note(
                    &place,
                    format!(
                        "{} has a null BSDF and no medium: it is invisible, left out",
                        shape.what()
                    ),
                );
                self.geometry(shape, &m, flip, false)?;
                shape.finish()?;
                return Ok(());
            }
            (Surface::Null, Some(medium)) => {
                // An index-matched boundary: a dielectric of index 1 around the medium.
                let name = self.medium(medium, 1.0)?;
                let boundary = self.made_material(Made::IndexMatched);
                out.insert("material".into(), string(&boundary));
                out.insert("interior".into(), string(&name));
            }
            (Surface::Material { name, ior, .. }, medium) => {
                out.insert("material".into(), string(name));
                match (ior, medium) {
                    (Some(eta), Some(medium)) => {
                        let inside = self.medium(medium, *eta)?;
                        out.insert("interior".into(), string(&inside));
                    }
                    (None, Some(medium)) => {
                        return Err(medium.error(format!(
                            "is the interior of {}, whose BSDF lets no light in",
                            shape.what()
                        )))
                    }
                    (_, None) => {}
                }
            }
        }
        if let (Some(ambient), None) = (&self.ambient, &exterior) {
            // Mitsuba's ray leaving this surface outward is in the medium it names there:
            // none, vacuum — where grinlight's goes on in the medium around the camera.
            let (ambient, place) = (ambient.clone(), shape.place.clone());
            self.told.approximate(
                &place,
                format!(
                    "{} names no exterior medium: Mitsuba's light leaves it in vacuum, \
                     grinlight's in '{ambient}', the sensor's medium (give it <ref \
                     name=\"exterior\" id=\"...\"/> to make the two agree)",
                    shape.what()
                ),
            )?;
        }
        if let Some(medium) = &exterior {
            let name = self.medium(medium, 1.0)?;
            if self.ambient.as_deref() != Some(name.as_str()) {
                out.insert("exterior".into(), string(&name));
            }
        }
        let textured = matches!(surface, Surface::Material { textured: true, .. });
        let mesh = matches!(shape.kind.as_str(), "obj" | "ply" | "serialized");
        let scatters = bsdf.as_deref().is_none_or(scatters_about_the_normal);
        // Where the mesh's interpolated normals are not its faces' (read from its file once
        // here, before the render reads it again).
        let turn = match mesh && scatters && !shape.boolean_or("face_normals", false)? {
            true => mesh_normal_turn(&*self.load_mesh(shape)?, &m),
            false => 0.0,
        };
        if turn > FACES_TOLERANCE {
            let place = shape.place.clone();
            self.told.approximate(
                &place,
                format!(
                    "{}: Mitsuba evaluates its {} about the mesh's interpolated normals \
                     (cosines and hemisphere), which turn up to {:.2}° from its faces', \
                     grinlight a diffuse or rough surface's about each triangle's own (an \
                     80-face icosphere, 20°, against Mitsuba 3.9.1: blocks up to 1 % apart, z \
                     10 to 13; with face_normals z 4)",
                    shape.what(),
                    bsdf.as_ref()
                        .map_or("default diffuse BSDF".to_string(), |b| b.what()),
                    turn.to_degrees()
                ),
            )?;
        }
        for (k, v) in self.geometry(shape, &m, flip, textured)? {
            out.insert(k, v);
        }
        shape.finish()?;
        self.push_shape(out);
        Ok(())
    }

    /// A shape table: a parallelepiped cube becomes six quads sharing its keys.
    fn push_shape(&mut self, mut out: Table) {
        if let Some(Toml::Array(faces)) = out.remove("faces") {
            for face in faces {
                let mut quad = out.clone();
                quad.insert("type".into(), string("quad"));
                quad.insert("vertices".into(), face);
                self.lists.shapes.push(quad);
            }
        } else {
            self.lists.shapes.push(out);
        }
    }

    fn medium_child(shape: &Object, name: &str) -> Result<Option<Rc<Object>>> {
        match shape.named_child(name) {
            None => Ok(None),
            Some(c) if c.object().tag == "medium" => Ok(Some(c.object().clone())),
            Some(c) => Err(c.place.error(format!("'{name}' should be a <medium>"))),
        }
    }

    /// Mitsuba's default BSDF, diffuse with reflectance 0.5 (one material for every shape
    /// without a BSDF, under a name no BSDF of the scene has).
    fn default_diffuse(&mut self) -> Surface {
        let name = self.made_material(Made::DefaultDiffuse);
        Surface::Material {
            name,
            ior: None,
            textured: false,
        }
    }

    /// The name of a material the import makes itself, made the first time it is asked for.
    fn made_material(&mut self, made: Made) -> String {
        if let Some(name) = self.made.get(&made) {
            return name.clone();
        }
        let (wanted, mut table) = match made {
            Made::DefaultDiffuse => (
                "default-diffuse",
                table([
                    ("type", string("diffuse")),
                    ("albedo", vec3(DVec3::splat(0.5))),
                ]),
            ),
            // A dielectric of relative index 1: the boundary of a medium behind a null BSDF.
            Made::IndexMatched => (
                "index-matched",
                table([("type", string("dielectric")), ("ior", Toml::Float(1.0))]),
            ),
        };
        let name = free_name(&self.lists.materials, wanted);
        table.insert("name".into(), string(&name));
        self.lists.materials.push(table);
        self.made.insert(made, name.clone());
        name
    }

    /// The geometry keys of a shape; `textured`: its material has an image texture, looked up
    /// at the shape's (u, v), which must then be Mitsuba's.
    fn geometry(&mut self, shape: &Object, m: &DMat4, flip: bool, textured: bool) -> Result<Table> {
        let refuse_flip = |what: &str| -> Result<()> {
            match flip {
                true => Err(shape.error(format!("flip_normals on a {what} is not supported"))),
                false => Ok(()),
            }
        };
        Ok(match shape.kind.as_str() {
            "obj" | "ply" | "serialized" => {
                refuse_flip("mesh")?;
                let mut t = self.mesh_source(shape, m)?;
                // Mitsuba interpolates vertex normals (the file's or its own) unless told not to.
                let smooth = !shape.boolean_or("face_normals", false)?;
                t.insert("smooth".into(), Toml::Boolean(smooth));
                // Mitsuba turns the file's v over where told to (an OBJ's by default, a PLY's
                // on request; a serialized mesh has no such parameter), and looks a texture up
                // at a mesh's v (or the corners' weights, where the file gives no (u, v)) from
                // the image's top row down; grinlight does both as told (checked against
                // Mitsuba 3.9.1: scenes/mitsuba/mesh_textures.xml, tests/import.rs).
                let flip_v = match shape.kind.as_str() {
                    "obj" => shape.boolean_or("flip_tex_coords", true)?,
                    "ply" => shape.boolean_or("flip_tex_coords", false)?,
                    // serialized
                    _ => false,
                };
                if textured {
                    t.insert("flip_v".into(), Toml::Boolean(flip_v));
                    t.insert("v_from_top".into(), Toml::Boolean(true));
                }
                t
            }
            "sphere" => {
                refuse_flip("sphere")?;
                let (center, radius) = sphere(shape, m)?;
                let l = linear(m);
                with_uv_frame(
                    table([
                        ("type", string("sphere")),
                        ("center", vec3(center)),
                        ("radius", Toml::Float(radius)),
                    ]),
                    textured.then(|| (local_frame(l.z_axis, l.x_axis, l.y_axis), true)),
                )
            }
            "rectangle" => {
                // Mitsuba's image row is v from the top, grinlight's from the bottom: a textured
                // quad starts at the rectangle's (−1, 1) corner, so that its v is 1 − Mitsuba's
                // (its normal turns over, which no two-sided textured surface minds).
                let corners = match textured {
                    true => {
                        let p = |x: f64, y: f64| m.transform_point3(DVec3::new(x, y, 0.0));
                        [p(-1.0, 1.0), p(1.0, 1.0), p(1.0, -1.0), p(-1.0, -1.0)]
                    }
                    false => rectangle(m, flip),
                };
                table([
                    ("type", string("quad")),
                    (
                        "vertices",
                        Toml::Array(corners.into_iter().map(vec3).collect()),
                    ),
                ])
            }
            "disk" => {
                let (center, normal, radius) = disk(shape, m, flip)?;
                let l = linear(m);
                with_uv_frame(
                    table([
                        ("type", string("disk")),
                        ("center", vec3(center)),
                        ("normal", vec3(normal)),
                        ("radius", Toml::Float(radius)),
                    ]),
                    textured.then(|| (local_frame(normal, l.x_axis, l.y_axis), true)),
                )
            }
            "cube" if textured => {
                refuse_flip("cube")?;
                if linear(m).determinant() == 0.0 {
                    return Err(shape.error("to_world flattens the cube"));
                }
                table([(
                    "faces",
                    Toml::Array(
                        textured_cube_faces(m)
                            .into_iter()
                            .map(|f| Toml::Array(f.into_iter().map(vec3).collect()))
                            .collect(),
                    ),
                )])
            }
            "cube" => {
                refuse_flip("cube")?;
                let l = linear(m);
                let diagonal = l.x_axis.y == 0.0
                    && l.x_axis.z == 0.0
                    && l.y_axis.x == 0.0
                    && l.y_axis.z == 0.0
                    && l.z_axis.x == 0.0
                    && l.z_axis.y == 0.0;
                if diagonal {
                    let (a, b) = (
                        m.transform_point3(DVec3::NEG_ONE),
                        m.transform_point3(DVec3::ONE),
                    );
                    table([
                        ("type", string("box")),
                        ("min", vec3(a.min(b))),
                        ("max", vec3(a.max(b))),
                    ])
                } else {
                    if l.determinant() == 0.0 {
                        return Err(shape.error("to_world flattens the cube"));
                    }
                    table([(
                        "faces",
                        Toml::Array(
                            cube_faces(m)
                                .into_iter()
                                .map(|f| Toml::Array(f.into_iter().map(vec3).collect()))
                                .collect(),
                        ),
                    )])
                }
            }
            "cylinder" => {
                refuse_flip("cylinder")?;
                let p0 = shape.vector("p0")?.unwrap_or(DVec3::ZERO);
                let p1 = shape.vector("p1")?.unwrap_or(DVec3::Z);
                let radius = shape.float_or("radius", 1.0)?;
                let s = similarity(m).ok_or_else(|| {
                    shape.error(
                        "to_world scales unevenly or shears: an elliptic cylinder is not supported",
                    )
                })?;
                let (a, b) = (m.transform_point3(p0), m.transform_point3(p1));
                let axis = (b - a)
                    .try_normalize()
                    .ok_or_else(|| shape.error("p0 = p1"))?;
                // Mitsuba's local frame: p0 at its origin, the axis its z, its x and y the
                // Duff et al. (2017) basis of the axis before to_world (Frame3f), as glam's.
                let local = (p1 - p0).normalize();
                let (x, y) = local.any_orthonormal_pair();
                let l = linear(m);
                with_uv_frame(
                    table([
                        ("type", string("cylinder")),
                        ("base", vec3(a)),
                        ("axis", vec3(axis)),
                        ("radius", Toml::Float(radius * s)),
                        ("height", Toml::Float((b - a).length())),
                        // Mitsuba's cylinder is a tube without caps.
                        ("capped", Toml::Boolean(false)),
                    ]),
                    textured.then(|| (local_frame(axis, l * x, l * y), true)),
                )
            }
            other => {
                return Err(shape.error(format!(
                    "the shape '{}' is not supported by grinlight's import (obj, ply, \
                     serialized, sphere, rectangle, disk, cube, cylinder are)",
                    cut(other)
                )))
            }
        })
    }

    /// A mesh shape's `mesh` keys: its file (and which of a serialized file's meshes) and
    /// `to_world`'s map `m` as its matrix.
    fn mesh_source(&mut self, shape: &Object, m: &DMat4) -> Result<Table> {
        let file = self.mesh_file(shape)?;
        let mut t = table([
            ("type", string("mesh")),
            ("file", string(&file.to_string_lossy())),
        ]);
        if shape.kind == "serialized" {
            let index = shape_index(shape)?;
            t.insert("shape_index".into(), Toml::Integer(index as i64));
        }
        if *m != DMat4::IDENTITY {
            t.insert("matrix".into(), affine_rows(m));
        }
        Ok(t)
    }

    fn mesh_file(&mut self, shape: &Object) -> Result<PathBuf> {
        let name = shape
            .string("filename")?
            .ok_or_else(|| shape.error("has no filename"))?
            .to_string();
        let extension = std::path::Path::new(&name)
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        if extension.as_deref() != Some(shape.kind.as_str()) {
            return Err(shape.error(format!(
                "filename '{}' should end in .{}",
                cut(&name),
                shape.kind
            )));
        }
        let path = self.doc.find(&name, &shape.place)?;
        Ok(std::fs::canonicalize(&path).unwrap_or(path))
    }

    /// The light an emitting shape becomes: a rectangle, a disk, a sphere, or a mesh (one
    /// parallelogram of two triangles as a quad).
    fn emitting_surface(&mut self, shape: &Object, m: &DMat4, flip: bool) -> Result<AreaEmitter> {
        match shape.kind.as_str() {
            "rectangle" => Ok(AreaEmitter::Quad(rectangle(m, flip))),
            "disk" => {
                let (center, normal, radius) = disk(shape, m, flip)?;
                Ok(AreaEmitter::Disk {
                    center,
                    normal,
                    radius,
                })
            }
            "sphere" => {
                if flip {
                    return Err(shape.error(
                        "an area emitter on a sphere with flip_normals (emitting inward) is not \
                         supported",
                    ));
                }
                let (center, radius) = sphere(shape, m)?;
                Ok(AreaEmitter::Sphere { center, radius })
            }
            "obj" | "ply" | "serialized" => {
                let face_normals = shape.boolean_or("face_normals", false)?;
                shape.ignore("flip_tex_coords");
                let mesh = self.load_mesh(shape)?;
                let corner = |i: u32| {
                    m.transform_point3(DVec3::from(mesh.positions[i as usize].map(f64::from)))
                };
                let quad = match mesh.triangles.as_slice() {
                    [a, b] => parallelogram([a.map(corner), b.map(corner)], flip),
                    _ => None,
                };
                if let Some(quad) = quad {
                    return Ok(AreaEmitter::Quad(quad));
                }
                // Mitsuba emits on the side of a hit's shading normal: the file's vertex
                // normals interpolated where it has them and face_normals is off, else the
                // winding's (its own vertex normals follow the winding).
                let to_normal = linear(m).inverse().transpose();
                let normals = mesh.normals.as_ref().filter(|_| !face_normals);
                let corner_normals = |i: usize| {
                    let n = normals.expect("asked only with normals");
                    (mesh.triangles[i])
                        .map(|k| to_normal * DVec3::from(n[k as usize].map(f64::from)))
                };
                let world: Vec<[DVec3; 3]> = mesh.triangles.iter().map(|t| t.map(corner)).collect();
                let side = emitting_side(
                    world.iter().copied(),
                    normals.map(|_| &corner_normals as &dyn Fn(usize) -> [DVec3; 3]),
                    flip,
                );
                let area = world.iter().map(triangle_area).sum();
                // Mitsuba's emission and its light samples' cosine follow the interpolated
                // normals (the file's, or its own averages of the faces at each vertex);
                // grinlight's, each triangle's own: the same where those are the faces'.
                let faceted = face_normals || mesh_normal_turn(&mesh, m) <= FACES_TOLERANCE;
                if !faceted {
                    self.told.approximate(
                        &shape.place,
                        format!(
                            "{}: Mitsuba evaluates an emitting mesh's radiance and its light \
                             samples' cosine at the interpolated vertex normal; grinlight's \
                             mesh lights at each triangle's own normal (exact with \
                             face_normals, or where a mesh's normals are its faces')",
                            shape.what()
                        ),
                    )?;
                }
                let mut keys = self.mesh_source(shape, m)?;
                match side {
                    Facing::Winding => {}
                    Facing::Against => {
                        keys.insert("flip".into(), Toml::Boolean(true));
                    }
                    Facing::Mixed { against, split, of } => {
                        return Err(shape.error(format!(
                            "an area emitter on a mesh whose triangles emit on different sides \
                             of their winding ({against} of {of} one way, {split} with normals \
                             on both sides): grinlight's mesh lights emit on one side of every \
                             triangle's winding"
                        )))
                    }
                }
                Ok(AreaEmitter::Mesh { keys, area })
            }
            other => Err(shape.error(format!(
                "an area emitter on a '{}': grinlight's area lights are rectangles, disks, \
                 spheres and triangle meshes",
                cut(other)
            ))),
        }
    }

    /// A top-level emitter.
    fn emitter(&mut self, e: &Rc<Object>) -> Result<()> {
        if matches!(e.kind.as_str(), "point" | "spot" | "directional") {
            if let Some((place, n)) = self.repeated_delta_lights.take() {
                self.told.note(
                    &place,
                    format!(
                        "<integrator type=\"direct\"> with emitter_samples = {n}: Mitsuba 3 counts \
                         each sample of a point, spot or directional light in full ({n} times \
                         its light: its direct.cpp leaves their 1/{n} out); grinlight renders \
                         the light's own intensity"
                    ),
                );
            }
        }
        let m = e.transform("to_world")?;
        let light = match e.kind.as_str() {
            "point" => {
                let position = match e.vector("position")? {
                    Some(p) => p,
                    None => m.transform_point3(DVec3::ZERO),
                };
                table([
                    ("type", string("point")),
                    ("position", vec3(position)),
                    ("intensity", vec3(self.colour(e, "intensity", 1.0)?)),
                ])
            }
            "spot" => {
                let cutoff = e.float_or("cutoff_angle", 20.0)?;
                let beam = e.float_or("beam_width", 0.75 * cutoff)?;
                if !(0.0 < beam && beam <= cutoff && cutoff <= 180.0) {
                    return Err(e.error(format!(
                        "beam_width {beam}° and cutoff_angle {cutoff}°: grinlight's spot needs \
                         0 < beam_width ≤ cutoff_angle ≤ 180°"
                    )));
                }
                table([
                    ("type", string("spot")),
                    ("position", vec3(m.transform_point3(DVec3::ZERO))),
                    ("direction", vec3(m.transform_vector3(DVec3::Z).normalize())),
                    ("intensity", vec3(self.colour(e, "intensity", 1.0)?)),
                    ("cone_deg", Toml::Float(cutoff)),
                    ("falloff_deg", Toml::Float(beam)),
                    // Mitsuba's falloff is linear in the angle.
                    ("falloff_curve", string("linear")),
                ])
            }
            "directional" => {
                let direction = match e.vector("direction")? {
                    Some(d) => d,
                    None => m.transform_vector3(DVec3::Z),
                };
                let direction = direction
                    .try_normalize()
                    .ok_or_else(|| e.error("the direction is zero"))?;
                table([
                    ("type", string("directional")),
                    ("direction", vec3(direction)),
                    ("irradiance", vec3(self.colour(e, "irradiance", 1.0)?)),
                ])
            }
            "constant" => {
                let radiance = self.colour(e, "radiance", 1.0)?;
                e.finish()?;
                return self.set_environment(
                    e,
                    table([
                        ("type", string("environment")),
                        ("sky", string("uniform")),
                        ("radiance", vec3(radiance)),
                    ]),
                );
            }
            "envmap" => {
                let name = e
                    .string("filename")?
                    .ok_or_else(|| e.error("has no filename"))?
                    .to_string();
                let ext = std::path::Path::new(&name)
                    .extension()
                    .map(|x| x.to_string_lossy().to_ascii_lowercase());
                if !matches!(ext.as_deref(), Some("exr") | Some("hdr")) {
                    return Err(e.error(format!(
                        "'{}': grinlight's environment maps are EXR or HDR files",
                        cut(&name)
                    )));
                }
                let path = self.doc.find(&name, &e.place)?;
                let scale = e.float_or("scale", 1.0)?;
                // Mitsuba's map has +z at its centre and grinlight's −z: grinlight's map is
                // Mitsuba's turned half a turn about +y, then by to_world (a rotation).
                // A rotation to the 1e-6 of a matrix written with six digits, made exactly
                // orthonormal (a turn of the map by 1e-6 rad at most, below Mitsuba's f32).
                let l = linear(&m);
                let rotation =
                    similarity(&m).is_some_and(|s| (s - 1.0).abs() < 1e-5) && l.determinant() > 0.0;
                if !rotation {
                    return Err(e.error("to_world must be a rotation (no scale, no mirror)"));
                }
                let x = l.x_axis.normalize();
                let y = (l.y_axis - x * x.dot(l.y_axis)).normalize();
                let l = DMat3::from_cols(x, y, x.cross(y));
                let about_y = (l.y_axis - DVec3::Y).length() < 1e-12;
                let turn = match about_y {
                    true => (
                        "rotation_deg",
                        Toml::Float(180.0 + l.z_axis.x.atan2(l.z_axis.z).to_degrees()),
                    ),
                    false => {
                        let map = l * DMat3::from_rotation_y(std::f64::consts::PI);
                        let rows = map.transpose().to_cols_array();
                        (
                            "matrix",
                            Toml::Array(rows.iter().map(|&x| Toml::Float(x)).collect()),
                        )
                    }
                };
                e.finish()?;
                let path = std::fs::canonicalize(&path).unwrap_or(path);
                return self.set_environment(
                    e,
                    table([
                        ("type", string("environment")),
                        ("file", string(&path.to_string_lossy())),
                        turn,
                        // Read between pixels as Mitsuba reads its map.
                        ("filter", string("bilinear")),
                        ("scale", Toml::Float(scale)),
                    ]),
                );
            }
            other => {
                return Err(e.error(format!(
                    "the emitter '{}' is not supported by grinlight's import (point, spot, \
                     directional, constant, envmap, and area on a shape are)",
                    cut(other)
                )))
            }
        };
        e.finish()?;
        self.lists.lights.push(light);
        Ok(())
    }

    fn set_environment(&mut self, e: &Object, env: Table) -> Result<()> {
        if self.environment.is_some() {
            return Err(
                e.error("a second environment emitter (constant or envmap): grinlight has one")
            );
        }
        self.environment = Some(env);
        Ok(())
    }
}

/// Mitsuba's rectangle [−1, 1]² at z = 0 (normal +z) placed by `m`: v0..v3 with the normal
/// (v1 − v0) × (v3 − v0), reversed when flipped.
fn rectangle(m: &DMat4, flip: bool) -> [DVec3; 4] {
    let p = |x: f64, y: f64| m.transform_point3(DVec3::new(x, y, 0.0));
    let v = [p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)];
    // Mitsuba's normal is +z through the inverse transpose; the corners' cross product is
    // that times the determinant, so a mirroring map reverses the order as a flip does.
    let mirrored = linear(m).determinant() < 0.0;
    match flip != mirrored {
        false => v,
        true => [v[0], v[3], v[2], v[1]],
    }
}

/// A `serialized` shape's `shape_index` (0: the file's first mesh).
fn shape_index(shape: &Object) -> Result<usize> {
    let index = shape.integer_or("shape_index", 0)?;
    usize::try_from(index).map_err(|_| shape.error(format!("shape_index {index} is negative")))
}

/// Mitsuba's sphere (`center`, `radius`) placed by `m`: its centre and radius (the map must
/// keep it round).
fn sphere(shape: &Object, m: &DMat4) -> Result<(DVec3, f64)> {
    let center = shape.vector("center")?.unwrap_or(DVec3::ZERO);
    let radius = shape.float_or("radius", 1.0)?;
    let s = similarity(m).ok_or_else(|| {
        shape.error("to_world scales unevenly or shears: an ellipsoid is not supported")
    })?;
    Ok((m.transform_point3(center), radius * s))
}

/// Mitsuba's unit disk at z = 0 (normal +z) placed by `m`: its centre, normal and radius (the
/// map must keep it round).
fn disk(shape: &Object, m: &DMat4, flip: bool) -> Result<(DVec3, DVec3, f64)> {
    let l = linear(m);
    let (a, b) = (l.x_axis, l.y_axis);
    let round = (a.length() - b.length()).abs() <= 1e-6 * a.length()
        && a.dot(b).abs() <= 1e-6 * a.length_squared();
    if !round || a.length() == 0.0 {
        return Err(shape.error("to_world makes the disk an ellipse: not supported"));
    }
    // Mitsuba's normal: +z through the inverse transpose.
    let normal = (l.inverse().transpose() * DVec3::Z).normalize();
    Ok((
        m.transform_point3(DVec3::ZERO),
        if flip { -normal } else { normal },
        a.length(),
    ))
}

/// Mitsuba 3.9.1's cube (`cube.cpp`) placed by `m` as six parallelograms whose corners are
/// its faces' four vertices in its order: texture coordinates (0, 1), (1, 1), (1, 0), (0, 0)
/// in Mitsuba, so that a quad from the first toward the second and the fourth reads (u,
/// 1 − v), grinlight's image coordinates of Mitsuba's (u, v).
fn textured_cube_faces(m: &DMat4) -> Vec<[DVec3; 4]> {
    const VERTICES: [[f64; 3]; 24] = [
        [1., -1., -1.],
        [1., -1., 1.],
        [-1., -1., 1.],
        [-1., -1., -1.],
        [1., 1., -1.],
        [-1., 1., -1.],
        [-1., 1., 1.],
        [1., 1., 1.],
        [1., -1., -1.],
        [1., 1., -1.],
        [1., 1., 1.],
        [1., -1., 1.],
        [1., -1., 1.],
        [1., 1., 1.],
        [-1., 1., 1.],
        [-1., -1., 1.],
        [-1., -1., 1.],
        [-1., 1., 1.],
        [-1., 1., -1.],
        [-1., -1., -1.],
        [1., 1., -1.],
        [1., -1., -1.],
        [-1., -1., -1.],
        [-1., 1., -1.],
    ];
    VERTICES
        .chunks(4)
        .map(|face| std::array::from_fn(|k| m.transform_point3(DVec3::from(face[k]))))
        .collect()
}

/// Mitsuba's cube [−1, 1]³ placed by `m` as six parallelograms, normals outward.
fn cube_faces(m: &DMat4) -> Vec<[DVec3; 4]> {
    let p = |x: f64, y: f64, z: f64| m.transform_point3(DVec3::new(x, y, z));
    // Each face: corners counterclockwise seen from outside the unit cube.
    let mut faces = vec![
        [
            p(1., -1., -1.),
            p(1., 1., -1.),
            p(1., 1., 1.),
            p(1., -1., 1.),
        ],
        [
            p(-1., -1., -1.),
            p(-1., -1., 1.),
            p(-1., 1., 1.),
            p(-1., 1., -1.),
        ],
        [
            p(-1., 1., -1.),
            p(-1., 1., 1.),
            p(1., 1., 1.),
            p(1., 1., -1.),
        ],
        [
            p(-1., -1., -1.),
            p(1., -1., -1.),
            p(1., -1., 1.),
            p(-1., -1., 1.),
        ],
        [
            p(-1., -1., 1.),
            p(1., -1., 1.),
            p(1., 1., 1.),
            p(-1., 1., 1.),
        ],
        [
            p(-1., -1., -1.),
            p(-1., 1., -1.),
            p(1., 1., -1.),
            p(1., -1., -1.),
        ],
    ];
    if linear(m).determinant() < 0.0 {
        for f in &mut faces {
            *f = [f[0], f[3], f[2], f[1]];
        }
    }
    faces
}

/// A texture's `to_uv` as grinlight's `texture_uv` (none where it is the identity): Mitsuba's
/// (u, v) are grinlight's image coordinates (u, 1 − v) (see `geometry`), and Mitsuba maps
/// them by the transform's affine part in the plane; a `to_uv` that reaches out of that
/// plane (a z part) is refused.
fn texture_uv(tex: &Object) -> Result<Table> {
    let m = tex.transform("to_uv")?;
    if m == DMat4::IDENTITY {
        return Ok(Table::new());
    }
    let out_of_plane = [m.x_axis.z, m.y_axis.z, m.w_axis.z, m.z_axis.x, m.z_axis.y];
    if out_of_plane.iter().any(|&x| x != 0.0) {
        return Err(tex.error("a to_uv transform out of the (u, v) plane is not supported"));
    }
    let rows = [
        m.x_axis.x, m.y_axis.x, m.w_axis.x, m.x_axis.y, m.y_axis.y, m.w_axis.y,
    ];
    Ok(table([(
        "texture_uv",
        Toml::Array(rows.iter().map(|&x| Toml::Float(x)).collect()),
    )]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_faces_face_outward() {
        for m in [
            DMat4::IDENTITY,
            DMat4::from_scale(DVec3::new(-1.0, 2.0, 1.0)),
            DMat4::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7),
        ] {
            let centre = m.transform_point3(DVec3::ZERO);
            for f in cube_faces(&m) {
                let n = (f[1] - f[0]).cross(f[3] - f[0]);
                let mid = 0.25 * (f[0] + f[1] + f[2] + f[3]);
                assert!(n.dot(mid - centre) > 0.0);
                assert!((f[1] + f[3] - f[0] - f[2]).length() < 1e-12);
            }
        }
    }

    #[test]
    fn a_split_quad_is_found_whichever_diagonal_and_order() {
        let v = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.0, 1.0), DVec3::Z];
        // Normal (x) × (z) = −y.
        let q = parallelogram([[v[0], v[1], v[2]], [v[0], v[2], v[3]]], false).unwrap();
        assert!((q[1] - q[0]).cross(q[3] - q[0]).dot(DVec3::NEG_Y) > 0.0);
        let q = parallelogram([[v[1], v[2], v[3]], [v[3], v[0], v[1]]], true).unwrap();
        assert!((q[1] - q[0]).cross(q[3] - q[0]).dot(DVec3::Y) > 0.0);
        assert!(parallelogram([[v[0], v[1], v[2]], [v[0], v[1], DVec3::Y]], false).is_none());
    }
}
