//! Scenes: the TOML description ([`desc`]), its loading with source positions ([`load`]) and
//! the validated, render-ready [`Scene`] ([`build`]).

pub mod build;
pub mod desc;
pub mod load;

pub use build::Scene;
pub use load::load_scene;
