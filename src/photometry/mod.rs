//! Measured luminaires: a luminaire's intensity over direction as its photometric file gives
//! it (a goniogram), read from IES LM-63 files ([`ies`]) and EULUMDAT files ([`eulumdat`]),
//! or as an image over the sphere in the equal-area map ([`image`], pbrt-v4's goniometric
//! light's).
//!
//! **Conventions** (type C photometry, as IES LM-63 and EULUMDAT state it): the vertical angle
//! γ is measured from the luminaire's nadir (γ = 0 straight down its axis, 180° straight up);
//! the horizontal angle C turns about the axis, counterclockwise seen from above, from the
//! luminaire's C = 0 direction. Intensities are in the file's unit (candela), scaled by the
//! scene (the light's colour). Between the measured angles the intensity is bilinear in
//! (γ, C); outside the measured γ range it is 0; C wraps around.

pub mod eulumdat;
pub mod ies;
pub mod image;

use crate::sampling::Discrete;
use std::f64::consts::TAU;

/// A luminaire's intensity over direction, as a file gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum IntensityMap {
    /// A table over the angles (γ, C) (an IES or EULUMDAT file).
    Table(Goniogram),
    /// An image over the sphere in the equal-area map (pbrt-v4's goniometric light).
    Image(image::IntensityImage),
}

impl IntensityMap {
    /// The largest intensity.
    pub fn peak(&self) -> f64 {
        match self {
            Self::Table(t) => t.peak(),
            Self::Image(i) => i.peak(),
        }
    }

    /// The power ∫ I dω (the file's unit times sr).
    pub fn power(&self) -> f64 {
        match self {
            Self::Table(t) => t.power(),
            Self::Image(i) => i.power(),
        }
    }
}

/// A luminaire's intensity I(γ, C) on a grid of angles (radians): bilinear between the nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Goniogram {
    /// Vertical angles γ, ascending, within [0, π].
    gammas: Vec<f64>,
    /// Horizontal angles C, ascending, from 0, the last below 2π (C wraps to the first).
    cs: Vec<f64>,
    /// Intensity at (C_i, γ_j): `values[i * gammas.len() + j]`, ≥ 0.
    values: Vec<f64>,
    /// The grid's cells (C_i..C_i+1 with wrap, γ_j..γ_j+1) weighed by their power, for
    /// drawing photon directions; None when the luminaire sends nothing.
    cells: Option<Discrete>,
    /// ∫ I dω over the cells.
    power: f64,
}

/// A direction drawn from a goniogram: its angles and the density it was drawn with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drawn {
    /// The vertical angle's cosine.
    pub cos_gamma: f64,
    /// The horizontal angle (radians).
    pub c: f64,
    /// The solid-angle density of the direction (1/sr).
    pub pdf: f64,
}

impl Goniogram {
    /// The goniogram of `values` (per horizontal angle, the intensities at every vertical
    /// angle) at vertical angles `gammas` and horizontal angles `cs` (radians; `cs` over a
    /// full turn, as [`ies`] expands a file's symmetry to). Checked by the reader.
    pub fn new(gammas: Vec<f64>, cs: Vec<f64>, values: Vec<f64>) -> Self {
        let mut g = Self {
            gammas,
            cs,
            values,
            cells: None,
            power: 0.0,
        };
        let weights: Vec<f64> = (0..g.cs.len())
            .flat_map(|i| (0..g.gammas.len() - 1).map(move |j| (i, j)))
            .map(|(i, j)| g.cell_power(i, j))
            .collect();
        g.cells = Discrete::new(&weights);
        g.power = weights.iter().sum();
        g
    }

    fn value(&self, i: usize, j: usize) -> f64 {
        self.values[(i % self.cs.len()) * self.gammas.len() + j]
    }

    /// The horizontal extent of cell column `i` (to the next C, the last wrapping to 2π).
    fn c_width(&self, i: usize) -> f64 {
        match self.cs.get(i + 1) {
            Some(next) => next - self.cs[i],
            None => TAU - self.cs[i] + self.cs[0],
        }
    }

    /// The cell's solid angle and power: its mean corner intensity times its solid angle
    /// (the bilinear field's power to second order in the cell's size).
    fn cell_power(&self, i: usize, j: usize) -> f64 {
        let mean = 0.25
            * (self.value(i, j)
                + self.value(i, j + 1)
                + self.value(i + 1, j)
                + self.value(i + 1, j + 1));
        mean * self.cell_solid_angle(i, j)
    }

    fn cell_solid_angle(&self, i: usize, j: usize) -> f64 {
        self.c_width(i) * (self.gammas[j].cos() - self.gammas[j + 1].cos())
    }

    /// The intensity at vertical angle `gamma` and horizontal angle `c` (radians): bilinear
    /// between the nodes, 0 outside the measured vertical range.
    pub fn intensity(&self, gamma: f64, c: f64) -> f64 {
        let g = &self.gammas;
        if !(g[0]..=g[g.len() - 1]).contains(&gamma) {
            return 0.0;
        }
        let j = (g.partition_point(|&x| x <= gamma).max(1) - 1).min(g.len() - 2);
        let tg = (gamma - g[j]) / (g[j + 1] - g[j]);
        let c = c.rem_euclid(TAU);
        let i = self.cs.partition_point(|&x| x <= c).max(1) - 1;
        let from = self.cs[i];
        let width = self.c_width(i);
        let tc = match width > 0.0 {
            true => ((c - from).rem_euclid(TAU) / width).min(1.0),
            false => 0.0,
        };
        let at = |i: usize| self.value(i, j) * (1.0 - tg) + self.value(i, j + 1) * tg;
        at(i) * (1.0 - tc) + at(i + 1) * tc
    }

    /// The largest intensity (the largest node: bilinear values lie between them).
    pub fn peak(&self) -> f64 {
        self.values.iter().copied().fold(0.0, f64::max)
    }

    /// The power ∫ I dω (the file's unit times sr) to second order in the grid's spacing.
    pub fn power(&self) -> f64 {
        self.power
    }

    /// A direction drawn for three uniform numbers: a cell by its power, then uniformly in
    /// solid angle within it (its density is the cell's share of the power over its solid
    /// angle; a photon sent along it carries I/pdf). None when the luminaire sends nothing.
    pub fn draw(&self, u: [f64; 3]) -> Option<Drawn> {
        let pick = self.cells.as_ref()?.pick(u[0]);
        let rows = self.gammas.len() - 1;
        let (i, j) = (pick.index / rows, pick.index % rows);
        let (top, bottom) = (self.gammas[j].cos(), self.gammas[j + 1].cos());
        let cos_gamma = top + (bottom - top) * u[1];
        let c = (self.cs[i] + self.c_width(i) * u[2]).rem_euclid(TAU);
        Some(Drawn {
            cos_gamma: cos_gamma.clamp(-1.0, 1.0),
            c,
            pdf: pick.probability / self.cell_solid_angle(i, j),
        })
    }
}
