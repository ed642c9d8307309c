//! Scenes: a TOML file read with every key's position kept ([`table`]), media tables
//! ([`media`]), and loading into the validated, render-ready [`Scene`] ([`load`]).

pub mod load;
pub mod media;
pub mod objects;
pub mod table;

pub use load::{load_scene, Layer, Scene, Surface};
