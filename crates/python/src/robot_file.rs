//! `dlw.Robot`: a robot file (issue 33) read and checked as `dlw inspect ROBOT` reads it, with
//! what its runtime needs (issue 34 §3): `inspect()` is `dlw inspect ROBOT --json`'s dict,
//! `estimator(config)` a `RobotEstimator` for a config of this robot (refused when it is
//! another robot's), `tip` and `backbone` its kinematics, and `estimator_config` the nominal
//! config `dlw estimator-config ROBOT` writes.

use std::path::PathBuf;

use dlw_core::robot::estimator_config::{joint_configs, nominal_linear};
use dlw_core::robot::{CheckedRobot, RobotInspection};
use dlw_estimator::{
    BendingSection, Kinematics, RobotEstimatorConfig, RobotJointConfig, DEFAULT_SUPPLY_V,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::robot::{backbone_of, config_arg, tip_of, RobotEstimator};
use super::{message, to_python, value_error};

/// Largest difference between a config's joint placement and the robot's that still counts as
/// the same robot (mm and °). Configs that dlw writes carry the robot's numbers exactly
/// (shortest round-trip decimals); this only absorbs a hand-written config's rounding.
const SAME_PLACEMENT_TOLERANCE: f64 = 1e-9;

/// A sensing robot: several joints on one tube (`docs/robots.md`).
#[pyclass(module = "dlw")]
pub(crate) struct Robot {
    robot: CheckedRobot,
    path: PathBuf,
    joints: Vec<RobotJointConfig>,
    kinematics: Kinematics,
}

impl Robot {
    /// Refuses a config that is not this robot's: its joints and sensors by count, each joint's
    /// place and design, each sensor's joint and number.
    fn check(&self, config: &RobotEstimatorConfig) -> PyResult<()> {
        let name = &self.robot.robot.name;
        let (joints, sensors) = (self.joints.len(), self.robot.sensors.len());
        if config.joint_count() != joints || config.sensor_count() != sensors {
            return Err(message(format!(
                "the config has {} joints and {} sensors, the robot {name:?} has {joints} joints and {sensors} sensors",
                config.joint_count(),
                config.sensor_count()
            )));
        }
        for (j, (c, r)) in config.joint.iter().zip(&self.joints).enumerate() {
            for (key, c, r) in [
                ("rotation_deg", c.rotation_deg, r.rotation_deg),
                ("x_start_mm", c.x_start_mm, r.x_start_mm),
                ("x_end_mm", c.x_end_mm, r.x_end_mm),
            ] {
                if (c - r).abs() > SAME_PLACEMENT_TOLERANCE || !c.is_finite() {
                    return Err(message(format!(
                        "joint {}: the config's {key} = {c} and the robot {name:?}'s {r}",
                        j + 1
                    )));
                }
            }
            if c.geometry != r.geometry {
                return Err(message(format!(
                    "joint {}: the config's geometry is not the robot {name:?}'s design ({})",
                    j + 1,
                    self.robot.robot.joints[j].design().file.name
                )));
            }
        }
        for (i, (c, r)) in config
            .sensor
            .iter()
            .zip(self.robot.robot.sensors())
            .enumerate()
        {
            let (joint, sensor) = (r.joint as u32 + 1, r.sensor as u32 + 1);
            if (c.joint, c.sensor) != (joint, sensor) {
                return Err(message(format!(
                    "sensor {}: the config's is joint {} sensor {}, the robot {name:?}'s is joint {joint} sensor {sensor}",
                    i + 1,
                    c.joint,
                    c.sensor
                )));
            }
        }
        Ok(())
    }
}

/// One value or a sequence of values (one per sensor).
fn values(value: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Vec<f64>> {
    let Some(value) = value else {
        return Ok(Vec::new());
    };
    if let Ok(v) = value.extract::<f64>() {
        return Ok(vec![v]);
    }
    value.extract::<Vec<f64>>().map_err(|_| {
        message(format!(
            "{name} must be a number or a sequence of numbers (one per sensor)"
        ))
    })
}

#[pymethods]
impl Robot {
    /// Reads, checks and routes a robot file (TOML), as `dlw inspect ROBOT` does.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let robot = CheckedRobot::load(&path).map_err(value_error)?;
        let joints = joint_configs(&robot);
        let sections: Vec<BendingSection> = joints.iter().map(RobotJointConfig::section).collect();
        let kinematics = Kinematics::new(&sections).map_err(|e| message(e.to_string()))?;
        Ok(Self {
            robot,
            path,
            joints,
            kinematics,
        })
    }

    /// The robot's name.
    #[getter]
    fn name(&self) -> String {
        self.robot.robot.name.clone()
    }

    /// The file it was read from.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// Joints `N`.
    #[getter]
    fn joints(&self) -> usize {
        self.joints.len()
    }

    /// Sensors `M`.
    #[getter]
    fn sensors(&self) -> usize {
        self.robot.sensors.len()
    }

    /// The robot's numbers, as `dlw inspect ROBOT --json` prints them: `joints` (each with its
    /// design's keys, `rotation_deg`, `x_start_mm`, `x_end_mm`), `sensors` (each with
    /// `crosstalk`), `warnings`.
    fn inspect<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &RobotInspection::of(&self.robot))
    }

    /// The runtime estimator of `config` (a path to a robot estimator config, its TOML text, a
    /// dict, or a `RobotEstimator`), refused unless it is this robot's config (the same joints
    /// in the same places, the same sensors).
    fn estimator(&self, config: &Bound<'_, PyAny>) -> PyResult<RobotEstimator> {
        // A string is TOML text when it is no file and reads as an assignment.
        let config = match config.extract::<String>() {
            Ok(text) if text.contains('=') && !std::path::Path::new(&text).is_file() => {
                toml::from_str(&text)
                    .map_err(|e| message(format!("the config: {}", e.to_string().trim_end())))?
            }
            _ => config_arg(config)?,
        };
        self.check(&config)?;
        RobotEstimator::new(config)
    }

    /// The nominal linear config `dlw estimator-config ROBOT` writes, as a dict (what
    /// `estimator` and `RobotEstimator.from_dict` take): `gauge_factor` and `r0_ohm` (Ω) once
    /// for every sensor or once per sensor in `inspect()`'s order; `divider_ohm` likewise
    /// (default: the bench's, 99.6 kΩ for each sensor 1, 102.5 kΩ for a BSN joint's sensor 2);
    /// the crosstalk matrix from the geometry.
    #[pyo3(signature = (gauge_factor, r0_ohm, divider_ohm=None, supply_v=DEFAULT_SUPPLY_V))]
    fn estimator_config<'py>(
        &self,
        py: Python<'py>,
        gauge_factor: &Bound<'py, PyAny>,
        r0_ohm: &Bound<'py, PyAny>,
        divider_ohm: Option<&Bound<'py, PyAny>>,
        supply_v: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let config = nominal_linear(
            &self.robot,
            &values(Some(gauge_factor), "gauge_factor")?,
            &values(Some(r0_ohm), "r0_ohm")?,
            &values(divider_ohm, "divider_ohm")?,
            supply_v,
        )
        .map_err(value_error)?;
        to_python(py, &config)
    }

    /// The tip's pose at joint angles `angles` (°, shape (n, N) or (N,)), as `dlw.tip`: a dict
    /// of `position_mm`, `rotation` and `quaternion` in the robot's base frame.
    fn tip<'py>(
        &self,
        py: Python<'py>,
        angles: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        tip_of(py, &self.kinematics, angles)
    }

    /// `points` points of the backbone (mm, base frame) from the base to the tip at joint
    /// angles `angles` (°), as `dlw.backbone`.
    #[pyo3(signature = (angles, points=20))]
    fn backbone<'py>(
        &self,
        py: Python<'py>,
        angles: &Bound<'py, PyAny>,
        points: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        backbone_of(py, &self.kinematics, angles, points)
    }

    fn __repr__(&self) -> String {
        format!(
            "Robot({:?}, joints={}, sensors={})",
            self.robot.robot.name,
            self.joints.len(),
            self.robot.sensors.len()
        )
    }
}
