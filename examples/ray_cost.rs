//! The cost of one straight ray against a shipped scene's primitives: nanoseconds a nearest-hit
//! query and an any-hit (shadow) query take, for rays from the camera's position and from the
//! surface points those rays reach, in random directions (uniform on the sphere; a room's
//! rays start inside it, as a path's bounces do). Median of 5 runs of 10⁶ rays each, 1 thread.
//!
//! `cargo run --release --example ray_cost [scene.toml ...]`

use glam::DVec3;
use grinlight::sampling::uniform_sphere;
use grinlight::scene::load::load_scene;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::path::Path;
use std::time::Instant;

/// One query's ray: origin and unit direction.
struct Query {
    origin: DVec3,
    direction: DVec3,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let scenes: Vec<String> = std::env::args().skip(1).collect();
    let scenes = match scenes.is_empty() {
        true => vec!["scenes/cornell_diffuse.toml".to_string()],
        false => scenes,
    };
    println!("| scene | primitives | nearest hit (ns) | any hit, to the nearest hit (ns) |");
    println!("|---|---|---|---|");
    for path in scenes {
        let (scene, _) = load_scene(Path::new(&path)).expect("a shipped scene loads");
        let accel = &scene.accel;
        let start = scene.camera.as_ref().map_or(DVec3::ZERO, |c| c.position);
        let mut rng = Pcg64Mcg::seed_from_u64(7);
        let draw = |rng: &mut Pcg64Mcg| uniform_sphere((rng.gen(), rng.gen()));
        // Origins: the camera, then where rays from the last origin land (a random walk).
        let mut queries = Vec::with_capacity(1_000_000);
        let mut origin = start;
        while queries.len() < 1_000_000 {
            let direction = draw(&mut rng);
            queries.push(Query { origin, direction });
            origin = match accel.intersect_ray(origin, direction, 1e-6, f64::INFINITY) {
                Some(h) => origin + direction * (h.hit.t * (1.0 - 1e-6)),
                None => start,
            };
        }
        let reach: Vec<f64> = (queries.iter())
            .map(|q| {
                (accel.intersect_ray(q.origin, q.direction, 1e-6, f64::INFINITY))
                    .map_or(1e3, |h| h.hit.t * (1.0 - 1e-6))
            })
            .collect();
        let (mut nearest, mut any) = (vec![], vec![]);
        let mut sink = 0.0;
        for _ in 0..5 {
            let t = Instant::now();
            for q in &queries {
                if let Some(h) = accel.intersect_ray(q.origin, q.direction, 1e-6, f64::INFINITY) {
                    sink += h.hit.t;
                }
            }
            nearest.push(t.elapsed().as_secs_f64() * 1e9 / queries.len() as f64);
            let t = Instant::now();
            for (q, &r) in queries.iter().zip(&reach) {
                if accel.blocked(q.origin, q.direction, 1e-6, r, |_| false) {
                    sink += 1.0;
                }
            }
            any.push(t.elapsed().as_secs_f64() * 1e9 / queries.len() as f64);
        }
        println!(
            "| `{path}` | {} | {:.1} | {:.1} |",
            accel.primitives().len(),
            median(nearest),
            median(any)
        );
        std::hint::black_box(sink);
    }
}
