//! The photon mapper (Zhdanov et al. (2020) §4, Jensen): each pass traces a caustic and a global photon
//! map, and each camera sample's visible point gets
//! - **direct**: light with no specular interaction on the way ([`super::direct`]);
//! - **caustic**: the caustic map's density estimate (photons with a specular bounce), with an
//!   Epanechnikov kernel of radius r_p at pass p: r₀ the k-nearest distance at the pixel's
//!   first visible point in that pass (or the scene's `radius`), shrunk by Knaus and Zwicker's
//!   probabilistic progressive schedule r_p² = r₀² Π_{j=1..p} (j + α)/(j + 1), α = 2/3: a
//!   function of the pass index alone, so passes are independent and their films merge;
//! - **secondary**: a final gather — cosine rays followed through specular surfaces to a
//!   diffuse one, where the global map's precomputed irradiance is read;
//! - **emitted**: emitters and the environment seen along the camera's specular chain.

use super::direct::{camera_path, direct, hero};
use super::{CameraRay, Integrator, Sample, Slot};
use crate::bsdf::Bsdf;
use crate::color::Rgb;
use crate::film::Layer;
use crate::photon::{shoot, Batch, PhotonMap, Photons, Sources};
use crate::report::Report;
use crate::scene::Scene;
use crate::settings::{PhotonSettings, Settings};
use crate::transport::chain::{Carried, End, Policy, Ray, Walker};
use crate::transport::{offset, Stats, Tracer};
use rand::Rng;
use std::f64::consts::FRAC_1_PI;
use std::time::Instant;

/// The radius-reduction parameter α (Hachisuka and Jensen 2009; Knaus and Zwicker 2011): the
/// fraction of a pass's photons a progressive estimate keeps.
pub const ALPHA: f64 = 2.0 / 3.0;

/// Which photon maps a scene needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// A caustic map: some light path can meet a specular surface before a diffuse one
    /// (light through gradient media alone is the direct estimate's).
    pub caustic: bool,
    /// A global map: secondary light is on (`gather` > 0) and something is diffuse.
    pub global: bool,
}

impl Plan {
    /// What `scene` needs with `photons`: nothing without diffuse surfaces or without
    /// emitters.
    pub fn of(scene: &Scene, photons: &PhotonSettings) -> Self {
        use crate::material::Material;
        let has = |f: fn(&Material) -> bool| {
            scene
                .surfaces
                .iter()
                .any(|s| f(&scene.materials[s.material]))
        };
        let diffuse = has(|m| matches!(m, Material::Diffuse { .. }));
        let emits = !scene.lights.is_empty() || scene.environment.is_some();
        // (A receiver's detector is transparent: it neither bends nor stores light.)
        let specular = has(|m| matches!(m, Material::Mirror { .. } | Material::Dielectric));
        Self {
            caustic: diffuse && emits && specular && photons.caustic > 0,
            global: diffuse && emits && photons.gather > 0 && photons.global > 0,
        }
    }
}

/// The layers, in order; `beauty` is their radiance sum.
const LAYERS: &[Layer] = &[
    Layer::radiance("direct"),
    Layer::radiance("caustic"),
    Layer::radiance("secondary"),
    Layer::radiance("emitted"),
    Layer::aux("albedo"),
    Layer::aux("normal"),
];
const DIRECT: Slot = Slot(0);
const CAUSTIC: Slot = Slot(1);
const SECONDARY: Slot = Slot(2);
const EMITTED: Slot = Slot(3);
const ALBEDO: Slot = Slot(4);
const NORMAL: Slot = Slot(5);

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
}

/// A pass's photon maps.
pub struct Maps {
    index: u32,
    caustic: Option<PhotonMap>,
    global: Option<PhotonMap>,
}

impl<'a> PhotonMapper<'a> {
    /// The photon mapper of the tracer's scene under `settings`.
    pub fn new(tracer: &'a Tracer<'a>, settings: &Settings) -> Self {
        let max_radius = settings.photons.radius.unwrap_or(0.05 * tracer.ball.1);
        Self {
            tracer,
            sources: Sources::new(tracer),
            caustic_sources: Sources::for_caustics(tracer),
            plan: Plan::of(tracer.scene, &settings.photons),
            photons: settings.photons,
            seed: settings.seed,
            max_r2: max_radius * max_radius,
        }
    }

    /// Traces one batch of pass `index` into a map (the global one with its precomputed
    /// irradiance); None when stopped.
    fn map(
        &self,
        batch: Batch,
        index: u32,
        count: u64,
        report: &mut Report,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<PhotonMap> {
        let t0 = Instant::now();
        let photons = Photons::all(batch, self.seed, index as u64, count);
        let sources = match batch {
            Batch::Caustic => &self.caustic_sources,
            _ => &self.sources,
        };
        let (sink, stats) = shoot(self.tracer, sources, photons, stop);
        let t1 = Instant::now();
        report.stats.add(&stats);
        if stop() {
            return None;
        }
        let mut map = PhotonMap::new(sink.photons);
        if batch == Batch::Global {
            map.precompute_irradiance(self.photons.knn as usize, self.max_r2);
        }
        report.seconds.photons += (t1 - t0).as_secs_f64();
        report.seconds.maps += t1.elapsed().as_secs_f64();
        Some(map)
    }

    /// The squared caustic radius of pass `index` at a visible point: the k-nearest distance
    /// there (or the scene's radius), times Knaus and Zwicker's schedule.
    fn caustic_r2(
        &self,
        caustic: &PhotonMap,
        index: u32,
        vp: &super::direct::VisiblePoint,
        stats: &mut Stats,
    ) -> f64 {
        let r0 = match self.photons.radius {
            Some(r) => r * r,
            None => stats.time_query(|| {
                caustic.knn_radius2(
                    vp.position,
                    vp.normal,
                    self.photons.knn as usize,
                    self.max_r2,
                )
            }),
        };
        r0 * schedule(index)
    }

    /// Secondary light at a visible point: `gather` cosine rays, each followed through
    /// specular surfaces to a diffuse one, where the global map's precomputed k-nearest
    /// irradiance of the nearest photon gives the radiance leaving it. Emission and
    /// environment met by gather rays are not counted: that light is the direct or caustic
    /// part.
    fn secondary(
        &self,
        global: &PhotonMap,
        vp: &super::direct::VisiblePoint,
        carried: Carried,
        s: &mut Sample,
    ) -> Rgb {
        let gather = self.photons.gather;
        let lambert = Bsdf::Lambert { albedo: vp.albedo };
        let mut sum = Rgb::ZERO;
        for _ in 0..gather {
            s.stats.gather_rays += 1;
            let b = lambert
                .sample(vp.normal, vp.normal, (s.rng.gen(), s.rng.gen(), 0.0))
                .expect("a Lambertian surface always scatters");
            let ray = Ray {
                origin: offset(vp.position, vp.normal),
                direction: b.wi,
                medium: vp.medium,
            };
            let mut walker = Walker::carrying(carried, Policy::Weighted);
            let chain = walker.follow(ray, s.rng, s.stats, &mut ());
            if let End::Diffuse {
                position,
                normal,
                albedo,
                ..
            } = chain.end
            {
                let e = s
                    .stats
                    .time_query(|| global.nearest_irradiance(position, normal));
                let e = walker.tracer.photon_irradiance(e);
                sum += b.weight * chain.weight * albedo * FRAC_1_PI * e * chain.radiance_scale();
            }
        }
        vp.throughput * sum / gather.max(1) as f64
    }
}

/// r_p²/r₀² of Knaus and Zwicker's schedule at pass `index`: Π_{j=1..index} (j + α)/(j + 1).
pub fn schedule(index: u32) -> f64 {
    (1..=index).fold(1.0, |f, j| f * (j as f64 + ALPHA) / (j as f64 + 1.0))
}

impl Integrator for PhotonMapper<'_> {
    type Pass = Maps;
    /// The pass's squared caustic radius at this pixel, once its first visible point set it.
    type Pixel = Option<f64>;

    fn layers(&self) -> &'static [Layer] {
        LAYERS
    }

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
        report.stored.caustic += caustic.as_ref().map_or(0, |m| m.len() as u64);
        report.stored.global += global.as_ref().map_or(0, |m| m.len() as u64);
        Some(Maps {
            index,
            caustic,
            global,
        })
    }

    fn sample(&self, maps: &Maps, r2: &mut Option<f64>, ray: CameraRay, s: &mut Sample) {
        let hero = hero(self.tracer, s.rng);
        let carried = Carried {
            tracer: self.tracer,
            hero: hero.as_ref(),
        };
        let c = camera_path(carried, ray.origin, ray.direction, s.rng, s.stats);
        s.add(EMITTED, c.emitted);
        let Some(vp) = c.visible else { return };
        s.add(ALBEDO, vp.albedo);
        s.add(NORMAL, Rgb(vp.normal));
        let direct = direct(c.carried, &vp, s.rng, s.stats);
        s.add(DIRECT, direct);
        if let Some(global) = &maps.global {
            let secondary = self.secondary(global, &vp, c.carried, s);
            s.add(SECONDARY, secondary);
        }
        if let Some(caustic) = &maps.caustic {
            let r2 = *r2.get_or_insert_with(|| self.caustic_r2(caustic, maps.index, &vp, s.stats));
            let (irradiance, _) = s
                .stats
                .time_query(|| caustic.irradiance(vp.position, vp.normal, r2));
            let irradiance = c.carried.tracer.photon_irradiance(irradiance);
            s.add(CAUSTIC, vp.throughput * vp.albedo * irradiance * FRAC_1_PI);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_slot_names_its_layer() {
        for (slot, name) in [
            (DIRECT, "direct"),
            (CAUSTIC, "caustic"),
            (SECONDARY, "secondary"),
            (EMITTED, "emitted"),
            (ALBEDO, "albedo"),
            (NORMAL, "normal"),
        ] {
            assert_eq!(slot.of(LAYERS).name, name);
        }
    }
}
