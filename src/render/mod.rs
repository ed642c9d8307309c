//! The camera pass: primary rays through specular chains and curved paths to the first
//! diffuse surface, direct light by light sampling where a straight shadow connection is
//! valid, emission and environment, written to the film's layers. Tiles run in parallel on a
//! local rayon pool; every sample's random stream is keyed by (seed, pixel, sample), so the
//! image does not depend on the thread count.

mod stats;
mod transport;

pub use stats::Stats;
pub use transport::{Event, Tracer};

use crate::color::Rgb;
use crate::error::{Error, Result};
use crate::film::{Film, PixelSample};
use crate::material::{fresnel, reflect, refract, Material};
use crate::scene::Scene;
use glam::DVec3;
use rand::Rng;
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use std::f64::consts::FRAC_1_PI;

/// The summed samples of a tile's pixels: (x, y, sum).
type TilePixels = Vec<(usize, usize, PixelSample)>;

/// Tile edge in pixels.
const TILE: usize = 16;

/// A random stream for one (seed, pixel, sample): splitmix-hashed into a PCG state.
pub fn stream(seed: u64, pixel: u64, sample: u64) -> Pcg64Mcg {
    let mix = |mut z: u64| {
        z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    let a = mix(seed ^ mix(pixel ^ mix(sample)));
    let b = mix(a ^ 0x5851_f42d_4c95_7f2d);
    Pcg64Mcg::new(((a as u128) << 64) | b as u128)
}

/// Offset of a point off a surface toward the side of unit `side` (scene-scale relative).
fn offset(p: DVec3, side: DVec3) -> DVec3 {
    p + side * (1e-9 * (1.0 + p.abs().max_element()))
}

/// Renders the scene's camera view. `progress` is called once per finished tile.
pub fn render(
    scene: &Scene,
    threads: usize,
    progress: &(dyn Fn() + Sync),
) -> Result<(Film, Stats)> {
    let camera = scene.camera.as_ref().ok_or_else(|| {
        Error::Usage(format!(
            "{}: the scene has no [camera]",
            scene.path().display()
        ))
    })?;
    let (w, h) = (camera.width as usize, camera.height as usize);
    let tiles: Vec<(usize, usize)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx, ty)))
        .collect();
    let tracer = Tracer::new(scene);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::Usage(format!("cannot start {threads} threads: {e}")))?;
    let spp = scene.render.spp;
    let results: Vec<(TilePixels, Stats)> = pool.install(|| {
        tiles
            .par_iter()
            .map(|&(tx, ty)| {
                let mut stats = Stats::default();
                let mut pixels = Vec::new();
                for y in ty * TILE..((ty + 1) * TILE).min(h) {
                    for x in tx * TILE..((tx + 1) * TILE).min(w) {
                        let mut sum: PixelSample = [Rgb::ZERO; 5];
                        for s in 0..spp {
                            let mut rng = stream(scene.render.seed, (y * w + x) as u64, s as u64);
                            let (u, v) = (rng.gen::<f64>(), rng.gen::<f64>());
                            let (o, d) =
                                camera.ray(x as u32, y as u32, u, v, (rng.gen(), rng.gen()));
                            stats.camera_rays += 1;
                            let sample = camera_path(&tracer, o, d, &mut rng, &mut stats);
                            for (a, b) in sum.iter_mut().zip(sample) {
                                *a += b;
                            }
                        }
                        pixels.push((x, y, sum));
                    }
                }
                progress();
                (pixels, stats)
            })
            .collect()
    });
    let mut film = Film::new(w, h);
    let mut stats = Stats::default();
    for (pixels, s) in &results {
        for (x, y, sum) in pixels {
            film.set_mean(*x, *y, sum, spp);
        }
        stats.add(s);
    }
    Ok((film, stats))
}

/// Layers of one camera sample: beauty, direct, emitted, albedo, normal.
fn camera_path(
    tracer: &Tracer,
    mut origin: DVec3,
    mut dir: DVec3,
    rng: &mut Pcg64Mcg,
    stats: &mut Stats,
) -> PixelSample {
    let scene = tracer.scene;
    let mut medium = scene.ambient;
    let mut throughput = Rgb::ONE;
    let (mut direct, mut emitted, mut albedo_aov, mut normal_aov) =
        (Rgb::ZERO, Rgb::ZERO, Rgb::ZERO, Rgb::ZERO);
    let mut depth = 0;
    loop {
        if depth == scene.render.max_depth {
            stats.depth_limited += 1;
            break;
        }
        depth += 1;
        let (prim, position, normal, incoming) = match tracer.next_event(origin, dir, medium, stats)
        {
            Event::Surface {
                prim,
                position,
                normal,
                direction,
            } => (prim, position, normal, direction),
            Event::Escaped(d) => {
                if medium == scene.ambient {
                    if let Some(env) = &scene.environment {
                        emitted += throughput * env.radiance(d);
                    }
                }
                break;
            }
            Event::Lost => break,
        };
        let surface = scene.surfaces[prim];
        let front = incoming.dot(normal) < 0.0;
        let facing = if front { normal } else { -normal };
        match &scene.materials[surface.material] {
            Material::Emissive { radiance } => {
                if front {
                    emitted += throughput * *radiance;
                }
                break;
            }
            Material::Diffuse { albedo } => {
                albedo_aov = *albedo;
                normal_aov = facing;
                let uniform_here = medium.is_none_or(|m| scene.medium_at(m).is_uniform());
                if uniform_here {
                    direct += throughput
                        * *albedo
                        * FRAC_1_PI
                        * direct_irradiance(tracer, position, facing, rng);
                }
                break;
            }
            Material::Mirror { reflectance } => {
                throughput *= *reflectance;
                dir = reflect(incoming, facing);
                origin = offset(position, facing);
            }
            Material::Dielectric => {
                let inside = surface
                    .interior
                    .expect("dielectrics have an interior (checked on load)");
                let to = if front { Some(inside) } else { scene.ambient };
                let index = |m: Option<usize>| {
                    m.map_or(Some(1.0), |i| {
                        scene.medium_at(i).sample(position).map(|s| s.n)
                    })
                };
                let (Some(n1), Some(n2)) = (index(medium), index(to)) else {
                    break;
                };
                let cos_i = -incoming.dot(facing);
                let (r, cos_t) = fresnel(cos_i, n1, n2);
                if rng.gen::<f64>() < r {
                    dir = reflect(incoming, facing);
                    origin = offset(position, facing);
                } else {
                    dir = refract(incoming, facing, n1, n2, cos_t);
                    origin = offset(position, -facing);
                    medium = to;
                }
            }
        }
    }
    [direct + emitted, direct, emitted, albedo_aov, normal_aov]
}

/// Irradiance-weighted cosine sum Σ E·cos θ over one sample of every light at a point with
/// unit `normal` (facing the arriving ray), through straight shadow rays; a shadow ray that
/// meets any surface (a glass or GRIN object included) carries nothing: light through those
/// is the photon maps' part.
fn direct_irradiance(tracer: &Tracer, p: DVec3, normal: DVec3, rng: &mut Pcg64Mcg) -> Rgb {
    let scene = tracer.scene;
    let origin = offset(p, normal);
    let mut sum = Rgb::ZERO;
    for light in &scene.lights {
        let uv = (rng.gen::<f64>(), rng.gen::<f64>());
        let Some(inc) = light.sample_incident(origin, uv) else {
            continue;
        };
        let cos = inc.wi.dot(normal);
        if cos <= 0.0 {
            continue;
        }
        let reach = if inc.distance.is_finite() {
            inc.distance * (1.0 - 1e-7)
        } else {
            f64::INFINITY
        };
        if scene
            .accel
            .intersect_ray(origin, inc.wi, 0.0, reach)
            .is_none()
        {
            sum += inc.irradiance * cos;
        }
    }
    sum
}
