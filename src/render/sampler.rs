//! Where a camera sample's numbers come from (`[render] sampler`, [`SamplerKind`]): the point
//! of the film and of the lens its ray is drawn through, the numbers of its first choices and
//! of its first vertex, and the stream the rest of its path draws from. Every number is keyed
//! by (seed, pass, pixel, sample), never by the thread or the tile that draws it, so shards of
//! a render merge bit for bit.

use crate::camera::FilmPoint;
use crate::integrator::FirstVertex;
use crate::sample_stream::{SampleStream, SobolStream};
use crate::sampling::{in_stratum, mix, stream, Given, Purpose, Strata, Strata2};
use crate::settings::SamplerKind;
use crate::transport::chain::Choices;
use crate::transport::lighting::LightNumbers;
use crate::transport::BsdfNumbers;
use glam::DVec2;
use rand::Rng;

/// Which camera samples a pass takes.
#[derive(Clone, Copy, Debug)]
pub struct Sampling {
    /// Seed of every random stream.
    pub seed: u64,
    /// Samples a pixel takes in a pass.
    pub spp: u32,
    /// The pass.
    pub pass: u32,
    /// Where the numbers come from.
    pub kind: SamplerKind,
}

impl Sampling {
    /// The pass's sampler, of its kind.
    pub fn sampler(self) -> Box<dyn PixelSampler> {
        match self.kind {
            SamplerKind::Stratified => Box::new(Stratified::new(self)),
            SamplerKind::Sobol => Box::new(Sobol::new(self)),
        }
    }
}

/// A pixel of the image in one pass.
#[derive(Clone, Copy, Debug)]
pub struct PixelPass {
    /// Column, from the left.
    pub x: u32,
    /// Row, from the top.
    pub y: u32,
    /// The image's width in pixels.
    pub width: u32,
    /// The image's height in pixels.
    pub height: u32,
}

impl PixelPass {
    /// The pixel's index in the image, row by row.
    fn index(self) -> u64 {
        u64::from(self.y) * u64::from(self.width) + u64::from(self.x)
    }

    /// The point (`u`, `v`) of the pixel, through the lens at `lens`.
    fn film_point(self, u: f64, v: f64, lens: DVec2) -> FilmPoint {
        FilmPoint {
            px: self.x,
            py: self.y,
            u,
            v,
            lens,
        }
    }

    /// The pixel's key in `pass`: unique over every pixel of every pass.
    fn key(self, pass: u32) -> u64 {
        u64::from(pass) * u64::from(self.width) * u64::from(self.height) + self.index()
    }
}

/// A camera sample's numbers of fixed meaning and the stream it goes on drawing from.
pub struct SampleStart {
    /// The point of the film and of the lens its ray is drawn through.
    pub film: FilmPoint,
    /// The numbers of its first choices between reflection and refraction.
    pub choices: Choices,
    /// The numbers of its first scattering vertex.
    pub first: FirstVertex,
    /// The stream of every other number of its path.
    pub rng: SampleStream,
}

/// The numbers of a pixel's samples in a pass.
pub trait PixelSampler {
    /// The samples a pixel takes in the pass.
    fn samples(&self) -> u32;

    /// Prepares `pixel`'s samples of the pass.
    fn start_pixel(&mut self, pixel: PixelPass);

    /// The numbers of the pixel's sample `s` (< the pass's samples a pixel).
    fn sample(&self, s: u32) -> SampleStart;
}

/// Independent numbers for each sample, with the film point (jittered over ⌊√spp⌋² cells)
/// and the first choices and first vertex's numbers ([`Strata`]) stratified over the pixel's
/// samples of the pass, each dimension in its own random order.
pub struct Stratified {
    sampling: Sampling,
    pixel: Option<PixelPass>,
    choices: [Strata; Choices::COUNT],
    light: Strata2,
    pick: Strata,
    direction: Strata2,
    choice: Strata,
}

impl Stratified {
    /// The sampler of a pass.
    pub fn new(sampling: Sampling) -> Self {
        Self {
            sampling,
            pixel: None,
            choices: Default::default(),
            light: Strata2::default(),
            pick: Strata::default(),
            direction: Strata2::default(),
            choice: Strata::default(),
        }
    }
}

impl PixelSampler for Stratified {
    fn samples(&self) -> u32 {
        self.sampling.spp
    }

    fn start_pixel(&mut self, pixel: PixelPass) {
        let Sampling {
            seed, spp, pass, ..
        } = self.sampling;
        let mut rng = stream(seed, Purpose::PixelStrata, pixel.key(pass), 0);
        for dimension in &mut self.choices {
            dimension.draw(spp, &mut rng);
        }
        self.light.draw(spp, &mut rng);
        self.pick.draw(spp, &mut rng);
        self.direction.draw(spp, &mut rng);
        self.choice.draw(spp, &mut rng);
        self.pixel = Some(pixel);
    }

    fn sample(&self, s: u32) -> SampleStart {
        let Sampling {
            seed, spp, pass, ..
        } = self.sampling;
        let pixel = self.pixel.expect("start_pixel() before sample()");
        let mut rng = stream(seed, Purpose::Camera, pixel.key(pass), u64::from(s));
        // Sample s of the first n² lies in cell (s mod n, s div n) of an n × n grid over the
        // pixel, n = ⌊√spp⌋ (sharp edges such as an emitter's converge much faster); any
        // further samples are uniform.
        let strata = spp.isqrt();
        let (mut u, mut v) = (rng.gen::<f64>(), rng.gen::<f64>());
        if s < strata * strata {
            u = in_stratum(s % strata, strata, u);
            v = in_stratum(s / strata, strata, v);
        }
        let lens = DVec2::new(rng.gen(), rng.gen());
        let choices = Choices::new(
            self.choices
                .each_ref()
                .map(|d| d.get(s).unwrap_or_else(|| rng.gen())),
        );
        let one = |strata: &Strata| Given(strata.get(s).map(|u| [u]));
        SampleStart {
            film: pixel.film_point(u, v, lens),
            choices,
            first: FirstVertex {
                light: LightNumbers {
                    uv: self.light.get(s),
                    pick: one(&self.pick),
                },
                bsdf: BsdfNumbers {
                    direction: self.direction.get(s),
                    choice: one(&self.choice),
                },
            },
            rng: SampleStream::Independent(rng),
        }
    }
}

/// Each sample's numbers the next dimensions of its Owen-scrambled Sobol point
/// ([`SobolStream`]): sample s of a pass is point s of a sequence scrambled for the pixel and
/// the pass. Each pass is a scrambling of its own, so passes stay independent estimates of a
/// pixel — what the film's estimate of its error from the spread of its passes assumes
/// (randomized quasi-Monte Carlo's independent replicates). The dimensions, in sets of four
/// stratified together:
/// the film point and the lens point; the first vertex's light point and BSDF direction; its
/// light pick and lobe choice and the first two choices; the third choice, then the path's.
pub struct Sobol {
    sampling: Sampling,
    /// The pixel and its sequence's seed in the pass.
    pixel: Option<(PixelPass, u64)>,
}

impl Sobol {
    /// The sampler of a pass.
    pub fn new(sampling: Sampling) -> Self {
        Self {
            sampling,
            pixel: None,
        }
    }
}

impl PixelSampler for Sobol {
    fn samples(&self) -> u32 {
        self.sampling.spp
    }

    fn start_pixel(&mut self, pixel: PixelPass) {
        let key = pixel.key(self.sampling.pass);
        let seed = mix(self.sampling.seed ^ mix(Purpose::Camera as u64 ^ mix(key)));
        self.pixel = Some((pixel, seed));
    }

    fn sample(&self, s: u32) -> SampleStart {
        let Sampling { seed, pass, .. } = self.sampling;
        let (pixel, pixel_seed) = self.pixel.expect("start_pixel() before sample()");
        let low = stream(seed, Purpose::Camera, pixel.key(pass), u64::from(s));
        let mut rng = SobolStream::new(pixel_seed, u64::from(s), low);
        let (u, v) = (rng.gen::<f64>(), rng.gen::<f64>());
        let lens = DVec2::new(rng.gen(), rng.gen());
        let light = Given(Some([rng.gen(), rng.gen()]));
        let direction = Given(Some([rng.gen(), rng.gen()]));
        let pick = Given(Some([rng.gen()]));
        let choice = Given(Some([rng.gen()]));
        let choices = Choices::new(std::array::from_fn(|_| rng.gen()));
        SampleStart {
            film: pixel.film_point(u, v, lens),
            choices,
            first: FirstVertex {
                light: LightNumbers { uv: light, pick },
                bsdf: BsdfNumbers { direction, choice },
            },
            rng: SampleStream::Sobol(rng),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The film points' horizontal offsets of a pixel's samples over `passes` passes of `spp`.
    fn film_u(kind: SamplerKind, passes: u32, spp: u32) -> Vec<f64> {
        let pixel = PixelPass {
            x: 3,
            y: 5,
            width: 8,
            height: 8,
        };
        (0..passes)
            .flat_map(|pass| {
                let sampling = Sampling {
                    seed: 1,
                    spp,
                    pass,
                    kind,
                };
                let mut sampler = sampling.sampler();
                sampler.start_pixel(pixel);
                (0..spp)
                    .map(move |s| sampler.sample(s).film.u)
                    .collect::<Vec<_>>()
            })
            .collect()
    }

    /// The strata of [0, 1) in `n` equal parts holding none of `us`.
    fn empty_strata(us: &[f64], n: usize) -> usize {
        let mut held = vec![false; n];
        us.iter()
            .for_each(|&u| held[(u * n as f64) as usize] = true);
        held.iter().filter(|&&h| !h).count()
    }

    /// Sobol stratifies a pass's film points over the pixel in every dimension: one pass of
    /// 64 samples puts one in each of 64 strata, where the stratified sampler's 8 × 8 cells
    /// give 8 strata of u, each holding 8. A new pass is a new scrambling: its points are not
    /// the first pass's.
    #[test]
    fn sobol_stratifies_a_pass_and_scrambles_each_pass_anew() {
        assert_eq!(empty_strata(&film_u(SamplerKind::Sobol, 1, 64), 64), 0);
        assert!(empty_strata(&film_u(SamplerKind::Stratified, 1, 64), 64) > 0);
        let two = film_u(SamplerKind::Sobol, 2, 64);
        assert!(two[..64].iter().zip(&two[64..]).all(|(a, b)| a != b));
    }

    /// A sample's numbers are the same however it is reached: asked twice, or after the
    /// pixel's other samples (what lets shards and tiles draw in any order).
    #[test]
    fn a_samples_numbers_depend_only_on_its_key() {
        for kind in SamplerKind::ALL {
            let sampling = Sampling {
                seed: 4,
                spp: 8,
                pass: 2,
                kind,
            };
            let mut a = sampling.sampler();
            let pixel = PixelPass {
                x: 1,
                y: 2,
                width: 4,
                height: 4,
            };
            a.start_pixel(pixel);
            let first = a.sample(5);
            a.start_pixel(PixelPass { x: 0, ..pixel });
            a.start_pixel(pixel);
            let again = a.sample(5);
            assert_eq!(first.film, again.film);
            assert_eq!(first.first, again.first);
            let (mut r1, mut r2) = (first.rng, again.rng);
            assert_eq!(r1.gen::<u64>(), r2.gen::<u64>());
        }
    }
}
