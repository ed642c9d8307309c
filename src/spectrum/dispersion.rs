//! A quantity as a function of vacuum wavelength — a refractive index (the dispersion models of
//! optical catalogues and a few named materials with their published coefficients) or a
//! scattering coefficient (Ångström's power law, a table).
//!
//! Conventions: λ is given in nm and converted to µm where a model is written in µm
//! (Sellmeier, Cauchy). Glass catalogue models (Schott, Malitson) give the index relative to
//! air, as the catalogues do — the index that matters for glass in air; water's (IAPWS-fitted)
//! is relative to vacuum (the two differ by n_air − 1 ≈ 2.7·10⁻⁴).

use super::{LAMBDA_C, LAMBDA_D, LAMBDA_F};
use crate::media::MonotoneCubic;

/// A quantity over wavelength: an index n(λ), or a scattering coefficient σs(λ) (1/length).
/// `Constant` does not depend on wavelength: every wavelength shares one path through it.
#[derive(Clone, Debug)]
pub enum Dispersion {
    /// The same index at every wavelength.
    Constant(f64),
    /// Sellmeier: n² = 1 + Σ Bᵢ λ² / (λ² − Cᵢ), λ in µm, Cᵢ in µm² (pairs (Bᵢ, Cᵢ)).
    Sellmeier(Vec<(f64, f64)>),
    /// Cauchy: n = Σ Aₖ / λ^(2k), λ in µm (A, B, C, ...: n = A + B/λ² + C/λ⁴ + ...).
    Cauchy(Vec<f64>),
    /// A table of (λ nm, value), monotone cubic between the nodes, constant beyond the ends.
    Table(MonotoneCubic),
    /// Ångström's power law v = v_ref (λ_ref/λ)^α: aerosol scattering (α ≈ 0.5–2.5 for haze),
    /// Rayleigh scattering by molecules (α = 4).
    PowerLaw {
        /// v at `nm`.
        value: f64,
        /// The reference wavelength λ_ref, nm.
        nm: f64,
        /// The exponent α.
        exponent: f64,
    },
}

/// Named materials: the name a scene gives, and its Sellmeier terms (Bᵢ, Cᵢ µm²).
const NAMED: &[(&str, &[(f64, f64)])] = &[
    // Schott N-BK7, Schott optical glass data sheet (2015).
    (
        "BK7",
        &[
            (1.039_612_12, 0.006_000_698_67),
            (0.231_792_344, 0.020_017_914_4),
            (1.010_469_45, 103.560_653),
        ],
    ),
    // Schott F2, Schott optical glass data sheet (2015).
    (
        "F2",
        &[
            (1.345_333_59, 0.009_977_438_71),
            (0.209_073_176, 0.047_045_076_7),
            (0.937_357_162, 111.886_764),
        ],
    ),
    // Fused silica: I. H. Malitson, J. Opt. Soc. Am. 55, 1205 (1965), Cᵢ = (0.0684043,
    // 0.1162414, 9.896161 µm)².
    (
        "fused_silica",
        &[
            (0.696_166_3, 0.004_679_148_267_857_849),
            (0.407_942_6, 0.013_512_062_912_359_6),
            (0.897_479_4, 97.934_002_537_921),
        ],
    ),
    // Water at 20 °C: M. Daimon, A. Masumura, Appl. Opt. 46, 3811 (2007).
    (
        "water",
        &[
            (0.568_402_756_5, 0.005_101_829_712),
            (0.172_617_739_1, 0.018_211_539_36),
            (0.020_861_895_78, 0.026_207_222_93),
            (0.113_074_868_8, 10.697_927_21),
        ],
    ),
];

impl Dispersion {
    /// The material called `name` (see [`Dispersion::names`]).
    pub fn named(name: &str) -> Option<Self> {
        NAMED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, terms)| Dispersion::Sellmeier(terms.to_vec()))
    }

    /// The names [`Dispersion::named`] knows.
    pub fn names() -> impl Iterator<Item = &'static str> {
        NAMED.iter().map(|(n, _)| *n)
    }

    /// The Abbe model: the Cauchy law n = A + B/λ² through n_d with Abbe number V_d =
    /// (n_d − 1)/(n_F − n_C), the usual two-number description of a catalogue glass.
    pub fn abbe(n_d: f64, v_d: f64) -> Self {
        let inv2 = |nm: f64| 1.0 / (nm * 1e-3).powi(2);
        let b = (n_d - 1.0) / v_d / (inv2(LAMBDA_F) - inv2(LAMBDA_C));
        Dispersion::Cauchy(vec![n_d - b * inv2(LAMBDA_D), b])
    }

    /// n at vacuum wavelength `nm`.
    pub fn at(&self, nm: f64) -> f64 {
        let um2 = (nm * 1e-3).powi(2);
        match self {
            Dispersion::Constant(n) => *n,
            Dispersion::Sellmeier(terms) => {
                (1.0 + terms.iter().map(|(b, c)| b * um2 / (um2 - c)).sum::<f64>()).sqrt()
            }
            // Horner's rule in 1/λ²: no power of λ to overflow or vanish.
            Dispersion::Cauchy(a) => a.iter().rev().fold(0.0, |acc, ak| ak + acc / um2),
            Dispersion::Table(t) => t.at(nm).0,
            Dispersion::PowerLaw {
                value,
                nm: reference,
                exponent,
            } => value * (reference / nm).powf(*exponent),
        }
    }

    /// Whether n depends on wavelength (a path through it is one wavelength's only).
    pub fn is_dispersive(&self) -> bool {
        !matches!(self, Dispersion::Constant(_))
    }

    /// The smallest value over the visible range (sampled every nm; NaN if it is NaN
    /// anywhere): an index that is not positive somewhere there cannot be used.
    pub fn min_visible(&self) -> f64 {
        self.fold_visible(f64::INFINITY, f64::min)
    }

    /// The largest value over the visible range likewise (NaN if it is NaN anywhere).
    pub fn max_visible(&self) -> f64 {
        self.fold_visible(f64::NEG_INFINITY, f64::max)
    }

    /// `pick` over the values every nm of the visible range, NaN winning.
    fn fold_visible(&self, start: f64, pick: fn(f64, f64) -> f64) -> f64 {
        (super::LAMBDA_MIN as u32..=super::LAMBDA_MAX as u32)
            .map(|nm| self.at(nm as f64))
            .fold(start, |a, b| if b.is_nan() { f64::NAN } else { pick(a, b) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Published catalogue indices (5 decimals, relative to air) at the d, F and C lines:
    /// Schott data sheets for N-BK7 and F2, Heraeus/Malitson for fused silica. Tolerance
    /// 1e-5: one unit of the last published decimal (the Sellmeier fits reproduce them to
    /// a few 10⁻⁶).
    #[test]
    fn named_glasses_meet_their_catalogue_indices() {
        let published = [
            ("BK7", [1.516_80, 1.522_38, 1.514_32]),
            ("F2", [1.620_04, 1.632_08, 1.615_03]),
            ("fused_silica", [1.458_46, 1.463_13, 1.456_37]),
        ];
        for (name, n) in published {
            let d = Dispersion::named(name).unwrap();
            for (nm, want) in [LAMBDA_D, LAMBDA_F, LAMBDA_C].into_iter().zip(n) {
                let got = d.at(nm);
                assert!(
                    (got - want).abs() < 1e-5,
                    "{name} at {nm} nm: {got} vs {want}"
                );
            }
        }
    }

    /// Water against an independent formula: the IAPWS R9-97 release (Harvey et al., J. Phys.
    /// Chem. Ref. Data 27, 761 (1998)) at 20 °C, ρ = 998.2063 kg/m³, vacuum index. Tolerance
    /// 2e-5, the IAPWS formulation's own stated uncertainty in the visible at 20 °C.
    #[test]
    fn water_meets_the_iapws_formulation() {
        let iapws = |nm: f64| {
            let a = [
                0.244_257_733,
                9.746_344_76e-3,
                -3.732_349_96e-3,
                2.686_784_72e-4,
                1.589_205_70e-3,
                2.459_342_59e-3,
                0.900_704_920,
                -1.666_262_19e-2,
            ];
            let (r, t, l) = (0.998_206_3, 293.15 / 273.15, nm * 1e-3 / 0.589);
            let l2 = l * l;
            let q = r
                * (a[0]
                    + a[1] * r
                    + a[2] * t
                    + a[3] * l2 * t
                    + a[4] / l2
                    + a[5] / (l2 - 0.229_202_0f64.powi(2))
                    + a[6] / (l2 - 5.432_937f64.powi(2))
                    + a[7] * r * r);
            ((2.0 * q + 1.0) / (1.0 - q)).sqrt()
        };
        let water = Dispersion::named("water").unwrap();
        for nm in [400.0, 486.1327, 550.0, 587.5618, 656.2725, 750.0] {
            let (got, want) = (water.at(nm), iapws(nm));
            assert!(
                (got - want).abs() < 2e-5,
                "water at {nm} nm: {got} vs {want}"
            );
        }
    }

    /// The Abbe model meets its definition exactly: n(λ_d) = n_d, (n_d − 1)/(n_F − n_C) = V_d.
    #[test]
    fn abbe_model_meets_its_definition() {
        let d = Dispersion::abbe(1.5168, 64.17);
        assert!((d.at(LAMBDA_D) - 1.5168).abs() < 1e-14);
        let v = (d.at(LAMBDA_D) - 1.0) / (d.at(LAMBDA_F) - d.at(LAMBDA_C));
        assert!((v - 64.17).abs() < 1e-9, "{v}");
        // And it is close to the glass it describes (BK7): within 2e-4 over the visible,
        // the size of a two-term Cauchy law's misfit to a Sellmeier glass.
        let bk7 = Dispersion::named("BK7").unwrap();
        for nm in [420.0, 500.0, 600.0, 700.0] {
            assert!((d.at(nm) - bk7.at(nm)).abs() < 2e-4, "{nm}");
        }
    }

    #[test]
    fn constant_and_table_forms() {
        assert_eq!(Dispersion::Constant(1.5).at(400.0), 1.5);
        assert!(!Dispersion::Constant(1.5).is_dispersive());
        let t = Dispersion::Table(
            MonotoneCubic::new(vec![400.0, 700.0], vec![1.52, 1.50], false, ("nm", "n")).unwrap(),
        );
        assert!(t.is_dispersive());
        assert!((t.at(400.0) - 1.52).abs() < 1e-15 && (t.at(900.0) - 1.50).abs() < 1e-15);
        // Cauchy with λ in µm: n = 1.5 + 0.01/0.25 at 500 nm.
        assert!((Dispersion::Cauchy(vec![1.5, 0.01]).at(500.0) - 1.54).abs() < 1e-14);
    }
}
