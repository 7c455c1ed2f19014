//! What `dlw fluoro` reports about a folder's series: frames fitted and skipped, the image
//! format, the baseline and the angle range. Its JSON is what `dlw fluoro --json` prints.

use std::path::PathBuf;

use serde::Serialize;

use super::{AngleSeries, FolderFits};

/// A frame without a fitted pin.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Skipped {
    /// The frame's file name.
    pub frame: String,
    /// Its time (s).
    pub time_s: f64,
    /// Why, as `|`-joined flags (`no_pin`, `too_small`, `edge`, `too_round`).
    pub flags: String,
}

/// A folder's series in numbers. The JSON keys are part of the interface.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FluoroSummary {
    /// Frames in the folder.
    pub frames: usize,
    /// Frames with a fitted pin.
    pub fitted: usize,
    /// The others, in order.
    pub skipped: Vec<Skipped>,
    /// Frame width (px).
    pub width_px: u32,
    /// Frame height (px).
    pub height_px: u32,
    /// Bits per pixel.
    pub bits: u32,
    /// The baseline subtracted (°).
    pub baseline_deg: f64,
    /// Frames averaged into it.
    pub baseline_frames: usize,
    /// Time (s) the baseline ends at, if it ends before the series does.
    pub baseline_end_s: Option<f64>,
    /// Smallest angle less the baseline (°); +∞ when no frame was fitted.
    pub angle_min_deg: f64,
    /// Largest angle less the baseline (°); −∞ when no frame was fitted.
    pub angle_max_deg: f64,
    /// `angles.csv`, as the caller wrote it.
    pub output: PathBuf,
    /// The overlay folder, as the caller wrote it.
    pub overlay: Option<PathBuf>,
}

impl FluoroSummary {
    /// The summary of `series`, computed from `folder`'s fits, written to `output` (and its
    /// overlays to `overlay`).
    pub fn of(
        folder: &FolderFits,
        series: &AngleSeries,
        output: PathBuf,
        overlay: Option<PathBuf>,
    ) -> Self {
        let skipped: Vec<Skipped> = series
            .rows
            .iter()
            .zip(&folder.names)
            .filter(|(r, _)| r.raw_deg.is_none())
            .map(|(r, name)| Skipped {
                frame: name.clone(),
                time_s: r.time_s,
                flags: r.flags.join("|"),
            })
            .collect();
        let angles = series.rows.iter().filter_map(|r| r.angle_deg);
        let (lo, hi) = angles.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
        let b = series.baseline;
        Self {
            frames: series.rows.len(),
            fitted: series.rows.len() - skipped.len(),
            skipped,
            width_px: folder.dimensions.0,
            height_px: folder.dimensions.1,
            bits: folder.bits,
            baseline_deg: b.mean_deg,
            baseline_frames: b.frames,
            baseline_end_s: b.end_s,
            angle_min_deg: lo,
            angle_max_deg: hi,
            output,
            overlay,
        }
    }
}
