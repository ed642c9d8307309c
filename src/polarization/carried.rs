//! The polarization a path carries, and the elements it meets.
//!
//! Light leaves every source unpolarized. Along a specular chain it meets smooth dielectrics,
//! conductors, polarizers, retarders and crystal faces, and along curved stretches its basis
//! is parallel-transported (Rytov's law, [`super::RytovTransport`]). At a scattering vertex a
//! rough conductor's or dielectric's microfacet and Rayleigh's phase function apply their
//! Mueller matrices, as does a plastic (its coat's reflection, and its base's light refracted
//! in and out); every other vertex (a Lambertian surface, isotropic and Henyey–Greenstein
//! phase functions) is taken as a perfect depolarizer.
//!
//! A photon's chain runs with the light and carries the light's Stokes vector per channel,
//! S0 = 1: the chain's weight holds the power, and each element's factor on S0 joins it. A
//! camera's path runs against the light and carries the measurement the camera makes of the
//! light arriving along it, a row vector r per channel (r·S is what the camera records of
//! light S): r = (1, 0, 0, 0) at the camera, r ← r·M at each element met, and where a chain
//! ends the camera records r0 of depolarized light there ([`Polarization::closing`]), which the
//! chain's weight takes on: the rows go on per unit of it ([`Polarization::close`]), past
//! the scattering vertex, to the next chain. Each element's matrix enters divided by its first
//! element (what it does to unpolarized light), which the scalar transport already carries in
//! its weight and its choices between reflection and refraction.

use super::mueller::basis_change;
use super::RytovTransport;
use crate::color::Rgb;
use glam::{DMat4, DVec3, DVec4};

/// Which way a chain runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sense {
    /// With the light (a photon): it carries the light's Stokes vector.
    WithLight,
    /// Against the light (a camera path): it carries a measurement of the light.
    AgainstLight,
}

/// An optical element's Mueller matrix per RGB channel (the same three for a wavelength-blind
/// element), from the light arriving, written in the basis whose first axis is `x`, to the
/// light leaving, in the basis whose first axis is `x_leaving` — the same axis for an
/// interface's s direction across both rays or a sheet's axis, another where the light leaves
/// as a crystal's wave, polarized along its own field ([`super::crystal`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Element {
    /// Per channel.
    pub mueller: [DMat4; 3],
    /// The arriving light's basis's first axis (any vector not along the light; its part
    /// across the light is taken).
    pub x: DVec3,
    /// The leaving light's basis's first axis (as `x`).
    pub x_leaving: DVec3,
}

impl Element {
    /// The same matrix `m` for every channel, in the basis `x` on both sides.
    pub fn grey(m: DMat4, x: DVec3) -> Self {
        Self {
            mueller: [m; 3],
            x,
            x_leaving: x,
        }
    }
}

/// A photon's Stokes vector as a photon map keeps it: per channel (S1, S2, S3)/S0, in the
/// basis whose first axis is `x` across its direction (f32, as its power).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StoredStokes {
    stokes: [[f32; 3]; 3],
    x: [f32; 3],
}

/// What a chain carries of the light's polarization (see the module's notes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Polarization {
    sense: Sense,
    /// Per channel: the Stokes vector with S0 = 1 (with the light), or the measurement row
    /// (against it).
    channels: [DVec4; 3],
    /// Against the light, where the camera measures the whole Stokes vector: per component
    /// S1, S2, S3 of it, per channel, the row that measures it (r·S of light S is what the
    /// camera records as that component), carried as the first row is.
    stokes: Option<[[DVec4; 3]; 3]>,
    /// The basis's first axis (unit, across the path).
    x: DVec3,
    /// Rytov's transport of the basis along the curved stretch under way, if any.
    curve: Option<RytovTransport>,
}

impl Polarization {
    /// Unpolarized light (or an unpolarized measurement) on a path along unit `direction`.
    pub fn unpolarized(sense: Sense, direction: DVec3) -> Self {
        Self {
            sense,
            channels: [DVec4::X; 3],
            stokes: None,
            x: direction.any_orthonormal_vector(),
            curve: None,
        }
    }

    /// A camera's measurement of the whole Stokes vector of the light arriving against unit
    /// `direction`, in the basis whose first axis is the unit `first_axis` across it (the
    /// second: the light's direction × it), through `analyzer` where it looks through one:
    /// row k measures S_k, so that where the chain ends on depolarized light of radiance L
    /// the camera sees L·(r₀₀, r₁₀, r₂₀, r₃₀) ([`Polarization::recorded`]).
    pub fn measuring_stokes(
        analyzer: Option<&Element>,
        direction: DVec3,
        first_axis: DVec3,
    ) -> Self {
        let mut state = Self {
            x: first_axis,
            stokes: Some([DVec4::Y, DVec4::Z, DVec4::W].map(|e| [e; 3])),
            ..Self::unpolarized(Sense::AgainstLight, direction)
        };
        if let Some(element) = analyzer {
            state.look_through(element, direction);
        }
        state
    }

    /// A camera measurement looks through `element` on a path starting along unit `direction`
    /// (against the light): each row r becomes Mᵀr, M not divided by its first element.
    fn look_through(&mut self, element: &Element, direction: DVec3) {
        self.rebase(direction, element.x_leaving);
        let through = |row: &mut [DVec4; 3]| {
            for (v, m) in row.iter_mut().zip(&element.mueller) {
                *v = m.transpose() * *v;
            }
        };
        through(&mut self.channels);
        if let Some(rows) = self.stokes.as_mut() {
            rows.iter_mut().for_each(through);
        }
    }

    /// A camera's measurement through the analyzer `element` it looks through, on a path
    /// starting along unit `direction` (against the light): the first row of the element's
    /// matrix, not divided by its first element — the camera records r·S of light S reaching
    /// it, so ½ of unpolarized light through an ideal polarizer.
    pub fn measured_through(element: &Element, direction: DVec3) -> Self {
        let mut state = Self::unpolarized(Sense::AgainstLight, direction);
        state.look_through(element, direction);
        state
    }

    /// Which way the light travels where the path runs along `direction`.
    fn light(&self, direction: DVec3) -> DVec3 {
        match self.sense {
            Sense::WithLight => direction,
            Sense::AgainstLight => -direction,
        }
    }

    /// Re-expressed in the basis whose first axis is `x`, on a path along unit `direction`
    /// (unchanged where `x` is along it).
    fn rebase(&mut self, direction: DVec3, x: DVec3) {
        if let Some((turn, x)) = basis_change(self.light(direction), self.x, x) {
            self.channels = self.channels.map(|v| turn * v);
            if let Some(rows) = self.stokes.as_mut() {
                *rows = rows.map(|row| row.map(|v| turn * v));
            }
            self.x = x;
        }
    }

    /// Meets `element` where the path arrives along unit `direction`: the element's matrix
    /// (divided by its first element) applied in its bases — the state is re-expressed in the
    /// basis of the light's side the path arrives on, and keeps the other's for the way on.
    /// Returns the factor by which the light's power changes beyond what unpolarized light's
    /// would (with the light; 1 against it, where it shows at the chain's end); zero where the
    /// element passes none.
    pub fn meet(&mut self, element: &Element, direction: DVec3) -> Rgb {
        let (arriving, leaving) = match self.sense {
            Sense::WithLight => (element.x, element.x_leaving),
            Sense::AgainstLight => (element.x_leaving, element.x),
        };
        self.rebase(direction, arriving);
        let mut factor = [1.0; 3];
        for (c, ((v, m), f)) in (self.channels.iter_mut())
            .zip(&element.mueller)
            .zip(&mut factor)
            .enumerate()
        {
            let unpolarized = m.col(0).x;
            let passes = !(unpolarized.is_nan() || unpolarized <= 0.0);
            if let Some(rows) = self.stokes.as_mut() {
                for row in rows {
                    row[c] = match passes {
                        true => (*m / unpolarized).transpose() * row[c],
                        false => DVec4::ZERO,
                    };
                }
            }
            if !passes {
                *v = DVec4::ZERO;
                *f = 0.0;
                continue;
            }
            let m = *m / unpolarized;
            match self.sense {
                Sense::WithLight => {
                    let out = m * *v;
                    *f = out.x.max(0.0);
                    *v = match *f > 0.0 {
                        true => out / out.x,
                        false => DVec4::ZERO,
                    };
                }
                Sense::AgainstLight => *v = m.transpose() * *v,
            }
        }
        // An element of one basis leaves the state in it (as projected across the light
        // arriving, which lies across the light leaving too); one of two, in the other's,
        // a unit axis across the light leaving.
        if element.x_leaving != element.x {
            self.x = leaving;
        }
        Rgb::new(factor[0], factor[1], factor[2])
    }

    /// Sets off on a curved stretch along unit `direction`: from here the basis is carried
    /// along the path by Rytov's law ([`RytovTransport`]) until [`Polarization::end_curve`].
    pub fn begin_curve(&mut self, direction: DVec3) {
        self.curve = RytovTransport::new(direction, self.x);
    }

    /// The path's direction at the curved stretch's next point (nothing off a curved stretch).
    pub fn turn(&mut self, direction: DVec3) {
        if let Some(r) = self.curve.as_mut() {
            r.push(direction);
        }
    }

    /// Ends the curved stretch with the path along `direction`: the basis's first axis is the
    /// one carried there (across the path).
    pub fn end_curve(&mut self, direction: DVec3) {
        if let Some(mut r) = self.curve.take() {
            r.push(direction);
            self.x = r.field();
        }
    }

    /// Meets an ideal depolarizer (Mueller matrix diag(1, 0, 0, 0)): the light beyond it is
    /// unpolarized, what the light's power or the camera's measurement of it was is kept.
    pub fn depolarize(&mut self) {
        let keep = |v: &mut DVec4| *v = DVec4::new(v.x, 0.0, 0.0, 0.0);
        self.channels.iter_mut().for_each(keep);
        if let Some(rows) = self.stokes.as_mut() {
            rows.iter_mut().flatten().for_each(keep);
        }
    }

    /// Which way the chain runs.
    pub fn sense(&self) -> Sense {
        self.sense
    }

    /// The largest degree of linear polarization √(S1² + S2²)/S0 of the light over the
    /// channels (with the light; 0 against it, and for a channel that carries nothing).
    pub fn linear_degree(&self) -> f64 {
        match self.sense {
            Sense::WithLight => (self.channels.iter())
                .filter(|v| v.x > 0.0)
                .map(|v| v.y.hypot(v.z) / v.x)
                .fold(0.0, f64::max),
            Sense::AgainstLight => 0.0,
        }
    }

    /// What the camera records of depolarized light where the chain ends, per channel (the
    /// first element of its measurement row; 1 with the light, whose power the weight holds).
    pub fn closing(&self) -> Rgb {
        match self.sense {
            Sense::WithLight => Rgb::ONE,
            Sense::AgainstLight => {
                let [r, g, b] = self.channels.map(|v| v.x.max(0.0));
                Rgb::new(r, g, b)
            }
        }
    }

    /// Closes a chain against the light: returns [`Polarization::closing`] — the chain's
    /// weight takes it on — and divides every row by it, per channel, so that from here the
    /// rows measure per unit of what the weight holds (where it records nothing every row is
    /// zero: each element of a physical chain's Mueller matrix is bounded by its first). With
    /// the light: 1, nothing changes.
    pub fn close(&mut self) -> Rgb {
        let closing = self.closing();
        if self.sense == Sense::AgainstLight {
            let per_unit = |row: &mut [DVec4; 3]| {
                for (v, c) in row.iter_mut().zip(closing.0.to_array()) {
                    *v = match c > 0.0 {
                        true => *v / c,
                        false => DVec4::ZERO,
                    };
                }
            };
            per_unit(&mut self.channels);
            if let Some(rows) = self.stokes.as_mut() {
                rows.iter_mut().for_each(per_unit);
            }
        }
        closing
    }

    /// What the camera records of depolarized light where the chain is now, per unit of
    /// radiance: S0 [`Polarization::closing`], and S1–S3 where it measures them (against the
    /// light; with it, S0 = 1 alone).
    pub fn recorded(&self) -> Recorded {
        let first = |row: &[DVec4; 3]| Rgb::new(row[0].x, row[1].x, row[2].x);
        Recorded {
            s0: self.closing(),
            stokes: match self.sense {
                Sense::AgainstLight => self.stokes.as_ref().map(|rows| rows.map(|r| first(&r))),
                Sense::WithLight => None,
            },
        }
    }

    /// What the camera records (against the light: the rows) of the light `light` (with it:
    /// its Stokes vector per unit of power) arriving along unit `direction` (the light's), per
    /// unit of that power: each row times the light's Stokes vector in one basis.
    fn recorded_of(&self, light: &Polarization, direction: DVec3) -> Recorded {
        let mut light = *light;
        // The rows' basis is across the light (a row's basis is the light's it measures).
        light.rebase(direction, self.x);
        let read = |row: &[DVec4; 3]| {
            let [r, g, b] = [0, 1, 2].map(|c| row[c].dot(light.channels[c]));
            Rgb::new(r, g, b)
        };
        Recorded {
            s0: read(&self.channels),
            stokes: self.stokes.as_ref().map(|rows| rows.map(|r| read(&r))),
        }
    }

    /// What the camera records, through these rows carried along unit `direction` (the
    /// path's), of light travelling along unit `light_direction` that meets `element` (None: a
    /// depolarizer) — unpolarized, or of the Stokes vector a photon map kept (`kept`) — per
    /// unit of the light the element sends on from unpolarized light.
    pub fn recorded_through(
        &self,
        element: Option<&Element>,
        direction: DVec3,
        kept: Option<&StoredStokes>,
        light_direction: DVec3,
    ) -> Recorded {
        let Some(element) = element else {
            // Depolarized light is recorded by each row's first element, which a depolarizer
            // keeps: no copy to depolarize.
            return self.recorded();
        };
        let mut rows = *self;
        rows.meet(element, direction);
        match kept {
            Some(s) => rows.recorded_of(&Self::from_stored(s, light_direction), light_direction),
            None => rows.recorded(),
        }
    }

    /// The light's Stokes vector as a photon map keeps it (with the light).
    pub fn stored(&self) -> StoredStokes {
        StoredStokes {
            stokes: self.channels.map(|v| [v.y as f32, v.z as f32, v.w as f32]),
            x: self.x.as_vec3().to_array(),
        }
    }

    /// The light a photon map kept (`stored`), travelling along unit `direction`: its axis
    /// (kept to f32's digits) projected across the direction again.
    fn from_stored(stored: &StoredStokes, direction: DVec3) -> Self {
        let x = DVec3::from_array(stored.x.map(f64::from));
        let x = (x - x.dot(direction) * direction)
            .try_normalize()
            .unwrap_or_else(|| direction.any_orthonormal_vector());
        Self {
            sense: Sense::WithLight,
            channels: (stored.stokes)
                .map(|[s1, s2, s3]| DVec4::new(1.0, f64::from(s1), f64::from(s2), f64::from(s3))),
            stokes: None,
            x,
            curve: None,
        }
    }

    /// The light's Stokes vector per channel with S0 = 1, in the basis whose first axis is `x`,
    /// on a path along unit `direction` (with the light; None against it).
    pub fn stokes(&self, direction: DVec3, x: DVec3) -> Option<[DVec4; 3]> {
        (self.sense == Sense::WithLight).then(|| {
            let mut turned = *self;
            turned.rebase(direction, x);
            turned.channels
        })
    }
}

/// Light as a camera records it: S0 per channel — what its radiance layers hold, through its
/// polarizer where it looks through one — and, where it measures the whole Stokes vector,
/// S1–S3 (W/(m²·sr), in the basis of [`crate::camera::Camera::stokes_axis`]). Also what it
/// records per unit of radiance ([`Polarization::recorded`]), which radiance multiplies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Recorded {
    /// S0.
    pub s0: Rgb,
    /// S1, S2, S3 (None where the camera measures S0 alone).
    pub stokes: Option<[Rgb; 3]>,
}

impl Recorded {
    /// Radiance `s0` of a camera that measures S0 alone.
    pub fn radiance(s0: Rgb) -> Self {
        Self { s0, stokes: None }
    }

    /// Depolarized light of radiance `value` (as the path's weight sees it where the light
    /// is met) as the camera records it through the measurement `measure` the path carries
    /// there ([`Polarization::recorded`]); None: radiance, where the transport is not
    /// polarized.
    pub fn of(measure: Option<&Polarization>, value: Rgb) -> Self {
        match measure {
            Some(p) => p.recorded() * value,
            None => Self::radiance(value),
        }
    }
}

impl std::ops::AddAssign for Recorded {
    fn add_assign(&mut self, other: Self) {
        self.s0 += other.s0;
        self.stokes = match (self.stokes, other.stokes) {
            (Some(a), Some(b)) => Some([0, 1, 2].map(|k| a[k] + b[k])),
            (a, None) => a,
            (None, b) => b,
        };
    }
}

impl std::ops::Add for Recorded {
    type Output = Self;
    fn add(mut self, other: Self) -> Self {
        self += other;
        self
    }
}

impl std::ops::Mul<Rgb> for Recorded {
    type Output = Self;
    fn mul(self, radiance: Rgb) -> Self {
        Self {
            s0: self.s0 * radiance,
            stokes: self.stokes.map(|s| s.map(|c| c * radiance)),
        }
    }
}

impl std::ops::Div<f64> for Recorded {
    type Output = Self;
    fn div(self, divisor: f64) -> Self {
        Self {
            s0: self.s0 / divisor,
            stokes: self.stokes.map(|s| s.map(|c| c / divisor)),
        }
    }
}

impl std::ops::Mul<f64> for Recorded {
    type Output = Self;
    fn mul(self, factor: f64) -> Self {
        self * Rgb::splat(factor)
    }
}

#[cfg(test)]
mod tests {
    use super::super::mueller::{dielectric_reflection, linear_polarizer, linear_retarder};
    use super::*;

    /// Two polarizers whose axes stand at θ pass cos²θ of what the first passes, whichever way
    /// the chain runs, in any basis the chain starts in: each sheet's ½ (what it passes of
    /// unpolarized light, the scalar transport's weight) times the factors.
    #[test]
    fn malus_law_with_and_against_the_light() {
        let k = DVec3::new(0.2, 0.3, -1.0).normalize();
        let first = k.any_orthonormal_vector();
        let across = k.cross(first);
        for deg in [0.0, 10.0, 30.0, 45.0, 60.0, 89.0, 90.0, 135.0] {
            let theta = f64::to_radians(deg);
            let second = theta.cos() * first + theta.sin() * across;
            let want = 0.5 * theta.cos().powi(2);
            // A photon: polarizer at `first`, then at `second`.
            let mut photon = Polarization::unpolarized(Sense::WithLight, k);
            let a = photon.meet(&Element::grey(linear_polarizer(0.0), first), k);
            let b = photon.meet(&Element::grey(linear_polarizer(0.0), second), k);
            assert_eq!(
                a,
                Rgb::ONE,
                "the first passes what unpolarized light passes"
            );
            assert!(
                (0.5 * a.0.x * 0.5 * b.0.x - want).abs() < 1e-12,
                "{deg}°: {b}"
            );
            // A camera path meets them in the other order, running along −k.
            let mut camera = Polarization::unpolarized(Sense::AgainstLight, -k);
            camera.meet(&Element::grey(linear_polarizer(0.0), second), -k);
            camera.meet(&Element::grey(linear_polarizer(0.0), first), -k);
            assert!((0.25 * camera.closing().0.x - want).abs() < 1e-12, "{deg}°");
        }
    }

    /// A depolarizer passes the power (or the camera's measurement) it is given: behind crossed
    /// polarizers it stays dark, whichever way the chain runs.
    #[test]
    fn a_depolarizer_keeps_what_reaches_it() {
        let k = DVec3::Z;
        let crossed = [
            Element::grey(linear_polarizer(0.0), DVec3::X),
            Element::grey(linear_polarizer(0.0), DVec3::Y),
        ];
        let mut camera = Polarization::unpolarized(Sense::AgainstLight, -k);
        for e in &crossed {
            camera.meet(e, -k);
        }
        camera.depolarize();
        assert_eq!(camera.closing(), Rgb::ZERO);
        let mut photon = Polarization::unpolarized(Sense::WithLight, k);
        let through = photon.meet(&crossed[0], k);
        photon.depolarize();
        assert_eq!(photon.stokes(k, DVec3::X), Some([DVec4::X; 3]));
        assert_eq!(through, Rgb::ONE);
    }

    /// Against the light the chain's row reproduces what the light's own Stokes vector gives,
    /// through a sequence of reflections, a retarder and a polarizer in different bases.
    #[test]
    fn the_measurement_row_agrees_with_the_stokes_vector() {
        let k = DVec3::Z;
        let elements = [
            Element::grey(
                dielectric_reflection(0.7, 1.0, 1.5),
                DVec3::new(1.0, 0.4, 0.0),
            ),
            Element::grey(linear_retarder(1.1, 0.0), DVec3::new(-0.3, 1.0, 0.0)),
            Element::grey(
                dielectric_reflection(0.2, 1.5, 1.0),
                DVec3::new(0.8, -0.6, 0.0),
            ),
            Element::grey(linear_polarizer(0.0), DVec3::new(0.1, 1.0, 0.0)),
        ];
        let mut photon = Polarization::unpolarized(Sense::WithLight, k);
        let mut power = 1.0;
        for e in &elements {
            power *= photon.meet(e, k).0.x;
        }
        let mut camera = Polarization::unpolarized(Sense::AgainstLight, -k);
        for e in elements.iter().rev() {
            camera.meet(e, -k);
        }
        assert!((camera.closing().0.x - power).abs() < 1e-12, "{power}");
        assert!(
            power > 0.05 && power < 0.95,
            "{power}: a case that tests something"
        );
        // A camera measuring the whole Stokes vector in the basis of x reads, as shares of
        // S0, the Stokes vector in that basis of the light reaching it, elliptical behind
        // the retarder (without the last sheet, which leaves it linear).
        let before_the_sheet = &elements[..3];
        let mut photon = Polarization::unpolarized(Sense::WithLight, k);
        let mut power = 1.0;
        for e in before_the_sheet {
            power *= photon.meet(e, k).0.x;
        }
        let mut measuring = Polarization::measuring_stokes(None, -k, DVec3::X);
        for e in before_the_sheet.iter().rev() {
            measuring.meet(e, -k);
        }
        let arrived = photon.stokes(k, DVec3::X).unwrap()[0];
        // Closed, the measurement records per unit of what it recorded as S0.
        assert!((measuring.close().0.x - power).abs() < 1e-12);
        let recorded = measuring.recorded();
        assert_eq!(recorded.s0, Rgb::ONE);
        let shares = recorded.stokes.unwrap().map(|s| s.0.x);
        let want = [arrived.y, arrived.z, arrived.w];
        for (got, want) in shares.iter().zip(want) {
            assert!((got - want).abs() < 1e-12, "{shares:?} against {arrived}");
        }
        assert!(
            want.iter().all(|s| s.abs() > 0.05),
            "{want:?}: every component tested"
        );
    }
}
