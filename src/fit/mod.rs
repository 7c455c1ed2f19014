//! Sensor identification: fitting the runtime crate's models to a bench recording
//! (Section IV-A), as a library; `dlw fit` is a thin command over it.
//!
//! ```text
//! recording ─observe─▶ strain, resistance ─fit_linear──▶ GF, R₀          (Eqs. 5-6)
//!   (Eq. 3, Eq. 4,        (prefiltered,   ─characteristic─▶ R_c, m_c, ε_c, R_peak, ε_peak
//!    prefilter)            decimated)     ─fit_plays─────▶ PI, continuous PI (Eqs. 8-11)
//!                                                          ─▶ EstimatorConfig ─▶ dlw estimate
//! ```
//!
//! Every model the runtime crate can run is fitted for every sensor asked for, so a user sees
//! which to use ([`SensorFit`] holds them all, with an information criterion); the config holds
//! the one asked for. `docs/fit.md` gives the procedure and where it departs from the paper.
//!
//! # Errors
//! [`FitError`]: a recording that cannot identify a model (no motion, too few cycles, a flat
//! resistance, a voltage at a rail) or a fit that did not converge. No NaN leaves a fit:
//! every fitted number is checked before a config is built.

// `!(x > 0.0)` is how a fit refuses NaN along with the out-of-range values, on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod characteristic;
mod nnls;
mod order;
mod pi;
mod plays;
pub(crate) mod report;
mod request;
pub mod robot;
pub mod robot_config;
pub mod tip_angles;

use std::time::Instant;

use dlw_estimator::{
    Coeffs, ContinuousPiConfig, EstimatorConfig, EstimatorError, JointConfig, LinearModel,
    ModelConfig, PiConfig, SensorConfig, SensorPlane,
};
use dlw_geometry::{Divider, Joint};
use serde::Serialize;

/// The characteristic points of a loop (Table III).
pub use characteristic::{characteristic, Characteristic};
/// Non-negative least squares on the normal equations.
pub use nnls::nnls;
/// The play count of a PI model, checked once.
pub use order::PlayOrder;
/// PI fits by variable projection.
pub use pi::{
    fit_plays, fit_plays_directed, fit_plays_on, PlayFit, Shape, Start, COARSE_SAMPLES,
    GRID_STARTS, LINEAR_START_REACH, RADIUS_SHARES, REFINEMENTS, SLOPE_RESTARTS,
};
/// The play models in the runtime crate's form.
pub use plays::{
    PlayKind, PlayModel, Unpacked, BRANCH_PARAMS, CONTINUOUS_WEIGHT_FLOOR, PARTIAL_SUM_MARGIN,
};
/// The fit report page.
pub use report::{report_page, Validation};
/// `dlw fit` as a library call.
pub use request::{fit, FitRequest, FitResult, PlayReport, Restart, SensorReport, Timings};

use crate::recording::Recording;
use crate::sensor::Sensor;
use crate::signal::{
    cycles, fit_linear, observe, phases, Cycle, LinearFit, Observations, Prefilter, SignalError,
    TURN_THRESHOLD,
};

/// Fewest cycles the PI procedure needs: the first cycle's loading and the last cycle's
/// unloading place `ε_c`, and a second cycle shows the loop repeating.
pub const MIN_PI_CYCLES: usize = 2;

/// Why a fit could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// The recording shows the sensor nothing to fit, or the line cannot be fitted.
    #[error(transparent)]
    Signal(#[from] SignalError),
    /// The strain never varies over the samples fitted.
    #[error("the strain does not vary over the {samples} samples fitted (the joint never moves there): there is no slope to fit; record motion")]
    FlatStrain {
        /// Samples looked at.
        samples: usize,
    },
    /// The resistance does not rise with strain.
    #[error("the resistance does not increase with strain: slope {slope_ohm_per_strain:.4e} Ω per unit strain, r² = {r2:.3} (needs a positive slope and r² ≥ {min_r2})")]
    NotIncreasing {
        /// Fitted slope (Ω per unit strain).
        slope_ohm_per_strain: f64,
        /// r² of the line.
        r2: f64,
        /// The least r² accepted.
        min_r2: f64,
    },
    /// Too few loading/unloading cycles.
    #[error("the {model} procedure needs at least {min} loading/unloading cycles; the strain shows {found} (a cycle rises and falls back by at least a tenth of the strain's span)")]
    TooFewCycles {
        /// Cycles found.
        found: usize,
        /// Cycles needed.
        min: usize,
        /// The model asked for.
        model: &'static str,
    },
    /// An optimizer run ended without converging.
    #[error("the {model} fit did not converge ({reason}); no config was written")]
    NotConverged {
        /// The model.
        model: &'static str,
        /// The optimizer's last termination.
        reason: String,
    },
    /// A play order outside what the runtime runs.
    #[error("order {order} must lie between {min} and {max} play operators")]
    Order {
        /// The order asked for.
        order: usize,
        /// The least accepted.
        min: usize,
        /// The most accepted.
        max: usize,
    },
    /// A sensor the joint does not carry.
    #[error("{sensors} needs a BSN joint (two sensors); the design is UAN (one sensor)")]
    NoSuchSensor {
        /// The sensors asked for.
        sensors: crate::sensor::Sensors,
    },
    /// The runtime crate refused a fitted model.
    #[error("the fitted model is not one the runtime can run: {0}")]
    Model(EstimatorError),
}

/// Which model the config gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum ModelKind {
    /// The linear gauge-factor model (Eqs. 5-6).
    Linear,
    /// The paper's generalized PI (Eqs. 8-14).
    Pi,
    /// The continuous (envelope) PI.
    ContinuousPi,
}

impl ModelKind {
    /// Every model, in the order reports list them.
    pub const ALL: [ModelKind; 3] = [ModelKind::Linear, ModelKind::Pi, ModelKind::ContinuousPi];
}

/// Everything `fit_recording` needs besides the recording.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// The model for the config.
    pub model: ModelKind,
    /// Plays `N` of the PI models.
    pub order: PlayOrder,
    /// Prefilter on strain and resistance (and the config's input filter).
    pub prefilter: Prefilter,
    /// Keep every `k`-th sample after the prefilter (`None`: the prefilter's own choice).
    pub decimation: Option<usize>,
}

/// The fit of one model, in a form for reports and `--json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelSummary {
    /// `linear`, `pi`, `continuous-pi`.
    pub model: ModelKind,
    /// RMS of the resistance residual (Ω), on the fitted samples.
    pub rmse_ohm: f64,
    /// Free parameters counted by the criterion.
    pub parameters: usize,
    /// Bayesian information criterion `n·ln(RSS/n) + k·ln n` on the fitted samples; lower is
    /// better. The samples are correlated, so use it to rank models, not as a test.
    pub bic: f64,
    /// Why the model was not fitted, when it was not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub skipped: Option<String>,
    /// What the fit found worth saying: a PI model that is the line it contains.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// One sensor's fits.
#[derive(Debug, Clone)]
pub struct SensorFit {
    /// The sensor's plane.
    pub plane: SensorPlane,
    /// Its observations (after prefilter and decimation).
    pub observations: Observations,
    /// Cycles of its strain.
    pub cycles: Vec<Cycle>,
    /// The linear model.
    pub linear: LinearFit,
    /// The characteristic points, when there are cycles.
    pub characteristic: Option<Characteristic>,
    /// The generalized PI, or why not.
    pub pi: Result<PlayFit, String>,
    /// The continuous PI, or why not.
    pub continuous_pi: Result<PlayFit, String>,
    /// The runtime config of each model that was fitted.
    pub configs: Vec<(ModelKind, SensorConfig)>,
    /// Per-model summaries.
    pub summaries: Vec<ModelSummary>,
    /// Seconds spent: `[observe, linear, pi, continuous_pi]`.
    pub seconds: [f64; 4],
}

impl SensorFit {
    /// The resistance-strain loops of this fit, as `dlw fit`'s report draws them
    /// (the paper's Fig. 4(d-f)): for any report that shows a fit.
    pub fn loop_chart(&self, title: String) -> crate::report::Chart {
        report::loop_chart(self, title)
    }

    /// The runtime sensor config of `model`, if it was fitted.
    pub fn config(&self, model: ModelKind) -> Option<&SensorConfig> {
        self.configs
            .iter()
            .find(|(m, _)| *m == model)
            .map(|(_, c)| c)
    }
}

/// Fits every model to the sensor on `plane` of `recording`.
///
/// # Errors
/// [`FitError`] when the observations or the linear fit fail, or when `options.model` is a PI
/// model that could not be fitted. Other models that fail are recorded in the summaries.
pub fn fit_sensor(
    recording: &Recording,
    joint: &Joint,
    plane: SensorPlane,
    options: &FitOptions,
    progress: &dyn Fn(&str),
) -> Result<SensorFit, FitError> {
    fit_sensor_models(recording, joint, plane, options, &ModelKind::ALL, progress)
}

/// Fits the linear model and the play models among `models` to the sensor on `plane` of
/// `recording` (the linear model is always fitted: every play fit starts from it). Models not
/// asked for have no summary and no config.
///
/// # Errors
/// As [`fit_sensor`].
pub fn fit_sensor_models(
    recording: &Recording,
    joint: &Joint,
    plane: SensorPlane,
    options: &FitOptions,
    models: &[ModelKind],
    progress: &dyn Fn(&str),
) -> Result<SensorFit, FitError> {
    let clock = Instant::now();
    let obs = observe(
        recording,
        joint,
        plane,
        options.prefilter,
        options.decimation,
    )?;
    let t_observe = clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let linear = fit_linear(&obs.strain, &obs.ohm)?;
    let t_linear = clock.elapsed().as_secs_f64();
    let (lo, hi) = min_max(&obs.strain);
    let cycles = cycles(&phases(&obs.strain, TURN_THRESHOLD * (hi - lo)));
    let rig = &recording.rig;
    let divider = rig
        .divider(Sensor::on_plane(plane))
        .ok_or(SignalError::NoColumn {
            column: plane.column() as usize,
            columns: rig.divider_ohm.len(),
        })?;
    let enough = cycles.len() >= MIN_PI_CYCLES;
    let characteristic = if enough {
        Some(characteristic(&obs.strain, &obs.ohm, &cycles)?)
    } else {
        None
    };
    let fit_pi = |kind: PlayKind| -> (Option<Result<PlayFit, FitError>>, f64) {
        if !models.contains(&kind_model(kind)) {
            return (None, 0.0);
        }
        let clock = Instant::now();
        let result = match &characteristic {
            None => Err(FitError::TooFewCycles {
                found: cycles.len(),
                min: MIN_PI_CYCLES,
                model: kind_name(kind),
            }),
            Some(points) => {
                progress(&format!(
                    "fitting {} (N = {})",
                    kind_name(kind),
                    options.order
                ));
                fit_plays_directed(
                    kind,
                    options.order.get(),
                    &obs.strain,
                    Some(&obs.falling),
                    &obs.ohm,
                    points,
                    2,
                )
            }
        };
        (Some(result), clock.elapsed().as_secs_f64())
    };
    let (pi, t_pi) = fit_pi(PlayKind::Generalized);
    let (cpi, t_cpi) = fit_pi(PlayKind::Continuous);
    let noise = resistance_noise(&obs.ohm);
    let mut configs = vec![(
        ModelKind::Linear,
        SensorConfig::new(
            divider,
            ModelConfig::Linear(
                LinearModel::new(linear.gauge_factor, linear.r0_ohm).map_err(FitError::Model)?,
            ),
        )
        .on_plane(plane),
    )];
    let n = obs.len();
    let mut summaries = vec![summary(ModelKind::Linear, linear.rmse_ohm, 2, n, None)];
    let mut results = Vec::new();
    for (kind, model, result) in [
        (PlayKind::Generalized, ModelKind::Pi, pi),
        (PlayKind::Continuous, ModelKind::ContinuousPi, cpi),
    ] {
        let play = Play {
            kind,
            model,
            plane,
            divider,
            noise,
        };
        results.push(play.record(result, &obs, options, &mut configs, &mut summaries)?);
    }
    let continuous_pi = results.pop().unwrap_or_else(|| Err("not fitted".into()));
    let pi = results.pop().unwrap_or_else(|| Err("not fitted".into()));
    Ok(SensorFit {
        plane,
        observations: obs,
        cycles,
        linear,
        characteristic,
        pi,
        continuous_pi,
        configs,
        summaries,
        seconds: [t_observe, t_linear, t_pi, t_cpi],
    })
}

/// One play model's fit, on its way into a [`SensorFit`].
struct Play {
    kind: PlayKind,
    model: ModelKind,
    plane: SensorPlane,
    divider: Divider,
    noise: f64,
}

impl Play {
    /// Adds the fit's summary and config (or the reason it has none) and returns what
    /// [`SensorFit`] keeps of it; the model the user asked for fails the whole fit instead.
    fn record(
        &self,
        result: Option<Result<PlayFit, FitError>>,
        obs: &Observations,
        options: &FitOptions,
        configs: &mut Vec<(ModelKind, SensorConfig)>,
        summaries: &mut Vec<ModelSummary>,
    ) -> Result<Result<PlayFit, String>, FitError> {
        let model = self.model;
        let n = obs.len();
        let Some(result) = result else {
            return Ok(Err(format!(
                "not asked for (--model {})",
                model_name(options.model)
            )));
        };
        let built = result.and_then(|fit| {
            let model_config = play_config(self.kind, &fit, obs, self.noise)?;
            model_config.validate().map_err(FitError::Model)?;
            Ok((fit, model_config))
        });
        match built {
            Ok((fit, model_config)) => {
                let mut s = match fit.set_aside_rmse_ohm {
                    // The line inside the PI model: two free constants, slope and offset.
                    Some(_) => summary(model, fit.rmse_ohm, 2, n, None),
                    None => summary(model, fit.rmse_ohm, fit.parameters(), n, None),
                };
                s.note = fit.set_aside_rmse_ohm.map(|hysteretic| {
                    format!(
                        "equivalent to the linear model: the best hysteretic fit ({hysteretic:.1} Ω) \
                         lowered the RMSE too little to pay for its {} extra parameters (BIC), so \
                         the line it contains was kept",
                        fit.parameters() - 2
                    )
                });
                summaries.push(s);
                configs.push((
                    model,
                    SensorConfig::new(self.divider, model_config).on_plane(self.plane),
                ));
                Ok(Ok(fit))
            }
            Err(e) => {
                if options.model == model {
                    return Err(e);
                }
                summaries.push(summary(model, f64::NAN, 0, n, Some(e.to_string())));
                Ok(Err(e.to_string()))
            }
        }
    }
}

/// The estimator config holding `model` for each fitted sensor (one, or both of a BSN joint),
/// with the prefilter as the runtime's input filter.
///
/// # Errors
/// [`FitError::Model`] when the runtime refuses it.
pub fn estimator_config(
    joint: &Joint,
    fits: &[SensorFit],
    model: ModelKind,
    prefilter: Prefilter,
) -> Result<EstimatorConfig, FitError> {
    let pick = |fit: &SensorFit| {
        fit.config(model).copied().ok_or(FitError::NotConverged {
            model: model_name(model),
            reason: "not fitted".into(),
        })
    };
    let sensor = pick(&fits[0])?;
    let second_sensor = fits.get(1).map(pick).transpose()?;
    let config = EstimatorConfig {
        joint: JointConfig::from_joint(joint),
        sensor,
        second_sensor,
        input_filter: prefilter.filter_config(),
        output_filter: dlw_estimator::FilterConfig::None,
    };
    config.validate().map_err(FitError::Model)?;
    Ok(config)
}

/// The runtime model for a play fit: the resistance range seen (PI) or the strain range seen
/// (continuous PI) as the clamp, as the paper clamps to the characterized range.
fn play_config(
    kind: PlayKind,
    fit: &PlayFit,
    obs: &Observations,
    noise_ohm: f64,
) -> Result<ModelConfig, FitError> {
    let weights = Coeffs::from_slice("weights", &fit.values.weights).map_err(FitError::Model)?;
    let radii = Coeffs::from_slice("radii", &fit.model.radii).map_err(FitError::Model)?;
    let (lo, hi) = min_max(&obs.strain);
    Ok(match kind {
        PlayKind::Generalized => ModelConfig::Pi(PiConfig {
            weights,
            radii,
            loading_tanh: fit.values.loading,
            unloading_tanh: fit.values.unloading,
            center_strain: fit.model.center_strain,
            center_ohm: fit.model.center_ohm,
            min_ohm: obs.ohm_range.0,
            max_ohm: obs.ohm_range.1,
            min_strain: Some(lo),
            max_strain: Some(hi),
            initial_state: fit.initial_state,
        }),
        PlayKind::Continuous => ModelConfig::ContinuousPi(ContinuousPiConfig {
            weights,
            radii,
            loading_envelope: fit.values.loading,
            unloading_envelope: fit.values.unloading,
            center_strain: fit.model.center_strain,
            center_ohm: fit.model.center_ohm,
            min_strain: lo,
            max_strain: hi,
            strain_tolerance: 1e-9,
            resistance_tolerance_ohm: noise_ohm,
            initial_state: fit.initial_state,
        }),
    })
}

/// The sample-to-sample noise of a resistance series (Ω): the median absolute first
/// difference over `0.6745·√2`, which a trend barely moves.
fn resistance_noise(ohm: &[f64]) -> f64 {
    let mut d: Vec<f64> = ohm.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    if d.is_empty() {
        return 0.0;
    }
    let mid = d.len() / 2;
    let (_, median, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
    *median / (0.6745 * std::f64::consts::SQRT_2)
}

fn summary(
    model: ModelKind,
    rmse_ohm: f64,
    k: usize,
    n: usize,
    skipped: Option<String>,
) -> ModelSummary {
    let nf = n as f64;
    let bic = if rmse_ohm.is_finite() && rmse_ohm > 0.0 {
        nf * (rmse_ohm * rmse_ohm).ln() + k as f64 * nf.ln()
    } else {
        f64::NAN
    };
    ModelSummary {
        model,
        rmse_ohm,
        parameters: k,
        bic,
        skipped,
        note: None,
    }
}

fn kind_model(kind: PlayKind) -> ModelKind {
    match kind {
        PlayKind::Generalized => ModelKind::Pi,
        PlayKind::Continuous => ModelKind::ContinuousPi,
    }
}

fn kind_name(kind: PlayKind) -> &'static str {
    match kind {
        PlayKind::Generalized => "pi",
        PlayKind::Continuous => "continuous-pi",
    }
}

/// The model's name as the command line writes it.
pub fn model_name(model: ModelKind) -> &'static str {
    match model {
        ModelKind::Linear => "linear",
        ModelKind::Pi => "pi",
        ModelKind::ContinuousPi => "continuous-pi",
    }
}

/// Moved to [`crate::stats`] (one NaN policy); re-exported here this round.
pub(crate) use crate::stats::min_max;
