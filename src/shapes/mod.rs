//! Geometric primitives and their intersections with straight rays ([`primitive`]) and with
//! curved segments ([`curved`]); shapes of the scene format (box, capped cylinder, mesh) are
//! made of these.

mod curved;
mod primitive;

pub use curved::segment_roots;
pub use primitive::{Hit, Primitive};
