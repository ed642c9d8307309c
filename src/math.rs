//! Small geometric helpers shared by every layer: which side of a surface a ray is on, and how
//! far to move a point off a surface so the next ray does not hit it again.

use glam::DVec3;

/// The unit normal of the side of a surface a ray arrives on: `normal` (the geometric one)
/// flipped to face against `direction`.
pub fn facing(normal: DVec3, direction: DVec3) -> DVec3 {
    if direction.dot(normal) < 0.0 {
        normal
    } else {
        -normal
    }
}

/// Offset of a point off a surface toward the side of unit `side` (scene-scale relative).
pub fn offset(p: DVec3, side: DVec3) -> DVec3 {
    p + side * (1e-9 * (1.0 + p.abs().max_element()))
}

/// The angle (rad) between unit vectors `a` and `b`, accurate to rounding for every angle:
/// 2·atan2(|a − b|, |a + b|). (acos of the dot product loses small angles: below ≈ 2·10⁻⁸ rad
/// it reads 0.)
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    2.0 * (a - b).length().atan2((a + b).length())
}

/// A ball: the points within `radius` of `center` (scene units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Its centre.
    pub center: DVec3,
    /// Its radius, ≥ 0.
    pub radius: f64,
}

/// An axis-aligned box: the points p with `lo` ≤ p ≤ `hi` in every coordinate (scene units).
/// [`Bounds3::EMPTY`] (lo = +∞, hi = −∞) holds nothing and starts a union.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds3 {
    /// The lower corner.
    pub lo: DVec3,
    /// The upper corner.
    pub hi: DVec3,
}

impl Bounds3 {
    /// The box that holds nothing.
    pub const EMPTY: Self = Self {
        lo: DVec3::INFINITY,
        hi: DVec3::NEG_INFINITY,
    };

    /// The box with corners `lo` and `hi`.
    pub fn new(lo: DVec3, hi: DVec3) -> Self {
        Self { lo, hi }
    }

    /// The part of the straight segment from `from` along unit `dir` over `length` inside the
    /// box, as the distances (t0, t1) along it where it enters and leaves (None: it misses the
    /// box, or touches it only at a point). A direction parallel to a pair of faces meets
    /// them only if it lies between them.
    pub fn clip(&self, from: DVec3, dir: DVec3, length: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (0.0f64, length);
        for a in 0..3 {
            let (o, d, lo, hi) = (from[a], dir[a], self.lo[a], self.hi[a]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (near, far) = ((lo - o) / d, (hi - o) / d);
            t0 = t0.max(near.min(far));
            t1 = t1.min(near.max(far));
        }
        (t0 < t1).then_some((t0, t1))
    }

    /// Whether `p` lies in the box (its faces included).
    pub fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.lo).all() && p.cmple(self.hi).all()
    }

    /// The smallest box holding `points` ([`Bounds3::EMPTY`] for none).
    pub fn of_points(points: impl IntoIterator<Item = DVec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, Self::with_point)
    }

    /// The smallest box holding this one and `p`.
    pub fn with_point(self, p: DVec3) -> Self {
        Self::new(self.lo.min(p), self.hi.max(p))
    }

    /// The smallest box holding this one and `other`.
    pub fn union(self, other: Self) -> Self {
        Self::new(self.lo.min(other.lo), self.hi.max(other.hi))
    }

    /// This box grown by `by` in every direction, per axis.
    pub fn grown(self, by: DVec3) -> Self {
        Self::new(self.lo - by, self.hi + by)
    }

    /// Whether the two boxes share a point (touching counts).
    pub fn overlaps(&self, other: &Self) -> bool {
        self.lo.cmple(other.hi).all() && other.lo.cmple(self.hi).all()
    }

    /// Its centre.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Its diagonal, hi − lo.
    pub fn diagonal(&self) -> DVec3 {
        self.hi - self.lo
    }

    /// Whether it holds no point (an empty union, or a box never grown from
    /// [`Bounds3::EMPTY`]).
    pub fn is_empty(&self) -> bool {
        !self.lo.cmple(self.hi).all()
    }
}

/// A straight piece of a path: from `origin` along unit `dir` for `length` (scene units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Where it starts.
    pub origin: DVec3,
    /// Unit direction.
    pub dir: DVec3,
    /// Its length.
    pub length: f64,
}

impl Segment {
    /// Where it ends.
    pub fn end(&self) -> DVec3 {
        self.origin + self.dir * self.length
    }
}

impl AsRef<Segment> for Segment {
    fn as_ref(&self) -> &Segment {
        self
    }
}
