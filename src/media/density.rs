//! A heterogeneous medium's density: a dimensionless field d(x) ≥ 0 on a lattice that scales
//! its absorption and scattering coefficients, σa(x) = σa·d(x) and σs(x) = σs·d(x), as smoke
//! or haze thins out. Light crossing a path keeps exp(−σ ∫d ds): the path's *column*
//! ∫d ds (scene units) stands where a homogeneous medium's arclength stood.

use super::lattice::{GridError, Lattice};
use crate::math::Bounds3;
use glam::DVec3;

/// d(x): trilinear between the nodes of a [`Lattice`] (clamped outside its box), 0 outside
/// the box it may end at ([`Density::ending_at`]), with its largest value, which bounds it
/// everywhere (a trilinear interpolant lies between its nodes), and the largest over blocks
/// of cells, which bound it near a point: the majorants of free-flight tracking
/// ([`Density::bound_near`]).
#[derive(Clone, Debug)]
pub struct Density {
    lattice: Lattice,
    max: f64,
    blocks: Blocks,
    /// The box outside which d is 0 (None: d goes on clamped everywhere).
    end: Option<Bounds3>,
}

/// Cells per axis of a block of [`Blocks`].
const BLOCK: usize = 8;

/// The largest node value over each block of BLOCK³ cells (the nodes on its faces included),
/// which bounds the trilinear interpolant in the block.
#[derive(Clone, Debug)]
struct Blocks {
    /// Blocks per axis.
    counts: [usize; 3],
    /// Each block's largest value, x fastest.
    max: Vec<f64>,
}

impl Blocks {
    fn new(lattice: &Lattice) -> Self {
        let dims = lattice.dims();
        // d − 1 cells per axis, in ⌈(d − 1)/BLOCK⌉ blocks.
        let counts = dims.map(|d| (d - 2) / BLOCK + 1);
        let mut max = vec![0.0f64; counts.iter().product()];
        // Node i lies on the cells i − 1 and i, so in their blocks.
        let blocks_of = |i: usize, a: usize| {
            let last = dims[a] - 2;
            [i.saturating_sub(1).min(last) / BLOCK, i.min(last) / BLOCK]
        };
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let v = lattice.node(i, j, k);
                    for bz in blocks_of(k, 2) {
                        for by in blocks_of(j, 1) {
                            for bx in blocks_of(i, 0) {
                                let m = &mut max[bx + counts[0] * (by + counts[1] * bz)];
                                *m = m.max(v);
                            }
                        }
                    }
                }
            }
        }
        Self { counts, max }
    }

    /// The largest value over the blocks `lo..=hi` (block indices per axis).
    fn max_over(&self, lo: [usize; 3], hi: [usize; 3]) -> f64 {
        let mut m = 0.0f64;
        for bz in lo[2]..=hi[2] {
            for by in lo[1]..=hi[1] {
                for bx in lo[0]..=hi[0] {
                    m = m.max(self.max[bx + self.counts[0] * (by + self.counts[1] * bz)]);
                }
            }
        }
        m
    }
}

/// A bound on the density along any path from a point, as far as it holds: the density is at
/// most `density` within arclength `reach` of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalMajorant {
    /// The bound (≥ every d(x) the path can reach).
    pub density: f64,
    /// The arclength it holds over (∞: everywhere).
    pub reach: f64,
}

impl Density {
    /// A density on the box `[min, max]` from `values` at `dims` nodes (x fastest); every value
    /// finite and ≥ 0.
    pub fn new(
        min: DVec3,
        max: DVec3,
        dims: [usize; 3],
        values: Vec<f64>,
    ) -> Result<Self, GridError> {
        let valid = |v: f64| v.is_finite() && v >= 0.0;
        let lattice = Lattice::new(
            min,
            max,
            dims,
            values,
            valid,
            "a density must be finite and ≥ 0",
        )?;
        let max = lattice.values().iter().copied().fold(0.0, f64::max);
        let blocks = Blocks::new(&lattice);
        Ok(Self {
            lattice,
            max,
            blocks,
            end: None,
        })
    }

    /// The same density, 0 outside the box `end` (Mitsuba's heterogeneous medium ends at its
    /// grid's box, while the grid's values are read clamped within it).
    pub fn ending_at(self, end: Bounds3) -> Self {
        Self {
            end: Some(end),
            ..self
        }
    }

    /// d at `p`.
    pub fn at(&self, p: DVec3) -> f64 {
        match self.end {
            Some(end) if !end.contains(p) => 0.0,
            Some(_) | None => self.lattice.trilinear(p),
        }
    }

    /// A bound on d along any path from `p`: a path of arclength h stays within the box
    /// p ± h, so the largest value over the blocks that box meets bounds d on it. h is a
    /// block's width along its shortest axis that has more than one block (a lattice of one
    /// block: the global maximum, everywhere), or — from a point outside the lattice — its
    /// distance to it plus that, so that paths leaving the lattice take few hops to the
    /// world's edge.
    pub fn bound_near(&self, p: DVec3) -> LocalMajorant {
        let cell = self.lattice.cell_size().to_array();
        let block = (0..3)
            .filter(|&a| self.blocks.counts[a] > 1)
            .map(|a| BLOCK as f64 * cell[a])
            .fold(f64::INFINITY, f64::min);
        if block.is_infinite() {
            return LocalMajorant {
                density: self.max,
                reach: f64::INFINITY,
            };
        }
        let Bounds3 { lo: min, hi: max } = self.lattice.bounds();
        let h = block + (p - p.clamp(min, max)).length();
        let corner = |q: DVec3| self.lattice.locate(q).cell.map(|c| c / BLOCK);
        LocalMajorant {
            density: self
                .blocks
                .max_over(corner(p - DVec3::splat(h)), corner(p + DVec3::splat(h))),
            reach: h,
        }
    }

    /// The column ∫d ds along the straight segment from `from` along unit `dir` over `length`,
    /// exact for the trilinear field ([`Lattice::integral`]).
    pub fn column(&self, from: DVec3, dir: DVec3, length: f64) -> f64 {
        match self.end {
            None => self.lattice.integral(from, dir, length),
            Some(end) => end.clip(from, dir, length).map_or(0.0, |(t0, t1)| {
                self.lattice.integral(from + dir * t0, dir, t1 - t0)
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// A density on the unit cube that is the trilinear function 1 + x + 2y·z + x·y·z at its
    /// nodes, so that the interpolant is that very function everywhere in the box (it is
    /// linear in each coordinate), whose integral along a line is a closed form.
    fn trilinear_field(dims: [usize; 3]) -> (Density, impl Fn(DVec3) -> f64) {
        let f = |p: DVec3| 1.0 + p.x + 2.0 * p.y * p.z + p.x * p.y * p.z;
        let mut values = Vec::new();
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let node = DVec3::new(
                        i as f64 / (dims[0] - 1) as f64,
                        j as f64 / (dims[1] - 1) as f64,
                        k as f64 / (dims[2] - 1) as f64,
                    );
                    values.push(f(node));
                }
            }
        }
        (
            Density::new(DVec3::ZERO, DVec3::ONE, dims, values).unwrap(),
            f,
        )
    }

    #[test]
    fn a_column_through_a_multilinear_field_is_exact() {
        // f along p(t) = a + t u is a cubic in t, which 4-point Gauss–Legendre integrates
        // exactly.
        let (density, f) = trilinear_field([4, 5, 3]);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        for _ in 0..200 {
            let a = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let b = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let length = (b - a).length();
            let dir = (b - a) / length;
            const X: [f64; 2] = [0.339_981_043_584_856, 0.861_136_311_594_053];
            const W: [f64; 2] = [0.652_145_154_862_546, 0.347_854_845_137_454];
            let exact: f64 = X
                .iter()
                .zip(W)
                .map(|(x, w)| {
                    let h = 0.5 * length;
                    w * h * (f(a + dir * h * (1.0 - x)) + f(a + dir * h * (1.0 + x)))
                })
                .sum();
            let column = density.column(a, dir, length);
            assert!(
                (column - exact).abs() < 1e-12 * exact.max(1.0),
                "{column} vs {exact} from {a} along {dir} over {length}"
            );
        }
    }

    /// A density that ends at a box (the field's own box of [0, 1]³, ending at [0.2, 0.9] ×
    /// [−1, 2] × [0.1, 0.5]) is 0 outside it and its column is the field's over the part of
    /// the segment inside it: against 4-point Gauss–Legendre over that part, found apart
    /// (1e-12), for segments inside, across and outside the box, and one running along a face.
    #[test]
    fn a_density_ending_at_a_box_integrates_only_inside_it() {
        let (density, f) = trilinear_field([4, 5, 3]);
        let end = Bounds3::new(DVec3::new(0.2, -1.0, 0.1), DVec3::new(0.9, 2.0, 0.5));
        let density = density.ending_at(end);
        assert_eq!(density.at(DVec3::new(0.1, 0.5, 0.3)), 0.0);
        assert_eq!(
            density.at(DVec3::new(0.5, 0.5, 0.3)),
            f(DVec3::new(0.5, 0.5, 0.3))
        );
        let inside = |p: DVec3| (0..3).all(|a| p[a] >= end.lo[a] && p[a] <= end.hi[a]);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut crossed = 0;
        for _ in 0..400 {
            let a = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let b = DVec3::new(rng.gen(), rng.gen(), rng.gen());
            let length = (b - a).length();
            let dir = (b - a) / length;
            // The part inside, by bisection on each side of a point inside (the box is
            // convex), independent of Bounds3::clip.
            let steps = 4096;
            let Some(k) =
                (0..=steps).find(|&k| inside(a + dir * (length * k as f64 / steps as f64)))
            else {
                assert_eq!(density.column(a, dir, length), 0.0);
                continue;
            };
            let mid = length * k as f64 / steps as f64;
            let edge = |mut lo: f64, mut hi: f64| {
                // lo inside, hi the segment's end on that side.
                if inside(a + dir * hi) {
                    return hi;
                }
                for _ in 0..200 {
                    let m = 0.5 * (lo + hi);
                    match inside(a + dir * m) {
                        true => lo = m,
                        false => hi = m,
                    }
                }
                lo
            };
            let (t0, t1) = (edge(mid, 0.0), edge(mid, length));
            crossed += usize::from(t0 > 0.0 || t1 < length);
            const X: [f64; 2] = [0.339_981_043_584_856, 0.861_136_311_594_053];
            const W: [f64; 2] = [0.652_145_154_862_546, 0.347_854_845_137_454];
            let h = 0.5 * (t1 - t0);
            let c = a + dir * (t0 + h);
            let exact: f64 = X
                .iter()
                .zip(W)
                .map(|(x, w)| w * h * (f(c - dir * h * x) + f(c + dir * h * x)))
                .sum();
            let column = density.column(a, dir, length);
            assert!(
                (column - exact).abs() < 1e-12 * exact.max(1.0),
                "{column} vs {exact} from {a} along {dir} over {length}"
            );
        }
        assert!(crossed > 100, "{crossed} segments crossed a face");
        // Along the face x = 0.2, inside the box's other extents: the face counts as inside.
        let along = density.column(DVec3::new(0.2, 0.3, 0.2), DVec3::Z, 0.2);
        let want = (0..1000)
            .map(|i| f(DVec3::new(0.2, 0.3, 0.2 + 0.2 * (i as f64 + 0.5) / 1000.0)) * 0.2e-3)
            .sum::<f64>();
        assert!((along - want).abs() < 1e-9, "{along} vs {want}");
    }

    /// The local bound holds: every point within the bound's reach of `p` (in the box p ± h,
    /// which holds every path of that arclength), inside the lattice and beyond it, has d at
    /// most the bound; and the bound is tighter than the global maximum where the field is
    /// low (a dense blob in a thin field).
    #[test]
    fn a_local_majorant_bounds_the_density_within_its_reach() {
        let dims = [40, 33, 25];
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let centre = DVec3::new(1.0, 0.5, 0.5);
        let mut values = Vec::new();
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let q = DVec3::new(2.0 * i as f64 / 39.0, j as f64 / 32.0, k as f64 / 24.0);
                    let blob = if (q - centre).length() < 0.2 {
                        20.0
                    } else {
                        0.0
                    };
                    values.push(blob + 0.1 * rng.gen::<f64>());
                }
            }
        }
        let density = Density::new(DVec3::ZERO, DVec3::new(2.0, 1.0, 1.0), dims, values).unwrap();
        let mut looser = 0;
        for _ in 0..2000 {
            let p = DVec3::new(
                rng.gen_range(-1.0..3.0),
                rng.gen_range(-1.0..2.0),
                rng.gen_range(-0.5..1.5),
            );
            let bound = density.bound_near(p);
            assert!(bound.reach.is_finite() && bound.reach > 0.0);
            for _ in 0..50 {
                let q = p + bound.reach
                    * DVec3::new(
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-1.0..1.0),
                        rng.gen_range(-1.0..1.0),
                    );
                assert!(density.at(q) <= bound.density, "{q} from {p}: {bound:?}");
            }
            looser += usize::from(bound.density < 1.0);
        }
        assert!(
            looser > 1000,
            "the bound is below 1 at {looser} of 2000 points"
        );
    }

    #[test]
    fn a_column_adds_up_over_a_rough_field_and_beyond_the_box() {
        // Random node values (the interpolant kinks at every node plane) and segments that
        // start and end outside the box: two pieces add up to the whole, and the whole agrees
        // with a fine midpoint sum (error O(h²) per kink: 1e-6 at 2·10⁵ points).
        let dims = [6, 4, 5];
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let values = (0..dims.iter().product::<usize>())
            .map(|_| rng.gen::<f64>())
            .collect();
        let density = Density::new(DVec3::ZERO, DVec3::new(2.0, 1.0, 1.5), dims, values).unwrap();
        for _ in 0..50 {
            let a = DVec3::new(
                rng.gen_range(-1.0..3.0),
                rng.gen_range(-1.0..2.0),
                rng.gen(),
            );
            let b = DVec3::new(
                rng.gen_range(-1.0..3.0),
                rng.gen(),
                rng.gen_range(-1.0..2.5),
            );
            let length = (b - a).length();
            let dir = (b - a) / length;
            let whole = density.column(a, dir, length);
            let cut = rng.gen::<f64>() * length;
            let parts =
                density.column(a, dir, cut) + density.column(a + dir * cut, dir, length - cut);
            assert!((whole - parts).abs() < 1e-12, "{whole} vs {parts}");
            let n = 200_000;
            let h = length / n as f64;
            let midpoint: f64 = (0..n)
                .map(|i| density.at(a + dir * (h * (i as f64 + 0.5))) * h)
                .sum();
            assert!((whole - midpoint).abs() < 1e-6, "{whole} vs {midpoint}");
            assert!(density.at(a) <= density.bound_near(a).density);
            assert!(density.at(b) <= density.bound_near(b).density);
        }
    }
}
