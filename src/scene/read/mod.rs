//! Reading a scene file's tables, one kind a file: `[camera]`, `[render]` and `[output]`,
//! `[[material]]`, `[[shape]]`, `[[light]]` and `[[receiver]]` (media are [`super::media`]'s).
//! Every key's unit and default is in `docs/scene-format.md`.

mod camera;
mod light;
mod material;
mod receiver;
mod render;
mod shape;

pub use camera::read_camera;
pub use light::{read_environment, read_light, read_light_and_spectrum, read_spectrum};
pub use material::{read_material, Interior};
pub use receiver::read_receiver;
pub use render::{read_output, read_render};
pub use shape::{read_shape, ShapeDesc};
