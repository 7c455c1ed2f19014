//! A sequence of frame fits to a series of angles: frame times, unwrapping, the moving average
//! and the baseline.
//!
//! Frame `k` (in name order, counting skipped frames) is at `time_s = start_s + k/fps`. The
//! fitted frames' axis angles are unwrapped ([`unwrap_axis_deg`](super::unwrap_axis_deg)) into
//! `raw_deg`; the moving average runs over the fitted frames in order (a skipped frame is left
//! out, not filled in), and the baseline's mean is subtracted:
//! `angle_deg = moving_average(raw_deg)_k − baseline`.

use super::analyze::FrameFit;
use super::{baseline, moving_average, unwrap_axis_deg, Baseline, BaselineRule, FluoroError};

/// How a sequence becomes a series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesSettings {
    /// Frames per second.
    pub fps: f64,
    /// Time of the first frame (s).
    pub start_s: f64,
    /// Moving-average width (frames); 1 for none.
    pub smooth: usize,
    /// The baseline window.
    pub baseline: BaselineRule,
}

/// One frame's line of `angles.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Frame time (s).
    pub time_s: f64,
    /// Smoothed angle less the baseline (°); `None` for a skipped frame.
    pub angle_deg: Option<f64>,
    /// Unwrapped, unsmoothed axis angle (°); `None` for a skipped frame.
    pub raw_deg: Option<f64>,
    /// Pixels of the largest component (0 without one).
    pub area_px: u64,
    /// `a/b` of its ellipse, `None` without one.
    pub axis_ratio: Option<f64>,
    /// Why the frame was skipped: `no_pin`, `too_small`, `edge` or `too_round`; empty when
    /// fitted.
    pub flags: Vec<&'static str>,
}

/// The series of a frame sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct AngleSeries {
    /// One row per frame.
    pub rows: Vec<Row>,
    /// The baseline subtracted.
    pub baseline: Baseline,
}

impl AngleSeries {
    /// The series of `fits`, one per frame in order.
    ///
    /// # Errors
    /// [`FluoroError::NoPin`] (carrying `min_area_px` and `min_axis_ratio` for the message) when
    /// no frame was fitted, [`FluoroError::EmptyBaseline`], [`FluoroError::Setting`] for a bad
    /// `fps` or `smooth`.
    pub fn from_fits(
        fits: &[FrameFit],
        settings: &SeriesSettings,
        min_area_px: u32,
        min_axis_ratio: f64,
    ) -> Result<Self, FluoroError> {
        if !(settings.fps.is_finite() && settings.fps > 0.0) {
            return Err(FluoroError::Setting {
                name: "--fps",
                value: settings.fps,
                limit: "finite and greater than 0",
            });
        }
        if settings.smooth == 0 {
            return Err(FluoroError::Setting {
                name: "--smooth",
                value: 0.0,
                limit: "at least 1 frame (1 for no smoothing)",
            });
        }
        let time_s: Vec<f64> = (0..fits.len())
            .map(|k| settings.start_s + k as f64 / settings.fps)
            .collect();
        let axis: Vec<Option<f64>> = fits.iter().map(FrameFit::angle_deg).collect();
        let raw = unwrap_axis_deg(&axis);
        let fitted: Vec<f64> = raw.iter().flatten().copied().collect();
        if fitted.is_empty() {
            return Err(FluoroError::NoPin {
                frames: fits.len(),
                min_area_px,
                min_axis_ratio,
            });
        }
        let base = baseline(&time_s, &raw, settings.baseline)?;
        let mut smoothed = moving_average(&fitted, settings.smooth).into_iter();
        let rows = fits
            .iter()
            .zip(&raw)
            .zip(&time_s)
            .map(|((fit, raw), &t)| {
                let mut flags = Vec::new();
                if let Some(skip) = fit.skip {
                    flags.push(skip.flag());
                }
                Row {
                    time_s: t,
                    angle_deg: raw.and_then(|_| smoothed.next()).map(|a| a - base.mean_deg),
                    raw_deg: *raw,
                    area_px: fit.area_px,
                    axis_ratio: fit.ellipse.map(|e| e.axis_ratio()),
                    flags,
                }
            })
            .collect();
        Ok(Self {
            rows,
            baseline: base,
        })
    }

    /// Frames without a fitted pin.
    pub fn skipped(&self) -> impl Iterator<Item = &Row> {
        self.rows.iter().filter(|r| r.raw_deg.is_none())
    }
}
