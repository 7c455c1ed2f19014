//! What `dlw discover --json` prints, and the scenario file it writes, as a library: the command
//! and the Python binding (`dlw.discover`) both build them here.

use std::collections::BTreeMap;

use serde::Serialize;

use super::{scenario, Ambiguity, Gap, Outcome};
use crate::design::Design;
use crate::recording::Recording;
use crate::sim::Scenario;

/// A named effect. The keys are part of the interface (issue 9).
#[derive(Debug, Clone, Serialize)]
pub struct Named {
    /// The effect's name.
    pub effect: &'static str,
    /// The channel it acts on.
    pub channel: String,
    /// Its evidence (the information criterion's gain).
    pub evidence: f64,
    /// Its fitted parameters.
    pub parameters: BTreeMap<String, f64>,
    /// A saturation's held-out RMSE in the library's form and with a curve of any shape.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub form: Option<super::FormFit>,
    /// The bootstrap it was named by (absent with `--fast`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calibration: Option<super::Calibration>,
    /// The rival names it was told from.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rivals: Vec<super::Rivalry>,
    /// The test against a smooth change in time (`drift`, `gain_drift`, `creep`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time: Option<super::TimeRivalry>,
}

/// A candidate with its score.
#[derive(Debug, Clone, Serialize)]
pub struct Scored {
    /// The effect's name.
    pub effect: &'static str,
    /// The channel.
    pub channel: String,
    /// Its evidence.
    pub evidence: f64,
    /// The round it was scored in.
    pub round: usize,
    /// The shape of its term.
    pub shape: String,
    /// Its memory (s), where it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub memory: Option<f64>,
}

/// The discovery's result in `--json`'s form, without the paths of the files written.
#[derive(Debug, Clone, Serialize)]
pub struct DiscoverySummary {
    /// Effects named.
    pub discovered: Vec<Named>,
    /// Every candidate scored.
    pub candidates: Vec<Scored>,
    /// Channels where two effects explain the data alike.
    pub ambiguous: Vec<Ambiguity>,
    /// Candidates that cleared the screen but not their calibration.
    pub declined: Vec<super::Declined>,
    /// Structure no candidate explains.
    pub unexplained: Vec<super::unexplained::Unexplained>,
    /// The gaps before and after.
    pub gaps: Vec<Gap>,
}

impl DiscoverySummary {
    /// The summary of `outcome`.
    pub fn of(outcome: &Outcome) -> Self {
        Self {
            discovered: outcome
                .discovered
                .iter()
                .map(|d| Named {
                    effect: d.effect.name(),
                    channel: d.channel.name(),
                    evidence: d.evidence,
                    parameters: d.parameters.clone(),
                    form: d.form,
                    calibration: d.calibration.clone(),
                    rivals: d.rivals.clone(),
                    time: d.time.clone(),
                })
                .collect(),
            candidates: outcome
                .candidates
                .iter()
                .map(|c| Scored {
                    effect: c.effect.name(),
                    channel: c.channel.name(),
                    evidence: c.evidence,
                    round: c.round,
                    shape: c.shape.clone(),
                    memory: c.memory,
                })
                .collect(),
            ambiguous: outcome.ambiguous.clone(),
            declined: outcome.declined.clone(),
            unexplained: outcome.unexplained.clone(),
            gaps: outcome.gaps.clone(),
        }
    }
}

/// The text of `scenario.toml`: `base` calibrated to `recording` with the named effects, under a
/// header naming them, checked to be a scenario `dlw simulate` accepts for `design`.
///
/// # Errors
/// A message naming what failed: building the scenario, serializing it, or its validation.
pub fn scenario_text(
    base: &Scenario,
    recording: &Recording,
    design: &Design,
    outcome: &Outcome,
) -> Result<String, String> {
    let written = scenario::scenario(base, recording, &design.joint, outcome)
        .map_err(|e| format!("writing the scenario: {e}"))?;
    let text = toml::to_string(&written).map_err(|e| format!("serializing the scenario: {e}"))?;
    toml::from_str::<Scenario>(&text)
        .map_err(|e| e.to_string())
        .and_then(|s| s.resolve(design).map_err(|e| e.to_string()))
        .map_err(|e| format!("the discovered scenario does not validate: {e}"))?;
    let named = if outcome.discovered.is_empty() {
        "none".to_owned()
    } else {
        outcome
            .discovered
            .iter()
            .map(|d| format!("{} on {}", d.effect.name(), d.channel.name()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let notes: String = outcome
        .discovered
        .iter()
        .filter_map(|d| {
            let f = d.form?;
            Some(format!(
                "# {} on {}: written in the library's form; held-out RMSE {:.4} {unit} with it, \
                 {:.4} {unit} with a memoryless curve of any shape.\n",
                d.effect.name(),
                d.channel.name(),
                f.library_rmse,
                f.any_shape_rmse,
                unit = d.channel.unit()
            ))
        })
        .collect();
    Ok(format!(
        "# Written by dlw discover: the base scenario calibrated to the recording, with the named effects: {named}.\n{notes}{text}"
    ))
}
