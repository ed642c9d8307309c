//! Scenes: a TOML file read with every key's position kept ([`table`], [`source`]), its
//! tables ([`media`], [`read`], [`mesh`]) read into a [`Description`] ([`load`]), and the
//! description built into the render-ready [`Scene`] ([`model`]).

pub mod data;
pub mod load;
pub mod media;
pub mod mesh;
pub mod model;
pub mod ply;
pub mod read;
pub mod serialized;
pub mod source;
pub mod table;
pub mod vdb;
pub mod vol;

pub use load::{load_description, load_scene, parse_data};
pub use model::{Description, Media, Role, Scene, Shape, Surface};
