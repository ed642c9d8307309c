//! Reading a scene file: TOML text ⇒ spanned tables ⇒ a [`Description`] with its names
//! resolved, and the [`Settings`] of its `[render]` and `[output]` tables; every error located
//! at file:line:col and naming the key.

use super::data::SceneText;
use super::media::{
    read_absorption, read_density, read_emission, read_fluorescence, read_profile, read_scattering,
    uniform,
};
use super::model::{Description, Media, Profile, Role, Scene, Shape, Surface};
use super::read::{
    read_camera, read_environment, read_light_and_spectrum, read_material, read_output,
    read_receiver, read_render, read_shape, Interior,
};
use super::source::Source;
use super::table::{SpannedTable, TableReader};
use crate::camera::Camera;
use crate::curve::StepControl;
use crate::environment::Environment;
use crate::error::{Error, Result};
use crate::ids::{MaterialId, MediumId};
use crate::lights::Light;
use crate::material::Material;
use crate::receiver::Receiver;
use crate::settings::Settings;
use crate::spectrum::{Dispersion, Spectrum};
use crate::volume::Participating;
use std::path::Path;
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

/// A reader of one table of `source`, called `what` in messages.
fn reader<'a>(source: &'a Source, table: Spanned<SpannedTable>, what: &str) -> TableReader<'a> {
    let span = table.span();
    TableReader::new(source, span, what, table.into_inner())
}

/// The file's materials, each with what fills it (a dielectric's `ior` becomes an anonymous
/// uniform medium, added to `media`), and their names.
struct Materials {
    list: Vec<Material>,
    names: Vec<String>,
    interiors: Vec<Option<MediumId>>,
}

/// The index of the medium `name` in `media`, or an error at `key` of `t`.
fn medium_index(t: &TableReader, key: &str, name: &str, media: &Media) -> Result<MediumId> {
    media
        .index(name)
        .ok_or_else(|| t.error(key, format!("no medium named '{name}'")))
}

/// The file's media, and the refusal of the first absorption that differs by channel, which
/// holds only where every path carries RGB ([`refuse_coloured_absorption`]).
struct ReadMedia {
    media: Media,
    coloured_absorption: Option<Error>,
}

fn read_media(source: &Source, tables: Vec<Spanned<SpannedTable>>) -> Result<ReadMedia> {
    let mut media = Media::default();
    let mut coloured_absorption = None;
    for table in tables {
        let mut t = reader(source, table, "[[medium]]");
        let name = named(&mut t, media.names(), "medium")?;
        let density = read_density(&mut t)?;
        let medium = read_profile(&mut t)?;
        let absorption = read_absorption(&mut t, density.clone())?;
        if absorption.as_ref().is_some_and(|a| !a.sigma_a.is_grey()) {
            coloured_absorption.get_or_insert_with(|| {
                t.error(
                    "absorption",
                    "differs by channel, which only images' RGB paths carry: this scene's \
                     photons carry single wavelengths (a dispersive medium, a dye or a \
                     fluorescent layer) or book an energy budget (receivers); give one number",
                )
            });
        }
        let scattering = read_scattering(&mut t, density.clone())?;
        let emission = read_emission(&mut t, absorption.is_some())?;
        let fluorescence = read_fluorescence(&mut t, density.is_some(), scattering.as_ref())?;
        if density.is_some() && scattering.is_none() && absorption.is_none() {
            let key = match t.has("density_file") {
                true => "density_file",
                false => "density_values",
            };
            t.warn(
                key,
                "a density scales `absorption` and `scattering`, and this medium has neither",
            );
        }
        if matches!(medium, Profile::Crystal(_)) {
            for (key, given) in [
                ("scattering", scattering.is_some()),
                ("emission", emission.is_some()),
                ("fluorescence", fluorescence.is_some()),
            ] {
                t.check(
                    key,
                    !given,
                    "a uniaxial crystal may absorb (`absorption`), but not scatter, emit or \
                     fluoresce: light in it travels as its two polarized waves, which those \
                     would need",
                )?;
            }
        }
        t.finish()?;
        let i = media.add_profile(name, medium);
        media.set_participating(
            i,
            Participating {
                absorption,
                scattering,
                emission,
                fluorescence,
            },
        );
    }
    Ok(ReadMedia {
        media,
        coloured_absorption,
    })
}

/// Refuses an absorption that differs by channel (`coloured`, its refusal) in a scene whose
/// photons carry single wavelengths — where σa would need a value at each — or whose receivers
/// book an energy budget, which books a photon's power by its channels' mean (a photon's
/// channels reweighed by Russian roulette on the way would leave the absorbed share unbooked).
fn refuse_coloured_absorption(
    coloured: Option<Error>,
    media: &Media,
    materials: &[Material],
    receivers: &[Receiver],
) -> Result<()> {
    let single_wavelengths = media.ids().any(|i| media.is_dispersive(i))
        || materials.iter().any(|m| m.fluorescence().is_some());
    match coloured {
        Some(refusal) if single_wavelengths || !receivers.is_empty() => Err(refusal),
        Some(_) | None => Ok(()),
    }
}

fn read_materials(
    source: &Source,
    tables: Vec<Spanned<SpannedTable>>,
    media: &mut Media,
) -> Result<Materials> {
    let mut m = Materials {
        list: Vec::new(),
        names: Vec::new(),
        interiors: Vec::new(),
    };
    for table in tables {
        let mut t = reader(source, table, "[[material]]");
        let name = named(&mut t, m.names.iter().map(String::as_str), "material")?;
        let (material, interior) = read_material(&mut t)?;
        let interior = match interior {
            None => None,
            Some(Interior::Medium(name)) => Some(medium_index(&t, "interior", &name, media)?),
            Some(Interior::Ior(d)) => {
                let label = match d {
                    Dispersion::Constant(n) => format!("{name} (ior {n})"),
                    _ => format!("{name} (dispersive ior)"),
                };
                Some(media.add_profile(label, uniform(d)))
            }
        };
        t.finish()?;
        m.list.push(material);
        m.names.push(name);
        m.interiors.push(interior);
    }
    Ok(m)
}

fn read_shapes(
    source: &Source,
    tables: Vec<Spanned<SpannedTable>>,
    materials: &Materials,
    media: &Media,
) -> Result<Vec<Shape>> {
    let mut shapes = Vec::new();
    for table in tables {
        let mut t = reader(source, table, "[[shape]]");
        let desc = read_shape(&mut t)?;
        let material = materials
            .names
            .iter()
            .position(|n| *n == desc.material)
            .ok_or_else(|| t.error("material", format!("no material named '{}'", desc.material)))?;
        let interior = match &desc.interior {
            Some(m) => Some(medium_index(&t, "interior", m, media)?),
            None => materials.interiors[material],
        };
        let kind = &materials.list[material];
        t.check(
            "material",
            !matches!(kind, Material::Dielectric { .. }) || interior.is_some(),
            "a dielectric shape needs an interior",
        )?;
        let exterior = match t.string_opt("exterior")? {
            Some(m) => Some(medium_index(&t, "exterior", &m, media)?),
            None => None,
        };
        let crystal = [interior, exterior]
            .into_iter()
            .flatten()
            .find(|&m| media.crystal(m).is_some());
        if let Some(m) = crystal {
            t.check(
                "material",
                matches!(kind, Material::Dielectric { microsurface: None }),
                format!(
                    "a surface of crystal '{}' must be a smooth `dielectric` (its faces split \
                     light into the crystal's two waves; a rough or thin one is not read)",
                    media.names().nth(m.index()).unwrap_or_default()
                ),
            )?;
        }
        t.finish()?;
        shapes.push(Shape {
            primitives: desc.primitives,
            uv_frame: desc.uv_frame,
            surface: Surface {
                role: Role::Scatter(MaterialId::new(material)),
                interior,
                exterior,
            },
        });
    }
    Ok(shapes)
}

/// The file's lights, the shape of each one's spectrum, and the environment.
type Lights = (Vec<Light>, Vec<Option<Spectrum>>, Option<Environment>);

fn read_lights(source: &Source, tables: Vec<Spanned<SpannedTable>>) -> Result<Lights> {
    let mut lights = Vec::new();
    let mut spectra = Vec::new();
    let mut environment = None;
    for table in tables {
        let mut t = reader(source, table, "[[light]]");
        let kind = t.string("type")?;
        if kind == "environment" {
            t.check(
                "type",
                environment.is_none(),
                "only one environment light is allowed",
            )?;
            environment = Some(read_environment(&mut t)?);
        } else {
            let (light, spectrum) = read_light_and_spectrum(&mut t, &kind)?;
            lights.push(light);
            spectra.push(spectrum);
        }
        t.finish()?;
    }
    Ok((lights, spectra, environment))
}

fn read_receivers(source: &Source, tables: Vec<Spanned<SpannedTable>>) -> Result<Vec<Receiver>> {
    let mut receivers: Vec<Receiver> = Vec::new();
    for table in tables {
        let mut t = reader(source, table, "[[receiver]]");
        let name = named(
            &mut t,
            receivers.iter().map(|r| r.name.as_str()),
            "receiver",
        )?;
        let receiver = read_receiver(&mut t, name)?;
        t.finish()?;
        receivers.push(receiver);
    }
    Ok(receivers)
}

fn read_settings(
    source: &Source,
    render: Option<Spanned<SpannedTable>>,
    output: Option<Spanned<SpannedTable>>,
    camera: Option<&Camera>,
) -> Result<Settings> {
    let mut settings = match render {
        Some(table) => {
            let mut t = reader(source, table, "[render]");
            let r = read_render(&mut t)?;
            if let (StepControl::Fixed { step }, Some(c)) = (r.trace.control, camera) {
                // A step below the rounding of the coordinates rays start at would leave
                // them where they are for every one of their steps.
                let floor = crate::curve::round_off_floor(c.position);
                t.check(
                    "step",
                    step > floor,
                    format!(
                        "a fixed step of {step:e} cannot move a ray from the camera at {:?} \
                         (the coordinates' rounding is {floor:.1e}): give a step above it",
                        c.position.to_array()
                    ),
                )?;
            }
            t.finish()?;
            r
        }
        None => Settings::default(),
    };
    if let Some(table) = output {
        let mut t = reader(source, table, "[output]");
        settings.output = read_output(&mut t)?;
        t.finish()?;
    }
    Ok(settings)
}

/// Parses scene text (already read from `path`): the scene's description and the settings of
/// its `[render]` and `[output]` tables.
pub fn parse_description(path: &Path, text: String) -> Result<(Description, Settings)> {
    parse(Source::file(path.to_path_buf(), text))
}

/// Parses a scene given as data (the scene file's schema as a table), its relative paths
/// resolved in `dir`: errors name the key's path (`medium[0].radius`).
pub fn parse_data(table: &toml::Table, dir: &Path) -> Result<(Description, Settings)> {
    parse(Source::data(SceneText::write(table), dir))
}

fn parse(source: Source) -> Result<(Description, Settings)> {
    let file: SceneFile = toml::from_str(&source.text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        let message = e.message().trim().replace('\n', " ");
        source.error_at(offset, message)
    })?;
    let ReadMedia {
        mut media,
        coloured_absorption,
    } = read_media(&source, file.medium)?;
    let materials = read_materials(&source, file.material, &mut media)?;
    let shapes = read_shapes(&source, file.shape, &materials, &media)?;
    let (lights, light_spectra, environment) = read_lights(&source, file.light)?;
    let receivers = read_receivers(&source, file.receiver)?;
    refuse_coloured_absorption(coloured_absorption, &media, &materials.list, &receivers)?;
    let ambient = match &file.ambient {
        None => None,
        Some(name) => {
            let error = |message: &str| {
                source.error_at(
                    name.span().start,
                    format!("key `ambient`: {message} '{}'", name.get_ref()),
                )
            };
            let m = (media.index(name.get_ref())).ok_or_else(|| error("no medium named"))?;
            if media.crystal(m).is_some() {
                return Err(error(
                    "the space around the scene cannot be a uniaxial crystal: bound it by a \
                     dielectric shape, as",
                ));
            }
            Some(m)
        }
    };
    let camera = file
        .camera
        .map(|table| {
            let mut t = reader(&source, table, "[camera]");
            let c = read_camera(&mut t)?;
            t.finish()?;
            Ok::<_, Error>(c)
        })
        .transpose()?;
    let settings = read_settings(&source, file.render, file.output, camera.as_ref())?;
    let description = Description {
        path: source.path.clone(),
        media,
        ambient,
        materials: materials.list,
        shapes,
        lights,
        light_spectra,
        environment,
        receivers,
        camera,
        inputs: (source.data.is_none())
            .then(|| source.path.clone())
            .into_iter()
            .chain(source.inputs.take())
            .collect(),
        warnings: source.warnings.take(),
    };
    Ok((description, settings))
}

/// Parses and builds scene text (already read from `path`): the scene and its settings.
pub fn parse_scene(path: &Path, text: String) -> Result<(Scene, Settings)> {
    let (description, settings) = parse_description(path, text)?;
    Ok((description.build(), settings))
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

/// Reads and parses the scene file at `path`: its description and settings.
pub fn load_description(path: &Path) -> Result<(Description, Settings)> {
    let text = crate::input::read_text(path, crate::input::MAX_SCENE_BYTES, "a scene file")?;
    parse_description(path, text)
}

/// Reads, parses and builds the scene file at `path`: the scene and its settings.
pub fn load_scene(path: &Path) -> Result<(Scene, Settings)> {
    let (description, settings) = load_description(path)?;
    Ok((description.build(), settings))
}
