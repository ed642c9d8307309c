//! Building a BVH: a top-down binned surface-area-heuristic build (Wald (2007), "On fast
//! construction of SAH-based bounding volume hierarchies"), in place over compact boxes.
//!
//! Working memory is the primitives' f32 boxes (24 bytes each), their order (4 bytes each,
//! which becomes the BVH's leaf order) and the nodes themselves (32 bytes each, at most
//! 2 n − 1, written as the build goes): nothing else grows with n. The result is an
//! obvhs [`Bvh2`] — root at index 0, an inner node's children at `first_index` and
//! `first_index + 1`, a leaf's primitives at `primitive_indices[first_index..][..prim_count]`
//! — so every traversal in obvhs and grinlight reads it as before.

use glam::{Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::bvh2::node::Bvh2Node;
use obvhs::bvh2::Bvh2;
use rayon::prelude::*;

/// Bins a node's primitives fall into along each axis, by their boxes' centres.
const BINS: usize = 16;
/// What a tree is built for: the surface-area heuristic's cost of visiting a node, relative
/// to testing one primitive (the SAH's constant; Wald 2007), decides how eagerly small
/// leaves are split. A low cost means more nodes and fewer primitive tests a ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tuning {
    /// A scene's primitives: few, large and often surrounding the rays (a room's walls,
    /// whose boxes' union is the room, so a leaf of two walls is entered by every ray in the
    /// room — a case the heuristic's rays from outside do not see). Node cost 1/2, as
    /// pbrt-v4's build: in the Cornell box a ray tests 1.6 primitives where it tested 5.7 at
    /// 1.5, a shadow ray 2.0 where it tested 5.4.
    Speed,
    /// Many small primitives (a mesh's triangles, volume photons' balls): node cost 1.5, so
    /// leaves keep several primitives and the tree few nodes (its bytes a primitive count).
    Memory,
}

impl Tuning {
    /// The cost of visiting a node, relative to testing one primitive: a node's test is one
    /// f32 box, a primitive's an exact f64 test after its own box.
    fn node_cost(self) -> f32 {
        match self {
            Tuning::Speed => 0.5,
            Tuning::Memory => 1.5,
        }
    }
}

/// The most primitives a leaf holds; more are always split.
const MAX_LEAF: usize = 8;
/// Nodes of more primitives than this are binned in parallel, in chunks of this many.
const PARALLEL_BINNING: usize = 1 << 16;

/// A primitive's box as the build keeps it: f32 corners, 24 bytes (obvhs's [`Aabb`] is 32).
#[derive(Clone, Copy, Debug)]
struct Packed {
    lo: Vec3,
    hi: Vec3,
}

impl Packed {
    fn of(aabb: &Aabb) -> Self {
        Self {
            lo: aabb.min.into(),
            hi: aabb.max.into(),
        }
    }

    fn unpack(self) -> Bounds {
        Bounds {
            lo: self.lo.into(),
            hi: self.hi.into(),
        }
    }
}

/// An f32 box in SIMD lanes, for the build's sums.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    lo: Vec3A,
    hi: Vec3A,
}

impl Bounds {
    /// The empty box: growing it by a box gives that box.
    const EMPTY: Self = Self {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
    };

    fn aabb(self) -> Aabb {
        Aabb::new(self.lo, self.hi)
    }

    fn grow(self, other: Self) -> Self {
        Self {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    fn grow_point(self, p: Vec3A) -> Self {
        Self {
            lo: self.lo.min(p),
            hi: self.hi.max(p),
        }
    }

    /// Half the surface area (0 for the empty box).
    fn half_area(self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    /// Twice the centre (a primitive's binning key; the factor 2 cancels).
    fn centre2(self) -> Vec3A {
        self.lo + self.hi
    }
}

/// What a set of primitives spans: the box of their boxes, and the box of their (doubled)
/// centres, by which they are binned.
#[derive(Clone, Copy, Debug)]
struct Hull {
    bounds: Bounds,
    centres: Bounds,
}

impl Hull {
    const EMPTY: Self = Self {
        bounds: Bounds::EMPTY,
        centres: Bounds::EMPTY,
    };

    fn add(self, b: Bounds) -> Self {
        Self {
            bounds: self.bounds.grow(b),
            centres: self.centres.grow_point(b.centre2()),
        }
    }

    fn merge(self, other: Self) -> Self {
        Self {
            bounds: self.bounds.grow(other.bounds),
            centres: self.centres.grow(other.centres),
        }
    }

    /// The hull of `refs`.
    fn of(refs: &[Packed]) -> Self {
        let fold = |refs: &[Packed]| refs.iter().fold(Self::EMPTY, |h, r| h.add(r.unpack()));
        if refs.len() <= PARALLEL_BINNING {
            return fold(refs);
        }
        refs.par_chunks(PARALLEL_BINNING)
            .map(fold)
            .reduce(|| Self::EMPTY, Self::merge)
    }
}

/// A bin: the box of the primitives in it and their number.
#[derive(Clone, Copy)]
struct Bin {
    bounds: Bounds,
    count: usize,
}

impl Bin {
    const EMPTY: Self = Self {
        bounds: Bounds::EMPTY,
        count: 0,
    };

    fn merge(self, other: Self) -> Self {
        Self {
            bounds: self.bounds.grow(other.bounds),
            count: self.count + other.count,
        }
    }
}

/// Where a node's primitives go into bins, along each axis at once: bin ⌊(c − lo)·scale⌋ of
/// their boxes' doubled centres c (to within a rounding at the bins' edges), clamped to the
/// last of `count` (scale 0 along an axis where the centres coincide: every primitive in bin
/// 0 there).
#[derive(Clone, Copy)]
struct Binning {
    lo: Vec3A,
    scale: Vec3A,
    count: usize,
}

/// 2²³: added to a float x in [0, 2²²], it leaves round(x) in the low bits of the sum's
/// mantissa — a float-to-integer conversion without `as`'s checks for NaN and overflow, which
/// cost more than the rest of binning a primitive.
const ROUNDING: f32 = 8_388_608.0;

impl Binning {
    fn new(centres: Bounds, count: usize) -> Self {
        let extent = centres.hi - centres.lo;
        let scale = Vec3A::select(
            extent.cmpgt(Vec3A::ZERO),
            Vec3A::splat(count as f32 * (1.0 - 1e-6)) / extent,
            Vec3A::ZERO,
        );
        Self {
            lo: centres.lo,
            scale,
            count,
        }
    }

    /// The bins of `b` along x, y and z.
    fn bins(self, b: Bounds) -> [usize; 3] {
        let x = ((b.centre2() - self.lo) * self.scale - Vec3A::splat(0.5))
            .max(Vec3A::ZERO)
            .min(Vec3A::splat(self.count as f32 - 1.0))
            + Vec3A::splat(ROUNDING);
        x.to_array().map(|v| (v.to_bits() & 0x7f_ffff) as usize)
    }

    /// The primitives of `refs` binned along each axis (`B` ≥ `self.count` bins).
    fn fill<const B: usize>(self, refs: &[Packed]) -> [[Bin; B]; 3] {
        let fill = |refs: &[Packed]| {
            let mut bins = [[Bin::EMPTY; B]; 3];
            for r in refs {
                let b = r.unpack();
                let k = self.bins(b);
                for (axis, bins) in bins.iter_mut().enumerate() {
                    let bin = &mut bins[k[axis]];
                    bin.bounds = bin.bounds.grow(b);
                    bin.count += 1;
                }
            }
            bins
        };
        if refs.len() <= PARALLEL_BINNING {
            return fill(refs);
        }
        refs.par_chunks(PARALLEL_BINNING).map(fill).reduce(
            || [[Bin::EMPTY; B]; 3],
            |a, b| {
                std::array::from_fn(|axis| std::array::from_fn(|k| a[axis][k].merge(b[axis][k])))
            },
        )
    }
}

/// How a node ends.
enum Choice {
    Leaf,
    /// Split along `axis` at bin `first_right` of `binning`, into two children with these
    /// boxes.
    Split {
        binning: Binning,
        axis: usize,
        first_right: usize,
        left: Bounds,
        right: Bounds,
    },
    /// The centres all coincide and there are too many to keep: halves by order.
    Halves,
}

/// The SAH's choice for the primitives `refs` within `hull`: all three axes binned in one
/// pass, into as many bins as there are primitives up to [`BINS`].
fn choose(refs: &[Packed], hull: Hull, tuning: Tuning) -> Choice {
    // The bins' arrays as small as the node: most nodes are near the leaves.
    match refs.len() {
        1 => Choice::Leaf,
        2..=4 => choose_in::<4>(refs, hull, tuning),
        5..=8 => choose_in::<8>(refs, hull, tuning),
        _ => choose_in::<BINS>(refs, hull, tuning),
    }
}

/// [`choose`] with arrays of `B` bins.
fn choose_in<const B: usize>(refs: &[Packed], hull: Hull, tuning: Tuning) -> Choice {
    let n = refs.len();
    let count = n.min(B);
    let binning = Binning::new(hull.centres, count);
    let bins = binning.fill::<B>(refs);
    let area = hull.bounds.half_area().max(f32::MIN_POSITIVE);
    let mut best: Option<(f32, Choice)> = None;
    for (axis, bins) in bins.iter().enumerate() {
        if binning.scale[axis] == 0.0 {
            continue;
        }
        let bins = &bins[..count];
        // Right sides swept from the last bin: right[k] holds bins k..count.
        let mut right = [Bin::EMPTY; B];
        for k in (1..count).rev() {
            right[k] = bins[k].merge(right.get(k + 1).copied().unwrap_or(Bin::EMPTY));
        }
        let mut left = Bin::EMPTY;
        for k in 1..count {
            left = left.merge(bins[k - 1]);
            if left.count == 0 || right[k].count == 0 {
                continue;
            }
            let cost = tuning.node_cost()
                + (left.bounds.half_area() * left.count as f32
                    + right[k].bounds.half_area() * right[k].count as f32)
                    / area;
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                let choice = Choice::Split {
                    binning,
                    axis,
                    first_right: k,
                    left: left.bounds,
                    right: right[k].bounds,
                };
                best = Some((cost, choice));
            }
        }
    }
    match best {
        Some((cost, _)) if n <= MAX_LEAF && n as f32 <= cost => Choice::Leaf,
        Some((_, split)) => split,
        None if n <= MAX_LEAF => Choice::Leaf,
        None => Choice::Halves,
    }
}

/// Moves the primitives of bins below `first_right` along `axis` to the front of `refs`
/// (and their indices in `order` with them); returns how many there are and the centres'
/// boxes of the two sides.
fn partition(
    refs: &mut [Packed],
    order: &mut [u32],
    binning: Binning,
    axis: usize,
    first_right: usize,
) -> (usize, Bounds, Bounds) {
    let (mut i, mut j) = (0, refs.len());
    let (mut left, mut right) = (Bounds::EMPTY, Bounds::EMPTY);
    while i < j {
        let b = refs[i].unpack();
        if binning.bins(b)[axis] < first_right {
            left = left.grow_point(b.centre2());
            i += 1;
        } else {
            right = right.grow_point(b.centre2());
            j -= 1;
            refs.swap(i, j);
            order.swap(i, j);
        }
    }
    (i, left, right)
}

/// A node still to be decided: its index, its primitives' range and hull, its depth, and what
/// its tree is built for.
#[derive(Clone, Copy)]
struct Task {
    node: usize,
    start: usize,
    end: usize,
    hull: Hull,
    depth: usize,
    tuning: Tuning,
}

/// Nodes being written: `slots[used..]` free, node `i` of the slots at index `base + i`
/// of the whole BVH.
struct Slots<'a> {
    slots: &'a mut [Bvh2Node],
    used: usize,
    base: usize,
}

impl Slots<'_> {
    /// Places a pair of children; returns the BVH index of the first.
    fn pair(&mut self, left: Bounds, right: Bounds) -> usize {
        self.slots[self.used] = Bvh2Node::new(left.aabb(), 0, 0);
        self.slots[self.used + 1] = Bvh2Node::new(right.aabb(), 0, 0);
        self.used += 2;
        self.base + self.used - 2
    }

    fn set(&mut self, node: usize, value: Bvh2Node) {
        self.slots[node - self.base] = value;
    }
}

/// Decides `root` and everything below it, writing nodes into `nodes` (`root.node` already
/// there), except that a node of fewer than `defer_below` primitives is put in `deferred`
/// undecided. `refs` and `order` are the primitives of the tasks' ranges; a leaf's primitives
/// sit at `offset + start` of the whole leaf order. Returns the deepest depth reached.
fn grow(
    nodes: &mut Slots,
    refs: &mut [Packed],
    order: &mut [u32],
    offset: usize,
    root: Task,
    defer_below: usize,
    deferred: &mut Vec<Task>,
) -> usize {
    let mut tasks = vec![root];
    let mut max_depth = root.depth;
    while let Some(task) = tasks.pop() {
        let range = task.start..task.end;
        if range.len() < defer_below {
            deferred.push(task);
            continue;
        }
        max_depth = max_depth.max(task.depth);
        let (mid, left, right) = match choose(&refs[range.clone()], task.hull, task.tuning) {
            Choice::Leaf => {
                let (count, first) = (range.len() as u32, (offset + task.start) as u32);
                nodes.set(
                    task.node,
                    Bvh2Node::new(task.hull.bounds.aabb(), count, first),
                );
                continue;
            }
            Choice::Split {
                binning,
                axis,
                first_right,
                left,
                right,
            } => {
                let (refs, order) = (&mut refs[range.clone()], &mut order[range.clone()]);
                let (count, left_centres, right_centres) =
                    partition(refs, order, binning, axis, first_right);
                let hull = |bounds, centres| Hull { bounds, centres };
                (
                    task.start + count,
                    hull(left, left_centres),
                    hull(right, right_centres),
                )
            }
            Choice::Halves => {
                let mid = task.start + range.len() / 2;
                let (left, right) = (&refs[task.start..mid], &refs[mid..task.end]);
                (mid, Hull::of(left), Hull::of(right))
            }
        };
        let first = nodes.pair(left.bounds, right.bounds);
        let inner = Bvh2Node::new(task.hull.bounds.aabb(), 0, first as u32);
        nodes.set(task.node, inner);
        let depth = task.depth + 1;
        tasks.push(Task {
            node: first + 1,
            start: mid,
            end: task.end,
            hull: right,
            depth,
            ..task
        });
        tasks.push(Task {
            node: first,
            start: task.start,
            end: mid,
            hull: left,
            depth,
            ..task
        });
    }
    max_depth
}

/// The BVH over the primitives whose boxes `boxes` gives, in order (primitive i is the
/// i-th box). An empty list gives the empty BVH.
///
/// The top of the tree is built on one thread down to nodes of about n / (8 threads)
/// primitives; those subtrees are built in parallel, each in a region of the node array
/// big enough for any tree over its primitives (2m − 1 nodes for m), and the regions'
/// nodes are then moved down to close the gaps. The array is allocated zeroed and only
/// the nodes written take memory.
pub fn build_bvh(boxes: impl IndexedParallelIterator<Item = Aabb>, tuning: Tuning) -> Bvh2 {
    let n = boxes.len();
    if n == 0 {
        return Bvh2::default();
    }
    let mut refs: Vec<Packed> = boxes.map(|b| Packed::of(&b)).collect();
    let mut order: Vec<u32> = (0..n as u32).collect();
    let root = Task {
        node: 0,
        start: 0,
        end: n,
        hull: Hull::of(&refs),
        depth: 1,
        tuning,
    };
    // The top takes at most 2n − 1 nodes and the regions 2n in all.
    let mut nodes: Vec<Bvh2Node> = bytemuck::zeroed_vec(4 * n);
    let grain = (n / (8 * rayon::current_num_threads())).max(4096);
    let mut deferred = Vec::new();
    let mut top = Slots {
        slots: &mut nodes,
        used: 1,
        base: 0,
    };
    let mut max_depth = grow(
        &mut top,
        &mut refs,
        &mut order,
        0,
        root,
        grain,
        &mut deferred,
    );
    let top_used = top.used;
    deferred.sort_by_key(|t| t.start);
    // Each deferred node's primitives and its region: its root first, then its descendants.
    let mut pieces = Vec::with_capacity(deferred.len());
    let (_, mut rest_nodes) = nodes.split_at_mut(top_used);
    let (mut rest_refs, mut rest_order) = (refs.as_mut_slice(), order.as_mut_slice());
    let (mut at, mut region) = (0, top_used);
    for task in deferred {
        let m = task.end - task.start;
        let skip = task.start - at;
        let (mine_refs, tail_refs) = rest_refs[skip..].split_at_mut(m);
        let (mine_order, tail_order) = rest_order[skip..].split_at_mut(m);
        let (mine_nodes, tail_nodes) = rest_nodes.split_at_mut(2 * m - 1);
        let slots = Slots {
            slots: mine_nodes,
            used: 1,
            base: region,
        };
        pieces.push((task, slots, mine_refs, mine_order));
        (rest_refs, rest_order, rest_nodes) = (tail_refs, tail_order, tail_nodes);
        (at, region) = (task.end, region + 2 * m - 1);
    }
    let built: Vec<(Task, usize, usize, usize)> = pieces
        .into_par_iter()
        .map(|(task, mut slots, refs, order)| {
            let root = Task {
                node: slots.base,
                start: 0,
                end: refs.len(),
                ..task
            };
            let depth = grow(
                &mut slots,
                refs,
                order,
                task.start,
                root,
                0,
                &mut Vec::new(),
            );
            (task, slots.base, slots.used, depth)
        })
        .collect();
    drop(refs);
    // Close the gaps: region r's node r + i (i ≥ 1) moves to `end` + i − 1, its root to the
    // place the top kept for it.
    let mut end = top_used;
    for (task, region, used, depth) in built {
        let shift = (region + 1 - end) as u32;
        let moved = |mut node: Bvh2Node| {
            if !node.is_leaf() {
                node.first_index -= shift;
            }
            node
        };
        nodes[task.node] = moved(nodes[region]);
        nodes.copy_within(region + 1..region + used, end);
        for node in &mut nodes[end..end + used - 1] {
            *node = moved(*node);
        }
        end += used - 1;
        max_depth = max_depth.max(depth);
    }
    nodes.truncate(end);
    nodes.shrink_to_fit();
    Bvh2 {
        nodes,
        primitive_indices: order,
        children_are_ordered_after_parents: true,
        max_depth,
        ..Bvh2::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64Mcg;

    /// Boxes of random size (up to `size` on a side) at random places in the unit cube.
    fn random_boxes(n: usize, size: f32, seed: u64) -> Vec<Aabb> {
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                let lo = Vec3A::new(rng.gen(), rng.gen(), rng.gen());
                let d = Vec3A::new(rng.gen(), rng.gen(), rng.gen()) * size;
                Aabb::new(lo, lo + d)
            })
            .collect()
    }

    fn contains(outer: &Aabb, inner: &Aabb) -> bool {
        outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all()
    }

    /// The tree's shape, checked on the way: every node reached once and no slot left over,
    /// every box holding its children's or its primitives', every leaf at most [`MAX_LEAF`],
    /// every primitive in exactly one leaf, the depth within `max_depth`. Returns the leaves'
    /// count and the depth.
    fn check(bvh: &Bvh2, boxes: &[Aabb]) -> (usize, usize) {
        let mut seen = vec![false; boxes.len()];
        let mut visited = 0;
        let (mut leaves, mut depth) = (0, 0);
        let mut stack = vec![(0usize, 1usize)];
        while let Some((i, d)) = stack.pop() {
            visited += 1;
            depth = depth.max(d);
            let node = &bvh.nodes[i];
            if node.is_leaf() {
                leaves += 1;
                assert!(node.prim_count as usize <= MAX_LEAF, "leaf {i}: {node:?}");
                let first = node.first_index as usize;
                for &p in &bvh.primitive_indices[first..first + node.prim_count as usize] {
                    assert!(!seen[p as usize], "primitive {p} in two leaves");
                    seen[p as usize] = true;
                    assert!(contains(node.aabb(), &boxes[p as usize]), "leaf {i}");
                }
            } else {
                for c in [node.first_index as usize, node.first_index as usize + 1] {
                    assert!(c > i, "node {i}'s child {c} before it");
                    assert!(contains(node.aabb(), bvh.nodes[c].aabb()), "node {i}");
                    stack.push((c, d + 1));
                }
            }
        }
        assert!(seen.iter().all(|&s| s), "a primitive in no leaf");
        assert_eq!(visited, bvh.nodes.len(), "nodes no root reaches");
        assert!(depth <= bvh.max_depth, "depth {depth} > {}", bvh.max_depth);
        (leaves, depth)
    }

    /// The expected cost of a ray through the root meeting the tree (a node's box met with
    /// probability its area over the root's): [`Tuning::Memory`]'s cost a node, 1 a primitive.
    fn sah_cost(bvh: &Bvh2) -> f64 {
        let root = bvh.nodes[0].aabb().half_area() as f64;
        bvh.nodes
            .iter()
            .map(|n| {
                let a = n.aabb().half_area() as f64 / root;
                match n.is_leaf() {
                    true => a * n.prim_count as f64,
                    false => a * Tuning::Memory.node_cost() as f64,
                }
            })
            .sum()
    }

    /// From one primitive to 10⁵ (the top built alone, then 25 subtrees in parallel whose
    /// regions are closed up): a sound tree every time, and the same tree every time.
    #[test]
    fn every_primitive_in_one_leaf_and_every_box_holds_what_is_below() {
        for n in [1, 2, 3, 8, 9, 100, 4095, 4096, 20_000, 100_000] {
            let boxes = random_boxes(n, 0.02, n as u64);
            let bvh = build_bvh(boxes.par_iter().copied(), Tuning::Memory);
            let (leaves, depth) = check(&bvh, &boxes);
            assert!(depth <= 64, "n = {n}: depth {depth}");
            assert!(leaves * MAX_LEAF >= n);
            let again = build_bvh(boxes.par_iter().copied(), Tuning::Memory);
            assert_eq!(bvh.primitive_indices, again.primitive_indices, "n = {n}");
            let bytes = |b: &Bvh2| bytemuck::cast_slice::<Bvh2Node, u8>(&b.nodes).to_vec();
            assert!(bytes(&bvh) == bytes(&again), "n = {n}");
        }
        assert!(
            build_bvh(Vec::<Aabb>::new().into_par_iter(), Tuning::Memory)
                .nodes
                .is_empty()
        );
    }

    /// A room's six walls and the two boxes standing in it (the Cornell box's primitives):
    /// built for speed, every wall is a leaf of its own, since a leaf of two walls spans the
    /// room and every ray in the room would test both; built for memory, the walls share
    /// leaves (the heuristic's rays come from outside, where the two walls' box is seldom
    /// met).
    #[test]
    fn a_rooms_walls_are_leaves_of_their_own_when_built_for_speed() {
        let slab = |axis: usize, at: f32, lo: Vec3A, hi: Vec3A| {
            let (mut a, mut b) = (lo, hi);
            a[axis] = at;
            b[axis] = at;
            Aabb::new(a, b)
        };
        let (lo, hi) = (Vec3A::splat(-1.0), Vec3A::splat(1.0));
        let mut boxes: Vec<Aabb> = (0..3)
            .flat_map(|axis| [slab(axis, -1.0, lo, hi), slab(axis, 1.0, lo, hi)])
            .collect();
        boxes.push(Aabb::new(
            Vec3A::new(-0.55, -1.0, -0.5),
            Vec3A::new(0.05, -0.4, 0.1),
        ));
        boxes.push(Aabb::new(
            Vec3A::new(0.1, -1.0, -0.2),
            Vec3A::new(0.7, 0.2, 0.4),
        ));
        let largest_leaf = |tuning| {
            let bvh = build_bvh(boxes.par_iter().copied(), tuning);
            check(&bvh, &boxes);
            let leaves = bvh.nodes.iter().filter(|n| n.is_leaf());
            leaves.map(|n| n.prim_count).max().unwrap_or(0)
        };
        assert_eq!(largest_leaf(Tuning::Speed), 1);
        assert!(largest_leaf(Tuning::Memory) > 1);
    }

    /// Boxes whose centres all coincide cannot be binned: they are halved by order into
    /// leaves of at most [`MAX_LEAF`], in a tree as deep as a balanced one; and boxes all
    /// in one plane (no extent along an axis) are binned along the other two.
    #[test]
    fn coincident_and_flat_boxes_make_balanced_trees() {
        let same = vec![Aabb::new(Vec3A::ZERO, Vec3A::ONE); 10_000];
        let (leaves, depth) = check(&build_bvh(same.par_iter().copied(), Tuning::Memory), &same);
        assert_eq!(leaves, 2048, "10 000 halved down to leaves of 4 or 5");
        assert_eq!(depth, 12);
        let flat: Vec<Aabb> = random_boxes(10_000, 0.01, 5)
            .into_iter()
            .map(|b| {
                Aabb::new(
                    b.min * Vec3A::new(1.0, 1.0, 0.0),
                    b.max * Vec3A::new(1.0, 1.0, 0.0),
                )
            })
            .collect();
        let (leaves, depth) = check(&build_bvh(flat.par_iter().copied(), Tuning::Memory), &flat);
        assert!(
            leaves > 10_000 / MAX_LEAF && depth < 40,
            "{leaves} leaves, depth {depth}"
        );
    }

    /// The binned SAH's tree against obvhs's PLOC build with reinsertion (the builder this
    /// one replaces, at its medium setting), on a surface's triangles (the boxes of a
    /// triangulated sphere, as a mesh lens's) and on scattered boxes: the expected cost of a
    /// ray, measured by the same rule, is no more than 5 % above PLOC's.
    #[test]
    fn the_tree_costs_no_more_than_ploc() {
        let mut rng = Pcg64Mcg::seed_from_u64(3);
        let sphere: Vec<Aabb> = (0..60_000)
            .map(|_| {
                let corner = |rng: &mut Pcg64Mcg| {
                    let p = Vec3A::new(rng.gen(), rng.gen(), rng.gen()) * 2.0 - 1.0;
                    p.normalize()
                };
                let a = corner(&mut rng);
                let (b, c) = (a + 0.004 * corner(&mut rng), a + 0.004 * corner(&mut rng));
                Aabb::new(a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        for (name, boxes) in [
            ("sphere", sphere),
            ("scattered", random_boxes(60_000, 0.01, 9)),
        ] {
            struct Boxed(Aabb);
            impl obvhs::Boundable for Boxed {
                fn aabb(&self) -> Aabb {
                    self.0
                }
            }
            let wrapped: Vec<Boxed> = boxes.iter().map(|&b| Boxed(b)).collect();
            let ploc = obvhs::bvh2::builder::build_bvh2(
                &wrapped,
                obvhs::BvhBuildParams::medium_build(),
                &mut Default::default(),
            );
            let (ours, theirs) = (
                sah_cost(&build_bvh(boxes.par_iter().copied(), Tuning::Memory)),
                sah_cost(&ploc),
            );
            println!("{name}: binned SAH {ours:.2}, PLOC {theirs:.2}");
            assert!(ours <= 1.05 * theirs, "{name}: {ours} against {theirs}");
        }
    }
}
