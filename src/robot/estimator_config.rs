//! A robot's estimator config from its geometry (issue 34 §4, `dlw estimator-config ROBOT`):
//! each joint's design and its place on the tube (`dlw inspect ROBOT --json`'s `rotation_deg`,
//! `x_start_mm`, `x_end_mm`), each sensor's model, divider and crosstalk row (the geometry's,
//! `docs/robots.md`), in the order of the inspection's `"sensors"`.

use dlw_estimator::{
    EstimatorError, JointConfig, LinearModel, ModelConfig, RobotError as RuntimeError,
    RobotEstimatorConfig, RobotJointConfig, RobotSensorConfig,
};
use dlw_geometry::{Divider, GeometryError};

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

/// The note a nominal robot config carries: the robot, and where its crosstalk came from.
pub fn nominal_note(robot: &CheckedRobot) -> String {
    format!(
        "Nominal linear estimator config for the robot {:?} (robot checksum {}), written by dlw estimator-config\nbefore any characterization: {} joints, {} sensors, the crosstalk matrix from the geometry (dlw inspect).",
        robot.robot.name,
        robot.robot.checksum,
        robot.robot.joints.len(),
        robot.sensors.len()
    )
}

/// Why [`nominal_linear`] refused its numbers. The messages name the command's options, as
/// `dlw estimator-config ROBOT` prints them.
#[derive(Debug, thiserror::Error)]
pub enum NominalConfigError {
    /// A per-sensor value given neither once nor once per sensor.
    #[error("--{option} is given {given} times; the robot has {sensors} sensors: give it once for every sensor, or once per sensor in dlw inspect's order")]
    Count {
        /// The option (`gauge-factor`, `r0-ohm`, `divider-ohm`).
        option: &'static str,
        /// Values given.
        given: usize,
        /// The robot's sensors.
        sensors: usize,
    },
    /// A sensor's gauge factor or R0.
    #[error("sensor {sensor}'s linear model")]
    Model {
        /// 1-based, in `dlw inspect`'s order.
        sensor: usize,
        /// What the model refused.
        #[source]
        source: EstimatorError,
    },
    /// A sensor's divider resistor or the supply.
    #[error("sensor {sensor}'s divider")]
    Divider {
        /// 1-based, in `dlw inspect`'s order.
        sensor: usize,
        /// What the divider refused.
        #[source]
        source: GeometryError,
    },
    /// The config as a whole (the crosstalk matrix's conditioning).
    #[error("the estimator config of {robot:?}")]
    Config {
        /// The robot's name.
        robot: String,
        /// What the runtime refused.
        #[source]
        source: RuntimeError,
    },
}

/// One value for every sensor (`values` of length 1), one per sensor, or `default` when none
/// is given.
fn per_sensor(
    option: &'static str,
    values: &[f64],
    default: Option<&[f64]>,
    sensors: usize,
) -> Result<Vec<f64>, NominalConfigError> {
    match (values.len(), default) {
        (0, Some(d)) => Ok(d.to_vec()),
        (1, _) => Ok(vec![values[0]; sensors]),
        (n, _) if n == sensors => Ok(values.to_vec()),
        (given, _) => Err(NominalConfigError::Count {
            option,
            given,
            sensors,
        }),
    }
}

/// The nominal linear config `dlw estimator-config ROBOT` writes: every sensor's linear model
/// (`gauge_factor`, `r0_ohm`: once for all sensors or once per sensor, in `dlw inspect`'s
/// order), its divider (`divider_ohm`, likewise; empty: [`default_dividers_ohm`]) on
/// `supply_v`, and the geometry's crosstalk matrix.
///
/// # Errors
/// [`NominalConfigError`]: a count of values, a sensor's model or divider, or the config.
pub fn nominal_linear(
    robot: &CheckedRobot,
    gauge_factor: &[f64],
    r0_ohm: &[f64],
    divider_ohm: &[f64],
    supply_v: f64,
) -> Result<RobotEstimatorConfig, NominalConfigError> {
    let m = robot.sensors.len();
    let gf = per_sensor("gauge-factor", gauge_factor, None, m)?;
    let r0 = per_sensor("r0-ohm", r0_ohm, None, m)?;
    let dividers = default_dividers_ohm(robot);
    let rk = per_sensor("divider-ohm", divider_ohm, Some(&dividers), m)?;
    let settings = (0..m)
        .map(|i| {
            let model =
                LinearModel::new(gf[i], r0[i]).map_err(|source| NominalConfigError::Model {
                    sensor: i + 1,
                    source,
                })?;
            let divider =
                Divider::new(rk[i], supply_v).map_err(|source| NominalConfigError::Divider {
                    sensor: i + 1,
                    source,
                })?;
            Ok(SensorSetting {
                model: ModelConfig::Linear(model),
                divider,
            })
        })
        .collect::<Result<Vec<_>, NominalConfigError>>()?;
    estimator_config(robot, &settings, &robot.crosstalk_matrix()).map_err(|source| {
        NominalConfigError::Config {
            robot: robot.robot.name.clone(),
            source,
        }
    })
}

/// Why a joint of a robot could not be picked for a one-joint config.
#[derive(Debug, thiserror::Error)]
pub enum JointChoiceError {
    /// No joint was named.
    #[error("{file} is a robot of {joints} joints ({list}): give --joint N for the nominal config of joint N's own sensors alone, or no --joint for the robot's own config")]
    NoJoint {
        /// The robot file.
        file: String,
        /// Its joints.
        joints: usize,
        /// `1 = name, 2 = name, …`.
        list: String,
    },
    /// The joint named is not one of the robot's.
    #[error("--joint {joint} must be from 1 to {joints}, the robot's joints ({list})")]
    OutOfRange {
        /// The joint named.
        joint: usize,
        /// The robot's joints.
        joints: usize,
        /// `1 = name, 2 = name, …`.
        list: String,
    },
}

/// Joint `joint` (1-based) of `robot`, read from the robot file `file`, for a config of its own
/// sensors alone: its design, and a note saying what such a config leaves out (the other
/// joints' bending its sensors read).
///
/// # Errors
/// [`JointChoiceError`] when `joint` is missing or not one of the robot's.
pub fn joint_alone(
    robot: &CheckedRobot,
    file: &std::path::Path,
    joint: Option<usize>,
) -> Result<(crate::design::Design, String), JointChoiceError> {
    let r = &robot.robot;
    let joints = r.joints.len();
    let list = r
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| format!("{} = {}", i + 1, j.design().file.name))
        .collect::<Vec<_>>()
        .join(", ");
    let Some(n) = joint else {
        return Err(JointChoiceError::NoJoint {
            file: file.display().to_string(),
            joints,
            list,
        });
    };
    if n == 0 || n > joints {
        return Err(JointChoiceError::OutOfRange {
            joint: n,
            joints,
            list,
        });
    }
    let mut lines = vec![format!(
        "Joint {n} of the robot {:?} (robot checksum {}); its sensors alone, as if the other joints did not bend.",
        r.name, r.checksum
    )];
    for s in robot.sensors.iter().filter(|s| s.sensor.joint == n - 1) {
        let others: Vec<String> = s
            .crosstalk
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != n - 1)
            .map(|(j, v)| format!("{:.2} % of joint {}", v * 100.0, j + 1))
            .collect();
        if !others.is_empty() {
            lines.push(format!(
                "Its sensor {} also reads {} (crosstalk, docs/robots.md).",
                s.sensor.sensor + 1,
                others.join(", ")
            ));
        }
    }
    Ok((r.joints[n - 1].design().clone(), lines.join("\n")))
}
