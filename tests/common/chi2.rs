//! The χ² test of a direction sampler against its pdf: directions binned over (cos θ, φ) on
//! the whole sphere, expected counts by integrating the pdf over each bin (dω = d(cos θ) dφ),
//! bins with fewer than 5 expected merged. It fails at significance 1e-4 (critical value by
//! the Wilson–Hilferty approximation), so a correct sampler fails it once in 10⁴ seeds, and
//! the seed is fixed.

use glam::DVec3;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use std::f64::consts::{PI, TAU};

const Z_BINS: usize = 24;
const PHI_BINS: usize = 24;
const SAMPLES: usize = 400_000;

fn bin(d: DVec3) -> usize {
    let z = ((d.z + 1.0) * 0.5 * Z_BINS as f64).clamp(0.0, Z_BINS as f64 - 1.0) as usize;
    let phi = (d.y.atan2(d.x) + PI) / TAU;
    let p = (phi * PHI_BINS as f64).clamp(0.0, PHI_BINS as f64 - 1.0) as usize;
    z * PHI_BINS + p
}

/// Samples `SAMPLES` directions (None: no direction) and tests their histogram against `pdf`.
pub fn chi2(
    name: &str,
    mut sample: impl FnMut(&mut Pcg64Mcg) -> Option<DVec3>,
    pdf: impl Fn(DVec3) -> f64,
) {
    let mut rng = Pcg64Mcg::seed_from_u64(11);
    let mut observed = vec![0.0; Z_BINS * PHI_BINS];
    for _ in 0..SAMPLES {
        if let Some(d) = sample(&mut rng) {
            assert!((d.length() - 1.0).abs() < 1e-12, "{name}: not unit");
            observed[bin(d)] += 1.0;
        }
    }
    // Expected: midpoint rule over 32 × 32 sub-cells of each bin (8 × 8 misjudged the narrow
    // transmitted lobe of a rough interface into glass, α = 0.2, by enough to fail it).
    let sub = 32;
    let mut expected = vec![0.0; Z_BINS * PHI_BINS];
    for (i, e) in expected.iter_mut().enumerate() {
        let (zi, pi) = (i / PHI_BINS, i % PHI_BINS);
        let (dz, dphi) = (2.0 / Z_BINS as f64, TAU / PHI_BINS as f64);
        for a in 0..sub {
            for b in 0..sub {
                let z = -1.0 + dz * (zi as f64 + (a as f64 + 0.5) / sub as f64);
                let phi = -PI + dphi * (pi as f64 + (b as f64 + 0.5) / sub as f64);
                let s = (1.0 - z * z).max(0.0).sqrt();
                let d = DVec3::new(s * phi.cos(), s * phi.sin(), z);
                *e += pdf(d) * dz * dphi / (sub * sub) as f64 * SAMPLES as f64;
            }
        }
    }
    let (mut stat, mut dof, mut pooled_o, mut pooled_e) = (0.0, 0usize, 0.0, 0.0);
    for (o, e) in observed.iter().zip(&expected) {
        if *e < 5.0 {
            pooled_o += o;
            pooled_e += e;
        } else {
            stat += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pooled_e >= 5.0 {
        stat += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        dof += 1;
    } else {
        assert!(
            pooled_o <= 5.0 + 5.0 * pooled_e,
            "{name}: {pooled_o} samples where the pdf has ~{pooled_e}"
        );
    }
    let k = (dof - 1) as f64;
    let z = 3.719; // the 1e-4 upper quantile of the standard normal
    let critical = k * (1.0 - 2.0 / (9.0 * k) + z * (2.0 / (9.0 * k)).sqrt()).powi(3);
    println!(
        "{name}: χ² {stat:.1} on {} dof (critical {critical:.1})",
        dof - 1
    );
    assert!(
        stat < critical,
        "{name}: χ² {stat:.1} ≥ {critical:.1} on {} dof",
        dof - 1
    );
}
