//! The three panels of Zhdanov et al. (2020) fig. 5 for a scene's GRIN fiber, from left to right: the index
//! from the axis to the wall, photon paths through the fiber over its index, and the irradiance
//! on a receiver.

use super::GrinFiber;
use crate::error::{Error, Result};
use crate::plot::{self, Labels, Panel, PALETTE};
use crate::receiver::{draw_heat_map, Measurement, Receiver};
use crate::scene::Scene;
use glam::DVec3;
use std::path::Path;

/// Panel sizes in pixels: profile width, paths width, receiver side, common height, margin.
const PROFILE_W: u32 = 260;
const PATHS_W: u32 = 720;
const RECEIVER: u32 = 300;
const HEIGHT: u32 = 300;
const MARGIN: u32 = 70;

/// Writes the figure to `out` and returns its legend. `paths` are photon paths (as from
/// [`crate::photon::photon_paths`]); they are drawn in the plane through the fiber's axis and
/// a fixed transverse direction (their coordinates along those two), clipped to the fiber
/// and a margin around it, in cycling colours over the index shaded grey (darker = lower n;
/// white outside the fiber).
pub fn write(
    scene: &Scene,
    fiber: &GrinFiber,
    paths: &[Vec<DVec3>],
    receiver: (&Receiver, &Measurement),
    out: &Path,
) -> Result<String> {
    let medium = scene.medium_at(fiber.medium);
    let profile = fiber.profile(medium, 200).ok_or_else(|| {
        Error::Usage("the fiber's index is singular inside it: no profile to draw".into())
    })?;
    let width = PROFILE_W + PATHS_W + RECEIVER + 130 + 4 * MARGIN;
    let mut img = plot::canvas(width, HEIGHT + 2 * MARGIN);
    // Left: n(r) from the axis to the wall.
    let n_range = plot::range_of(profile.iter().map(|p| p.1));
    let mut panel = Panel::new(
        &mut img,
        (MARGIN, MARGIN, PROFILE_W, HEIGHT),
        (0.0, fiber.radius),
        n_range,
        (false, false),
    );
    panel.polyline(&profile, PALETTE[0]);
    panel.axes(&Labels {
        title: "index across the fiber",
        x: "r from the axis (scene units)",
        y: "n",
    });
    // Middle: the paths over the index in the plane (axis, perp).
    let perp = fiber.axis.any_orthonormal_vector();
    let (r, len) = (fiber.radius, fiber.height);
    let along = (-0.05 * len, 1.05 * len);
    let across = (-1.5 * r, 1.5 * r);
    let left = 2 * MARGIN + PROFILE_W;
    let mut panel = Panel::new(
        &mut img,
        (left, MARGIN, PATHS_W, HEIGHT),
        along,
        across,
        (false, false),
    );
    panel.shade(n_range, |h, y| {
        if (0.0..=len).contains(&h) && y.abs() <= r {
            let p = fiber.base + fiber.axis * h + perp * y;
            medium.sample(p).map_or(f64::NAN, |s| s.n)
        } else {
            f64::INFINITY
        }
    });
    for (k, path) in paths.iter().enumerate() {
        let line: Vec<(f64, f64)> = path
            .iter()
            .map(|p| {
                let d = *p - fiber.base;
                (d.dot(fiber.axis), d.dot(perp))
            })
            .collect();
        panel.polyline(&line, PALETTE[k % PALETTE.len()]);
    }
    panel.axes(&Labels {
        title: &format!(
            "{} photon paths over the index (darker = lower n)",
            paths.len()
        ),
        x: "along the axis (scene units)",
        y: "across, in a plane through the axis",
    });
    // Right: the receiver.
    let (rec, m) = receiver;
    draw_heat_map(
        &mut img,
        rec,
        m,
        (3 * MARGIN + PROFILE_W + PATHS_W, MARGIN),
        RECEIVER,
    );
    plot::save(&img, out)?;
    Ok(format!(
        "left: n against r from the axis to the wall (r in [0, {r}], n in [{:.6}, {:.6}]); \
         middle: {} photon paths, horizontal along the axis in [{:.3}, {:.3}], vertical along \
         ({:.3}, {:.3}, {:.3}) in [{:.3}, {:.3}], index shaded (darker = lower n); right: \
         receiver '{}' irradiance (W per unit²), {} × {} bins over {} × {}",
        n_range.0,
        n_range.1,
        paths.len(),
        along.0,
        along.1,
        perp.x,
        perp.y,
        perp.z,
        across.0,
        across.1,
        rec.name,
        rec.bins.0,
        rec.bins.1,
        rec.size.0,
        rec.size.1
    ))
}
