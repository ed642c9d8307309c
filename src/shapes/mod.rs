//! Geometric primitives and their intersections with straight rays ([`primitive`]) and with
//! curved segments ([`curved`]); shapes of the scene format (box, capped cylinder, mesh) are
//! made of these.

mod curved;
mod hit;
mod mesh;
mod primitive;
mod triangle;

pub use curved::{round_roots, segment_roots};
pub(crate) use hit::{padded_box, TraversalRay};
pub use hit::{Hit, SegmentHits};
pub use mesh::TriangleMesh;
pub use primitive::{Disk, Primitive, Quad};
pub use triangle::{Plane, Triangle};
