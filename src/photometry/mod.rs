//! Measured luminaires: a luminaire's intensity over direction as its photometric file gives
//! it (a goniogram), read from IES LM-63 files ([`ies`]) and EULUMDAT files ([`eulumdat`]),
//! or as an image over the sphere in the equal-area map ([`image`], pbrt-v4's goniometric
//! light's).
//!
//! **Conventions.** Directions are given in the luminaire's frame: x along its C = 0 direction
//! (the luminaire's length), y along C = 90° (its width), z its nadir (γ = 0, straight down
//! its axis); C turns counterclockwise seen from above, from x toward y. A table is a grid on
//! a photometric web ([`Web`]) — polar angles θ from the web's polar axis, longitudes φ about
//! it — placed on the luminaire as IES LM-63 defines its photometric types A, B and C. Between
//! the measured angles the intensity is bilinear in (θ, φ); outside the measured range it is
//! 0; type C's longitudes wrap around. Intensities are in the file's unit (candela), scaled by
//! the scene (the light's colour).

pub mod eulumdat;
pub mod ies;
pub mod image;

use crate::sampling::Discrete;
use glam::DVec3;
use std::f64::consts::TAU;

/// A luminaire's intensity over direction, as a file gives it.
#[derive(Clone, Debug, PartialEq)]
pub enum IntensityMap {
    /// A table over a photometric web (an IES or EULUMDAT file).
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

    /// The intensity toward unit direction `d` of the luminaire's frame (x along C = 0, y along
    /// C = 90°, z the nadir).
    pub fn intensity(&self, d: DVec3) -> f64 {
        match self {
            Self::Table(t) => t.toward(d),
            Self::Image(i) => i.intensity(zenith_up(d)),
        }
    }

    /// A unit direction of the luminaire's frame drawn for three uniform numbers, with its
    /// solid-angle density (a photon sent along it carries I/pdf). None when the luminaire
    /// sends nothing.
    pub fn draw(&self, u: [f64; 3]) -> Option<Drawn> {
        match self {
            Self::Table(t) => t.draw(u),
            Self::Image(i) => i.draw(u).map(|(d, pdf)| Drawn {
                direction: zenith_up(d),
                pdf,
            }),
        }
    }
}

/// A direction of the luminaire's frame in an intensity image's (its z the zenith), and back.
fn zenith_up(d: DVec3) -> DVec3 {
    DVec3::new(d.x, d.y, -d.z)
}

/// Where a goniogram's photometric web lies on the luminaire: which of its axes is the web's
/// polar axis and where the web's longitudes start: IES LM-63's photometric types (its type
/// C is CIE 121's C-γ system, its type B CIE 121's B-β). A table's angles are (θ, φ): θ from
/// the polar axis in [0, π], φ about it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Web {
    /// Type C (architectural and roadway luminaires): the polar axis is the nadir z; θ = γ
    /// and φ = C, from x toward y, over a full turn.
    C,
    /// Type B (floodlights): the polar axis is the luminaire's width y. A direction of
    /// horizontal angle H and vertical angle V is (cos H sin V, sin H, cos H cos V): the
    /// photometric axis (0°, 0°) is the nadir, H turns toward y, V toward x. θ = 90° − H and
    /// φ = V, from z toward x, within ±90°.
    B,
    /// Type A (automotive): the polar axis is the luminaire's length x. A direction of
    /// horizontal angle H and vertical angle V is (sin V, cos V sin H, cos V cos H). θ = 90° − V
    /// and φ = H, from z toward y, within ±90°.
    A,
}

impl Web {
    /// The angles (cos θ, φ) of unit direction `d` of the luminaire's frame.
    fn angles(self, d: DVec3) -> (f64, f64) {
        match self {
            Web::C => (d.z, d.y.atan2(d.x)),
            Web::B => (d.y, d.x.atan2(d.z)),
            Web::A => (d.x, d.y.atan2(d.z)),
        }
    }

    /// The unit direction of the luminaire's frame at angles (cos θ, φ).
    fn direction(self, cos_theta: f64, phi: f64) -> DVec3 {
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let (along, across) = (sin_theta * phi.cos(), sin_theta * phi.sin());
        match self {
            Web::C => DVec3::new(along, across, cos_theta),
            Web::B => DVec3::new(across, cos_theta, along),
            Web::A => DVec3::new(cos_theta, across, along),
        }
    }

    /// Whether the longitudes go round a full turn (type C), or span at most ±90° and the
    /// intensity beyond them is 0 (types A and B).
    fn wraps(self) -> bool {
        match self {
            Web::C => true,
            Web::B | Web::A => false,
        }
    }
}

/// A luminaire's intensity I(θ, φ) on a grid of angles (radians) of its photometric web:
/// bilinear between the nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct Goniogram {
    /// Where the web lies on the luminaire.
    web: Web,
    /// Polar angles θ, ascending, within [0, π].
    thetas: Vec<f64>,
    /// Longitudes φ, ascending: from 0, the last below 2π (wrapping to the first) for type C;
    /// within [−π/2, π/2] for types A and B.
    phis: Vec<f64>,
    /// Intensity at (φ_i, θ_j): `values[i * thetas.len() + j]`, ≥ 0.
    values: Vec<f64>,
    /// The grid's cells (φ_i..φ_i+1, with wrap for type C; θ_j..θ_j+1) weighed by their
    /// power, for drawing photon directions; None when the luminaire sends nothing.
    cells: Option<Discrete>,
    /// ∫ I dω over the cells.
    power: f64,
}

/// A direction drawn from a goniogram and the density it was drawn with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drawn {
    /// The unit direction, in the luminaire's frame.
    pub direction: DVec3,
    /// The solid-angle density of the direction (1/sr).
    pub pdf: f64,
}

impl Goniogram {
    /// The goniogram of `values` (per longitude, the intensities at every polar angle) at
    /// polar angles `thetas` and longitudes `phis` (radians) of web `web`: `phis` over a full
    /// turn for type C (as [`ies`] expands a file's symmetry to), within ±π/2 for A and B.
    /// Checked by the reader.
    pub fn new(web: Web, thetas: Vec<f64>, phis: Vec<f64>, values: Vec<f64>) -> Self {
        let mut g = Self {
            web,
            thetas,
            phis,
            values,
            cells: None,
            power: 0.0,
        };
        let weights: Vec<f64> = (0..g.columns())
            .flat_map(|i| (0..g.thetas.len() - 1).map(move |j| (i, j)))
            .map(|(i, j)| g.cell_power(i, j))
            .collect();
        g.cells = Discrete::new(&weights);
        g.power = weights.iter().sum();
        g
    }

    /// The number of columns of cells in longitude: one a longitude when they wrap (the last
    /// to the first), one between each two neighbours when they do not.
    fn columns(&self) -> usize {
        match self.web.wraps() {
            true => self.phis.len(),
            false => self.phis.len() - 1,
        }
    }

    fn value(&self, i: usize, j: usize) -> f64 {
        self.values[(i % self.phis.len()) * self.thetas.len() + j]
    }

    /// The longitude extent of cell column `i` (to the next φ, the last of a wrapping web to
    /// the first a turn on).
    fn phi_width(&self, i: usize) -> f64 {
        match self.phis.get(i + 1) {
            Some(next) => next - self.phis[i],
            None => TAU - self.phis[i] + self.phis[0],
        }
    }

    /// The cell's power: its mean corner intensity times its solid angle (the bilinear
    /// field's power to second order in the cell's size).
    fn cell_power(&self, i: usize, j: usize) -> f64 {
        let mean = 0.25
            * (self.value(i, j)
                + self.value(i, j + 1)
                + self.value(i + 1, j)
                + self.value(i + 1, j + 1));
        mean * self.cell_solid_angle(i, j)
    }

    fn cell_solid_angle(&self, i: usize, j: usize) -> f64 {
        self.phi_width(i) * (self.thetas[j].cos() - self.thetas[j + 1].cos())
    }

    /// The intensity toward unit direction `d` of the luminaire's frame.
    pub fn toward(&self, d: DVec3) -> f64 {
        let (cos_theta, phi) = self.web.angles(d);
        self.intensity(cos_theta.clamp(-1.0, 1.0).acos(), phi)
    }

    /// The intensity at polar angle `theta` and longitude `phi` of the web (radians):
    /// bilinear between the nodes, 0 outside the measured range.
    pub fn intensity(&self, theta: f64, phi: f64) -> f64 {
        let t = &self.thetas;
        if !(t[0]..=t[t.len() - 1]).contains(&theta) {
            return 0.0;
        }
        let j = (t.partition_point(|&x| x <= theta).max(1) - 1).min(t.len() - 2);
        let tt = (theta - t[j]) / (t[j + 1] - t[j]);
        let p = &self.phis;
        let phi = match self.web.wraps() {
            true => phi.rem_euclid(TAU),
            false if (p[0]..=p[p.len() - 1]).contains(&phi) => phi,
            false => return 0.0,
        };
        let i = (p.partition_point(|&x| x <= phi).max(1) - 1).min(self.columns() - 1);
        let width = self.phi_width(i);
        let tp = match width > 0.0 {
            true => ((phi - p[i]).rem_euclid(TAU) / width).min(1.0),
            false => 0.0,
        };
        let at = |i: usize| self.value(i, j) * (1.0 - tt) + self.value(i, j + 1) * tt;
        at(i) * (1.0 - tp) + at(i + 1) * tp
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
        let rows = self.thetas.len() - 1;
        let (i, j) = (pick.index / rows, pick.index % rows);
        let (top, bottom) = (self.thetas[j].cos(), self.thetas[j + 1].cos());
        let cos_theta = (top + (bottom - top) * u[1]).clamp(-1.0, 1.0);
        let phi = self.phis[i] + self.phi_width(i) * u[2];
        Some(Drawn {
            direction: self.web.direction(cos_theta, phi),
            pdf: pick.probability / self.cell_solid_angle(i, j),
        })
    }
}
