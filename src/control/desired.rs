//! The desired joint angle, one value per sample: from a built-in protocol (its stroke profile
//! times the plant's nominal gain) or from a CSV `time_s,angle_deg`.

use std::path::{Path, PathBuf};

use crate::design::Design;
use crate::sim::{
    self, parse_series, ProtocolError, ProtocolKind, Scenario, SimError, MAX_SAMPLES,
};

use super::ControlError;

/// Where the desired angle comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum DesiredSource {
    /// The scenario's protocol (the CLI's `--protocol` already applied): the desired angle is
    /// the protocol's stroke profile times the plant's nominal gain, so it spans the angles the
    /// protocol was designed to reach (the paper's ~1.5 % peak strain).
    Protocol,
    /// A CSV file with the header `time_s,angle_deg`, interpolated linearly and held after its
    /// last row.
    Csv(PathBuf),
}

/// The desired angle at every sample, and the resolved scenario it was sampled with.
#[derive(Debug, Clone, PartialEq)]
pub struct Desired {
    /// The resolved scenario (duration, seed and every effect filled in).
    pub scenario: Scenario,
    /// Desired angle per sample (°), at `t = i/sample_hz`.
    pub angle_deg: Vec<f64>,
    /// Where it came from, in words, for the report.
    pub description: String,
}

impl Desired {
    /// Samples the desired angle for `design` under `scenario` (CLI overrides applied).
    ///
    /// # Errors
    /// [`ControlError`]: a refused scenario, no protocol, an unreadable or malformed profile, or
    /// more samples than a simulation may hold.
    pub fn resolve(
        design: &Design,
        scenario: Scenario,
        source: &DesiredSource,
    ) -> Result<Self, ControlError> {
        match source {
            DesiredSource::Protocol => {
                match scenario.protocol {
                    None => return Err(ControlError::NoDesired),
                    // `--profile` is the desired angle here, not a stroke profile.
                    Some(ProtocolKind::Custom) if scenario.protocols.custom.profile.is_none() => {
                        return Err(ControlError::CustomWithoutStroke)
                    }
                    _ => {}
                }
                let plan = sim::plan(design, scenario, None)?;
                let hz = plan.scenario.sample_hz;
                let gain = plan.scenario.plant.gain_deg_per_mm;
                let mut stroke = plan.profile.sampler();
                let angle_deg = (0..plan.samples)
                    .map(|i| gain * stroke.at(i as f64 / hz))
                    .collect();
                let kind = plan.scenario.protocol.map_or("?", |k| k.name());
                Ok(Self {
                    description: format!(
                        "the {kind} protocol's stroke profile times the plant's nominal gain ({gain} °/mm)"
                    ),
                    scenario: plan.scenario,
                    angle_deg,
                })
            }
            DesiredSource::Csv(path) => {
                let knots = read_profile(path)?;
                let mut scenario = scenario.resolve(design).map_err(SimError::from)?;
                let last_s = knots.last().map_or(0.0, |k| k.0);
                let duration_s = *scenario.duration_s.get_or_insert(last_s);
                let hz = scenario.sample_hz;
                let samples = (duration_s * hz).round().max(1.0);
                if samples > MAX_SAMPLES as f64 {
                    return Err(SimError::TooLong {
                        duration_s,
                        sample_hz: hz,
                        samples,
                        max: MAX_SAMPLES,
                    }
                    .into());
                }
                let angle_deg = interpolate(&knots, samples as usize, hz);
                Ok(Self {
                    description: format!("the desired-angle profile {}", path.display()),
                    scenario,
                    angle_deg,
                })
            }
        }
    }

    /// Largest `|desired angle|` (°).
    pub fn peak_deg(&self) -> f64 {
        self.angle_deg.iter().fold(0.0, |m, a| f64::max(m, a.abs()))
    }
}

/// Reads a desired-angle CSV with the simulator's time-series parser.
fn read_profile(path: &Path) -> Result<Vec<(f64, f64)>, ControlError> {
    let text = crate::output::read_limited(path, crate::limits::MAX_RECORDING_BYTES).map_err(
        |source| ControlError::ProfileRead {
            path: path.to_path_buf(),
            source,
        },
    )?;
    parse_series(&text, "angle_deg").map_err(|e| match e {
        ProtocolError::Line { line, reason, .. } => ControlError::Profile {
            path: path.to_path_buf(),
            line,
            reason,
        },
        _ => ControlError::ProfileEmpty {
            path: path.to_path_buf(),
        },
    })
}

/// The piecewise-linear profile through `knots` (strictly increasing times) at `t = i/hz`,
/// held before the first and after the last knot (0 without knots).
fn interpolate(knots: &[(f64, f64)], samples: usize, hz: f64) -> Vec<f64> {
    let (time_s, values): (Vec<f64>, Vec<f64>) = knots.iter().copied().unzip();
    (0..samples)
        .map(|i| crate::stats::interpolate_held(&time_s, &values, i as f64 / hz).unwrap_or(0.0))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn interpolates_and_holds() {
        let knots = [(1.0, 10.0), (2.0, 20.0), (4.0, 0.0)];
        let v = interpolate(&knots, 11, 2.0);
        let want = [10.0, 10.0, 10.0, 15.0, 20.0, 15.0, 10.0, 5.0, 0.0, 0.0, 0.0];
        for (a, b) in v.iter().zip(want) {
            assert_relative_eq!(*a, b, epsilon = 1e-12);
        }
    }

    #[test]
    fn protocol_desired_is_gain_times_stroke() {
        let design = crate::sim::test_design(dlw_geometry::NotchStyle::Uan);
        let sc = Scenario {
            protocol: Some(crate::sim::ProtocolKind::Characterization),
            duration_s: Some(10.0),
            ..Scenario::default()
        };
        let d = Desired::resolve(&design, sc.clone(), &DesiredSource::Protocol).unwrap();
        assert_eq!(d.angle_deg.len(), 5000);
        let plan = sim::plan(&design, sc, None).unwrap();
        let mut s = plan.profile.sampler();
        assert_relative_eq!(d.angle_deg[4321], 35.49 * s.at(4321.0 / 500.0));
        let none = Desired::resolve(&design, Scenario::default(), &DesiredSource::Protocol);
        assert!(matches!(none, Err(ControlError::NoDesired)));
    }
}
