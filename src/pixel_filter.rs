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

    /// The filter prepared for placing a render's samples ([`Placement`]).
    pub fn placement(&self) -> Placement {
        let tabulated = match *self {
            PixelFilter::Box => None,
            PixelFilter::Gaussian {
                stddev,
                radius,
                reach,
            } => {
                let gaussian = Gaussian::new(stddev, radius);
                let whole = gaussian.span((-radius, radius));
                Some(Tabulated {
                    quantiles: gaussian.quantiles(&whole),
                    whole,
                    gaussian,
                    reach,
                })
            }
        };
        Placement { tabulated }
    }
}

/// A pixel filter prepared for placing samples: for a Gaussian its quantiles over its whole
/// support, tabulated once, from which the exact solve of a pixel whose support is whole
/// starts (a Newton step or two from there, where it would take five or more from the
/// support's linear map).
#[derive(Clone, Debug)]
pub struct Placement {
    /// The Gaussian's (None: a box).
    tabulated: Option<Tabulated>,
}

/// A Gaussian filter with its quantiles.
#[derive(Clone, Debug)]
struct Tabulated {
    gaussian: Gaussian,
    reach: Reach,
    /// Its whole support, [−r, r].
    whole: Span,
    /// The offsets at shares k/[`QUANTILES`], k = 0..=QUANTILES.
    quantiles: Vec<f64>,
}

/// Intervals of a Gaussian's tabulated quantiles.
const QUANTILES: usize = 4096;

impl Placement {
    /// Where, along one axis, a sample of the pixel `index` of an image `size` pixels long
    /// falls under the filter, given its position `u` in [0, 1) (pixels from the pixel's
    /// edge): `u` itself for a box; for a Gaussian the position whose offset from the pixel's
    /// centre has the filter's share (restricted to the image) below it that `u` is — outside
    /// [0, 1) where it falls in a neighbouring pixel.
    pub fn place(&self, index: u32, size: u32, u: f64) -> f64 {
        let Some(Tabulated {
            gaussian,
            reach,
            whole,
            quantiles,
        }) = &self.tabulated
        else {
            return u;
        };
        let offset = match gaussian.support(index, size, *reach) {
            (a, b) if (a, b) == (whole.a, whole.b) => {
                gaussian.offset(whole, u, interpolate(quantiles, u))
            }
            cut => gaussian.offset(&gaussian.span(cut), u, cut.0 + u * (cut.1 - cut.0)),
        };
        0.5 + offset
    }
}

/// The table's value at `u` in [0, 1], linearly between its entries at k/(len − 1).
fn interpolate(table: &[f64], u: f64) -> f64 {
    let t = u.clamp(0.0, 1.0) * (table.len() - 1) as f64;
    let k = (t as usize).min(table.len() - 2);
    let f = t - k as f64;
    table[k] + f * (table[k + 1] - table[k])
}

/// A part [a, b] of a filter's support (offsets from the pixel's centre, pixels) and the
/// filter's integrals ∫₀ᵃ f and ∫₀ᵇ f.
#[derive(Clone, Copy, Debug)]
struct Span {
    a: f64,
    b: f64,
    from: f64,
    to: f64,
}

/// A truncated Gaussian along one axis.
#[derive(Clone, Debug)]
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

    /// The part of f's support a pixel weighs, as offsets from its centre: [−r, r] (`reach`
    /// beyond the image), or its part inside the image, [max(−r, −(index + ½)),
    /// min(r, size − index − ½)], for pixel `index` of an image `size` pixels long.
    fn support(&self, index: u32, size: u32, reach: Reach) -> (f64, f64) {
        let centre = f64::from(index) + 0.5;
        match reach {
            Reach::Beyond => (-self.radius, self.radius),
            Reach::Image => (
                (-self.radius).max(-centre),
                self.radius.min(f64::from(size) - centre),
            ),
        }
    }

    /// The span from `a` to `b`, with f's integrals up to its ends.
    fn span(&self, (a, b): (f64, f64)) -> Span {
        Span {
            a,
            b,
            from: self.integral(a),
            to: self.integral(b),
        }
    }

    /// The quantiles of f over its whole support at shares k/[`QUANTILES`], each solved
    /// exactly.
    fn quantiles(&self, whole: &Span) -> Vec<f64> {
        (0..=QUANTILES)
            .map(|k| {
                let u = k as f64 / QUANTILES as f64;
                self.offset(whole, u, whole.a + u * (whole.b - whole.a))
            })
            .collect()
    }

    /// The offset in `support` whose share of f over it below it is `u`: the root of the
    /// cumulative integral F by Newton steps from `guess`, kept inside a shrinking bracket
    /// (bisection where a step would leave it), to 1e-12 pixels. A Newton step s from x leaves
    /// an error of about K s², K = |F''|/(2F') = |f'(x)|/(2 f(x)) (locally, for s ≤ 1e-6, as
    /// f is smooth on that scale inside its support): where that is below 1e-13 the step's
    /// end is the root, and no further step is taken to find out.
    fn offset(&self, support: &Span, u: f64, guess: f64) -> f64 {
        let Span { a, b, from, to } = *support;
        let target = from + u * (to - from);
        let (mut lo, mut hi) = (a, b);
        let mut x = guess.clamp(a, b);
        let variance = self.stddev * self.stddev;
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
            let step = (next - x).abs();
            // f′(x) = −x e^(−x²/(2σ²))/σ² = −x (f(x) + floor)/σ².
            let curvature = (x * (slope + self.floor) / variance).abs() / (2.0 * slope);
            let converged = next == newton && step <= 1e-6 && curvature * step * step <= 1e-13;
            if step <= 1e-12 || hi - lo <= 1e-12 || converged {
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
    /// 10⁶ steps) is u, to 1e-9, and as close to it as the root bisection finds — Mitsuba's
    /// filter (σ 0.5, r 2) inside the image at its edges
    /// (the support cut at the first and last pixels' outer edges), pbrt's (σ 0.5, r 1.5)
    /// beyond them too; a box leaves points alone.
    #[test]
    fn gaussian_offsets_are_the_filters_quantiles() {
        for (radius, reach) in [(2.0, Reach::Image), (1.5, Reach::Beyond)] {
            let g = Gaussian::new(0.5, radius);
            let placement = PixelFilter::Gaussian {
                stddev: 0.5,
                radius,
                reach,
            }
            .placement();
            let midpoint = |a: f64, b: f64| {
                let n = 1_000_000;
                let h = (b - a) / n as f64;
                (0..n).map(|k| g.f(a + (k as f64 + 0.5) * h)).sum::<f64>() * h
            };
            // Pixels whose support is whole (started from the table) and cut by the image's
            // edge (started from the support's linear map).
            for (index, size) in [(10, 40), (0, 40), (1, 40), (39, 40), (0, 1)] {
                let centre = f64::from(index) + 0.5;
                let (a, b) = match reach {
                    Reach::Image => ((-radius).max(-centre), radius.min(f64::from(size) - centre)),
                    Reach::Beyond => (-radius, radius),
                };
                let whole = midpoint(a, b);
                for u in [0.0, 1e-7, 0.01, 0.2, 0.5, 0.77, 0.999, 1.0 - 1e-9] {
                    let x = placement.place(index, size, u) - 0.5;
                    assert!(
                        (a..=b).contains(&x),
                        "{index}/{size} u {u}: {x} outside [{a}, {b}]"
                    );
                    // The root by bisection alone, to the last bits: Newton's early stop
                    // leaves a share no further from u than it does (to 1e-12, the stop's
                    // 1e-13 with room; at the support's ends, where f vanishes, F is flat and
                    // the root's place is only as sharp as F's rounding, so shares are
                    // compared, not places).
                    let (from, to) = (g.integral(a), g.integral(b));
                    let (mut lo, mut hi) = (a, b);
                    for _ in 0..100 {
                        let mid = 0.5 * (lo + hi);
                        match (g.integral(mid) - from) / (to - from) > u {
                            true => hi = mid,
                            false => lo = mid,
                        }
                    }
                    let off = (g.integral(x) - g.integral(lo)).abs() / (to - from);
                    assert!(off < 1e-12, "{index}/{size} u {u}: {x} vs {lo}: {off}");
                    let share = midpoint(a, x) / whole;
                    assert!(
                        (share - u).abs() < 1e-9,
                        "{index}/{size} u {u}: share {share}"
                    );
                }
            }
        }
        assert_eq!(PixelFilter::Box.placement().place(3, 8, 0.25), 0.25);
        let centred = PixelFilter::mitsuba_gaussian(0.5)
            .placement()
            .place(10, 40, 0.5);
        assert!((centred - 0.5).abs() < 1e-12, "{centred}");
    }
}
