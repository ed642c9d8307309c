//! Geometric primitives and their intersections with straight rays ([`primitive`]) and with
//! curved segments ([`curved`]); shapes of the scene format (box, capped cylinder, mesh) are
//! made of these; points are drawn over a mesh's surface by area ([`SampledMesh`]); a round
//! shape's surface coordinates may be read in a frame of its own ([`UvFrame`]).

mod curved;
mod hit;
mod mesh;
mod primitive;
mod sampled_mesh;
mod triangle;
mod uv_frame;

pub use curved::{round_roots, segment_roots};
pub(crate) use hit::{padded_box, TraversalRay};
pub use hit::{Hit, SegmentHits};
pub use mesh::TriangleMesh;
pub use primitive::{Disk, Primitive, Quad};
pub use sampled_mesh::{SampledMesh, SurfaceSample};
pub use triangle::{Plane, Triangle};
pub use uv_frame::UvFrame;
