//! The rough plastic against the layer it stands for, simulated light ray by light ray: a
//! rough dielectric coat (GGX, α, index η over the outside) on a Lambertian base of albedo ρ,
//! light walking over the coat's microsurface (Heitz et al. 2016: every order, nothing lost)
//! and bouncing between coat and base until it leaves or the base absorbs it. Prints, for
//! light arriving at θo, the BRDF the layer shows at directions away from the coat's specular
//! peak (f from the share of rays leaving within 4° of them, with its standard error),
//! grinlight's plastic `eval` there, and their ratio; and the albedo of both.
//! `bench/mitsuba_plastic.py` adds Mitsuba 3's `roughplastic` to the table.
//!
//!     cargo run --release --example plastic_layer [ALPHA] [ETA] [RHO] [RAYS]
use glam::DVec3;
use grinlight::bsdf::{walk, Bsdf, Coat, Microsurface};
use grinlight::color::Rgb;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;

fn flip(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.y, -v.z)
}

/// Where a ray arriving along −`o` (o.z > 0) leaves the layer: Some(direction) above it, None
/// where the base absorbs it.
fn through_layer(
    g: &Microsurface,
    eta: f64,
    rho: f64,
    o: DVec3,
    rng: &mut Pcg64Mcg,
) -> Option<DVec3> {
    let exit = walk::dielectric(g, 1.0, eta, o, (rng.gen(), rng.gen(), rng.gen()))?;
    if exit.wi.z > 0.0 {
        return Some(exit.wi);
    }
    loop {
        // At the base: absorbed, or sent up (cosine-distributed).
        if rng.gen::<f64>() >= rho {
            return None;
        }
        let (r, phi) = (rng.gen::<f64>().sqrt(), 2.0 * PI * rng.gen::<f64>());
        let up = DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - r * r).max(0.0).sqrt());
        // The coat from below: its microsurface upside down, the layer's index on the near side.
        let exit = walk::dielectric(g, eta, 1.0, -flip(up), (rng.gen(), rng.gen(), rng.gen()))?;
        let out = flip(exit.wi);
        if out.z > 0.0 {
            return Some(out);
        }
    }
}

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let alpha = args.first().copied().unwrap_or(0.1);
    let eta = args.get(1).copied().unwrap_or(1.5);
    let rho = args.get(2).copied().unwrap_or(0.8);
    let rays = args.get(3).copied().unwrap_or(4e6) as usize;
    let g = Microsurface::ggx(alpha);
    let coat = Coat::new(eta, g);
    let plastic = Bsdf::Plastic {
        albedo: Rgb::splat(rho),
        coat: &coat,
    };
    let cap = 4f64.to_radians();
    let cap_solid = 2.0 * PI * (1.0 - cap.cos());
    println!("α {alpha}, η {eta}, ρ {rho}: {rays} rays a row");
    println!("θo   θi   φ     layer f             plastic f  ratio");
    let mut rng = Pcg64Mcg::seed_from_u64(1);
    for to in [0.0f64, 30.0, 60.0, 75.0, 85.0] {
        let t = to.to_radians();
        let o = DVec3::new(t.sin(), 0.0, t.cos());
        let targets: Vec<(f64, f64, DVec3)> = [0.0f64, 30.0, 60.0, 75.0, 85.0]
            .iter()
            .flat_map(|&ti| {
                [0.0f64, 90.0].map(|phi| {
                    let (a, p) = (ti.to_radians(), phi.to_radians());
                    (
                        ti,
                        phi,
                        DVec3::new(a.sin() * p.cos(), a.sin() * p.sin(), a.cos()),
                    )
                })
            })
            .collect();
        let mut counts = vec![0usize; targets.len()];
        let mut left = 0usize;
        for _ in 0..rays {
            if let Some(d) = through_layer(&g, eta, rho, o, &mut rng) {
                left += 1;
                for (k, (_, _, i)) in targets.iter().enumerate() {
                    if d.dot(*i) >= cap.cos() {
                        counts[k] += 1;
                    }
                }
            }
        }
        for (k, (ti, phi, i)) in targets.iter().enumerate() {
            // Where the cap reaches the horizon it is cut; near the mirror direction the coat's
            // specular lobe, not the layer's diffuse light, decides.
            let mirror = DVec3::new(-o.x, -o.y, o.z);
            if ti + 4.0 > 90.0 || i.dot(mirror) > 15f64.to_radians().cos() {
                continue;
            }
            let scale = rays as f64 * cap_solid * i.z;
            let layer = counts[k] as f64 / scale;
            let se = (counts[k] as f64).sqrt() / scale;
            let f = plastic.eval(o, *i, DVec3::Z).0.x;
            println!(
                "{to:<4} {ti:<4} {phi:<5} {layer:.5} ± {se:.5}   {f:.5}    {:.4}",
                f / layer
            );
        }
        // The plastic's albedo by quadrature over the hemisphere (midpoint in cos² and φ).
        let (nt, np) = (400, 200);
        let mut albedo = 0.0;
        for a in 0..nt {
            let c = ((a as f64 + 0.5) / nt as f64).sqrt();
            let s = (1.0 - c * c).sqrt();
            for b in 0..np {
                let phi = 2.0 * PI * (b as f64 + 0.5) / np as f64;
                let i = DVec3::new(s * phi.cos(), s * phi.sin(), c);
                albedo += plastic.eval(o, i, DVec3::Z).0.x;
            }
        }
        albedo *= PI / (nt * np) as f64;
        println!(
            "θo {to}: albedo layer {:.4}, plastic {albedo:.4}",
            left as f64 / rays as f64
        );
    }
}
