//! Single scattering of direct light along a camera chain's straight stretches through
//! scattering media, by equiangular sampling (Kulla and Fajardo 2012). In a medium holding a
//! dye, σs is the share of the collision rate σs + σf that scatters.
//!
//! **The estimator.** Light scattered toward the chain's start along a stretch of length T is
//! ∫₀ᵀ σs(t) (T_s(t)/P(t)) T_a(t) (n_start/n)² L_direct(x(t)) dt, where P(t) is the chance the
//! stretch reaches t (its free flight's survival; T_s/P = 1 for a grey σs) and L_direct the
//! direct light a phase-function vertex at x(t) scatters ([`crate::transport::lighting::direct_light`]: a light
//! sample and a phase sample, weighed against each other). Drawing the free flight's end and
//! lighting it estimates this integral with density ∝ σs T_s, which near a small bright light
//! leaves most samples in the dark. Here t is drawn with density ∝ 1/|x(t) − y|² about a point
//! y on one light (chosen uniformly; a light without a point — parallel light, and the
//! environment, one more strategy — draws t uniformly), and weighed by the mixture of every
//! strategy's density (one-sample multiple importance sampling), so the samples crowd where
//! the light is. The free flight's end then takes no direct light of its own
//! ([`super::direct::direct`]). Curved stretches keep the point estimate: a stretch through a
//! gradient medium is not a line to sample along.

use super::beam::{Beams, Straight};
use crate::polarization::Recorded;
use crate::transport::chain::Carried;
use crate::transport::lighting::{direct_light, Radiance};
use crate::transport::{MediumVertex, Stats, Vertex};
use glam::DVec3;
use rand::Rng;
use smallvec::SmallVec;

/// The direct light scattered toward the start of the chain recorded in `beams` along its
/// straight stretches, per unit of the path's throughput there, as the camera records it;
/// `carried`: what the chain carried at its end.
pub fn single_scattering(
    beams: &Beams,
    carried: Carried,
    rng: &mut impl Rng,
    stats: &mut Stats,
) -> Recorded {
    let tracer = carried.tracer;
    let scene = tracer.scene;
    // The environment is found by the phase sample alone: uniform draws serve it.
    let sky = scene.environment.is_some();
    if scene.lights.is_empty() && !sky {
        return Recorded::default();
    }
    let mut sum = Recorded::default();
    for s in beams.straight(tracer) {
        let middle = s.segment.origin + s.segment.dir * (0.5 * s.segment.length);
        let mut strategies: Strategies = scene
            .lights
            .iter()
            .map(|light| {
                let sample = light.sample_incident(middle, (rng.gen(), rng.gen()));
                match sample.filter(|i| i.distance.is_finite()) {
                    Some(i) => Strategy::about(&s, middle + i.wi * i.distance),
                    None => Strategy::Uniform,
                }
            })
            .collect();
        if sky {
            strategies.push(Strategy::Uniform);
        }
        let pick = rng.gen_range(0..strategies.len());
        let t = strategies[pick].sample(&s, rng.gen());
        let pdf = strategies.iter().map(|q| q.pdf(&s, t)).sum::<f64>() / strategies.len() as f64;
        if pdf.is_nan() || pdf <= 0.0 || pdf.is_infinite() {
            continue;
        }
        let x = s.segment.origin + s.segment.dir * t;
        let absorbed =
            (-tracer
                .participating(s.medium)
                .optical_depth(s.segment.origin, s.segment.dir, t))
            .exp();
        let mut flights = s.flights;
        let column = s.scattering.column(s.segment.origin, s.segment.dir, t);
        let kept = flights.weigh(&s.scattering, column, false);
        let density = s.scattering.density.as_ref().map_or(1.0, |d| d.at(x));
        let vertex = Vertex::Medium(MediumVertex {
            position: x,
            wo: -s.segment.dir,
            medium: Some(s.medium),
            phase: s.scattering.phase,
        });
        // Of the collisions a dye counts in, the share that scatter.
        let scatters = tracer
            .dye_share(s.medium)
            .map_or(1.0, |(_, share)| 1.0 - share);
        let throughput = s.weight
            * s.scattering.sigma_s
            * kept
            * (scatters * density * absorbed * s.radiance_scale / pdf);
        // As the camera records it through the measurement it carries there, a phase
        // function that polarizes (Rayleigh's) met on the way from each light.
        sum += match s.measure {
            Some(m) => direct_light(carried, &vertex, m, rng, stats) * throughput,
            None => Recorded::radiance(
                throughput * direct_light(carried, &vertex, &Radiance, rng, stats),
            ),
        };
    }
    sum
}

/// A stretch's strategies, one a light and the sky's: held in place for up to four, so that
/// a stretch allocates nothing in a scene of a few lights.
type Strategies = SmallVec<[Strategy; 4]>;

/// How one light's sample draws t along a stretch.
enum Strategy {
    /// Equiangular about a point off the stretch's line.
    Equiangular(Equiangular),
    /// Uniform over the stretch.
    Uniform,
}

/// Equiangular sampling about a point at `along` on a stretch's line, `distance` off it.
struct Equiangular {
    along: f64,
    distance: f64,
    /// The angles the stretch's ends subtend from the point, measured from the foot.
    from: f64,
    to: f64,
}

impl Strategy {
    /// Equiangular sampling of stretch `s` about the light point `y`; uniform where `y` lies
    /// on the stretch's line (to 1e-9 of its length), where equiangular would not be finite.
    fn about(s: &Straight, y: DVec3) -> Self {
        let along = (y - s.segment.origin).dot(s.segment.dir);
        let distance = (s.segment.origin + s.segment.dir * along - y).length();
        if distance.is_nan() || distance <= 1e-9 * s.segment.length {
            return Strategy::Uniform;
        }
        Strategy::Equiangular(Equiangular {
            along,
            distance,
            from: (-along / distance).atan(),
            to: ((s.segment.length - along) / distance).atan(),
        })
    }

    /// t from uniform `u` ∈ [0, 1).
    fn sample(&self, s: &Straight, u: f64) -> f64 {
        match self {
            Strategy::Equiangular(q) => (q.along
                + q.distance * (q.from + u * (q.to - q.from)).tan())
            .clamp(0.0, s.segment.length),
            Strategy::Uniform => u * s.segment.length,
        }
    }

    /// The density of t (per unit length).
    fn pdf(&self, s: &Straight, t: f64) -> f64 {
        match self {
            Strategy::Equiangular(q) => {
                let off = t - q.along;
                q.distance / ((q.to - q.from) * (q.distance * q.distance + off * off))
            }
            Strategy::Uniform => 1.0 / s.segment.length,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;

    /// Equiangular draws follow their density: the density integrates to 1 over the stretch
    /// (midpoint sum, 1e-6) and the draws' histogram matches it (χ² over 20 bins at 10⁵ draws,
    /// below the 0.1 % critical value 45.3 of 19 degrees of freedom).
    #[test]
    fn equiangular_draws_follow_their_density() {
        use rand::SeedableRng;
        let s = Straight {
            segment: crate::math::Segment {
                origin: DVec3::ZERO,
                dir: DVec3::X,
                length: 3.0,
            },
            medium: crate::ids::MediumId::new(0),
            scattering: std::borrow::Cow::Owned(crate::volume::Scattering {
                sigma_s: Rgb::ONE,
                spectrum: None,
                phase: crate::volume::Phase::Isotropic,
                density: None,
            }),
            weight: Rgb::ONE,
            flights: crate::volume::Flights::default(),
            radiance_scale: 1.0,
            measure: None,
        };
        let q = Strategy::about(&s, DVec3::new(0.7, 0.2, 0.0));
        let n = 100_000;
        let h = s.segment.length / n as f64;
        let total: f64 = (0..n).map(|i| q.pdf(&s, h * (i as f64 + 0.5)) * h).sum();
        assert!((total - 1.0).abs() < 1e-6, "{total}");
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(5);
        let bins = 20;
        let mut counts = vec![0u64; bins];
        let draws = 100_000;
        for _ in 0..draws {
            let t = q.sample(&s, rng.gen());
            counts[((t / s.segment.length * bins as f64) as usize).min(bins - 1)] += 1;
        }
        let width = s.segment.length / bins as f64;
        let chi2: f64 = counts
            .iter()
            .enumerate()
            .map(|(b, &c)| {
                let m = 1000;
                let expected: f64 = (0..m)
                    .map(|k| q.pdf(&s, width * (b as f64 + (k as f64 + 0.5) / m as f64)))
                    .sum::<f64>()
                    * width
                    / m as f64
                    * draws as f64;
                (c as f64 - expected).powi(2) / expected
            })
            .sum();
        assert!(chi2 < 45.3, "χ² = {chi2}");
    }
}
