//! The stream a camera sample draws its random numbers from: independent numbers, or
//! Owen-scrambled Sobol points (Burley 2020, "Practical Hash-based Owen Scrambling", through
//! the `sobol_burley` crate) read as a random stream: each number a camera sample draws is the
//! next dimension of its point, so the samples of a pixel fill every dimension they draw in
//! the same order evenly (the first vertex's light and BSDF numbers, the film and the lens),
//! where independent numbers would clump.
//!
//! Dimensions are padded in sets of four (Burley's recommendation): set k is dimensions 0–3
//! of a Sobol sequence scrambled and shuffled by its own seed, so every four consecutive
//! draws are stratified together and sets are independent of one another. A sequence holds
//! 2¹⁶ points; the samples of a pixel past that start an independent one. Each number is
//! exact to 2⁻²³ (the crate's resolution) and uniform below that: its low bits come from an
//! independent stream, so numbers are continuous in [0, 1) as a renderer's warps expect.

use crate::sampling::mix;
use rand::RngCore;
use rand_pcg::Pcg64Mcg;

/// A camera sample's random stream (`[render] sampler`).
#[derive(Clone, Debug)]
pub enum SampleStream {
    /// Independent numbers (a PCG stream keyed by the sample).
    Independent(Pcg64Mcg),
    /// The sample's Owen-scrambled Sobol point.
    Sobol(SobolStream),
}

impl RngCore for SampleStream {
    fn next_u32(&mut self) -> u32 {
        match self {
            Self::Independent(r) => r.next_u32(),
            Self::Sobol(r) => r.next_u32(),
        }
    }

    fn next_u64(&mut self) -> u64 {
        match self {
            Self::Independent(r) => r.next_u64(),
            Self::Sobol(r) => r.next_u64(),
        }
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        match self {
            Self::Independent(r) => r.fill_bytes(dest),
            Self::Sobol(r) => r.fill_bytes(dest),
        }
    }

    fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), rand::Error> {
        self.fill_bytes(dest);
        Ok(())
    }
}

/// The points of one sequence (the crate's limit).
const SEQUENCE_LENGTH: u64 = 1 << 16;

/// Dimensions a sample draws from its Sobol point; the numbers after them are independent.
/// Stratification pays in a path's first dimensions (the film, the first vertices); far down
/// a long path (a fog's hundreds of events) it no longer shows, and a Sobol number costs more
/// than an independent one (a set of four, 19 ns here).
pub const SOBOL_DIMENSIONS: u32 = 64;

/// Bits of a number that come from its Sobol point.
const POINT_BITS: u32 = 23;

/// One sample's point, read a dimension at a time.
#[derive(Clone, Debug)]
pub struct SobolStream {
    /// The sample's index in its sequence (< 2¹⁶).
    index: u32,
    /// The sequence's seed (the pixel's and the block of 2¹⁶ samples it is in).
    seed: u64,
    /// The next dimension drawn.
    dimension: u32,
    /// The current set of four dimensions, as 23-bit integers.
    set: [u32; 4],
    /// The bits below a point's resolution.
    low: Pcg64Mcg,
}

impl SobolStream {
    /// Sample `sample` (counted over every pass of the pixel) of the pixel whose sequences
    /// `pixel_seed` keys; `low` fills the bits below the points' resolution.
    pub fn new(pixel_seed: u64, sample: u64, low: Pcg64Mcg) -> Self {
        Self {
            index: (sample % SEQUENCE_LENGTH) as u32,
            seed: mix(pixel_seed ^ mix(sample / SEQUENCE_LENGTH)),
            dimension: 0,
            set: [0; 4],
            low,
        }
    }

    /// The next dimension's value as a 23-bit integer (the point's coordinate times 2²³).
    fn next_point(&mut self) -> u32 {
        let within = (self.dimension % 4) as usize;
        if within == 0 {
            let set_seed = mix(self.seed ^ u64::from(self.dimension / 4)) as u32;
            self.set = first_dimensions(self.index, set_seed);
        }
        self.dimension = self.dimension.wrapping_add(1);
        self.set[within]
    }
}

/// Dimensions 0–3 of point `index` of the Sobol sequence scrambled and shuffled by `seed`, as
/// 23-bit integers: exactly `sobol_burley::sample_4d(index, 0, seed)` times 2²³ (tested),
/// computed from the crate's parts with the Sobol matrices' product read from a table
/// ([`SOBOL_PIECES`]) instead of a loop over the index's bits (19.2 ns a set against 44.7).
fn first_dimensions(index: u32, seed: u32) -> [u32; 4] {
    use sobol_burley::parts::{hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, Int4};
    // sample_4d's steps and constants for dimension set 0: the index shuffled by the seed ...
    let shuffled = owen_scramble_rev(index.reverse_bits(), hash(seed ^ 0x79c68e4a));
    // ... its Sobol point (bit-reversed) ...
    let pieces = SOBOL_PIECES.get_or_init(sobol_pieces);
    let mut sobol = [0u32; 4];
    for (piece, table) in pieces.iter().enumerate() {
        let row = table[((shuffled >> (16 + 4 * piece)) & 0xf) as usize];
        for (s, r) in sobol.iter_mut().zip(row) {
            *s ^= r;
        }
    }
    // ... Owen-scrambled per dimension ...
    let lanes = seed.wrapping_mul(0x9c8f2d3b);
    let scramble: Int4 = [0x912f69ba, 0x174f18ab, 0x691e72ca, 0xb40cc1b8]
        .map(|c| lanes ^ c)
        .into();
    let owen = owen_scramble_int4_rev(sobol.into(), hash_int4(scramble));
    // ... and its top 23 bits, as the crate's float holds them.
    let reversed: [u32; 4] = owen.reverse_bits().into();
    reversed.map(|x| x >> (32 - POINT_BITS))
}

/// The Sobol matrices' products by 4-bit pieces of an index, for dimensions 0–3: the
/// bit-reversed point of a reversed index is linear over GF(2) in its bits, so it is the
/// exclusive or of the points of its four 4-bit pieces (the crate reads the index's top 16
/// bits), each looked up by piece and value (1 KiB, made once from
/// `sobol_burley::parts::sobol_int4_rev`).
static SOBOL_PIECES: std::sync::OnceLock<[[[u32; 4]; 16]; 4]> = std::sync::OnceLock::new();

fn sobol_pieces() -> [[[u32; 4]; 16]; 4] {
    std::array::from_fn(|piece| {
        std::array::from_fn(|value| {
            let reversed_index = (value as u32) << (16 + 4 * piece);
            sobol_burley::parts::sobol_int4_rev(reversed_index, 0).into()
        })
    })
}

/// Each call is one dimension: its point's 23 bits on top, independent bits below; past
/// [`SOBOL_DIMENSIONS`], an independent number.
impl RngCore for SobolStream {
    fn next_u32(&mut self) -> u32 {
        if self.dimension >= SOBOL_DIMENSIONS {
            return self.low.next_u32();
        }
        (self.next_point() << (32 - POINT_BITS)) | (self.low.next_u32() >> POINT_BITS)
    }

    fn next_u64(&mut self) -> u64 {
        if self.dimension >= SOBOL_DIMENSIONS {
            return self.low.next_u64();
        }
        (u64::from(self.next_point()) << (64 - POINT_BITS)) | (self.low.next_u64() >> POINT_BITS)
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        for chunk in dest.chunks_mut(8) {
            let bytes = self.next_u64().to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
    }

    fn try_fill_bytes(&mut self, dest: &mut [u8]) -> Result<(), rand::Error> {
        self.fill_bytes(dest);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;
    use rand_pcg::Pcg64Mcg;

    /// Dimension `d` (0-based) of samples `0..n` of the pixel keyed by `pixel_seed`.
    fn column(pixel_seed: u64, n: u64, d: usize) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let mut s = SobolStream::new(pixel_seed, i, Pcg64Mcg::new(i as u128 | 1));
                (0..d).for_each(|_| {
                    s.gen::<f64>();
                });
                s.gen::<f64>()
            })
            .collect()
    }

    /// The cells of a grid of `cols` × `rows` over [0, 1)² holding no point of `points`.
    fn empty_cells(xs: &[f64], ys: &[f64], cols: usize, rows: usize) -> usize {
        let mut count = vec![0; cols * rows];
        for (&x, &y) in xs.iter().zip(ys) {
            assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
            count[(y * rows as f64) as usize * cols + (x * cols as f64) as usize] += 1;
        }
        count.iter().filter(|&&c| c == 0).count()
    }

    /// The first 2^m points of a scrambled Sobol sequence are stratified in every
    /// dimension (each of 256 intervals holds one of 256 points), and dimensions 0 and 1 of a
    /// set are a (0, m, 2)-net: every elementary interval of area 2^−m (here 256 × 1, 16 × 16,
    /// 64 × 4, 1 × 256 cells) holds exactly one point. The set's other pairs are nets of a
    /// larger t (Sobol's pairs beyond the first two), checked as t ≤ 2 nets are: none of the
    /// 8 × 8 cells of area 2^−(m−2) is empty. Independent points leave e^−1 ≈ 37 % of 256
    /// cells empty, and one of 64 cells of 4 on average empty in about 1 of 900 images.
    #[test]
    fn a_pixels_first_points_fill_the_elementary_intervals_of_a_set() {
        for (a, b) in [(0, 1), (4, 5)] {
            let (xs, ys) = (column(7, 256, a), column(7, 256, b));
            for (cols, rows) in [(256, 1), (16, 16), (64, 4), (1, 256)] {
                assert_eq!(
                    empty_cells(&xs, &ys, cols, rows),
                    0,
                    "dims {a}, {b}: {cols}×{rows}"
                );
            }
        }
        for (a, b) in [(2, 3), (1, 2), (4, 7), (5, 6)] {
            let (xs, ys) = (column(7, 256, a), column(7, 256, b));
            for (cols, rows) in [(256, 1), (8, 8), (1, 256)] {
                assert_eq!(
                    empty_cells(&xs, &ys, cols, rows),
                    0,
                    "dims {a}, {b}: {cols}×{rows}"
                );
            }
        }
    }

    /// The table and the crate's parts give exactly the crate's own `sample_4d` (times 2²³),
    /// at every index of the sequence, each under other seeds.
    #[test]
    fn a_set_is_the_crates_sample_4d_exactly() {
        let mut rng = Pcg64Mcg::new(11);
        for index in 0..1u32 << 16 {
            for seed in [rng.gen::<u32>(), rng.gen(), index, !index] {
                let crate_point = sobol_burley::sample_4d(index, 0, seed)
                    .map(|u| (u * (1u32 << POINT_BITS) as f32) as u32);
                assert_eq!(first_dimensions(index, seed), crate_point, "{index} {seed}");
            }
        }
    }

    /// Sets of four are independent of one another: dimensions 1 and 4 are not a net (their
    /// 16 × 16 grid has empty cells, as independent points' would: about 37 %).
    #[test]
    fn sets_are_decorrelated_from_one_another() {
        let empty = empty_cells(&column(7, 256, 1), &column(7, 256, 4), 16, 16);
        assert!((40..140).contains(&empty), "{empty} of 256 cells empty");
    }

    /// Every number is uniform on [0, 1): over many pixels the mean of each dimension is ½
    /// within 4 standard errors (1/√(12 n)), and no number reaches 1.
    #[test]
    fn numbers_are_uniform_over_pixels() {
        let n = 20_000u64;
        for d in [0, 3, 9, 40] {
            let sum: f64 = (0..n).map(|p| column(mix(p), 1, d)[0]).sum();
            let mean = sum / n as f64;
            let se = (1.0 / (12.0 * n as f64)).sqrt();
            assert!((mean - 0.5).abs() < 4.0 * se, "dimension {d}: mean {mean}");
        }
    }

    /// Past 2¹⁶ samples a pixel goes on with an independent sequence, still uniform and in
    /// [0, 1).
    #[test]
    fn samples_past_a_sequence_go_on() {
        let a = column(3, 1, 0)[0];
        let far = SobolStream::new(3, SEQUENCE_LENGTH, Pcg64Mcg::new(1)).gen::<f64>();
        assert!((0.0..1.0).contains(&far));
        assert_ne!(a, far);
    }
}
