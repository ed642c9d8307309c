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

use super::Photon;
use crate::accel::build_bvh;
use crate::shapes::padded_box;
use glam::{DVec3, Vec3A};
use kiddo::immutable::float::kdtree::ImmutableKdTree;
use kiddo::SquaredEuclidean;
use obvhs::bvh2::Bvh2;
use obvhs::ray::{Ray, RayHit};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::num::NonZero;

/// Volume photons, each with the squared radius of its ball, and a BVH over the balls.
pub struct VolumeMap {
    /// In the BVH's leaf order.
    photons: Vec<Photon>,
    /// Each photon's squared radius (same order).
    r2: Vec<f64>,
    bvh: Bvh2,
}

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
    pub fn new(mut photons: Vec<Photon>, k: usize, max_r2: f64, shrink: f64) -> Self {
        photons.truncate(u32::MAX as usize);
        if photons.is_empty() {
            return Self {
                photons,
                r2: Vec::new(),
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
        let bvh = build_bvh(photons.par_iter().zip(&r2).map(|(p, &r2)| {
            let r = DVec3::splat(r2.sqrt());
            padded_box(p.position - r, p.position + r)
        }));
        let order = &bvh.primitive_indices;
        Self {
            photons: order.iter().map(|&i| photons[i as usize]).collect(),
            r2: order.iter().map(|&i| r2[i as usize]).collect(),
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
    /// `dir` over `length` passes through, with where and how much of its kernel it meets.
    pub fn along(
        &self,
        origin: DVec3,
        dir: DVec3,
        length: f64,
        mut visit: impl FnMut(&Photon, Along),
    ) {
        if self.photons.is_empty() || length.is_nan() || length <= 0.0 {
            return;
        }
        let ray = Ray::new(
            Vec3A::from(origin.as_vec3()),
            Vec3A::from(dir.as_vec3()),
            0.0,
            // Rounded up: the f32 bound must not cull a ball the f64 stretch reaches.
            (length as f32).next_up(),
        );
        let mut unused = RayHit::none();
        self.bvh.ray_traverse(ray, &mut unused, |_, i| {
            let photon = &self.photons[i];
            if let Some(along) = chord(photon.position - origin, dir, length, self.r2[i]) {
                visit(photon, along);
            }
            // Never a hit: every ball on the stretch is visited.
            f32::INFINITY
        });
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

    /// The BVH finds exactly the balls a brute-force test finds, with the same kernels.
    #[test]
    fn the_map_visits_every_ball_on_a_stretch() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let photons: Vec<Photon> = (0..3000)
            .map(|_| Photon {
                position: DVec3::new(rng.gen(), rng.gen(), rng.gen()),
                normal: DVec3::ZERO,
                power: [1.0; 3],
                from: [0.0, 0.0, 1.0],
                base: 1.0,
            })
            .collect();
        let map = VolumeMap::new(photons, 8, 0.01, 0.5);
        for _ in 0..50 {
            let origin = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let dir = (DVec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5).normalize();
            let length = rng.gen::<f64>();
            let mut found = 0.0;
            map.along(origin, dir, length, |_, a| found += a.kernel);
            let brute: f64 = (0..map.len())
                .filter_map(|i| chord(map.photons[i].position - origin, dir, length, map.r2[i]))
                .map(|a| a.kernel)
                .sum();
            assert!(
                (found - brute).abs() <= 1e-9 * brute.max(1.0),
                "{found} vs {brute}"
            );
        }
    }
}
