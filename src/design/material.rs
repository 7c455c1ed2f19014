//! The tube materials a joint can be cut from, with their sources: Young's modulus for the
//! bending stiffness and tendon force, and the strain limit for the backbone.

use serde::{Deserialize, Serialize};

/// Young's modulus of polyimide film (Pa): 2.5 GPa, DuPont Kapton HN datasheet (tensile
/// modulus at 23 °C, ASTM D-882). The paper's tubes are MicroLumen polyimide tubing.
pub const POLYIMIDE_YOUNGS_MODULUS_PA: f64 = 2.5e9;
/// Strain limit of polyimide: 3 %, the Kapton HN datasheet's "yield point at 3 %" (69 MPa at
/// 23 °C), the end of its linear-elastic range; `dlw`'s backbone limit since the first release.
pub const POLYIMIDE_STRAIN_LIMIT: f64 = 0.03;
/// Young's modulus of superelastic nitinol in its austenite phase (Pa): 75 GPa, the low end of
/// the 75-83 GPa suppliers list (e.g. Fort Wayne Metals' Nitinol #1 datasheet).
pub const NITINOL_YOUNGS_MODULUS_PA: f64 = 75.0e9;
/// Strain limit of superelastic nitinol: 6 %, the recoverable strain notched-tube wrists are
/// designed to (York, Swaney et al., ICRA 2015, keep peak strain within the superelastic plateau,
/// 6-8 %); the lower end is taken.
pub const NITINOL_STRAIN_LIMIT: f64 = 0.06;

/// A tube material from the table above.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TubeMaterial {
    /// Polyimide tubing, the paper's.
    #[default]
    Polyimide,
    /// Superelastic nitinol, the usual metal for notched-tube wrists.
    Nitinol,
}

impl TubeMaterial {
    /// Young's modulus (Pa).
    pub fn youngs_modulus_pa(self) -> f64 {
        match self {
            Self::Polyimide => POLYIMIDE_YOUNGS_MODULUS_PA,
            Self::Nitinol => NITINOL_YOUNGS_MODULUS_PA,
        }
    }

    /// Peak strain the material takes without yielding (a fraction).
    pub fn strain_limit(self) -> f64 {
        match self {
            Self::Polyimide => POLYIMIDE_STRAIN_LIMIT,
            Self::Nitinol => NITINOL_STRAIN_LIMIT,
        }
    }

    /// The name as written in design files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Polyimide => "polyimide",
            Self::Nitinol => "nitinol",
        }
    }

    /// Whether this is the default material (so it need not be written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}
