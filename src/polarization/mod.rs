//! Polarization: the Stokes vector light carries, the Mueller matrices of what it meets
//! ([`mueller`]), and the field carried along a curved ray by Rytov's law ([`rytov`]).

pub mod mueller;
pub mod rytov;

pub use rytov::RytovTransport;
