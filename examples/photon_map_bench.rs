//! Photon-map build and query times: photons spread over the six walls of a unit box (as in a
//! room), 5·10³ (a sparse caustic map), 10⁵ and 10⁶ of them; median of 5 runs of each measurement.
//!
//! `cargo run --release --example photon_map_bench`

use glam::DVec3;
use grinlight::photon::{Photon, PhotonMap};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::time::Instant;

fn wall_point(rng: &mut Pcg64Mcg) -> (DVec3, DVec3) {
    let axis = rng.gen_range(0..3);
    let side = if rng.gen::<bool>() { 1.0 } else { 0.0 };
    let mut p = DVec3::new(rng.gen(), rng.gen(), rng.gen());
    p[axis] = side;
    let mut n = DVec3::ZERO;
    n[axis] = if side == 1.0 { -1.0 } else { 1.0 };
    (p, n)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    println!("| photons | build (ms) | precompute k=16 (ms) | nearest site (µs) | within r (k≈16) (µs) | 16 nearest (µs) |");
    println!("|---|---|---|---|---|---|");
    for n in [5_000usize, 100_000, 1_000_000] {
        let mut rng = Pcg64Mcg::seed_from_u64(1);
        let photons: Vec<Photon> = (0..n)
            .map(|_| {
                let (position, normal) = wall_point(&mut rng);
                Photon {
                    position,
                    normal,
                    power: [1.0; 3],
                    from: normal.as_vec3().to_array(),
                    base: 1.0,
                }
            })
            .collect();
        let queries: Vec<(DVec3, DVec3)> = (0..100_000).map(|_| wall_point(&mut rng)).collect();
        // Radius holding ~16 photons: density n/6 per unit area.
        let r2 = 16.0 / (std::f64::consts::PI * n as f64 / 6.0);
        let (mut build, mut pre, mut near, mut within, mut knn) =
            (vec![], vec![], vec![], vec![], vec![]);
        let mut sink = 0.0;
        for _ in 0..5 {
            let t = Instant::now();
            let mut map = PhotonMap::new(photons.clone());
            build.push(t.elapsed().as_secs_f64() * 1e3);
            let t = Instant::now();
            map.precompute_irradiance(16, 1.0);
            pre.push(t.elapsed().as_secs_f64() * 1e3);
            let per = |t: Instant| t.elapsed().as_secs_f64() * 1e6 / queries.len() as f64;
            let t = Instant::now();
            for (p, n) in &queries {
                sink += map.nearest_irradiance(*p, *n).x;
            }
            near.push(per(t));
            let t = Instant::now();
            for (p, n) in &queries {
                sink += map.irradiance(*p, *n, r2).0.x;
            }
            within.push(per(t));
            let t = Instant::now();
            for (p, n) in &queries {
                sink += map.knn_radius2(*p, *n, 16, 1.0);
            }
            knn.push(per(t));
        }
        println!(
            "| {n} | {:.1} | {:.1} | {:.3} | {:.3} | {:.3} |",
            median(build),
            median(pre),
            median(near),
            median(within),
            median(knn)
        );
        assert!(sink.is_finite());
    }
}
