//! What a ray that leaves the scene sees: a lat-long image, an image in the equal-area
//! octahedral map ([`crate::equal_area`], pbrt-v4's environment maps) or a procedural sky.
//! Lat-long convention: u = 0.5 + atan2(x, −z)/2π (−z at the centre), v = acos(y)/π (+y at the
//! top row); the map is turned by a [`Turn`].

use crate::color::Rgb;
use crate::equal_area::Grid;
use crate::lights::{covering_disk, Aim, Emission};
use crate::sampling::{uniform_sphere, UNIFORM_SPHERE_PDF};
use glam::{DMat3, DVec3};
use std::f64::consts::{PI, TAU};

/// The source of environment radiance.
#[derive(Clone, Debug, PartialEq)]
pub enum Sky {
    /// A lat-long image, linear RGB, row-major from the top.
    Image {
        /// Width in pixels.
        width: usize,
        /// Height in pixels.
        height: usize,
        /// Pixels.
        pixels: Vec<[f32; 3]>,
        /// How radiance between the pixels is read.
        filter: ImageFilter,
    },
    /// A square image in the equal-area octahedral map, linear RGB, row-major from the top,
    /// read by nearest pixel (as pbrt-v4 reads its environment maps): +z at its centre, +x at
    /// its right edge's midpoint, +y at its bottom edge's (at its top edge's with `flip_v`).
    EqualArea {
        /// How the pixels lie over the sphere.
        grid: Grid,
        /// Pixels.
        pixels: Vec<[f32; 3]>,
    },
    /// Random stars on black, deterministic in `seed` (about 2 stars per square degree on
    /// average, denser toward the poles where lat-long cells are smaller).
    Starfield {
        /// Seed of the star positions.
        seed: u64,
    },
    /// A lat-long checkerboard of `squares` × `squares`/2 cells, 1 and 0.1.
    Checker {
        /// Cells around the equator.
        squares: u32,
    },
    /// The same radiance from every direction (a white furnace).
    Uniform {
        /// Radiance per channel, W/(m²·sr).
        radiance: Rgb,
    },
}

/// How an environment image is read between its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ImageFilter {
    /// Constant over each pixel (pixel (i, j) covers u ∈ [i/W, (i+1)/W), v ∈ [j/H, (j+1)/H)).
    #[default]
    Nearest,
    /// Bilinear as Mitsuba 3's `envmap` reads its map: columns at the pixel centres
    /// u = (i + ½)/W, wrapping around; rows from pole to pole, row j at v = j/(H − 1).
    Bilinear,
}

/// An environment: a sky, turned and scaled.
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// The source.
    pub sky: Sky,
    /// How the map is turned in the scene.
    pub turn: Turn,
    /// Radiance multiplier.
    pub scale: f64,
}

/// How an environment's map is turned in the scene: the map's frame to the world's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Turn {
    /// About +y by an angle (radians, counterclockwise seen from +y).
    AboutY(f64),
    /// By a rotation matrix (orthonormal, determinant 1).
    Rotation(DMat3),
}

impl Turn {
    /// World direction `d` in the map's frame.
    fn to_map(self, d: DVec3) -> DVec3 {
        match self {
            Turn::AboutY(angle) => {
                let (s, c) = angle.sin_cos();
                DVec3::new(c * d.x - s * d.z, d.y, s * d.x + c * d.z)
            }
            Turn::Rotation(m) => m.transpose() * d,
        }
    }
}

/// An environment image's radiance at (u, v) ∈ [0, 1]², read by `filter`.
fn image_radiance(
    pixels: &[[f32; 3]],
    width: usize,
    height: usize,
    filter: ImageFilter,
    u: f64,
    v: f64,
) -> Rgb {
    let at = |x: usize, y: usize| {
        let p = pixels[y * width + x];
        Rgb::new(p[0] as f64, p[1] as f64, p[2] as f64)
    };
    match filter {
        ImageFilter::Nearest => {
            let x = ((u * width as f64) as usize).min(width - 1);
            let y = ((v * height as f64) as usize).min(height - 1);
            at(x, y)
        }
        ImageFilter::Bilinear => {
            let x = (u - 0.5 / width as f64).rem_euclid(1.0) * width as f64;
            let y = v * (height.max(2) - 1) as f64;
            let (x0, y0) = (
                (x as usize).min(width - 1),
                (y as usize).min(height.saturating_sub(2)),
            );
            let (fx, fy) = (x - x0 as f64, y - y0 as f64);
            let (x1, y1) = ((x0 + 1) % width, (y0 + 1).min(height - 1));
            let row = |y: usize| at(x0, y) * (1.0 - fx) + at(x1, y) * fx;
            row(y0) * (1.0 - fy) + row(y1) * fy
        }
    }
}

/// Star cells per 2π of longitude (cell ≈ 0.18°) and the chance that a cell holds a star.
const STAR_CELLS: f64 = 2048.0;
const STAR_CHANCE: f64 = 0.04;
/// Angular radius of a star's disc (radians, ≈ 0.05°): small against a pixel of the
/// 1920×1080, 40° view (0.02°) only by a few pixels, so stars render as soft points.
const STAR_RADIUS: f64 = 8e-4;

impl Environment {
    /// Radiance arriving from unit direction `d` (travelling along −d toward the scene).
    pub fn radiance(&self, d: DVec3) -> Rgb {
        let d = self.turn.to_map(d);
        let latlong = || {
            (
                0.5 + d.x.atan2(-d.z) / TAU,
                d.y.clamp(-1.0, 1.0).acos() / PI,
            )
        };
        self.scale
            * match &self.sky {
                Sky::Image {
                    width,
                    height,
                    pixels,
                    filter,
                } => {
                    let (u, v) = latlong();
                    image_radiance(pixels, *width, *height, *filter, u, v)
                }
                Sky::EqualArea { grid, pixels } => {
                    let p = pixels[grid.index(d)];
                    Rgb::new(p[0] as f64, p[1] as f64, p[2] as f64)
                }
                Sky::Starfield { seed } => {
                    let (u, v) = latlong();
                    starfield(*seed, d, u, v)
                }
                Sky::Checker { squares } => {
                    let (u, v) = latlong();
                    let n = *squares as f64;
                    let odd = ((u * n).floor() + (v * n * 0.5).floor()) as i64 % 2 == 0;
                    Rgb::splat(if odd { 1.0 } else { 0.1 })
                }
                Sky::Uniform { radiance } => *radiance,
            }
    }
}

impl Environment {
    /// A photon of environment light for four uniform numbers: its direction of arrival is
    /// uniform over the sphere and it sets off where [`covering_disk`] says, so the power
    /// estimate is L(ω)·area/pdf(ω) (see [`Emission`]); None where its line misses the world.
    pub fn emit(&self, u: [f64; 4], aim: Aim) -> Option<Emission> {
        let from = uniform_sphere((u[0], u[1]));
        let direction = -from;
        let (origin, area) = covering_disk(aim, direction, (u[2], u[3]))?;
        Some(Emission {
            origin,
            direction,
            power: self.radiance(from) * (area / UNIFORM_SPHERE_PDF),
        })
    }

    /// A weight for choosing the environment among the lights: its power through the
    /// covering disk (W, mean over channels), with the mean radiance taken over a fixed
    /// 64 × 128 grid of directions (equal solid angle per cell).
    pub fn selection_power(&self, aim: Aim) -> f64 {
        let (rows, cols) = (64, 128);
        let mut sum = Rgb::ZERO;
        for i in 0..rows {
            for j in 0..cols {
                let u = (
                    (i as f64 + 0.5) / rows as f64,
                    (j as f64 + 0.5) / cols as f64,
                );
                sum += self.radiance(uniform_sphere(u));
            }
        }
        let mean = sum / (rows * cols) as f64;
        let r = aim.target.radius;
        mean.element_sum() / 3.0 * 4.0 * PI * PI * r * r
    }
}

/// 64-bit mix (splitmix64 finaliser) for hashing star cells.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

fn unit(h: u64) -> f64 {
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// Stars: each lat-long cell holds a star with probability STAR_CHANCE at a hashed position,
/// with a hashed brightness (heavy-tailed) and colour temperature; the 3×3 neighbouring cells
/// are searched so discs are not cut at cell edges.
fn starfield(seed: u64, d: DVec3, u: f64, v: f64) -> Rgb {
    let (nu, nv) = (STAR_CELLS, STAR_CELLS / 2.0);
    let (cu, cv) = ((u * nu).floor() as i64, (v * nv).floor() as i64);
    let mut sum = Rgb::ZERO;
    for dv in -1..=1 {
        let row = cv + dv;
        if row < 0 || row >= nv as i64 {
            continue;
        }
        for du in -1..=1 {
            let col = (cu + du).rem_euclid(nu as i64);
            let h = mix(seed ^ mix((row as u64) << 32 | col as u64));
            if unit(h) >= STAR_CHANCE {
                continue;
            }
            let su = (col as f64 + unit(mix(h ^ 1))) / nu;
            let sv = (row as f64 + unit(mix(h ^ 2))) / nv;
            let (phi, theta) = ((su - 0.5) * TAU, sv * PI);
            let star = DVec3::new(
                theta.sin() * phi.sin(),
                theta.cos(),
                -theta.sin() * phi.cos(),
            );
            let ang = d.dot(star).clamp(-1.0, 1.0).acos();
            if ang < STAR_RADIUS {
                let brightness = 0.5 / (1e-3 + unit(mix(h ^ 3))).powf(0.7);
                let warm = unit(mix(h ^ 4));
                let color = Rgb::new(1.0, 0.85 + 0.15 * warm, 0.7 + 0.3 * (1.0 - warm));
                let w = 1.0 - ang / STAR_RADIUS;
                sum += color * (brightness * w * w);
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_about_y_is_its_rotation_matrix() {
        let sky = Sky::Checker { squares: 24 };
        let angle = 0.7;
        let env = |turn| Environment {
            sky: sky.clone(),
            turn,
            scale: 1.0,
        };
        let (a, b) = (
            env(Turn::AboutY(angle)),
            env(Turn::Rotation(DMat3::from_rotation_y(angle))),
        );
        for i in 0..1000 {
            let t = i as f64 * 0.37;
            let d = DVec3::new(t.sin() * (2.0 * t).cos(), (3.0 * t).cos(), t.cos()).normalize();
            assert_eq!(a.radiance(d), b.radiance(d), "{d}");
        }
    }

    #[test]
    fn bilinear_reads_pixels_at_their_centres_and_wraps_around() {
        // 4 × 3 pixels, each its own value: (x + 10 y).
        let pixels: Vec<[f32; 3]> = (0..12)
            .map(|i| [((i % 4) + 10 * (i / 4)) as f32; 3])
            .collect();
        let read = |u: f64, v: f64| {
            image_radiance(&pixels, 4, 3, ImageFilter::Bilinear, u, v)
                .0
                .x
        };
        // Column i at u = (i + ½)/4; row j at v = j/2 (pole to pole).
        assert_eq!(read(0.375, 0.0), 1.0);
        assert_eq!(read(0.375, 0.5), 11.0);
        assert_eq!(read(0.375, 1.0), 21.0);
        // Halfway between columns 1 and 2, and between rows 0 and 1.
        assert_eq!(read(0.5, 0.25), 6.5);
        // Across the seam: halfway between the last column and the first.
        assert_eq!(read(0.0, 0.0), 1.5);
        assert_eq!(read(1.0, 0.0), 1.5);
        // Nearest: constant over each pixel.
        let near = |u: f64, v: f64| {
            image_radiance(&pixels, 4, 3, ImageFilter::Nearest, u, v)
                .0
                .x
        };
        assert_eq!(near(0.3, 0.1), 1.0);
        assert_eq!(near(0.99, 0.99), 23.0);
    }
}
