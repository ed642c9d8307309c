//! The photon mapper (Zhdanov et al. (2020) §4, Jensen; glossy surfaces as in SPPM, Hachisuka
//! and Jensen 2009, and pbrt-v4): each pass traces a caustic and a global photon map. A camera
//! path goes through purely specular surfaces within its chain and through glossy-only
//! vertices by sampling their BSDF (with direct light at each), and makes its visible point at
//! the first vertex with a diffuse lobe (photons are stored only at such vertices). There:
//! - **direct**: light with no specular interaction on the way ([`super::direct`]);
//! - **caustic**: the caustic map's density estimate (photons that met only specular or glossy
//!   lobes since the light), each photon weighted by the BSDF f(ωo, ωi) (albedo/π at a
//!   Lambertian surface), with an Epanechnikov
//!   kernel of radius r_p at pass p: r₀ the k-nearest distance at the pixel's first visible
//!   point in that pass (or the scene's `radius`), shrunk by Knaus and Zwicker's probabilistic
//!   progressive schedule r_p² = r₀² Π_{j=1..p} (j + α)/(j + 1), α = 2/3: a function of the
//!   pass index alone, so passes are independent and their films merge. A photon that a
//!   surface hides from the visible point (a thin wall standing on the floor between them)
//!   is not read ([`crate::transport::visibility::Occluders`]): it lit another place, and
//!   read through the wall it leaks that light (a ring's bright caustic read outside the
//!   ring). One map query per pixel and pass serves the pixel's samples
//!   ([`super::neighbourhood`]);
//! - **secondary**: a final gather — BSDF-sampled rays followed through specular surfaces and
//!   glossy-only vertices to a vertex with a diffuse lobe, where the global map's precomputed
//!   irradiance reaching the diffuse base gives the light its diffuse lobe sends back (the
//!   diffuse lobe factorises into an entry and an exit factor; photons carry the entry); the
//!   ray goes on through the vertex's other lobes (a plastic's coat), as SPPM passes glossy
//!   lobes;
//! - **emitted**: emitters and the environment seen along the camera's chains;
//! - **volume caustic** (in the caustic layer): in scattering media, the volume caustic map's
//!   photons read along every stretch of the camera path up to its visible point by the beam
//!   radiance estimate ([`super::beam`]), each photon a ball of its k-nearest distance shrunk
//!   by the same schedule (a beam reads a 2D kernel, as a surface does).

use super::beam::Beams;
use super::direct::{camera_path, direct, emission_seen, hero, record_cut, VisiblePoint};
use super::footprint::{Eye, Way};
use super::neighbourhood::Neighbourhood;
use super::path::{dye_light, onward, onward_from_unpolarized};
use super::relight::fluoresces;
use super::single::single_scattering;
use super::{CameraRay, FirstVertex, Integrator, Sample};
use crate::color::Rgb;
use crate::material::Material;
use crate::photon::{shoot, Batch, PhotonMap, Photons, Sources, VolumeMap};
use crate::polarization::{Polarization, Recorded};
use crate::report::Report;
use crate::scene::Scene;
use crate::settings::{PhotonSettings, Settings};
use crate::transport::chain::{Carried, End, Policy, Walker};
use crate::transport::lighting::{Measure, Radiance};
use crate::transport::{Stats, SurfaceVertex, Tracer, Vertex};
use std::f64::consts::FRAC_1_PI;
use std::time::Instant;

/// The radius-reduction parameter α (Hachisuka and Jensen 2009; Knaus and Zwicker 2011): the
/// fraction of a pass's photons a progressive estimate keeps.
pub const ALPHA: f64 = 2.0 / 3.0;

/// Which photon maps a scene needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// A caustic map: some light path can meet a specular or glossy lobe, or scatter in a
    /// medium, before a diffuse surface (light through gradient media alone is the direct
    /// estimate's).
    pub caustic: bool,
    /// A global map: secondary light is on (`gather` > 0) and something scatters.
    pub global: bool,
    /// A volume caustic map: a medium scatters and some light path can meet a specular or
    /// glossy surface before it.
    pub volume: bool,
}

impl Plan {
    /// What `scene` needs with `photons`: nothing without scattering surfaces or without
    /// emitters.
    pub fn of(scene: &Scene, photons: &PhotonSettings) -> Self {
        let lobes = || {
            scene
                .surfaces
                .iter()
                .filter_map(|&s| scene.material(s).map(Material::lobes))
        };
        // (A receiver's detector is transparent: it neither bends nor stores light.) Light
        // scattered in a medium on its way to a surface is a caustic of that surface.
        let fog = scene.media().any_scatters();
        let scatters = fog || lobes().any(|l| !l.is_specular());
        let surfaces_bend = lobes().any(|l| l != crate::bsdf::Lobes::DIFFUSE_REFLECTION);
        let bends = fog || surfaces_bend;
        let emits = !scene.lights.is_empty() || scene.environment.is_some();
        Self {
            caustic: scatters && emits && bends && photons.caustic > 0,
            global: scatters && emits && photons.gather > 0 && photons.global > 0,
            volume: fog && surfaces_bend && emits && photons.caustic > 0,
        }
    }
}

super::layers!(
    /// The layers, in order; `beauty` is their radiance sum.
    MapLayer {
        /// Light from the lights at the visible point.
        Direct: radiance "direct",
        /// The caustic map's estimate (and volume caustics).
        Caustic: radiance "caustic",
        /// The final gather over the global map.
        Secondary: radiance "secondary",
        /// Emission seen directly.
        Emitted: radiance "emitted",
        /// The first scattering surface's albedo.
        Albedo: aux "albedo",
        /// Its normal.
        Normal: aux "normal",
    }
);

/// The photon mapper of a scene.
pub struct PhotonMapper<'a> {
    tracer: &'a Tracer<'a>,
    /// The global photons' sources.
    sources: Sources<'a>,
    /// The caustic photons' (parallel and environment light aimed at the specular surfaces).
    caustic_sources: Sources<'a>,
    plan: Plan,
    photons: PhotonSettings,
    seed: u64,
    /// Largest squared radius of a k-nearest query.
    max_r2: f64,
    /// The camera, for the caustic radius's floor (None without one).
    eye: Option<Eye<'a>>,
}

/// A pass's photon maps.
pub struct Maps {
    index: u32,
    caustic: Option<PhotonMap>,
    global: Option<PhotonMap>,
    /// The caustic photons where they first scattered in a medium.
    volume: Option<VolumeMap>,
}

/// What a batch of photons left: the map of those stored on surfaces, and of those stored in
/// media (empty but for the caustic batch in a scene with scattering media).
struct Traced {
    surfaces: PhotonMap,
    volume: VolumeMap,
}

impl PhotonMapper<'_> {
    /// The film's layers.
    pub const LAYERS: &'static [crate::film::Layer] = <MapLayer as super::Layers>::FILM;

    /// What one pass's photon maps take (bytes) for `scene` with `photons`: as traced in
    /// chunks and merged, global photons stored ≈ 4 times each (the mean path of Russian
    /// roulette at albedo 0.75), with their kd-tree entries, and each caustic photon's Stokes
    /// vector where the transport is `polarized`.
    pub fn memory_needed(scene: &Scene, photons: &PhotonSettings, polarized: bool) -> u64 {
        use std::mem::size_of;
        let plan = Plan::of(scene, photons);
        let stokes = match polarized {
            true => size_of::<crate::polarization::StoredStokes>() as u64,
            false => 0,
        };
        let per_photon = 2 * size_of::<crate::photon::Photon>() as u64 + 32;
        let caustic = if plan.caustic { photons.caustic } else { 0 };
        let global = if plan.global { 4 * photons.global } else { 0 };
        (caustic + global).saturating_mul(per_photon) + caustic.saturating_mul(2 * stokes)
    }
}

impl<'a> PhotonMapper<'a> {
    /// The photon mapper of the tracer's scene under `settings`.
    pub fn new(tracer: &'a Tracer<'a>, settings: &Settings) -> Self {
        let max_radius = settings.photons.radius.unwrap_or(0.05 * tracer.ball.radius);
        Self {
            tracer,
            sources: Sources::new(tracer),
            caustic_sources: Sources::for_caustics(tracer),
            plan: Plan::of(tracer.scene, &settings.photons),
            photons: settings.photons,
            seed: settings.seed,
            max_r2: max_radius * max_radius,
            eye: tracer.scene.camera.as_ref().map(Eye::new),
        }
    }

    /// Traces one batch of pass `index` into its maps (the global one with its precomputed
    /// irradiance); None when stopped.
    fn map(
        &self,
        batch: Batch,
        index: u32,
        count: u64,
        report: &mut Report,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Traced> {
        let t0 = Instant::now();
        let photons = Photons::all(batch, self.seed, index as u64, count);
        let sources = match batch {
            Batch::Caustic => &self.caustic_sources,
            Batch::Global | Batch::Receivers => &self.sources,
        };
        let (sink, stats) = shoot(self.tracer, sources, photons, stop);
        let t1 = Instant::now();
        report.stats.add(&stats);
        if stop() {
            return None;
        }
        let mut map = PhotonMap::traced(sink.photons);
        if batch == Batch::Global {
            map.precompute_irradiance(self.photons.knn as usize, self.max_r2);
        }
        // Each volume photon's ball: its k-nearest distance, shrunk by the schedule (a beam
        // reads a 2D kernel, so its area follows the surfaces' schedule).
        let k = self.photons.knn as usize;
        let volume = VolumeMap::new(sink.volume, k, self.max_r2, schedule(index));
        report.seconds.photons += (t1 - t0).as_secs_f64();
        report.seconds.maps += t1.elapsed().as_secs_f64();
        Some(Traced {
            surfaces: map,
            volume,
        })
    }

    /// The squared caustic radius of pass `index` at a visible point `v`: the k-nearest
    /// distance there, no less than `floor` — half the smallest width of the pixel's
    /// footprint there, where it is known ([`Eye::half_width`]; asked only where the
    /// k-nearest distance is below the largest radius and the footprint may be wider,
    /// [`Eye::may_exceed`]) —, or the scene's radius; times Knaus and Zwicker's schedule. A
    /// pixel averages the radiance over its footprint, so a kernel narrower than that only
    /// adds noise: in a bright caustic the k nearest photons lie within a small part of a
    /// pixel, and the pixel's samples, each reading its own few photons, would leave most of
    /// the photons in it unread.
    fn caustic_r2(
        &self,
        caustic: &PhotonMap,
        index: u32,
        v: &SurfaceVertex,
        floor: impl FnOnce(&mut Stats) -> Option<f64>,
        stats: &mut Stats,
    ) -> f64 {
        let r0 = match self.photons.radius {
            Some(r) => r * r,
            None => {
                let knn = stats.time_query(|| {
                    let k = self.photons.knn as usize;
                    caustic.knn_radius2(v.position, v.normal, k, self.max_r2)
                });
                let may_bind = self
                    .eye
                    .as_ref()
                    .is_some_and(|e| e.may_exceed(v.position, knn));
                match knn < self.max_r2 && may_bind {
                    true => knn.max(floor(stats).map_or(0.0, |h| (h * h).min(self.max_r2))),
                    false => knn,
                }
            }
        };
        r0 * schedule(index)
    }

    /// Secondary light at a visible point: `gather` BSDF-sampled rays, each followed through
    /// specular surfaces and glossy-only vertices (sampling their BSDF) to a vertex with a
    /// diffuse lobe, where the global map's precomputed irradiance reaching the diffuse base
    /// times the lobe's exit factor gives the light the diffuse lobe sends back
    /// ([`SurfaceVertex::diffuse_exit`]: albedo/π at a Lambertian surface). Where that vertex
    /// has other lobes too (a plastic's coat), the ray goes on through them
    /// ([`SurfaceVertex::scatter_beyond_diffuse_with`]) to the next such vertex, as SPPM passes
    /// glossy lobes: the map is read through diffuse lobes only, so each light path is
    /// counted once, and through a glossy lobe the photons would be a narrow, noisy estimate.
    /// Emission and environment met by gather rays are not counted: that light is the direct
    /// or caustic part. The light a gather ray brings back is taken as unpolarized (the global
    /// map's irradiance reads no Stokes vector); `measure` records it through the visible
    /// point's Mueller matrix for the ray's direction (a plastic's polarizes it).
    fn secondary<M: Measure>(
        &self,
        global: &PhotonMap,
        vp: &VisiblePoint,
        carried: Carried,
        measure: &M,
        s: &mut Sample<MapLayer>,
    ) -> M::Light {
        let gather = self.photons.gather;
        let dyes = self.tracer.scene.media().first_fluorescent().is_some();
        let mut sum = M::Light::default();
        for _ in 0..gather {
            s.stats.gather_rays += 1;
            let mut walker = Walker::carrying(carried, Policy::Weighted);
            let mut weight = Rgb::ONE;
            let mut next = vp.vertex.scatter_with(s.rng);
            let Some(first) = &next else { continue };
            let seen = measure.through(&vp.vertex, first.sample.wi, None);
            let mut beams = Beams::default();
            while let Some(b) = next {
                // A dye's light is path traced from points on the ray's way through it.
                let chain = match dyes {
                    true => {
                        let recording = &mut beams.record(walker.tracer);
                        walker.follow(b.ray, s.rng, s.stats, recording)
                    }
                    false => walker.follow(b.ray, s.rng, s.stats, &mut ()),
                };
                let before = vp.throughput * weight * b.sample.weight * b.radiance_scale;
                record_cut(&chain, before / gather as f64, s.stats);
                if dyes {
                    let dyed = dye_light(&beams, walker.carried(), s.rng, s.stats);
                    // The gather ray carries no measurement: the dye's radiance.
                    sum += seen * (weight * b.sample.weight * b.radiance_scale * dyed.s0);
                }
                weight = weight * b.sample.weight * chain.weight * b.radiance_scale;
                let End::Scatter(y) = chain.end else { break };
                weight *= chain.radiance_scale();
                next = match y {
                    // A fluorescent layer's photons carry no wavelength to read its response
                    // at: the light it sends is path traced.
                    y if fluoresces(walker.tracer, &y) => {
                        let vp = VisiblePoint {
                            vertex: y,
                            throughput: Rgb::ONE,
                        };
                        let carried = walker.carried();
                        sum +=
                            seen * (weight * onward_from_unpolarized(vp, carried, s.rng, s.stats));
                        None
                    }
                    Vertex::Surface(y) if y.lobes().has_diffuse() => {
                        let e = s
                            .stats
                            .time_query(|| global.nearest_irradiance(y.position, y.normal));
                        sum +=
                            seen * (weight * y.diffuse_exit() * walker.tracer.photon_irradiance(e));
                        match walker.depth > 0 {
                            true => y.scatter_beyond_diffuse_with(s.rng),
                            false => None,
                        }
                    }
                    y if walker.depth > 0 => y.scatter_with(s.rng),
                    _ => None,
                };
            }
        }
        sum * vp.throughput / gather.max(1) as f64
    }

    /// The camera path's visible point: past glossy-only vertices and points in scattering
    /// media by sampling their BSDF or phase function (adding their direct light to `direct`,
    /// and emission met after a specular bounce to `emitted`), to the first surface with a
    /// diffuse lobe (returned with the path's point there); None where the path leaves, or
    /// spends its depth before one.
    fn visible_point<'w>(
        &self,
        maps: &Maps,
        mut vp: VisiblePoint<'w>,
        carried: Carried<'w>,
        measure: &mut Option<Polarization>,
        found: &mut Found,
        s: &mut Sample<MapLayer>,
    ) -> Option<(VisiblePoint<'w>, SurfaceVertex<'w>, Carried<'w>)> {
        let mut walker = Walker::carrying(carried, Policy::Weighted);
        // Whether the path has scattered at a point in a medium with a volume caustic map and
        // met only specular and glossy lobes since: light reaching it from there through
        // them alone (L (S|G)+ V) is the map's — the beams that reached the point counted
        // it — so neither the direct light of a glossy vertex on the way nor emission a
        // specular chain finds is added again.
        let mut volume = false;
        loop {
            if let Vertex::Surface(v) = vp.vertex {
                if v.lobes().has_diffuse() {
                    return Some((vp, v, walker.carried()));
                }
            }
            if walker.depth == 0 {
                s.stats.camera_weight_cut += vp.throughput.mean();
                s.stats.depth_limited += 1;
                return None;
            }
            let in_medium = matches!(vp.vertex, Vertex::Medium(_));
            if in_medium || !volume {
                found.direct += recorded_direct(walker.carried(), &vp, measure, s.rng, s.stats);
            }
            volume |= maps.volume.is_some() && in_medium;
            let b = vp.vertex.scatter_with(s.rng)?;
            if let Some(p) = measure.as_mut() {
                vp.vertex.measure_toward(p, b.sample.wi);
            }
            let throughput = vp.throughput * b.sample.weight * b.radiance_scale;
            let mut beams = Beams::default();
            let recording = &mut beams.record(walker.tracer);
            let chain = walker.follow_carrying(b.ray, measure, s.rng, s.stats, recording);
            let at_end = |value: Rgb| Recorded::of(measure.as_ref(), value);
            record_cut(&chain, throughput, s.stats);
            found.caustic += self.volume_caustic(maps, &beams, walker.tracer, s) * throughput;
            found.direct +=
                single_scattering(&beams, walker.carried(), s.rng, s.stats) * throughput;
            found.dyed += dye_light(&beams, walker.carried(), s.rng, s.stats) * throughput;
            if chain.specular > 0 && !volume {
                found.emitted += at_end(throughput * emission_seen(walker.tracer, &chain));
            }
            let End::Scatter(vertex) = chain.end else {
                return None;
            };
            vp = VisiblePoint {
                vertex,
                throughput: throughput * chain.weight * chain.radiance_scale(),
            };
        }
    }

    /// The volume caustic a camera chain recorded in `beams` collects on its way through media,
    /// per unit of the path's throughput before it; `tracer`: the one it ended on.
    fn volume_caustic(
        &self,
        maps: &Maps,
        beams: &Beams,
        tracer: &Tracer,
        s: &mut Sample<MapLayer>,
    ) -> Recorded {
        match &maps.volume {
            Some(volume) => s.stats.time_query(|| beams.radiance(volume, tracer)),
            None => Recorded::default(),
        }
    }
}

/// [`direct`] as the camera records it through the measurement `measure` its path carries
/// (None: unpolarized transport).
fn recorded_direct(
    carried: Carried,
    vp: &VisiblePoint,
    measure: &Option<Polarization>,
    rng: &mut impl rand::Rng,
    stats: &mut Stats,
) -> Recorded {
    match measure {
        Some(p) => direct(carried, vp, p, rng, stats),
        None => Recorded::radiance(direct(carried, vp, &Radiance, rng, stats)),
    }
}

/// The caustic light the photons of `map` around the visible point `v` (the path's `vp`,
/// served by `near`; `tracer` the one the path ended on) send the camera, as `measure`
/// records it: each photon's flux through the BSDF (a Lambertian surface's albedo/π applied
/// once), taken to the camera through the point's Mueller matrix for the photon's direction
/// and the Stokes vector the map kept of it, where the point has one (a plastic's).
fn caustic_light<M: Measure>(
    tracer: &Tracer,
    map: &PhotonMap,
    near: &Neighbourhood,
    vp: &VisiblePoint,
    v: &SurfaceVertex,
    measure: &M,
    stats: &mut Stats,
) -> M::Light {
    stats.time_query(|| match v.bsdf.lambert_albedo() {
        Some(albedo) => {
            let e = tracer.photon_irradiance(near.estimate(map, v, |p, _| p.flux()));
            measure.of(vp.throughput * albedo * e * FRAC_1_PI)
        }
        None => {
            let sum = near.estimate(map, v, |p, kept| {
                let wi = p.from_direction();
                measure.through(&vp.vertex, wi, kept) * (v.eval(wi) * p.flux())
            });
            sum * tracer.photon_irradiance(Rgb::ONE) * vp.throughput
        }
    })
}

/// Light a camera path found on its way to its visible point.
#[derive(Default)]
struct Found {
    direct: Recorded,
    emitted: Recorded,
    /// Volume caustics scattered into the path along its way through media.
    caustic: Recorded,
    /// Light dyes emitted toward it along its way through their media (path traced).
    dyed: Recorded,
}

/// r_p²/r₀² of Knaus and Zwicker's schedule at pass `index`: Π_{j=1..index} (j + α)/(j + 1).
pub fn schedule(index: u32) -> f64 {
    (1..=index).fold(1.0, |f, j| f * (j as f64 + ALPHA) / (j as f64 + 1.0))
}

impl<'a> Integrator for PhotonMapper<'a> {
    type Pass = Maps;
    type Pixel = PixelCaustics<'a>;
    type Layer = MapLayer;

    fn begin_pass(
        &self,
        index: u32,
        report: &mut Report,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Maps> {
        let caustic = match self.plan.caustic {
            true => Some(self.map(Batch::Caustic, index, self.photons.caustic, report, stop)?),
            false => None,
        };
        let global = match self.plan.global {
            true => Some(self.map(Batch::Global, index, self.photons.global, report, stop)?),
            false => None,
        };
        let (caustic, volume) = match caustic {
            Some(t) => (Some(t.surfaces), self.plan.volume.then_some(t.volume)),
            None => (None, None),
        };
        let global = global.map(|t| t.surfaces);
        report.stored.caustic += caustic.as_ref().map_or(0, |m| m.len() as u64);
        report.stored.global += global.as_ref().map_or(0, |m| m.len() as u64);
        report.stored.volume += volume.as_ref().map_or(0, |m| m.len() as u64);
        Some(Maps {
            index,
            caustic,
            global,
            volume,
        })
    }

    fn sample(
        &self,
        maps: &Maps,
        pixel: &mut PixelCaustics<'a>,
        ray: CameraRay,
        s: &mut Sample<MapLayer>,
    ) {
        let hero = hero(self.tracer, s.rng);
        let carried = Carried::starting(self.tracer, hero.as_ref());
        // What the path starts with, for the footprint's neighbouring paths.
        let (start, start_rng) = (carried, s.rng.clone());
        let mut beams = Beams::default();
        let mut measure = None;
        let c = camera_path(carried, ray, &mut beams, &mut measure, s.rng, s.stats);
        s.record(MapLayer::Emitted, c.emitted);
        s.record(MapLayer::Direct, c.single);
        let caustic = self.volume_caustic(maps, &beams, c.carried.tracer, s);
        s.record(MapLayer::Caustic, caustic);
        let dyed = dye_light(&beams, c.carried, s.rng, s.stats);
        s.record(MapLayer::Secondary, dyed);
        let Some(first) = c.visible else { return };
        // The way the path took to its visible point, where that is its first vertex (the
        // pixel's footprint is measured there).
        let way = match first.vertex {
            Vertex::Surface(v) if v.lobes().has_diffuse() => Some(Way {
                prim: v.prim,
                bounces: c.bounces,
                curved: c.curved,
            }),
            Vertex::Surface(_) | Vertex::Medium(_) => None,
        };
        s.add(MapLayer::Albedo, first.vertex.albedo());
        s.add(MapLayer::Normal, first.vertex.normal());
        let mut found = Found::default();
        let visible = self.visible_point(maps, first, c.carried, &mut measure, &mut found, s);
        s.record(MapLayer::Direct, found.direct);
        s.record(MapLayer::Emitted, found.emitted);
        s.record(MapLayer::Caustic, found.caustic);
        s.record(MapLayer::Secondary, found.dyed);
        let Some((vp, v, carried)) = visible else {
            return;
        };
        if fluoresces(carried.tracer, &vp.vertex) {
            // A fluorescent layer's light is path traced ([`super::relight`]).
            let first = FirstVertex::default();
            let onward = match measure.as_mut() {
                Some(p) => onward(vp, carried, first, p, s.rng, s.stats),
                None => onward(vp, carried, first, &mut Radiance, s.rng, s.stats)
                    .map(Recorded::radiance),
            };
            s.record(MapLayer::Direct, onward.lit + onward.direct);
            s.record(MapLayer::Secondary, onward.indirect);
            return;
        }
        let direct = recorded_direct(carried, &vp, &measure, s.rng, s.stats);
        s.record(MapLayer::Direct, direct);
        // The maps bring depolarized light, which the visible point's matrix takes to the
        // camera (a plastic's polarizes it; a Lambertian surface's is none).
        if let Some(global) = &maps.global {
            let secondary = match &measure {
                Some(p) => self.secondary(global, &vp, carried, p, s),
                None => Recorded::radiance(self.secondary(global, &vp, carried, &Radiance, s)),
            };
            s.record(MapLayer::Secondary, secondary);
        }
        if let Some(caustic) = &maps.caustic {
            let r2 = match pixel.radii.iter().find(|r| r.way == way) {
                Some(known) => known.r2,
                None => {
                    let floor = |stats: &mut Stats| {
                        let eye = self.eye.as_ref()?;
                        eye.half_width(&ray, start, &start_rng, &v, way?, stats)
                    };
                    let r2 = self.caustic_r2(caustic, maps.index, &v, floor, s.stats);
                    pixel.radii.push(Radius { way, r2 });
                    r2
                }
            };
            let near = match pixel.near.take() {
                Some(near) if near.serves(&v, r2) => near,
                _ => s
                    .stats
                    .time_query(|| Neighbourhood::around(self.tracer, caustic, &v, r2)),
            };
            let tracer = carried.tracer;
            let light = match &measure {
                Some(p) => caustic_light(tracer, caustic, &near, &vp, &v, p, s.stats),
                None => Recorded::radiance(caustic_light(
                    tracer, caustic, &near, &vp, &v, &Radiance, s.stats,
                )),
            };
            pixel.near = Some(near);
            s.record(MapLayer::Caustic, light);
        }
    }
}

/// What a pass keeps per pixel for its caustic estimates.
#[derive(Default)]
pub struct PixelCaustics<'a> {
    /// The pass's squared caustic radius for each way the pixel's paths took to their
    /// visible points (straight to the floor, through the glass to it, reflected in it to a
    /// wall: each its own footprint; one for every path whose visible point is not its first
    /// vertex), set by the first path that took it.
    radii: Vec<Radius>,
    /// The caustic photons around the latest visible point that asked the map.
    near: Option<Neighbourhood<'a>>,
}

/// The squared caustic radius of a pass for paths that took one way (None: past a glossy
/// surface or a point in a medium, where no footprint is measured).
struct Radius {
    way: Option<Way>,
    r2: f64,
}
