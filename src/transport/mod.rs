//! Moving a ray through the scene to its next event: straight through uniform media (BVH ray
//! traversal), curved through gradient media (the march, each accepted step tested against
//! the BVH as an exact arc). On top of it, shared by every pass: the specular chain
//! ([`chain`]: mirrors, dielectrics and detectors followed to the next diffuse surface,
//! emitter or escape, with the radiance change across indices), the visibility query
//! ([`visibility`]: the only straight shadow ray) and curved connections to lights from
//! gradient media ([`connect`]).
//!
//! [`Tracer`] itself finds next events (this file). Beside it: what a ray meets
//! (`event.rs`), which medium fills a point (`fill.rs`), the tracer at a hero wavelength and
//! how colours read there (`spectral.rs`), and the vertex a surface hit makes
//! (`surface.rs`).

pub mod chain;
pub mod connect;
mod event;
mod fill;
pub mod lighting;
mod spectral;
mod stats;
mod surface;
mod vertex;
pub mod visibility;

pub use event::{Event, Normals, SurfaceHit};
pub use spectral::HeroTracer;
pub use spectral::MediumAt;
pub use vertex::{BsdfNumbers, MediumVertex, Scattered, SurfaceVertex, Vertex};

use crate::accel::PrimHit;
use crate::color::Rgb;
use crate::curve::{
    march_with, ArcPoint, Bounds, ExactPath, HermitePath, MarchLimits, MarchOutcome, Path,
    RayState, StepControl, Termination,
};
use crate::ids::{MediumId, PrimId};
use crate::lights::{LightSampler, LightSamples};
use crate::math::{Ball, Bounds3};
use crate::media::{Medium, WithMedium};
use crate::scene::Scene;
use crate::settings::TraceSettings;
use crate::shapes::{Hit, SegmentHits};
use crate::volume::Participating;
use glam::DVec3;
pub use stats::Stats;
use std::borrow::Cow;
use std::ops::ControlFlow;

pub use crate::math::{facing, offset};

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
    /// Which light a vertex's light sample goes to: the tracer's own, or borrowed from the
    /// tracer it was made at a wavelength from ([`Tracer::at_wavelength`]: a spectral photon
    /// costs nothing there; a shared count, raised and dropped by every photon of every
    /// thread, did).
    pub light_sampler: Cow<'a, LightSampler>,
    /// How many lights a vertex's direct estimate samples (the integrator's choice:
    /// [`Tracer::sampling_lights`]; one unless it says).
    pub light_samples: LightSamples,
    /// The wavelength rays travel at, when it is not [`crate::spectrum::LAMBDA_D`] (see
    /// [`Tracer::at_wavelength`]).
    wavelength: Option<f64>,
    /// Whether a surface of the scene may join equal indices ([`Scene::may_match_indices`],
    /// asked once here rather than by every shadow ray).
    pub may_match_indices: bool,
    /// Whether a medium of the scene is a crystal ([`crate::scene::Media::crystal`], asked once
    /// here rather than at every surface a path meets).
    pub has_crystals: bool,
    /// Whether a direction sample finds emission only where its straight line meets an area
    /// light, and the lights are few enough to look through for each sample: the scene has
    /// no environment, every medium a uniform index, and at most [`MOST_LIGHTS_ON_LINES`]
    /// lights (asked once here; see [`lighting::may_find_emission`]).
    pub emission_on_lines: bool,
}

/// The most lights a direction sample's line is checked against one by one before its chain
/// is traced ([`Tracer::emission_on_lines`]): an area light's test is a few dozen operations
/// (another light's a comparison), so 32 cost about one traversal of the scene's BVH, which
/// the check is there to save. Scenes with more lights trace every such ray, as before.
pub const MOST_LIGHTS_ON_LINES: usize = 32;

/// A gradient medium a march crosses: its index field and what it does to light's power.
struct Along<'m, M: ?Sized> {
    medium: &'m M,
    radiometry: &'m Participating,
}

/// A ray's march through gradient medium `medium` to its next event ([`Tracer::curved`]),
/// done with the medium as whatever type the caller holds it as.
struct CurvedMarch<'t, 'a, 'p> {
    tracer: &'t Tracer<'a>,
    medium: MediumId,
    origin: DVec3,
    dir: DVec3,
    reach: f64,
    stats: &'t mut Stats,
    path: Option<&'p mut dyn FnMut(ArcPoint)>,
}

/// A march to the next surface: the surface met or the point at the reach (None: neither),
/// how the march ended, and the optical depth of absorption along the path it went.
struct Marched {
    hit: Option<Event>,
    outcome: MarchOutcome,
    optical_depth: Rgb,
}

/// Whether transport on `scene` under `settings` is polarized: asked for (`polarized`, or
/// `stokes`), or implied by a polarizing sheet, a camera polarizer or a crystal.
pub fn carries_polarization(scene: &Scene, settings: &TraceSettings) -> bool {
    settings.polarized
        || settings.stokes
        || (scene.materials.iter()).any(|m| matches!(m, crate::material::Material::Sheet(_)))
        || (scene.camera.as_ref()).is_some_and(|c| c.polarizer.is_some())
        || scene.media().first_crystal().is_some()
}

impl<'a> Tracer<'a> {
    /// The tracer of a scene; the world sphere is the scene's `world_radius` around the centre
    /// of everything in it (primitives and camera), or 10× its extent (at least 10 units).
    pub fn new(scene: &'a Scene, settings: &TraceSettings) -> Self {
        let mut bounds =
            (scene.accel.primitives().iter()).fold(Bounds3::EMPTY, |b, p| b.union(p.bounds()));
        if let Some(c) = &scene.camera {
            bounds = bounds.with_point(c.position);
        }
        if !bounds.lo.is_finite() {
            bounds = Bounds3::new(DVec3::ZERO, DVec3::ZERO);
        }
        let center = bounds.center();
        let extent = 0.5 * bounds.diagonal().length();
        let radius = settings.world_radius.unwrap_or(10.0 * extent.max(1.0));
        let ball = Ball {
            center,
            radius: extent.max(1e-9),
        };
        let has_crystals = scene.media().first_crystal().is_some();
        let emission_on_lines = scene.environment.is_none()
            && scene.media().all_uniform()
            && scene.lights.len() <= MOST_LIGHTS_ON_LINES;
        let polarized = carries_polarization(scene, settings);
        let mut tracer = Self {
            scene,
            settings: TraceSettings {
                polarized,
                ..*settings
            },
            ball,
            world: Bounds::Ball { center, radius },
            camera_medium: scene.ambient(),
            light_sampler: Cow::Owned(LightSampler::new(&scene.lights)),
            light_samples: LightSamples::One,
            wavelength: None,
            may_match_indices: scene.may_match_indices(),
            has_crystals,
            emission_on_lines,
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

    /// [`Self::next_event`], showing `path` every accepted point of a curved path (with its
    /// unit direction) between
    /// the origin and the event (neither included; a straight ray has none), and on a step's
    /// exact circle points close enough that the chords between them follow it.
    pub fn next_event_along(
        &self,
        origin: DVec3,
        dir: DVec3,
        medium: Option<MediumId>,
        stats: &mut Stats,
        path: &mut dyn FnMut(ArcPoint),
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
        path: Option<&mut dyn FnMut(ArcPoint)>,
    ) -> Event {
        match medium {
            Some(i) if !self.medium(i).is_uniform() => {
                self.curved(i, origin, dir, reach, stats, path)
            }
            _ => {
                stats.straight_rays += 1;
                let depth = |length: f64| self.optical_depth(medium, origin, dir, length);
                match self.scene.accel.intersect_ray(origin, dir, 0.0, reach) {
                    Some(found) => Event::Surface {
                        hit: SurfaceHit::straight(origin, dir, found),
                        distance: found.hit.t,
                        optical_depth: depth(found.hit.t),
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
        path: Option<&mut dyn FnMut(ArcPoint)>,
    ) -> Event {
        let at_wavelength = self.medium(i);
        let march = CurvedMarch {
            tracer: self,
            medium: i,
            origin,
            dir,
            reach,
            stats,
            path,
        };
        match at_wavelength.parametric() {
            // Compiled for the medium's own type, its samples inlined into the steppers: a
            // march behind `dyn Medium` takes 1.25–1.33× as long (`examples/march_dispatch`).
            Some(p) => p.apply(march),
            None => march.with(&*at_wavelength),
        }
    }
}

impl WithMedium for CurvedMarch<'_, '_, '_> {
    type Output = Event;

    fn with<M: Medium + ?Sized>(self, medium: &M) -> Event {
        let (tracer, origin, dir) = (self.tracer, self.origin, self.dir);
        let settings = &tracer.settings;
        let Some(start) = RayState::new(medium, origin, dir) else {
            self.stats.record_end(Termination::Captured);
            return Event::Lost;
        };
        let limits = MarchLimits {
            length: 100.0 * tracer.world.scale(),
            max_steps: settings.max_steps,
            bounds: tracer.world,
        };
        let control = keyed_by_ray(settings.control, origin, dir);
        let along = Along {
            medium,
            radiometry: tracer.participating(self.medium),
        };
        let Marched {
            hit,
            outcome: out,
            optical_depth,
        } = tracer.march_to_surface(along, control, start, &limits, self.reach, self.path);
        let stats = self.stats;
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
}

impl Tracer<'_> {
    /// Marches from `start` until an accepted step's path meets a surface or passes
    /// arclength `reach`: the hit or the point at `reach` (its distance and depth from
    /// `start`), with the march's outcome. `path` is shown each accepted point before it.
    fn march_to_surface<M: Medium + ?Sized>(
        &self,
        along: Along<M>,
        control: StepControl,
        start: RayState,
        limits: &MarchLimits,
        reach: f64,
        mut path: Option<&mut dyn FnMut(ArcPoint)>,
    ) -> Marched {
        let Along { medium, radiometry } = along;
        let mut prev = start;
        let (mut prev_s, mut prev_depth) = (0.0, Rgb::ZERO);
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
                        hit: SurfaceHit {
                            prim: c.prim,
                            position: c.position,
                            normals: Normals {
                                geometric: c.hit.normal,
                                shading: c.hit.shading,
                            },
                            uv: c.hit.uv,
                            incoming: c.direction,
                        },
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
                    path(ArcPoint {
                        position: st.position,
                        direction: st.direction,
                    });
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
fn show_circle(exact: Option<&ExactPath>, upto: f64, path: &mut Option<&mut dyn FnMut(ArcPoint)>) {
    if let (Some(ExactPath::Circle(circle)), Some(path)) = (exact, path) {
        let pieces = (upto * circle.curvature.length() / SHOWN_TURN).ceil();
        if pieces > 1.0 && pieces.is_finite() {
            let pieces = pieces as usize;
            for i in 1..pieces {
                path(circle.at(upto * i as f64 / pieces as f64));
            }
        }
    }
}

/// Where a step's path meets a surface.
struct Crossing {
    prim: PrimId,
    hit: Hit,
    position: DVec3,
    direction: DVec3,
    /// Arclength from the step's start.
    along: f64,
}

impl Crossing {
    /// Primitive `prim`'s `hit` on `path`, a piece of the step that starts `offset` into it.
    fn on<P: Path + ?Sized>(path: &P, offset: f64, PrimHit { prim, hit }: PrimHit) -> Self {
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
