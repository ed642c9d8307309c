//! The scene as data, in two forms. A [`Description`] is what the file says with its names
//! resolved — media, materials, shapes, lights, receivers, camera — and may be edited (the
//! layered twin of a GRIN fiber is such an edit, [`crate::fiber`]). [`Description::build`]
//! turns it into the render-ready [`Scene`]: every surface a primitive with its surface
//! description, area lights and receivers among them, all in one acceleration structure.

use crate::accel::Accel;
use crate::camera::Camera;
use crate::environment::Environment;
use crate::error::{Error, Result};
use crate::ids::{LightId, MaterialId, MediumId, PrimId, ReceiverId};
use crate::lights::Light;
use crate::material::{FluorescentLayer, Material};
use crate::media::{Medium, Parametric, UniformMedium};
use crate::polarization::crystal::{Uniaxial, Wave};
use crate::receiver::Receiver;
use crate::shapes::{Primitive, UvFrame};
use crate::spectrum::Dispersion;
use crate::spectrum::{colour, Binned, Excitation, Hero, Spectrum, LAMBDA_D};
use crate::volume::{Fluorescence, Participating, Scattering};
use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};

/// A dispersive medium's profile at a vacuum wavelength (nm): its constants evaluated there.
pub type AtWavelength = Box<dyn Fn(f64) -> Parametric + Send + Sync>;

/// A medium as read: one medium, or, when its index depends on wavelength, how to build it at
/// each.
pub enum Profile {
    /// The same at every wavelength.
    Fixed(Box<dyn Medium>),
    /// The same at every wavelength, given by a formula and its constants.
    Parametric(Parametric),
    /// Dispersive.
    Dispersive(AtWavelength),
    /// A uniaxial crystal: a medium for each of its two waves ([`Media::crystal`]).
    Crystal(Box<Crystal>),
}

/// A uniaxial crystal as read: its indices over wavelength and its optic axis.
#[derive(Clone, Debug)]
pub struct Crystal {
    /// n_o(λ), the ordinary index.
    pub ordinary: Dispersion,
    /// n_e(λ), the extraordinary index.
    pub extraordinary: Dispersion,
    /// The unit optic axis.
    pub axis: DVec3,
}

impl Crystal {
    /// The crystal at vacuum wavelength `nm`.
    pub fn at(&self, nm: f64) -> Uniaxial {
        Uniaxial {
            ordinary: self.ordinary.at(nm),
            extraordinary: self.extraordinary.at(nm),
            axis: self.axis,
        }
    }

    /// Whether its indices depend on wavelength.
    pub fn is_dispersive(&self) -> bool {
        self.ordinary.is_dispersive() || self.extraordinary.is_dispersive()
    }
}

/// Where a medium is one of a crystal's waves: the crystal, the wave, and the medium of its
/// other wave.
#[derive(Clone, Debug)]
pub struct CrystalWave {
    /// The crystal.
    pub crystal: Crystal,
    /// Which of its waves the medium carries.
    pub wave: Wave,
    /// The medium of its other wave.
    pub other: MediumId,
}

/// One medium of the scene: its name, the medium at [`LAMBDA_D`] (what RGB camera paths see)
/// and, if its index depends on wavelength, how to build it at another.
struct Entry {
    name: String,
    medium: Held,
    dispersion: Option<AtWavelength>,
    /// What it does to light's power: absorbs, scatters, emits.
    participating: Participating,
    /// Where it is one of a crystal's waves.
    crystal: Option<CrystalWave>,
}

/// How a medium at [`LAMBDA_D`] is held: as its own type where it is given by a formula (a
/// march can then be compiled for it: [`Media::parametric`]), else behind `dyn Medium`.
enum Held {
    Parametric(Parametric),
    Boxed(Box<dyn Medium>),
}

impl Held {
    fn medium(&self) -> &(dyn Medium + 'static) {
        match self {
            Held::Parametric(p) => p.as_medium(),
            Held::Boxed(m) => m.as_ref(),
        }
    }
}

/// The scene's media by name; [`Surface::interior`], [`Surface::exterior`] and the ambient
/// medium refer to them by index. Zhdanov et al. (2020) asks each medium which wavelengths can share a
/// path through it: all of them unless it is dispersive ([`Media::is_dispersive`]), and then
/// each wavelength has a path of its own ([`Media::at_wavelength`]).
#[derive(Default)]
pub struct Media(Vec<Entry>);

impl Media {
    /// Adds a medium whose index does not depend on wavelength and returns its index.
    pub fn add(&mut self, name: impl Into<String>, medium: Box<dyn Medium>) -> MediumId {
        self.push(name.into(), Held::Boxed(medium))
    }

    /// Adds a medium given by a formula, the same at every wavelength, and returns its index.
    pub fn add_parametric(&mut self, name: impl Into<String>, medium: Parametric) -> MediumId {
        self.push(name.into(), Held::Parametric(medium))
    }

    fn push(&mut self, name: String, medium: Held) -> MediumId {
        self.0.push(Entry {
            name,
            medium,
            dispersion: None,
            participating: Participating::default(),
            crystal: None,
        });
        MediumId::new(self.0.len() - 1)
    }

    /// Adds a dispersive medium, built by `at` for each wavelength, and returns its index.
    pub fn add_dispersive(&mut self, name: impl Into<String>, at: AtWavelength) -> MediumId {
        self.0.push(Entry {
            name: name.into(),
            medium: Held::Parametric(at(LAMBDA_D)),
            dispersion: Some(at),
            participating: Participating::default(),
            crystal: None,
        });
        MediumId::new(self.0.len() - 1)
    }

    /// Adds a medium as read and returns its index.
    pub fn add_profile(&mut self, name: impl Into<String>, profile: Profile) -> MediumId {
        match profile {
            Profile::Fixed(m) => self.add(name, m),
            Profile::Parametric(m) => self.add_parametric(name, m),
            Profile::Dispersive(at) => self.add_dispersive(name, at),
            Profile::Crystal(crystal) => self.add_crystal(name.into(), *crystal),
        }
    }

    /// Adds a uniaxial crystal: the medium its ordinary wave travels in (index n_o, called
    /// `name`: shapes and materials name it) and, next, its extraordinary wave's ("`name`
    /// (extraordinary wave)"), each straight and uniform, and dispersive where either index
    /// is (a path takes on one wavelength where it meets the crystal); returns the ordinary
    /// one's index. What either is to the transport beyond a straight stretch — its index for
    /// a wave, and what its faces do — is [`Media::crystal`]'s.
    fn add_crystal(&mut self, name: String, crystal: Crystal) -> MediumId {
        let (ordinary, extraordinary) =
            (MediumId::new(self.0.len()), MediumId::new(self.0.len() + 1));
        for (label, wave, other) in [
            (name.clone(), Wave::Ordinary, extraordinary),
            (
                format!("{name} (extraordinary wave)"),
                Wave::Extraordinary,
                ordinary,
            ),
        ] {
            let n = crystal.ordinary.clone();
            let at = move |nm: f64| Parametric::Uniform(UniformMedium { n: n.at(nm) });
            self.0.push(Entry {
                name: label,
                medium: Held::Parametric(at(LAMBDA_D)),
                dispersion: crystal
                    .is_dispersive()
                    .then(|| Box::new(at) as AtWavelength),
                participating: Participating::default(),
                crystal: Some(CrystalWave {
                    crystal: crystal.clone(),
                    wave,
                    other,
                }),
            });
        }
        ordinary
    }

    /// Where medium `i` is one of a crystal's waves (None: it is isotropic).
    pub fn crystal(&self, i: MediumId) -> Option<&CrystalWave> {
        self.0[i.index()].crystal.as_ref()
    }

    /// The medium of crystal medium `i`'s wave `wave` (`i` itself for an isotropic one).
    pub fn of_wave(&self, i: MediumId, wave: Wave) -> MediumId {
        match self.crystal(i) {
            Some(c) if c.wave != wave => c.other,
            Some(_) | None => i,
        }
    }

    /// The first crystal, by name (None: none).
    pub fn first_crystal(&self) -> Option<&str> {
        (self.0.iter())
            .find(|e| e.crystal.is_some())
            .map(|e| e.name.as_str())
    }

    /// The medium at index `i`, at [`LAMBDA_D`].
    pub fn at(&self, i: MediumId) -> &(dyn Medium + 'static) {
        self.0[i.index()].medium.medium()
    }

    /// Medium `i` at [`LAMBDA_D`] as its own type, where it is given by a formula.
    pub fn parametric(&self, i: MediumId) -> Option<&Parametric> {
        match &self.0[i.index()].medium {
            Held::Parametric(p) => Some(p),
            Held::Boxed(_) => None,
        }
    }

    /// Sets what medium `i` does to light's power (and its other wave's, for a crystal).
    pub fn set_participating(&mut self, i: MediumId, participating: Participating) {
        if let Some(other) = self.0[i.index()].crystal.as_ref().map(|c| c.other) {
            self.0[other.index()].participating = participating.clone();
        }
        self.0[i.index()].participating = participating;
    }

    /// What medium `i` does to light's power.
    pub fn participating(&self, i: MediumId) -> &Participating {
        &self.0[i.index()].participating
    }

    /// How medium `i` scatters (None: it does not).
    pub fn scattering(&self, i: MediumId) -> Option<&Scattering> {
        self.0[i.index()].participating.scattering.as_ref()
    }

    /// Whether every medium's index is the same all through it (each as it is at
    /// [`LAMBDA_D`]; a dispersive medium keeps its form at every wavelength): rays are then
    /// straight between surfaces.
    pub fn all_uniform(&self) -> bool {
        self.0.iter().all(|e| e.medium.medium().is_uniform())
    }

    /// Whether any medium scatters.
    pub fn any_scatters(&self) -> bool {
        self.0.iter().any(|e| e.participating.scattering.is_some())
    }

    /// The first medium that emits, by name (None: none does).
    pub fn first_emitting(&self) -> Option<&str> {
        self.0
            .iter()
            .find(|e| e.participating.emission.is_some())
            .map(|e| e.name.as_str())
    }

    /// The dye medium `i` holds (None: none).
    pub fn fluorescence(&self, i: MediumId) -> Option<&Fluorescence> {
        self.0[i.index()].participating.fluorescence.as_ref()
    }

    /// The first medium that holds a dye, by name (None: none does).
    pub fn first_fluorescent(&self) -> Option<&str> {
        self.0
            .iter()
            .find(|e| e.participating.fluorescence.is_some())
            .map(|e| e.name.as_str())
    }

    /// Whether a path through medium `i` depends on its wavelength: its index does, its
    /// scattering coefficient, or a dye's absorption.
    pub fn is_dispersive(&self, i: MediumId) -> bool {
        let e = &self.0[i.index()];
        e.dispersion.is_some()
            || e.participating.fluorescence.is_some()
            || e.participating
                .scattering
                .as_ref()
                .is_some_and(Scattering::is_spectral)
    }

    /// Medium `i` at vacuum wavelength `nm`, when it is dispersive (None: it is
    /// [`Media::at`] at every wavelength). Made on the stack: a path at a wavelength asks
    /// for it where it enters the medium.
    pub fn at_wavelength(&self, i: MediumId, nm: f64) -> Option<Parametric> {
        self.0[i.index()].dispersion.as_ref().map(|at| at(nm))
    }

    /// The number of media.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Every medium's id, in order.
    pub fn ids(&self) -> impl Iterator<Item = MediumId> {
        (0..self.0.len()).map(MediumId::new)
    }

    /// The index of the medium called `name`.
    pub fn index(&self, name: &str) -> Option<MediumId> {
        self.0
            .iter()
            .position(|e| e.name == name)
            .map(MediumId::new)
    }

    /// Names of all media, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.0.iter().map(|e| e.name.as_str())
    }
}

/// A surface of the scene: what it does to light and what fills it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// What it does to the light that meets it.
    pub role: Role,
    /// What is inside (dielectrics; None: vacuum).
    pub interior: Option<MediumId>,
    /// What is outside (dielectrics; None: vacuum). Lets a dielectric separate two media,
    /// e.g. concentric layers of a fiber. In a [`Description`], None is the ambient medium,
    /// which [`Description::build`] writes here.
    pub exterior: Option<MediumId>,
}

/// What a surface does to the light that meets it: scatter it by a material, record it (a
/// receiver's detector plane) or emit (an area light's surface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Role {
    /// It scatters by this material.
    Scatter(MaterialId),
    /// A receiver's detector plane: transparent, it
    /// records the photons crossing it.
    Detector(ReceiverId),
    /// An area light's emitting surface: the light's
    /// radiance from its front side (the side its normal points to), black behind; it
    /// reflects nothing.
    Emitter(LightId),
}

impl Surface {
    /// A receiver's detector plane, which every ray and photon passes through unchanged.
    pub fn is_detector(&self) -> bool {
        matches!(self.role, Role::Detector(_))
    }
}

/// A `[[shape]]`: its primitives, all with one surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// The primitives.
    pub primitives: Vec<Primitive>,
    /// What they are made of and what they hold.
    pub surface: Surface,
    /// The frame its round primitives' surface coordinates are read in (None: their own).
    pub uv_frame: Option<UvFrame>,
}

/// What a scene file says, names resolved: editable, then built.
pub struct Description {
    /// The scene file.
    pub path: PathBuf,
    /// Media.
    pub media: Media,
    /// The medium filling space outside all shapes (None: vacuum, n = 1).
    pub ambient: Option<MediumId>,
    /// The file's materials.
    pub materials: Vec<Material>,
    /// The file's shapes.
    pub shapes: Vec<Shape>,
    /// Lights (the environment apart); area lights are also surfaces of the built scene.
    pub lights: Vec<Light>,
    /// The emission spectrum each light was given, by light index (None: none given; see
    /// [`Scene::light_spectrum`]).
    pub light_spectra: Vec<Option<Spectrum>>,
    /// What escaping rays see (None: black).
    pub environment: Option<Environment>,
    /// Detector planes (also transparent surfaces of the built scene).
    pub receivers: Vec<Receiver>,
    /// The camera, if any.
    pub camera: Option<Camera>,
    /// The scene file and every file it reads (meshes, images, grids).
    pub inputs: Vec<PathBuf>,
    /// What its user should know though it loads (file:line:col: message): shown by the
    /// commands that render it.
    pub warnings: Vec<String>,
}

impl Description {
    /// The render-ready scene: the shapes' primitives, then each area light's emitting surface,
    /// then each receiver's detector, in one acceleration structure.
    pub fn build(self) -> Scene {
        let mut primitives = Vec::new();
        let mut surfaces = Vec::new();
        let mut uv_frames = Vec::new();
        for shape in self.shapes {
            let surface = Surface {
                exterior: shape.surface.exterior.or(self.ambient),
                ..shape.surface
            };
            if let Some(frame) = shape.uv_frame {
                let first = primitives.len();
                uv_frames.extend(
                    (first..first + shape.primitives.len()).map(|i| (PrimId::new(i), frame)),
                );
            }
            surfaces.extend(std::iter::repeat_n(surface, shape.primitives.len()));
            primitives.extend(shape.primitives);
        }
        let mut add = |role: Role, primitive: Primitive| {
            surfaces.push(Surface {
                role,
                interior: None,
                exterior: None,
            });
            primitives.push(primitive);
        };
        for (i, light) in self.lights.iter().enumerate() {
            match light {
                Light::Area { emitter, .. } => {
                    add(Role::Emitter(LightId::new(i)), emitter.primitive())
                }
                Light::Point { .. }
                | Light::Spot { .. }
                | Light::Led { .. }
                | Light::Goniometric { .. }
                | Light::Directional { .. } => {}
            }
        }
        for (receiver, r) in self.receivers.iter().enumerate() {
            add(Role::Detector(ReceiverId::new(receiver)), r.primitive());
        }
        let fluoresces = self.materials.iter().any(|m| m.fluorescence().is_some());
        let sources = (fluoresces || self.media.first_fluorescent().is_some())
            .then(|| source_spectrum(&self.light_spectra, self.environment.is_some()))
            .flatten();
        let excited = |f: &Excitation| {
            let sources = sources.as_ref()?;
            Binned::new(|nm| f.at(nm) * nm * sources.pdf(nm))
        };
        let excitations = (self.materials.iter())
            .map(|m| excited(&m.fluorescence()?.excitation))
            .collect();
        let dye_excitations = (self.media.ids())
            .map(|i| excited(&self.media.fluorescence(i)?.absorption))
            .collect();
        let dye_lines: Vec<Binned> = (self.media.ids())
            .filter_map(|i| self.media.fluorescence(i))
            .filter_map(|dye| Binned::new(|nm| dye.fluorophore.emission.pdf(nm)))
            .collect();
        let dye_lines = Binned::mixture(&dye_lines);
        Scene {
            fluoresces,
            sources,
            excitations,
            dye_excitations,
            dye_lines,
            path: self.path,
            media: self.media,
            ambient: self.ambient,
            materials: self.materials,
            surfaces,
            uv_frames,
            accel: Accel::new(primitives),
            lights: self.lights,
            light_spectra: self.light_spectra,
            environment: self.environment,
            receivers: self.receivers,
            camera: self.camera,
            inputs: self.inputs,
        }
    }
}

/// The density over wavelength of the light of lights of `spectra` (None: D65) and, where
/// `environment`, the environment's D65, in equal shares; None without a source.
fn source_spectrum(spectra: &[Option<Spectrum>], environment: bool) -> Option<Binned> {
    let d65 = || Binned::new(colour::d65);
    let parts: Option<Vec<Binned>> = spectra
        .iter()
        .map(|s| match s {
            Some(s) => Binned::new(|nm| s.pdf(nm)),
            None => d65(),
        })
        .chain(environment.then(d65))
        .collect();
    Binned::mixture(&parts?)
}

/// A built scene, immutable and shareable across threads.
pub struct Scene {
    path: PathBuf,
    media: Media,
    /// The medium filling space outside all shapes (None: vacuum, n = 1); every surface's
    /// exterior is resolved against it when the scene is built.
    ambient: Option<MediumId>,
    /// Materials by index.
    pub materials: Vec<Material>,
    /// Per primitive of [`Scene::accel`], its surface.
    pub surfaces: Vec<Surface>,
    /// The primitives whose surface coordinates are read in a frame of their own, ascending.
    uv_frames: Vec<(PrimId, UvFrame)>,
    /// The primitives and their BVH.
    pub accel: Accel,
    /// Lights (the environment apart).
    pub lights: Vec<Light>,
    /// The emission spectrum each light was given, by light index (None: none given; see
    /// [`Scene::light_spectrum`]).
    pub light_spectra: Vec<Option<Spectrum>>,
    /// What escaping rays see (None: black).
    pub environment: Option<Environment>,
    /// Detector planes.
    pub receivers: Vec<Receiver>,
    /// The camera, if the scene has one.
    pub camera: Option<Camera>,
    /// The scene file and every file it reads (meshes, images, grids).
    pub inputs: Vec<PathBuf>,
    /// Whether a surface has a fluorescent layer (see [`Scene::fluoresces`]).
    fluoresces: bool,
    /// Where a surface fluoresces or a medium holds a dye: the light the scene's sources emit
    /// over wavelength (see
    /// [`Scene::sources`]).
    sources: Option<Binned>,
    /// By material, for a material with a fluorescent layer: the density of the light it
    /// absorbs from the scene's sources over wavelength (see [`Scene::excitation`]).
    excitations: Vec<Option<Binned>>,
    /// By medium, for a medium holding a dye: the density of the light the dye absorbs from
    /// the scene's sources over wavelength (see [`Scene::dye_excitation`]).
    dye_excitations: Vec<Option<Binned>>,
    /// The dyes' emission lines in equal shares (None: no medium holds a dye; see
    /// [`Scene::hero`]).
    dye_lines: Option<Binned>,
}

impl Scene {
    /// The material a surface scatters by; None for a detector or an emitter.
    pub fn material(&self, surface: Surface) -> Option<&Material> {
        match surface.role {
            Role::Scatter(m) => Some(&self.materials[m.index()]),
            Role::Detector(_) | Role::Emitter(_) => None,
        }
    }

    /// The medium called `name`; the error lists the names that exist. A crystal is refused:
    /// what a ray does in it depends on which of its waves it is.
    pub fn medium(&self, name: &str) -> Result<&dyn Medium> {
        match self.media.index(name) {
            Some(i) if self.media.crystal(i).is_some() => Err(Error::Usage(format!(
                "{}: medium '{name}' is a uniaxial crystal: rays in it are straight, and its \
                 light travels as two waves that part at its faces — render it, or measure \
                 it with receivers",
                self.path.display()
            ))),
            Some(i) => Ok(self.media.at(i)),
            None => {
                let known: Vec<&str> = self.media.names().collect();
                Err(Error::Usage(format!(
                    "{}: no medium named '{name}' (the scene has: {})",
                    self.path.display(),
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                )))
            }
        }
    }

    /// The surface of primitive `prim`.
    pub fn surface(&self, prim: PrimId) -> Surface {
        self.surfaces[prim.index()]
    }

    /// The surface coordinates of point `x` on analytic primitive `prim`: in its shape's
    /// frame where the scene gives one ([`UvFrame`]), else its own ([`Primitive::uv_at`]).
    pub fn uv_at(&self, prim: PrimId, x: DVec3) -> DVec2 {
        let primitive = self.accel.primitive(prim);
        match self.uv_frames.binary_search_by_key(&prim, |(p, _)| *p) {
            Ok(i) => self.uv_frames[i].1.uv_at(primitive, x),
            Err(_) => primitive.uv_at(x),
        }
    }

    /// Whether a surface may join equal indices (a smooth dielectric: its indices are
    /// known only at a hit, [`crate::transport::Tracer::crosses_unchanged`]); where none
    /// may, a shadow ray is blocked by any surface it meets.
    pub fn may_match_indices(&self) -> bool {
        (self.materials.iter()).any(|m| matches!(m, Material::Dielectric { microsurface: None }))
    }

    /// The light `id`.
    pub fn light(&self, id: LightId) -> &Light {
        &self.lights[id.index()]
    }

    /// The receiver `id`.
    pub fn receiver(&self, id: ReceiverId) -> &Receiver {
        &self.receivers[id.index()]
    }

    /// The medium filling space outside all shapes (None: vacuum, n = 1).
    pub fn ambient(&self) -> Option<MediumId> {
        self.ambient
    }

    /// The medium `i` (see [`Surface::interior`] and [`Scene::ambient`]).
    pub fn medium_at(&self, i: MediumId) -> &dyn Medium {
        self.media.at(i)
    }

    /// The scene's media.
    pub fn media(&self) -> &Media {
        &self.media
    }

    /// The emission spectrum light `i` was given (its colour in images is the spectrum's,
    /// scaled by its power key), or None: its colour is its RGB and it emits D65
    /// ([`Spectrum::white`], as the environment does).
    pub fn light_spectrum(&self, i: usize) -> Option<&Spectrum> {
        self.light_spectra.get(i).and_then(Option::as_ref)
    }

    /// Whether a path's course depends on its wavelength: some medium is dispersive (camera
    /// paths and photons then take a hero wavelength where they meet it).
    pub fn is_dispersive(&self) -> bool {
        self.media.ids().any(|i| self.media.is_dispersive(i))
    }

    /// Whether photons must carry a wavelength: a medium is dispersive, a surface fluoresces
    /// or a receiver measures wavelength bands.
    pub fn is_spectral(&self) -> bool {
        self.is_dispersive()
            || self.materials.iter().any(|m| m.fluorescence().is_some())
            || self.receivers.iter().any(|r| !r.bands.is_empty())
    }

    /// Whether a surface has a fluorescent layer: a path that meets one takes on one
    /// wavelength there (as where it meets dispersion).
    pub fn fluoresces(&self) -> bool {
        self.fluoresces
    }

    /// The density over wavelength of the light the scene's sources emit, each light and the
    /// environment in equal shares (a light without a spectrum, and the environment, emit
    /// D65): where camera paths that meet a fluorescent layer draw a wavelength
    /// ([`FluorescentLayer::hero`]). None in a scene without a fluorescent layer or a dye, or
    /// without a source.
    pub fn sources(&self) -> Option<&Binned> {
        self.sources.as_ref()
    }

    /// The density over wavelength of the light the fluorescent layer on primitive `prim`'s
    /// surface absorbs from the scene's sources, in proportion to a(λ)·λ·s(λ): s the light the
    /// sources emit, each light and the environment in equal shares (a light without a
    /// spectrum, and the environment, emit D65). Where camera paths draw the wavelength a
    /// layer absorbs ([`FluorescentLayer::relight`]). None without a layer there, or without a
    /// source whose light it absorbs.
    pub fn excitation(&self, prim: PrimId) -> Option<&Binned> {
        match self.surfaces[prim.index()].role {
            Role::Scatter(m) => self.excitations[m.index()].as_ref(),
            Role::Detector(_) | Role::Emitter(_) => None,
        }
    }

    /// The hero wavelength a camera sample draws for uniform `u` ([`Hero`]): from the
    /// visible-importance density, and in a scene with dyes from their emission lines too, in
    /// equal shares (a dye's light is seen only by paths at its line's wavelengths).
    pub fn hero(&self, u: f64) -> Hero {
        match &self.dye_lines {
            Some(lines) => Hero::visible_or(&[lines], u),
            None => Hero::visible(u),
        }
    }

    /// The density over wavelength of the light the dye in medium `i` absorbs from the
    /// scene's sources, in proportion to σf(λ)·λ·s(λ) (s as in [`Scene::excitation`]): where
    /// camera paths draw the wavelength a dye absorbs. None without a dye there, or without a
    /// source whose light it absorbs.
    pub fn dye_excitation(&self, i: MediumId) -> Option<&Binned> {
        self.dye_excitations[i.index()].as_ref()
    }

    /// The fluorescent layer on primitive `prim`'s surface (None: none).
    pub fn fluorescent_layer(&self, prim: PrimId) -> Option<&FluorescentLayer> {
        self.material(self.surfaces[prim.index()])?.fluorescence()
    }

    /// What fluoresces first in the scene, in words (None: nothing does).
    pub fn first_fluorescent(&self) -> Option<String> {
        match self.media.first_fluorescent() {
            Some(name) => Some(format!("medium '{name}' holds a dye")),
            None => self
                .materials
                .iter()
                .any(|m| m.fluorescence().is_some())
                .then(|| "a diffuse material has a fluorescent layer".to_string()),
        }
    }

    /// Names of all media, in file order.
    pub fn medium_names(&self) -> impl Iterator<Item = &str> {
        self.media.names()
    }

    /// The scene file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}
