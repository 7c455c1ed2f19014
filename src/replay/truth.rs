//! Comparing estimates with a ground truth taken at other times: fluoroscopy frames at 2 Hz
//! against a 500 Hz recording (the paper's Table VII).
//!
//! The estimate is interpolated linearly between the two samples around each frame time `t_k`,
//! `ê(t_k)`, and compared with the frame's angle `g_k`: `error_k = ê(t_k) − g_k`,
//! `rmse_deg = √(mean(error²))`, `max_abs_error_deg = max |error|`, `mean_error_deg =
//! mean(error)` (a bias, e.g. a baseline mismatch). Frames outside the recording's time span are
//! counted and left out, not extrapolated.

use dlw_estimator::{EstimatorConfig, Flags};
use serde::Serialize;

use super::{estimates_csv, run_estimator, tracker_metrics, ReplayError, TrackerMetrics};
use crate::recording::Recording;
use crate::recording::TruthAngles;

/// The comparison of estimates with a ground truth. The JSON keys are part of the interface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TruthMetrics {
    /// Root mean square of `estimate − truth` over the frames compared (°).
    pub rmse_deg: f64,
    /// Largest `|estimate − truth|` (°).
    pub max_abs_error_deg: f64,
    /// Mean of `estimate − truth` (°).
    pub mean_error_deg: f64,
    /// Frames compared.
    pub frames: usize,
    /// Frames with an angle outside the recording's time span, left out.
    pub frames_outside: usize,
    /// Frames without an angle in the truth file (skipped by `dlw fluoro`).
    pub frames_without_angle: usize,
}

/// Compares `estimate_deg` at `time_s` with `truth`.
///
/// # Errors
/// [`ReplayError::NoOverlap`] when no frame lies within the recording's time span.
pub fn compare_with_truth(
    time_s: &[f64],
    estimate_deg: &[f64],
    truth: &TruthAngles,
) -> Result<TruthMetrics, ReplayError> {
    let (mut sum, mut sum_sq, mut max_abs, mut n) = (0.0, 0.0, 0.0f64, 0usize);
    for (&t, &g) in truth.time_s.iter().zip(&truth.angle_deg) {
        if let Some(e) = crate::stats::interpolate(time_s, estimate_deg, t) {
            let err = e - g;
            sum += err;
            sum_sq += err * err;
            max_abs = max_abs.max(err.abs());
            n += 1;
        }
    }
    if n == 0 {
        return Err(ReplayError::NoOverlap {
            truth: truth.path.display().to_string(),
            start_s: time_s.first().copied().unwrap_or(f64::NAN),
            end_s: time_s.last().copied().unwrap_or(f64::NAN),
            frames: truth.time_s.len(),
            first_s: truth.time_s.first().copied().unwrap_or(f64::NAN),
            last_s: truth.time_s.last().copied().unwrap_or(f64::NAN),
        });
    }
    Ok(TruthMetrics {
        rmse_deg: (sum_sq / n as f64).sqrt(),
        max_abs_error_deg: max_abs,
        mean_error_deg: sum / n as f64,
        frames: n,
        frames_outside: truth.time_s.len() - n,
        frames_without_angle: truth.skipped,
    })
}

/// The estimates over a recording compared with a ground truth, and with the tracker when the
/// recording has its angle.
#[derive(Debug, Clone)]
pub struct TruthReplay {
    /// The estimated angle per sample (°).
    pub estimate_deg: Vec<f64>,
    /// The estimator's flags per sample.
    pub flags: Vec<Flags>,
    /// The comparison with the ground truth.
    pub truth: TruthMetrics,
    /// The comparison with the tracker, `None` for a recording without its angle.
    pub tracker: Option<TrackerMetrics>,
    /// Samples whose estimate carried any flag.
    pub flagged_samples: usize,
    /// Samples held.
    pub held_samples: usize,
    /// Delay of the estimator's filters on a ramp (samples), not compensated in the error.
    pub filter_delay_samples: f64,
    /// The same delay in seconds.
    pub filter_delay_s: f64,
    /// Things the user should know.
    pub warnings: Vec<String>,
}

/// Runs `config`'s estimator over `recording` and compares it with `truth` at the frame times.
///
/// # Errors
/// [`ReplayError`]: a config the estimator refuses, a sensor the recording lacks, no frame in
/// the recording's time span.
pub fn replay_against_truth(
    config: &EstimatorConfig,
    recording: &Recording,
    truth: &TruthAngles,
) -> Result<TruthReplay, ReplayError> {
    let run = run_estimator(config, recording)?;
    let metrics = compare_with_truth(&recording.samples.time_s, &run.estimate_deg, truth)?;
    let mut warnings = run.warnings.clone();
    if metrics.frames_outside > 0 {
        warnings.push(format!(
            "{} ground-truth frame(s) lie outside the recording's time span and are not compared",
            metrics.frames_outside
        ));
    }
    let tracker = recording
        .samples
        .has_tracker_angle()
        .then(|| tracker_metrics(&run, recording));
    let delay = run.delay_samples;
    Ok(TruthReplay {
        truth: metrics,
        tracker,
        flagged_samples: run.flagged,
        held_samples: run.held,
        filter_delay_samples: delay,
        filter_delay_s: delay / recording.rig.sample_hz,
        warnings,
        estimate_deg: run.estimate_deg,
        flags: run.flags,
    })
}

impl TruthReplay {
    /// The estimates as CSV, as [`Replay::csv_bytes`](super::Replay::csv_bytes); `angle_deg` and
    /// `error_deg` are empty for a recording without the tracker's angle.
    pub fn csv_bytes(&self, recording: &Recording) -> Vec<u8> {
        self.csv_bytes_with(recording, super::ESTIMATE_DECIMALS)
    }

    /// [`TruthReplay::csv_bytes`] with the estimates to `decimals` places.
    pub fn csv_bytes_with(&self, recording: &Recording, decimals: u32) -> Vec<u8> {
        estimates_csv(&self.estimate_deg, &self.flags, recording, decimals)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    #[test]
    fn compares_at_frame_times() {
        // Estimates of a ramp 10 °/s with a 1° bias; truth frames at 2 Hz, one beyond the end.
        let t: Vec<f64> = (0..=1000).map(|k| k as f64 * 0.002).collect();
        let est: Vec<f64> = t.iter().map(|t| 10.0 * t + 1.0).collect();
        let truth = TruthAngles {
            path: PathBuf::from("angles.csv"),
            time_s: vec![0.25, 0.75, 1.25, 1.75, 2.25],
            angle_deg: vec![2.5, 7.5, 12.5, 17.5, 22.5],
            skipped: 2,
        };
        let m = compare_with_truth(&t, &est, &truth).unwrap();
        assert_eq!(
            (m.frames, m.frames_outside, m.frames_without_angle),
            (4, 1, 2)
        );
        assert!(
            (m.rmse_deg - 1.0).abs() < 1e-9 && (m.mean_error_deg - 1.0).abs() < 1e-9,
            "{m:?}"
        );
        let late = TruthAngles {
            time_s: vec![5.0],
            angle_deg: vec![0.0],
            ..truth
        };
        let err = compare_with_truth(&t, &est, &late).unwrap_err().to_string();
        assert!(
            err.contains("no ground-truth frame") && err.contains("0..2 s"),
            "{err}"
        );
    }
}
