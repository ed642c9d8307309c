//! The acceleration structure: an obvhs `Bvh2` over the primitives' bounds, except stacks of
//! coaxial tubes ([`coaxial`]), which a BVH cannot prune. The BVH knows nothing of primitives:
//! f32 boxes are padded outward, and the closures do the exact f64 test.

mod coaxial;

use coaxial::CoaxialStack;

use crate::bvh::{build_bvh, Tuning};
use crate::curve::{ArcHull, Path};
use crate::ids::PrimId;
use crate::math::Bounds3;
use crate::shapes::{padded_box as padded, Hit, Primitive, SegmentHits, TraversalRay};
use glam::DVec3;
use obvhs::bvh2::Bvh2;
use obvhs::ray::RayHit;
use rayon::prelude::*;

/// A primitive met by a ray or a curved path, and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimHit {
    /// Which primitive.
    pub prim: PrimId,
    /// Where (its `t` is the ray's parameter or the path's arclength).
    pub hit: Hit,
}

/// Primitives with a BVH over them; a hit names its primitive by its place in `primitives`.
pub struct Accel {
    primitives: Vec<Primitive>,
    /// Over the primitives not in a stack.
    bvh: Bvh2,
    /// The primitive in each of the BVH's leaf slots (`bvh.primitive_indices`' order).
    in_slot: Vec<PrimId>,
    stacks: Vec<CoaxialStack>,
}

impl Accel {
    /// Builds the BVH.
    pub fn new(primitives: Vec<Primitive>) -> Self {
        let mut taken = vec![false; primitives.len()];
        let stacks = CoaxialStack::gather(&primitives, &mut taken);
        let in_bvh: Vec<PrimId> = (0..primitives.len())
            .filter(|&i| !taken[i])
            .map(PrimId::new)
            .collect();
        let bvh = build_bvh(
            in_bvh
                .par_iter()
                .map(|&i| padded(primitives[i.index()].bounds())),
            Tuning::Speed,
        );
        let in_slot = (bvh.primitive_indices.iter())
            .map(|&i| in_bvh[i as usize])
            .collect();
        Self {
            primitives,
            bvh,
            in_slot,
            stacks,
        }
    }

    /// The primitives.
    pub fn primitives(&self) -> &[Primitive] {
        &self.primitives
    }

    /// The primitive `id`.
    pub fn primitive(&self, id: PrimId) -> &Primitive {
        &self.primitives[id.index()]
    }

    /// Nearest hit of the straight ray o + t d (d unit), t ∈ (t_min, t_max).
    pub fn intersect_ray(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> Option<PrimHit> {
        let mut best: Option<PrimHit> = None;
        for stack in &self.stacks {
            let limit = best.map_or(t_max, |b| b.hit.t);
            if let Some(hit) = stack.intersect_ray(&self.primitives, o, d, t_min, limit) {
                best = Some(hit);
            }
        }
        if self.in_slot.is_empty() {
            return best;
        }
        // The search ends at t_max or a stack's hit: nodes beyond it are not visited (a free
        // flight in fog ends long before the walls).
        let ray = TraversalRay::new(o, d, best.map_or(t_max, |b| b.hit.t));
        let mut found = RayHit::none();
        self.bvh.ray_traverse(ray.ray, &mut found, |_, i| {
            let prim = self.in_slot[i];
            let limit = best.map_or(t_max, |b| b.hit.t);
            match self.primitive(prim).intersect_ray(o, d, t_min, limit) {
                Some(hit) => {
                    best = Some(PrimHit { prim, hit });
                    TraversalRay::bound(hit.t)
                }
                None => f32::INFINITY,
            }
        });
        best
    }

    /// Whether a surface lies on the straight ray o + t d (d unit), t ∈ (t_min, t_max), other
    /// than those `passes` lets through: an any-hit query, which stops at the first blocking
    /// surface it meets (a shadow ray needs no nearest hit).
    pub fn blocked(
        &self,
        o: DVec3,
        d: DVec3,
        t_min: f64,
        t_max: f64,
        passes: impl Fn(PrimId) -> bool,
    ) -> bool {
        for stack in &self.stacks {
            let mut from = t_min;
            while let Some(b) = stack.intersect_ray(&self.primitives, o, d, from, t_max) {
                if !passes(b.prim) {
                    return true;
                }
                from = b.hit.t;
            }
        }
        if self.in_slot.is_empty() {
            return false;
        }
        let ray = TraversalRay::new(o, d, t_max);
        let missed = self.bvh.ray_traverse_miss(ray.ray, |_, i| {
            let id = self.in_slot[i];
            match self.primitive(id).meets_ray(o, d, t_min, t_max) && !passes(id) {
                // Any value below the ray's bound ends the traversal.
                true => f32::NEG_INFINITY,
                false => f32::INFINITY,
            }
        });
        !missed
    }

    /// Whether the scene has no surface at all.
    pub fn is_empty(&self) -> bool {
        self.primitives.is_empty()
    }

    /// Whether any primitive may meet a path held by `hull` ([`Primitive::may_cross`] on the
    /// primitives whose boxes meet the hull's): false lets a march skip a step's surface
    /// tests (the inside of a fiber, far from its wall).
    pub fn may_hit(&self, hull: &ArcHull) -> bool {
        let bounds = hull.bounds();
        if self.stacks.iter().any(|st| {
            st.bounds().overlaps(&bounds)
                && st.members().any(|id| self.primitive(id).may_cross(hull))
        }) {
            return true;
        }
        let mut found = false;
        if !self.in_slot.is_empty() {
            self.bvh.aabb_traverse(padded(bounds), |bvh, node_index| {
                let node = &bvh.nodes[node_index as usize];
                found = (node.first_index..node.first_index + node.prim_count).any(|i| {
                    let id = self.in_slot[i as usize];
                    self.primitive(id).may_cross(hull)
                });
                !found
            });
        }
        found
    }

    /// Calls `f(id)` for every primitive whose box meets `bounds` (a stack's members when the
    /// stack's box does).
    pub fn boxes_meeting(&self, bounds: Bounds3, mut f: impl FnMut(PrimId)) {
        for stack in &self.stacks {
            if stack.bounds().overlaps(&bounds) {
                stack.members().for_each(&mut f);
            }
        }
        if self.in_slot.is_empty() {
            return;
        }
        self.bvh.aabb_traverse(padded(bounds), |bvh, node_index| {
            let node = &bvh.nodes[node_index as usize];
            for i in node.first_index..node.first_index + node.prim_count {
                let id = self.in_slot[i as usize];
                if self.primitive(id).bounds().overlaps(&bounds) {
                    f(id);
                }
            }
            true
        });
    }
}

impl SegmentHits for Accel {
    type Found = PrimHit;

    fn intersect_segment<P: Path + ?Sized>(
        &self,
        seg: &P,
        hull: &ArcHull,
        s_min: f64,
        length: f64,
    ) -> Option<PrimHit> {
        let bounds = hull.bounds();
        let mut best: Option<PrimHit> = None;
        for stack in &self.stacks {
            if stack.bounds().overlaps(&bounds) {
                let limit = best.map_or(length, |b| b.hit.t);
                if let Some(hit) =
                    stack.intersect_segment(&self.primitives, seg, hull, s_min, limit)
                {
                    best = Some(hit);
                }
            }
        }
        if self.in_slot.is_empty() {
            return best;
        }
        self.bvh.aabb_traverse(padded(bounds), |bvh, node_index| {
            let node = &bvh.nodes[node_index as usize];
            for i in node.first_index..node.first_index + node.prim_count {
                let prim = self.in_slot[i as usize];
                let limit = best.map_or(length, |b| b.hit.t);
                if let Some(hit) = self
                    .primitive(prim)
                    .intersect_segment(seg, hull, s_min, limit)
                {
                    best = Some(PrimHit { prim, hit });
                }
            }
            true
        });
        best
    }
}
