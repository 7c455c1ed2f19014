//! The scenario options `simulate` and `control` share, flattened into both.

use std::path::PathBuf;

use dlw::sim::{Overrides, ProtocolKind, Scenario};

/// A scenario file and the command line's choices over it.
#[derive(Debug, clap::Args)]
pub struct ScenarioArgs {
    /// Scenario file (TOML): which effects are on, with their parameters. Without one, only
    /// white ADC and EM-tracker noise are on.
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Stroke profile (for control, the desired angle is it times the plant gain):
    /// characterization, rate-dependence, relaxation, random, or custom (with --profile).
    /// Overrides the scenario's `protocol`.
    #[arg(long, value_parser = parse_protocol)]
    pub protocol: Option<ProtocolKind>,
    /// Seed of every random stream (noise, drift, the random pattern); overrides the scenario's.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Length (s); defaults to the protocol's: 10 s at rest, then 1000 s characterization or
    /// 3000 s of the others; a CSV profile's last time.
    #[arg(long)]
    pub duration_s: Option<f64>,
}

impl ScenarioArgs {
    /// The scenario file (or the default scenario) with the options put over it.
    ///
    /// # Errors
    /// The scenario file cannot be read or is invalid.
    pub fn load(&self) -> anyhow::Result<Scenario> {
        let scenario = match &self.scenario {
            Some(path) => Scenario::load(path)?,
            None => Scenario::default(),
        };
        Ok(scenario.overridden(&Overrides {
            protocol: self.protocol,
            seed: self.seed,
            duration_s: self.duration_s,
        }))
    }
}

pub(super) fn parse_protocol(s: &str) -> Result<ProtocolKind, String> {
    ProtocolKind::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = ProtocolKind::ALL.iter().map(|(_, n)| *n).collect();
        format!(
            "unknown protocol {s:?} (expected one of: {})",
            names.join(", ")
        )
    })
}
