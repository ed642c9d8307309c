//! The volume caustic map: photons stored where they scatter in a medium (Jensen and
//! Christensen 1998; a [`Photon`] there has no surface: its normal is zero), each a ball of
//! its own radius, with a BVH over the balls for the beam radiance estimate (Jarosz, Zwicker
//! and Jensen 2008).
//!
//! Photons are stored at scattering events, whose density per unit volume is σs times the
//! fluence; so at a point x, Σ p(ωi → ωo) Φ K(|x − x_p|) over the photons near x — K a kernel
//! normalised over the ball — estimates σs ∫ p L dω, the radiance the medium scatters into ωo
//! per unit length. Integrated along a stretch of a camera path, each photon's 3D kernel
//! becomes its chord integral ([`Along::kernel`], 1/area): the photon's share of the light
//! in-scattered along the whole stretch, with no distance drawn.

use super::{Photon, TracedPhotons};
use crate::bvh::{build_bvh, Tuning};
use crate::math::Bounds3;
use crate::math::Segment;
use crate::polarization::StoredStokes;
use crate::shapes::{padded_box, TraversalRay};
use glam::DVec3;
use kiddo::immutable::float::kdtree::ImmutableKdTree;
use kiddo::SquaredEuclidean;
use obvhs::bvh2::Bvh2;
use obvhs::ray::RayHit;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::num::NonZero;

/// Volume photons, each with the squared radius of its ball, and a BVH over the balls.
pub struct VolumeMap {
    /// In the BVH's leaf order.
    photons: Vec<Photon>,
    /// Their Stokes vectors, where the transport is polarized (same order; else empty).
    stokes: Vec<StoredStokes>,
    /// Each photon's squared radius (same order).
    r2: Vec<f64>,
    /// The photons' mean radius: the width of the tube around a path that its balls touch.
    mean_radius: f64,
    bvh: Bvh2,
}

/// At most how many consecutive segments of a path one descent of the BVH serves: every
/// photon in their box is tested against each of them (on the fish-eye's chords, 0.03 rad of
/// their circles, runs of 2 to 4 made the camera pass 10 % shorter than a descent for each,
/// of 8 and 16 longer).
const GROUP: usize = 4;

/// How many times the volume of the tube of the map's mean radius around a run of segments
/// the run's box (widened by that radius) may hold for the run to be served by one descent
/// through the box: a long segment askew to the axes fills a small part of its box, and is
/// followed down the BVH as a ray instead. (At 4 the fish-eye's camera pass was 20 %
/// shorter, but the fogged Luneburg lens's — chords of its RKN steps — 9 % longer; at 2, 18 %
/// shorter and 1 % longer; medians of 5.)
const LOOSENESS: f64 = 2.0;

/// Where a photon's ball meets a straight stretch, and how much of its kernel lies on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Along {
    /// Distance from the stretch's start to the middle of its chord through the ball.
    pub distance: f64,
    /// ∫ K ds over the chord (1/length²): the 3D Epanechnikov kernel of the ball,
    /// K(d) = 15 (1 − d²/r²) / (8π r³), integrated along the part of the stretch inside it.
    /// A stretch through the whole ball at distance d from its centre gets the 2D kernel
    /// 5 (r² − d²)^{3/2} / (2π r⁵), normalised over the disk.
    pub kernel: f64,
}

impl VolumeMap {
    /// The map of `photons` (at most u32::MAX of them), each with the squared radius
    /// `shrink` × the squared distance to its k-th nearest neighbour among them (bounded by
    /// `max_r2`: where fewer lie within that, `max_r2`), as in Jarosz et al.'s estimate.
    pub fn new(traced: TracedPhotons, k: usize, max_r2: f64, shrink: f64) -> Self {
        let (mut photons, mut stokes) = traced.into_parts();
        photons.truncate(u32::MAX as usize);
        stokes.truncate(u32::MAX as usize);
        if photons.is_empty() {
            return Self {
                photons,
                stokes,
                r2: Vec::new(),
                mean_radius: 0.0,
                bvh: Bvh2::default(),
            };
        }
        let points: Vec<[f64; 3]> = photons.iter().map(|p| p.position.to_array()).collect();
        let tree: ImmutableKdTree<f64, u32, 3, 32> = ImmutableKdTree::new_from_slice(&points);
        // The photon itself is its own nearest neighbour: ask for k + 1.
        let ask = NonZero::new(k.max(1) + 1).expect("k + 1 > 0");
        let r2: Vec<f64> = points
            .par_iter()
            .map(|p| {
                let found = tree.nearest_n_within::<SquaredEuclidean>(p, max_r2, ask, true);
                let kth = match found.len() == ask.get() {
                    true => found[found.len() - 1].distance.min(max_r2),
                    false => max_r2,
                };
                kth * shrink
            })
            .collect();
        let bvh = build_bvh(
            photons.par_iter().zip(&r2).map(|(p, &r2)| {
                let r = DVec3::splat(r2.sqrt());
                padded_box(Bounds3::new(p.position - r, p.position + r))
            }),
            Tuning::Memory,
        );
        let order = &bvh.primitive_indices;
        let mean_radius = r2.iter().map(|r2| r2.sqrt()).sum::<f64>() / r2.len() as f64;
        Self {
            photons: order.iter().map(|&i| photons[i as usize]).collect(),
            stokes: match stokes.is_empty() {
                true => stokes,
                false => order.iter().map(|&i| stokes[i as usize]).collect(),
            },
            r2: order.iter().map(|&i| r2[i as usize]).collect(),
            mean_radius,
            bvh,
        }
    }

    /// Number of photons.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// True when the map holds no photon.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// Shows `visit` every photon whose ball the straight stretch from `origin` along unit
    /// `dir` over `length` passes through, with its Stokes vector where the map keeps them,
    /// and where and how much of its kernel it meets.
    pub fn along(
        &self,
        origin: DVec3,
        dir: DVec3,
        length: f64,
        mut visit: impl FnMut(&Photon, Option<&StoredStokes>, Along),
    ) {
        if self.photons.is_empty() || length.is_nan() || length <= 0.0 {
            return;
        }
        let ray = TraversalRay::new(origin, dir, length);
        let mut unused = RayHit::none();
        self.bvh.ray_traverse(ray.ray, &mut unused, |_, i| {
            let photon = &self.photons[i];
            if let Some(along) = chord(photon.position - origin, dir, length, self.r2[i]) {
                visit(photon, self.stokes.get(i), along);
            }
            // Never a hit: every ball on the stretch is visited.
            f32::INFINITY
        });
    }

    /// Shows `visit` every photon whose ball one of `path`'s segments passes through, with
    /// the segment's index in `path`, where and how much of its kernel it meets (as
    /// [`VolumeMap::along`] for each). Runs of up to [`GROUP`] consecutive short segments —
    /// the chords of a curved stretch — are served by one descent of the BVH through their
    /// box, where a descent for each would repeat the same nodes.
    pub fn along_path<S: AsRef<Segment>>(
        &self,
        path: &[S],
        mut visit: impl FnMut(usize, &Photon, Option<&StoredStokes>, Along),
    ) {
        if self.photons.is_empty() {
            return;
        }
        for run in self.runs(path) {
            let segments = &path[run.first..run.first + run.count];
            match run.is_tight() {
                true => self.within(&run, segments, |k, photon, stokes, along| {
                    visit(run.first + k, photon, stokes, along)
                }),
                false => {
                    let s = segments[0].as_ref();
                    self.along(s.origin, s.dir, s.length, |photon, stokes, along| {
                        visit(run.first, photon, stokes, along)
                    })
                }
            }
        }
    }

    /// `path` cut into runs, each as long as it stays tight (at most [`GROUP`] segments), or
    /// a loose segment alone.
    fn runs<'p, S: AsRef<Segment>>(&self, path: &'p [S]) -> impl Iterator<Item = Run> + 'p {
        let radius = self.mean_radius;
        let mut first = 0;
        std::iter::from_fn(move || {
            let mut run = Run::of(first, path.get(first)?.as_ref(), radius);
            while run.count < GROUP {
                match path
                    .get(first + run.count)
                    .and_then(|s| run.with(s.as_ref()))
                {
                    Some(longer) => run = longer,
                    None => break,
                }
            }
            first += run.count;
            Some(run)
        })
    }

    /// Every photon whose ball reaches the run's box, tested against each of its `segments`.
    fn within<S: AsRef<Segment>>(
        &self,
        run: &Run,
        segments: &[S],
        mut visit: impl FnMut(usize, &Photon, Option<&StoredStokes>, Along),
    ) {
        self.bvh.aabb_traverse(padded_box(run.bounds), |bvh, node| {
            let node = &bvh.nodes[node as usize];
            let leaf = node.first_index as usize..(node.first_index + node.prim_count) as usize;
            for i in leaf {
                let photon = &self.photons[i];
                // A ball clear of the run's box meets none of its segments.
                let outside = (run.bounds.lo - photon.position)
                    .max(photon.position - run.bounds.hi)
                    .max(DVec3::ZERO);
                if outside.length_squared() > self.r2[i] {
                    continue;
                }
                for (k, s) in segments.iter().enumerate() {
                    let s = s.as_ref();
                    if let Some(along) =
                        chord(photon.position - s.origin, s.dir, s.length, self.r2[i])
                    {
                        visit(k, photon, self.stokes.get(i), along);
                    }
                }
            }
            true
        });
    }
}

/// Consecutive segments of a path and their box.
struct Run {
    bounds: Bounds3,
    /// The index of the first in the path.
    first: usize,
    count: usize,
    /// Their lengths' sum.
    length: f64,
    /// The radius of the tube around them that photons' balls touch.
    radius: f64,
}

impl Run {
    /// Segment `s`, the path's `first`, alone.
    fn of(first: usize, s: &Segment, radius: f64) -> Self {
        let end = s.end();
        Self {
            bounds: Bounds3::new(s.origin.min(end), s.origin.max(end)),
            first,
            count: 1,
            length: s.length,
            radius,
        }
    }

    /// The run with `s` after it, where it stays tight.
    fn with(&self, s: &Segment) -> Option<Self> {
        let end = s.end();
        let longer = Self {
            bounds: self.bounds.with_point(s.origin).with_point(end),
            first: self.first,
            count: self.count + 1,
            length: self.length + s.length,
            radius: self.radius,
        };
        longer.is_tight().then_some(longer)
    }

    /// Whether the box, widened by the radius, holds at most [`LOOSENESS`] times the tube's
    /// volume (a box with a NaN or an infinite side is not tight: such a segment is followed
    /// as a ray, alone).
    fn is_tight(&self) -> bool {
        let w = 2.0 * self.radius;
        let box_volume = (self.bounds.diagonal() + DVec3::splat(w)).element_product();
        let tube = (self.length + w) * w * w;
        box_volume.is_finite() && box_volume <= LOOSENESS * tube
    }
}

/// The part of the stretch [0, `length`] along unit `dir` inside the ball of squared radius
/// `r2` centred at `w` from the stretch's start, and its kernel integral; None where the
/// stretch misses the ball.
fn chord(w: DVec3, dir: DVec3, length: f64, r2: f64) -> Option<Along> {
    let s = w.dot(dir);
    let d2 = w.length_squared() - s * s;
    let h2 = r2 - d2;
    if h2.is_nan() || h2 <= 0.0 {
        return None;
    }
    let h = h2.sqrt();
    // The chord in the ball's own coordinate u = t − s.
    let u0 = (-s).max(-h);
    let u1 = (length - s).min(h);
    if u1 <= u0 {
        return None;
    }
    // ∫ (1 − (d² + u²)/r²) du over [u0, u1] = (h² (u1 − u0) − (u1³ − u0³)/3) / r².
    let integral = (h2 * (u1 - u0) - (u1 * u1 * u1 - u0 * u0 * u0) / 3.0) / r2;
    Some(Along {
        distance: s + 0.5 * (u0 + u1),
        kernel: 15.0 / (8.0 * PI * r2 * r2.sqrt()) * integral,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chord through the whole ball integrates the 3D kernel to the 2D one, which is
    /// normalised over the disk (checked by quadrature over the impact parameter).
    #[test]
    fn a_whole_chord_gives_the_disk_kernel() {
        let r2: f64 = 0.04;
        let r = r2.sqrt();
        let dir = DVec3::X;
        let n = 20_000;
        let mut disk = 0.0;
        for i in 0..n {
            let d = (i as f64 + 0.5) / n as f64 * r;
            let w = DVec3::new(1.0, d, 0.0);
            let along = chord(w, dir, 2.0, r2).expect("inside");
            let closed = 5.0 * (r2 - d * d).powf(1.5) / (2.0 * PI * r2 * r2 * r);
            assert!((along.kernel - closed).abs() <= 1e-12 * closed.max(1.0));
            assert!((along.distance - 1.0).abs() < 1e-12);
            disk += along.kernel * 2.0 * PI * d * (r / n as f64);
        }
        assert!((disk - 1.0).abs() < 1e-6, "∫ K dA = {disk}");
    }

    /// Stretches that end inside a ball take their part of its kernel: two halves of a
    /// stretch add up to the whole, and a stretch that stops short of the ball gets nothing.
    #[test]
    fn pieces_of_a_stretch_add_up() {
        let r2 = 0.09;
        let w = DVec3::new(1.0, 0.1, 0.05);
        let whole = chord(w, DVec3::X, 2.0, r2).expect("inside").kernel;
        let first = chord(w, DVec3::X, 0.93, r2).expect("inside").kernel;
        let second = chord(w - DVec3::X * 0.93, DVec3::X, 2.0 - 0.93, r2)
            .expect("inside")
            .kernel;
        assert!((first + second - whole).abs() < 1e-12 * whole);
        assert_eq!(chord(w, DVec3::X, 0.6, r2), None);
        assert_eq!(chord(w, -DVec3::X, 5.0, r2), None);
    }

    /// 3000 photons spread over the unit cube, each ball through its 8 nearest neighbours.
    fn scattered_map(rng: &mut rand_pcg::Pcg64Mcg) -> VolumeMap {
        use rand::Rng;
        let photons: Vec<Photon> = (0..3000)
            .map(|_| Photon {
                position: DVec3::new(rng.gen(), rng.gen(), rng.gen()),
                normal: DVec3::ZERO,
                power: [1.0; 3],
                from: [0.0, 0.0, 1.0],
                base: 1.0,
            })
            .collect();
        let mut traced = TracedPhotons::default();
        photons.into_iter().for_each(|p| traced.push(p, None));
        VolumeMap::new(traced, 8, 0.01, 0.5)
    }

    /// The sum of the kernels of the balls segment `s` meets, found by testing every photon.
    fn brute_force(map: &VolumeMap, s: &Segment) -> f64 {
        (0..map.len())
            .filter_map(|i| {
                chord(
                    map.photons[i].position - s.origin,
                    s.dir,
                    s.length,
                    map.r2[i],
                )
            })
            .map(|a| a.kernel)
            .sum()
    }

    /// The BVH finds exactly the balls a brute-force test finds, with the same kernels.
    #[test]
    fn the_map_visits_every_ball_on_a_stretch() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let map = scattered_map(&mut rng);
        for _ in 0..50 {
            let origin = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let dir = (DVec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5).normalize();
            let length = rng.gen::<f64>();
            let mut found = 0.0;
            map.along(origin, dir, length, |_, _, a| found += a.kernel);
            let brute = brute_force(
                &map,
                &Segment {
                    origin,
                    dir,
                    length,
                },
            );
            assert!(
                (found - brute).abs() <= 1e-9 * brute.max(1.0),
                "{found} vs {brute}"
            );
        }
    }

    /// Along a path of segments — the short chords of circles, served in runs by one descent
    /// through their box, and long ones askew, each followed as a ray — every segment finds
    /// exactly the balls a brute-force test finds, with the same kernels.
    #[test]
    fn the_map_visits_every_ball_on_a_path() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(5);
        let map = scattered_map(&mut rng);
        let mut runs = [0; 2];
        for path_index in 0..40 {
            // A circle's chords 0.03 rad apart, or (every fourth path) long straight segments
            // turning at random.
            let centre = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let radius = rng.gen_range(0.1..0.5);
            let (u, v) = (DVec3::X, DVec3::new(0.0, 0.6, 0.8));
            let points: Vec<DVec3> = (0..30)
                .map(|k| match path_index % 4 {
                    0 => DVec3::new(rng.gen(), rng.gen(), rng.gen()),
                    _ => {
                        let a = 0.03 * k as f64;
                        centre + radius * (a.cos() * u + a.sin() * v)
                    }
                })
                .collect();
            let mut path: Vec<Segment> = points
                .windows(2)
                .map(|w| Segment {
                    origin: w[0],
                    dir: (w[1] - w[0]).normalize(),
                    length: (w[1] - w[0]).length(),
                })
                .collect();
            // A segment without end from the cube's middle and one of NaN, after a circle's
            // chords: each alone, as a ray (all the balls along the first, none on the
            // second).
            if path_index % 4 == 1 {
                let last = path[path.len() - 1];
                path.push(Segment {
                    origin: DVec3::splat(0.5),
                    length: f64::INFINITY,
                    ..last
                });
                path.push(Segment {
                    origin: DVec3::NAN,
                    ..last
                });
            }
            let mut found = vec![0.0; path.len()];
            map.along_path(&path, |k, _, _, a| found[k] += a.kernel);
            for (s, found) in path.iter().zip(&found) {
                let brute = brute_force(&map, s);
                assert!(
                    (found - brute).abs() <= 1e-9 * brute.max(1.0),
                    "{found} vs {brute}"
                );
            }
            if path_index % 4 == 1 {
                let n = found.len();
                assert!(
                    found[n - 2] > 0.0 && found[n - 1] == 0.0,
                    "{:?}",
                    &found[n - 2..]
                );
            }
            // Both ways of serving a run are taken.
            for run in map.runs(&path) {
                runs[usize::from(run.is_tight())] += 1;
            }
        }
        assert!(runs[0] > 0 && runs[1] > 0, "loose and tight runs: {runs:?}");
    }
}
