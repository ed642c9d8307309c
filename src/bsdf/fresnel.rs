//! The Fresnel equations: unpolarised reflectance at a smooth interface between dielectrics
//! and at a conductor of complex index η + ik, with the mirror and refraction directions.

use crate::color::Rgb;
use glam::DVec3;

/// Unpolarised Fresnel reflectance for a ray from index `n1` to `n2` with cos θi = `cos_i`
/// (> 0); 1 under total internal reflection. Also returns cos θt.
pub fn dielectric(cos_i: f64, n1: f64, n2: f64) -> (f64, f64) {
    match amplitudes(cos_i, n1, n2) {
        Some(a) => (0.5 * (a.rs * a.rs + a.rp * a.rp), a.cos_t),
        None => (1.0, 0.0),
    }
}

/// The reflected amplitudes r_s, r_p of a ray from index `n1` to `n2` with cos θi = `cos_i`
/// (> 0), and cos θt (Born and Wolf's, in the module's s/p conventions).
struct Amplitudes {
    rs: f64,
    rp: f64,
    cos_t: f64,
}

/// [`Amplitudes`] at cos θi = `cos_i` from `n1` to `n2`; None under total internal reflection.
fn amplitudes(cos_i: f64, n1: f64, n2: f64) -> Option<Amplitudes> {
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(Amplitudes {
        rs: (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t),
        rp: (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t),
        cos_t,
    })
}

/// 1 − [`dielectric`]'s reflectance, written without the cancellation of 1 − R: with
/// 1 − r² = 4ab/(a + b)² for each polarisation, T = 2 n1 n2 cos θi cos θt (1/(n1 cos θi +
/// n2 cos θt)² + 1/(n2 cos θi + n1 cos θt)²); 0 under total internal reflection. At grazing
/// incidence, where R → 1, it keeps its digits.
pub fn dielectric_transmittance(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let (r, cos_t) = dielectric(cos_i, n1, n2);
    if r >= 1.0 {
        return 0.0;
    }
    let (s, p) = (n1 * cos_i + n2 * cos_t, n2 * cos_i + n1 * cos_t);
    2.0 * n1 * n2 * cos_i * cos_t * (1.0 / (s * s) + 1.0 / (p * p))
}

/// Unpolarised reflectance of a thin dielectric pane of index `eta` relative to the medium
/// around it at cos θi = `cos_i` ∈ (0, 1], its internal reflections summed for s and p light
/// apart: ½(2R_s/(1 + R_s) + 2R_p/(1 + R_p)), each R the outer face's (1 where it reflects
/// totally). pbrt-v4 and Mitsuba 3 sum them for the unpolarised R, 2R/(1 + R): the same square
/// on, more than this obliquely (0.1638 against 0.1519 at 60° for η = 1.5).
pub fn thin_dielectric(cos_i: f64, eta: f64) -> f64 {
    let Some(a) = amplitudes(cos_i, 1.0, eta) else {
        return 1.0;
    };
    let summed = |r: f64| 2.0 * r * r / (1.0 + r * r);
    0.5 * (summed(a.rs) + summed(a.rp))
}

/// Unpolarised reflectance of a conductor of complex index `eta` + i`k` relative to the
/// medium the light arrives in, at cos θi = `cos_i` ∈ [0, 1] (the exact form for a
/// conductor: Born and Wolf §14.2; written as in Pharr, Jakob and Humphreys §8.2).
pub fn conductor(cos_i: f64, eta: f64, k: f64) -> f64 {
    let c2 = cos_i.clamp(0.0, 1.0).powi(2);
    let s2 = 1.0 - c2;
    let (e2, k2) = (eta * eta, k * k);
    let t0 = e2 - k2 - s2;
    let a2b2 = (t0 * t0 + 4.0 * e2 * k2).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let t1 = a2b2 + c2;
    let t2 = 2.0 * cos_i.clamp(0.0, 1.0) * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * a2b2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    let r = 0.5 * (rs + rp);
    if r.is_finite() {
        r.clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// A conductor's reflectance per channel.
pub fn conductor_rgb(cos_i: f64, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        conductor(cos_i, eta.0.x, k.0.x),
        conductor(cos_i, eta.0.y, k.0.y),
        conductor(cos_i, eta.0.z, k.0.z),
    )
}

/// Mirror reflection of direction `d` about unit normal `n`.
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refraction of unit `d` through a surface with unit normal `n` facing the incident side
/// (d·n < 0), from `n1` to `n2`, given cos θt from [`dielectric`].
pub fn refract(d: DVec3, n: DVec3, n1: f64, n2: f64, cos_t: f64) -> DVec3 {
    let eta = n1 / n2;
    let cos_i = -d.dot(n);
    (eta * d + (eta * cos_i - cos_t) * n).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cancellation-free transmittance is 1 − R (1e-15 where R is not near 1).
    #[test]
    fn transmittance_is_one_minus_reflectance() {
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.33, 2.4)] {
            for i in 0..=1000 {
                let cos = i as f64 / 1000.0;
                let (r, _) = dielectric(cos.max(1e-9), n1, n2);
                let t = dielectric_transmittance(cos.max(1e-9), n1, n2);
                assert!(
                    (t - (1.0 - r)).abs() < 1e-15,
                    "{n1}→{n2} cos {cos}: {t} vs {}",
                    1.0 - r
                );
            }
        }
    }

    /// The polarized transport's Mueller matrices pass unpolarized light as these scalar terms
    /// do (their first elements), at every angle: a dielectric's reflection and transmission
    /// both ways, thin panes' reflection, and conductors'.
    #[test]
    fn the_mueller_matrices_first_elements_are_these_terms() {
        use crate::polarization::mueller;
        for i in 0..=1000 {
            let cos = (i as f64 / 1000.0).max(1e-9);
            for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.33, 2.4)] {
                let (r, _) = dielectric(cos, n1, n2);
                let m = mueller::dielectric_reflection(cos, n1, n2);
                assert!((m.col(0).x - r).abs() < 1e-12, "{n1}→{n2} cos {cos}");
                let t = mueller::dielectric_transmission(cos, n1, n2);
                let want = dielectric_transmittance(cos, n1, n2);
                assert!((t.col(0).x - want).abs() < 1e-12, "{n1}→{n2} cos {cos}");
            }
            for eta in [1.5, 2.4, 1.0 / 1.33, 1.0] {
                let m = mueller::thin_pane(cos, eta)[0];
                assert!(
                    (m.col(0).x - thin_dielectric(cos, eta)).abs() < 1e-12,
                    "pane η {eta} cos {cos}"
                );
            }
            for (eta, k) in [(0.2, 3.0), (1.1, 2.5), (2.9, 3.1), (0.05, 8.0)] {
                let m = mueller::conductor_reflection(cos, eta, k);
                assert!(
                    (m.col(0).x - conductor(cos, eta, k)).abs() < 1e-12,
                    "{eta}+{k}i"
                );
            }
        }
    }

    /// With k = 0 the conductor's formula is the dielectric's (an independent form of the
    /// same equations); at normal incidence it is ((η−1)² + k²)/((η+1)² + k²).
    #[test]
    fn the_conductor_formula_reduces_to_known_cases() {
        for eta in [1.2, 1.5, 2.4] {
            for i in 0..=100 {
                let cos = i as f64 / 100.0;
                let (r, _) = dielectric(cos.max(1e-9), 1.0, eta);
                let c = conductor(cos.max(1e-9), eta, 0.0);
                assert!((r - c).abs() < 1e-12, "η {eta} cos {cos}: {r} vs {c}");
            }
        }
        for (eta, k) in [(0.2, 3.0), (1.1, 6.8), (0.05, 4.2)] {
            let r0 = ((eta - 1.0f64).powi(2) + k * k) / ((eta + 1.0f64).powi(2) + k * k);
            assert!((conductor(1.0, eta, k) - r0).abs() < 1e-12);
            assert_eq!(conductor(0.0, eta, k), 1.0);
        }
    }
}
