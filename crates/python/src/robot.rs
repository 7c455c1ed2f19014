//! `dlw.RobotEstimator`, `dlw.tip` and `dlw.backbone`: the robot runtime (issue 34) from
//! Python, vectorised over numpy arrays. Angles are in degrees at this edge, as in
//! `Estimator.run`.
//!
//! `dlw.Robot` (`robot_file.rs`) reuses [`config_arg`], [`tip_of`] and [`backbone_of`] with
//! the kinematics of a robot file.

use std::path::{Path, PathBuf};

use dlw_core::replay::ConfigFormat;
use dlw_estimator::{Kinematics, RobotEstimator as Runtime, RobotEstimatorConfig};
use numpy::ndarray::{Array2, Array3, ArrayView2};
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{from_python, message, to_python, value_error};

/// A robot estimator config from a file (`.toml` or `.json`), through the bounded reader.
fn load(path: &Path) -> PyResult<RobotEstimatorConfig> {
    let format = ConfigFormat::of(path).map_err(value_error)?;
    let text = dlw_core::output::read_limited(path, dlw_core::limits::MAX_TEXT_INPUT_BYTES)
        .map_err(|e| message(format!("reading {}: {e}", path.display())))?;
    let config = match format {
        ConfigFormat::Toml => {
            toml::from_str(&text).map_err(|e| dlw_core::limits::parser_message(&e))
        }
        ConfigFormat::Json => {
            serde_json::from_str(&text).map_err(|e| dlw_core::limits::parser_message(&e))
        }
    };
    config.map_err(|e| message(format!("{}: {}", path.display(), e.trim_end())))
}

/// A robot estimator config: a path to a config file, a dict (the file's tables), or a
/// `RobotEstimator`.
pub(crate) fn config_arg(value: &Bound<'_, PyAny>) -> PyResult<RobotEstimatorConfig> {
    if let Ok(e) = value.extract::<PyRef<'_, RobotEstimator>>() {
        return Ok(e.config);
    }
    if value.cast::<PyDict>().is_ok() {
        return from_python(value);
    }
    let path: PathBuf = value.extract().map_err(|_| {
        message("config must be a RobotEstimator, a dict or a path to a robot estimator config")
    })?;
    load(&path)
}

/// The kinematics of a robot argument (see [`config_arg`]).
fn kinematics_arg(value: &Bound<'_, PyAny>) -> PyResult<Kinematics> {
    config_arg(value)?
        .kinematics()
        .map_err(|e| message(e.to_string()))
}

/// Rows of numbers: a 2-D numpy array, a 1-D one (one row), or nested sequences; and whether
/// the input was one row.
fn rows(value: &Bound<'_, PyAny>, width: usize, what: &str) -> PyResult<(Array2<f64>, bool)> {
    if let Ok(a) = value.extract::<PyReadonlyArray2<'_, f64>>() {
        return check_width(a.as_array().to_owned(), width, what).map(|a| (a, false));
    }
    if let Ok(a) = value.extract::<PyReadonlyArray1<'_, f64>>() {
        let row = a.as_array().to_owned();
        let n = row.len();
        let a = row
            .into_shape_with_order((1, n))
            .map_err(|e| message(e.to_string()))?;
        return check_width(a, width, what).map(|a| (a, true));
    }
    if let Ok(v) = value.extract::<Vec<Vec<f64>>>() {
        let n = v.len();
        let flat: Vec<f64> = v.iter().flatten().copied().collect();
        if v.iter().any(|r| r.len() != width) {
            return Err(message(format!(
                "{what} must have {width} columns, a row has {}",
                v.iter().map(Vec::len).find(|&l| l != width).unwrap_or(0)
            )));
        }
        let a = Array2::from_shape_vec((n, width), flat).map_err(|e| message(e.to_string()))?;
        return Ok((a, false));
    }
    let row: Vec<f64> = value.extract().map_err(|_| {
        message(format!(
            "{what} must be a numpy array of shape (n, {width}) or ({width},)"
        ))
    })?;
    let n = row.len();
    let a = Array2::from_shape_vec((1, n), row).map_err(|e| message(e.to_string()))?;
    check_width(a, width, what).map(|a| (a, true))
}

fn check_width(a: Array2<f64>, width: usize, what: &str) -> PyResult<Array2<f64>> {
    if a.ncols() != width {
        return Err(message(format!(
            "{what} has {} columns, must have {width} (one per {})",
            a.ncols(),
            if what == "volts" { "sensor" } else { "joint" }
        )));
    }
    Ok(a)
}

/// Degrees to radians, refusing a NaN or infinite angle with its sample and joint.
fn radians(angles_deg: ArrayView2<'_, f64>) -> PyResult<Array2<f64>> {
    if let Some(((k, j), a)) = angles_deg.indexed_iter().find(|(_, a)| !a.is_finite()) {
        return Err(message(format!(
            "angles[{k}, {j}] = {a} is not a finite number"
        )));
    }
    Ok(angles_deg.mapv(f64::to_radians))
}

/// The robot's runtime estimator: every sensor's divider voltage in, every joint's angle (°)
/// out, the crosstalk undone.
#[pyclass(module = "dlw")]
pub(crate) struct RobotEstimator {
    config: RobotEstimatorConfig,
    runtime: Box<Runtime>,
    flags: Vec<u32>,
}

impl RobotEstimator {
    pub(crate) fn new(config: RobotEstimatorConfig) -> PyResult<Self> {
        let runtime = Box::new(Runtime::new(&config).map_err(|e| message(e.to_string()))?);
        Ok(Self {
            flags: vec![0; config.joint_count()],
            config,
            runtime,
        })
    }
}

#[pymethods]
impl RobotEstimator {
    /// The estimator of a robot estimator config file (`.toml` or `.json`).
    #[staticmethod]
    fn from_config(path: PathBuf) -> PyResult<Self> {
        Self::new(load(&path)?)
    }

    /// The estimator of a config's TOML text.
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        let config: RobotEstimatorConfig = toml::from_str(text)
            .map_err(|e| message(format!("the config: {}", e.to_string().trim_end())))?;
        Self::new(config)
    }

    /// The estimator of a config given as a dict (the TOML file's tables).
    #[staticmethod]
    fn from_dict(config: &Bound<'_, PyDict>) -> PyResult<Self> {
        Self::new(from_python(config.as_any())?)
    }

    /// The config, as a dict.
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.config)
    }

    /// The config as TOML text.
    fn config_toml(&self) -> PyResult<String> {
        toml::to_string(&self.config).map_err(|e| message(e.to_string()))
    }

    /// Joints `N`.
    #[getter]
    fn joints(&self) -> usize {
        self.config.joint_count()
    }

    /// Sensors `M`: the voltages per sample.
    #[getter]
    fn sensors(&self) -> usize {
        self.config.sensor_count()
    }

    /// Condition number of the crosstalk matrix.
    #[getter]
    fn condition_number(&self) -> f64 {
        self.runtime.unmixing().condition_number()
    }

    /// Each joint's flags from the last `step` (the runtime's bits; 0: none).
    #[getter]
    fn flags(&self) -> Vec<u32> {
        self.flags.clone()
    }

    /// Angles (°, shape (n, N)) over voltages (shape (n, M)), from a fresh estimator (this
    /// object's state is not touched). With `flags=True`, also each joint's flags (uint32,
    /// shape (n, N)).
    #[pyo3(signature = (volts, flags=false))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        volts: &Bound<'py, PyAny>,
        flags: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (volts, _) = rows(volts, self.config.sensor_count(), "volts")?;
        let config = self.config;
        let n = self.config.joint_count();
        let (angles, bits) = py
            .detach(|| -> Result<(Array2<f64>, Array2<u32>), String> {
                let mut runtime = Box::new(Runtime::new(&config).map_err(|e| e.to_string())?);
                let mut angles = Array2::zeros((volts.nrows(), n));
                let mut bits = Array2::zeros((volts.nrows(), n));
                for (k, row) in volts.rows().into_iter().enumerate() {
                    let v = row.to_vec();
                    let e = runtime.step(&v);
                    for j in 0..n {
                        angles[(k, j)] = e.angle_deg(j);
                        bits[(k, j)] = u32::from(e.flags()[j].bits());
                    }
                }
                Ok((angles, bits))
            })
            .map_err(message)?;
        let angles = angles.into_pyarray(py).into_any();
        if flags {
            let tuple = (angles, bits.into_pyarray(py));
            Ok(tuple.into_pyobject(py)?.into_any())
        } else {
            Ok(angles)
        }
    }

    /// One sample: the M voltages to the N angles (°); `flags` then holds their flags.
    fn step(&mut self, volts: Vec<f64>) -> PyResult<Vec<f64>> {
        if volts.len() != self.config.sensor_count() {
            return Err(message(format!(
                "{} voltages were given, the robot has {} sensors",
                volts.len(),
                self.config.sensor_count()
            )));
        }
        let e = self.runtime.step(&volts);
        self.flags = e.flags().iter().map(|f| u32::from(f.bits())).collect();
        Ok((0..self.config.joint_count())
            .map(|j| e.angle_deg(j))
            .collect())
    }

    /// Back to the state of a new estimator.
    fn reset(&mut self) {
        self.runtime.reset();
        self.flags = vec![0; self.config.joint_count()];
    }

    fn __repr__(&self) -> String {
        format!(
            "RobotEstimator(joints={}, sensors={})",
            self.config.joint_count(),
            self.config.sensor_count()
        )
    }
}

/// The tip's pose at joint angles `angles` (°, shape (n, N) or (N,)) of the robot `config` (a
/// `RobotEstimator`, a robot estimator config dict or file): a dict of `position_mm` (n, 3),
/// `rotation` (n, 3, 3; columns are the tip frame's axes, the third its tangent) and
/// `quaternion` (n, 4: w, x, y, z with w ≥ 0), in the robot's base frame; without the leading
/// n for one row of angles.
#[pyfunction]
pub(crate) fn tip<'py>(
    py: Python<'py>,
    angles: &Bound<'py, PyAny>,
    config: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    tip_of(py, &kinematics_arg(config)?, angles)
}

/// [`tip`] for a robot's kinematics.
pub(crate) fn tip_of<'py>(
    py: Python<'py>,
    kinematics: &Kinematics,
    angles: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let kinematics = *kinematics;
    let (angles, single) = rows(angles, kinematics.joint_count(), "angles")?;
    let angles = radians(angles.view())?;
    let n = angles.nrows();
    let (position, rotation, quaternion) = py
        .detach(|| -> Result<_, String> {
            let mut position = Array2::zeros((n, 3));
            let mut rotation = Array3::zeros((n, 3, 3));
            let mut quaternion = Array2::zeros((n, 4));
            for (k, row) in angles.rows().into_iter().enumerate() {
                let pose = kinematics.tip(&row.to_vec()).map_err(|e| e.to_string())?;
                for i in 0..3 {
                    position[(k, i)] = pose.position_mm[i];
                    for c in 0..3 {
                        rotation[(k, i, c)] = pose.rotation[i][c];
                    }
                }
                for i in 0..4 {
                    quaternion[(k, i)] = pose.quaternion[i];
                }
            }
            Ok((position, rotation, quaternion))
        })
        .map_err(message)?;
    let d = PyDict::new(py);
    if single {
        d.set_item("position_mm", position.row(0).to_owned().into_pyarray(py))?;
        d.set_item(
            "rotation",
            rotation
                .index_axis(numpy::ndarray::Axis(0), 0)
                .to_owned()
                .into_pyarray(py),
        )?;
        d.set_item("quaternion", quaternion.row(0).to_owned().into_pyarray(py))?;
    } else {
        d.set_item("position_mm", position.into_pyarray(py))?;
        d.set_item("rotation", rotation.into_pyarray(py))?;
        d.set_item("quaternion", quaternion.into_pyarray(py))?;
    }
    Ok(d)
}

/// `points` points of the backbone (mm, base frame), equally spaced in arc length from the base
/// to the tip, at joint angles `angles` (°, shape (n, N) or (N,)): shape (n, points, 3), or
/// (points, 3) for one row of angles.
#[pyfunction]
#[pyo3(signature = (angles, config, points=20))]
pub(crate) fn backbone<'py>(
    py: Python<'py>,
    angles: &Bound<'py, PyAny>,
    config: &Bound<'py, PyAny>,
    points: usize,
) -> PyResult<Bound<'py, PyAny>> {
    backbone_of(py, &kinematics_arg(config)?, angles, points)
}

/// [`backbone`] for a robot's kinematics.
pub(crate) fn backbone_of<'py>(
    py: Python<'py>,
    kinematics: &Kinematics,
    angles: &Bound<'py, PyAny>,
    points: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let kinematics = *kinematics;
    let (angles, single) = rows(angles, kinematics.joint_count(), "angles")?;
    let angles = radians(angles.view())?;
    let n = angles.nrows();
    let out = py
        .detach(|| -> Result<Array3<f64>, String> {
            let mut out = Array3::zeros((n, points, 3));
            let mut buffer = vec![[0.0; 3]; points];
            for (k, row) in angles.rows().into_iter().enumerate() {
                kinematics
                    .backbone(&row.to_vec(), &mut buffer)
                    .map_err(|e| e.to_string())?;
                for (p, xyz) in buffer.iter().enumerate() {
                    for i in 0..3 {
                        out[(k, p, i)] = xyz[i];
                    }
                }
            }
            Ok(out)
        })
        .map_err(message)?;
    if single {
        let one: Array2<f64> = out.index_axis(numpy::ndarray::Axis(0), 0).to_owned();
        Ok(one.into_pyarray(py).into_any())
    } else {
        Ok(out.into_pyarray(py).into_any())
    }
}
