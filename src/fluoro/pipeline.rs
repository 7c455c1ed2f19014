//! `dlw fluoro` as a library call: a folder of frames to `angles.csv`, its overlays and a
//! [`FluoroSummary`], with every check the command makes.

use std::path::{Path, PathBuf};

use super::{
    analyze_folder, angles_csv_bytes, AngleSeries, BaselineRule, FluoroError, FluoroSummary,
    SeriesSettings, Settings, StagedFolder,
};
use crate::limits;
use crate::output::write_atomic;

impl BaselineRule {
    /// The rule the command line asks for: `--baseline-s T` (0 for none) or, without it, the
    /// mean before the angle departs by more than `motion_deg`.
    pub fn from_options(baseline_s: Option<f64>, motion_deg: f64) -> Result<Self, FluoroError> {
        match baseline_s {
            Some(t) if !(t.is_finite() && t >= 0.0) => Err(FluoroError::Option {
                flag: "--baseline-s",
                value: t,
                limit: "finite and at least 0",
            }),
            Some(0.0) => Ok(Self::Off),
            Some(t) => Ok(Self::Seconds(t)),
            None if !(motion_deg.is_finite() && motion_deg > 0.0) => Err(FluoroError::Option {
                flag: "--motion-deg",
                value: motion_deg,
                limit: "finite and greater than 0",
            }),
            None => Ok(Self::UntilMotion {
                threshold_deg: motion_deg,
            }),
        }
    }
}

/// What `dlw fluoro` is asked to do.
#[derive(Debug, Clone)]
pub struct FluoroRequest<'a> {
    /// The folder of frames.
    pub frames: &'a Path,
    /// How each frame is analyzed.
    pub settings: Settings,
    /// How the frames become a series.
    pub series: SeriesSettings,
    /// `angles.csv`.
    pub output: &'a Path,
    /// The overlay folder, if one is asked for.
    pub overlay: Option<&'a Path>,
    /// Replace an existing overlay folder.
    pub force: bool,
}

/// A folder analyzed and written: the summary `--json` prints, and what the text needs.
#[derive(Debug, Clone)]
pub struct Fluoro {
    /// The series in numbers.
    pub summary: FluoroSummary,
    /// The frames folder, as given.
    pub frames: PathBuf,
    /// The baseline rule the series used.
    pub baseline: BaselineRule,
}

impl serde::Serialize for Fluoro {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.summary.serialize(serializer)
    }
}

/// Analyzes `request.frames`, writes the overlays (if asked) and then `angles.csv`. Checks the
/// frame rate, start time and the CSV's folder before any frame is read, so that nothing is
/// written by a run that fails.
pub fn fluoro(request: &FluoroRequest) -> Result<Fluoro, FluoroError> {
    check_series(&request.series)?;
    check_output_folder(request.output)?;
    let overlay = request
        .overlay
        .map(|dir| StagedFolder::create(dir, request.force))
        .transpose()?;
    let analyzing = |source| FluoroError::Analyzing {
        frames: request.frames.to_path_buf(),
        source: Box::new(source),
    };
    let folder =
        analyze_folder(request.frames, &request.settings, overlay.as_ref()).map_err(analyzing)?;
    let series = AngleSeries::from_fits(
        &folder.fits,
        &request.series,
        request.settings.min_area_px,
        request.settings.min_axis_ratio,
    )
    .map_err(analyzing)?;
    if let Some(o) = overlay {
        o.finish()?;
    }
    write_atomic(request.output, &angles_csv_bytes(&series))?;
    Ok(Fluoro {
        summary: FluoroSummary::of(
            &folder,
            &series,
            request.output.to_path_buf(),
            request.overlay.map(Path::to_path_buf),
        ),
        frames: request.frames.to_path_buf(),
        baseline: request.series.baseline,
    })
}

fn check_series(series: &SeriesSettings) -> Result<(), FluoroError> {
    let limit = |message| FluoroError::Limit { message };
    limits::within(
        "--fps",
        series.fps,
        limits::MIN_FPS,
        limits::MAX_FPS,
        "frames per second",
    )
    .map_err(limit)?;
    limits::within(
        "--start-s",
        series.start_s,
        -limits::MAX_ABS_START_S,
        limits::MAX_ABS_START_S,
        "s",
    )
    .map_err(limit)?;
    Ok(())
}

/// The CSV is written last, after the overlay folder is in place: its folder is checked first
/// so that a typo there cannot leave overlays without angles.
fn check_output_folder(output: &Path) -> Result<(), FluoroError> {
    let folder = match output.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if folder.is_dir() {
        Ok(())
    } else {
        Err(FluoroError::NoOutputFolder {
            output: output.to_path_buf(),
            folder: folder.to_path_buf(),
        })
    }
}

impl Fluoro {
    /// One warning per skipped frame.
    pub fn warnings(&self) -> Vec<String> {
        self.summary
            .skipped
            .iter()
            .map(|s| {
                format!(
                    "frame {} (t = {:.3} s) skipped: {}",
                    s.frame, s.time_s, s.flags
                )
            })
            .collect()
    }

    /// The text `dlw fluoro` prints.
    pub fn text(&self) -> String {
        let s = &self.summary;
        let mut out = format!("{}\n", self.frames.display());
        out += &format!(
            "  frames              {} ({}×{} px, {}-bit), {} fitted, {} skipped\n",
            s.frames,
            s.width_px,
            s.height_px,
            s.bits,
            s.fitted,
            s.skipped.len()
        );
        out += &match self.baseline {
            BaselineRule::Off => "  baseline            none\n".to_string(),
            _ => format!(
                "  baseline            {:.3}° (mean of {} frame(s){})\n",
                s.baseline_deg,
                s.baseline_frames,
                s.baseline_end_s
                    .map_or_else(String::new, |t| format!(" before {t:.3} s"))
            ),
        };
        out += &format!(
            "  angle               {:.2}° to {:.2}°\n",
            s.angle_min_deg, s.angle_max_deg
        );
        out += &format!("  angles              {}\n", s.output.display());
        if let Some(o) = &s.overlay {
            out += &format!("  overlays            {}\n", o.display());
        }
        out
    }
}
