//! Moving a ray through the scene to its next event: straight through uniform media (BVH ray
//! traversal), curved through gradient media (the march, each accepted step tested against
//! the BVH as an exact arc). On top of it, shared by every pass: the specular chain
//! ([`chain`]: mirrors, dielectrics and detectors followed to the next diffuse surface,
//! emitter or escape, with the radiance change across indices), the visibility query
//! ([`visibility`]: the only straight shadow ray) and curved connections to lights from
//! gradient media ([`connect`]).

pub mod chain;
pub mod connect;
pub mod lighting;
mod stats;
mod vertex;
pub mod visibility;

pub use vertex::{BsdfNumbers, MediumVertex, Scattered, SurfaceVertex, Vertex};

use crate::color::Rgb;
use crate::curve::{
    march_with, Bounds, ExactPath, HermitePath, MarchLimits, MarchOutcome, Path, RayState,
    StepControl, Termination,
};
use crate::ids::MediumId;
use crate::lights::{LightSampler, LightSamples};
use crate::material::{Material, SurfacePoint};
use crate::math::Ball;
use crate::media::Medium;
use crate::scene::{Scene, Surface};
use crate::settings::TraceSettings;
use crate::shapes::Hit;
use crate::spectrum::{colour, Hero, LAMBDA_D};
use crate::volume::{Participating, Scattering};
use glam::{DVec2, DVec3};
pub use stats::Stats;
use std::ops::ControlFlow;

/// What a ray meets next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A surface: the primitive, the hit point, the primitive's geometric and shading normals
    /// there and the ray's direction on arrival.
    Surface {
        /// Primitive index.
        prim: usize,
        /// Hit point.
        position: DVec3,
        /// Geometric normal (see [`crate::shapes::Hit`]): which side the ray is on.
        normal: DVec3,
        /// Shading normal, on the geometric normal's side: what a specular surface reflects
        /// and refracts about.
        shading: DVec3,
        /// A mesh's surface coordinates (u, v) of the hit, for textures
        /// ([`crate::shapes::Hit::uv`]).
        uv: Option<DVec2>,
        /// Unit direction of arrival.
        direction: DVec3,
        /// Path length from the origin to the hit (scene units).
        distance: f64,
        /// Optical depth ∫ σa ds of absorption from the origin to the hit.
        optical_depth: f64,
    },
    /// The ray left the world sphere.
    Escaped {
        /// Where it left.
        position: DVec3,
        /// Unit direction when leaving.
        direction: DVec3,
        /// Path length from the origin to the world sphere (scene units).
        distance: f64,
        /// Optical depth ∫ σa ds of absorption from the origin to the world sphere.
        optical_depth: f64,
    },
    /// The ray went the arclength it was allowed ([`Tracer::next_event_within`]) before any
    /// surface: where a free flight in a scattering medium ends.
    Reached {
        /// Where.
        position: DVec3,
        /// Unit direction of travel there.
        direction: DVec3,
        /// Path length from the origin (the allowed arclength).
        distance: f64,
        /// Optical depth ∫ σa ds of absorption from the origin.
        optical_depth: f64,
    },
    /// The ray ended without reaching a surface or escaping: captured, out of steps, trapped
    /// (a curved path 100 world radii long that never left the world), or lost inside an
    /// object it should have left; the reason is counted in the statistics.
    Lost,
}

impl Event {
    /// Where the ray meets a surface, if it does.
    pub fn surface_hit(&self) -> Option<SurfaceHit> {
        match *self {
            Event::Surface {
                prim,
                position,
                normal,
                shading,
                uv,
                direction,
                ..
            } => Some(SurfaceHit {
                prim,
                position,
                normals: Normals {
                    geometric: normal,
                    shading,
                },
                uv,
                incoming: direction,
            }),
            _ => None,
        }
    }

    /// The path length from the origin to the event (0 when lost).
    pub fn distance(&self) -> f64 {
        match *self {
            Event::Surface { distance, .. }
            | Event::Escaped { distance, .. }
            | Event::Reached { distance, .. } => distance,
            Event::Lost => 0.0,
        }
    }

    /// Where the event happens (None when lost).
    pub fn position(&self) -> Option<DVec3> {
        match *self {
            Event::Surface { position, .. }
            | Event::Escaped { position, .. }
            | Event::Reached { position, .. } => Some(position),
            Event::Lost => None,
        }
    }

    /// The event of a ray that had gone `distance` with absorption `depth` before the start
    /// it was traced from: both added to its own.
    pub fn continuing(mut self, before: f64, depth_before: f64) -> Event {
        if let Event::Surface {
            distance,
            optical_depth,
            ..
        }
        | Event::Escaped {
            distance,
            optical_depth,
            ..
        }
        | Event::Reached {
            distance,
            optical_depth,
            ..
        } = &mut self
        {
            *distance += before;
            *optical_depth += depth_before;
        }
        self
    }

    /// The optical depth ∫σa ds of absorption on the way to the event (∞ when lost).
    pub fn optical_depth(&self) -> f64 {
        match *self {
            Event::Surface { optical_depth, .. }
            | Event::Escaped { optical_depth, .. }
            | Event::Reached { optical_depth, .. } => optical_depth,
            Event::Lost => f64::INFINITY,
        }
    }

    /// The fraction exp(−∫σa ds) of light kept on the way to the event (0 when lost).
    pub fn transmittance(&self) -> f64 {
        (-self.optical_depth()).exp()
    }
}

pub use crate::math::{facing, offset};

/// A surface's two normals at a hit (see [`crate::shapes::Hit`]): the geometric one tells
/// which side a ray is on, the shading one (same side) is what a specular surface reflects
/// and refracts about.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Normals {
    /// Unit geometric normal.
    pub geometric: DVec3,
    /// Unit shading normal.
    pub shading: DVec3,
}

/// Where a path meets a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    /// Primitive index.
    pub prim: usize,
    /// Hit point.
    pub position: DVec3,
    /// The surface's normals there.
    pub normals: Normals,
    /// A mesh's surface coordinates (u, v) there ([`crate::shapes::Hit::uv`]; an analytic
    /// primitive's are worked out where a texture asks).
    pub uv: Option<DVec2>,
    /// Unit direction of arrival.
    pub incoming: DVec3,
}

/// Where rays travel: the scene, how rays travel in it, the sphere holding everything in it,
/// and the sphere beyond which rays count as escaped.
pub struct Tracer<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// How rays travel.
    pub settings: TraceSettings,
    /// The smallest axis-aligned-box sphere around the primitives and the camera.
    pub ball: Ball,
    /// The world sphere.
    pub world: Bounds,
    /// The medium the camera sits in (see [`Tracer::medium_containing`]).
    pub camera_medium: Option<MediumId>,
    /// Which light a vertex's light sample goes to.
    pub light_sampler: LightSampler,
    /// How many lights a vertex's direct estimate samples (the integrator's choice:
    /// [`Tracer::sampling_lights`]; one unless it says).
    pub light_samples: LightSamples,
    /// The wavelength rays travel at, when it is not [`LAMBDA_D`] (see
    /// [`Tracer::at_wavelength`]).
    wavelength: Option<Wavelength>,
}

/// A vacuum wavelength (nm) and the scene's dispersive media rebuilt at it (None where a
/// medium is the same at every wavelength).
struct Wavelength {
    nm: f64,
    media: Vec<Option<Box<dyn Medium>>>,
    /// Each medium's scattering at `nm`, where σs depends on wavelength.
    scattering: Vec<Option<Scattering>>,
}

/// A hero wavelength ready for the paths of one camera sample or one photon to take on where
/// they meet dispersion ([`Hero`]; [`chain::Walker`] does it): the tracer at that wavelength,
/// built the first time a path needs it (most paths of a scene never meet its dispersive
/// part), and the sRGB weight r̄(λ)/p(λ) a camera path's throughput takes on there.
pub struct HeroTracer<'a> {
    /// The tracer the paths start on.
    base: &'a Tracer<'a>,
    /// The hero wavelength, nm.
    nm: f64,
    /// The tracer at `nm`, once built.
    at: std::cell::OnceCell<Tracer<'a>>,
    /// [`Hero::sensor_weight`] (one for a photon, whose power changes at dispersion as its
    /// source's spectrum says).
    pub weight: Rgb,
}

impl<'a> HeroTracer<'a> {
    /// `tracer`'s hero `hero`, for camera paths.
    pub fn new(tracer: &'a Tracer<'a>, hero: Hero) -> Self {
        Self {
            base: tracer,
            nm: hero.nm,
            at: std::cell::OnceCell::new(),
            weight: hero.sensor_weight(),
        }
    }

    /// `tracer`'s hero at vacuum wavelength `nm`, for a photon.
    pub fn for_photon(tracer: &'a Tracer<'a>, nm: f64) -> Self {
        Self {
            base: tracer,
            nm,
            at: std::cell::OnceCell::new(),
            weight: Rgb::ONE,
        }
    }

    /// The tracer with rays at the hero wavelength.
    pub fn tracer(&self) -> &Tracer<'a> {
        self.at.get_or_init(|| self.base.at_wavelength(self.nm))
    }
}

/// A gradient medium a march crosses: its index field and what it does to light's power.
#[derive(Clone, Copy)]
struct Along<'m> {
    medium: &'m dyn Medium,
    radiometry: &'m Participating,
}

/// A march to the next surface: the surface met or the point at the reach (None: neither),
/// how the march ended, and the optical depth of absorption along the path it went.
struct Marched {
    hit: Option<Event>,
    outcome: MarchOutcome,
    optical_depth: f64,
}

/// Directions along which [`Tracer::medium_containing`] looks for the enclosing surface: far
/// from any axis, so they rarely graze the axis-aligned walls of a scene.
const PROBES: [DVec3; 3] = [
    DVec3::new(
        0.267_261_241_912_424_4,
        0.534_522_483_824_848_8,
        0.801_783_725_737_273_2,
    ),
    DVec3::new(
        -0.615_457_454_897_398_3,
        0.492_365_963_917_918_6,
        0.615_457_454_897_398_3,
    ),
    DVec3::new(
        0.455_842_305_838_552_3,
        -0.683_763_458_757_828_4,
        -0.569_802_882_298_190_4,
    ),
];

impl<'a> Tracer<'a> {
    /// The tracer of a scene; the world sphere is the scene's `world_radius` around the centre
    /// of everything in it (primitives and camera), or 10× its extent (at least 10 units).
    pub fn new(scene: &'a Scene, settings: &TraceSettings) -> Self {
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for p in scene.accel.primitives() {
            let (a, b) = p.bounds();
            lo = lo.min(a);
            hi = hi.max(b);
        }
        if let Some(c) = &scene.camera {
            lo = lo.min(c.position);
            hi = hi.max(c.position);
        }
        if !lo.is_finite() {
            (lo, hi) = (DVec3::ZERO, DVec3::ZERO);
        }
        let center = 0.5 * (lo + hi);
        let extent = 0.5 * (hi - lo).length();
        let radius = settings.world_radius.unwrap_or(10.0 * extent.max(1.0));
        let ball = Ball {
            center,
            radius: extent.max(1e-9),
        };
        let mut tracer = Self {
            scene,
            settings: *settings,
            ball,
            world: Bounds::Ball { center, radius },
            camera_medium: scene.ambient(),
            light_sampler: LightSampler::new(&scene.lights),
            light_samples: LightSamples::One,
            wavelength: None,
        };
        if let Some(c) = &scene.camera {
            tracer.camera_medium = tracer.medium_containing(c.position);
        }
        tracer
    }

    /// The same tracer with each vertex's direct estimate sampling lights as `samples` says.
    pub fn sampling_lights(self, samples: LightSamples) -> Self {
        Self {
            light_samples: samples,
            ..self
        }
    }

    /// The same tracer with rays at vacuum wavelength `nm`: each dispersive medium is the
    /// one at that wavelength, and so is each scattering coefficient over wavelength. Rays of
    /// a tracer from [`Tracer::new`] see every medium at [`LAMBDA_D`].
    pub fn at_wavelength(&self, nm: f64) -> Self {
        let media = self.scene.media();
        Self {
            scene: self.scene,
            settings: self.settings,
            ball: self.ball,
            world: self.world,
            camera_medium: self.camera_medium,
            light_sampler: self.light_sampler.clone(),
            light_samples: self.light_samples,
            wavelength: Some(Wavelength {
                nm,
                media: media.ids().map(|i| media.at_wavelength(i, nm)).collect(),
                scattering: media
                    .ids()
                    .map(|i| {
                        media
                            .scattering(i)
                            .filter(|s| s.is_spectral())
                            .map(|s| s.at_wavelength(nm))
                    })
                    .collect(),
            }),
        }
    }

    /// The vacuum wavelength rays travel at, nm.
    pub fn wavelength(&self) -> f64 {
        self.wavelength.as_ref().map_or(LAMBDA_D, |w| w.nm)
    }

    /// Whether a ray in `medium` travels a path that depends on its wavelength.
    pub fn disperses_in(&self, medium: Option<MediumId>) -> bool {
        medium.is_some_and(|i| self.scene.media().is_dispersive(i))
    }

    /// Whether a dielectric `surface` bends rays by their wavelength (a dispersive medium on
    /// either side).
    pub fn disperses_at(&self, surface: Surface) -> bool {
        self.disperses_in(surface.interior) || self.disperses_in(surface.exterior)
    }

    /// A reflectance (an albedo, a mirror's reflectance) as this tracer's rays see it: the
    /// RGB itself, or — rays at one wavelength — its reflectance spectrum there
    /// ([`colour::reflectance`]), the same in every channel.
    pub fn reflectance(&self, rgb: Rgb) -> Rgb {
        crate::material::reflectance(rgb, self.wavelength.as_ref().map(|w| w.nm))
    }

    /// A radiance, irradiance or intensity of emitted light likewise: the RGB itself, or its
    /// spectral value (per nm) at the tracer's wavelength ([`colour::illuminant`]).
    pub fn radiance(&self, rgb: Rgb) -> Rgb {
        match &self.wavelength {
            None => rgb,
            Some(w) => Rgb::splat(colour::illuminant(rgb, w.nm)),
        }
    }

    /// An irradiance estimated from stored photons (an RGB sum of a few photons' colours,
    /// whose channels may be negative: [`colour::sensor`]) as this tracer's rays see it: the
    /// RGB itself, or — rays at one wavelength — each channel times D65 there, joined to the
    /// path's sRGB weight channel by channel (as pbrt-v4's SPPM joins camera and photon). The
    /// reading is linear, so the estimate's noise averages out (an upsampled spectrum of a
    /// noisy colour would be biased: its negative channels clip), and its expectation over
    /// wavelengths is the RGB itself wherever the rest of the path is grey.
    pub fn photon_irradiance(&self, rgb: Rgb) -> Rgb {
        match &self.wavelength {
            None => rgb,
            Some(w) => rgb * colour::d65(w.nm),
        }
    }

    /// Medium `i` at the tracer's wavelength.
    pub fn medium(&self, i: MediumId) -> &dyn Medium {
        match self
            .wavelength
            .as_ref()
            .and_then(|w| w.media[i.index()].as_deref())
        {
            Some(m) => m,
            None => self.scene.medium_at(i),
        }
    }

    /// How medium `i` scatters at the tracer's wavelength (None: it does not).
    pub fn scattering(&self, i: MediumId) -> Option<&Scattering> {
        self.wavelength
            .as_ref()
            .and_then(|w| w.scattering[i.index()].as_ref())
            .or_else(|| self.scene.media().scattering(i))
    }

    /// What medium `i` does to light's power: its absorption and emission (its scattering at
    /// the tracer's wavelength is [`Tracer::scattering`]).
    pub fn participating(&self, i: MediumId) -> &Participating {
        self.scene.media().participating(i)
    }

    /// The optical depth of absorption along the straight piece from `from` along unit `dir`
    /// over `length` in `medium` (0 in vacuum and in a medium that does not absorb).
    pub fn optical_depth(
        &self,
        medium: Option<MediumId>,
        from: DVec3,
        dir: DVec3,
        length: f64,
    ) -> f64 {
        medium.map_or(0.0, |i| {
            self.participating(i).optical_depth(from, dir, length)
        })
    }

    /// The refractive index at `p` in `medium` (None: vacuum, n = 1); None where the medium
    /// captures rays (a horizon).
    pub fn index(&self, medium: Option<MediumId>, p: DVec3) -> Option<f64> {
        match medium {
            None => Some(1.0),
            Some(m) => self.medium(m).sample(p).map(|s| s.n),
        }
    }

    /// The medium filling point `p`: the interior of the innermost dielectric shape holding
    /// it, else the ambient medium. Found by the first dielectric surface along fixed probe
    /// rays (met from its back: `p` is inside it; from its front: outside, in its exterior);
    /// the majority of three probes decides, so a probe grazing an edge does not.
    pub fn medium_containing(&self, p: DVec3) -> Option<MediumId> {
        let [a, b, c] = PROBES.map(|d| self.enclosing_along(p, d));
        if a == b || a == c {
            a
        } else {
            b
        }
    }

    fn enclosing_along(&self, p: DVec3, d: DVec3) -> Option<MediumId> {
        let scene = self.scene;
        let mut o = p;
        loop {
            let Some((prim, h)) = scene.accel.intersect_ray(o, d, 0.0, f64::INFINITY) else {
                return scene.ambient();
            };
            let s = scene.surfaces[prim];
            if matches!(scene.material(s), Some(Material::Dielectric { .. })) {
                return if d.dot(h.normal) > 0.0 {
                    s.interior
                } else {
                    s.exterior
                };
            }
            o = offset(o + h.t * d, d);
        }
    }

    /// The scattering vertex where a path arriving along unit `incoming` in `medium` meets
    /// `surface` at `position` (with its normals and surface coordinates `uv` there): the
    /// BSDF its material makes at the tracer's wavelength, with n evaluated at the hit point
    /// on each side of a dielectric. None for a detector or an emitter (they scatter
    /// nothing), or where a side's index cannot be evaluated (a singular medium).
    pub fn vertex(
        &self,
        hit: SurfaceHit,
        surface: Surface,
        medium: Option<MediumId>,
    ) -> Option<SurfaceVertex<'a>> {
        let scene = self.scene;
        let SurfaceHit {
            prim,
            position,
            normals,
            uv,
            incoming,
        } = hit;
        let side = facing(normals.geometric, incoming);
        let material = scene.material(surface)?;
        let beyond = match material.lobes().transmits() {
            true => {
                let inside = surface.interior?;
                match side == normals.geometric {
                    true => Some(inside),
                    false => surface.exterior,
                }
            }
            false => medium,
        };
        let bsdf = material.bsdf(&HitPoint {
            tracer: self,
            prim,
            position,
            uv,
            near: medium,
            far: beyond,
        })?;
        let shading = if side == normals.geometric {
            normals.shading
        } else {
            -normals.shading
        };
        Some(SurfaceVertex {
            prim,
            position,
            normal: side,
            shading,
            wo: -incoming,
            bsdf,
            medium,
            beyond,
        })
    }

    /// The next event of a ray from `origin` along unit `dir` inside medium `medium` (None:
    /// vacuum).
    pub fn next_event(
        &self,
        origin: DVec3,
        dir: DVec3,
        medium: Option<MediumId>,
        stats: &mut Stats,
    ) -> Event {
        self.next_event_within(origin, dir, medium, f64::INFINITY, stats, None)
    }

    /// [`Self::next_event`], showing `path` every accepted point of a curved path between
    /// the origin and the event (neither included; a straight ray has none), and on a step's
    /// exact circle points close enough that the chords between them follow it.
    pub fn next_event_along(
        &self,
        origin: DVec3,
        dir: DVec3,
        medium: Option<MediumId>,
        stats: &mut Stats,
        path: &mut dyn FnMut(DVec3),
    ) -> Event {
        self.next_event_within(origin, dir, medium, f64::INFINITY, stats, Some(path))
    }

    /// [`Self::next_event_along`] for a ray allowed arclength `reach` (scene units; ∞: no
    /// limit): [`Event::Reached`] where it goes that far before any surface or the world's
    /// edge. Without `path` no points between a step's ends are computed.
    pub fn next_event_within(
        &self,
        origin: DVec3,
        dir: DVec3,
        medium: Option<MediumId>,
        reach: f64,
        stats: &mut Stats,
        path: Option<&mut dyn FnMut(DVec3)>,
    ) -> Event {
        match medium {
            Some(i) if !self.medium(i).is_uniform() => {
                self.curved(i, origin, dir, reach, stats, path)
            }
            _ => {
                stats.straight_rays += 1;
                let depth = |length: f64| self.optical_depth(medium, origin, dir, length);
                match self.scene.accel.intersect_ray(origin, dir, 0.0, reach) {
                    Some((prim, h)) => Event::Surface {
                        prim,
                        position: origin + h.t * dir,
                        normal: h.normal,
                        shading: h.shading,
                        uv: h.uv,
                        direction: dir,
                        distance: h.t,
                        optical_depth: depth(h.t),
                    },
                    None => {
                        let distance = self.world.exit_distance(origin, dir);
                        match reach < distance {
                            true => Event::Reached {
                                position: origin + reach * dir,
                                direction: dir,
                                distance: reach,
                                optical_depth: depth(reach),
                            },
                            false => Event::Escaped {
                                position: origin + distance * dir,
                                direction: dir,
                                distance,
                                optical_depth: depth(distance),
                            },
                        }
                    }
                }
            }
        }
    }

    fn curved(
        &self,
        i: MediumId,
        origin: DVec3,
        dir: DVec3,
        reach: f64,
        stats: &mut Stats,
        path: Option<&mut dyn FnMut(DVec3)>,
    ) -> Event {
        let settings = &self.settings;
        let medium = self.medium(i);
        let Some(start) = RayState::new(medium, origin, dir) else {
            stats.record_end(Termination::Captured);
            return Event::Lost;
        };
        let limits = MarchLimits {
            length: 100.0 * self.world.scale(),
            max_steps: settings.max_steps,
            bounds: self.world,
        };
        let control = keyed_by_ray(settings.control, origin, dir);
        let along = Along {
            medium,
            radiometry: self.participating(i),
        };
        let Marched {
            hit,
            outcome: out,
            optical_depth,
        } = self.march_to_surface(along, control, start, &limits, reach, path);
        stats.curved_marches += 1;
        stats.curved_steps += out.steps;
        stats.record_end(out.reason);
        match (hit, out.reason) {
            (Some(hit), _) => hit,
            (None, Termination::LeftBounds) => Event::Escaped {
                position: out.state.position,
                direction: out.state.direction,
                distance: out.arclength,
                optical_depth,
            },
            // Trapped (the path's length ran out inside the world), captured, out of steps.
            (None, _) => Event::Lost,
        }
    }

    /// Marches from `start` until an accepted step's path meets a surface or passes
    /// arclength `reach`: the hit or the point at `reach` (its distance and depth from
    /// `start`), with the march's outcome. `path` is shown each accepted point before it.
    fn march_to_surface(
        &self,
        along: Along,
        control: StepControl,
        start: RayState,
        limits: &MarchLimits,
        reach: f64,
        mut path: Option<&mut dyn FnMut(DVec3)>,
    ) -> Marched {
        let Along { medium, radiometry } = along;
        let mut prev = start;
        let (mut prev_s, mut prev_depth) = (0.0, 0.0);
        let mut hit = None;
        let out = march_with(
            self.settings.stepper,
            medium,
            control,
            start,
            limits,
            |s, step| {
                if s == 0.0 {
                    return ControlFlow::Continue(());
                }
                let len = s - prev_s;
                let st = &step.state;
                let found = match &step.path {
                    Some(exact) => self.crossing_on_path(exact, &prev, st, len),
                    None => self.crossing_between(&prev, st, len),
                };
                if let Some(c) = found.filter(|c| prev_s + c.along <= reach) {
                    show_circle(step.path.as_ref(), c.along, &mut path);
                    hit = Some(Event::Surface {
                        prim: c.prim,
                        position: c.position,
                        normal: c.hit.normal,
                        shading: c.hit.shading,
                        uv: c.hit.uv,
                        direction: c.direction,
                        distance: prev_s + c.along,
                        optical_depth: prev_depth
                            + radiometry.step_depth(prev.position, c.position, c.along),
                    });
                    return ControlFlow::Break(());
                }
                if s >= reach {
                    let along = reach - prev_s;
                    let p = match &step.path {
                        Some(exact) => exact.at(&prev, len, along),
                        None => HermitePath::new(&prev, st, len).at(along),
                    };
                    show_circle(step.path.as_ref(), along, &mut path);
                    hit = Some(Event::Reached {
                        position: p.position,
                        direction: p.direction,
                        distance: reach,
                        optical_depth: prev_depth
                            + radiometry.step_depth(prev.position, p.position, along),
                    });
                    return ControlFlow::Break(());
                }
                show_circle(step.path.as_ref(), len, &mut path);
                if let Some(path) = path.as_mut() {
                    path(st.position);
                }
                prev_depth += radiometry.step_depth(prev.position, st.position, len);
                prev = *st;
                prev_s = s;
                ControlFlow::Continue(())
            },
        );
        Marched {
            hit,
            outcome: out,
            optical_depth: prev_depth,
        }
    }

    /// The first surface on a step from `prev` to `st` whose path is known exactly — a chain
    /// of two exact arcs of `len`/2 each, or the ray's circle — met on the path itself, so the
    /// hit is exact; skipped when no surface can meet the capsule that holds the path.
    fn crossing_on_path(
        &self,
        path: &ExactPath,
        prev: &RayState,
        st: &RayState,
        len: f64,
    ) -> Option<Crossing> {
        let accel = &self.scene.accel;
        match path {
            ExactPath::Arcs(arcs) => {
                if !accel.may_hit(&arcs.hull(prev, st, len)) {
                    return None;
                }
                let half = 0.5 * len;
                arcs.arcs(prev).iter().enumerate().find_map(|(k, arc)| {
                    let hull = arc.hull(half);
                    let found = accel.intersect_segment(arc, &hull, 0.0, half)?;
                    Some(Crossing::on(arc, k as f64 * half, found))
                })
            }
            ExactPath::Circle(circle) => accel
                .intersect_segment(circle, &path.hull(prev, st, len), 0.0, len)
                .map(|found| Crossing::on(circle, 0.0, found)),
        }
    }

    /// The first surface between two accepted states `len` apart whose stepper knows only the
    /// ends (RK4, RKN, Snell): on the step's quintic Hermite path ([`HermitePath`]), which
    /// joins the two states continuously, so no surface between them is stepped over, and
    /// errs from the ray by O(len⁶), so the hit is as good as the step's ends. Surfaces the
    /// capsule of its control polygon cannot meet are not searched.
    fn crossing_between(&self, prev: &RayState, st: &RayState, len: f64) -> Option<Crossing> {
        let accel = &self.scene.accel;
        if accel.is_empty() || len <= 0.0 {
            return None;
        }
        let path = HermitePath::new(prev, st, len);
        // The search culls by the hull itself (a separate `may_hit` would traverse twice).
        let hull = path.hull();
        accel
            .intersect_segment(&path, &hull, 0.0, len)
            .map(|found| Crossing::on(&path, 0.0, found))
    }
}

/// The most a ray turns between two points a curved path shows (rad): chords between them are
/// within 0.004 % of the arc's length and 0.4 % of it from the arc (at 0.1 rad the fish-eye
/// scene's beams read 0.2 % high: `tests/linearize.rs`).
const SHOWN_TURN: f64 = 0.03;

/// Shows `path` the points of a step's exact circle (if it is one) between its start and
/// `upto` along it, at most [`SHOWN_TURN`] apart, neither end included: a step of the exact
/// stepper may turn a right angle of its circle, and what follows a path by its chords (the
/// beams of the volume caustic estimate, the columns of a density) needs them close to it.
fn show_circle(exact: Option<&ExactPath>, upto: f64, path: &mut Option<&mut dyn FnMut(DVec3)>) {
    if let (Some(ExactPath::Circle(circle)), Some(path)) = (exact, path) {
        let pieces = (upto * circle.curvature.length() / SHOWN_TURN).ceil();
        if pieces > 1.0 && pieces.is_finite() {
            let pieces = pieces as usize;
            for i in 1..pieces {
                path(circle.at(upto * i as f64 / pieces as f64).position);
            }
        }
    }
}

/// Where a step's path meets a surface.
struct Crossing {
    prim: usize,
    hit: Hit,
    position: DVec3,
    direction: DVec3,
    /// Arclength from the step's start.
    along: f64,
}

impl Crossing {
    /// Primitive `prim`'s `hit` on `path`, a piece of the step that starts `offset` into it.
    fn on<P: Path + ?Sized>(path: &P, offset: f64, (prim, hit): (usize, Hit)) -> Self {
        let p = path.at(hit.t);
        Crossing {
            prim,
            hit,
            position: p.position,
            direction: p.direction,
            along: offset + hit.t,
        }
    }
}

/// `control`, with a Tessendorf control's ξ stream keyed by the ray itself (its seed mixed
/// with the bits of its origin and direction), so rays do not share one sequence of step
/// sizes; the same ray draws the same ξ in every run.
fn keyed_by_ray(control: StepControl, origin: DVec3, dir: DVec3) -> StepControl {
    use crate::sampling::mix;
    match control {
        StepControl::Tessendorf {
            initial_step,
            t_max,
            t_min,
            seed,
        } => {
            let words = [origin.x, origin.y, origin.z, dir.x, dir.y, dir.z];
            let key = words.iter().fold(mix(seed), |h, w| mix(h ^ w.to_bits()));
            StepControl::Tessendorf {
                initial_step,
                t_max,
                t_min,
                seed: key,
            }
        }
        other => other,
    }
}

/// A surface point as [`Material::bsdf`] asks of it: the hit, the media on each side and the
/// tracer's wavelength.
struct HitPoint<'t, 'a> {
    tracer: &'t Tracer<'a>,
    prim: usize,
    position: DVec3,
    uv: Option<DVec2>,
    near: Option<MediumId>,
    far: Option<MediumId>,
}

impl SurfacePoint for HitPoint<'_, '_> {
    fn uv(&self) -> DVec2 {
        self.uv
            .unwrap_or_else(|| self.tracer.scene.accel.primitives()[self.prim].uv_at(self.position))
    }
    fn wavelength(&self) -> Option<f64> {
        self.tracer.wavelength.as_ref().map(|w| w.nm)
    }
    fn index_near(&self) -> Option<f64> {
        self.tracer.index(self.near, self.position)
    }
    fn index_far(&self) -> Option<f64> {
        self.tracer.index(self.far, self.position)
    }
}
