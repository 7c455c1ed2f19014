//! `dlw estimate` as a library call: an [`EstimateRequest`] (a config, a recording, and
//! optionally a ground truth) in, an [`Estimation`] (the estimates, their comparison, the
//! command's JSON and text) out.

use std::path::PathBuf;

use dlw_estimator::EstimatorConfig;
use serde::Serialize;

use super::{
    replay, replay_against_truth, Replay, ReplayError, TrackerMetrics, TruthMetrics, TruthReplay,
};
use crate::analysis::{Analysis, Placement};
use crate::recording::{Recording, TruthAngles};
use crate::report::{Page, Table};

/// What to estimate: everything `dlw estimate` takes besides its output.
#[derive(Debug, Clone, Copy)]
pub struct EstimateRequest<'a> {
    /// The estimator's config (its output filter as the caller wants it).
    pub config: &'a EstimatorConfig,
    /// The recording run through it.
    pub recording: &'a Recording,
    /// Its name, for the text and the messages (the command gives its path).
    pub recording_name: &'a str,
    /// A ground truth at other times (fluoroscopy), with its name, to compare with in place of
    /// the tracker column.
    pub truth: Option<(&'a TruthAngles, &'a str)>,
}

/// The estimates over a recording, compared with its tracker angle or with a ground truth.
/// Serializes to what `dlw estimate --json` prints.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum Estimation {
    /// Against the tracker angle of every sample.
    Tracker(TrackerEstimation),
    /// Against a ground truth's frames.
    Truth(TruthEstimation),
}

/// The estimates compared with the tracker: `dlw estimate --json`'s keys.
#[derive(Debug, Clone, Serialize)]
pub struct TrackerEstimation {
    /// The comparison.
    #[serde(flatten)]
    pub metrics: TrackerMetrics,
    /// The estimates file, once the caller has written it.
    pub estimates: Option<PathBuf>,
    /// Things the user should know.
    pub warnings: Vec<String>,
    #[serde(skip)]
    replay: Replay,
    #[serde(skip)]
    recording_name: String,
}

/// The estimates compared with a ground truth: `dlw estimate --truth --json`'s keys.
#[derive(Debug, Clone, Serialize)]
pub struct TruthEstimation {
    /// The comparison with the ground truth.
    pub truth: TruthMetrics,
    /// The comparison with the tracker, `null` for a recording without its angle.
    pub tracker: Option<TrackerMetrics>,
    /// Samples whose estimate carried any flag.
    pub flagged_samples: usize,
    /// Samples held.
    pub held_samples: usize,
    /// Delay of the estimator's filters on a ramp (samples), not compensated in the error.
    pub filter_delay_samples: f64,
    /// The same delay in seconds.
    pub filter_delay_s: f64,
    /// The estimates file, once the caller has written it.
    pub estimates: Option<PathBuf>,
    /// Things the user should know.
    pub warnings: Vec<String>,
    #[serde(skip)]
    replay: TruthReplay,
    #[serde(skip)]
    names: (String, String),
}

/// Runs the request's estimator over its recording and compares the estimates.
///
/// # Errors
/// [`ReplayError::Over`]: the replay's own error (a config the estimator refuses, a sensor the
/// recording lacks, no tracker angle, no ground-truth frame in the recording's span), with
/// what was being compared.
pub fn estimate(request: &EstimateRequest<'_>) -> Result<Estimation, ReplayError> {
    let (config, recording, name) = (request.config, request.recording, request.recording_name);
    match request.truth {
        None => {
            let replay = replay(config, recording).map_err(|e| ReplayError::Over {
                what: format!("estimating over {name}"),
                source: Box::new(e),
            })?;
            Ok(Estimation::Tracker(TrackerEstimation {
                metrics: replay.metrics,
                estimates: None,
                warnings: replay.warnings.clone(),
                replay,
                recording_name: name.to_owned(),
            }))
        }
        Some((truth, truth_name)) => {
            let r =
                replay_against_truth(config, recording, truth).map_err(|e| ReplayError::Over {
                    what: format!("comparing the estimates over {name} with {truth_name}"),
                    source: Box::new(e),
                })?;
            Ok(Estimation::Truth(TruthEstimation {
                truth: r.truth,
                tracker: r.tracker,
                flagged_samples: r.flagged_samples,
                held_samples: r.held_samples,
                filter_delay_samples: r.filter_delay_samples,
                filter_delay_s: r.filter_delay_s,
                estimates: None,
                warnings: r.warnings.clone(),
                replay: r,
                names: (name.to_owned(), truth_name.to_owned()),
            }))
        }
    }
}

impl Estimation {
    /// The estimates as CSV with `decimals` decimal places (`Replay::csv_bytes_with`).
    pub fn csv_bytes(&self, recording: &Recording, decimals: u32) -> Vec<u8> {
        match self {
            Self::Tracker(e) => e.replay.csv_bytes_with(recording, decimals),
            Self::Truth(e) => e.replay.csv_bytes_with(recording, decimals),
        }
    }

    /// Things the user should know, for the terminal's error stream.
    pub fn warnings(&self) -> &[String] {
        match self {
            Self::Tracker(e) => &e.warnings,
            Self::Truth(e) => &e.warnings,
        }
    }

    /// Records where the caller wrote the estimates.
    pub fn set_estimates(&mut self, path: PathBuf) {
        match self {
            Self::Tracker(e) => e.estimates = Some(path),
            Self::Truth(e) => e.estimates = Some(path),
        }
    }

    /// The estimates file, once written.
    fn estimates(&self) -> Option<&PathBuf> {
        match self {
            Self::Tracker(e) => e.estimates.as_ref(),
            Self::Truth(e) => e.estimates.as_ref(),
        }
    }

    /// The metrics as label/value rows, as the terminal and a report show them.
    fn rows(&self) -> Vec<(&'static str, String)> {
        let delay = |samples: f64, seconds: f64| {
            format!("{samples} samples ({seconds:.3} s), not compensated in the error")
        };
        let mut rows = match self {
            Self::Tracker(e) => {
                let m = &e.metrics;
                vec![
                    ("samples", m.samples.to_string()),
                    ("RMSE", format!("{:.3}°", m.rmse_deg)),
                    ("max |error|", format!("{:.3}°", m.max_abs_error_deg)),
                    (
                        "filter delay",
                        delay(m.filter_delay_samples, m.filter_delay_s),
                    ),
                    (
                        "flagged samples",
                        format!("{} ({} held)", m.flagged_samples, m.held_samples),
                    ),
                ]
            }
            Self::Truth(e) => {
                let t = &e.truth;
                vec![
                    (
                        "frames compared",
                        format!(
                            "{} ({} outside the recording, {} without an angle)",
                            t.frames, t.frames_outside, t.frames_without_angle
                        ),
                    ),
                    ("RMSE", format!("{:.3}°", t.rmse_deg)),
                    ("max |error|", format!("{:.3}°", t.max_abs_error_deg)),
                    ("mean error", format!("{:.3}°", t.mean_error_deg)),
                    (
                        "RMSE vs tracker",
                        match &e.tracker {
                            Some(m) => format!("{:.3}° over {} samples", m.rmse_deg, m.samples),
                            None => "— (no tracker angle in the recording)".to_owned(),
                        },
                    ),
                    (
                        "filter delay",
                        delay(e.filter_delay_samples, e.filter_delay_s),
                    ),
                    (
                        "flagged samples",
                        format!("{} ({} held)", e.flagged_samples, e.held_samples),
                    ),
                ]
            }
        };
        if let Some(path) = self.estimates() {
            rows.push(("estimates", path.display().to_string()));
        }
        rows
    }

    /// What was compared: `rec`, or `rec against angles.csv`.
    fn title(&self) -> String {
        match self {
            Self::Tracker(e) => e.recording_name.clone(),
            Self::Truth(e) => format!("{} against {}", e.names.0, e.names.1),
        }
    }
}

impl Analysis for Estimation {
    /// The title, then one line per metric (the warnings are [`Estimation::warnings`]).
    fn summary(&self) -> String {
        let mut out = format!("{}\n", self.title());
        for (label, value) in self.rows() {
            out.push_str(&format!("  {label:<20}{value}\n"));
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        page.heading(at.titled(&format!("Estimates: {}", self.title())));
        page.table(Table {
            header: vec!["".into(), "".into()],
            rows: self
                .rows()
                .into_iter()
                .map(|(label, value)| vec![label.to_owned(), value])
                .collect(),
        });
    }
}
