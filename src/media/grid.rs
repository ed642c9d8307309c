//! A tabulated index on a regular grid over a box (a "3D texture"): trilinear, or tricubic
//! (Catmull–Rom) so that ∇n is continuous across cells.

use super::{IndexSample, Medium};
use glam::DVec3;

/// n on the box `[min, max]` sampled at `dims` nodes per axis (node (i,j,k) at
/// min + (i,j,k)·(max − min)/(dims − 1)); `values` is x-fastest, interpolated by
/// [`Interpolation`]. The gradient is the exact gradient of the interpolant. Outside the box,
/// positions are clamped to it: n continues constant along the clamped axes.
#[derive(Clone, Debug)]
pub struct GridMedium {
    min: DVec3,
    max: DVec3,
    dims: [usize; 3],
    values: Vec<f64>,
    /// Node spacing along each axis.
    cell: DVec3,
    interpolation: Interpolation,
}

/// How a grid is read between its nodes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    /// Trilinear: n is continuous, ∇n jumps at every cell face (a ray kinks there, and the
    /// curved engine's error control sees the kink as error). Second order.
    #[default]
    Linear,
    /// Tricubic Catmull–Rom (the cubic convolution of Keys 1981 with a = −½, as a tensor
    /// product): interpolating, C¹, so ∇n is continuous across cells; third order, the
    /// boundary cells too (ghost nodes extrapolated quadratically).
    Cubic,
}

/// Catmull–Rom weights of the four nodes around a point at fraction `t` ∈ [0, 1] of its cell
/// (nodes at −1, 0, 1, 2), and their derivatives in t.
fn catmull_rom(t: f64) -> ([f64; 4], [f64; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    (
        [
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ],
        [
            0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
            0.5 * (9.0 * t2 - 10.0 * t),
            0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
            0.5 * (3.0 * t2 - 2.0 * t),
        ],
    )
}

/// Why a grid cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum GridError {
    /// Each axis needs at least two nodes.
    #[error("dims must be at least 2 along every axis, got {0:?}")]
    TooFewNodes([usize; 3]),
    /// The node count nx·ny·nz does not fit in memory's address space.
    #[error("dims {0:?} hold more nodes than can be addressed")]
    TooManyNodes([usize; 3]),
    /// The value count does not match the node count.
    #[error("expected {expected} values (dims product), got {got}")]
    WrongCount {
        /// nx·ny·nz
        expected: usize,
        /// values given
        got: usize,
    },
    /// A value is not a finite positive index.
    #[error("value #{index} is {value}: every index must be finite and > 0")]
    BadValue {
        /// Position in the list.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The box has no volume.
    #[error("bounds must satisfy min < max on every axis")]
    EmptyBox,
}

impl GridMedium {
    /// Builds and validates a grid.
    pub fn new(
        min: DVec3,
        max: DVec3,
        dims: [usize; 3],
        values: Vec<f64>,
        interpolation: Interpolation,
    ) -> Result<Self, GridError> {
        if dims.iter().any(|&d| d < 2) {
            return Err(GridError::TooFewNodes(dims));
        }
        if !(min.cmplt(max).all()) {
            return Err(GridError::EmptyBox);
        }
        let expected = dims[0]
            .checked_mul(dims[1])
            .and_then(|n| n.checked_mul(dims[2]))
            .ok_or(GridError::TooManyNodes(dims))?;
        if values.len() != expected {
            return Err(GridError::WrongCount {
                expected,
                got: values.len(),
            });
        }
        if let Some((index, &value)) = values
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v > 0.0))
        {
            return Err(GridError::BadValue { index, value });
        }
        let cell = (max - min)
            / DVec3::new(
                dims[0] as f64 - 1.0,
                dims[1] as f64 - 1.0,
                dims[2] as f64 - 1.0,
            );
        Ok(Self {
            min,
            max,
            dims,
            values,
            cell,
            interpolation,
        })
    }

    fn node(&self, i: usize, j: usize, k: usize) -> f64 {
        self.values[i + self.dims[0] * (j + self.dims[1] * k)]
    }

    /// n and ∂n/∂(cell fractions) by the tricubic Catmull–Rom interpolant of the cell `cell`
    /// at fractions `frac`. Ghost nodes beyond the box are extrapolated quadratically along
    /// their axis (linearly on a two-node axis), which keeps the boundary cells third order
    /// (repeating the face's value would make ∂n/∂x wrong there by O(h)).
    fn cubic(&self, cell: [usize; 3], frac: [f64; 3]) -> (f64, DVec3) {
        let clamp = |a: usize, o: usize| (cell[a] + o).saturating_sub(1).min(self.dims[a] - 1);
        let mut block = [[[0.0f64; 4]; 4]; 4];
        for (oz, plane) in block.iter_mut().enumerate() {
            for (oy, row) in plane.iter_mut().enumerate() {
                for (ox, v) in row.iter_mut().enumerate() {
                    *v = self.node(clamp(0, ox), clamp(1, oy), clamp(2, oz));
                }
            }
        }
        // Replace ghosts axis by axis: the node before the first (o = 0 when cell = 0) and
        // after the last (o = 3 when cell = dims − 2).
        for (a, &c) in cell.iter().enumerate() {
            let low = c == 0;
            let high = c + 2 >= self.dims[a];
            if !(low || high) {
                continue;
            }
            let two_nodes = self.dims[a] == 2;
            for u in 0..4 {
                for v in 0..4 {
                    let at = |o: usize| match a {
                        0 => (v, u, o),
                        1 => (v, o, u),
                        _ => (o, v, u),
                    };
                    let get = |b: &[[[f64; 4]; 4]; 4], o: usize| {
                        let (z, y, x) = at(o);
                        b[z][y][x]
                    };
                    let line = [
                        get(&block, 0),
                        get(&block, 1),
                        get(&block, 2),
                        get(&block, 3),
                    ];
                    let mut set = |o: usize, value: f64| {
                        let (z, y, x) = at(o);
                        block[z][y][x] = value;
                    };
                    // The ghost beyond `inner`, from `inner`, `next` and `far` inward.
                    let ghost = |inner: f64, next: f64, far: f64| {
                        if two_nodes {
                            2.0 * inner - next
                        } else {
                            3.0 * inner - 3.0 * next + far
                        }
                    };
                    if low {
                        set(0, ghost(line[1], line[2], line[3]));
                    }
                    if high {
                        set(3, ghost(line[2], line[1], line[0]));
                    }
                }
            }
        }
        let w = [
            catmull_rom(frac[0]),
            catmull_rom(frac[1]),
            catmull_rom(frac[2]),
        ];
        let (mut n, mut d) = (0.0, DVec3::ZERO);
        for (oz, plane) in block.iter().enumerate() {
            for (oy, row) in plane.iter().enumerate() {
                for (ox, &value) in row.iter().enumerate() {
                    let (wx, wy, wz) = (w[0].0[ox], w[1].0[oy], w[2].0[oz]);
                    n += wx * wy * wz * value;
                    d += value
                        * DVec3::new(
                            w[0].1[ox] * wy * wz,
                            wx * w[1].1[oy] * wz,
                            wx * wy * w[2].1[oz],
                        );
                }
            }
        }
        (n, d)
    }

    /// n and ∂n/∂(cell fractions) by the trilinear interpolant.
    fn linear(&self, cell: [usize; 3], frac: [f64; 3]) -> (f64, DVec3) {
        let [i, j, k] = cell;
        let [fx, fy, fz] = frac;
        let c = |di, dj, dk| self.node(i + di, j + dj, k + dk);
        let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
        // Edges along x, then faces, then the value and its partial derivatives.
        let (c00, c10, c01, c11) = (
            lerp(c(0, 0, 0), c(1, 0, 0), fx),
            lerp(c(0, 1, 0), c(1, 1, 0), fx),
            lerp(c(0, 0, 1), c(1, 0, 1), fx),
            lerp(c(0, 1, 1), c(1, 1, 1), fx),
        );
        let (d00, d10, d01, d11) = (
            c(1, 0, 0) - c(0, 0, 0),
            c(1, 1, 0) - c(0, 1, 0),
            c(1, 0, 1) - c(0, 0, 1),
            c(1, 1, 1) - c(0, 1, 1),
        );
        let c0 = lerp(c00, c10, fy);
        let c1 = lerp(c01, c11, fy);
        let n = lerp(c0, c1, fz);
        let dndx = lerp(lerp(d00, d10, fy), lerp(d01, d11, fy), fz);
        let dndy = lerp(c10 - c00, c11 - c01, fz);
        let dndz = c1 - c0;
        (n, DVec3::new(dndx, dndy, dndz))
    }
}

impl Medium for GridMedium {
    /// Transparent.
    fn absorbs(&self) -> bool {
        false
    }
    fn sample(&self, p: DVec3) -> Option<IndexSample> {
        let scale = DVec3::new(
            (self.dims[0] - 1) as f64,
            (self.dims[1] - 1) as f64,
            (self.dims[2] - 1) as f64,
        ) / (self.max - self.min);
        let u = ((p.clamp(self.min, self.max) - self.min) * scale).to_array();
        let mut cell = [0usize; 3];
        let mut frac = [0.0f64; 3];
        for a in 0..3 {
            cell[a] = (u[a].floor() as usize).min(self.dims[a] - 2);
            frac[a] = u[a] - cell[a] as f64;
        }
        let inside = p.cmpge(self.min) & p.cmple(self.max);
        let (n, d) = match self.interpolation {
            Interpolation::Linear => self.linear(cell, frac),
            Interpolation::Cubic => self.cubic(cell, frac),
        };
        // Clamped axes: n is constant there.
        let grad = DVec3::select(inside, d * scale, DVec3::ZERO);
        // A cubic interpolant may overshoot between nodes; n stays the data's sign.
        (n > 0.0).then_some(IndexSample { n, grad })
    }
    /// The length along `dir` that crosses one cell along some axis: features of the data
    /// are a cell wide (and the trilinear gradient jumps at cell faces), so a layered grid's
    /// thin cells bound a step across the layers, not along them. Beyond the box along an
    /// axis n is constant along it: that axis bounds a step only by the way back in plus one
    /// cell, and not at all while `p` moves away.
    fn step_hint(&self, p: DVec3, dir: DVec3) -> f64 {
        let outside = (self.min - p).max(p - self.max).max(DVec3::ZERO);
        let away = (p.cmplt(self.min) & dir.cmplt(DVec3::ZERO))
            | (p.cmpgt(self.max) & dir.cmpgt(DVec3::ZERO));
        let reach = (outside + self.cell) / dir.abs();
        DVec3::select(away, DVec3::INFINITY, reach).min_element()
    }
}
