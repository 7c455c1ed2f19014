//! The protocol a recording follows: the name `rig.toml` states (`protocol`), as a type that
//! belongs to the recording, so that analysing an imported recording needs nothing from the
//! simulator (which runs these protocols).

use serde::{Deserialize, Serialize};

/// The bench protocols.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProtocolKind {
    /// Five cycles of increasing amplitude, repeated (Section IV-A1).
    Characterization,
    /// Five equal-amplitude cycles of different speeds, repeated (Section IV-A2).
    RateDependence,
    /// Stepwise holds, repeated (Section IV-A3).
    Relaxation,
    /// A seeded random pattern, repeated (Section IV-B).
    Random,
    /// A stroke profile from a CSV file.
    Custom,
}

impl ProtocolKind {
    /// Every protocol with its name as written in files and on the command line.
    pub const ALL: [(Self, &'static str); 5] = [
        (Self::Characterization, "characterization"),
        (Self::RateDependence, "rate-dependence"),
        (Self::Relaxation, "relaxation"),
        (Self::Random, "random"),
        (Self::Custom, "custom"),
    ];

    /// The protocol's name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Characterization => "characterization",
            Self::RateDependence => "rate-dependence",
            Self::Relaxation => "relaxation",
            Self::Random => "random",
            Self::Custom => "custom",
        }
    }

    /// The protocol called `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(k, _)| *k)
    }
}
