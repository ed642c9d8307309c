//! Reading a scene file: TOML text ⇒ spanned tables ⇒ the validated [`Scene`], with every
//! error located at file:line:col and naming the key.

use super::media::read_medium;
use super::objects::{
    read_camera, read_environment, read_light, read_material, read_output, read_receiver,
    read_render, read_shape, Interior,
};
use super::source::Source;
use super::table::{SpannedTable, TableReader};
use crate::accel::Accel;
use crate::camera::Camera;
use crate::environment::Environment;
use crate::error::{Error, Result};
use crate::lights::Light;
use crate::material::Material;
use crate::media::{Medium, UniformMedium};
use crate::receiver::Receiver;
use crate::settings::Settings;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// The scene file's top level: only the tables grinlight knows; each kept with its span.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    medium: Vec<Spanned<SpannedTable>>,
    #[serde(default)]
    material: Vec<Spanned<SpannedTable>>,
    #[serde(default)]
    shape: Vec<Spanned<SpannedTable>>,
    #[serde(default)]
    light: Vec<Spanned<SpannedTable>>,
    #[serde(default)]
    receiver: Vec<Spanned<SpannedTable>>,
    camera: Option<Spanned<SpannedTable>>,
    render: Option<Spanned<SpannedTable>>,
    output: Option<Spanned<SpannedTable>>,
    ambient: Option<Spanned<String>>,
}

/// A surface of the scene: what it is made of and what fills it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// Index into the scene's media of what is inside (dielectrics), if anything.
    pub interior: Option<usize>,
    /// Index into [`Scene::lights`] when this primitive is an area light's emitting surface.
    pub light: Option<usize>,
    /// Index into the scene's media of what is outside (dielectrics; None: the ambient
    /// medium). Lets a dielectric separate two media, e.g. concentric layers of a fiber.
    pub exterior: Option<usize>,
}

/// A validated scene, immutable and shareable across threads.
pub struct Scene {
    pub(super) path: PathBuf,
    pub(super) media: Vec<(String, Box<dyn Medium>)>,
    /// The medium filling space outside all shapes (None: vacuum, n = 1).
    pub ambient: Option<usize>,
    /// Materials by index.
    pub materials: Vec<Material>,
    /// Per primitive of [`Scene::accel`], its surface.
    pub surfaces: Vec<Surface>,
    /// The primitives and their BVH.
    pub accel: Accel,
    /// Lights (the environment apart).
    pub lights: Vec<Light>,
    /// What escaping rays see (None: black).
    pub environment: Option<Environment>,
    /// Detector planes.
    pub receivers: Vec<Receiver>,
    /// The camera, if the scene has one.
    pub camera: Option<Camera>,
    /// The scene file and every file it reads (meshes, images, grids).
    pub inputs: Vec<PathBuf>,
}

impl Scene {
    /// The medium called `name`; the error lists the names that exist.
    pub fn medium(&self, name: &str) -> Result<&dyn Medium> {
        self.media
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, m)| m.as_ref())
            .ok_or_else(|| {
                let known: Vec<&str> = self.media.iter().map(|(n, _)| n.as_str()).collect();
                Error::Usage(format!(
                    "{}: no medium named '{name}' (the scene has: {})",
                    self.path.display(),
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ))
            })
    }

    /// Adds a medium (e.g. a profile of one's own) and returns its index, for
    /// [`Surface::interior`] or [`Scene::ambient`].
    pub fn add_medium(&mut self, name: impl Into<String>, medium: Box<dyn Medium>) -> usize {
        self.media.push((name.into(), medium));
        self.media.len() - 1
    }

    /// The medium at index `i` (see [`Surface::interior`] and [`Scene::ambient`]).
    pub fn medium_at(&self, i: usize) -> &dyn Medium {
        self.media[i].1.as_ref()
    }

    /// Names of all media, in file order.
    pub fn medium_names(&self) -> impl Iterator<Item = &str> {
        self.media.iter().map(|(n, _)| n.as_str())
    }

    /// The scene file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Parses and builds scene text (already read from `path`): the scene and the settings of its
/// `[render]` and `[output]` tables.
pub fn parse_scene(path: &Path, text: String) -> Result<(Scene, Settings)> {
    let source = Source {
        path: path.to_path_buf(),
        text,
        inputs: Default::default(),
    };
    let file: SceneFile = toml::from_str(&source.text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        let message = e.message().trim().replace('\n', " ");
        source.error_at(offset, message)
    })?;
    let reader = |table: Spanned<SpannedTable>, what: &str| {
        let span = table.span();
        TableReader::new(&source, span, what, table.into_inner())
    };
    // Media, by name.
    let mut media: Vec<(String, Box<dyn Medium>)> = Vec::new();
    for table in file.medium {
        let mut t = reader(table, "[[medium]]");
        let name = named(&mut t, media.iter().map(|(n, _)| n.as_str()), "medium")?;
        let medium = read_medium(&mut t)?;
        t.finish()?;
        media.push((name, medium));
    }
    let medium_index =
        |t: &TableReader, key: &str, name: &str, media: &[(String, Box<dyn Medium>)]| {
            media
                .iter()
                .position(|(n, _)| n == name)
                .ok_or_else(|| t.error(key, format!("no medium named '{name}'")))
        };
    // Materials, by name; a dielectric's `ior` becomes an anonymous uniform medium.
    let mut materials = Vec::new();
    let mut material_names: Vec<String> = Vec::new();
    let mut material_interiors = Vec::new();
    for table in file.material {
        let mut t = reader(table, "[[material]]");
        let name = named(
            &mut t,
            material_names.iter().map(String::as_str),
            "material",
        )?;
        let (material, interior) = read_material(&mut t)?;
        let interior = match interior {
            None => None,
            Some(Interior::Medium(m)) => Some(medium_index(&t, "interior", &m, &media)?),
            Some(Interior::Ior(n)) => {
                media.push((format!("{name} (ior {n})"), Box::new(UniformMedium { n })));
                Some(media.len() - 1)
            }
        };
        t.finish()?;
        materials.push(material);
        material_names.push(name);
        material_interiors.push(interior);
    }
    // Shapes.
    let mut primitives = Vec::new();
    let mut surfaces = Vec::new();
    for table in file.shape {
        let mut t = reader(table, "[[shape]]");
        let desc = read_shape(&mut t)?;
        let material = material_names
            .iter()
            .position(|n| *n == desc.material)
            .ok_or_else(|| t.error("material", format!("no material named '{}'", desc.material)))?;
        let interior = match &desc.interior {
            Some(m) => Some(medium_index(&t, "interior", m, &media)?),
            None => material_interiors[material],
        };
        t.check(
            "material",
            !matches!(materials[material], Material::Dielectric) || interior.is_some(),
            "a dielectric shape needs an interior",
        )?;
        // An emissive shape would be seen but would light nothing (it is neither sampled
        // nor a photon source): refuse it rather than render it silently wrong.
        t.check(
            "material",
            !matches!(materials[material], Material::Emissive { .. }),
            "an emissive material on a [[shape]] would light nothing; make it a [[light]] \
             (quad or disk, with `radiance`)",
        )?;
        let exterior = match t.string_opt("exterior")? {
            Some(m) => Some(medium_index(&t, "exterior", &m, &media)?),
            None => None,
        };
        t.finish()?;
        let surface = Surface {
            material,
            interior,
            light: None,
            exterior,
        };
        surfaces.extend(std::iter::repeat_n(surface, desc.primitives.len()));
        primitives.extend(desc.primitives);
    }
    // Lights; area lights are also emissive surfaces.
    let mut lights = Vec::new();
    let mut environment = None;
    for table in file.light {
        let mut t = reader(table, "[[light]]");
        let kind = t.string("type")?;
        if kind == "environment" {
            t.check(
                "type",
                environment.is_none(),
                "only one environment light is allowed",
            )?;
            environment = Some(read_environment(&mut t)?);
        } else {
            let (light, visible) = read_light(&mut t, &kind)?;
            if let (Some(prim), Light::Area { radiance, .. }) = (visible, &light) {
                materials.push(Material::Emissive {
                    radiance: *radiance,
                });
                surfaces.push(Surface {
                    material: materials.len() - 1,
                    interior: None,
                    light: Some(lights.len()),
                    exterior: None,
                });
                primitives.push(prim);
            }
            lights.push(light);
        }
        t.finish()?;
    }
    // Receivers: transparent detector quads.
    let mut receivers: Vec<Receiver> = Vec::new();
    for table in file.receiver {
        let mut t = reader(table, "[[receiver]]");
        let name = named(
            &mut t,
            receivers.iter().map(|r| r.name.as_str()),
            "receiver",
        )?;
        let receiver = read_receiver(&mut t, name)?;
        t.finish()?;
        materials.push(Material::Detector {
            receiver: receivers.len(),
        });
        surfaces.push(Surface {
            material: materials.len() - 1,
            interior: None,
            light: None,
            exterior: None,
        });
        primitives.push(receiver.primitive());
        receivers.push(receiver);
    }
    let ambient = match &file.ambient {
        None => None,
        Some(name) => Some(
            media
                .iter()
                .position(|(n, _)| n == name.get_ref())
                .ok_or_else(|| {
                    source.error_at(
                        name.span().start,
                        format!("key `ambient`: no medium named '{}'", name.get_ref()),
                    )
                })?,
        ),
    };
    let camera = file
        .camera
        .map(|table| {
            let mut t = reader(table, "[camera]");
            let c = read_camera(&mut t)?;
            t.finish()?;
            Ok::<_, Error>(c)
        })
        .transpose()?;
    let mut settings = match file.render {
        Some(table) => {
            let mut t = reader(table, "[render]");
            let r = read_render(&mut t)?;
            t.finish()?;
            r
        }
        None => Settings::default(),
    };
    if let Some(table) = file.output {
        let mut t = reader(table, "[output]");
        settings.output = read_output(&mut t)?;
        t.finish()?;
    }
    let scene = Scene {
        path: source.path.clone(),
        media,
        ambient,
        materials,
        surfaces,
        accel: Accel::new(primitives),
        lights,
        environment,
        receivers,
        camera,
        inputs: std::iter::once(source.path.clone())
            .chain(source.inputs.take())
            .collect(),
    };
    Ok((scene, settings))
}

/// Reads a table's `name`: non-empty and not among `taken`. Later messages name the table.
fn named<'a>(
    t: &mut TableReader,
    mut taken: impl Iterator<Item = &'a str>,
    what: &str,
) -> Result<String> {
    let name = t.string("name")?;
    t.check("name", !name.is_empty(), "must not be empty")?;
    t.check(
        "name",
        !taken.any(|n| n == name),
        format!("a {what} named '{name}' is already defined"),
    )?;
    t.describe(format!("{what} '{name}'"));
    Ok(name)
}

/// Reads, parses and builds the scene file at `path`: the scene and its settings.
pub fn load_scene(path: &Path) -> Result<(Scene, Settings)> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_scene(path, text)
}
