//! Uniaxial crystals (calcite, quartz, sapphire): light in one travels as two plane waves of
//! its own, each polarized, and an interface to one splits a ray in two.
//!
//! **The crystal.** Its dielectric tensor has the ordinary index n_o across its unit optic
//! axis c and the extraordinary index n_e along it: ε = n_o² I + (n_e² − n_o²) c cᵀ. A plane
//! wave of wave vector k (written in units of the vacuum wave number, so |k| is the index
//! the wave sees) is one of two eigenwaves (Born and Wolf, §15.3):
//! - the **ordinary** wave, |k| = n_o in every direction, its field E along k × c;
//! - the **extraordinary** wave, on the ellipsoid kᵀ M k = 1 with
//!   M = I/n_e² + (1/n_o² − 1/n_e²) c cᵀ (so 1/n(θ)² = cos²θ/n_o² + sin²θ/n_e², θ the
//!   angle between k and c), its displacement D in the plane of k and c, its field
//!   E = ε⁻¹ D. Its energy — the ray a renderer follows — runs along the normal of that
//!   ellipsoid, s ∝ M k, not along k: the walk-off, tan θ_s = (n_o/n_e)² tan θ.
//!
//! **The interface.** Across a plane interface the tangential part of k is kept (Snell's law
//! for any medium), and each side holds the two eigenwaves of that tangential part leaving
//! the interface into it (an isotropic side's are its s and p waves). The tangential E and
//! H = k × E are continuous: four equations for the four waves leaving, solved for the
//! complex amplitudes of a wave arriving (Born and Wolf's Fresnel equations where both sides
//! are isotropic). The power each wave carries away is its share of the arriving power along
//! the normal, Re(E × H*)·N. A wave whose normal component of k is complex decays away from
//! the interface and carries none: total internal reflection of one wave or both.
//!
//! Each way the light leaves is a [`Branch`]: its ray direction, its side and wave, and the
//! Mueller matrix from the arriving light into it, in the conventions of [`super::mueller`]
//! (its Jones matrix's; an isotropic side's basis is the s direction and k̂ × s, a crystal
//! wave's its field's direction). A crystal's wave is wholly polarized, so light arriving in
//! one is its field's, whatever a Stokes vector would say: its matrix reads only the power.

use super::carried::Element;
use super::mueller::from_jones;
use glam::{DMat3, DMat4, DVec3, DVec4};
use num_complex::Complex64;

type C = Complex64;

/// A uniaxial crystal: its indices across and along its optic axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uniaxial {
    /// n_o, the ordinary index (> 0): the index across the optic axis.
    pub ordinary: f64,
    /// n_e, the extraordinary index (> 0): the index of a wave polarized along the axis.
    pub extraordinary: f64,
    /// c, the unit optic axis.
    pub axis: DVec3,
}

/// One of a crystal's two eigenwaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wave {
    /// Index n_o every way, polarized across the plane of k and the optic axis.
    Ordinary,
    /// Index between n_o and n_e by direction, polarized in the plane of k and the axis.
    Extraordinary,
}

impl Uniaxial {
    /// M, the extraordinary wave's normal surface kᵀ M k = 1.
    fn normal_surface(&self) -> DMat3 {
        let (o, e) = (self.ordinary, self.extraordinary);
        let c = self.axis;
        DMat3::from_diagonal(DVec3::splat(1.0 / (e * e)))
            + outer(c, c) * (1.0 / (o * o) - 1.0 / (e * e))
    }

    /// ε⁻¹, which takes a wave's displacement D to its field E.
    fn impermeability(&self) -> DMat3 {
        let (o, e) = (self.ordinary, self.extraordinary);
        let c = self.axis;
        DMat3::from_diagonal(DVec3::splat(1.0 / (o * o)))
            + outer(c, c) * (1.0 / (e * e) - 1.0 / (o * o))
    }

    /// The index `wave` sees along unit wave normal `k`.
    pub fn index(&self, wave: Wave, k: DVec3) -> f64 {
        match wave {
            Wave::Ordinary => self.ordinary,
            Wave::Extraordinary => 1.0 / k.dot(self.normal_surface() * k).sqrt(),
        }
    }

    /// The unit wave normal of `wave` whose unit ray direction is `s` (the ray runs along the
    /// normal surface's normal M k, so k ∝ M⁻¹ s).
    pub fn wave_normal(&self, wave: Wave, s: DVec3) -> DVec3 {
        match wave {
            Wave::Ordinary => s,
            Wave::Extraordinary => {
                let (o, e) = (self.ordinary, self.extraordinary);
                let c = self.axis;
                (s * (e * e) + c * (c.dot(s) * (o * o - e * e))).normalize()
            }
        }
    }
}

/// u vᵀ.
fn outer(u: DVec3, v: DVec3) -> DMat3 {
    DMat3::from_cols(u * v.x, u * v.y, u * v.z)
}

/// What one side of an interface is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Optics {
    /// An isotropic medium of this index.
    Isotropic(f64),
    /// A uniaxial crystal.
    Crystal(Uniaxial),
}

/// Light on one side of an interface, arriving at it or leaving it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beam {
    /// Its unit ray direction (the way its energy travels).
    pub direction: DVec3,
    /// Its wave where the side is a crystal (None on an isotropic side).
    pub wave: Option<Wave>,
}

/// One way light meets an interface: in [`Interface::scatter`] the light leaving, in
/// [`Interface::gather`] the light arriving, with the Mueller matrix from the light arriving
/// into the light leaving.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Branch {
    /// The light of this branch.
    pub beam: Beam,
    /// Whether it is on the far side of the interface (the near side holds the other beam).
    pub beyond: bool,
    /// The Mueller matrix from the light arriving (in the basis of `element.x`) into the light
    /// leaving (in the basis of `element.x_leaving`), scaled to power: its first element is
    /// the share of the arriving light's power the leaving light carries — of unpolarized
    /// light arriving on an isotropic side, of its own wave's in a crystal.
    pub element: Element,
}

impl Branch {
    /// The share of the arriving light's power it carries (see [`Branch::element`]).
    pub fn power(&self) -> f64 {
        self.element.mueller[0].col(0).x
    }
}

/// At most four branches: two waves on each side.
#[derive(Clone, Copy, Debug, Default)]
pub struct Branches {
    items: [Option<Branch>; 4],
}

impl Branches {
    fn push(&mut self, branch: Branch) {
        if let Some(slot) = self.items.iter_mut().find(|b| b.is_none()) {
            *slot = Some(branch);
        }
    }

    /// The branches.
    pub fn iter(&self) -> impl Iterator<Item = &Branch> {
        self.items.iter().flatten()
    }

    /// The sum of their powers.
    pub fn power(&self) -> f64 {
        self.iter().map(Branch::power).sum()
    }
}

/// A plane interface between two sides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    /// The side the light is on (arriving in [`Interface::scatter`], leaving in
    /// [`Interface::gather`]).
    pub near: Optics,
    /// The other side.
    pub far: Optics,
    /// The unit normal, pointing into the near side.
    pub normal: DVec3,
}

/// A complex 3-vector: a wave vector whose normal part may be imaginary, and a field.
#[derive(Clone, Copy, Debug)]
struct Phasor([C; 3]);

impl Phasor {
    fn real(v: DVec3) -> Self {
        Self([v.x, v.y, v.z].map(|x| C::new(x, 0.0)))
    }
    fn add(self, o: Self) -> Self {
        Self([0, 1, 2].map(|i| self.0[i] + o.0[i]))
    }
    fn scale(self, a: C) -> Self {
        Self(self.0.map(|x| x * a))
    }
    fn cross(self, o: Self) -> Self {
        let (a, b) = (self.0, o.0);
        Self([
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ])
    }
    /// a · v for a real v.
    fn along(self, v: DVec3) -> C {
        self.0[0] * v.x + self.0[1] * v.y + self.0[2] * v.z
    }
    fn apply(m: DMat3, v: Self) -> Self {
        let re = m * DVec3::new(v.0[0].re, v.0[1].re, v.0[2].re);
        let im = m * DVec3::new(v.0[0].im, v.0[1].im, v.0[2].im);
        Self([C::new(re.x, im.x), C::new(re.y, im.y), C::new(re.z, im.z)])
    }
    fn norm(self) -> f64 {
        self.0.iter().map(|c| c.norm_sqr()).sum::<f64>().sqrt()
    }
    fn re(self) -> DVec3 {
        DVec3::new(self.0[0].re, self.0[1].re, self.0[2].re)
    }
    fn conj(self) -> Self {
        Self(self.0.map(|c| c.conj()))
    }
}

/// One plane wave of a side: its wave vector, field and magnetic field H = k × E.
#[derive(Clone, Copy, Debug)]
struct PlaneWave {
    k: Phasor,
    e: Phasor,
    h: Phasor,
}

impl PlaneWave {
    fn new(k: Phasor, e: Phasor) -> Self {
        let e = e.scale(C::new(1.0 / e.norm(), 0.0));
        Self {
            k,
            e,
            h: k.cross(e),
        }
    }

    /// The power it carries along unit `n` per unit amplitude²: Re(E × H*)·n (0 for a wave
    /// that decays away from the interface).
    fn flux(&self, n: DVec3) -> f64 {
        self.e.cross(self.h.conj()).re().dot(n)
    }

    /// Whether it carries power: its wave vector is real (else it decays away from the
    /// interface, beyond a critical angle).
    fn propagates(&self) -> bool {
        self.k.0.iter().all(|c| c.im == 0.0)
    }

    /// Its ray direction: the time-averaged Poynting vector's.
    fn ray(&self) -> DVec3 {
        self.e.cross(self.h.conj()).re().normalize()
    }
}

/// The two waves of a side that share the tangential wave vector `kt` and carry their energy
/// along unit `n` (into the side, away from the interface — or toward it, for `n` pointing at
/// it), with `s` the unit direction across the plane of `kt` and `n`: an isotropic side's s
/// and p waves (E along s, and along k̂ × s), a crystal's ordinary and extraordinary waves.
fn waves(optics: Optics, kt: DVec3, n: DVec3, s: DVec3) -> [(PlaneWave, Option<Wave>); 2] {
    // The normal part q of k = kt + q n on a circle of radius `index`: decaying away from the
    // interface (Im q > 0) where it cannot propagate.
    let normal_part = |index: f64| -> C {
        let q2 = index * index - kt.length_squared();
        match q2 >= 0.0 {
            true => C::new(q2.sqrt(), 0.0),
            false => C::new(0.0, (-q2).sqrt()),
        }
    };
    let along = |q: C| Phasor::real(kt).add(Phasor::real(n).scale(q));
    let s_and_p = |k: Phasor, index: f64| {
        let p = k.cross(Phasor::real(s)).scale(C::new(1.0 / index, 0.0));
        [PlaneWave::new(k, Phasor::real(s)), PlaneWave::new(k, p)]
    };
    match optics {
        Optics::Isotropic(index) => {
            let [te, tm] = s_and_p(along(normal_part(index)), index);
            [(te, None), (tm, None)]
        }
        Optics::Crystal(crystal) => {
            let c = Phasor::real(crystal.axis);
            let ko = along(normal_part(crystal.ordinary));
            // kᵀMk = 1 along k = kt + q n: A q² + B q + C = 0; the root whose energy
            // (∝ M k) runs along n: n·M k = B/2 + A q = √(B² − 4AC)/2 > 0.
            let m = crystal.normal_surface();
            let (a, b, cc) = (n.dot(m * n), 2.0 * kt.dot(m * n), kt.dot(m * kt) - 1.0);
            let disc = b * b - 4.0 * a * cc;
            let root = match disc >= 0.0 {
                true => C::new(disc.sqrt(), 0.0),
                false => C::new(0.0, (-disc).sqrt()),
            };
            let ke = along((root - b) / (2.0 * a));
            let eo = ko.cross(c);
            let de = extraordinary_displacement(ke, c);
            // Along the optic axis the two waves are one (index n_o): any two fields across
            // it are eigenwaves; take the s and p waves there.
            let degenerate =
                eo.norm() < 1e-9 * ko.norm() || de.norm() < 1e-9 * ke.norm() * ke.norm();
            match degenerate {
                true => {
                    let [te, tm] = s_and_p(ko, crystal.ordinary);
                    [(te, Some(Wave::Ordinary)), (tm, Some(Wave::Extraordinary))]
                }
                false => [
                    (PlaneWave::new(ko, eo), Some(Wave::Ordinary)),
                    (
                        PlaneWave::new(ke, Phasor::apply(crystal.impermeability(), de)),
                        Some(Wave::Extraordinary),
                    ),
                ],
            }
        }
    }
}

/// The extraordinary wave's displacement direction, (k × c) × k: across k, in the plane of
/// k and c.
fn extraordinary_displacement(k: Phasor, c: Phasor) -> Phasor {
    k.cross(c).cross(k)
}

/// Solves the 4 × 4 complex system a x = b by Gaussian elimination with partial pivoting
/// (None where it is singular).
fn solve(mut a: [[C; 4]; 4], mut b: [C; 4]) -> Option<[C; 4]> {
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].norm().total_cmp(&a[j][col].norm()))?;
        if a[pivot][col].norm() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..4 {
            let f = a[row][col] / a[col][col];
            let pivot_row = a[col];
            for (x, v) in a[row].iter_mut().zip(pivot_row).skip(col) {
                *x -= f * v;
            }
            let v = b[col];
            b[row] -= f * v;
        }
    }
    let mut x = [C::new(0.0, 0.0); 4];
    for row in (0..4).rev() {
        let mut sum = b[row];
        for k in row + 1..4 {
            sum -= a[row][k] * x[k];
        }
        x[row] = sum / a[row][row];
    }
    x.iter().all(|z| z.is_finite()).then_some(x)
}

/// One side's two waves leaving the interface and the basis their light is written in.
struct Leaving {
    waves: [(PlaneWave, Option<Wave>); 2],
    /// Which side (false: the near one).
    beyond: bool,
    /// The unit direction the waves' energy leaves along (into their side).
    into: DVec3,
}

impl Interface {
    /// The unit direction across the plane of incidence of tangential wave vector `kt`
    /// (any direction in the interface where `kt` vanishes).
    fn s_direction(&self, kt: DVec3) -> DVec3 {
        self.normal
            .cross(kt)
            .try_normalize()
            .unwrap_or_else(|| self.normal.any_orthonormal_vector())
    }

    /// The tangential wave vector of `beam` on the side `optics`.
    fn tangential(&self, optics: Optics, beam: Beam) -> DVec3 {
        let k = match (optics, beam.wave) {
            (Optics::Crystal(c), Some(w)) => {
                let k = c.wave_normal(w, beam.direction);
                k * c.index(w, k)
            }
            (Optics::Crystal(c), None) => beam.direction * c.ordinary,
            (Optics::Isotropic(n), _) => beam.direction * n,
        };
        k - k.dot(self.normal) * self.normal
    }

    /// The amplitudes of the four waves leaving (near side's two, then far side's) for the
    /// arriving `incident` wave (amplitude 1): tangential E and H continuous.
    fn amplitudes(
        &self,
        incident: &PlaneWave,
        near: &Leaving,
        far: &Leaving,
        s: DVec3,
    ) -> Option<[C; 4]> {
        let t = [s, self.normal.cross(s)];
        let rows = |w: &PlaneWave| {
            [
                w.e.along(t[0]),
                w.e.along(t[1]),
                w.h.along(t[0]),
                w.h.along(t[1]),
            ]
        };
        let mut a = [[C::new(0.0, 0.0); 4]; 4];
        let columns = [
            (rows(&near.waves[0].0), 1.0),
            (rows(&near.waves[1].0), 1.0),
            (rows(&far.waves[0].0), -1.0),
            (rows(&far.waves[1].0), -1.0),
        ];
        for (col, (entries, sign)) in columns.iter().enumerate() {
            for (row, v) in entries.iter().enumerate() {
                a[row][col] = *v * *sign;
            }
        }
        solve(a, rows(incident).map(|v| -v))
    }

    /// The waves of both sides leaving the interface with tangential wave vector `kt`.
    fn leaving(&self, kt: DVec3, s: DVec3) -> [Leaving; 2] {
        let n = self.normal;
        [
            Leaving {
                waves: waves(self.near, kt, n, s),
                beyond: false,
                into: n,
            },
            Leaving {
                waves: waves(self.far, kt, -n, s),
                beyond: true,
                into: -n,
            },
        ]
    }

    /// The ways light arriving as `arriving` on the near side leaves the interface: reflected
    /// on the near side and transmitted to the far side, each wave (an isotropic side's s and
    /// p light as one beam) with the power it carries; waves that cannot leave (total
    /// internal reflection) are left out.
    pub fn scatter(&self, arriving: Beam) -> Branches {
        let kt = self.tangential(self.near, arriving);
        let s = self.s_direction(kt);
        let toward = -self.normal;
        let incident = waves(self.near, kt, toward, s);
        // The waves arriving: both of an isotropic side (the light's s and p parts), the
        // arriving wave alone in a crystal.
        let inputs: [Option<&PlaneWave>; 2] = match arriving.wave {
            None => [Some(&incident[0].0), Some(&incident[1].0)],
            Some(w) => [
                incident.iter().find(|(_, v)| *v == Some(w)).map(|(p, _)| p),
                None,
            ],
        };
        let sides = self.leaving(kt, s);
        let mut amplitudes = [[C::new(0.0, 0.0); 4]; 2];
        let mut arriving_flux = [1.0; 2];
        for ((input, a), f) in inputs.iter().zip(&mut amplitudes).zip(&mut arriving_flux) {
            if let Some(w) = input {
                *f = w.flux(toward);
                match (*f > 0.0, self.amplitudes(w, &sides[0], &sides[1], s)) {
                    (true, Some(x)) => *a = x,
                    _ => return Branches::default(),
                }
            }
        }
        let x_in = match (arriving.wave, inputs[0]) {
            (Some(_), Some(w)) => w.e.re().normalize(),
            _ => s,
        };
        let mut branches = Branches::default();
        for (side_index, side) in sides.iter().enumerate() {
            // Row `wave` of the Jones matrix into this side: that wave's amplitude from each
            // arriving wave, scaled so that its square is the share of power.
            let row = |wave: usize| -> [C; 2] {
                let flux = side.waves[wave].0.flux(side.into).max(0.0);
                [0, 1].map(|input| match inputs[input] {
                    Some(_) => {
                        amplitudes[input][2 * side_index + wave]
                            * (flux / arriving_flux[input]).sqrt()
                    }
                    None => C::new(0.0, 0.0),
                })
            };
            let flows = |wave: usize| side.waves[wave].0.propagates();
            let beyond = side.beyond;
            match self.side(beyond) {
                Optics::Isotropic(_) if flows(0) => {
                    let beam = Beam {
                        direction: side.waves[0].0.ray(),
                        wave: None,
                    };
                    let j = [row(0), row(1)];
                    branches.push(branch(j, [x_in, s], beam, beyond, arriving.wave));
                }
                Optics::Isotropic(_) => {}
                Optics::Crystal(_) => {
                    for (wave, (out, label)) in side.waves.iter().enumerate() {
                        if flows(wave) {
                            let beam = Beam {
                                direction: out.ray(),
                                wave: *label,
                            };
                            let j = [row(wave), [C::new(0.0, 0.0); 2]];
                            let x_out = out.e.re().normalize();
                            branches.push(branch(j, [x_in, x_out], beam, beyond, arriving.wave));
                        }
                    }
                }
            }
        }
        branches
    }

    /// The ways light arrives at the interface to leave it as `leaving` on the near side: the
    /// beams on either side whose light (reflected or transmitted) goes into it, each with
    /// the Mueller matrix from it into `leaving` (its first element: the share of that beam's
    /// power — unpolarized on an isotropic side, its own wave's in a crystal — that
    /// `leaving` carries). Found by scattering each such beam ([`Interface::scatter`]).
    pub fn gather(&self, leaving: Beam) -> Branches {
        let kt = self.tangential(self.near, leaving);
        let s = self.s_direction(kt);
        let flipped = Interface {
            near: self.far,
            far: self.near,
            normal: -self.normal,
        };
        let mut found = Branches::default();
        for (interface, beyond) in [(*self, false), (flipped, true)] {
            // The beams arriving on this side: its waves whose energy runs toward the
            // interface (an isotropic side's s and p waves are one beam).
            let toward = -interface.normal;
            let candidates = waves(interface.near, kt, toward, s);
            let beams = match interface.near {
                Optics::Isotropic(_) => [Some((&candidates[0].0, None)), None],
                Optics::Crystal(_) => candidates.each_ref().map(|(w, v)| Some((w, *v))),
            };
            for (wave, label) in beams.into_iter().flatten() {
                if !wave.propagates() {
                    continue;
                }
                let beam = Beam {
                    direction: wave.ray(),
                    wave: label,
                };
                let into_leaving = interface
                    .scatter(beam)
                    .iter()
                    .find(|b| b.beyond == beyond && b.beam.wave == leaving.wave)
                    .copied();
                if let Some(b) = into_leaving {
                    found.push(Branch {
                        beam,
                        beyond,
                        element: b.element,
                    });
                }
            }
        }
        found
    }

    fn side(&self, beyond: bool) -> Optics {
        match beyond {
            false => self.near,
            true => self.far,
        }
    }
}

/// A branch of Jones matrix `j` from the arriving light (in the basis of `axes[0]`) into the
/// leaving light `beam` (in the basis of `axes[1]`). Light arriving in a crystal's wave
/// (`arriving`) is its field's, (1, 1, 0, 0) in its basis: the matrix then reads its power
/// alone, whatever a Stokes vector carried says.
fn branch(
    j: [[C; 2]; 2],
    axes: [DVec3; 2],
    beam: Beam,
    beyond: bool,
    arriving: Option<Wave>,
) -> Branch {
    let mut m = from_jones(j);
    if arriving.is_some() {
        let out = m.col(0) + m.col(1);
        m = DMat4::from_cols(out, DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
    }
    Branch {
        beam,
        beyond,
        element: Element {
            mueller: [m; 3],
            x: axes[0],
            x_leaving: axes[1],
        },
    }
}

#[cfg(test)]
mod tests {
    use super::super::mueller::{dielectric_reflection, dielectric_transmission, Amplitudes};
    use super::*;
    use glam::DVec4;

    const CALCITE: (f64, f64) = (1.6584, 1.4864);

    fn calcite(axis: DVec3) -> Uniaxial {
        Uniaxial {
            ordinary: CALCITE.0,
            extraordinary: CALCITE.1,
            axis: axis.normalize(),
        }
    }

    /// Directions spread over a hemisphere about `n` (a golden-angle spiral), none grazing.
    fn arriving(n: DVec3, count: usize) -> impl Iterator<Item = DVec3> {
        let (t, b) = n.any_orthonormal_pair();
        (0..count).map(move |i| {
            let cos = 1.0 - 0.98 * (i as f64 + 0.5) / count as f64;
            let sin = (1.0 - cos * cos).sqrt();
            let phi = 2.399963229728653 * i as f64;
            -(cos * n + sin * (phi.cos() * t + phi.sin() * b))
        })
    }

    fn close(a: DMat4, b: DMat4, tol: f64) -> bool {
        (a - b).to_cols_array().iter().all(|d| d.abs() < tol)
    }

    /// Between two isotropic sides the solver is Born and Wolf's Fresnel equations: the
    /// reflected and transmitted beams' Mueller matrices equal the s/p amplitudes' written out
    /// (`mueller::Amplitudes`) to 1e-12, denser and less dense, below and beyond the critical
    /// angle; and a Jones matrix diag(r_s, r_p) gives `Amplitudes::reflection`'s matrix.
    #[test]
    fn between_isotropic_sides_it_is_fresnel() {
        let n = DVec3::new(0.3, 0.2, 0.9).normalize();
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.33, 2.4)] {
            let interface = Interface {
                near: Optics::Isotropic(n1),
                far: Optics::Isotropic(n2),
                normal: n,
            };
            for d in arriving(n, 40) {
                let cos = -d.dot(n);
                let branches = interface.scatter(Beam {
                    direction: d,
                    wave: None,
                });
                let reflected = branches.iter().find(|b| !b.beyond).unwrap();
                let want = dielectric_reflection(cos, n1, n2);
                assert!(
                    close(reflected.element.mueller[0], want, 1e-12),
                    "{n1}→{n2} at cos {cos}: {:?} against {want:?}",
                    reflected.element.mueller[0]
                );
                let mirrored = d - 2.0 * d.dot(n) * n;
                assert!(reflected.beam.direction.distance(mirrored) < 1e-12);
                let want = dielectric_transmission(cos, n1, n2);
                let transmitted = branches.iter().find(|b| b.beyond).copied();
                match transmitted {
                    Some(t) => assert!(close(t.element.mueller[0], want, 1e-12), "{cos}"),
                    None => assert_eq!(want, DMat4::ZERO, "{n1}→{n2} at {cos}"),
                }
            }
        }
        let amplitudes = Amplitudes::new(0.6, C::new(1.7, 0.0));
        let [rs, rp] = amplitudes.reflected;
        let zero = C::new(0.0, 0.0);
        assert!(close(
            from_jones([[rs, zero], [zero, rp]]),
            amplitudes.reflection(),
            1e-15
        ));
    }

    /// Every wave of the crystal solves Maxwell's equations in it: k × (k × E) + ε E = 0 with
    /// ε = n_o² I + (n_e² − n_o²) c cᵀ, to 1e-12, for waves that propagate and that decay.
    #[test]
    fn its_waves_solve_the_wave_equation() {
        let crystal = calcite(DVec3::new(1.0, 2.0, 0.5));
        let (o, e) = (crystal.ordinary, crystal.extraordinary);
        let eps = DMat3::from_diagonal(DVec3::splat(o * o))
            + outer(crystal.axis, crystal.axis) * (e * e - o * o);
        let n = DVec3::Z;
        for i in 0..50 {
            let angle = i as f64 * 0.7;
            let size = 0.05 * i as f64; // beyond 1.66 the waves decay
            let kt = size * DVec3::new(angle.cos(), angle.sin(), 0.0);
            let s = n.cross(kt).try_normalize().unwrap_or(DVec3::X);
            for (w, _) in waves(Optics::Crystal(crystal), kt, n, s) {
                let residual = w.k.cross(w.k.cross(w.e)).add(Phasor::apply(eps, w.e));
                assert!(residual.norm() < 1e-12, "|kt| {size}: {residual:?}");
            }
        }
    }

    /// Power is kept: the beams leaving carry all of the light arriving, to 1e-12 — from an
    /// isotropic side into a crystal (s, p and elliptical light), from each of a crystal's
    /// waves out of it and back into it (total internal reflection included), and between two
    /// crystals of different axes.
    #[test]
    fn it_keeps_power() {
        let n = DVec3::new(-0.2, 0.1, 1.0).normalize();
        let a = calcite(DVec3::new(0.3, -0.8, 0.5));
        let b = calcite(DVec3::new(1.0, 0.2, -0.1));
        let pairs = [
            (Optics::Isotropic(1.0), Optics::Crystal(a)),
            (Optics::Isotropic(1.7), Optics::Crystal(a)),
            (Optics::Crystal(a), Optics::Isotropic(1.0)),
            (Optics::Crystal(a), Optics::Crystal(b)),
        ];
        let stokes = [
            DVec4::new(1.0, 0.0, 0.0, 0.0),
            DVec4::new(1.0, 1.0, 0.0, 0.0),
            DVec4::new(1.0, -1.0, 0.0, 0.0),
            DVec4::new(1.0, 0.3, -0.5, 0.6),
        ];
        let mut tested = 0;
        for (near, far) in pairs {
            let interface = Interface {
                near,
                far,
                normal: n,
            };
            for d in arriving(n, 60) {
                let beams = match near {
                    Optics::Isotropic(_) => vec![None],
                    Optics::Crystal(_) => vec![Some(Wave::Ordinary), Some(Wave::Extraordinary)],
                };
                for wave in beams {
                    let branches = interface.scatter(Beam { direction: d, wave });
                    for s in stokes {
                        let out: f64 = branches.iter().map(|b| (b.element.mueller[0] * s).x).sum();
                        assert!((out - 1.0).abs() < 1e-12, "{near:?} {wave:?} {d}: {out}");
                        tested += 1;
                    }
                    for b in branches.iter() {
                        let into = match b.beyond {
                            true => -n,
                            false => n,
                        };
                        assert!(b.beam.direction.dot(into) > 0.0, "leaves the interface");
                    }
                }
            }
        }
        assert_eq!(tested, 4 * (60 + 60 + 120 + 120));
    }

    /// A c-cut face (the optic axis along the normal): the extraordinary wave's ray leaves at
    /// tan θ_s = n_o sin θi / (n_e √(n_e² − sin²θi)) from the normal (Born and Wolf §15.3 from
    /// the normal surface k_⊥²/n_e² + k_∥²/n_o² = 1), the ordinary one at Snell's angle for
    /// n_o; with the axis in the face across the plane of incidence, both obey Snell's law,
    /// the extraordinary wave at n_e. To 1e-12 from 0 to 80°.
    #[test]
    fn rays_refract_as_the_closed_forms_say() {
        let n = DVec3::Z;
        for deg in (0..=80).step_by(5) {
            let theta = f64::to_radians(deg as f64);
            let d = DVec3::new(theta.sin(), 0.0, -theta.cos());
            let angle = |b: &Branch| b.beam.direction.x.atan2(-b.beam.direction.z);
            let ray = |axis: DVec3, wave: Wave| {
                let interface = Interface {
                    near: Optics::Isotropic(1.0),
                    far: Optics::Crystal(calcite(axis)),
                    normal: n,
                };
                let branches = interface.scatter(Beam {
                    direction: d,
                    wave: None,
                });
                let b = *branches
                    .iter()
                    .find(|b| b.beyond && b.beam.wave == Some(wave))
                    .unwrap();
                assert!(b.beam.direction.y.abs() < 1e-12, "in the plane");
                angle(&b)
            };
            let (o, e) = CALCITE;
            let sin = theta.sin();
            if deg > 0 {
                let want = (o * sin / (e * (e * e - sin * sin).sqrt())).atan();
                let got = ray(DVec3::Z, Wave::Extraordinary);
                assert!((got - want).abs() < 1e-12, "{deg}°: {got} against {want}");
            }
            let snell = |index: f64| (sin / index).asin();
            assert!((ray(DVec3::Z, Wave::Ordinary) - snell(o)).abs() < 1e-12);
            assert!((ray(DVec3::Y, Wave::Ordinary) - snell(o)).abs() < 1e-12);
            assert!((ray(DVec3::Y, Wave::Extraordinary) - snell(e)).abs() < 1e-12);
        }
    }

    /// Square on a plate whose axis stands at θ to the normal, the ordinary ray goes straight
    /// and the extraordinary one walks off by tan ρ = (n_o² − n_e²) tan θ / (n_e² + n_o² tan²θ)
    /// (from tan θ_s = (n_o/n_e)² tan θ), 6.2° in calcite at 45° — the double image's
    /// separation t tan ρ. Both leave the far face parallel to the light that came in, and
    /// their fields are orthogonal; the ordinary one carries half of unpolarized light's
    /// transmittance at n_o.
    #[test]
    fn the_extraordinary_ray_walks_off() {
        let (o, e) = CALCITE;
        for deg in [10.0, 30.0, 45.0, 60.0, 80.0] {
            let theta = f64::to_radians(deg);
            let crystal = calcite(DVec3::new(theta.sin(), 0.0, theta.cos()));
            let entry = Interface {
                near: Optics::Isotropic(1.0),
                far: Optics::Crystal(crystal),
                normal: DVec3::Z,
            };
            let branches = entry.scatter(Beam {
                direction: -DVec3::Z,
                wave: None,
            });
            let inside = |w: Wave| {
                *branches
                    .iter()
                    .find(|b| b.beyond && b.beam.wave == Some(w))
                    .unwrap()
            };
            let (bo, be) = (inside(Wave::Ordinary), inside(Wave::Extraordinary));
            assert!(bo.beam.direction.distance(-DVec3::Z) < 1e-12);
            let t = theta.tan();
            let want = (o * o - e * e) * t / (e * e + o * o * t * t);
            let got = be.beam.direction.x / -be.beam.direction.z;
            assert!((got - want).abs() < 1e-12, "{deg}°: {got} against {want}");
            if deg == 45.0 {
                assert!((want.atan().to_degrees() - 6.22).abs() < 0.01);
            }
            assert!(bo.element.x_leaving.dot(be.element.x_leaving).abs() < 1e-12);
            // The ordinary wave takes half of unpolarized light's n_o-transmittance,
            // ½·4n_o/(1 + n_o)²; the extraordinary one what is left (power is kept).
            let half = 2.0 * o / ((1.0 + o) * (1.0 + o));
            assert!((bo.power() - half).abs() < 1e-12, "{}", bo.power());
            let exit = Interface {
                near: Optics::Crystal(crystal),
                far: Optics::Isotropic(1.0),
                normal: DVec3::Z,
            };
            for b in [bo, be] {
                let out = exit.scatter(b.beam);
                let through = out.iter().find(|x| x.beyond).unwrap();
                assert!(through.beam.direction.distance(-DVec3::Z) < 1e-12);
            }
        }
    }

    /// Reciprocity (Stokes–Helmholtz, for a crystal's symmetric ε): the power a crystal's wave
    /// sends out into an isotropic side, summed over that side's polarizations, is twice what
    /// unpolarized light arriving back along the ray it leaves on sends into the reversed wave
    /// — computed by separate solves, to 1e-12. And [`Interface::gather`] finds each beam
    /// feeding a given beam with the matrix [`Interface::scatter`] gives it.
    #[test]
    fn it_is_reciprocal() {
        let crystal = calcite(DVec3::new(0.4, 0.7, 0.6));
        let n = DVec3::new(0.1, -0.3, 1.0).normalize();
        let outward = Interface {
            near: Optics::Crystal(crystal),
            far: Optics::Isotropic(1.2),
            normal: n,
        };
        let inward = Interface {
            near: Optics::Isotropic(1.2),
            far: Optics::Crystal(crystal),
            normal: -n,
        };
        let mut tested = 0;
        for d in arriving(n, 80) {
            for wave in [Wave::Ordinary, Wave::Extraordinary] {
                let out = outward.scatter(Beam {
                    direction: d,
                    wave: Some(wave),
                });
                let Some(through) = out.iter().find(|b| b.beyond) else {
                    continue;
                };
                let back = inward.scatter(Beam {
                    direction: -through.beam.direction,
                    wave: None,
                });
                let reversed = back
                    .iter()
                    .find(|b| b.beyond && b.beam.wave == Some(wave))
                    .unwrap();
                assert!(reversed.beam.direction.distance(-d) < 1e-9);
                let (there, here) = (through.power(), 2.0 * reversed.power());
                assert!((there - here).abs() < 1e-12, "{d} {wave:?}: {there} {here}");
                // Gathering the transmitted beam finds the crystal's wave with the same matrix.
                let gathered = inward.gather(through.beam);
                let fed = gathered
                    .iter()
                    .find(|b| b.beyond && b.beam.wave == Some(wave))
                    .copied()
                    .unwrap();
                assert!(fed.beam.direction.distance(d) < 1e-9);
                assert!(close(
                    fed.element.mueller[0],
                    through.element.mueller[0],
                    1e-9
                ));
                tested += 1;
            }
        }
        assert!(
            tested > 40,
            "{tested} of 160 leave (n_o → 1.2: the rest is reflected)"
        );
    }
}
