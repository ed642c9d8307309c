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
