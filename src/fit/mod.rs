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
mod cycles;
mod data;
mod linear;
mod nnls;
mod pi;
mod plays;
pub(crate) mod report;
mod request;
pub mod robot;

use std::time::Instant;

use dlw_estimator::{
    Coeffs, ContinuousPiConfig, EstimatorConfig, EstimatorError, JointConfig, LinearModel,
    ModelConfig, PiConfig, SensorConfig, SensorPlane,
};
use dlw_geometry::{Divider, Joint};
use serde::Serialize;

/// The characteristic points of a loop (Table III).
pub use characteristic::{characteristic, Characteristic};
/// Loading and unloading phases and cycles of the strain.
pub use cycles::{cycles, phases, Cycle, Phase};
/// A sensor's strain and resistance as a fit sees them.
pub use data::{
    observe, Observations, Prefilter, MAX_FIT_SAMPLES, MIN_ANGLE_SPAN_DEG, RAIL_FRACTION,
};
/// The linear model by least squares.
pub use linear::{fit_linear, slope, LinearFit, MIN_R2};
/// Non-negative least squares on the normal equations.
pub use nnls::nnls;
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
pub use request::{
    fit, prefilter_name, FitRequest, FitResult, PlayReport, Restart, SensorReport, Timings,
    MAX_ORDER, MIN_ORDER,
};

use crate::recording::Recording;

/// Fewest cycles the PI procedure needs: the first cycle's loading and the last cycle's
/// unloading place `ε_c`, and a second cycle shows the loop repeating.
pub const MIN_PI_CYCLES: usize = 2;

/// A turning point of the strain needs the strain to come back by this share of its span.
pub const TURN_THRESHOLD: f64 = 0.1;

/// Why a fit could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FitError {
    /// The recording has no such voltage column.
    #[error("the recording has {columns} voltage column(s); sensor on that plane is recorded as v{column}_V")]
    NoColumn {
        /// The column needed (1-based).
        column: usize,
        /// Columns present.
        columns: usize,
    },
    /// The joint hardly moved.
    #[error("no motion: the recorded angle spans {span_deg:.3}°, a fit needs at least {min_deg}°")]
    NoMotion {
        /// Span of the recorded angle (°).
        span_deg: f64,
        /// The least span accepted (°).
        min_deg: f64,
    },
    /// A voltage at a rail.
    #[error("v{column}_V is at a rail in {count} sample(s), first at t = {time_s} s ({volts} V, within {margin_v} V of 0 or the supply): the divider resolves no resistance there (saturated ADC, open or shorted sensor)")]
    Rail {
        /// Column (1-based).
        column: usize,
        /// Samples at a rail.
        count: usize,
        /// Time of the first (s).
        time_s: f64,
        /// Its voltage (V).
        volts: f64,
        /// How near a rail counts (V).
        margin_v: f64,
    },
    /// Too few samples for any fit.
    #[error("{samples} sample(s) after decimation; a fit needs at least {min}")]
    TooFewSamples {
        /// Samples left.
        samples: usize,
        /// The least accepted.
        min: usize,
    },
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
    /// A fitted value no sensor has.
    #[error("the fit gives {what} = {value}, which no sensor has")]
    NonPhysical {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
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
    pub order: usize,
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
    let divider = Divider {
        fixed_ohm: rig.divider_ohm[plane.column() as usize - 1],
        supply_v: rig.supply_v,
    };
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
                    options.order,
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
        let Some(result) = result else {
            results.push(Err(format!(
                "not asked for (--model {})",
                model_name(options.model)
            )));
            continue;
        };
        let built = result.and_then(|fit| {
            let model_config = play_config(kind, &fit, &obs, noise)?;
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
                    SensorConfig::new(divider, model_config).on_plane(plane),
                ));
                results.push(Ok(fit));
            }
            Err(e) => {
                if options.model == model {
                    return Err(e);
                }
                summaries.push(summary(model, f64::NAN, 0, n, Some(e.to_string())));
                results.push(Err(e.to_string()));
            }
        }
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
