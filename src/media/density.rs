//! A heterogeneous medium's density: a dimensionless field d(x) ≥ 0 on a lattice that scales
//! its absorption and scattering coefficients, σa(x) = σa·d(x) and σs(x) = σs·d(x), as smoke
//! or haze thins out. Light crossing a path keeps exp(−σ ∫d ds): the path's *column*
//! ∫d ds (scene units) stands where a homogeneous medium's arclength stood.

use super::lattice::{GridError, Lattice};
use glam::DVec3;

/// d(x): trilinear between the nodes of a [`Lattice`] (clamped outside its box), with its
/// largest value, which bounds it everywhere (a trilinear interpolant lies between its
/// nodes) and so is the majorant of free-flight tracking.
#[derive(Clone, Debug)]
pub struct Density {
    lattice: Lattice,
    max: f64,
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
        Ok(Self { lattice, max })
    }

    /// d at `p`.
    pub fn at(&self, p: DVec3) -> f64 {
        self.lattice.trilinear(p)
    }

    /// The largest d anywhere.
    pub fn max(&self) -> f64 {
        self.max
    }

    /// The column ∫d ds along the straight segment from `from` along unit `dir` over `length`,
    /// exact for the trilinear field ([`Lattice::integral`]).
    pub fn column(&self, from: DVec3, dir: DVec3, length: f64) -> f64 {
        self.lattice.integral(from, dir, length)
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
            assert!(density.at(a) <= density.max() && density.at(b) <= density.max());
        }
    }
}
