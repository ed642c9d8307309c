//! Values on a regular lattice of nodes over a box, read trilinearly: the storage an index
//! grid ([`super::GridMedium`]) and a medium's density ([`super::Density`]) share.

use crate::math::Bounds3;
use glam::DVec3;

/// Values at `dims` nodes per axis over the box `[min, max]` (node (i,j,k) at
/// min + (i,j,k)·(max − min)/(dims − 1)), x-fastest. Outside the box a position is clamped to
/// it: the values continue constant along the clamped axes.
#[derive(Clone, Debug)]
pub struct Lattice {
    min: DVec3,
    max: DVec3,
    dims: [usize; 3],
    values: Vec<f64>,
    /// Node spacing along each axis.
    cell: DVec3,
    /// Cells per unit length along each axis (worked out once: a lookup's division was a
    /// tenth of a tricubic grid's sample).
    scale: DVec3,
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
    /// A value is out of the quantity's range.
    #[error("value #{index} is {value}: {expected}")]
    BadValue {
        /// Position in the list.
        index: usize,
        /// The value.
        value: f64,
        /// What every value must be ("finite and > 0").
        expected: &'static str,
    },
    /// The box has no volume.
    #[error("bounds must satisfy min < max on every axis")]
    EmptyBox,
}

/// Where a position falls in the lattice.
#[derive(Clone, Copy, Debug)]
pub struct Located {
    /// The cell's first node along each axis (0 ..= dims − 2).
    pub cell: [usize; 3],
    /// The fraction of the cell along each axis, in [0, 1].
    pub frac: [f64; 3],
    /// Per axis, whether the position lies within the box (else it was clamped).
    pub inside: glam::BVec3,
}

impl Lattice {
    /// Builds and validates a lattice; every value must pass `valid`, which `expected` says
    /// in words.
    pub fn new(
        min: DVec3,
        max: DVec3,
        dims: [usize; 3],
        values: Vec<f64>,
        valid: impl Fn(f64) -> bool,
        expected: &'static str,
    ) -> Result<Self, GridError> {
        if dims.iter().any(|&d| d < 2) {
            return Err(GridError::TooFewNodes(dims));
        }
        if !(min.cmplt(max).all()) {
            return Err(GridError::EmptyBox);
        }
        let count = dims[0]
            .checked_mul(dims[1])
            .and_then(|n| n.checked_mul(dims[2]))
            .ok_or(GridError::TooManyNodes(dims))?;
        if values.len() != count {
            return Err(GridError::WrongCount {
                expected: count,
                got: values.len(),
            });
        }
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !valid(**v)) {
            return Err(GridError::BadValue {
                index,
                value,
                expected,
            });
        }
        let cell = (max - min) / (Self::extent(dims));
        Ok(Self {
            min,
            max,
            dims,
            values,
            cell,
            scale: Self::extent(dims) / (max - min),
        })
    }

    /// The number of cells along each axis.
    fn extent(dims: [usize; 3]) -> DVec3 {
        DVec3::new(
            dims[0] as f64 - 1.0,
            dims[1] as f64 - 1.0,
            dims[2] as f64 - 1.0,
        )
    }

    /// Nodes per axis.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// Node spacing along each axis (scene units).
    pub fn cell_size(&self) -> DVec3 {
        self.cell
    }

    /// The box.
    pub fn bounds(&self) -> Bounds3 {
        Bounds3::new(self.min, self.max)
    }

    /// Every node's value.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The value at node (i, j, k).
    pub fn node(&self, i: usize, j: usize, k: usize) -> f64 {
        self.values[i + self.dims[0] * (j + self.dims[1] * k)]
    }

    /// Cells per unit length along each axis.
    pub fn scale(&self) -> DVec3 {
        self.scale
    }

    /// The cell `p` (clamped to the box) lies in and its fractions there.
    pub fn locate(&self, p: DVec3) -> Located {
        let u = ((p.clamp(self.min, self.max) - self.min) * self.scale).to_array();
        let mut cell = [0usize; 3];
        let mut frac = [0.0f64; 3];
        for a in 0..3 {
            // u ≥ 0 (clamped to the box), where truncation is the floor.
            cell[a] = (u[a] as usize).min(self.dims[a] - 2);
            frac[a] = u[a] - cell[a] as f64;
        }
        Located {
            cell,
            frac,
            inside: p.cmpge(self.min) & p.cmple(self.max),
        }
    }

    /// The trilinear interpolant and its partial derivatives in the cell fractions, in cell
    /// `cell` at fractions `frac`.
    pub fn linear(&self, cell: [usize; 3], frac: [f64; 3]) -> (f64, DVec3) {
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
        let value = lerp(c0, c1, fz);
        let dx = lerp(lerp(d00, d10, fy), lerp(d01, d11, fy), fz);
        let dy = lerp(c10 - c00, c11 - c01, fz);
        let dz = c1 - c0;
        (value, DVec3::new(dx, dy, dz))
    }

    /// The trilinear interpolant at `p` (clamped to the box).
    pub fn trilinear(&self, p: DVec3) -> f64 {
        let at = self.locate(p);
        self.linear(at.cell, at.frac).0
    }

    /// ∫ of the trilinear interpolant along the straight segment from `from` along unit `dir`
    /// over `length`, exactly (to round-off): the segment is cut where it crosses a node
    /// plane, and within each piece every coordinate stays in one cell (or clamped), so the
    /// interpolant is a cubic in arclength there, which Simpson's rule integrates exactly.
    pub fn integral(&self, from: DVec3, dir: DVec3, length: f64) -> f64 {
        if length.is_nan() || length <= 0.0 {
            return 0.0;
        }
        let mut crossings = [0, 1, 2].map(|a| self.crossings(a, from, dir, length));
        let f = |t: f64| self.trilinear(from + dir * t);
        let (mut t0, mut f0, mut sum) = (0.0, f(0.0), 0.0);
        loop {
            let next = (0..3)
                .filter(|&a| crossings[a].left > 0)
                .min_by(|&a, &b| crossings[a].t().total_cmp(&crossings[b].t()));
            let t1 = next.map_or(length, |a| crossings[a].t().min(length));
            if t1 > t0 {
                let f1 = f(t1);
                sum += (t1 - t0) / 6.0 * (f0 + 4.0 * f(0.5 * (t0 + t1)) + f1);
                (t0, f0) = (t1, f1);
            }
            match next {
                Some(a) if t1 < length => crossings[a].advance(),
                _ => break sum,
            }
        }
    }

    /// The node planes across axis `a` that the segment crosses strictly inside it, in order.
    fn crossings(&self, a: usize, from: DVec3, dir: DVec3, length: f64) -> Crossings {
        let d = dir[a];
        let mut crossings = Crossings {
            plane: 0.0,
            step: d.signum(),
            offset: self.min[a] - from[a],
            cell: self.cell[a],
            d,
            left: 0,
        };
        if d == 0.0 || d.is_nan() {
            return crossings;
        }
        let u = |t: f64| (from[a] + t * d - self.min[a]) / self.cell[a];
        let (u0, u1) = (u(0.0), u(length));
        let first = (u0.min(u1).floor() + 1.0).max(0.0);
        let last = (u0.max(u1).ceil() - 1.0).min(self.dims[a] as f64 - 1.0);
        if first <= last {
            crossings.plane = if d > 0.0 { first } else { last };
            crossings.left = (last - first) as usize + 1;
        }
        crossings
    }
}

/// The node planes a segment crosses across one axis, in the order it meets them.
#[derive(Clone, Copy, Debug)]
struct Crossings {
    /// The next plane's node number along the axis.
    plane: f64,
    /// +1 or −1: the way the segment goes through the planes.
    step: f64,
    /// The box's low face less the segment's start, along the axis.
    offset: f64,
    /// Node spacing along the axis.
    cell: f64,
    /// The segment direction's component along the axis.
    d: f64,
    /// Planes still to cross.
    left: usize,
}

impl Crossings {
    /// The segment's parameter at the next plane.
    fn t(&self) -> f64 {
        (self.offset + self.plane * self.cell) / self.d
    }

    fn advance(&mut self) {
        self.plane += self.step;
        self.left -= 1;
    }
}
