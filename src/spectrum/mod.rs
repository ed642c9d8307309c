//! Wavelength as a physical quantity (DESIGN §12). Wavelengths are in nanometres (vacuum)
//! throughout, over the visible range [`LAMBDA_MIN`, `LAMBDA_MAX`] = 360–830 nm of the CIE
//! 1931 observer. Here: [`dispersion`] (a refractive index as a function of wavelength — seed
//! 004's media answer "which wavelengths share a path" with it: media whose index does not
//! depend on λ keep them all on one) and [`emission`] (the shape of a light's spectrum, and
//! sampling a photon's wavelength from it).

pub mod dispersion;
pub mod emission;

pub use dispersion::Dispersion;
pub use emission::Spectrum;

/// Shortest wavelength transported, nm.
pub const LAMBDA_MIN: f64 = 360.0;
/// Longest wavelength transported, nm.
pub const LAMBDA_MAX: f64 = 830.0;

/// The wavelength at which an index is quoted when one number is wanted: the helium d line,
/// 587.5618 nm, where glass catalogues give n_d and the Abbe number is anchored. Camera paths
/// (RGB) see every medium at this wavelength.
pub const LAMBDA_D: f64 = 587.5618;
/// Hydrogen F line (blue), nm: with C, the lines of the Abbe number V_d = (n_d − 1)/(n_F − n_C).
pub const LAMBDA_F: f64 = 486.1327;
/// Hydrogen C line (red), nm.
pub const LAMBDA_C: f64 = 656.2725;
