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

use super::PrimHit;
use crate::curve::{ArcHull, Path};
use crate::ids::PrimId;
use crate::math::Bounds3;
use crate::shapes::{Disk, Primitive, SegmentHits};
use glam::DVec3;

/// Fewer coaxial tubes than this are left to the BVH.
const MIN_TUBES: usize = 4;

/// An annular cap at one end of a stack.
#[derive(Clone, Copy, Debug)]
struct Cap {
    inner: f64,
    outer: f64,
    id: PrimId,
}

/// A tube of a stack.
#[derive(Clone, Copy, Debug)]
struct Tube {
    radius: f64,
    id: PrimId,
}

/// Coaxial tubes of one base, axis and height, sorted by radius, and their end caps.
pub(super) struct CoaxialStack {
    base: DVec3,
    axis: DVec3,
    height: f64,
    /// The tubes, radii strictly ascending.
    tubes: Vec<Tube>,
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
        for (i, p) in primitives.iter().enumerate() {
            let id = PrimId::new(i);
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
                    Some(g) => g.tubes.push(Tube { radius, id }),
                    None => groups.push(Self {
                        base,
                        axis,
                        height,
                        tubes: vec![Tube { radius, id }],
                        caps: [Vec::new(), Vec::new()],
                        bounds: p.bounds(),
                    }),
                }
            }
        }
        groups.retain_mut(|g| {
            g.tubes.sort_by(|a, b| a.radius.total_cmp(&b.radius));
            g.tubes.len() >= MIN_TUBES && g.tubes.windows(2).all(|w| w[0].radius < w[1].radius)
        });
        for g in &mut groups {
            let top = g.base + g.axis * g.height;
            for (end, centre) in [g.base, top].into_iter().enumerate() {
                let mut caps: Vec<Cap> = primitives
                    .iter()
                    .enumerate()
                    .filter_map(|(i, p)| match *p {
                        Primitive::Disk(Disk {
                            center,
                            normal,
                            radius,
                            inner,
                        }) if center == centre && (normal == g.axis || normal == -g.axis) => {
                            Some(Cap {
                                inner,
                                outer: radius,
                                id: PrimId::new(i),
                            })
                        }
                        _ => None,
                    })
                    .collect();
                caps.sort_by(|a, b| a.outer.total_cmp(&b.outer));
                if caps.windows(2).all(|w| w[1].inner >= w[0].outer) {
                    for c in &caps {
                        g.bounds = g.bounds.union(primitives[c.id.index()].bounds());
                    }
                    g.caps[end] = caps;
                }
            }
            let outer = primitives[g.tubes.last().expect("MIN_TUBES > 0").id.index()].bounds();
            g.bounds = g.bounds.union(outer);
            for id in g.members() {
                taken[id.index()] = true;
            }
        }
        groups
    }

    /// The stack's box.
    pub fn bounds(&self) -> Bounds3 {
        self.bounds
    }

    /// Nearest hit of the straight ray o + t d (d unit), t ∈ (t_min, t_max).
    pub fn intersect_ray(
        &self,
        primitives: &[Primitive],
        o: DVec3,
        d: DVec3,
        t_min: f64,
        t_max: f64,
    ) -> Option<PrimHit> {
        let oc = o - self.base;
        let (h0, hd) = (oc.dot(self.axis), d.dot(self.axis));
        let (op, dp) = (oc - self.axis * h0, d - self.axis * hd);
        let rho = |t: f64| (op + dp * t).length();
        let mut best: Option<PrimHit> = None;
        let test = |prim: PrimId, best: &mut Option<PrimHit>| {
            let limit = best.map_or(t_max, |b| b.hit.t);
            if let Some(hit) = primitives[prim.index()].intersect_ray(o, d, t_min, limit) {
                *best = Some(PrimHit { prim, hit });
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
            let k = caps.partition_point(|c| c.outer < rho(t));
            for c in &caps[k.saturating_sub(1)..(k + 2).min(caps.len())] {
                test(c.id, &mut best);
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
            let k = self.tubes.partition_point(|t| t.radius <= r);
            let n = self.tubes.len();
            for t in &self.tubes[k.saturating_sub(2)..(k + 2).min(n)] {
                test(t.id, &mut best);
            }
        }
        best
    }

    /// Every member primitive's id (curved segments test them all: they are rare in a stack,
    /// which holds homogeneous layers, and the shell argument above is for straight rays).
    pub fn members(&self) -> impl Iterator<Item = PrimId> + '_ {
        self.tubes
            .iter()
            .map(|t| t.id)
            .chain(self.caps.iter().flatten().map(|c| c.id))
    }

    /// Nearest crossing of a curved path with a member at arclength s ∈ (s_min, length].
    pub fn intersect_segment<P: Path + ?Sized>(
        &self,
        primitives: &[Primitive],
        seg: &P,
        hull: &ArcHull,
        s_min: f64,
        length: f64,
    ) -> Option<PrimHit> {
        let mut best: Option<PrimHit> = None;
        for prim in self.members() {
            let limit = best.map_or(length, |b| b.hit.t);
            if let Some(hit) = primitives[prim.index()].intersect_segment(seg, hull, s_min, limit) {
                best = Some(PrimHit { prim, hit });
            }
        }
        best
    }
}
