//! The photon map: photons stored at diffuse hits, in a kiddo `ImmutableKdTree` built once
//! after a pass (the mutable tree panics on many coplanar points; the immutable one does not).
//! Queries take squared radii, as kiddo's `SquaredEuclidean` does.

use crate::color::Rgb;
use crate::polarization::StoredStokes;
use glam::DVec3;
use kiddo::immutable::float::kdtree::ImmutableKdTree;
use kiddo::SquaredEuclidean;
use std::num::NonZero;
use std::ops::{AddAssign, Mul};

/// A stored photon: at a scattering surface (diffuse or glossy), or where it scattered in a
/// medium ([`super::VolumeMap`]: no surface, a zero normal).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    /// Where it hit.
    pub position: DVec3,
    /// Unit normal of the side of the surface it arrived on (zero in a medium).
    pub normal: DVec3,
    /// Flux it carries, W per channel (already divided by the photon count of its pass).
    pub power: [f32; 3],
    /// Unit direction back toward where it came from (ωi of the BSDF that reflects it).
    pub from: [f32; 3],
    /// The share of its flux that reaches the diffuse base of the surface it arrived at
    /// ([`crate::bsdf::Bsdf::diffuse_entry`]: 1 on a Lambertian surface, 1 − E(μi) under a
    /// plastic's coat; 1 in a medium, where it is not read).
    pub base: f32,
}

impl Photon {
    /// [`Photon::from`] as f64.
    pub fn from_direction(&self) -> DVec3 {
        DVec3::from_array(self.from.map(f64::from))
    }

    /// The flux as f64 RGB.
    pub fn flux(&self) -> Rgb {
        Rgb::new(
            self.power[0] as f64,
            self.power[1] as f64,
            self.power[2] as f64,
        )
    }

    /// The flux that reaches the surface's diffuse base ([`Photon::base`] of it).
    pub fn flux_to_base(&self) -> Rgb {
        self.flux() * self.base as f64
    }
}

/// Photons as traced, in photon order, with their Stokes vectors where the transport
/// is polarized (one each, or none at all).
#[derive(Clone, Debug, Default)]
pub struct TracedPhotons {
    photons: Vec<Photon>,
    stokes: Vec<StoredStokes>,
}

impl TracedPhotons {
    /// Adds `photon`, with its Stokes vector where the transport is polarized.
    pub fn push(&mut self, photon: Photon, stokes: Option<StoredStokes>) {
        self.photons.push(photon);
        self.stokes.extend(stokes);
        debug_assert!(self.stokes.is_empty() || self.stokes.len() == self.photons.len());
    }

    /// Adds `more`, traced after these.
    pub fn extend(&mut self, more: TracedPhotons) {
        self.photons.extend(more.photons);
        self.stokes.extend(more.stokes);
    }

    /// The photons.
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// The photons and their Stokes vectors (empty where the transport is not polarized).
    pub fn into_parts(self) -> (Vec<Photon>, Vec<StoredStokes>) {
        (self.photons, self.stokes)
    }
}

/// What a density estimate sums per photon: its weight per channel (`Rgb`), or what a camera
/// records of its light ([`crate::polarization::Recorded`]).
pub trait Summand: Copy + Default + AddAssign + Mul<f64, Output = Self> {}

impl<T: Copy + Default + AddAssign + Mul<f64, Output = T>> Summand for T {}

/// The Epanechnikov density estimate, K(d) = 2(1 − d²/r²)/(π r²) (normalised over the disk),
/// summed over photons.
struct Epanechnikov<T> {
    r2: f64,
    sum: T,
    count: usize,
}

impl<T: Summand> Epanechnikov<T> {
    fn new(r2: f64) -> Self {
        Self {
            r2,
            sum: T::default(),
            count: 0,
        }
    }

    /// The estimate of squared radius `r2` over the photons `gather` adds: (Σ weight·K, how
    /// many); nothing for r² ≤ 0.
    fn sum(r2: f64, gather: impl FnOnce(&mut Self)) -> (T, usize) {
        if r2 <= 0.0 {
            return (T::default(), 0);
        }
        let mut kernel = Self::new(r2);
        gather(&mut kernel);
        kernel.estimate()
    }

    /// Adds a photon's weight at squared distance `d2` (≤ r²).
    fn add(&mut self, weight: T, d2: f64) {
        self.sum += weight * (1.0 - d2 / self.r2);
        self.count += 1;
    }

    /// Σ weight·K(d), and how many photons were added.
    fn estimate(&self) -> (T, usize) {
        let k = 2.0 / (std::f64::consts::PI * self.r2);
        (self.sum * k, self.count)
    }
}

/// Photons with a kd-tree over their positions.
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// Their Stokes vectors, where the transport is polarized (same order; else empty).
    stokes: Vec<StoredStokes>,
    tree: Option<ImmutableKdTree<f64, u32, 3, 32>>,
    /// Precomputed irradiance of the diffuse bases, when [`PhotonMap::precompute_irradiance`]
    /// has run.
    sites: Option<Sites>,
}

/// Every [`SITE_STRIDE`]-th photon with its precomputed irradiance and a tree over them.
struct Sites {
    tree: ImmutableKdTree<f64, u32, 3, 32>,
    /// Each site's estimate, by the tree's item: all a lookup reads of a site in one place
    /// (it read the photon's normal, the site's photon index and its irradiance from three
    /// arrays: three cache misses a final-gather ray where one will do).
    estimates: Vec<SiteEstimate>,
}

/// What a site holds.
struct SiteEstimate {
    /// Its photon's normal (the side of the surface it lies on).
    normal: DVec3,
    /// Irradiance reaching the diffuse base there, W/m² per channel.
    irradiance: [f32; 3],
}

/// Where a position is kept in the kd-trees: turned by a fixed rotation (about the axis
/// (1, 2, 3), by 0.7 rad). Photons lie on surfaces, which in scenes are often axis-aligned; a
/// kd-tree splitting such a wall along its own constant coordinate cannot prune, and queries
/// slow down several times. Turned, no wall is axis-aligned, and distances are unchanged (to
/// rounding, ~1e-16 relative).
fn tree_point(p: DVec3) -> [f64; 3] {
    const R: [[f64; 3]; 3] = rotation();
    [0, 1, 2].map(|i| R[i][0] * p.x + R[i][1] * p.y + R[i][2] * p.z)
}

/// The rotation of [`tree_point`], rows of the matrix (Rodrigues' formula, evaluated once at
/// compile time from its cos and sin).
const fn rotation() -> [[f64; 3]; 3] {
    // Unit axis (1, 2, 3)/√14; angle 0.7: cos 0.7 and sin 0.7 to 17 digits.
    let (x, y, z) = (
        0.267_261_241_912_424_4,
        0.534_522_483_824_848_8,
        0.801_783_725_737_273_2,
    );
    let (c, s) = (0.764_842_187_284_488_4, 0.644_217_687_237_691);
    let t = 1.0 - c;
    [
        [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
        [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
        [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
    ]
}

/// One photon in this many is a site of precomputed irradiance.
pub const SITE_STRIDE: usize = 8;

/// A photon only counts for a query point when it lies on the same side of (nearly) the
/// same surface: its normal within ~25° of the query's (cos ≥ 0.9). This rejects photons on
/// the other wall of a corner and on the back of a thin object.
const SAME_SURFACE_COS: f64 = 0.9;

/// Whether a photon (or a site) of normal `at` lies on the surface side of unit normal
/// `normal` (see [`SAME_SURFACE_COS`]).
fn on_side(at: DVec3, normal: DVec3) -> bool {
    at.dot(normal) >= SAME_SURFACE_COS
}

impl PhotonMap {
    /// Builds the tree over `photons`. At most u32::MAX photons are indexed (a pass of that
    /// many would need > 300 GiB); any beyond are dropped.
    pub fn new(photons: Vec<Photon>) -> Self {
        let mut traced = TracedPhotons::default();
        photons.into_iter().for_each(|p| traced.push(p, None));
        Self::traced(traced)
    }

    /// [`PhotonMap::new`] of photons with their Stokes vectors where the transport is
    /// polarized ([`PhotonMap::weighted_among`] shows them).
    pub fn traced(traced: TracedPhotons) -> Self {
        let (mut photons, mut stokes) = traced.into_parts();
        photons.truncate(u32::MAX as usize);
        stokes.truncate(u32::MAX as usize);
        let tree = (!photons.is_empty()).then(|| {
            let points: Vec<[f64; 3]> = photons.iter().map(|p| tree_point(p.position)).collect();
            ImmutableKdTree::new_from_slice(&points)
        });
        Self {
            photons,
            stokes,
            tree,
            sites: None,
        }
    }

    /// Precomputes the irradiance that reaches the diffuse base ([`Photon::flux_to_base`]) at
    /// sites — every [`SITE_STRIDE`]-th photon — from the other photons, so that a later
    /// lookup costs one nearest-site query ([`PhotonMap::nearest_irradiance`]). The sites'
    /// estimates use only non-site photons, scaled by stride/(stride − 1): they are then
    /// independent of where the sites lie. (An estimate at every photon from all the others,
    /// Christensen's choice, is biased low when looked up by nearest photon: a photon in a
    /// sparse spot owns a large Voronoi cell and is found more often; measured −11 % on a
    /// uniform plane with k = 16.) Runs on the current rayon pool.
    pub fn precompute_irradiance(&mut self, k: usize, max_r2: f64) {
        use rayon::prelude::*;
        let stride = SITE_STRIDE as u32;
        let sites: Vec<u32> = (0..self.photons.len() as u32)
            .step_by(SITE_STRIDE)
            .collect();
        let scale = SITE_STRIDE as f64 / (SITE_STRIDE - 1) as f64;
        let estimates: Vec<SiteEstimate> = sites
            .par_iter()
            .map(|&i| {
                let p = &self.photons[i as usize];
                let keep = |j| j % stride != 0;
                let e =
                    self.knn_weighted(p.position, p.normal, k, max_r2, keep, Photon::flux_to_base);
                SiteEstimate {
                    normal: p.normal,
                    irradiance: (e * scale).as_vec3().to_array(),
                }
            })
            .collect();
        let points: Vec<[f64; 3]> = sites
            .iter()
            .map(|&i| tree_point(self.photons[i as usize].position))
            .collect();
        self.sites = (!sites.is_empty()).then(|| Sites {
            tree: ImmutableKdTree::new_from_slice(&points),
            estimates,
        });
    }

    /// The precomputed irradiance reaching the diffuse base at the nearest site to `p` on the
    /// surface side `normal` (zero when none of the 16 nearest sites lies on that side, or
    /// when [`PhotonMap::precompute_irradiance`] has not run). No distance limit: where
    /// photons are sparse the nearest site may lie farther than the estimates' radius, and its
    /// irradiance is still the estimate there. (A cut-off at that radius read zero instead:
    /// the Luneburg scene with a quad light and `--radius 0.02` rendered its secondary light
    /// 28× too dark, 0.0005 against 0.014 at the default radius; now 0.016.)
    pub fn nearest_irradiance(&self, p: DVec3, normal: DVec3) -> Rgb {
        let Some(sites) = &self.sites else {
            return Rgb::ZERO;
        };
        let query = tree_point(p);
        let matches = |item: u32| on_side(sites.estimates[item as usize].normal, normal);
        let value = |item: u32| {
            Rgb(DVec3::from_array(
                sites.estimates[item as usize].irradiance.map(f64::from),
            ))
        };
        // Almost always the nearest site lies on the same surface: one cheap query.
        let nearest = sites.tree.nearest_one::<SquaredEuclidean>(&query);
        if matches(nearest.item) {
            return value(nearest.item);
        }
        sites
            .tree
            .nearest_n::<SquaredEuclidean>(&query, NonZero::new(16).expect("16 > 0"))
            .iter()
            .find(|nn| matches(nn.item))
            .map_or(Rgb::ZERO, |nn| value(nn.item))
    }

    /// Number of photons.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when the map holds no photon.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The stored photons, in the order they were given.
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// Calls `f(photon, d²)` for every photon within squared distance `r2` of `p` (inclusive)
    /// that lies on the surface side with unit normal `normal`.
    pub fn for_each_within(
        &self,
        p: DVec3,
        normal: DVec3,
        r2: f64,
        mut f: impl FnMut(&Photon, f64),
    ) {
        let Some(tree) = &self.tree else { return };
        for nn in tree.within_unsorted::<SquaredEuclidean>(&tree_point(p), r2) {
            let photon = &self.photons[nn.item as usize];
            if on_side(photon.normal, normal) {
                f(photon, nn.distance);
            }
        }
    }

    /// The k nearest photons to `p` within squared distance `max_r2` on the surface side
    /// `normal` for which `keep(index)` holds: (index, d²), nearest first. Asks the tree for
    /// more candidates until k pass the filters or none are left within `max_r2`.
    fn nearest(
        &self,
        p: DVec3,
        normal: DVec3,
        k: usize,
        max_r2: f64,
        keep: impl Fn(u32) -> bool,
    ) -> Vec<(u32, f64)> {
        let Some(tree) = &self.tree else {
            return Vec::new();
        };
        let mut ask = 2 * k + 2;
        loop {
            // Bounded by `max_r2`: where photons are sparse (a caustic map away from its
            // caustics) an unbounded `nearest_n` searches far beyond it for candidates it
            // then drops (measured 6× slower with 5 photons within `max_r2`, 1.2× faster with
            // 500).
            let candidates = tree.nearest_n_within::<SquaredEuclidean>(
                &tree_point(p),
                max_r2,
                NonZero::new(ask).expect("ask > 0"),
                true,
            );
            let exhausted = candidates.len() < ask;
            let found: Vec<(u32, f64)> = candidates
                .into_iter()
                .filter(|nn| {
                    keep(nn.item) && on_side(self.photons[nn.item as usize].normal, normal)
                })
                .take(k)
                .map(|nn| (nn.item, nn.distance))
                .collect();
            if found.len() == k || exhausted {
                return found;
            }
            ask *= 4;
        }
    }

    /// The squared distance from `p` to its k-th nearest photon on the surface side `normal`,
    /// or `max_r2` when fewer than k lie within that.
    pub fn knn_radius2(&self, p: DVec3, normal: DVec3, k: usize, max_r2: f64) -> f64 {
        let found = self.nearest(p, normal, k.max(1), max_r2, |_| true);
        if found.len() == k.max(1) {
            found[found.len() - 1].1
        } else {
            max_r2
        }
    }

    /// Σ weight(photon)·K(d) over the k nearest photons on the side `normal` that `keep`
    /// admits, with the Epanechnikov kernel of r² the k-th distance² (or `max_r2` when fewer
    /// are found): with weight = flux the irradiance. The k-th photon has weight 0, so this is
    /// the (k − 1)/(π r²) density estimate, unbiased for uniformly scattered photons (πr²ρ is
    /// Gamma(k)-distributed, E[1/Gamma(k)] = 1/(k − 1)).
    fn knn_weighted(
        &self,
        p: DVec3,
        normal: DVec3,
        k: usize,
        max_r2: f64,
        keep: impl Fn(u32) -> bool,
        weight: impl Fn(&Photon) -> Rgb,
    ) -> Rgb {
        let found = self.nearest(p, normal, k.max(2), max_r2, keep);
        let r2 = if found.len() == k.max(2) {
            found[found.len() - 1].1
        } else {
            max_r2
        };
        Epanechnikov::sum(r2, |kernel| {
            for &(i, d2) in &found {
                kernel.add(weight(&self.photons[i as usize]), d2);
            }
        })
        .0
    }

    /// Irradiance at `p` (W/m² per channel) from the photons within squared radius `r2` on
    /// the surface side `normal`, with the Epanechnikov kernel K(d) = 2(1 − d²/r²)/(π r²)
    /// (normalised over the disk): E = Σ Φ K. Also returns how many photons were found.
    pub fn irradiance(&self, p: DVec3, normal: DVec3, r2: f64) -> (Rgb, usize) {
        self.weighted(p, normal, r2, Photon::flux)
    }

    /// Σ weight(photon)·K(d) over the photons within squared radius `r2` on the side
    /// `normal`, with the Epanechnikov kernel (see [`PhotonMap::irradiance`], weight = flux);
    /// also how many were found.
    pub fn weighted(
        &self,
        p: DVec3,
        normal: DVec3,
        r2: f64,
        weight: impl Fn(&Photon) -> Rgb,
    ) -> (Rgb, usize) {
        Epanechnikov::sum(r2, |kernel| {
            self.for_each_within(p, normal, r2, |ph, d2| kernel.add(weight(ph), d2))
        })
    }

    /// The indices of the photons within squared distance `r2` of `p` (inclusive), on any
    /// side: a neighbourhood that later estimates around points near `p` read
    /// ([`PhotonMap::weighted_among`]) without asking the tree again.
    pub fn indices_within(&self, p: DVec3, r2: f64) -> Vec<u32> {
        let Some(tree) = &self.tree else {
            return Vec::new();
        };
        tree.within_unsorted::<SquaredEuclidean>(&tree_point(p), r2)
            .into_iter()
            .map(|nn| nn.item)
            .collect()
    }

    /// [`PhotonMap::weighted`] over the photons `among` (indices, e.g. from
    /// [`PhotonMap::indices_within`] around a nearby point): the same sum when `among` holds
    /// every photon within √`r2` of `p`. `weight` is shown each photon's Stokes vector where
    /// the map keeps them.
    pub fn weighted_among<T: Summand>(
        &self,
        p: DVec3,
        normal: DVec3,
        r2: f64,
        among: &[u32],
        weight: impl Fn(&Photon, Option<&StoredStokes>) -> T,
    ) -> (T, usize) {
        Epanechnikov::sum(r2, |kernel| {
            for &i in among {
                let photon = &self.photons[i as usize];
                let d2 = photon.position.distance_squared(p);
                if d2 <= r2 && on_side(photon.normal, normal) {
                    kernel.add(weight(photon, self.stokes.get(i as usize)), d2);
                }
            }
        })
    }

    /// Irradiance at `p` from its k nearest photons on the surface side `normal` (the
    /// Epanechnikov kernel with r the k-th distance, at most √`max_r2`).
    pub fn knn_irradiance(&self, p: DVec3, normal: DVec3, k: usize, max_r2: f64) -> Rgb {
        self.knn_weighted(p, normal, k, max_r2, |_| true, Photon::flux)
    }
}
