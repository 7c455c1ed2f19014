//! `import dlw`: the Python face of `dlw` (issue 20), built with PyO3 and maturin.
//!
//! Every function is a thin layer over the library the command line uses, so a result here is
//! the command's result: `fit` is `dlw::fit::fit`, `Estimator.run` steps the runtime crate's
//! estimator exactly as `dlw estimate` does, `discover` builds `dlw discover --json`'s
//! summary. `RobotEstimator`, `tip` and `backbone` are the robot runtime (`robot.rs`), `Robot`
//! a robot file with its inspection, estimator and kinematics (`robot_file.rs`). Bad
//! input raises `ValueError` with the command's message; long work releases the GIL.
//! `docs/python.md` is the user's guide.

use std::path::{Path, PathBuf};

mod robot;
mod robot_file;

use dlw_core::analysis::Analysis as _;
use dlw_core::design::{Design as CoreDesign, DesignFile};
use dlw_core::discover as discovery;
use dlw_core::fit::{FitRequest, ModelKind, PlayOrder};
use dlw_core::recording::{Recording, Rig, Samples};
use dlw_core::sensor::Sensors;
use dlw_core::signal::Prefilter;
use dlw_core::sim::{self, ProtocolKind, Scenario};
use dlw_estimator::{Estimator as Runtime, EstimatorConfig};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `e`'s message and its causes, joined as the command line joins them (a cause the message
/// already quotes is not repeated).
fn error_text(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        let cause = s.to_string();
        if !text.contains(&cause) {
            text.push_str(": ");
            text.push_str(&cause);
        }
        source = s.source();
    }
    text
}

/// A `ValueError` carrying [`error_text`].
fn value_error(e: impl std::error::Error) -> PyErr {
    PyValueError::new_err(error_text(&e))
}

fn message(text: impl Into<String>) -> PyErr {
    PyValueError::new_err(text.into())
}

/// A serializable value as the Python object `json.loads` makes of it.
fn to_python<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = dlw_core::finite::to_json(value).map_err(|e| message(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object as `T`, through `json.dumps`.
fn from_python<T: serde::de::DeserializeOwned>(value: &Bound<'_, PyAny>) -> PyResult<T> {
    let text: String = value
        .py()
        .import("json")?
        .call_method1("dumps", (value,))?
        .extract()?;
    serde_json::from_str(&text).map_err(|e| message(e.to_string()))
}

/// Float64 samples from a numpy array (any contiguity) or any sequence of numbers.
fn floats(value: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(array) = value.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(array.as_array().to_vec());
    }
    value.extract::<Vec<f64>>()
}

/// A design: the checked design file and the numbers `dlw inspect` derives from it.
#[pyclass(module = "dlw")]
struct Design {
    design: CoreDesign,
    inspection: dlw_core::rules::Inspection,
    /// The file it was read from: an input no `save` may replace.
    path: Option<PathBuf>,
}

#[pymethods]
impl Design {
    /// Reads and checks a design file (TOML), as `dlw inspect` does.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Self> {
        let file = DesignFile::read(&path).map_err(value_error)?;
        let checked = dlw_core::rules::check_file(file).map_err(value_error)?;
        Ok(Self {
            inspection: dlw_core::rules::Inspection::of(&checked),
            design: checked.design,
            path: Some(path),
        })
    }

    /// The design's name.
    #[getter]
    fn name(&self) -> String {
        self.design.file.name.clone()
    }

    /// The derived numbers, as `dlw inspect --json` prints them: `y_bar_mm`, `y_s_mm`,
    /// `delta_y_mm`, `strain_per_deg`, the closing angle, the warnings.
    fn geometry<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inspection)
    }

    fn __repr__(&self) -> String {
        format!("Design({:?})", self.design.file.name)
    }
}

/// The file a design or recording argument names (a path, or a `Design` read from one); `None`
/// for a dict or a design made in memory. Such files are inputs that no `save` may replace.
fn input_path(value: &Bound<'_, PyAny>) -> Option<PathBuf> {
    if let Ok(d) = value.extract::<PyRef<'_, Design>>() {
        return d.path.clone();
    }
    if value.cast::<PyDict>().is_ok() {
        return None;
    }
    value.extract::<PathBuf>().ok()
}

/// A design argument: a `Design` or a path to a design file.
fn design_arg(value: &Bound<'_, PyAny>) -> PyResult<CoreDesign> {
    if let Ok(d) = value.extract::<PyRef<'_, Design>>() {
        return Ok(d.design.clone());
    }
    let path: PathBuf = value.extract()?;
    Ok(Design::from_file(path)?.design)
}

/// A recording as the dict `read_recording` returns.
fn recording_dict<'py>(py: Python<'py>, recording: &Recording) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let s = &recording.samples;
    d.set_item("time_s", PyArray1::from_slice(py, &s.time_s))?;
    d.set_item("stroke_mm", PyArray1::from_slice(py, &s.stroke_mm))?;
    d.set_item("angle_deg", PyArray1::from_slice(py, &s.angle_deg))?;
    for (i, v) in s.volts.iter().enumerate() {
        d.set_item(format!("v{}_V", i + 1), PyArray1::from_slice(py, v))?;
    }
    if !s.tracker_valid.is_empty() {
        let valid: Vec<bool> = s.tracker_valid.clone();
        d.set_item("tracker_valid", PyArray1::from_vec(py, valid))?;
    }
    d.set_item("rig", to_python(py, &recording.rig)?)?;
    Ok(d)
}

/// A recording argument: a path to a recording folder, or a dict as `read_recording` returns;
/// refused, as the commands refuse it, when a column was not measured throughout or the
/// tracker's clock is off the DAQ's ([`Recording::read_measured`]).
fn recording_arg(value: &Bound<'_, PyAny>) -> PyResult<Recording> {
    let Ok(d) = value.cast::<PyDict>() else {
        let path: PathBuf = value.extract()?;
        return Recording::read_measured(&path).map_err(value_error);
    };
    let column = |key: &str| -> PyResult<Option<Vec<f64>>> {
        d.get_item(key)?.map(|v| floats(&v)).transpose()
    };
    let need = |key: &str| -> PyResult<Vec<f64>> {
        column(key)?.ok_or_else(|| message(format!("the recording dict has no {key:?}")))
    };
    let rig: Rig = from_python(
        &d.get_item("rig")?
            .ok_or_else(|| message("the recording dict has no \"rig\""))?,
    )?;
    let mut volts = vec![need("v1_V")?];
    if let Some(v2) = column("v2_V")? {
        volts.push(v2);
    }
    let tracker_valid = match d.get_item("tracker_valid")? {
        Some(v) => v.extract::<Vec<bool>>()?,
        None => Vec::new(),
    };
    let time_s = need("time_s")?;
    let stroke_mm = need("stroke_mm")?;
    let angle_deg = need("angle_deg")?;
    let rows = time_s.len();
    let mut columns = vec![
        ("stroke_mm", stroke_mm.len()),
        ("angle_deg", angle_deg.len()),
    ];
    columns.extend(
        volts
            .iter()
            .enumerate()
            .map(|(i, v)| (if i == 0 { "v1_V" } else { "v2_V" }, v.len())),
    );
    if !tracker_valid.is_empty() {
        columns.push(("tracker_valid", tracker_valid.len()));
    }
    for (name, len) in columns {
        if len != rows {
            return Err(message(format!(
                "the recording dict's {name} has {len} samples and time_s {rows}: every column must be as long"
            )));
        }
    }
    let samples = Samples {
        time_s,
        stroke_mm,
        angle_deg,
        volts,
        tracker_valid,
    };
    // Every check `Recording::read` makes, with its messages: through a folder of its own.
    let dir = tempfile::tempdir().map_err(|e| message(e.to_string()))?;
    let path = dir.path().join("recording");
    Recording { rig, samples }
        .write(&path, false)
        .map_err(value_error)?;
    let recording = Recording::read(&path).map_err(value_error)?;
    // The analyses' refusals of a column not measured throughout, or a late tracker
    // (`Recording::check_measured`), named as the dict's: its rows are the data file's lines.
    recording
        .check_measured(Path::new("the recording dict"))
        .map_err(value_error)?;
    Ok(recording)
}

/// Reads a recording folder (`rig.toml` + `data.csv`): a dict of numpy arrays (`time_s`,
/// `stroke_mm`, `angle_deg`, `v1_V`, and `v2_V` where there is one) and the rig under `"rig"`.
#[pyfunction]
fn read_recording<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let recording = Recording::read(&path).map_err(value_error)?;
    recording_dict(py, &recording)
}

/// The runtime estimator: divider voltages in, the joint angle (°) out, sample by sample.
#[pyclass(module = "dlw")]
struct Estimator {
    config: EstimatorConfig,
    runtime: Box<Runtime>,
    flags: u32,
}

impl Estimator {
    fn new(config: EstimatorConfig) -> PyResult<Self> {
        config.validate().map_err(|e| message(e.to_string()))?;
        let runtime = Box::new(Runtime::new(&config).map_err(|e| message(e.to_string()))?);
        Ok(Self {
            config,
            runtime,
            flags: 0,
        })
    }

    fn two(&self) -> bool {
        self.config.second_sensor.is_some()
    }
}

#[pymethods]
impl Estimator {
    /// The estimator of a config file (`.toml` or `.json`), as `dlw estimate` reads it.
    #[staticmethod]
    fn from_config(path: PathBuf) -> PyResult<Self> {
        let config = dlw_core::replay::load_config(&path).map_err(value_error)?;
        Self::new(config)
    }

    /// The estimator of a config's TOML text.
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        let config: EstimatorConfig = toml::from_str(text)
            .map_err(|e| message(format!("the config: {}", e.to_string().trim_end())))?;
        Self::new(config)
    }

    /// Sensors the config reads: 1 or 2.
    #[getter]
    fn sensors(&self) -> usize {
        if self.two() {
            2
        } else {
            1
        }
    }

    /// The flags of the last `step` (the runtime crate's bits; 0: none).
    #[getter]
    fn flags(&self) -> u32 {
        self.flags
    }

    /// Angles (°) over voltage arrays, from a fresh estimator (this object's state is not
    /// touched): equal to `dlw estimate`'s `estimate_deg` column over the same recording. A
    /// one-sensor config on plane −y_s reads `v2` where it is given (the recording's `v2_V`),
    /// else `v1`.
    #[pyo3(signature = (v1, v2=None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        v1: &Bound<'py, PyAny>,
        v2: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v1 = floats(v1)?;
        let v2 = v2.map(floats).transpose()?;
        let two = self.two();
        let (first, second) = match (&v2, two) {
            (Some(v2), true) => {
                if v2.len() != v1.len() {
                    return Err(message(format!(
                        "v1 has {} samples and v2 {}: they must be as long",
                        v1.len(),
                        v2.len()
                    )));
                }
                (v1.as_slice(), Some(v2.as_slice()))
            }
            (None, true) => {
                return Err(message(
                    "the config has two sensors: pass v2 (the recording's v2_V)",
                ))
            }
            (Some(v2), false) if self.config.first_plane().column() == 2 => (v2.as_slice(), None),
            _ => (v1.as_slice(), None),
        };
        let config = self.config;
        let angles = py.detach(|| -> Result<Vec<f64>, String> {
            let mut runtime = Box::new(Runtime::new(&config).map_err(|e| e.to_string())?);
            Ok(match second {
                Some(second) => first
                    .iter()
                    .zip(second)
                    .map(|(a, b)| runtime.step2(*a, *b).angle_deg)
                    .collect(),
                None => first.iter().map(|v| runtime.step(*v).angle_deg).collect(),
            })
        });
        Ok(PyArray1::from_vec(py, angles.map_err(message)?))
    }

    /// One sample: the angle (°); `flags` then holds its flags.
    #[pyo3(signature = (v1, v2=None))]
    fn step(&mut self, v1: f64, v2: Option<f64>) -> PyResult<f64> {
        let e = match (self.two(), v2) {
            (true, Some(v2)) => self.runtime.step2(v1, v2),
            (true, None) => {
                return Err(message(
                    "the config has two sensors: pass v2 (the second sensor's voltage)",
                ))
            }
            (false, _) => self.runtime.step(v1),
        };
        self.flags = u32::from(e.flags.bits());
        Ok(e.angle_deg)
    }

    /// Back to the state of a new estimator.
    fn reset(&mut self) {
        self.runtime.reset();
        self.flags = 0;
    }

    fn __repr__(&self) -> String {
        format!("Estimator(sensors={})", self.sensors())
    }
}

/// A fitted sensor model: its config and the fitted numbers.
#[pyclass(module = "dlw")]
struct Fit {
    config_toml: String,
    summary: serde_json::Value,
    config: EstimatorConfig,
    /// The files the fit read (recording folders, the design): `save` never replaces one.
    inputs: Vec<PathBuf>,
}

#[pymethods]
impl Fit {
    /// The estimator config, as TOML (what `dlw fit -o config.toml` writes).
    fn config_toml(&self) -> String {
        self.config_toml.clone()
    }

    /// Writes the config; an existing file is replaced only with `force=True`, and a file the
    /// fit read (the recording's folder or anything in it, the design) never is, as
    /// `dlw fit -o` refuses it.
    #[pyo3(signature = (path, force=false))]
    fn save(&self, path: PathBuf, force: bool) -> PyResult<()> {
        dlw_core::output::claim(&path, &self.inputs, force).map_err(value_error)?;
        dlw_core::output::write_atomic(&path, self.config_toml.as_bytes()).map_err(value_error)
    }

    /// The fitted numbers, as `dlw fit --json` prints them.
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.summary)
    }

    /// The runtime estimator of this config.
    fn estimator(&self) -> PyResult<Estimator> {
        Estimator::new(self.config)
    }
}

fn model_kind(model: &str) -> PyResult<ModelKind> {
    match model {
        "linear" => Ok(ModelKind::Linear),
        "pi" => Ok(ModelKind::Pi),
        "continuous-pi" => Ok(ModelKind::ContinuousPi),
        other => Err(message(format!(
            "unknown model {other:?} (expected linear, pi or continuous-pi)"
        ))),
    }
}

/// Fits a sensor model to a recording (a path, or a dict from `read_recording`), as `dlw fit`.
#[pyfunction]
#[pyo3(signature = (recording, design, model="pi", order=10, prefilter="ma:100", sensor=None, compare=false, validate=None))]
#[allow(clippy::too_many_arguments)]
fn fit(
    py: Python<'_>,
    recording: &Bound<'_, PyAny>,
    design: &Bound<'_, PyAny>,
    model: &str,
    order: usize,
    prefilter: &str,
    sensor: Option<&str>,
    compare: bool,
    validate: Option<&Bound<'_, PyAny>>,
) -> PyResult<Fit> {
    let inputs: Vec<PathBuf> = [Some(recording), Some(design), validate]
        .into_iter()
        .flatten()
        .filter_map(input_path)
        .collect();
    let recording = recording_arg(recording)?;
    let design = design_arg(design)?;
    let validate = validate.map(recording_arg).transpose()?;
    let model = model_kind(model)?;
    let prefilter: Prefilter = prefilter.parse().map_err(|e: String| message(e))?;
    let order = PlayOrder::new(order).map_err(|e| message(e.to_string()))?;
    let sensors: Option<Sensors> = sensor
        .map(|s| {
            s.parse()
                .map_err(|e: dlw_core::sensor::UnknownSensor| message(e.to_string()))
        })
        .transpose()?;
    let name = design.file.name.clone();
    let result = py.detach(|| {
        let mut request = FitRequest::new(&design.joint, &recording);
        request.design_name = name;
        request.model = model;
        request.order = order;
        request.prefilter = prefilter;
        request.sensors = sensors;
        request.compare = compare;
        request.validate = validate.as_ref();
        dlw_core::fit::fit(&request, &|_| {})
    });
    let result = result.map_err(value_error)?;
    let config_toml = result
        .config_text(dlw_core::replay::ConfigFormat::Toml)
        .map_err(value_error)?;
    let config: EstimatorConfig =
        toml::from_str(&config_toml).map_err(|e| message(e.to_string()))?;
    let summary = result.to_json().map_err(|e| message(e.to_string()))?;
    Ok(Fit {
        config_toml,
        summary,
        config,
        inputs,
    })
}

/// Simulates a bench run of a design, as `dlw simulate`: the same dict as `read_recording`.
#[pyfunction]
#[pyo3(signature = (design, protocol="random", duration_s=60.0, seed=1, scenario=None))]
fn simulate<'py>(
    py: Python<'py>,
    design: &Bound<'py, PyAny>,
    protocol: &str,
    duration_s: f64,
    seed: u64,
    scenario: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let design = design_arg(design)?;
    let mut sc = match &scenario {
        Some(path) => Scenario::load(path).map_err(value_error)?,
        None => Scenario::default(),
    };
    let kind: ProtocolKind = serde_json::from_value(serde_json::Value::String(protocol.into()))
        .map_err(|_| {
            message(format!(
                "unknown protocol {protocol:?} (expected characterization, rate-dependence, relaxation, random or custom)"
            ))
        })?;
    sc.protocol = Some(kind);
    sc.duration_s = Some(duration_s);
    sc.seed = seed;
    let recording = py
        .detach(|| -> Result<Recording, String> {
            let plan = sim::plan(&design, sc, None).map_err(|e| error_text(&e))?;
            let run = plan.run().map_err(|e| error_text(&e))?;
            Ok(Recording {
                rig: plan.rig(),
                samples: run.samples,
            })
        })
        .map_err(message)?;
    recording_dict(py, &recording)
}

/// Finds where a recording departs from the base model, as `dlw discover --json`: the dict it
/// prints (without the paths of files), plus `"scenario_toml"`, the scenario it would write.
#[pyfunction]
#[pyo3(signature = (recording, design, holdout=None, scenario=None))]
fn discover<'py>(
    py: Python<'py>,
    recording: &Bound<'py, PyAny>,
    design: &Bound<'py, PyAny>,
    holdout: Option<&Bound<'py, PyAny>>,
    scenario: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let recording = recording_arg(recording)?;
    let design = design_arg(design)?;
    let holdout = holdout.map(recording_arg).transpose()?;
    let base = match &scenario {
        Some(path) => Scenario::load(path).map_err(value_error)?,
        None => Scenario::default(),
    };
    let (result, text) = py
        .detach(|| -> Result<_, String> {
            let resolved = base
                .clone()
                .resolve(&design)
                .map_err(|e| format!("resolving the base scenario: {}", error_text(&e)))?;
            let known = discovery::scenario::known(&resolved);
            let outcome =
                discovery::discover(&recording, holdout.as_ref(), &design.joint, &known, &|_| {})
                    .map_err(|e| format!("discovering: {}", error_text(&e)))?;
            let text = discovery::scenario_text(&base, &recording, &design, &outcome)?;
            Ok((discovery::DiscoverResult::new(outcome), text))
        })
        .map_err(message)?;
    // The result's JSON, the one `dlw discover --json` prints, without the files' paths.
    let out = to_python(py, &result)?;
    out.set_item("scenario_toml", text)?;
    Ok(out)
}

/// Characterizes a recording, as `dlw characterize --json`: the dict it prints (its `report` is
/// `None`: no page is written). `kind` is `"loops"`, `"rate"`, `"relaxation"` or
/// `"estimation"` (`None`: the one the recording's protocol names); `configs` are estimator
/// config files for `"estimation"`.
#[pyfunction]
#[pyo3(signature = (recording, design, kind=None, configs=None, prefilter="ma:100", order=10, min_hold_s=5.0, paper_processing=false))]
#[allow(clippy::too_many_arguments)]
fn characterize<'py>(
    py: Python<'py>,
    recording: &Bound<'py, PyAny>,
    design: &Bound<'py, PyAny>,
    kind: Option<&str>,
    configs: Option<Vec<PathBuf>>,
    prefilter: &str,
    order: usize,
    min_hold_s: f64,
    paper_processing: bool,
) -> PyResult<Bound<'py, PyAny>> {
    use dlw_core::characterize::{AnalysisKind, CharacterizeRequest, Options};
    let recording_name = recording
        .extract::<PathBuf>()
        .map_or_else(|_| "recording".to_owned(), |p| p.display().to_string());
    let recording = recording_arg(recording)?;
    let design = design_arg(design)?;
    let kind = kind
        .map(|k| {
            AnalysisKind::from_name(k).ok_or_else(|| {
                message(format!(
                    "kind {k:?} is not loops, rate, relaxation or estimation"
                ))
            })
        })
        .transpose()?;
    let options = Options {
        prefilter: prefilter.parse().map_err(|e: String| message(e))?,
        order: PlayOrder::new(order).map_err(value_error)?,
        min_hold_s,
        paper_processing,
        decimation: None,
        models: &dlw_core::fit::ModelKind::ALL,
    };
    let result = py
        .detach(|| {
            dlw_core::characterize::characterize(&CharacterizeRequest {
                recording: &recording,
                recording_name,
                joint: &design.joint,
                design_name: design.file.name.clone(),
                design_source: design.file.name.clone(),
                kind,
                configs: configs.unwrap_or_default(),
                options,
            })
        })
        .map_err(value_error)?;
    to_python(py, &result)
}

/// The extension module `dlw._dlw`; `dlw/__init__.py` re-exports it.
#[pymodule]
fn _dlw(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Design>()?;
    m.add_class::<Estimator>()?;
    m.add_class::<Fit>()?;
    m.add_class::<robot::RobotEstimator>()?;
    m.add_class::<robot_file::Robot>()?;
    m.add_function(wrap_pyfunction!(robot::tip, m)?)?;
    m.add_function(wrap_pyfunction!(robot::backbone, m)?)?;
    m.add_function(wrap_pyfunction!(read_recording, m)?)?;
    m.add_function(wrap_pyfunction!(characterize, m)?)?;
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(discover, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
