//! The visibility query: the one shadow ray. A straight connection from a point through a
//! uniform medium is blocked by any surface but a receiver's detector (detectors are
//! transparent to every query), and keeps exp(−∫σa ds) of the light.

use super::{offset, Tracer};
use crate::material::Material;
use glam::DVec3;

/// The fraction of light kept along the straight segment from `from` along unit `dir` over
/// `reach` (∞: to the world sphere) in `medium`: 0 if a surface other than a detector lies
/// on it, else its transmittance.
pub fn transmittance(
    tracer: &Tracer,
    from: DVec3,
    medium: Option<usize>,
    dir: DVec3,
    reach: f64,
) -> f64 {
    let scene = tracer.scene;
    let (mut o, mut left) = (from, reach);
    while let Some((prim, h)) = scene.accel.intersect_ray(o, dir, 0.0, left) {
        if !matches!(
            scene.materials[scene.surfaces[prim].material],
            Material::Detector { .. }
        ) {
            return 0.0;
        }
        let next = offset(o + h.t * dir, dir);
        left -= (next - o).dot(dir);
        o = next;
    }
    match medium.map(|m| tracer.medium(m)) {
        Some(m) if m.absorbs() => {
            let length = reach.min(tracer.world.exit_distance(from, dir));
            (-m.optical_depth(from, dir, length)).exp()
        }
        _ => 1.0,
    }
}
