//! Concentric tubes sharing one axis and length — a layered fiber — with the annular end caps
//! between them. A BVH cannot help here: each tube's box contains every inner tube's box, so a
//! ray inside the stack would test every layer, and a photon crossing N layers would cost O(N²).
//!
//! Inside the stack's slab (0 ≤ h ≤ height along the axis) every tube exists, and ρ(t), the
//! distance of the straight ray from the axis, is continuous: the first tube the ray meets is one
//! of the two that bound the shell it is in when it enters the slab (or starts). The first cap it
//! meets is the annulus that contains the point where it crosses a cap plane. Both are found by
//! binary search, and the candidates (with one neighbour either side, so a point a rounding error
//! from a boundary is safe) are tested exactly: O(log N) per ray.

use crate::curve::{ArcHull, Path};
use crate::math::Bounds3;
use crate::shapes::{Hit, Primitive};
use glam::DVec3;

/// Fewer coaxial tubes than this are left to the BVH.
const MIN_TUBES: usize = 4;

/// An annular cap at one end: (inner radius, outer radius, primitive id).
type Cap = (f64, f64, usize);

/// Coaxial tubes of one base, axis and height, sorted by radius, and their end caps.
pub(super) struct CoaxialStack {
    base: DVec3,
    axis: DVec3,
    height: f64,
    /// Tube radii, strictly ascending, and each tube's primitive id.
    tubes: Vec<(f64, usize)>,
    /// Caps at the base (h = 0) and the top (h = height), sorted and non-overlapping.
    caps: [Vec<Cap>; 2],
    /// The stack's box.
    bounds: Bounds3,
}

impl CoaxialStack {
    /// Finds the stacks among `primitives`; `taken[i]` is set for each primitive they hold.
    /// A group qualifies with at least [`MIN_TUBES`] tubes of distinct radii; a cap joins it when
    /// it is a disk centred on an end with the axis as normal and the group's caps at that end
    /// do not overlap (otherwise they all stay in the BVH, where any layout is correct).
    pub fn gather(primitives: &[Primitive], taken: &mut [bool]) -> Vec<Self> {
        let mut groups: Vec<Self> = Vec::new();
        for (id, p) in primitives.iter().enumerate() {
            if let Primitive::Tube {
                base,
                axis,
                radius,
                height,
            } = *p
            {
                match groups
                    .iter_mut()
                    .find(|g| g.base == base && g.axis == axis && g.height == height)
                {
                    Some(g) => g.tubes.push((radius, id)),
                    None => groups.push(Self {
                        base,
                        axis,
                        height,
                        tubes: vec![(radius, id)],
                        caps: [Vec::new(), Vec::new()],
                        bounds: p.bounds(),
                    }),
                }
            }
        }
        groups.retain_mut(|g| {
            g.tubes.sort_by(|a, b| a.0.total_cmp(&b.0));
            g.tubes.len() >= MIN_TUBES && g.tubes.windows(2).all(|w| w[0].0 < w[1].0)
        });
        for g in &mut groups {
            let top = g.base + g.axis * g.height;
            for (end, centre) in [g.base, top].into_iter().enumerate() {
                let mut caps: Vec<Cap> = primitives
                    .iter()
                    .enumerate()
                    .filter_map(|(id, p)| match *p {
                        Primitive::Disk {
                            center,
                            normal,
                            radius,
                            inner,
                        } if center == centre && (normal == g.axis || normal == -g.axis) => {
                            Some((inner, radius, id))
                        }
                        _ => None,
                    })
                    .collect();
                caps.sort_by(|a, b| a.1.total_cmp(&b.1));
                if caps.windows(2).all(|w| w[1].0 >= w[0].1) {
                    for c in &caps {
                        g.bounds = g.bounds.union(primitives[c.2].bounds());
                    }
                    g.caps[end] = caps;
                }
            }
            let outer = primitives[g.tubes.last().expect("MIN_TUBES > 0").1].bounds();
            g.bounds = g.bounds.union(outer);
            for id in g.members() {
                taken[id] = true;
            }
        }
        groups
    }

    /// The stack's box.
    pub fn bounds(&self) -> Bounds3 {
        self.bounds
    }

    /// Nearest hit of the straight ray o + t d (d unit), t ∈ (t_min, t_max), as (id, hit).
    pub fn intersect_ray(
        &self,
        primitives: &[Primitive],
        o: DVec3,
        d: DVec3,
        t_min: f64,
        t_max: f64,
    ) -> Option<(usize, Hit)> {
        let oc = o - self.base;
        let (h0, hd) = (oc.dot(self.axis), d.dot(self.axis));
        let (op, dp) = (oc - self.axis * h0, d - self.axis * hd);
        let rho = |t: f64| (op + dp * t).length();
        let mut best: Option<(usize, Hit)> = None;
        let test = |id: usize, best: &mut Option<(usize, Hit)>| {
            let limit = best.map_or(t_max, |(_, h)| h.t);
            if let Some(h) = primitives[id].intersect_ray(o, d, t_min, limit) {
                *best = Some((id, h));
            }
        };
        // Caps: the annulus holding the crossing of each end plane.
        for (end, caps) in self.caps.iter().enumerate() {
            if caps.is_empty() || hd == 0.0 {
                continue;
            }
            let t = (end as f64 * self.height - h0) / hd;
            if t <= t_min || t >= t_max {
                continue;
            }
            let k = caps.partition_point(|c| c.1 < rho(t));
            for c in &caps[k.saturating_sub(1)..(k + 2).min(caps.len())] {
                test(c.2, &mut best);
            }
        }
        // Tubes: the two bounding the shell where the ray is first inside the slab.
        let (enter, leave) = if hd == 0.0 {
            if (0.0..=self.height).contains(&h0) {
                (t_min, t_max)
            } else {
                return best;
            }
        } else {
            let (a, b) = ((0.0 - h0) / hd, (self.height - h0) / hd);
            (t_min.max(a.min(b)), t_max.min(a.max(b)))
        };
        if enter <= leave {
            let r = rho(enter);
            let k = self.tubes.partition_point(|&(radius, _)| radius <= r);
            let n = self.tubes.len();
            for &(_, id) in &self.tubes[k.saturating_sub(2)..(k + 2).min(n)] {
                test(id, &mut best);
            }
        }
        best
    }

    /// Every member primitive's id (curved segments test them all: they are rare in a stack,
    /// which holds homogeneous layers, and the shell argument above is for straight rays).
    pub fn members(&self) -> impl Iterator<Item = usize> + '_ {
        self.tubes
            .iter()
            .map(|t| t.1)
            .chain(self.caps.iter().flatten().map(|c| c.2))
    }

    /// Nearest crossing of a curved path with a member at arclength s ∈ (s_min, length].
    pub fn intersect_segment<P: Path + ?Sized>(
        &self,
        primitives: &[Primitive],
        seg: &P,
        hull: &ArcHull,
        s_min: f64,
        length: f64,
    ) -> Option<(usize, Hit)> {
        let mut best: Option<(usize, Hit)> = None;
        for id in self.members() {
            let limit = best.map_or(length, |(_, h)| h.t);
            if let Some(h) = primitives[id].intersect_segment(seg, hull, s_min, limit) {
                best = Some((id, h));
            }
        }
        best
    }
}
