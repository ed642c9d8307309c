//! Scenes: a TOML file read with every key's position kept ([`table`]), media tables
//! ([`media`]), loading into the validated, render-ready [`Scene`] ([`load`]), and the GRIN
//! fiber with its layered twin ([`fiber`]).

pub mod fiber;
pub mod load;
pub mod media;
pub mod mesh;
pub mod objects;
pub mod source;
pub mod table;

pub use fiber::{GrinFiber, Layer};
pub use load::{load_scene, Scene, Surface};
