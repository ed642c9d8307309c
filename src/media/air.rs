//! The index of air from its state, for volume data that comes as density or temperature (a
//! plume or heat-haze simulation): the Gladstone–Dale relation n − 1 = K ρ, with the density of
//! an ideal gas ρ = p M / (R T).

/// Gladstone–Dale constant of dry air at 589 nm (m³/kg): n − 1 = 2.9262·10⁻⁴ at 0 °C and
/// 101 325 Pa (Ciddor's air at the sodium D line), where ρ = 1.29228 kg/m³.
pub const GLADSTONE_DALE_AIR: f64 = 2.2644e-4;
/// Molar mass of dry air (kg/mol).
pub const MOLAR_MASS_AIR: f64 = 0.028_964_4;
/// Molar gas constant (J/(mol K)).
pub const GAS_CONSTANT: f64 = 8.314_462_618;
/// Standard atmospheric pressure (Pa).
pub const STANDARD_PRESSURE: f64 = 101_325.0;

/// What the values of a grid are, and how each becomes an index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GridQuantity {
    /// The index n itself.
    Index,
    /// Mass density ρ (kg/m³) of a gas with Gladstone–Dale constant `gladstone_dale` (m³/kg).
    Density {
        /// K in n − 1 = K ρ.
        gladstone_dale: f64,
    },
    /// Temperature T (K) of air at `pressure` (Pa), an ideal gas.
    Temperature {
        /// Pressure (Pa), the same everywhere (a heat haze's pressure varies by ~1e-5 of
        /// itself over metres; its temperature by tens of per cent).
        pressure: f64,
        /// K in n − 1 = K ρ.
        gladstone_dale: f64,
    },
}

impl GridQuantity {
    /// The index of a value, or why the value cannot be one: a density must be finite and
    /// ≥ 0, a temperature finite and > 0 (the index then is finite and ≥ 1).
    pub fn index(&self, value: f64) -> Result<f64, String> {
        match *self {
            GridQuantity::Index => Ok(value),
            GridQuantity::Density { gladstone_dale } => {
                if value.is_finite() && value >= 0.0 {
                    Ok(1.0 + gladstone_dale * value)
                } else {
                    Err(format!("{value} is not a density (finite, ≥ 0 kg/m³)"))
                }
            }
            GridQuantity::Temperature {
                pressure,
                gladstone_dale,
            } => {
                if value.is_finite() && value > 0.0 {
                    let rho = pressure * MOLAR_MASS_AIR / (GAS_CONSTANT * value);
                    Ok(1.0 + gladstone_dale * rho)
                } else {
                    Err(format!("{value} is not a temperature (finite, > 0 K)"))
                }
            }
        }
    }
}
