//! Random streams and warps. Every random number of a render comes from a stream keyed by
//! (seed, stream, index) — e.g. (seed, pass·pixels + pixel, sample) for camera samples and
//! (seed, pass, photon) for photons — so an image does not depend on how work is split over
//! threads. Warps map uniform numbers in [0,1)² to directions with a known density (solid
//! angle, 1/sr); each is checked by a χ² test against its pdf.

use glam::DVec3;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_pcg::Pcg64Mcg;
use std::f64::consts::{PI, TAU};

/// Which part of a render a stream belongs to (keeps camera and photon streams apart).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Purpose {
    /// Camera samples.
    Camera = 1,
    /// Caustic photons.
    CausticPhotons = 2,
    /// Global photons.
    GlobalPhotons = 3,
    /// Photons measured by receivers.
    ReceiverPhotons = 4,
    /// A pixel's [`Strata`] in a pass.
    PixelStrata = 5,
    /// Samples that weigh photon sources before a pass (the same in every pass).
    Pilot = 6,
}

/// A 64-bit hash of `z` (splitmix64: an increment, then its finaliser), for keying streams.
pub fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The random stream for (seed, purpose, a, b): splitmix-hashed into a PCG state.
pub fn stream(seed: u64, purpose: Purpose, a: u64, b: u64) -> Pcg64Mcg {
    let h = mix(seed ^ mix(purpose as u64 ^ mix(a ^ mix(b))));
    let l = mix(h ^ 0x5851_f42d_4c95_7f2d);
    Pcg64Mcg::new(((h as u128) << 64) | l as u128)
}

/// One dimension of a pixel's n samples, stratified: one number in each of the n equal
/// intervals of [0, 1) (uniform within it), handed to the samples in a random order — so
/// each sample's number is uniform, the pixel's numbers are spread evenly, and the order is
/// independent of the pixel's other stratified dimensions (its image-plane cells). Only a
/// pixel's first [`Strata::MOST`] samples are stratified (over that many intervals), so its
/// memory stays bounded for any `spp`; later samples draw their own numbers.
#[derive(Default)]
pub struct Strata {
    numbers: Vec<f64>,
}

impl Strata {
    /// The most samples a pixel's strata hold (0.5 MB a dimension).
    pub const MOST: u32 = 1 << 16;

    /// Draws the numbers of `n` samples from `rng` (reusing its storage).
    pub fn draw(&mut self, n: u32, rng: &mut impl Rng) {
        let n = n.min(Self::MOST);
        self.numbers.clear();
        self.numbers
            .extend((0..n).map(|i| in_stratum(i, n, rng.gen())));
        self.numbers.shuffle(rng);
    }

    /// Sample `s`'s number; None beyond the first [`Strata::MOST`].
    pub fn get(&self, s: u32) -> Option<f64> {
        self.numbers.get(s as usize).copied()
    }
}

/// The point at `u` ∈ [0, 1) of stratum `i` of `n` over [0, 1): (i + u)/n, kept below 1 (for
/// u near 1 the sum rounds up to i + 1, and the last stratum's point would be 1 itself).
pub fn in_stratum(i: u32, n: u32, u: f64) -> f64 {
    ((i as f64 + u) / n as f64).min(1.0 - f64::EPSILON / 2.0)
}

/// Two dimensions of a pixel's n samples, stratified together (jittered): one point in each
/// cell of an m × m grid over [0, 1)², m = ⌊√n⌋, uniform within it, handed to the samples in
/// a random order independent of the pixel's other dimensions (pbrt's stratified sampler,
/// its dimensions padded by shuffling). Samples past the first m² (at most [`Strata::MOST`])
/// draw their own numbers.
#[derive(Default)]
pub struct Strata2 {
    points: Vec<[f64; 2]>,
}

impl Strata2 {
    /// Draws the points of `n` samples from `rng` (reusing its storage).
    pub fn draw(&mut self, n: u32, rng: &mut impl Rng) {
        let m = n.min(Strata::MOST).isqrt();
        self.points.clear();
        self.points.extend((0..m * m).map(|s| {
            let (i, j) = (s % m, s / m);
            [in_stratum(i, m, rng.gen()), in_stratum(j, m, rng.gen())]
        }));
        self.points.shuffle(rng);
    }

    /// Sample `s`'s point (None past the stratified ones).
    pub fn get(&self, s: u32) -> Given<2> {
        Given(self.points.get(s as usize).copied())
    }
}

/// Uniform numbers in [0, 1) a draw takes in place of its stream's, where given (a camera
/// sample's stratified numbers for its first vertex: [`Strata`], [`Strata2`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Given<const N: usize>(pub Option<[f64; N]>);

impl<const N: usize> Given<N> {
    /// The given numbers, or N drawn from `rng` in order.
    pub fn or_draw(self, rng: &mut impl Rng) -> [f64; N] {
        self.0
            .unwrap_or_else(|| std::array::from_fn(|_| rng.gen::<f64>()))
    }
}

/// An orthonormal frame (t, b, n) around a unit vector n.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    t: DVec3,
    b: DVec3,
    n: DVec3,
}

impl Frame {
    /// The frame of unit `n`.
    pub fn new(n: DVec3) -> Self {
        let t = n.any_orthonormal_vector();
        Self {
            t,
            b: n.cross(t),
            n,
        }
    }

    /// The world vector of local coordinates (x, y, z) (z along n).
    pub fn to_world(&self, v: DVec3) -> DVec3 {
        v.x * self.t + v.y * self.b + v.z * self.n
    }

    /// The local coordinates (x, y, z) (z along n) of world vector `v`.
    pub fn to_local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }
}

/// A unit vector at polar cosine `cos` about +z and azimuth 2π·`u`.
fn polar(cos: f64, u: f64) -> DVec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = TAU * u;
    DVec3::new(sin * phi.cos(), sin * phi.sin(), cos)
}

/// Cosine-weighted hemisphere about +z: pdf cos θ / π.
pub fn cosine_hemisphere(uv: (f64, f64)) -> DVec3 {
    polar((1.0 - uv.0).sqrt(), uv.1)
}

/// The "power cosine" lobe about +z: pdf (m + 1) cos^m θ / 2π on the hemisphere (m ≥ 0);
/// m = 1 is [`cosine_hemisphere`]'s density, m = 0 the uniform hemisphere.
pub fn power_cosine_hemisphere(m: f64, uv: (f64, f64)) -> DVec3 {
    polar((1.0 - uv.0).powf(1.0 / (m + 1.0)), uv.1)
}

/// Uniform over the sphere: pdf 1/4π.
pub fn uniform_sphere(uv: (f64, f64)) -> DVec3 {
    polar(1.0 - 2.0 * uv.0, uv.1)
}

/// Uniform inside the cone of half-angle acos(`cos_max`) about +z: pdf 1/(2π(1 − cos_max)).
pub fn uniform_cone(cos_max: f64, uv: (f64, f64)) -> DVec3 {
    polar(1.0 - uv.0 * (1.0 - cos_max), uv.1)
}

/// Uniform on the unit disk in the xy plane (polar map): density 1/π.
pub fn uniform_disk(uv: (f64, f64)) -> (f64, f64) {
    let r = uv.0.sqrt();
    let phi = TAU * uv.1;
    (r * phi.cos(), r * phi.sin())
}

/// Pdf of [`power_cosine_hemisphere`] at a direction with polar cosine `cos` (1/sr).
pub fn power_cosine_pdf(m: f64, cos: f64) -> f64 {
    if cos <= 0.0 {
        0.0
    } else {
        (m + 1.0) * cos.powf(m) / TAU
    }
}

/// Pdf of [`uniform_sphere`] (1/sr).
pub const UNIFORM_SPHERE_PDF: f64 = 0.25 / PI;

/// A discrete distribution over indices 0..n, each drawn with probability proportional to its
/// weight (≥ 0; a weight of 0 is never drawn): its cumulative sums, the last one 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Discrete {
    cdf: Vec<f64>,
}

/// An index drawn from a [`Discrete`] and the probability it had.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    /// The index.
    pub index: usize,
    /// Its probability, > 0.
    pub probability: f64,
}

impl Discrete {
    /// The distribution of `weights` (each finite and ≥ 0); None when they sum to 0.
    pub fn new(weights: &[f64]) -> Option<Self> {
        let total: f64 = weights.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let mut acc = 0.0;
        let mut cdf: Vec<f64> = weights
            .iter()
            .map(|w| {
                acc += w / total;
                acc
            })
            .collect();
        // The last index that can be drawn ends at exactly 1, and so does every one after it.
        let last = weights.iter().rposition(|&w| w > 0.0)?;
        cdf[last..].fill(1.0);
        Some(Self { cdf })
    }

    /// The index a uniform `u` in [0, 1) draws.
    pub fn pick(&self, u: f64) -> Pick {
        let index = self
            .cdf
            .partition_point(|c| *c <= u)
            .min(self.cdf.len() - 1);
        Pick {
            index,
            probability: self.probability(index),
        }
    }

    /// The probability of index `i`.
    pub fn probability(&self, i: usize) -> f64 {
        self.cdf[i] - if i == 0 { 0.0 } else { self.cdf[i - 1] }
    }

    /// Where `u`, which drew `pick`, lies within that index's share of [0, 1), rescaled to
    /// [0, 1): uniform again, so one number both picks an index and places a point.
    pub fn within(&self, u: f64, pick: Pick) -> f64 {
        let start = self.cdf[pick.index] - pick.probability;
        ((u - start) / pick.probability).clamp(0.0, 1.0 - f64::EPSILON / 2.0)
    }
}
