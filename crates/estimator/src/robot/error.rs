use core::fmt;

use dlw_geometry::{KinematicsError, NotchStyle};

use crate::error::EstimatorError;

/// Why a robot estimator configuration was refused. Joints and sensors are numbered from 1, in
/// the order of `dlw inspect ROBOT --json` (joint 1 distal; sensors by joint, then sensor 1
/// before 2). Every variant names the offending value and the limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RobotError {
    /// A joint's design parameters were refused.
    Joint {
        /// 1-based joint number.
        joint: usize,
        /// Why.
        error: EstimatorError,
    },
    /// A sensor's divider, model or filter was refused.
    Sensor {
        /// 1-based sensor number.
        sensor: usize,
        /// Why.
        error: EstimatorError,
    },
    /// The joints' sections were refused by the kinematics.
    Kinematics(KinematicsError),
    /// A list is longer than the inline storage, or a value that must be finite is not.
    Config(EstimatorError),
    /// Fewer sensors than joints: the joint angles cannot all be told apart.
    TooFewSensors {
        /// Sensors configured.
        sensors: usize,
        /// Joints of the robot.
        joints: usize,
    },
    /// A sensor names a joint the robot does not have.
    SensorJoint {
        /// 1-based sensor number.
        sensor: usize,
        /// The `joint` it names.
        joint: u32,
        /// Joints of the robot.
        joints: usize,
    },
    /// A sensor's number within its joint is not one the joint carries.
    SensorNumber {
        /// 1-based sensor number.
        sensor: usize,
        /// The `sensor` number it gives within its joint.
        number: u32,
        /// Its joint (1-based).
        joint: u32,
        /// The joint's notch style.
        style: NotchStyle,
    },
    /// Two sensors are the same sensor of the same joint.
    DuplicateSensor {
        /// 1-based sensor number of the second one.
        sensor: usize,
        /// 1-based sensor number of the first one.
        first: usize,
        /// Their joint.
        joint: u32,
        /// Their number within the joint.
        number: u32,
    },
    /// A sensor's crosstalk row does not have one entry per joint.
    CrosstalkLength {
        /// 1-based sensor number.
        sensor: usize,
        /// Entries given.
        len: usize,
        /// Joints of the robot.
        joints: usize,
    },
    /// A crosstalk entry is not finite.
    CrosstalkNotFinite {
        /// 1-based sensor number.
        sensor: usize,
        /// 1-based joint number (the entry's column).
        joint: usize,
        /// The value.
        value: f64,
    },
    /// A sensor's crosstalk on its own joint is not 1 (the sensor's gain lives in its model).
    CrosstalkOwn {
        /// 1-based sensor number.
        sensor: usize,
        /// Its joint (1-based).
        joint: u32,
        /// The value given.
        value: f64,
    },
    /// `max_condition_number` is not a finite number of at least 1.
    ConditionLimit {
        /// The value given.
        value: f64,
    },
    /// The crosstalk matrix does not have full column rank (to rounding): some combination of
    /// joint angles moves no sensor.
    RankDeficient {
        /// Its smallest singular value.
        smallest: f64,
        /// The numerical-rank threshold `max(M, N)·ε·σ_max` it is at or below.
        threshold: f64,
    },
    /// The crosstalk matrix's condition number exceeds the configured limit.
    IllConditioned {
        /// `σ_max/σ_min`.
        condition: f64,
        /// `max_condition_number`.
        limit: f64,
    },
    /// The singular value decomposition did not converge.
    Decomposition {
        /// The iteration limit it reached.
        iterations: usize,
    },
    /// The pseudo-inverse failed its self-check `P·C = I`.
    SelfCheck {
        /// `max |P·C − I|`.
        error: f64,
        /// The rounding allowed.
        limit: f64,
    },
}

impl fmt::Display for RobotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Joint { joint, error } => write!(f, "joint {joint}: {error}"),
            Self::Sensor { sensor, error } => write!(f, "sensor {sensor}: {error}"),
            Self::Kinematics(e) => e.fmt(f),
            Self::Config(e) => e.fmt(f),
            Self::TooFewSensors { sensors, joints } => write!(
                f,
                "{sensors} sensors cannot tell {joints} joint angles apart (needs at least {joints} sensors)"
            ),
            Self::SensorJoint { sensor, joint, joints } => write!(
                f,
                "sensor {sensor}: joint = {joint} must lie between 1 and {joints} (the robot's joints)"
            ),
            Self::SensorNumber { sensor, number, joint, style } => write!(
                f,
                "sensor {sensor}: sensor = {number} must be 1{} ({} joint {joint} carries {})",
                if style.sensor_count() > 1 { " or 2" } else { "" },
                match style {
                    NotchStyle::Uan => "the uan",
                    NotchStyle::Bsn => "the bsn",
                },
                style.sensor_count()
            ),
            Self::DuplicateSensor { sensor, first, joint, number } => write!(
                f,
                "sensor {sensor}: it is sensor {number} of joint {joint}, as sensor {first} already is"
            ),
            Self::CrosstalkLength { sensor, len, joints } => write!(
                f,
                "sensor {sensor}: crosstalk has {len} entries, must have one per joint ({joints})"
            ),
            Self::CrosstalkNotFinite { sensor, joint, value } => write!(
                f,
                "sensor {sensor}: crosstalk[{joint}] = {value} is not a finite number"
            ),
            Self::CrosstalkOwn { sensor, joint, value } => write!(
                f,
                "sensor {sensor}: crosstalk[{joint}] = {value} is its own joint's and must be 1 (the sensor's gain lives in its model)"
            ),
            Self::ConditionLimit { value } => write!(
                f,
                "max_condition_number = {value} must be a finite number of at least 1"
            ),
            Self::RankDeficient { smallest, threshold } => write!(
                f,
                "the crosstalk matrix is rank deficient: its smallest singular value {smallest:.3e} is at or below {threshold:.3e} (max(M, N)·ε·σ_max), so some joint angles cannot be told apart"
            ),
            Self::IllConditioned { condition, limit } => write!(
                f,
                "the crosstalk matrix's condition number {condition:.4} exceeds max_condition_number = {limit} (a sensor's error could reach the joint angles amplified up to that much)"
            ),
            Self::Decomposition { iterations } => write!(
                f,
                "the crosstalk matrix's singular value decomposition did not converge in {iterations} iterations"
            ),
            Self::SelfCheck { error, limit } => write!(
                f,
                "the crosstalk pseudo-inverse P fails its self-check: max |P·C − I| = {error:.3e} exceeds {limit:.3e}"
            ),
        }
    }
}

impl From<KinematicsError> for RobotError {
    fn from(e: KinematicsError) -> Self {
        Self::Kinematics(e)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for RobotError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Joint { error, .. } | Self::Sensor { error, .. } | Self::Config(error) => {
                Some(error)
            }
            Self::Kinematics(e) => Some(e),
            _ => None,
        }
    }
}
