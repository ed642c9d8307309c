//! The shape of a light's emission spectrum, and the wavelength of a photon drawn from it.
//! A light's power (or radiance, intensity, irradiance) keeps its meaning and units; the
//! spectrum only says how that power is spread over wavelength, so a photon drawn from it
//! carries the light's full power and a receiver band collects the photons whose wavelength
//! falls in it (in expectation, the band's share of the power).

use super::{LAMBDA_MAX, LAMBDA_MIN};
use crate::color::Rgb;

/// A spectral shape over [`LAMBDA_MIN`, `LAMBDA_MAX`], any scale.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// CIE illuminant D65, sRGB's white: the default of every light (white light in the
    /// images is D65).
    D65,
    /// Equal energy per nm (CIE illuminant E).
    Equal,
    /// A Gaussian line of an LED: peak and full width at half maximum, nm.
    Gaussian {
        /// Peak wavelength, nm.
        peak: f64,
        /// Full width at half maximum, nm.
        fwhm: f64,
    },
    /// Planck's law at a temperature, K.
    Blackbody {
        /// Temperature, K.
        kelvin: f64,
    },
    /// A measured spectrum: (nm, power) nodes, rising in wavelength, the power ≥ 0; linear
    /// between them and 0 beyond them, as pbrt-v4's piecewise-linear spectra.
    Table(std::sync::Arc<[(f64, f64)]>),
}

/// A Gaussian's standard deviation from its full width at half maximum.
fn sigma(fwhm: f64) -> f64 {
    fwhm / (8.0 * std::f64::consts::LN_2).sqrt()
}

/// ∫ from a to b of the standard normal density, a ≤ b, accurate in both tails (differences
/// of erfc on the side away from the peak, never of two numbers near 1).
fn normal_mass(a: f64, b: f64) -> f64 {
    let r = std::f64::consts::FRAC_1_SQRT_2;
    if a >= 0.0 {
        0.5 * (libm::erfc(a * r) - libm::erfc(b * r))
    } else if b <= 0.0 {
        0.5 * (libm::erfc(-b * r) - libm::erfc(-a * r))
    } else {
        1.0 - 0.5 * (libm::erfc(-a * r) + libm::erfc(b * r))
    }
}

impl Shape {
    /// Relative spectral power at `nm` (shape only; any positive scale; a Gaussian's is its
    /// density, so that [`Shape::power`] and [`Shape::mass`] agree).
    pub fn power(&self, nm: f64) -> f64 {
        match *self {
            Shape::Table(ref nodes) => table_at(nodes, nm),
            Shape::D65 => super::colour::d65(nm),
            Shape::Equal => 1.0,
            Shape::Gaussian { peak, fwhm } => {
                let s = sigma(fwhm);
                (-0.5 * ((nm - peak) / s).powi(2)).exp() / (s * (2.0 * std::f64::consts::PI).sqrt())
            }
            Shape::Blackbody { kelvin } => {
                // Planck: M ∝ λ⁻⁵ / (exp(hc/λkT) − 1), hc/k = 1.438 776 877e7 nm·K (CODATA 2018).
                let x = 1.438_776_877e7 / (nm * kelvin);
                (nm * 1e-3).powi(-5) / x.exp_m1()
            }
        }
    }

    /// The power between `lo` and `hi` nm (lo ≤ hi, [`Shape::power`]'s scale): exact for a
    /// Gaussian — so a line far narrower than a nanometre keeps its power — and the midpoint
    /// rule for the smooth shapes.
    pub fn mass(&self, lo: f64, hi: f64) -> f64 {
        match *self {
            Shape::Gaussian { peak, fwhm } => {
                let s = sigma(fwhm);
                normal_mass((lo - peak) / s, (hi - peak) / s)
            }
            Shape::Table(ref nodes) => table_mass(nodes, lo, hi),
            Shape::D65 | Shape::Equal | Shape::Blackbody { .. } => {
                self.power(0.5 * (lo + hi)) * (hi - lo)
            }
        }
    }
}

/// A table's power at `nm`: linear between its nodes, 0 beyond them.
fn table_at(nodes: &[(f64, f64)], nm: f64) -> f64 {
    let k = nodes.partition_point(|&(x, _)| x <= nm);
    match (k.checked_sub(1).map(|i| nodes[i]), nodes.get(k)) {
        (Some((x0, y0)), Some(&(x1, y1))) => y0 + (y1 - y0) * (nm - x0) / (x1 - x0),
        (Some((x0, y0)), None) if nm == x0 => y0,
        (Some(_), None) | (None, Some(_)) | (None, None) => 0.0,
    }
}

/// A table's power between `lo` and `hi` nm (lo ≤ hi): the exact integral of its linear
/// pieces (trapezoids between the nodes within, and the pieces cut at `lo` and `hi`), so a
/// line a few nanometres wide keeps its power in the 1 nm bins.
fn table_mass(nodes: &[(f64, f64)], lo: f64, hi: f64) -> f64 {
    // Beyond the rows the power is 0: a step at each end, not a ramp.
    let (Some(&(first, _)), Some(&(last, _))) = (nodes.first(), nodes.last()) else {
        return 0.0;
    };
    let (lo, hi) = (lo.max(first), hi.min(last));
    if hi <= lo {
        return 0.0;
    }
    let mut cuts = vec![lo];
    cuts.extend(nodes.iter().map(|&(x, _)| x).filter(|&x| x > lo && x < hi));
    cuts.push(hi);
    cuts.windows(2)
        .map(|w| 0.5 * (table_at(nodes, w[0]) + table_at(nodes, w[1])) * (w[1] - w[0]))
        .sum()
}

/// Bins of the tabulated spectrum: 1 nm wide.
const BINS: usize = (LAMBDA_MAX - LAMBDA_MIN) as usize;

/// A light's spectrum ready for sampling: the shape's power at each 1 nm bin's centre as a
/// piecewise-constant density, and its cumulative sum.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// The shape.
    pub shape: Shape,
    /// Cumulative power at the bins' upper edges, normalised to end at 1.
    cdf: Vec<f64>,
    /// The linear sRGB in which a unit of its power appears (see [`Spectrum::colour`]).
    colour: Rgb,
    /// The luminance of a unit of its power (see [`Spectrum::luminance`]).
    luminance: f64,
}

impl Spectrum {
    /// The spectrum of `shape`, or why not (no power in the visible range).
    pub fn new(shape: Shape) -> Result<Self, String> {
        let mut cdf = Vec::with_capacity(BINS);
        let mut sum = 0.0;
        for i in 0..BINS {
            let lo = LAMBDA_MIN + i as f64;
            sum += shape.mass(lo, lo + 1.0);
            cdf.push(sum);
        }
        if !(sum > 0.0 && sum.is_finite()) {
            return Err(format!(
                "the spectrum has no power between {LAMBDA_MIN} and {LAMBDA_MAX} nm"
            ));
        }
        cdf.iter_mut().for_each(|c| *c /= sum);
        // Its power by the same 1 nm node sums as the colour's (each node the power of the
        // nanometre around it), so unit-power D65 is white and a line narrower than a node
        // keeps its colour.
        let node = |nm: f64| shape.mass(nm - 0.5, nm + 0.5);
        let nodes: f64 = (LAMBDA_MIN as usize..=LAMBDA_MAX as usize)
            .map(|nm| node(nm as f64))
            .sum();
        let colour = super::colour::colour_of(|nm| node(nm) / nodes);
        let luminance = super::colour::luminance_of(|nm| node(nm) / nodes);
        Ok(Self {
            shape,
            cdf,
            colour,
            luminance,
        })
    }

    /// The linear sRGB in which one unit of its power appears in an image (unit-power D65 is
    /// (1, 1, 1)); a narrow line outside sRGB's gamut has negative channels.
    pub fn colour(&self) -> Rgb {
        self.colour
    }

    /// The luminance (CIE 1931 Y) of one unit of its power, relative to unit-power D65's (1).
    pub fn luminance(&self) -> f64 {
        self.luminance
    }

    /// The wavelength (nm) for uniform `u` in [0, 1): inverse of the cumulative distribution
    /// — within its 1 nm bin linear for the smooth shapes, and for a Gaussian the exact
    /// inverse (bisection of its CDF to rounding), so a line narrower than the bin is
    /// sampled as itself.
    pub fn sample(&self, u: f64) -> f64 {
        let i = self.cdf.partition_point(|&c| c <= u).min(BINS - 1);
        let below = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let t = ((u - below) / (self.cdf[i] - below)).clamp(0.0, 1.0);
        let lo = LAMBDA_MIN + i as f64;
        if !matches!(self.shape, Shape::Gaussian { .. }) {
            return lo + t;
        }
        // The share t of the bin's mass, found in the bin.
        let target = t * self.shape.mass(lo, lo + 1.0);
        let (mut a, mut b) = (lo, lo + 1.0);
        for _ in 0..64 {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                break;
            }
            if self.shape.mass(lo, m) < target {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    }

    /// Probability density (1/nm) of [`Spectrum::sample`] at `nm`.
    pub fn pdf(&self, nm: f64) -> f64 {
        if !(LAMBDA_MIN..LAMBDA_MAX).contains(&nm) {
            return 0.0;
        }
        let i = (nm - LAMBDA_MIN) as usize;
        let bin = self.cdf[i] - if i == 0 { 0.0 } else { self.cdf[i - 1] };
        match self.shape {
            // Within the bin, the Gaussian's own density, scaled as the bin is.
            Shape::Gaussian { .. } => {
                let lo = LAMBDA_MIN + i as f64;
                let mass = self.shape.mass(lo, lo + 1.0);
                if mass > 0.0 {
                    bin * self.shape.power(nm) / mass
                } else {
                    0.0
                }
            }
            Shape::D65 | Shape::Equal | Shape::Blackbody { .. } | Shape::Table(_) => bin,
        }
    }

    /// The share of the power between `lo` and `hi` nm.
    pub fn fraction(&self, lo: f64, hi: f64) -> f64 {
        if let Shape::Gaussian { .. } = self.shape {
            let (lo, hi) = (lo.max(LAMBDA_MIN), hi.min(LAMBDA_MAX));
            return if hi > lo {
                self.shape.mass(lo, hi) / self.shape.mass(LAMBDA_MIN, LAMBDA_MAX)
            } else {
                0.0
            };
        }
        let cdf_at = |nm: f64| {
            let x = (nm - LAMBDA_MIN).clamp(0.0, BINS as f64);
            let i = x as usize;
            let below = if i == 0 { 0.0 } else { self.cdf[i - 1] };
            below
                + if i < BINS {
                    (x - i as f64) * (self.cdf[i] - below)
                } else {
                    0.0
                }
        };
        cdf_at(hi) - cdf_at(lo)
    }
}

impl Spectrum {
    /// D65, shared: what every light emits unless it says otherwise, and the environment.
    pub fn white() -> &'static Spectrum {
        static WHITE: std::sync::LazyLock<Spectrum> =
            std::sync::LazyLock::new(|| Spectrum::new(Shape::D65).expect("D65 has power"));
        &WHITE
    }
}

impl Default for Spectrum {
    fn default() -> Self {
        Self::white().clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// χ² of 200 000 sampled wavelengths in 47 bins of 10 nm against the pdf's bin masses,
    /// for each shape. With 46 degrees of freedom the 0.1 % critical value is 81.4: a
    /// correct sampler fails once in a thousand seeds (the seed is fixed).
    #[test]
    fn sampled_wavelengths_follow_the_pdf() {
        let shapes = [
            Shape::D65,
            Shape::Equal,
            Shape::Gaussian {
                peak: 450.0,
                fwhm: 20.0,
            },
            Shape::Blackbody { kelvin: 3000.0 },
            Shape::Table(
                vec![
                    (400.0, 0.2),
                    (520.0, 1.0),
                    (523.0, 5.0),
                    (526.0, 1.0),
                    (700.0, 0.5),
                ]
                .into(),
            ),
        ];
        for shape in shapes {
            let e = Spectrum::new(shape.clone()).unwrap();
            let n = 200_000;
            let mut counts = [0u32; 47];
            let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(7);
            for _ in 0..n {
                let nm = e.sample(rng.gen());
                assert!((LAMBDA_MIN..LAMBDA_MAX).contains(&nm));
                counts[((nm - LAMBDA_MIN) / 10.0) as usize] += 1;
            }
            let (mut chi2, mut dof) = (0.0, 0usize);
            for (k, &c) in counts.iter().enumerate() {
                let lo = LAMBDA_MIN + 10.0 * k as f64;
                let expected = n as f64 * e.fraction(lo, lo + 10.0);
                // Bins expecting fewer than 5 samples are outside χ²'s validity: they must be
                // (nearly) empty instead.
                if expected < 5.0 {
                    assert!((c as f64) < expected + 12.0, "{shape:?} bin {k}: {c}");
                    continue;
                }
                chi2 += (c as f64 - expected).powi(2) / expected;
                dof += 1;
            }
            let critical = dof as f64 + 3.1 * (2.0 * dof as f64).sqrt() + 2.0;
            assert!(chi2 < critical, "{shape:?}: χ² {chi2} over {dof} bins");
        }
    }

    /// The pdf integrates to 1 and the Gaussian's mass within one FWHM of its peak is
    /// erf(√(ln 2)) = 0.7610 (exact for a Gaussian), to the 1 nm binning's 1e-3.
    #[test]
    fn pdf_and_band_fractions() {
        let e = Spectrum::new(Shape::Gaussian {
            peak: 600.0,
            fwhm: 30.0,
        })
        .unwrap();
        let total: f64 = (0..BINS).map(|i| e.pdf(LAMBDA_MIN + i as f64 + 0.5)).sum();
        assert!((total - 1.0).abs() < 1e-12);
        assert!((e.fraction(585.0, 615.0) - 0.760_968_7).abs() < 1e-3);
        let equal = Spectrum::new(Shape::Equal).unwrap();
        assert!((equal.fraction(400.0, 447.0) - 0.1).abs() < 1e-12);
        assert_eq!(Spectrum::default().shape, Shape::D65);
        assert!((Spectrum::white().colour().0 - glam::DVec3::ONE).length() < 1e-12);
        // Wien: a 5800 K blackbody peaks at 2.897 771 955e6 nm·K / 5800 K = 499.6 nm.
        let sun = Shape::Blackbody { kelvin: 5800.0 };
        let peak = (400..700).max_by(|a, b| sun.power(*a as f64).total_cmp(&sun.power(*b as f64)));
        assert_eq!(peak, Some(500));
        assert!(Spectrum::new(Shape::Gaussian {
            peak: 2000.0,
            fwhm: 1.0
        })
        .is_err());
    }

    /// A laser line far narrower than the 1 nm table (532 nm, FWHM 0.01 nm: σ = 4.25e-3 nm)
    /// keeps its power, is sampled as itself and has the colour of its wavelength: the mean
    /// and standard deviation of 20 000 samples within 4 standard errors of 532 and σ, every
    /// sample within 6σ, the share within ±1 FWHM/2 erf(√ln 2) = 0.76097, and the colour that
    /// of a 1 nm-wide line at 532 nm (the node quadrature's) to 1e-9.
    #[test]
    fn a_line_narrower_than_a_nanometre_is_sampled_exactly() {
        let line = Spectrum::new(Shape::Gaussian {
            peak: 532.0,
            fwhm: 0.01,
        })
        .unwrap();
        let sigma = sigma(0.01);
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(3);
        let n = 20_000;
        let samples: Vec<f64> = (0..n).map(|_| line.sample(rng.gen())).collect();
        let mean = samples.iter().sum::<f64>() / n as f64;
        let sd = (samples.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        assert!(
            (mean - 532.0).abs() < 4.0 * sigma / (n as f64).sqrt(),
            "{mean}"
        );
        assert!(
            (sd / sigma - 1.0).abs() < 4.0 / (2.0 * n as f64).sqrt(),
            "{sd}"
        );
        assert!(samples.iter().all(|x| (x - 532.0).abs() < 6.0 * sigma));
        assert!((line.fraction(531.995, 532.005) - 0.760_968_7).abs() < 1e-6);
        assert!(
            (line.pdf(532.0) - 1.0 / (sigma * (2.0 * std::f64::consts::PI).sqrt())).abs()
                < 1e-6 * line.pdf(532.0)
        );
        let c = line.colour();
        assert!(c.0.is_finite());
        let nodes: f64 = 1.0; // the line's power, all in the node at 532 nm
        let expected = super::super::colour::colour_of(|nm| if nm == 532.0 { nodes } else { 0.0 });
        assert!(
            (c.0 - expected.0).length() < 1e-9 * expected.0.length(),
            "{c:?} vs {expected:?}"
        );
    }

    /// A table's power is linear between its rows and 0 beyond them, and its mass the exact
    /// integral of its pieces: a 6 nm triangle of height 4 on a floor of 1 (rows 400, 520, 523,
    /// 526, 700) holds 4·6/2 + 300·1 = 312 over 400–700, 1e-12; its 1 nm bins sum to it; the
    /// spectrum's share of 520–526 nm is that triangle's and floor's (18)/(312), 1e-12.
    #[test]
    fn a_table_spectrum_is_linear_between_its_rows() {
        let shape = Shape::Table(
            vec![
                (400.0, 1.0),
                (520.0, 1.0),
                (523.0, 5.0),
                (526.0, 1.0),
                (700.0, 1.0),
            ]
            .into(),
        );
        assert_eq!(shape.power(521.5), 3.0);
        assert_eq!(shape.power(399.0), 0.0);
        assert_eq!(shape.power(701.0), 0.0);
        assert_eq!(shape.power(700.0), 1.0);
        assert!((shape.mass(400.0, 700.0) - 312.0).abs() < 1e-12);
        let bins: f64 = (400..700)
            .map(|nm| shape.mass(nm as f64, nm as f64 + 1.0))
            .sum();
        assert!((bins - 312.0).abs() < 1e-9, "{bins}");
        let e = Spectrum::new(shape).unwrap();
        let share = e.fraction(520.0, 526.0);
        assert!((share - 18.0 / 312.0).abs() < 1e-12, "{share}");
    }
}
