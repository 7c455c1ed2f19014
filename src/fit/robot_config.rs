//! A robot's fit made into its estimator config (`dlw fit --design ROBOT REC -o cfg`): the
//! runtime's config from each sensor's fitted model and crosstalk row, the note the config file
//! carries, the summary lines and the JSON `--json` prints.

use std::path::{Path, PathBuf};

use dlw_estimator::{FilterConfig, RobotEstimatorConfig};
use dlw_geometry::{Divider, GeometryError};
use serde::Serialize;

use crate::recording::Rig;
use crate::robot::estimator_config::{estimator_config, SensorSetting};
use crate::robot::CheckedRobot;

use super::robot::{AnglesFrom, RobotFit};
use super::{ModelKind, Prefilter};

/// Why a robot's fit could not be made into a config.
#[derive(Debug, thiserror::Error)]
pub enum RobotConfigError {
    /// A sensor's divider in the recording's rig.
    #[error("sensor {sensor}'s divider in rig.toml")]
    Divider {
        /// 1-based.
        sensor: usize,
        /// What the divider refused.
        #[source]
        source: GeometryError,
    },
    /// The recording's rig has no divider for a sensor.
    #[error("sensor {sensor} has no divider_ohm in rig.toml")]
    NoDivider {
        /// 1-based.
        sensor: usize,
    },
    /// The runtime refused the fitted config.
    #[error("the fitted config (the runtime refused it)")]
    Runtime(#[source] dlw_estimator::RobotError),
}

/// The runtime's config of `robot` from `fitted`, read through the dividers of `rig`; a PI fit's
/// moving-average prefilter is its config's input filter, as the one-joint fit's is.
///
/// # Errors
/// [`RobotConfigError`] naming the sensor.
pub fn robot_fit_config(
    robot: &CheckedRobot,
    fitted: &RobotFit,
    rig: &Rig,
    model: ModelKind,
    prefilter: Prefilter,
) -> Result<RobotEstimatorConfig, RobotConfigError> {
    let settings = fitted
        .sensors
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let fixed_ohm = *rig
                .divider_ohm
                .get(i)
                .ok_or(RobotConfigError::NoDivider { sensor: i + 1 })?;
            let divider = Divider::new(fixed_ohm, rig.supply_v).map_err(|source| {
                RobotConfigError::Divider {
                    sensor: i + 1,
                    source,
                }
            })?;
            Ok(SensorSetting {
                model: s.model,
                divider,
            })
        })
        .collect::<Result<Vec<_>, RobotConfigError>>()?;
    let crosstalk: Vec<Vec<f64>> = fitted.sensors.iter().map(|s| s.crosstalk.clone()).collect();
    let mut config =
        estimator_config(robot, &settings, &crosstalk).map_err(RobotConfigError::Runtime)?;
    if model != ModelKind::Linear {
        if let Prefilter::MovingAverage(n) = prefilter {
            config.input_filter = FilterConfig::MovingAverage { samples: n };
        }
    }
    Ok(config)
}

/// The note a fitted robot config carries: where it was fitted from, and how its crosstalk
/// matrix was had.
pub fn robot_fit_note(robot: &CheckedRobot, fitted: &RobotFit, recording_name: &str) -> String {
    format!(
        "Fitted by dlw fit from {} for the robot {:?} (robot checksum {}): {} model per sensor,\n{}.",
        recording_name,
        robot.robot.name,
        robot.robot.checksum,
        fitted.model,
        crosstalk_source(fitted)
    )
}

/// How the config's note says the crosstalk matrix was had.
fn crosstalk_source(fitted: &RobotFit) -> &'static str {
    if !fitted.crosstalk_fitted {
        return "the crosstalk matrix the geometry's (the recording cannot tell the joints apart)";
    }
    match fitted.angles_from {
        AnglesFrom::Joints => {
            "the crosstalk matrix fitted by least squares on the recorded joint angles"
        }
        AnglesFrom::Tip => {
            "the crosstalk matrix fitted by least squares on the joint angles from the tracked tip (inverse kinematics)"
        }
    }
}

/// What `dlw fit --design ROBOT --json` prints; the keys are part of the interface.
#[derive(Debug, Serialize)]
pub struct RobotFitReport<'a> {
    /// The fit.
    #[serde(flatten)]
    pub fit: &'a RobotFit,
    /// The config file written.
    pub config: PathBuf,
}

impl RobotFit {
    /// The terminal's lines for the fit of `recording_name`, written to `config`: rows fitted,
    /// conditioning, each sensor's numbers beside the geometry's.
    pub fn summary(&self, recording_name: &str, config: &Path) -> String {
        let mut out = format!(
            "{}: {} rows fitted, angle columns' condition number {}, {} model, crosstalk {}\n",
            recording_name,
            self.samples_fitted,
            self.angle_condition
                .map_or("— (a joint did not move)".to_string(), |c| format!(
                    "{c:.2}"
                )),
            self.model,
            if self.crosstalk_fitted {
                "fitted"
            } else {
                "kept from the geometry"
            }
        );
        if let Some(t) = &self.tip_angles {
            out += &format!(
                "  angles from the tip {} of {} tracked rows used; dropped {} not identifiable, {} ambiguous, {} off the kinematics; tracker noise {:.3e} mm\n",
                t.used,
                t.rows,
                t.dropped_not_identifiable,
                t.dropped_ambiguous,
                t.dropped_off_kinematics,
                t.tip_noise_mm
            );
        }
        let row = |c: &[f64]| {
            c.iter()
                .map(|v| format!("{v:.4}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        for (i, s) in self.sensors.iter().enumerate() {
            out += &format!(
                "  sensor {} (joint {} sensor {})  GF {:.4}, R0 {:.1} Ω, crosstalk [{}] (geometry [{}]), residual {:.1} Ω RMS\n",
                i + 1,
                s.joint,
                s.sensor,
                s.gauge_factor,
                s.r0_ohm,
                row(&s.crosstalk),
                row(&s.crosstalk_geometry),
                s.residual_rms_ohm
            );
        }
        out += &format!("  config              {}\n", config.display());
        out
    }
}
