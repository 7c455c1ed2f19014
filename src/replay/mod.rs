//! Running the runtime estimator over a recording, as a controller would have run it live.
//!
//! [`replay`] feeds every sample's divider voltage(s) to a `dlw_estimator::Estimator`, in order,
//! and compares each estimate with the angle the EM tracker recorded at the same sample:
//! `error = estimate − recorded`. The metrics are over every sample, held or not:
//! `rmse_deg = √(mean(error²))`, `max_abs_error_deg = max |error|`.
//!
//! The error is raw: a filter's delay is not compensated. A moving average of `N` samples lags
//! a ramp by `(N − 1)/2` samples, so on a signal moving at `ω` °/s it adds about
//! `ω·(N − 1)/(2·f_s)` degrees of lag error while it removes noise (by `√N` for white noise);
//! the report gives the delay so a reader can tell the two apart.
//!
//! [`replay_against_truth`] compares the same estimates with a ground truth taken at other
//! times (fluoroscopy frames, `dlw estimate --truth`), interpolated at the frame times
//! ([`truth`]).
//!
//! [`config_file`] reads and writes estimator configs as TOML or JSON.

mod config_file;
mod estimate;
pub mod nominal;
pub mod robot;
pub mod robot_report;
pub mod truth;

use dlw_estimator::{Estimator, EstimatorConfig, EstimatorError, Flags};
use serde::Serialize;

use crate::fixed::push_fixed;
use crate::recording::Recording;

/// Estimator config files in TOML or JSON.
pub use config_file::{
    config_text, is_robot_config, load_config, load_robot_config, robot_config_text,
    ConfigFileError, ConfigFormat,
};
/// `dlw estimate` as a library call.
pub use estimate::{estimate, EstimateRequest, Estimation, TrackerEstimation, TruthEstimation};
/// Comparing estimates with a ground truth at other times.
pub use truth::{compare_with_truth, replay_against_truth, TruthMetrics, TruthReplay};

/// Why a replay could not run.
#[derive(Debug, thiserror::Error)]
pub enum ReplayError {
    /// A replay's error, with what was being compared.
    #[error("{what}")]
    Over {
        /// What was being compared (`estimating over rec`).
        what: String,
        /// Why it failed.
        source: Box<ReplayError>,
    },
    /// The config needs more sensors than the recording has.
    #[error(
        "the config reads {config} sensor(s), up to voltage column v{column}_V, but the recording has {recording} voltage column(s)"
    )]
    SensorCount {
        /// Sensors in the config.
        config: u32,
        /// The highest voltage column the config reads (1-based).
        column: usize,
        /// Voltage columns in the recording.
        recording: usize,
    },
    /// The estimator could not be built.
    #[error("cannot build the estimator: {0}")]
    Estimator(#[from] EstimatorError),
    /// The recording has no tracker angle to compare with.
    #[error("the recording has no tracker angle (its angle_deg column is empty); compare with a ground truth: --truth angles.csv")]
    NoTrackerAngle,
    /// The ground truth and the recording share no time.
    #[error("no ground-truth frame of {truth} lies within the recording's time span {start_s}..{end_s} s ({frames} frame(s) from {first_s} s to {last_s} s)")]
    NoOverlap {
        /// The ground-truth file.
        truth: String,
        /// The recording's first time (s).
        start_s: f64,
        /// The recording's last time (s).
        end_s: f64,
        /// Frames with an angle.
        frames: usize,
        /// The first frame's time (s).
        first_s: f64,
        /// The last frame's time (s).
        last_s: f64,
    },
}

/// The comparison of the estimates with the recorded angle. The JSON keys are part of the
/// interface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TrackerMetrics {
    /// Root mean square of `estimate − recorded` (°).
    pub rmse_deg: f64,
    /// Largest `|estimate − recorded|` (°).
    pub max_abs_error_deg: f64,
    /// Samples compared (every sample of the recording).
    pub samples: usize,
    /// Samples whose estimate carried any flag.
    pub flagged_samples: usize,
    /// Samples held (the estimate is a previous one).
    pub held_samples: usize,
    /// Delay of the estimator's filters on a ramp (samples), not compensated in the error.
    pub filter_delay_samples: f64,
    /// The same delay in seconds, at the recording's sample rate.
    pub filter_delay_s: f64,
}

/// The estimates for every sample and their metrics.
#[derive(Debug, Clone)]
pub struct Replay {
    /// The estimated angle per sample (°).
    pub estimate_deg: Vec<f64>,
    /// The estimator's flags per sample.
    pub flags: Vec<Flags>,
    /// The comparison with the recorded angle.
    pub metrics: TrackerMetrics,
    /// Things the user should know (a divider that differs from the rig, an unused column).
    pub warnings: Vec<String>,
}

/// Runs `config`'s estimator over `recording`.
///
/// # Errors
/// [`ReplayError`]: a config the estimator crate refuses, or one that needs a second sensor the
/// recording does not have.
pub fn replay(config: &EstimatorConfig, recording: &Recording) -> Result<Replay, ReplayError> {
    if !recording.samples.has_tracker_angle() {
        return Err(ReplayError::NoTrackerAngle);
    }
    let run = run_estimator(config, recording)?;
    Ok(Replay {
        metrics: tracker_metrics(&run, recording),
        estimate_deg: run.estimate_deg,
        flags: run.flags,
        warnings: run.warnings,
    })
}

/// The comparison of a run's estimates with the recording's tracker angle, which it must have.
pub(crate) fn tracker_metrics(run: &Run, recording: &Recording) -> TrackerMetrics {
    let samples = &recording.samples;
    let (mut sum_sq, mut max_abs) = (0.0f64, 0.0f64);
    // Rows the tracker did not measure (`tracker_valid = 0`) are not compared.
    let mut n = 0usize;
    for (i, (e, a)) in run.estimate_deg.iter().zip(&samples.angle_deg).enumerate() {
        if !samples.angle_valid(i) {
            continue;
        }
        n += 1;
        let err = e - a;
        sum_sq += err * err;
        max_abs = max_abs.max(err.abs());
    }
    TrackerMetrics {
        rmse_deg: (sum_sq / n.max(1) as f64).sqrt(),
        max_abs_error_deg: max_abs,
        samples: n,
        flagged_samples: run.flagged,
        held_samples: run.held,
        filter_delay_samples: run.delay_samples,
        filter_delay_s: run.delay_samples / recording.rig.sample_hz,
    }
}

/// The estimator's output over a recording, before any comparison.
#[derive(Debug, Clone)]
pub(crate) struct Run {
    pub(crate) estimate_deg: Vec<f64>,
    pub(crate) flags: Vec<Flags>,
    pub(crate) flagged: usize,
    pub(crate) held: usize,
    pub(crate) delay_samples: f64,
    pub(crate) warnings: Vec<String>,
}

/// Runs `config`'s estimator over every sample of `recording`.
pub(crate) fn run_estimator(
    config: &EstimatorConfig,
    recording: &Recording,
) -> Result<Run, ReplayError> {
    let rig = &recording.rig;
    let samples = &recording.samples;
    let channels = samples.volts.len();
    let two = config.second_sensor.is_some();
    // A one-sensor config reads the column of its plane (v2_V for a sensor on −y_s).
    let first_column = config.first_plane().column() as usize;
    let needed = if two { 2 } else { first_column };
    if needed > channels {
        return Err(ReplayError::SensorCount {
            config: config.sensor_count(),
            column: needed,
            recording: channels,
        });
    }
    let mut warnings = Vec::new();
    if !two && channels > 1 {
        warnings.push(format!(
            "the recording has {channels} voltage columns; the config reads only v{first_column}_V"
        ));
    }
    warnings.extend(divider_warnings(
        config,
        &rig.divider_ohm,
        rig.supply_v,
        "rig.toml",
    ));
    warnings.extend(recorded_design_warning(config, rig));
    // About 100 KiB of filter buffers: on the heap.
    let mut estimator = Box::new(Estimator::new(config)?);
    let n = samples.len();
    let mut estimate_deg = Vec::with_capacity(n);
    let mut flags = Vec::with_capacity(n);
    let (mut flagged, mut held) = (0, 0);
    for i in 0..n {
        let e = if two {
            estimator.step2(samples.volts[0][i], samples.volts[1][i])
        } else {
            estimator.step(samples.volts[first_column - 1][i])
        };
        flagged += usize::from(!e.flags.is_empty());
        held += usize::from(e.flags.contains(Flags::HELD));
        estimate_deg.push(e.angle_deg);
        flags.push(e.flags);
    }
    Ok(Run {
        estimate_deg,
        flags,
        flagged,
        held,
        delay_samples: estimator.delay_samples(),
        warnings,
    })
}

impl Replay {
    /// The replay as an offline, zero-phase filter would give it: the estimates moved earlier
    /// by the filters' delay (rounded to a sample), so that a filter applied after the fact (the
    /// paper's moving averages, MATLAB's centred `movmean`) costs no lag. The last `delay`
    /// samples, which have no estimate left, are not compared; the metrics are computed again
    /// and keep the delay they compensated in `filter_delay_*`.
    pub fn delay_compensated(mut self, recording: &Recording) -> Self {
        let shift = self.metrics.filter_delay_samples.round().max(0.0) as usize;
        let n = self.estimate_deg.len();
        if shift == 0 || shift >= n {
            return self;
        }
        self.estimate_deg.drain(..shift);
        let last = self.estimate_deg[self.estimate_deg.len() - 1];
        self.estimate_deg.resize(n, last);
        let samples = &recording.samples;
        let (mut sum_sq, mut max_abs, mut compared) = (0.0f64, 0.0f64, 0usize);
        for i in (0..n - shift).filter(|&i| samples.angle_valid(i)) {
            let err = self.estimate_deg[i] - samples.angle_deg[i];
            sum_sq += err * err;
            max_abs = max_abs.max(err.abs());
            compared += 1;
        }
        self.metrics.rmse_deg = (sum_sq / compared.max(1) as f64).sqrt();
        self.metrics.max_abs_error_deg = max_abs;
        self.metrics.samples = compared;
        self
    }
}

/// Warnings for each configured sensor whose divider resistor or supply differs from the
/// bench's (`divider_ohm[i]` for sensor `i + 1`, `supply_v`, as written in `source`, e.g.
/// `rig.toml`): the estimator would then read a wrong resistance.
pub fn divider_warnings(
    config: &EstimatorConfig,
    divider_ohm: &[f64],
    supply_v: f64,
    source: &str,
) -> Vec<String> {
    let mut warnings = Vec::new();
    let sensors = std::iter::once(&config.sensor).chain(config.second_sensor.as_ref());
    let two = config.second_sensor.is_some();
    for (place, s) in sensors.enumerate() {
        // A one-sensor config reads the column of its plane.
        let i = if two {
            place
        } else {
            config.first_plane().column() as usize - 1
        };
        let Some(&rig_ohm) = divider_ohm.get(i) else {
            break;
        };
        if !close(s.divider_ohm, rig_ohm) {
            warnings.push(format!(
                "sensor {} divider_ohm is {} Ω in the config but {} Ω in {source}",
                i + 1,
                s.divider_ohm,
                rig_ohm
            ));
        }
        if !close(s.supply_v, supply_v) {
            warnings.push(format!(
                "sensor {} supply_v is {} V in the config but {} V in {source}",
                i + 1,
                s.supply_v,
                supply_v
            ));
        }
    }
    warnings
}

/// A warning when `config`'s joint is not the design a simulated recording states in its
/// `[design]` table: the config would convert the recording's strain with another geometry.
/// Nothing for a recording that states no design (imported, or written by hand).
fn recorded_design_warning(
    config: &EstimatorConfig,
    rig: &crate::recording::Rig,
) -> Option<String> {
    let table = rig.design.clone()?;
    let file: crate::design::DesignFile = table.try_into().ok()?;
    let design = crate::design::Design::from_file(file).ok()?;
    let checksum = rig.simulation.as_ref().map_or(String::new(), |s| {
        format!(", checksum {}", s.design_checksum)
    });
    geometry_warning(
        config,
        &design,
        &format!(
            "the recording's design {:?} (rig.toml{checksum})",
            design.file.name
        ),
    )
}

/// A warning naming every joint parameter where `config` differs from `design` (described as
/// `source`), or nothing when they agree.
pub fn geometry_warning(
    config: &EstimatorConfig,
    design: &crate::design::Design,
    source: &str,
) -> Option<String> {
    let theirs = dlw_estimator::JointConfig::from_joint(&design.joint);
    let ours = &config.joint;
    let numbers = [
        (
            "outer_radius_mm",
            ours.outer_radius_mm,
            theirs.outer_radius_mm,
        ),
        (
            "inner_radius_mm",
            ours.inner_radius_mm,
            theirs.inner_radius_mm,
        ),
        ("notch_arc_mm", ours.notch_arc_mm, theirs.notch_arc_mm),
        ("notch_width_mm", ours.notch_width_mm, theirs.notch_width_mm),
        (
            "notch_spacing_mm",
            ours.notch_spacing_mm,
            theirs.notch_spacing_mm,
        ),
        (
            "notch_count",
            f64::from(ours.notch_count),
            f64::from(theirs.notch_count),
        ),
        (
            "joint_length_mm",
            ours.joint_length_mm,
            theirs.joint_length_mm,
        ),
        ("sensor_arc_mm", ours.sensor_arc_mm, theirs.sensor_arc_mm),
    ];
    let mut differences: Vec<String> = numbers
        .iter()
        .filter(|(_, a, b)| !close(*a, *b))
        .map(|(key, a, b)| format!("{key} {a} vs {b}"))
        .collect();
    if ours.style != theirs.style {
        differences.insert(
            0,
            format!(
                "style {} vs {}",
                style_name(ours.style),
                style_name(theirs.style)
            ),
        );
    }
    (!differences.is_empty()).then(|| {
        format!(
            "the estimator config's joint is not {source}: {} (config vs design); the estimate \
             converts strain to angle with the config's geometry",
            differences.join(", ")
        )
    })
}

fn style_name(style: dlw_geometry::NotchStyle) -> &'static str {
    match style {
        dlw_geometry::NotchStyle::Uan => "uan",
        dlw_geometry::NotchStyle::Bsn => "bsn",
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

impl Replay {
    /// The estimates as CSV: `time_s,angle_deg,estimate_deg,error_deg,flags`, where `angle_deg`
    /// is the recorded angle, `error_deg = estimate_deg − angle_deg` and `flags` the estimator's
    /// flag names joined by `|` (`none` when clean).
    pub fn csv_bytes(&self, recording: &Recording) -> Vec<u8> {
        estimates_csv(
            &self.estimate_deg,
            &self.flags,
            recording,
            ESTIMATE_DECIMALS,
        )
    }

    /// [`Replay::csv_bytes`] with `estimate_deg` and `error_deg` to `decimals` places (e.g. 12,
    /// to compare with another implementation to 1e-9).
    pub fn csv_bytes_with(&self, recording: &Recording, decimals: u32) -> Vec<u8> {
        estimates_csv(&self.estimate_deg, &self.flags, recording, decimals)
    }
}

/// Decimal places of `estimate_deg` and `error_deg` in `estimates.csv` by default.
pub const ESTIMATE_DECIMALS: u32 = 4;
/// The most decimal places `estimates.csv` can be asked for (beyond this, f64 has no digits).
pub const MAX_ESTIMATE_DECIMALS: u32 = 15;

/// `time_s,angle_deg,estimate_deg,error_deg,flags`; `angle_deg` and `error_deg` are empty when
/// the recording has no tracker angle.
pub(crate) fn estimates_csv(
    estimate_deg: &[f64],
    flags: &[Flags],
    recording: &Recording,
    decimals: u32,
) -> Vec<u8> {
    let s = &recording.samples;
    let mut out = Vec::with_capacity(s.len() * 48 + 64);
    out.extend_from_slice(b"time_s,angle_deg,estimate_deg,error_deg,flags\n");
    for i in 0..s.len() {
        push_fixed(&mut out, s.time_s[i], 6);
        out.push(b',');
        let angle = s.angle_deg.get(i).copied();
        if let Some(a) = angle {
            push_fixed(&mut out, a, 4);
        }
        out.push(b',');
        push_fixed(&mut out, estimate_deg[i], decimals);
        out.push(b',');
        if let Some(a) = angle {
            push_fixed(&mut out, estimate_deg[i] - a, decimals);
        }
        out.push(b',');
        out.extend_from_slice(flags[i].to_string().as_bytes());
        out.push(b'\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::{plan, ProtocolKind, Scenario};
    use dlw_estimator::{nominal_divider, FilterConfig, JointConfig};
    use dlw_geometry::NotchStyle;

    fn recording(style: NotchStyle, edit: impl FnOnce(&mut Scenario)) -> Recording {
        let design = crate::sim::test_design(style);
        let mut sc = Scenario {
            protocol: Some(ProtocolKind::Random),
            duration_s: Some(30.0),
            ..Scenario::default()
        };
        edit(&mut sc);
        let p = plan(&design, sc, None).unwrap();
        Recording {
            rig: p.rig(),
            samples: p.run().unwrap().samples,
        }
    }

    fn nominal(style: NotchStyle, gf: f64, r0: f64) -> EstimatorConfig {
        let design = crate::sim::test_design(style);
        EstimatorConfig::nominal_linear(
            JointConfig::from_joint(&design.joint),
            gf,
            r0,
            nominal_divider(),
        )
        .unwrap()
    }

    #[test]
    fn noise_free_linear_recording_is_recovered_exactly() {
        let rec = recording(NotchStyle::Uan, |s| {
            s.adc.enabled = false;
            s.tracker.enabled = false;
        });
        let r = replay(&nominal(NotchStyle::Uan, 15.3, 215e3), &rec).unwrap();
        assert!(r.metrics.rmse_deg < 1e-9, "{:?}", r.metrics);
        assert_eq!(r.metrics.samples, 15_000);
        assert_eq!(r.metrics.flagged_samples, 0);
        assert!(r.warnings.is_empty());
        let wrong = replay(&nominal(NotchStyle::Uan, 14.0, 215e3), &rec).unwrap();
        assert!(wrong.metrics.rmse_deg > 0.5, "{:?}", wrong.metrics);
    }

    #[test]
    fn two_sensor_config_needs_two_columns_and_reports_divider_mismatch() {
        let uan = recording(NotchStyle::Uan, |_| {});
        let mut cfg = nominal(NotchStyle::Bsn, 1.28, 74e3);
        let err = replay(&cfg, &uan).unwrap_err().to_string();
        assert!(
            err.contains("2 sensor(s)") && err.contains("1 voltage column"),
            "{err}"
        );
        let bsn = recording(NotchStyle::Bsn, |_| {});
        cfg.output_filter = FilterConfig::MovingAverage { samples: 101 };
        let r = replay(&cfg, &bsn).unwrap();
        // The nominal config gives sensor 2 the 99.6 kΩ divider; the bench has 102.5 kΩ.
        assert!(
            r.warnings.iter().any(|w| w.contains("102500")),
            "{:?}",
            r.warnings
        );
        assert_eq!(r.metrics.filter_delay_samples, 50.0);
        assert_eq!(r.metrics.filter_delay_s, 0.1);
    }

    /// The simulator's PI sensor is the estimator crate's forward model, so the estimator's PI
    /// inverse with the same parameters recovers the angle of a noise-free recording; only the
    /// samples at reversals may be off (the tanh branch switch, bounded in the estimator crate).
    #[test]
    fn pi_inverse_recovers_the_simulated_pi_sensor() {
        use crate::sim::{SensorModelKind, JOINT_A_PI};
        use dlw_estimator::ModelConfig;
        let rec = recording(NotchStyle::Uan, |s| {
            s.adc.enabled = false;
            s.tracker.enabled = false;
            s.sensor1.model = SensorModelKind::Pi;
        });
        let mut cfg = nominal(NotchStyle::Uan, 15.3, 215e3);
        cfg.sensor.model = ModelConfig::Pi(JOINT_A_PI.to_config());
        let r = replay(&cfg, &rec).unwrap();
        let clean: Vec<f64> = (0..rec.samples.len())
            .filter(|&i| r.flags[i].is_empty())
            .map(|i| (r.estimate_deg[i] - rec.samples.angle_deg[i]).abs())
            .collect();
        let worst = clean.iter().cloned().fold(0.0, f64::max);
        assert!(clean.len() > 14_000, "{} clean samples", clean.len());
        assert!(worst < 1e-6, "largest error on unflagged samples {worst}°");
        // The linear model of the same sensor is degrees off.
        let linear = replay(&nominal(NotchStyle::Uan, 15.3, 215e3), &rec).unwrap();
        assert!(linear.metrics.rmse_deg > 0.5, "{:?}", linear.metrics);
    }

    #[test]
    fn a_recording_without_tracker_angle_needs_a_ground_truth() {
        let mut rec = recording(NotchStyle::Uan, |s| {
            s.duration_s = Some(2.0);
            s.adc.enabled = false;
            s.tracker.enabled = false;
        });
        let true_deg = std::mem::take(&mut rec.samples.angle_deg);
        let cfg = nominal(NotchStyle::Uan, 15.3, 215e3);
        let err = replay(&cfg, &rec).unwrap_err().to_string();
        assert!(
            err.contains("no tracker angle") && err.contains("--truth"),
            "{err}"
        );
        // Frames at 2 Hz from the true angle, offset by 0.5°: the RMSE is the offset.
        let frames: Vec<usize> = (0..4).map(|k| k * 250).collect();
        let truth = crate::recording::TruthAngles {
            path: "angles.csv".into(),
            time_s: frames.iter().map(|&i| rec.samples.time_s[i]).collect(),
            angle_deg: frames.iter().map(|&i| true_deg[i] + 0.5).collect(),
            skipped: 0,
        };
        let r = replay_against_truth(&cfg, &rec, &truth).unwrap();
        assert!(r.tracker.is_none());
        assert_eq!(r.truth.frames, 4);
        assert!((r.truth.rmse_deg - 0.5).abs() < 1e-6, "{:?}", r.truth);
        let text = String::from_utf8(r.csv_bytes(&rec)).unwrap();
        let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
        assert_eq!((row[1], row[3]), ("", ""));
    }

    #[test]
    fn csv_has_a_row_per_sample() {
        let rec = recording(NotchStyle::Uan, |s| s.duration_s = Some(0.01));
        let r = replay(&nominal(NotchStyle::Uan, 15.3, 215e3), &rec).unwrap();
        let text = String::from_utf8(r.csv_bytes(&rec)).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "time_s,angle_deg,estimate_deg,error_deg,flags");
        assert_eq!(lines.len(), 6);
        assert!(
            lines[1].starts_with("0.000000,") && lines[1].ends_with(",none"),
            "{}",
            lines[1]
        );
    }
}
