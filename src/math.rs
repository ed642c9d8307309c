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
