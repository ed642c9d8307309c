//! The GRIN fiber as an instrument (Zhdanov et al. (2020) §5): a scene's fiber — a cylinder filled with a
//! gradient medium — its layered twin of homogeneous cylinders in optical contact, made by
//! editing the scene's description and building again ([`Description::layer_fiber`]), the
//! drawing of its photons' paths ([`figure`]); `grinlight validate`
//! ([`crate::commands::validate`]) compares the two on a receiver.

pub mod figure;

use crate::error::{Error, Result};
use crate::ids::MediumId;
use crate::media::{Medium, UniformMedium};
use crate::scene::{Description, Shape, Surface};
use crate::settings::TraceSettings;
use crate::shapes::{Disk, Primitive};
use crate::volume::{Absorption, Participating};
use glam::DVec3;

/// The cylinder filled with a gradient medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GrinFiber {
    /// Centre of the base face.
    pub base: DVec3,
    /// Unit axis.
    pub axis: DVec3,
    /// Radius.
    pub radius: f64,
    /// Length.
    pub height: f64,
    /// Its side's surface (material, interior medium, exterior).
    pub surface: Surface,
    /// The interior medium.
    pub medium: MediumId,
    /// Index of its shape in the description.
    pub shape: usize,
}

impl GrinFiber {
    /// The index of `medium` (the fiber's) along one radius at mid-length, at `samples` + 1
    /// evenly spaced radii from the axis to the wall: (r, n). None where it is singular.
    pub fn profile(&self, medium: &dyn Medium, samples: usize) -> Option<Vec<(f64, f64)>> {
        let perp = self.axis.any_orthonormal_vector();
        let mid = self.base + self.axis * (0.5 * self.height);
        (0..=samples)
            .map(|i| {
                let r = self.radius * i as f64 / samples as f64;
                let n = medium.sample(mid + perp * r)?.n;
                Some((r, n))
            })
            .collect()
    }

    /// The layers of its twin in `medium` (the fiber's): a new layer wherever the index along
    /// a radius has changed by `dn` since the layer's start or the layer is `max_width` wide,
    /// each with the area-weighted mean of the profile over its annulus, innermost first. The
    /// profile is sampled at ≥ 4 points per layer (at its steepest slope); a layering that
    /// would need over 4·10⁵ samples (10⁵ layers) is refused, as is a singular index.
    pub fn layers(
        &self,
        medium: &dyn Medium,
        dn: f64,
        max_width: f64,
    ) -> std::result::Result<Vec<Layer>, String> {
        // The index along one radius, finely sampled: ≥ 4 samples per layer of either limit.
        let singular = || "the fiber's index is singular inside it".to_string();
        let coarse = self.profile(medium, 4000).ok_or_else(singular)?;
        // The steepest change of n from the axis to the wall, as if it held everywhere.
        let steepest = 4000.0
            * coarse
                .windows(2)
                .map(|w| (w[1].1 - w[0].1).abs())
                .fold(0.0, f64::max);
        let wanted = (4.0 * steepest / dn).max(4.0 * self.radius / max_width);
        const MAX_SAMPLES: f64 = 4e5;
        if wanted > MAX_SAMPLES {
            return Err(format!(
                "Δn {dn} and largest width {max_width} would make over {} layers",
                MAX_SAMPLES / 4.0
            ));
        }
        let samples = (wanted.ceil() as usize).max(4000);
        let profile = if samples == 4000 {
            coarse
        } else {
            self.profile(medium, samples).ok_or_else(singular)?
        };
        let mut layers = Vec::new();
        let (mut start, mut n_start) = (0, profile[0].1);
        for i in 1..=samples {
            let width = profile[i].0 - profile[start].0;
            if (profile[i].1 - n_start).abs() >= dn
                || width >= max_width * (1.0 - 1e-9)
                || i == samples
            {
                // Area-weighted mean of n over [r_start, r_i] (trapezoid rule on n·r).
                let (mut num, mut den) = (0.0, 0.0);
                for w in profile[start..=i].windows(2) {
                    let dr = w[1].0 - w[0].0;
                    num += 0.5 * (w[0].1 * w[0].0 + w[1].1 * w[1].0) * dr;
                    den += 0.5 * (w[0].0 + w[1].0) * dr;
                }
                layers.push(Layer {
                    inner: profile[start].0,
                    outer: profile[i].0,
                    n: num / den,
                });
                (start, n_start) = (i, profile[i].1);
            }
        }
        Ok(layers)
    }
}

/// One homogeneous layer of a fiber's layered twin: outer radius and index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// Inner radius (scene units).
    pub inner: f64,
    /// Outer radius.
    pub outer: f64,
    /// Index: the profile's area-weighted mean over the annulus.
    pub n: f64,
}

impl Description {
    /// The first shape with a cylinder side whose interior is a non-uniform medium.
    pub fn grin_fiber(&self) -> Option<GrinFiber> {
        self.shapes.iter().enumerate().find_map(|(k, shape)| {
            let medium = shape
                .surface
                .interior
                .filter(|&m| !self.media.at(m).is_uniform())?;
            shape.primitives.iter().find_map(|p| match *p {
                Primitive::Tube {
                    base,
                    axis,
                    radius,
                    height,
                } => Some(GrinFiber {
                    base,
                    axis,
                    radius,
                    height,
                    surface: shape.surface,
                    medium,
                    shape: k,
                }),
                _ => None,
            })
        })
    }

    /// Replaces the description's GRIN fiber — the cylinder whose interior is a non-uniform
    /// medium — by concentric homogeneous cylinders in optical contact (Zhdanov et al. (2020) §5): a new
    /// layer wherever the index along a radius has changed by `dn` since the layer's start
    /// or the layer is `max_width` wide (∞: no limit; see below), each with the area-weighted
    /// mean of the profile over its annulus, each layer a tube (a dielectric between it and
    /// the next layer out) with annular end faces. The index is read along one radius at
    /// mid-length, so the profile must be radial (parabolic, sech, a radial table, or a radial
    /// grid), at ≥ 4 samples per layer (so no layer is coarser than asked); a layering that
    /// would need over 4·10⁵ samples (10⁵ layers) is refused. Returns the layers, innermost
    /// first.
    ///
    /// Layers of equal Δn are wide where the profile is flat — near the axis of a parabolic
    /// fiber the first is R·√(Δn/Δn_total) wide — and a ray inside a homogeneous layer feels
    /// no gradient: a paraxial ray at angle θ crosses only ≈ n₀θ²/(2Δn) layers, and one
    /// parallel to the axis none. `max_width` bounds that error where the index barely changes.
    ///
    /// Every layer boundary is a surface event for the twin where the GRIN fiber has none: a
    /// path that meets k surfaces in the GRIN fiber meets up to ≈ 2·layers·k in the twin (each
    /// sweep from wall to wall crosses every boundary twice), so `trace.max_depth` is
    /// multiplied by 2·layers + 1.
    pub fn layer_fiber(
        &mut self,
        trace: &mut TraceSettings,
        dn: f64,
        max_width: f64,
    ) -> Result<Vec<Layer>> {
        let usage = |m: &str| Error::Usage(format!("{}: {m}", self.path.display()));
        if !(dn.is_finite() && dn > 0.0) {
            return Err(usage("Δn must be a finite number > 0"));
        }
        if max_width.is_nan() || max_width <= 0.0 {
            return Err(usage("the largest layer width must be > 0"));
        }
        let fiber = self
            .grin_fiber()
            .ok_or_else(|| usage("no cylinder filled with a gradient medium to layer"))?;
        let medium = self.media.at(fiber.medium);
        let layers = fiber.layers(medium, dn, max_width).map_err(|m| usage(&m))?;
        let GrinFiber {
            base,
            axis,
            radius: _,
            height,
            surface,
            shape,
            ..
        } = fiber;
        let top = base + axis * height;
        let uv_frame = self.shapes[shape].uv_frame;
        // The fiber's shape (its tube and end faces) gives way to one shape per layer: a tube
        // with the next layer (or the fiber's exterior) outside, and two annular end faces.
        let mut twin = Vec::with_capacity(layers.len());
        let first_medium = self.media.len();
        // Each layer keeps the GRIN medium's radiometry: its absorption (at the layer's
        // middle radius, density included), its scattering (a density field and all) and its
        // emission.
        let radiometry = self.media.participating(fiber.medium).clone();
        let side = axis.any_orthonormal_vector();
        for (i, l) in layers.iter().enumerate() {
            let inside: Box<dyn Medium> = Box::new(UniformMedium { n: l.n });
            let middle = base + side * (0.5 * (l.inner + l.outer));
            let layer = self.media.add(format!("layer {i} (n {:.6})", l.n), inside);
            self.media.set_participating(
                layer,
                Participating {
                    absorption: radiometry.absorption.as_ref().map(|_| Absorption {
                        sigma_a: radiometry.sigma_a(middle),
                        density: None,
                    }),
                    ..radiometry.clone()
                },
            );
            let outside = if i + 1 < layers.len() {
                Some(MediumId::new(first_medium + i + 1))
            } else {
                surface.exterior
            };
            twin.push(Shape {
                primitives: vec![Primitive::Tube {
                    base,
                    axis,
                    radius: l.outer,
                    height,
                }],
                surface: Surface {
                    interior: Some(layer),
                    exterior: outside,
                    ..surface
                },
                uv_frame,
            });
            twin.push(Shape {
                primitives: [(base, -axis), (top, axis)]
                    .map(|(center, normal)| {
                        Primitive::Disk(Disk {
                            center,
                            normal,
                            radius: l.outer,
                            inner: l.inner,
                        })
                    })
                    .to_vec(),
                surface: Surface {
                    interior: Some(layer),
                    ..surface
                },
                uv_frame,
            });
        }
        self.shapes.splice(shape..=shape, twin);
        let factor = 2 * u32::try_from(layers.len()).unwrap_or(u32::MAX / 2) + 1;
        trace.max_depth = trace.max_depth.saturating_mul(factor);
        Ok(layers)
    }
}
