use dlw_geometry::{BendingSection, Divider, Kinematics, MAX_JOINTS};

use super::error::RobotError;
use super::unmix::{Unmixing, DEFAULT_MAX_CONDITION_NUMBER, MAX_SENSORS};
use crate::config::{EstimatorConfig, JointConfig, ModelConfig, SensorConfig, SensorPlane};
use crate::filter::FilterConfig;
use crate::linear::LinearModel;
use crate::list::List;

/// One joint of a robot: where its notched section lies on the tube and how it is turned (as
/// `dlw inspect ROBOT --json` reports them), and its design parameters, which its sensors'
/// models turn strain into angle with.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct RobotJointConfig {
    /// Its bending plane about the tube axis: its `+y` (backbone, sensor side) lies at
    /// `s = r_o·rotation` (degrees).
    pub rotation_deg: f64,
    /// Distal end of its notched section, drawing `x` (mm).
    pub x_start_mm: f64,
    /// Proximal end of its notched section, drawing `x` (mm).
    pub x_end_mm: f64,
    /// Its design parameters (cross-section, notches, gauge length).
    pub geometry: JointConfig,
}

impl RobotJointConfig {
    /// The section the kinematics bends (rotation in radians).
    pub fn section(&self) -> BendingSection {
        BendingSection {
            rotation_rad: self.rotation_deg.to_radians(),
            x_start_mm: self.x_start_mm,
            x_end_mm: self.x_end_mm,
        }
    }
}

/// One sensor of a robot: which joint carries it, its divider and model (as for one joint), and
/// its row of the crosstalk matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct RobotSensorConfig {
    /// The joint that carries it (1-based, joint 1 distal).
    pub joint: u32,
    /// Which of its joint's sensors: 1 (plane `+y_s`) or, on a BSN joint, 2 (plane `−y_s`).
    pub sensor: u32,
    /// Fixed divider resistor `R_k` (Ω).
    pub divider_ohm: f64,
    /// Divider supply `V+` (V).
    pub supply_v: f64,
    /// Resistance to strain, as for one joint (`[sensor.model.linear]`, `.pi`,
    /// `.continuous_pi`).
    pub model: ModelConfig,
    /// Its row of the crosstalk matrix `C`, one entry per joint: the share of each joint's
    /// angle the sensor reads, relative to its own joint's (`crosstalk[own] = 1`).
    pub crosstalk: List<f64, MAX_JOINTS>,
}

impl RobotSensorConfig {
    /// A linear sensor: gauge factor `GF`, unstrained resistance `R₀`, read through `divider`.
    ///
    /// # Errors
    /// As [`LinearModel::new`]; a crosstalk row longer than [`MAX_JOINTS`].
    pub fn linear(
        joint: u32,
        sensor: u32,
        gauge_factor: f64,
        r0_ohm: f64,
        divider: Divider,
        crosstalk: &[f64],
    ) -> Result<Self, RobotError> {
        let model = LinearModel::new(gauge_factor, r0_ohm).map_err(RobotError::Config)?;
        Ok(Self {
            joint,
            sensor,
            divider_ohm: divider.fixed_ohm,
            supply_v: divider.supply_v,
            model: ModelConfig::Linear(model),
            crosstalk: List::from_slice("crosstalk", crosstalk).map_err(RobotError::Config)?,
        })
    }

    /// The plane its number puts it on.
    pub fn plane(&self) -> SensorPlane {
        if self.sensor == 2 {
            SensorPlane::MinusYs
        } else {
            SensorPlane::PlusYs
        }
    }
}

#[cfg(feature = "serde")]
fn default_max_condition_number() -> f64 {
    DEFAULT_MAX_CONDITION_NUMBER
}

/// Everything a [`super::RobotEstimator`] is built from: the robot's joints, its sensors and the
/// crosstalk matrix (one row per sensor), the filters and the conditioning limit.
///
/// Sensors are in the order of `dlw inspect ROBOT --json`'s `"sensors"` (by joint, then sensor 1
/// before 2), which is also the order of the voltages each sample. In TOML:
///
/// ```toml
/// max_condition_number = 10.0      # optional, this default
/// # input_filter, output_filter: optional, as for one joint
///
/// [[joint]]
/// rotation_deg = 0.0
/// x_start_mm = 0.5
/// x_end_mm = 10.0
/// [joint.geometry]                 # the joint's design, as [joint] of a one-joint config
/// style = "uan"
/// # …
///
/// [[sensor]]
/// joint = 1
/// sensor = 1
/// divider_ohm = 99600.0
/// supply_v = 5.0
/// crosstalk = [1.0, 0.031]
/// [sensor.model.linear]
/// gauge_factor = 15.3
/// r0_ohm = 215000.0
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct RobotEstimatorConfig {
    /// Largest condition number of the crosstalk matrix accepted (≥ 1); default
    /// [`DEFAULT_MAX_CONDITION_NUMBER`].
    #[cfg_attr(feature = "serde", serde(default = "default_max_condition_number"))]
    pub max_condition_number: f64,
    /// Filter on each sensor's resistance, before its model.
    #[cfg_attr(feature = "serde", serde(default))]
    pub input_filter: FilterConfig,
    /// Filter on each sensor's mixed angle, before the crosstalk is undone. The filters are
    /// linear and the same for every sensor, so this is the same filter on the joint angles.
    #[cfg_attr(feature = "serde", serde(default))]
    pub output_filter: FilterConfig,
    /// The joints, joint 1 (distal) first.
    pub joint: List<RobotJointConfig, MAX_JOINTS>,
    /// The sensors, in `dlw inspect`'s order.
    pub sensor: List<RobotSensorConfig, MAX_SENSORS>,
}

/// A checked configuration: each sensor's one-joint estimator config, the kinematics and the
/// unmixing.
pub(crate) struct Resolved {
    pub(crate) chains: List<EstimatorConfig, MAX_SENSORS>,
    pub(crate) kinematics: Kinematics,
    pub(crate) unmixing: Unmixing,
}

impl RobotEstimatorConfig {
    /// A configuration of `joints` and `sensors`, with no filters and the default conditioning
    /// limit.
    ///
    /// # Errors
    /// More than [`MAX_JOINTS`] joints or [`MAX_SENSORS`] sensors, or anything
    /// [`RobotEstimatorConfig::validate`] refuses.
    pub fn new(
        joints: &[RobotJointConfig],
        sensors: &[RobotSensorConfig],
    ) -> Result<Self, RobotError> {
        let config = Self {
            max_condition_number: DEFAULT_MAX_CONDITION_NUMBER,
            input_filter: FilterConfig::None,
            output_filter: FilterConfig::None,
            joint: List::from_slice("joint", joints).map_err(RobotError::Config)?,
            sensor: List::from_slice("sensor", sensors).map_err(RobotError::Config)?,
        };
        config.validate()?;
        Ok(config)
    }

    /// Joints `N`.
    pub fn joint_count(&self) -> usize {
        self.joint.len()
    }

    /// Sensors `M`.
    pub fn sensor_count(&self) -> usize {
        self.sensor.len()
    }

    /// The robot's kinematics, to turn estimated angles into the tip's pose and the backbone.
    ///
    /// # Errors
    /// As [`Kinematics::new`].
    pub fn kinematics(&self) -> Result<Kinematics, RobotError> {
        let mut sections = [BendingSection {
            rotation_rad: 0.0,
            x_start_mm: 0.0,
            x_end_mm: 0.0,
        }; MAX_JOINTS];
        for (s, j) in sections.iter_mut().zip(self.joint.iter()) {
            *s = j.section();
        }
        Ok(Kinematics::new(&sections[..self.joint.len()])?)
    }

    /// The one-joint estimator config sensor `index` (0-based) runs on: its joint's geometry,
    /// its divider and model on its plane, the robot's filters.
    ///
    /// # Errors
    /// [`RobotError::SensorJoint`] when it names a joint the robot lacks.
    pub fn sensor_estimator_config(&self, index: usize) -> Result<EstimatorConfig, RobotError> {
        let s = &self.sensor[index];
        let joint = self.joint_of(index)?;
        Ok(EstimatorConfig {
            joint: joint.geometry,
            sensor: SensorConfig {
                divider_ohm: s.divider_ohm,
                supply_v: s.supply_v,
                plane: Some(s.plane()),
                model: s.model,
            },
            second_sensor: None,
            input_filter: self.input_filter,
            output_filter: self.output_filter,
        })
    }

    fn joint_of(&self, index: usize) -> Result<&RobotJointConfig, RobotError> {
        let s = &self.sensor[index];
        match (s.joint as usize)
            .checked_sub(1)
            .and_then(|j| self.joint.get(j))
        {
            Some(joint) => Ok(joint),
            None => Err(RobotError::SensorJoint {
                sensor: index + 1,
                joint: s.joint,
                joints: self.joint.len(),
            }),
        }
    }

    /// Checks the whole configuration without building the estimator.
    ///
    /// # Errors
    /// A joint's geometry or section; a sensor naming a missing joint or a sensor its joint does
    /// not carry, or the same sensor twice; a sensor's divider, model or filter; a crosstalk row
    /// of the wrong length, with a non-finite entry, or whose own entry is not 1; fewer sensors
    /// than joints; a crosstalk matrix that is rank deficient or whose condition number exceeds
    /// `max_condition_number`.
    pub fn validate(&self) -> Result<(), RobotError> {
        self.resolve().map(|_| ())
    }

    pub(crate) fn resolve(&self) -> Result<Resolved, RobotError> {
        let joints = self.joint.len();
        for (j, joint) in self.joint.iter().enumerate() {
            joint.geometry.to_joint().map_err(|e| RobotError::Joint {
                joint: j + 1,
                error: e.into(),
            })?;
        }
        let kinematics = self.kinematics()?;
        if self.sensor.len() < joints {
            return Err(RobotError::TooFewSensors {
                sensors: self.sensor.len(),
                joints,
            });
        }
        let mut chains = List::new();
        let mut rows = [[0.0; MAX_JOINTS]; MAX_SENSORS];
        for (i, s) in self.sensor.iter().enumerate() {
            let sensor = i + 1;
            let joint = self.joint_of(i)?;
            let style = joint.geometry.style;
            if s.sensor == 0 || s.sensor > style.sensor_count() {
                return Err(RobotError::SensorNumber {
                    sensor,
                    number: s.sensor,
                    joint: s.joint,
                    style,
                });
            }
            if let Some(first) = self.sensor[..i]
                .iter()
                .position(|o| o.joint == s.joint && o.sensor == s.sensor)
            {
                return Err(RobotError::DuplicateSensor {
                    sensor,
                    first: first + 1,
                    joint: s.joint,
                    number: s.sensor,
                });
            }
            let config = self.sensor_estimator_config(i)?;
            config
                .validate()
                .map_err(|error| RobotError::Sensor { sensor, error })?;
            chains.push(config);
            if s.crosstalk.len() != joints {
                return Err(RobotError::CrosstalkLength {
                    sensor,
                    len: s.crosstalk.len(),
                    joints,
                });
            }
            for (j, &value) in s.crosstalk.iter().enumerate() {
                if !value.is_finite() {
                    return Err(RobotError::CrosstalkNotFinite {
                        sensor,
                        joint: j + 1,
                        value,
                    });
                }
            }
            let own = s.crosstalk[s.joint as usize - 1];
            if own != 1.0 {
                return Err(RobotError::CrosstalkOwn {
                    sensor,
                    joint: s.joint,
                    value: own,
                });
            }
            rows[i][..joints].copy_from_slice(&s.crosstalk);
        }
        let unmixing = Unmixing::new(
            &rows[..self.sensor.len()],
            joints,
            self.max_condition_number,
        )?;
        Ok(Resolved {
            chains,
            kinematics,
            unmixing,
        })
    }
}
