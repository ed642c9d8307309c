//! The state a ray carries from step to step.

use crate::media::{IndexSample, Medium};
use glam::DVec3;

/// Where a ray is, where it goes, and the medium's answer there (reused by the next step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayState {
    /// Position (scene units).
    pub position: DVec3,
    /// Unit direction of propagation.
    pub direction: DVec3,
    /// n and ∇n at `position`.
    pub index: IndexSample,
}

impl RayState {
    /// The state at `position` heading along `direction` (normalised here), or `None` if the
    /// medium captures a ray at that point.
    pub fn new<M: Medium + ?Sized>(medium: &M, position: DVec3, direction: DVec3) -> Option<Self> {
        Some(Self {
            position,
            direction: unit(direction),
            index: medium.sample(position)?,
        })
    }
}

/// `v` normalised; a vector whose squared length overflows or underflows (1e300, 1e300, 0)
/// is scaled by its largest component first.
fn unit(v: DVec3) -> DVec3 {
    let l2 = v.length_squared();
    if l2.is_finite() && l2 >= f64::MIN_POSITIVE {
        v.normalize()
    } else {
        (v / v.abs().max_element()).normalize()
    }
}
