//! The pixel filter: how a pixel weighs the film around it. A pixel's value is the mean of
//! the radiance over the film weighed by the filter f centred on the pixel, ∫ f(p − c) L(p) dp
//! / ∫ f(p − c) dp, over the filter's support: only its part inside the image (as a renderer
//! that splats its samples into the pixels around them and divides by the weights has it in
//! the limit — Mitsuba's film), or all of it, the film beyond the image included (pbrt-v4's,
//! whose samples are drawn from the filter). grinlight draws each sample's film point from f
//! itself (filter importance sampling, Ernst et al. 2006) over that support, so that every
//! sample carries weight 1 and stays in its pixel: the plain mean of a pixel's samples
//! estimates that value, and the film, its passes and its shards are as for a box.
//!
//! Separable filters only: f(x, y) = f(x) f(y), x and y in pixels from the pixel's centre.

use std::f64::consts::SQRT_2;

/// A pixel filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PixelFilter {
    /// The pixel's own square, uniformly.
    Box,
    /// A truncated Gaussian, f(x) = max(0, e^(−x²/(2σ²)) − e^(−r²/(2σ²))): Mitsuba's (r = 4σ,
    /// σ = 0.5 by default) and pbrt-v4's (r = 1.5, σ = 0.5 by default).
    Gaussian {
        /// σ, pixels.
        stddev: f64,
        /// r, pixels: where f falls to 0.
        radius: f64,
        /// Which of its support a pixel at the image's edge weighs.
        reach: Reach,
    },
}

/// Which part of a filter's support a pixel weighs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// The film inside the image only (Mitsuba).
    Image,
    /// All of it, the film beyond the image's edges included (pbrt-v4).
    Beyond,
}

impl PixelFilter {
    /// Mitsuba's Gaussian of standard deviation `stddev`: r = 4σ, inside the image.
    pub fn mitsuba_gaussian(stddev: f64) -> Self {
        PixelFilter::Gaussian {
            stddev,
            radius: 4.0 * stddev,
            reach: Reach::Image,
        }
    }

    /// pbrt-v4's Gaussian of standard deviation `stddev` and radius `radius`, beyond the image
    /// too.
    pub fn pbrt_gaussian(stddev: f64, radius: f64) -> Self {
        PixelFilter::Gaussian {
            stddev,
            radius,
            reach: Reach::Beyond,
        }
    }

    /// Where, along one axis, a sample of the pixel `index` of an image `size` pixels long
    /// falls under the filter, given its position `u` in [0, 1) (pixels from the pixel's
    /// edge): `u` itself for a box; for a Gaussian the position whose offset from the pixel's
    /// centre has the filter's share (restricted to the image) below it that `u` is — outside
    /// [0, 1) where it falls in a neighbouring pixel.
    pub fn place(&self, index: u32, size: u32, u: f64) -> f64 {
        match *self {
            PixelFilter::Box => u,
            PixelFilter::Gaussian {
                stddev,
                radius,
                reach,
            } => 0.5 + Gaussian::new(stddev, radius).offset(index, size, reach, u),
        }
    }
}

/// A truncated Gaussian along one axis.
struct Gaussian {
    stddev: f64,
    /// r.
    radius: f64,
    /// e^(−r²/(2σ²)), subtracted so that f falls to 0 at r.
    floor: f64,
}

impl Gaussian {
    fn new(stddev: f64, radius: f64) -> Self {
        Self {
            stddev,
            radius,
            floor: (-radius * radius / (2.0 * stddev * stddev)).exp(),
        }
    }

    /// f(x).
    fn f(&self, x: f64) -> f64 {
        ((-x * x / (2.0 * self.stddev * self.stddev)).exp() - self.floor).max(0.0)
    }

    /// ∫₀ˣ f, for |x| ≤ r.
    fn integral(&self, x: f64) -> f64 {
        let s = self.stddev;
        s * (std::f64::consts::PI / 2.0).sqrt() * libm::erf(x / (s * SQRT_2)) - self.floor * x
    }

    /// The offset from the centre of pixel `index` of an image `size` pixels long whose share
    /// of f over the support `reach` gives — [−r, r], or its part inside the image,
    /// [max(−r, −(index + ½)), min(r, size − index − ½)] — below it is `u`: the root of the
    /// cumulative integral by Newton steps kept inside a shrinking bracket (bisection where a
    /// step would leave it), to 1e-12 pixels.
    fn offset(&self, index: u32, size: u32, reach: Reach, u: f64) -> f64 {
        let centre = f64::from(index) + 0.5;
        let (a, b) = match reach {
            Reach::Beyond => (-self.radius, self.radius),
            Reach::Image => (
                (-self.radius).max(-centre),
                self.radius.min(f64::from(size) - centre),
            ),
        };
        let (from, to) = (self.integral(a), self.integral(b));
        let target = from + u * (to - from);
        let (mut lo, mut hi) = (a, b);
        let mut x = a + u * (b - a);
        for _ in 0..200 {
            let g = self.integral(x) - target;
            match g > 0.0 {
                true => hi = x,
                false => lo = x,
            }
            let slope = self.f(x);
            let newton = x - g / slope;
            let next = match slope > 0.0 && newton > lo && newton < hi {
                true => newton,
                false => 0.5 * (lo + hi),
            };
            if (next - x).abs() <= 1e-12 || hi - lo <= 1e-12 {
                return next;
            }
            x = next;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The offsets are f's quantiles: the share of f below each (by a midpoint sum of f over
    /// 10⁶ steps) is u, to 1e-9 — Mitsuba's filter (σ 0.5, r 2) inside the image at its edges
    /// (the support cut at the first and last pixels' outer edges), pbrt's (σ 0.5, r 1.5)
    /// beyond them too; a box leaves points alone.
    #[test]
    fn gaussian_offsets_are_the_filters_quantiles() {
        for (radius, reach) in [(2.0, Reach::Image), (1.5, Reach::Beyond)] {
            let g = Gaussian::new(0.5, radius);
            let midpoint = |a: f64, b: f64| {
                let n = 1_000_000;
                let h = (b - a) / n as f64;
                (0..n).map(|k| g.f(a + (k as f64 + 0.5) * h)).sum::<f64>() * h
            };
            for (index, size) in [(10, 40), (0, 40), (1, 40), (39, 40), (0, 1)] {
                let centre = f64::from(index) + 0.5;
                let (a, b) = match reach {
                    Reach::Image => ((-radius).max(-centre), radius.min(f64::from(size) - centre)),
                    Reach::Beyond => (-radius, radius),
                };
                let whole = midpoint(a, b);
                for u in [0.0, 0.01, 0.2, 0.5, 0.77, 0.999] {
                    let x = g.offset(index, size, reach, u);
                    assert!(
                        (a..=b).contains(&x),
                        "{index}/{size} u {u}: {x} outside [{a}, {b}]"
                    );
                    let share = midpoint(a, x) / whole;
                    assert!(
                        (share - u).abs() < 1e-9,
                        "{index}/{size} u {u}: share {share}"
                    );
                }
            }
        }
        assert_eq!(PixelFilter::Box.place(3, 8, 0.25), 0.25);
        let centred = PixelFilter::mitsuba_gaussian(0.5).place(10, 40, 0.5);
        assert!((centred - 0.5).abs() < 1e-12, "{centred}");
    }
}
