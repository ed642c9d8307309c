//! Geometric primitives and their intersections with straight rays ([`primitive`]) and with
//! curved segments ([`curved`]); shapes of the scene format (box, capped cylinder, mesh) are
//! made of these.

mod curved;
mod mesh;
mod primitive;

pub use curved::segment_roots;
pub use mesh::TriangleMesh;
pub(crate) use primitive::padded_box;
pub use primitive::{Hit, Primitive};
