//! A robot's estimator config from its geometry (issue 34 §4, `dlw estimator-config ROBOT`):
//! each joint's design and its place on the tube (`dlw inspect ROBOT --json`'s `rotation_deg`,
//! `x_start_mm`, `x_end_mm`), each sensor's model, divider and crosstalk row (the geometry's,
//! `docs/robots.md`), in the order of the inspection's `"sensors"`.

use dlw_estimator::{
    JointConfig, ModelConfig, RobotError as RuntimeError, RobotEstimatorConfig, RobotJointConfig,
    RobotSensorConfig,
};
use dlw_geometry::Divider;

use super::checked::CheckedRobot;

/// The bench's divider resistor for a sensor 1 (Ω): Section II-B, and the simulator's default.
pub const SENSOR1_DIVIDER_OHM: f64 = 99.6e3;
/// The bench's divider resistor for a BSN joint's sensor 2 (Ω): the paper's 102.5 kΩ, the
/// simulator's default.
pub const SENSOR2_DIVIDER_OHM: f64 = 102.5e3;

/// One sensor's model and divider, in the order of the robot's sensors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorSetting {
    /// Its model (linear or PI).
    pub model: ModelConfig,
    /// Its divider.
    pub divider: Divider,
}

/// The joints of `robot` as the runtime config lists them.
pub fn joint_configs(robot: &CheckedRobot) -> Vec<RobotJointConfig> {
    robot
        .robot
        .joints
        .iter()
        .map(|j| RobotJointConfig {
            rotation_deg: j.rotation_deg,
            x_start_mm: j.x_start_mm(),
            x_end_mm: j.x_end_mm(),
            geometry: JointConfig::from_joint(&j.design().joint),
        })
        .collect()
}

/// The config of `robot` with `settings` (one per sensor) and `crosstalk` (one row per sensor,
/// one entry per joint; [`CheckedRobot::crosstalk_matrix`] for the geometry's).
///
/// # Errors
/// What [`RobotEstimatorConfig::new`] refuses (a sensor's model, the matrix's conditioning),
/// or a number of settings or rows other than the robot's sensors (named as a list length).
pub fn estimator_config(
    robot: &CheckedRobot,
    settings: &[SensorSetting],
    crosstalk: &[Vec<f64>],
) -> Result<RobotEstimatorConfig, RuntimeError> {
    let sensors = robot.robot.sensors();
    if settings.len() != sensors.len() || crosstalk.len() != sensors.len() {
        return Err(RuntimeError::TooFewSensors {
            sensors: settings.len().min(crosstalk.len()),
            joints: robot.robot.joints.len(),
        });
    }
    let list = sensors
        .iter()
        .zip(settings)
        .zip(crosstalk)
        .map(|((s, set), row)| {
            let mut c = RobotSensorConfig::linear(
                s.joint as u32 + 1,
                s.sensor as u32 + 1,
                1.0,
                1.0,
                set.divider,
                row,
            )?;
            c.model = set.model;
            Ok(c)
        })
        .collect::<Result<Vec<_>, RuntimeError>>()?;
    RobotEstimatorConfig::new(&joint_configs(robot), &list)
}

/// The bench's divider for each sensor of `robot`: [`SENSOR1_DIVIDER_OHM`] for a sensor 1,
/// [`SENSOR2_DIVIDER_OHM`] for a BSN joint's sensor 2.
pub fn default_dividers_ohm(robot: &CheckedRobot) -> Vec<f64> {
    robot
        .robot
        .sensors()
        .iter()
        .map(|s| {
            if s.sensor == 1 {
                SENSOR2_DIVIDER_OHM
            } else {
                SENSOR1_DIVIDER_OHM
            }
        })
        .collect()
}
