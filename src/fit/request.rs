//! `dlw fit` as a library call: a [`FitRequest`] (joint, recording, model, order, prefilter,
//! sensors, compare, validate), [`fit`] that runs it, and a [`FitResult`] whose JSON is what
//! `dlw fit --json` prints ([`Analysis`]) and that renders the estimator config.
//!
//! The command and the Python binding both call [`fit`]; the command only reads the files,
//! writes the outputs and fills in their paths ([`FitResult::config`], [`FitResult::report`]).

use std::path::PathBuf;
use std::time::Instant;

use dlw_estimator::{EstimatorConfig, SensorPlane};
use dlw_geometry::{Joint, NotchStyle};
use serde::Serialize;

use super::PlayOrder;
use super::{
    estimator_config, fit_sensor_models, min_max, model_name, report, Characteristic, FitError,
    FitOptions, ModelKind, ModelSummary, PlayFit, Prefilter, SensorFit, Validation,
};
use crate::analysis::{Analysis, Placement};
use crate::recording::Recording;
use crate::replay::{config_text, replay, ConfigFileError, ConfigFormat};
use crate::report::Page;
use crate::sensor::{Sensor, Sensors};

/// What to fit: everything `dlw fit` takes besides its output paths.
#[derive(Debug, Clone)]
pub struct FitRequest<'a> {
    /// The recorded joint (the design's joint).
    pub joint: &'a Joint,
    /// The recording fitted (a characterization run, say).
    pub recording: &'a Recording,
    /// The recording's name, for the config's note and the report's title.
    pub recording_name: String,
    /// The design's name, for the config's note.
    pub design_name: String,
    /// The model the config gets.
    pub model: ModelKind,
    /// Play operators `N` of the PI models.
    pub order: PlayOrder,
    /// Prefilter on strain and resistance, and the config's input filter.
    pub prefilter: Prefilter,
    /// The sensors fitted; `None`: both for a BSN joint recorded with two columns, else sensor 1.
    pub sensors: Option<Sensors>,
    /// Fit every model for the comparison table, not only `model`.
    pub compare: bool,
    /// A second recording of the same sensor: each fitted model is run over it through the
    /// runtime estimator.
    pub validate: Option<&'a Recording>,
}

impl<'a> FitRequest<'a> {
    /// The command's defaults: PI with N = 10, a 100-sample moving average, the default
    /// sensors, no comparison, no validation.
    pub fn new(joint: &'a Joint, recording: &'a Recording) -> Self {
        FitRequest {
            joint,
            recording,
            recording_name: String::from("recording"),
            design_name: String::from("design"),
            model: ModelKind::Pi,
            order: PlayOrder::DEFAULT,
            prefilter: Prefilter::MovingAverage(100),
            sensors: None,
            compare: false,
            validate: None,
        }
    }

    /// The sensors fitted, `sensors` or the default.
    pub fn resolved_sensors(&self) -> Sensors {
        let bsn = self.joint.style() == NotchStyle::Bsn;
        let columns = self.recording.samples.volts.len();
        self.sensors.unwrap_or(if bsn && columns >= 2 {
            Sensors::Both
        } else {
            Sensors::Single(Sensor::One)
        })
    }

    /// The models fitted: `model` alone, or every model with `compare`.
    pub fn models(&self) -> Vec<ModelKind> {
        if self.compare {
            ModelKind::ALL.to_vec()
        } else {
            vec![self.model]
        }
    }
}

/// The outcome of [`fit`]: every fitted number (its JSON is `dlw fit --json`), the fits
/// themselves and the estimator config.
#[derive(Debug, Clone, Serialize)]
pub struct FitResult {
    /// The model the config holds.
    pub model: ModelKind,
    /// Where the config was written (set by the caller that writes it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub config: Option<PathBuf>,
    /// Where the HTML report was written (set by the caller that writes it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub report: Option<PathBuf>,
    /// `none` or `ma:N`.
    pub prefilter: String,
    /// Every `k`-th sample was fitted.
    pub decimation: usize,
    /// Samples fitted per sensor.
    pub samples_fitted: usize,
    /// `sensor1`, `sensor2` or `both`.
    pub sensor: Sensors,
    /// One entry per sensor fitted.
    pub sensors: Vec<SensorReport>,
    /// Angle RMSE of each fitted model on the validation recording.
    pub validation: Vec<Validation>,
    /// Seconds spent.
    pub timings_s: Timings,
    /// The fits, for reports and further analysis.
    #[serde(skip)]
    pub fits: Vec<SensorFit>,
    /// The runtime config of `model`.
    #[serde(skip)]
    pub estimator: EstimatorConfig,
    #[serde(skip)]
    note: String,
    #[serde(skip)]
    title: String,
}

/// One sensor's fitted numbers.
#[derive(Debug, Clone, Serialize)]
pub struct SensorReport {
    /// `v1_V` or `v2_V`.
    pub column: String,
    /// The sensor's plane.
    pub plane: SensorPlane,
    /// Linear model: gauge factor.
    pub gauge_factor: f64,
    /// Linear model: unstrained resistance (Ω).
    pub r0_ohm: f64,
    /// Linear model: r².
    pub r2: f64,
    /// Linear model: RMS residual (Ω).
    pub rmse_ohm: f64,
    /// The characteristic points, when the strain cycles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub characteristic: Option<Characteristic>,
    /// The generalized PI, when fitted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pi: Option<PlayReport>,
    /// The continuous PI, when fitted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub continuous_pi: Option<PlayReport>,
    /// One line per model fitted (or that failed).
    pub models: Vec<ModelSummary>,
}

/// A play model's fitted numbers.
#[derive(Debug, Clone, Serialize)]
pub struct PlayReport {
    /// Weights `P_i`.
    pub weights: Vec<f64>,
    /// Radii `ρ_i`.
    pub radii: Vec<f64>,
    /// Loading `a₁…a₄` then unloading `a₅…a₈`.
    pub a: [f64; 8],
    /// `R_c` (Ω).
    pub center_ohm: f64,
    /// `ε_c`.
    pub center_strain: f64,
    /// The plays' initial state.
    pub initial_state: f64,
    /// The generalized PI's resistance clamp (Ω).
    pub clamp_ohm: Option<(f64, f64)>,
    /// The continuous PI's strain clamp.
    pub clamp_strain: Option<(f64, f64)>,
    /// RMS residual (Ω).
    pub rmse_ohm: f64,
    /// Each start of the optimizer.
    pub restarts: Vec<Restart>,
    /// Weight solves spent (variable projection).
    pub evaluations: usize,
    /// When the model is the line it contains: the best hysteretic fit's RMSE, set aside (Ω).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub set_aside_rmse_ohm: Option<f64>,
}

/// One start of a play fit.
#[derive(Debug, Clone, Serialize)]
pub struct Restart {
    /// `"k = 0.5"` (Eq. 15's tanh with that slope multiplier) or `"linear"`.
    pub start: String,
    /// RMS residual it reached (Ω).
    pub rmse_ohm: f64,
    /// Whether the optimizer converged from it.
    pub converged: bool,
}

/// Seconds spent in each step.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct Timings {
    /// Reading the files (set by the caller that reads them).
    pub read: f64,
    /// Observations (strain, resistance, prefilter).
    pub observe: f64,
    /// The linear fit.
    pub linear: f64,
    /// The generalized PI fit.
    pub pi: f64,
    /// The continuous PI fit.
    pub continuous_pi: f64,
    /// Validation.
    pub validate: f64,
    /// Everything.
    pub total: f64,
}

/// Runs `request`: fits its model (every model with `compare`) to each sensor asked for,
/// builds the config and validates on the second recording.
///
/// # Errors
/// [`FitError`]: a sensor the joint does not carry, a recording that
/// cannot identify the model asked for. A model other than the one asked for that cannot be
/// fitted is reported in the summaries, never an error.
pub fn fit(request: &FitRequest<'_>, progress: &dyn Fn(&str)) -> Result<FitResult, FitError> {
    let start = Instant::now();
    let sensors = request.resolved_sensors();
    if sensors != Sensors::Single(Sensor::One) && request.joint.style() != NotchStyle::Bsn {
        return Err(FitError::NoSuchSensor { sensors });
    }
    let options = FitOptions {
        model: request.model,
        order: request.order,
        prefilter: request.prefilter,
        decimation: None,
    };
    let models = request.models();
    let mut fits: Vec<SensorFit> = Vec::new();
    for sensor in sensors.members() {
        progress(&format!("{sensor}"));
        fits.push(fit_sensor_models(
            request.recording,
            request.joint,
            sensor.plane(),
            &options,
            &models,
            progress,
        )?);
    }
    let estimator = estimator_config(request.joint, &fits, request.model, request.prefilter)?;
    let clock = Instant::now();
    let validation = match request.validate {
        None => Vec::new(),
        Some(rec) => {
            progress("validating");
            models
                .iter()
                .map(|&model| validate(request, &fits, model, rec))
                .collect()
        }
    };
    let t_validate = clock.elapsed().as_secs_f64();
    let sum = |i: usize| fits.iter().map(|f| f.seconds[i]).sum::<f64>();
    let prefilter = request.prefilter.to_string();
    let note = format!(
        "Fitted by dlw fit ({} model, prefilter {}) from {} for {}.\nThe input filter is the fit's prefilter; the clamp range is the range the recording saw.",
        model_name(request.model),
        prefilter,
        request.recording_name,
        request.design_name,
    );
    Ok(FitResult {
        model: request.model,
        config: None,
        report: None,
        prefilter,
        decimation: fits[0].observations.decimation,
        samples_fitted: fits[0].observations.len(),
        sensor: sensors,
        sensors: fits.iter().map(sensor_report).collect(),
        validation,
        timings_s: Timings {
            read: 0.0,
            observe: sum(0),
            linear: sum(1),
            pi: sum(2),
            continuous_pi: sum(3),
            validate: t_validate,
            total: start.elapsed().as_secs_f64(),
        },
        fits,
        estimator,
        note,
        title: request.recording_name.clone(),
    })
}

fn validate(
    request: &FitRequest<'_>,
    fits: &[SensorFit],
    model: ModelKind,
    rec: &Recording,
) -> Validation {
    let result = estimator_config(request.joint, fits, model, request.prefilter)
        .map_err(|e| e.to_string())
        .and_then(|c| replay(&c, rec).map_err(|e| e.to_string()));
    match result {
        Ok(r) => Validation {
            model,
            rmse_deg: Some(r.metrics.rmse_deg),
            error: None,
        },
        Err(e) => Validation {
            model,
            rmse_deg: None,
            error: Some(e),
        },
    }
}

impl FitResult {
    /// The estimator config as the file `format` names, with a note on how it was fitted.
    ///
    /// # Errors
    /// [`ConfigFileError`] when it cannot be serialized.
    pub fn config_text(&self, format: ConfigFormat) -> Result<String, ConfigFileError> {
        config_text(&self.estimator, format, &self.note)
    }

    /// The HTML report on a page of its own.
    pub fn report_page(&self) -> Page {
        report::report_page(&self.title, &self.fits, &self.validation)
    }
}

impl Analysis for FitResult {
    fn summary(&self) -> String {
        let mut out = String::new();
        let mut line = |s: String| {
            out.push_str(&s);
            out.push('\n');
        };
        if let Some(config) = &self.config {
            line(format!(
                "config {} ({} model)",
                config.display(),
                model_name(self.model)
            ));
        }
        for s in &self.sensors {
            line(format!("sensor {}", s.column));
            line(format!(
                "  linear  GF = {:.4}, R0 = {:.1} Ω, r² = {:.4}",
                s.gauge_factor, s.r0_ohm, s.r2
            ));
            for m in &s.models {
                line(match &m.skipped {
                    Some(why) => format!("  {:<14} not fitted: {why}", model_name(m.model)),
                    None => format!(
                        "  {:<14} RMSE {:>9.1} Ω   BIC {:>12.1}   ({} parameters){}",
                        model_name(m.model),
                        m.rmse_ohm,
                        m.bic,
                        m.parameters,
                        m.note
                            .as_ref()
                            .map_or(String::new(), |note| format!("\n    {note}"))
                    ),
                });
            }
        }
        for v in &self.validation {
            match (v.rmse_deg, &v.error) {
                (Some(rmse), _) => line(format!(
                    "validation {:<14} angle RMSE {rmse:.3}°",
                    model_name(v.model)
                )),
                (None, Some(e)) => line(format!("validation {:<14} {e}", model_name(v.model))),
                _ => {}
            }
        }
        if let Some(dir) = &self.report {
            line(format!("report {}", dir.join("report.html").display()));
        }
        line(format!(
            "fitted {} samples (prefilter {}, every {}th) in {:.2} s",
            self.samples_fitted, self.prefilter, self.decimation, self.timings_s.total
        ));
        out
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        report::add_sections(page, &self.fits, &self.validation, at);
    }
}

fn sensor_report(fit: &SensorFit) -> SensorReport {
    let play = |r: &Result<PlayFit, String>, generalized: bool| {
        r.as_ref().ok().map(|p| {
            let (l, u) = (p.values.loading, p.values.unloading);
            let obs = &fit.observations;
            PlayReport {
                weights: p.values.weights.clone(),
                radii: p.model.radii.clone(),
                a: [l[0], l[1], l[2], l[3], u[0], u[1], u[2], u[3]],
                center_ohm: p.model.center_ohm,
                center_strain: p.model.center_strain,
                initial_state: p.initial_state,
                clamp_ohm: generalized.then_some(obs.ohm_range),
                clamp_strain: (!generalized).then(|| min_max(&obs.strain)),
                rmse_ohm: p.rmse_ohm,
                restarts: p
                    .restarts
                    .iter()
                    .map(|r| Restart {
                        start: r.start.to_string(),
                        rmse_ohm: r.rmse_ohm,
                        converged: r.converged,
                    })
                    .collect(),
                evaluations: p.evaluations,
                set_aside_rmse_ohm: p.set_aside_rmse_ohm,
            }
        })
    };
    SensorReport {
        column: format!("v{}_V", fit.plane.column()),
        plane: fit.plane,
        gauge_factor: fit.linear.gauge_factor,
        r0_ohm: fit.linear.r0_ohm,
        r2: fit.linear.r2,
        rmse_ohm: fit.linear.rmse_ohm,
        characteristic: fit.characteristic,
        pi: play(&fit.pi, true),
        continuous_pi: play(&fit.continuous_pi, false),
        models: fit.summaries.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::Design;
    use crate::sim::{plan, ProtocolKind, Scenario};

    fn joint_a_characterization() -> (Design, Recording) {
        let design = Design::from_toml(include_str!("../../designs/joint-a.toml")).unwrap();
        let scenario = Scenario {
            protocol: Some(ProtocolKind::Characterization),
            duration_s: Some(200.0),
            seed: 3,
            ..Scenario::default()
        };
        let p = plan(&design, scenario, None).unwrap();
        let recording = Recording {
            rig: p.rig(),
            samples: p.run().unwrap().samples,
        };
        (design, recording)
    }

    #[test]
    fn a_linear_request_fits_the_line_alone_and_its_json_is_the_analysis_json() {
        let (design, recording) = joint_a_characterization();
        let mut request = FitRequest::new(&design.joint, &recording);
        request.model = ModelKind::Linear;
        let result = fit(&request, &|_| {}).unwrap();
        assert_eq!(result.sensor, Sensors::Single(Sensor::One));
        assert_eq!(result.sensors.len(), 1);
        let models: Vec<ModelKind> = result.sensors[0].models.iter().map(|m| m.model).collect();
        assert_eq!(models, [ModelKind::Linear]);
        let json = result.to_json().unwrap();
        assert_eq!(json["model"], "linear");
        assert_eq!(json["sensor"], "sensor1");
        assert!(
            json.get("config").is_none(),
            "no config path until one is written"
        );
        assert!(json["sensors"][0].get("pi").is_none());
        let gf = json["sensors"][0]["gauge_factor"].as_f64().unwrap();
        assert!((gf / 15.3 - 1.0).abs() < 0.01, "GF {gf}");
        let text = result.config_text(ConfigFormat::Toml).unwrap();
        assert!(text.contains("[sensor.model.linear]"), "{text}");
        assert!(result.summary().contains("linear"));
        let mut page = Page::new("t");
        result.add_to_page(&mut page, Placement::ALONE);
        assert!(!page.files().unwrap().is_empty());
    }

    #[test]
    fn a_sensor_the_joint_lacks_is_a_named_error() {
        // An order out of range cannot be asked for: `PlayOrder::new` refuses it (its test).
        let (design, recording) = joint_a_characterization();
        let mut request = FitRequest::new(&design.joint, &recording);
        request.sensors = Some(Sensors::Both);
        let e = fit(&request, &|_| {}).unwrap_err().to_string();
        assert!(e.contains("BSN") && e.contains("UAN"), "{e}");
    }
}
