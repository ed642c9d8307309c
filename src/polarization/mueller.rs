//! Stokes vectors and Mueller matrices: how much light there is and how it is polarized, and
//! what a surface does to both.
//!
//! **Conventions** (Collett 2005; Born & Wolf for the amplitudes; the scheme of Mitsuba 3's
//! polarized variants, "Mitsuba 3 polarization" in docs/references.md). Light travelling along unit k is described in a basis (x, y) of the
//! plane perpendicular to k, right-handed about it: y = k × x. With the field's complex
//! amplitudes (Ex, Ey) in that basis, time dependence e^(−iωt), its Stokes vector is
//! S = (S0, S1, S2, S3) with S0 = |Ex|² + |Ey|², S1 = |Ex|² − |Ey|², S2 = 2 Re(Ex Ey*) and
//! S3 = 2 Im(Ex Ey*): S1 > 0 is linear polarization along x, S2 > 0 along x + y (halfway from
//! x to y), S3 > 0 a field turning from y toward x — clockwise seen by a receiver looking into
//! the light, right-handed in the SPIE convention, as Mitsuba 3 labels it (its Stokes images'
//! S3 agree in sign: tests/polarization.rs). Unpolarized light is (S0, 0, 0, 0).
//!
//! A Mueller matrix M takes the Stokes vector of light arriving (in the basis the element
//! names) to that of the light leaving. An interface's matrix is written in its s/p basis:
//! x = s, the unit normal of the plane of incidence (the same for the light arriving and
//! leaving), and y = k × s for each. In these right-handed bases the amplitude coefficients are
//! Born and Wolf's: r_s = (cos θi − η cos θt)/(cos θi + η cos θt),
//! r_p = (η cos θi − cos θt)/(η cos θi + cos θt), so at normal incidence r_p = −r_s and a
//! reflection turns S2 and S3 over (a circular polarization's sense flips on a mirror).

use glam::{DMat4, DVec3};
use num_complex::Complex64;

/// The change from the basis whose first axis is `from` (unit, across unit `k`, the light's
/// direction) to the one whose first axis is `to` projected across `k`: the matrix that
/// re-expresses a Stokes vector (or a measurement row) and that axis, normalised. None where
/// the projection is within 1e-9 of zero (`to` along `k`, or not finite).
pub fn basis_change(k: DVec3, from: DVec3, to: DVec3) -> Option<(DMat4, DVec3)> {
    let across = to - to.dot(k) * k;
    match across.length() > 1e-9 * to.length() {
        true => {
            let x = across.normalize();
            let angle = k.cross(from).dot(x).atan2(from.dot(x));
            Some((rotation(angle), x))
        }
        false => None,
    }
}

/// The matrix that re-expresses a Stokes vector in the basis turned by `angle` (radians) about
/// the light's direction, from x toward y: (S1, S2) turn by −2·angle, S0 and S3 stay.
pub fn rotation(angle: f64) -> DMat4 {
    let (s, c) = (2.0 * angle).sin_cos();
    DMat4::from_cols_array_2d(&[
        [1.0, 0.0, 0.0, 0.0],
        [0.0, c, -s, 0.0],
        [0.0, s, c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// Rows of a Mueller matrix as written on paper, into glam's column-major matrix.
fn from_rows(rows: [[f64; 4]; 4]) -> DMat4 {
    DMat4::from_cols_array_2d(&rows).transpose()
}

/// The element of Mueller matrix `m` written with `axis` at `angle` (radians, from x toward y)
/// where `m` has it along x: m turned into the basis at `angle`, applied, and turned back.
fn turned(m: DMat4, angle: f64) -> DMat4 {
    rotation(-angle) * m * rotation(angle)
}

/// An ideal linear polarizer whose transmission axis lies at `angle` (radians) from x toward y:
/// it passes half of unpolarized light and cos² of the angle to linear light (Malus's law).
pub fn linear_polarizer(angle: f64) -> DMat4 {
    let along_x = from_rows([
        [0.5, 0.5, 0.0, 0.0],
        [0.5, 0.5, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0],
    ]);
    turned(along_x, angle)
}

/// An ideal linear retarder of retardance `retardance` (radians: the slow axis's phase lag)
/// whose fast axis lies at `angle` (radians) from x toward y; a quarter-wave plate
/// (retardance π/2) at 45° to a linear polarization makes it circular.
pub fn linear_retarder(retardance: f64, angle: f64) -> DMat4 {
    interface(
        Complex64::new(1.0, 0.0),
        Complex64::from_polar(1.0, retardance),
        1.0,
    )
    .map_or(DMat4::IDENTITY, |m| turned(m, angle))
}

/// The Mueller matrix, in the s/p basis, of an element whose Jones matrix there is
/// diag(`a_s`, `a_p`), times `scale` (the ratio of power densities across it, for a
/// transmission): A = (|a_s|² + |a_p|²)/2, B = (|a_s|² − |a_p|²)/2, C + iS = a_s*·a_p (S's
/// sign the module's S3 convention's). None where a coefficient is not finite.
fn interface(a_s: Complex64, a_p: Complex64, scale: f64) -> Option<DMat4> {
    let (ss, pp) = (a_s.norm_sqr(), a_p.norm_sqr());
    let z = a_s.conj() * a_p;
    let (a, b, c, s) = (0.5 * (ss + pp), 0.5 * (ss - pp), z.re, z.im);
    let m = from_rows([
        [a, b, 0.0, 0.0],
        [b, a, 0.0, 0.0],
        [0.0, 0.0, c, s],
        [0.0, 0.0, -s, c],
    ]) * scale;
    m.is_finite().then_some(m)
}

/// The Mueller matrix of Jones matrix `j` (rows: the leaving light's x and y components; columns:
/// the arriving light's): M_ab = ½ tr(σ_a J σ_b J†), with the Pauli matrices of
/// the module's Stokes convention (σ1 = diag(1, −1), σ2 = [[0, 1], [1, 0]],
/// σ3 = [[0, i], [−i, 0]]); [`interface`] is its diagonal case written out (a crystal's
/// unit tests hold the two equal).
pub fn from_jones(j: [[Complex64; 2]; 2]) -> DMat4 {
    let (o, i) = (Complex64::new(0.0, 0.0), Complex64::new(0.0, 1.0));
    let one = Complex64::new(1.0, 0.0);
    let sigma = [
        [[one, o], [o, one]],
        [[one, o], [o, -one]],
        [[o, one], [one, o]],
        [[o, i], [-i, o]],
    ];
    let mul = |a: [[Complex64; 2]; 2], b: [[Complex64; 2]; 2]| {
        let mut r = [[o; 2]; 2];
        for (r_row, a_row) in r.iter_mut().zip(&a) {
            for (c, out) in r_row.iter_mut().enumerate() {
                *out = a_row[0] * b[0][c] + a_row[1] * b[1][c];
            }
        }
        r
    };
    let dagger = [
        [j[0][0].conj(), j[1][0].conj()],
        [j[0][1].conj(), j[1][1].conj()],
    ];
    let mut rows = [[0.0; 4]; 4];
    for (a, row) in rows.iter_mut().enumerate() {
        for (b, m) in row.iter_mut().enumerate() {
            let p = mul(mul(sigma[a], j), mul(sigma[b], dagger));
            *m = 0.5 * (p[0][0] + p[1][1]).re;
        }
    }
    DMat4::from_cols_array_2d(&rows).transpose()
}

/// The Fresnel amplitude coefficients of the interface to relative index η (complex for a
/// conductor, η + ik; below 1 toward a less dense dielectric) at cos θi = `cos_i` ∈ (0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Amplitudes {
    /// r_s, r_p (module conventions).
    pub reflected: [Complex64; 2],
    /// t_s, t_p.
    pub transmitted: [Complex64; 2],
    /// η cos θt (imaginary beyond the critical angle: total internal reflection).
    pub eta_cos_t: Complex64,
}

impl Amplitudes {
    /// The coefficients at cos θi = `cos_i` for relative index `eta`.
    pub fn new(cos_i: f64, eta: Complex64) -> Self {
        let c = Complex64::new(cos_i, 0.0);
        // η cos θt = √(η² − sin²θi); the principal root has Im ≥ 0: a wave that decays away
        // from the interface in an absorbing or beyond-critical medium.
        let g = (eta * eta - (1.0 - cos_i * cos_i)).sqrt();
        let e2c = eta * eta * c;
        Self {
            reflected: [(c - g) / (c + g), (e2c - g) / (e2c + g)],
            transmitted: [2.0 * c / (c + g), 2.0 * eta * c / (e2c + g)],
            eta_cos_t: g,
        }
    }

    /// The Mueller matrix of the reflection (module conventions).
    pub fn reflection(&self) -> DMat4 {
        let [rs, rp] = self.reflected;
        interface(rs, rp, 1.0).unwrap_or(DMat4::ZERO)
    }

    /// The Mueller matrix of the transmission, power per unit area of the beam's cross section
    /// (the factor η cos θt / cos θi; zero under total internal reflection and into a
    /// conductor). For a dielectric its first element is 1 − R.
    pub fn transmission(&self, cos_i: f64) -> DMat4 {
        let g = self.eta_cos_t;
        if g.re <= 0.0 || g.im.abs() > 1e-12 * g.re {
            return DMat4::ZERO;
        }
        let [ts, tp] = self.transmitted;
        interface(ts, tp, g.re / cos_i).unwrap_or(DMat4::ZERO)
    }
}

/// The reflection's Mueller matrix of a dielectric interface from index `n1` (the light's
/// side) to `n2` at cos θi = `cos_i`.
pub fn dielectric_reflection(cos_i: f64, n1: f64, n2: f64) -> DMat4 {
    Amplitudes::new(cos_i, Complex64::new(n2 / n1, 0.0)).reflection()
}

/// The transmission's Mueller matrix of a dielectric interface from `n1` to `n2`.
pub fn dielectric_transmission(cos_i: f64, n1: f64, n2: f64) -> DMat4 {
    Amplitudes::new(cos_i, Complex64::new(n2 / n1, 0.0)).transmission(cos_i)
}

/// A thin dielectric pane of index `eta` relative to the medium around it (parallel faces;
/// the reflections inside summed incoherently) at cos θi = `cos_i`: the Mueller matrices of
/// its reflection and its transmission (straight through), in the s/p basis. Each order of
/// reflection inside is coherent in itself: with r the outer face's amplitude for each
/// polarization (r′ = −r inside), R = |r|² and T = 1 − R (Stokes's relations: t t′ = 1 − r²),
/// order k of the reflection is r (k = 0) or −T r^(2k−1), order k of the transmission T r^(2k).
/// Summed: the reflectance of each polarization 2R/(1 + R), its transmittance (1 − R)/(1 + R),
/// and between s and p r_s* r_p + T_s T_p r_s r_p/(1 − R_s R_p) reflected,
/// T_s T_p/(1 − R_s R_p) transmitted (real inside: the light that enters the pane meets no
/// total internal reflection there). Where the outer face reflects totally (a pane less dense
/// than its surroundings, beyond the critical angle) it is that face's reflection.
pub fn thin_pane(cos_i: f64, eta: f64) -> [DMat4; 2] {
    let [rs, rp] = Amplitudes::new(cos_i, Complex64::new(eta, 0.0)).reflected;
    let (big_rs, big_rp) = (rs.norm_sqr().min(1.0), rp.norm_sqr().min(1.0));
    let (ts, tp) = (1.0 - big_rs, 1.0 - big_rp);
    let inside = match ts * tp > 0.0 {
        true => ts * tp / (1.0 - big_rs * big_rp),
        false => 0.0,
    };
    let diattenuator = |ss: f64, pp: f64, z: Complex64| {
        from_rows([
            [0.5 * (ss + pp), 0.5 * (ss - pp), 0.0, 0.0],
            [0.5 * (ss - pp), 0.5 * (ss + pp), 0.0, 0.0],
            [0.0, 0.0, z.re, z.im],
            [0.0, 0.0, -z.im, z.re],
        ])
    };
    let reflected = |r: f64| 2.0 * r / (1.0 + r);
    let transmitted = |r: f64| (1.0 - r) / (1.0 + r);
    [
        diattenuator(
            reflected(big_rs),
            reflected(big_rp),
            rs.conj() * rp + inside * (rs * rp).re,
        ),
        diattenuator(
            transmitted(big_rs),
            transmitted(big_rp),
            Complex64::new(inside, 0.0),
        ),
    ]
}

/// The reflection's Mueller matrix of a conductor of complex index η + ik relative to the
/// medium outside (`eta`, `k`) at cos θi = `cos_i`.
pub fn conductor_reflection(cos_i: f64, eta: f64, k: f64) -> DMat4 {
    Amplitudes::new(cos_i, Complex64::new(eta, k)).reflection()
}

/// The reflection's Mueller matrix of a perfect conductor (r_s = −1, r_p = 1: every state
/// kept, S2 and S3 turned over as on any mirror at normal incidence).
pub fn perfect_mirror() -> DMat4 {
    from_rows([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0, 0.0],
        [0.0, 0.0, 0.0, -1.0],
    ])
}

/// Rayleigh scattering through the angle of cosine `cos` (an electric dipole much smaller than
/// the wavelength, driven by the field: Chandrasekhar 1960, ch. I §15), in
/// the s/p basis of the scattering plane — x = s, its unit normal k_in × k_out, the same for
/// the light arriving and leaving, and y = k × s for each. The dipole radiates the s field
/// whole and the p field times cos θ (their amplitudes' ratio; y_out·y_in = cos θ), so this
/// is the element of Jones matrix diag(1, cos θ) times 3/(8π): M00 = 3(1 + cos²θ)/(16π) is the
/// phase function for unpolarized light (1/sr, the medium's `Phase::Rayleigh`), and
/// unpolarized light leaves with S1/S0 = sin²θ/(1 + cos²θ), polarized across the scattering
/// plane (wholly at 90°).
pub fn rayleigh(cos: f64) -> DMat4 {
    let cos = cos.clamp(-1.0, 1.0);
    let jones = interface(Complex64::new(1.0, 0.0), Complex64::new(cos, 0.0), 1.0);
    jones.unwrap_or(DMat4::ZERO) * (3.0 / (8.0 * std::f64::consts::PI))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec4;

    const GLASS: f64 = 1.5;

    fn unpolarized() -> DVec4 {
        DVec4::new(1.0, 0.0, 0.0, 0.0)
    }

    /// The degree of linear polarization √(S1² + S2²)/S0 of `v`.
    fn degree_linear(v: DVec4) -> f64 {
        v.y.hypot(v.z) / v.x
    }

    /// Rs, Rp of a dielectric from the amplitudes' squares, against the textbook's power
    /// formulas written out on their own.
    fn rs_rp(cos_i: f64, n1: f64, n2: f64) -> (f64, f64) {
        let sin_t = n1 / n2 * (1.0 - cos_i * cos_i).sqrt();
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let rs = ((n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)).powi(2);
        let rp = ((n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i)).powi(2);
        (rs, rp)
    }

    #[test]
    fn reflected_light_is_polarized_as_fresnel_says_at_every_angle() {
        for deg in 0..90 {
            let cos_i = (deg as f64).to_radians().cos();
            let m = dielectric_reflection(cos_i, 1.0, GLASS);
            let out = m * unpolarized();
            let (rs, rp) = rs_rp(cos_i, 1.0, GLASS);
            let r = 0.5 * (rs + rp);
            assert!((out.x - r).abs() < 1e-12, "{deg}°");
            // Degree of linear polarization (Rs − Rp)/(Rs + Rp), s (x) preferred.
            let dolp = (rs - rp) / (rs + rp);
            assert!((degree_linear(out) - dolp).abs() < 1e-12, "{deg}°");
            assert!(out.y >= -1e-15 && out.z == 0.0 && out.w == 0.0, "{deg}°");
            // Transmission: what reflection leaves, its first element 1 − R.
            let t = dielectric_transmission(cos_i, 1.0, GLASS) * unpolarized();
            assert!((t.x - (1.0 - r)).abs() < 1e-12, "{deg}°");
            assert!((t.y + out.y).abs() < 1e-12, "{deg}°: Ts − Tp = −(Rs − Rp)");
        }
    }

    #[test]
    fn brewsters_reflection_is_s_polarized_only() {
        for (n1, n2) in [(1.0, GLASS), (GLASS, 1.0), (1.0, 2.4), (1.33, 1.7)] {
            let brewster = (n2 / n1).atan();
            let m = dielectric_reflection(brewster.cos(), n1, n2);
            // p light (S1 = −1) is not reflected at all.
            let p = m * DVec4::new(1.0, -1.0, 0.0, 0.0);
            assert!(p.length() < 1e-12, "{n1} → {n2}: {p}");
            // Unpolarized light comes back wholly s polarized.
            let s = m * unpolarized();
            assert!((degree_linear(s) - 1.0).abs() < 1e-12, "{n1} → {n2}");
        }
    }

    #[test]
    fn total_internal_reflection_keeps_all_light_and_retards_p_as_born_and_wolf_say() {
        let (n1, n2) = (GLASS, 1.0);
        let n = n2 / n1;
        for deg in [42.0, 45.0, 50.0, 54.0, 60.0, 75.0, 89.0] {
            let theta = f64::to_radians(deg);
            let (sin, cos) = theta.sin_cos();
            let m = dielectric_reflection(cos, n1, n2);
            let total = m * unpolarized();
            assert!(
                (total.x - 1.0).abs() < 1e-12 && total.y.abs() < 1e-12,
                "{deg}°"
            );
            // Born & Wolf (§1.5.4, eq. 60): tan(δ/2) = cos θ √(sin²θ − n²)/sin²θ, δ the
            // phase of r_s less that of r_p (their r_p is ours).
            let delta = 2.0 * (cos * (sin * sin - n * n).sqrt() / (sin * sin)).atan();
            let a = Amplitudes::new(cos, Complex64::new(n, 0.0));
            let [rs, rp] = a.reflected;
            assert!((rs.norm() - 1.0).abs() < 1e-12 && (rp.norm() - 1.0).abs() < 1e-12);
            let ours = (rs * rp.conj()).arg();
            assert!((ours - delta).abs() < 1e-12, "{deg}°: {ours} {delta}");
            // No light crosses.
            assert_eq!(dielectric_transmission(cos, n1, n2), DMat4::ZERO, "{deg}°");
            // The retardance shows in the matrix: +45° linear light leaves with S2 = cos δ
            // and S3 = sin δ.
            let out = m * DVec4::new(1.0, 0.0, 1.0, 0.0);
            let want = DVec4::new(1.0, 0.0, delta.cos(), delta.sin());
            assert!((out - want).length() < 1e-12, "{deg}°: {out}");
        }
    }

    #[test]
    fn the_conductors_matrix_is_complex_fresnel_and_reduces_to_a_dielectric() {
        for (eta, k) in [(0.2, 3.0), (1.1, 2.5), (2.9, 3.1), (0.05, 8.0)] {
            for deg in [0.0, 20.0, 45.0, 70.0, 85.0, 89.5] {
                let cos = f64::to_radians(deg).cos();
                let m = conductor_reflection(cos, eta, k);
                // Complex Fresnel's powers written out on their own (Born & Wolf §14.2; pbrt-v3's
                // FrConductor).
                let (c2, s2) = (cos * cos, 1.0 - cos * cos);
                let t0 = eta * eta - k * k - s2;
                let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
                let a = (0.5 * (a2b2 + t0)).sqrt();
                let rs = (a2b2 + c2 - 2.0 * a * cos) / (a2b2 + c2 + 2.0 * a * cos);
                let rp = rs * (c2 * a2b2 + s2 * s2 - 2.0 * a * cos * s2)
                    / (c2 * a2b2 + s2 * s2 + 2.0 * a * cos * s2);
                let out = m * unpolarized();
                assert!(
                    (out.x - 0.5 * (rs + rp)).abs() < 1e-12,
                    "{eta}+{k}i at {deg}°"
                );
                assert!(
                    (out.y - 0.5 * (rs - rp)).abs() < 1e-12,
                    "{eta}+{k}i at {deg}°"
                );
            }
        }
        // k = 0: the dielectric's.
        let cos = 0.6;
        let d = dielectric_reflection(cos, 1.0, 1.7);
        let c = conductor_reflection(cos, 1.7, 0.0);
        assert!((d - c).abs_diff_eq(DMat4::ZERO, 1e-15));
    }

    #[test]
    fn a_mirror_at_normal_incidence_turns_circular_light_over() {
        let m = dielectric_reflection(1.0, 1.0, GLASS);
        let r = ((GLASS - 1.0) / (GLASS + 1.0)).powi(2);
        let out = m * DVec4::new(1.0, 0.0, 0.0, 1.0);
        assert!(
            (out - DVec4::new(r, 0.0, 0.0, -r)).length() < 1e-15,
            "{out}"
        );
        let out = perfect_mirror() * DVec4::new(1.0, 0.0, 1.0, 0.0);
        assert_eq!(out, DVec4::new(1.0, 0.0, -1.0, 0.0));
        // A perfect conductor is the limit of a conductor of large k.
        let limit = conductor_reflection(1.0, 1.0, 1e9);
        assert!(limit.abs_diff_eq(perfect_mirror(), 1e-8));
    }

    #[test]
    fn malus_law_and_a_quarter_wave_plate() {
        let first = linear_polarizer(0.0) * unpolarized();
        assert!((first - DVec4::new(0.5, 0.5, 0.0, 0.0)).length() < 1e-15);
        for deg in (0..=180).step_by(15) {
            let theta = f64::to_radians(deg as f64);
            let second = linear_polarizer(theta) * first;
            let want = 0.5 * theta.cos().powi(2);
            assert!((second.x - want).abs() < 1e-15, "{deg}°");
            // What passes is polarized along the second axis.
            let (sin2, cos2) = (2.0 * theta).sin_cos();
            let along = DVec4::new(1.0, cos2, sin2, 0.0) * want;
            assert!((second - along).length() < 1e-15, "{deg}°: {second}");
        }
        let quarter = std::f64::consts::FRAC_PI_2;
        for (axis, sign) in [(45.0, 1.0), (-45.0, -1.0)] {
            let circular = linear_retarder(quarter, f64::to_radians(axis)) * first;
            assert!(
                (circular.w / circular.x - sign).abs() < 1e-12,
                "{axis}°: {circular}"
            );
            assert!(circular.y.abs() < 1e-12 && circular.z.abs() < 1e-12);
        }
        // A half-wave plate at 22.5° turns x-linear light to 45°.
        let half = linear_retarder(std::f64::consts::PI, f64::to_radians(22.5)) * first;
        assert!(
            (half - DVec4::new(0.5, 0.0, 0.5, 0.0)).length() < 1e-12,
            "{half}"
        );
    }

    #[test]
    fn a_basis_change_is_a_rotation_of_the_linear_part() {
        let k = DVec3::new(0.3, -0.4, 0.5).normalize();
        let light = DVec4::new(1.0, 0.6, 0.0, 0.3);
        let x = k.any_orthonormal_vector();
        let y = k.cross(x);
        let in_basis = |from: DVec3, to: DVec3, v: DVec4| {
            let (turn, axis) = basis_change(k, from, to).unwrap();
            (turn * v, axis)
        };
        // Linear along the old x is linear across the new x.
        let (turned, _) = in_basis(x, y, light);
        assert!((turned - DVec4::new(1.0, -0.6, 0.0, 0.3)).length() < 1e-12);
        let (diagonal, axis) = in_basis(x, x + y, light);
        assert!((diagonal - DVec4::new(1.0, 0.0, -0.6, 0.3)).length() < 1e-12);
        let (back, axis) = in_basis(axis, x, diagonal);
        assert!((back - light).length() < 1e-12);
        assert!((axis - x).length() < 1e-12);
        // Along k, or not finite: no basis.
        assert_eq!(basis_change(k, x, k), None);
        assert_eq!(basis_change(k, x, DVec3::new(f64::NAN, 0.0, 0.0)), None);
    }

    /// A thin pane's matrices against the orders of reflection summed one by one (each order's
    /// Jones amplitudes from the interface's r and t, t·t′ = 1 − r², r′ = −r; until they fall below 1e-17):
    /// 1e-12, for panes denser and less dense than their surroundings (the latter beyond its
    /// critical angle too); reflection and transmission add to 1 for each polarization; square
    /// on 2R/(1 + R); an index equal to the surroundings' passes everything.
    #[test]
    fn a_thin_pane_sums_its_internal_reflections() {
        for eta in [1.5, 2.4, 1.0 / 1.33, 1.0] {
            for i in 1..=200 {
                let cos = i as f64 / 200.0;
                let [reflection, transmission] = thin_pane(cos, eta);
                let a = Amplitudes::new(cos, Complex64::new(eta, 0.0));
                let (mut rj, mut tj) = (Vec::new(), Vec::new());
                rj.push(a.reflected);
                if a.eta_cos_t.im.abs() < 1e-12 {
                    let [rs, rp] = a.reflected.map(|r| r.re);
                    let (ts, tp) = (1.0 - rs * rs, 1.0 - rp * rp);
                    let largest = rs.abs().max(rp.abs());
                    for e in (0..).step_by(2).take_while(|&e| largest.powi(e) > 1e-17) {
                        tj.push([ts * rs.powi(e), tp * rp.powi(e)].map(|v| Complex64::new(v, 0.0)));
                        rj.push(
                            [-ts * rs.powi(e + 1), -tp * rp.powi(e + 1)]
                                .map(|v| Complex64::new(v, 0.0)),
                        );
                    }
                }
                let sum = |orders: &[[Complex64; 2]]| {
                    orders
                        .iter()
                        .fold(DMat4::ZERO, |m, &[s, p]| m + interface(s, p, 1.0).unwrap())
                };
                for (name, closed, summed) in [
                    ("reflection", reflection, sum(&rj)),
                    ("transmission", transmission, sum(&tj)),
                ] {
                    assert!(
                        closed.abs_diff_eq(summed, 1e-12),
                        "η {eta}, cos {cos}, {name}: {closed} against {summed}"
                    );
                }
                let (x, y) = (DVec4::X + DVec4::Y, DVec4::X - DVec4::Y);
                for polarized in [x, y] {
                    let kept = (reflection * polarized).x + (transmission * polarized).x;
                    assert!((kept - 1.0).abs() < 1e-12, "η {eta}, cos {cos}: {kept}");
                }
            }
            let r = ((eta - 1.0) / (eta + 1.0)).powi(2);
            assert!((thin_pane(1.0, eta)[0].col(0).x - 2.0 * r / (1.0 + r)).abs() < 1e-15);
        }
        assert!(thin_pane(0.3, 1.0)[1].abs_diff_eq(DMat4::IDENTITY, 1e-15));
    }

    /// Rayleigh's matrix against the dipole's field computed on its own: a field (Ex, Ey) in
    /// the basis (x, k × x) of light along k drives a dipole p = E, which radiates along k′ the
    /// field p − (p·k′)k′; its Stokes vector in the basis (s, k′ × s) of the scattering plane,
    /// times 3/(8π), is the matrix times the incident Stokes vector in (s, k × s), to 1e-12,
    /// for linear, elliptical and circular fields and scattering angles from 0.5° to 179.5°.
    /// Unpolarized light leaves with S1/S0 = sin²θ/(1 + cos²θ), and M00 is the phase function.
    #[test]
    fn rayleighs_matrix_is_the_dipoles_field() {
        let stokes = |ex: Complex64, ey: Complex64| {
            let z = ex * ey.conj();
            DVec4::new(
                ex.norm_sqr() + ey.norm_sqr(),
                ex.norm_sqr() - ey.norm_sqr(),
                2.0 * z.re,
                2.0 * z.im,
            )
        };
        let k = DVec3::new(0.3, -0.4, 0.866).normalize();
        let fields = [
            (Complex64::new(1.0, 0.0), Complex64::new(0.0, 0.0)),
            (Complex64::new(0.0, 0.0), Complex64::new(1.0, 0.0)),
            (Complex64::new(0.6, 0.0), Complex64::new(0.8, 0.0)),
            (Complex64::new(0.5, 0.2), Complex64::new(-0.3, 0.7)),
            (Complex64::new(1.0, 0.0), Complex64::new(0.0, 1.0)),
        ];
        for deg in [0.5, 10.0, 45.0, 90.0, 120.0, 179.5] {
            for azimuth in [0.0, 1.0, 2.5] {
                let theta = f64::to_radians(deg);
                let (a, b) = (
                    k.any_orthonormal_vector(),
                    k.cross(k.any_orthonormal_vector()),
                );
                let across = (a * f64::cos(azimuth) + b * f64::sin(azimuth)).normalize();
                let out = (k * theta.cos() + across * theta.sin()).normalize();
                let s = k.cross(out).normalize();
                let (y_in, y_out) = (k.cross(s), out.cross(s));
                let m = rayleigh(k.dot(out));
                for &(ex, ey) in &fields {
                    let p = |axis: DVec3| ex * axis.dot(s) + ey * axis.dot(y_in);
                    // The field's Cartesian components, the radiated field, and its (s, p) parts.
                    let e = [DVec3::X, DVec3::Y, DVec3::Z].map(p);
                    let along = e[0] * out.x + e[1] * out.y + e[2] * out.z;
                    let radiated = [0, 1, 2].map(|i| e[i] - along * out[i]);
                    let on = |axis: DVec3| {
                        radiated[0] * axis.x + radiated[1] * axis.y + radiated[2] * axis.z
                    };
                    let want = stokes(on(s), on(y_out)) * (3.0 / (8.0 * std::f64::consts::PI));
                    let got = m * stokes(ex, ey);
                    assert!(
                        got.abs_diff_eq(want, 1e-12),
                        "{deg}°, ({ex}, {ey}): {got} against {want}"
                    );
                }
            }
            let c = f64::to_radians(deg).cos();
            let v = rayleigh(c) * unpolarized();
            let phase = 3.0 * (1.0 + c * c) / (16.0 * std::f64::consts::PI);
            assert!(
                (v.x - phase).abs() < 1e-15 * phase,
                "{deg}°: {} against {phase}",
                v.x
            );
            let dolp = (1.0 - c * c) / (1.0 + c * c);
            assert!(
                (v.y / v.x - dolp).abs() < 1e-12,
                "{deg}°: S1/S0 {}",
                v.y / v.x
            );
        }
    }
}
