//! `[[receiver]]`: detector planes. Every key's unit and default is in `docs/scene-format.md`.

use crate::error::Result;
use crate::receiver::Receiver;
use crate::scene::table::TableReader;
use crate::spectrum::{LAMBDA_MAX, LAMBDA_MIN};
use glam::DVec3;

/// A `[[receiver]]` called `name`: a detector rectangle.
pub fn read_receiver(t: &mut TableReader, name: String) -> Result<Receiver> {
    let center = t.vec3("center")?;
    let normal = t.direction_or("normal", DVec3::Z)?;
    let up = t.direction_or("up", DVec3::Y)?;
    let u = up.cross(normal);
    t.check("up", u.length() > 1e-9, "must not be parallel to `normal`")?;
    let u = u.normalize();
    let size = t
        .f64_list_opt("size")?
        .ok_or_else(|| t.error("size", "is missing"))?;
    t.check(
        "size",
        size.len() == 2 && size.iter().all(|s| *s > 0.0 && s.is_finite()),
        "expected [width, height], both > 0",
    )?;
    let [nx, ny] = t.counts::<2>("bins")?;
    t.check(
        "bins",
        (1..=4096).contains(&nx) && (1..=4096).contains(&ny),
        "each must be in 1..=4096",
    )?;
    let bands = t.vec2_list_opt("bands")?.unwrap_or_default();
    t.check(
        "bands",
        bands
            .iter()
            .all(|&(lo, hi)| LAMBDA_MIN <= lo && lo < hi && hi <= LAMBDA_MAX),
        format!("each band is [lo_nm, hi_nm] with {LAMBDA_MIN} ≤ lo < hi ≤ {LAMBDA_MAX}"),
    )?;
    Ok(Receiver {
        bands,
        name,
        center,
        u,
        v: normal.cross(u),
        size: (size[0], size[1]),
        bins: (nx, ny),
    })
}
