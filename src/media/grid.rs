//! A tabulated index: trilinear interpolation of n on a regular grid over a box (a "3D texture").

use super::{IndexSample, Medium};
use glam::DVec3;

/// Trilinear n on the box `[min, max]` sampled at `dims` nodes per axis (node (i,j,k) at
/// min + (i,j,k)·(max − min)/(dims − 1)); `values` is x-fastest. The gradient is the exact
/// gradient of the trilinear interpolant (piecewise, discontinuous across cell faces).
/// Outside the box, positions are clamped to it: n continues constant along the clamped axes.
#[derive(Clone, Debug)]
pub struct GridMedium {
    min: DVec3,
    max: DVec3,
    dims: [usize; 3],
    values: Vec<f64>,
    min_cell: f64,
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
            min_cell: cell.min_element(),
        })
    }

    fn node(&self, i: usize, j: usize, k: usize) -> f64 {
        self.values[i + self.dims[0] * (j + self.dims[1] * k)]
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
        let mut grad = DVec3::new(dndx, dndy, dndz) * scale;
        // Clamped axes: n is constant there.
        grad = DVec3::select(inside, grad, DVec3::ZERO);
        Some(IndexSample { n, grad })
    }
    /// One cell: the interpolant's gradient jumps at cell faces.
    fn step_hint(&self, _p: DVec3, _dir: DVec3) -> f64 {
        self.min_cell
    }
}
