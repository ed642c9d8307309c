//! Polarization: the Stokes vector light carries and the Mueller matrices of what it meets
//! ([`mueller`]), what a specular chain carries of it ([`carried`]), the thin sheets that polarize and
//! retard it ([`Sheet`]), and the field carried
//! along a curved ray by Rytov's law ([`rytov`]), and a false-colour picture of the linear
//! polarization of a render's Stokes layers ([`preview`]).

pub mod carried;
pub mod crystal;
pub mod mueller;
pub mod preview;
pub mod rytov;
mod sheet;

pub use carried::{Element, Polarization, Recorded, Sense, StoredStokes};
pub use rytov::RytovTransport;
pub use sheet::Sheet;
