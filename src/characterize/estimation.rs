//! Angle estimation (Section IV-B, Tables IV-V, Figs. 7-8): each estimator config run over the
//! recording through the runtime estimator exactly as `dlw estimate` runs it
//! (`crate::replay::replay`), its angle RMSE against the tracker, and the estimates drawn over
//! the ground truth.
//!
//! - **The paper's processing** (an option): the PI models clamp the resistance to the range
//!   seen during characterization (a config from `dlw fit` carries that range as
//!   `min_ohm`/`max_ohm`), and the estimated angle goes through a 1000-sample moving average,
//!   which replaces the config's output filter. The paper filtered its recordings offline, where
//!   a centred moving average has no delay, so the filters' delay is compensated before the
//!   RMSE (`Replay::delay_compensated`). Left in, the 1 s delay was an error common to every
//!   estimate, larger than the sensors' own, and hid Table V's two-sensor gain.
//! - **Two sensors** (a BSN joint, Table V and Fig. 8): a two-sensor config is also run as the
//!   tension sensor alone (its first sensor, `v1_V`) and the compression sensor alone (its
//!   second, `v2_V`), then both (Eq. 7).

use dlw_estimator::{EstimatorConfig, FilterConfig, SensorPlane};
use serde::Serialize;

use crate::sensor::{Sensor, Sensors};

use super::{figure_name, titled, CharacterizeError, Options};
use crate::recording::Recording;
use crate::replay::{replay, TrackerMetrics};
use crate::report::{Chart, Page, Series, Table, PALETTE};

/// The paper's moving average on the estimated angle (samples).
pub const PAPER_MOVING_AVERAGE: u32 = 1000;

/// Length of the window the figure shows (s), as the paper shows a portion.
pub const WINDOW_S: f64 = 300.0;

/// A config with the name the report gives it (its file name, or `linear`, `PI`).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedConfig {
    /// Name in tables and legends.
    pub name: String,
    /// The config.
    pub config: EstimatorConfig,
}

/// One run of the estimator.
#[derive(Debug, Clone, Serialize)]
pub struct EstimationRun {
    /// The config's name.
    pub config: String,
    /// Which sensors the estimate reads: `sensor1`, `sensor2` or `both` (the one sensor
    /// identity, [`Sensors`]).
    pub sensors: Sensors,
    /// Whether it is one part of a two-sensor config (Table V's tension, compression, both).
    pub split: bool,
    /// The reading as the paper names it, for people: `one sensor`, or a two-sensor config's
    /// `tension`, `compression` or `both` ([`EstimationRun::role_of`]).
    pub role: &'static str,
    /// RMSE and the rest, as `dlw estimate --json` prints them.
    #[serde(flatten)]
    pub metrics: TrackerMetrics,
    /// The estimates (°), every sample.
    #[serde(skip)]
    pub estimate_deg: Vec<f64>,
}

/// Every run over one recording.
#[derive(Debug, Clone, Serialize)]
pub struct EstimationResult {
    /// Whether the paper's processing was applied.
    pub paper_processing: bool,
    /// The runs, in config order.
    pub runs: Vec<EstimationRun>,
    /// The recording's times (s).
    #[serde(skip)]
    pub time_s: Vec<f64>,
    /// The tracker angle (°).
    #[serde(skip)]
    pub truth_deg: Vec<f64>,
}

/// Runs each config (and each sensor alone of a two-sensor config) over `recording`.
///
/// # Errors
/// [`CharacterizeError::NoConfig`] without a config; [`CharacterizeError::Replay`] when the
/// estimator refuses a config or it needs a column the recording lacks.
pub fn estimate(
    recording: &Recording,
    configs: &[NamedConfig],
    options: &Options,
) -> Result<EstimationResult, CharacterizeError> {
    if configs.is_empty() {
        return Err(CharacterizeError::NoConfig);
    }
    let mut runs = Vec::new();
    for named in configs {
        let mut config = named.config;
        if options.paper_processing {
            config.output_filter = FilterConfig::MovingAverage {
                samples: PAPER_MOVING_AVERAGE,
            };
        }
        let variants: Vec<(Sensors, EstimatorConfig)> = match config.second_sensor {
            None => vec![(
                Sensors::Single(Sensor::on_plane(config.first_plane())),
                config,
            )],
            Some(second) => {
                let tension = EstimatorConfig {
                    second_sensor: None,
                    ..config
                };
                let compression = EstimatorConfig {
                    sensor: second.on_plane(SensorPlane::MinusYs),
                    second_sensor: None,
                    ..config
                };
                vec![
                    (Sensors::Single(Sensor::One), tension),
                    (Sensors::Single(Sensor::Two), compression),
                    (Sensors::Both, config),
                ]
            }
        };
        let split = config.second_sensor.is_some();
        for (sensors, c) in variants {
            let mut r = replay(&c, recording)?;
            if options.paper_processing {
                // The paper filtered offline (a centred moving average): no lag.
                r = r.delay_compensated(recording);
            }
            runs.push(EstimationRun {
                config: named.name.clone(),
                sensors,
                split,
                role: EstimationRun::role_of(sensors, split),
                metrics: r.metrics,
                estimate_deg: r.estimate_deg,
            });
        }
    }
    Ok(EstimationResult {
        paper_processing: options.paper_processing,
        runs,
        time_s: recording.samples.time_s.clone(),
        truth_deg: recording.samples.angle_deg.clone(),
    })
}

impl EstimationRun {
    /// How the paper names a reading: `one sensor` for a one-sensor config; a two-sensor
    /// config's sensor 1 is the one in `tension` (stretched by a positive angle), sensor 2 the
    /// one in `compression`, and `both` is Eq. 7.
    pub fn role_of(sensors: Sensors, split: bool) -> &'static str {
        match (split, sensors) {
            (false, _) => "one sensor",
            (true, Sensors::Single(Sensor::One)) => "tension",
            (true, Sensors::Single(Sensor::Two)) => "compression",
            (true, Sensors::Both) => "both",
        }
    }

    /// `config` or `config, tension`.
    pub fn name(&self) -> String {
        if self.split {
            format!("{}, {}", self.config, self.role)
        } else {
            self.config.clone()
        }
    }
}

impl EstimationResult {
    /// Adds the RMSE table (Table IV's rows, Table V's three for a two-sensor config) and the
    /// estimates over the ground truth (Figs. 7, 8(b)).
    fn section(&self, page: &mut Page, label: &str, prefix: &str) {
        let mut t = Table::new([
            "config",
            "sensors",
            "RMSE (°)",
            "max |error| (°)",
            "filter delay (s)",
            "flagged samples",
        ]);
        for r in &self.runs {
            let m = &r.metrics;
            t.row([
                r.config.clone(),
                r.role.to_owned(),
                format!("{:.3}", m.rmse_deg),
                format!("{:.2}", m.max_abs_error_deg),
                format!("{:.3}", m.filter_delay_s),
                m.flagged_samples.to_string(),
            ]);
        }
        page.table(t);
        if self.paper_processing {
            page.text(
                "The paper's processing: each estimate went through a 1000-sample moving average \
                 (2 s at 500 Hz), applied as the paper applied it, offline: the filters' delay \
                 (the column above) is taken out before the error is measured, as a centred \
                 moving average has none. The PI configs clamp the resistance to the range seen \
                 during characterization.",
            );
        }
        let t0 = self.time_s.first().copied().unwrap_or(0.0);
        let end = self
            .time_s
            .iter()
            .position(|&t| t > t0 + WINDOW_S)
            .unwrap_or(self.time_s.len());
        let mut chart = Chart::new(
            titled(label, "Estimated angle over the ground truth"),
            "time (s)",
            "angle (°)",
        );
        chart.size = (900, 420);
        chart.push(Series::line(
            "ground truth (tracker)",
            Series::zip(&self.time_s[..end], &self.truth_deg[..end]),
            (30, 30, 30),
        ));
        for (k, r) in self.runs.iter().enumerate() {
            chart.push(Series::line(
                r.name(),
                Series::zip(&self.time_s[..end], &r.estimate_deg[..end]),
                PALETTE[k % PALETTE.len()],
            ));
        }
        let shown = self
            .time_s
            .get(end.saturating_sub(1))
            .copied()
            .unwrap_or(t0)
            - t0;
        page.figure(
            figure_name(prefix, "estimates"),
            chart,
            format!(
                "The ground-truth angle and the estimates of each config over the first {shown:.0} s \
                 (cf. Figs. 7 and 8(b)); the RMSE is over the whole recording."
            ),
        );
    }
}

impl crate::analysis::Analysis for EstimationResult {
    fn summary(&self) -> String {
        use std::fmt::Write;
        let r = self;
        let mut out = String::new();
        for run in &r.runs {
            let _ = writeln!(
                out,
                "{:<28} RMSE {:>7.3}°   max |error| {:>7.3}°",
                run.name(),
                run.metrics.rmse_deg,
                run.metrics.max_abs_error_deg
            );
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: crate::analysis::Placement<'_>) {
        self.section(page, at.label, at.figure_prefix);
    }
}
