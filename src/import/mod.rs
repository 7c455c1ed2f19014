//! Importing real bench files (issues 18 and 30): a DAQ's file (a CSV export, [`daq_csv`], NI's
//! TDMS, [`tdms`], or a LabVIEW measurement file, [`lvm`]) and a tracker log (NDI's own layout
//! or a lab's logger described by a [`map::TrackerMap`], [`tracker`]) become one recording on
//! the DAQ's clock: the bending angle from the tip tool's orientation ([`angle`]), the clocks
//! aligned ([`align`], per stretch of the DAQ's clock, [`stretch`]) and the alignment checked
//! ([`check`]), the angle placed on the DAQ's samples ([`place`]: never across more than
//! [`MAX_GAP_FRAMES`] missing frames, nor across frames absent from the log; such rows are
//! written with `tracker_valid = 0`), every value checked by the recording's own rules before
//! anything is written ([`values`]), and an `[import]` table saying where it all came from
//! (`docs/import.md`). What the import cannot vouch for is refused, saying where and by how
//! much. [`info`] lists what a file holds before importing it (`dlw daq-info`).

pub mod align;
pub mod angle;
pub mod check;
pub mod daq_csv;
pub mod files;
pub mod info;
pub mod lvm;
pub mod map;
pub mod place;
pub mod report;
pub mod resample;
pub mod robot;
pub mod stretch;
pub mod sync;
pub mod tdms;
pub mod tracker;
pub mod values;

pub use map::TrackerMap;
pub use place::MAX_GAP_FRAMES;
pub use tracker::{ToolFrame, TrackerError, TrackerLog};

use std::path::Path;

use sha2::{Digest, Sha256};

use crate::recording::{
    ImportInfo, ImportSource, ImportStretch, Recording, RecordingError, Rig, Samples,
};
use align::{AlignError, Signal};
use angle::{AngleError, BendingAngles};
use check::{AlignmentCheck, CheckError};
use daq_csv::{DaqCsvError, DaqTable};
use stretch::{StretchError, Stretches};
use sync::SyncError;
use tdms::TdmsError;

/// The out-of-plane share of the in-plane range above which a warning is given.
pub const OUT_OF_PLANE_WARNING: f64 = 0.05;

/// The DAQ file's format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DaqFormat {
    /// A CSV export with a header row ([`daq_csv`]).
    Csv,
    /// NI's TDMS ([`tdms`]).
    Tdms,
    /// A LabVIEW measurement file ([`lvm`]).
    Lvm,
}

impl DaqFormat {
    /// The format named `name` (`csv`, `tdms`).
    ///
    /// # Errors
    /// [`ImportError::Options`] naming the formats there are.
    pub fn from_name(name: &str) -> Result<Self, ImportError> {
        match name.to_ascii_lowercase().as_str() {
            "csv" => Ok(DaqFormat::Csv),
            "tdms" => Ok(DaqFormat::Tdms),
            "lvm" => Ok(DaqFormat::Lvm),
            _ => Err(ImportError::Options(format!(
                "--daq-format {name:?} is not one of csv, tdms, lvm"
            ))),
        }
    }

    /// The format a file's extension says (`.tdms`, `.lvm`), CSV otherwise.
    pub fn from_path(path: &std::path::Path) -> Self {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("tdms") => DaqFormat::Tdms,
            Some(e) if e.eq_ignore_ascii_case("lvm") => DaqFormat::Lvm,
            _ => DaqFormat::Csv,
        }
    }
}

/// Why a DAQ file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum DaqError {
    /// A CSV export.
    #[error(transparent)]
    Csv(#[from] DaqCsvError),
    /// A TDMS file.
    #[error(transparent)]
    Tdms(#[from] TdmsError),
    /// A LabVIEW measurement file.
    #[error(transparent)]
    Lvm(#[from] lvm::LvmError),
    /// A text format that is not UTF-8.
    #[error("the DAQ file is not UTF-8 text ({0}); is --daq-format right?")]
    NotText(std::str::Utf8Error),
}

/// Why an import failed.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The DAQ file (its error is the source, printed after the path in an error chain).
    #[error("{path}")]
    Daq {
        /// The file.
        path: String,
        /// Why.
        source: DaqError,
    },
    /// The tracker log (its error is the source, printed after the path in an error chain).
    #[error("{path}")]
    Tracker {
        /// The file.
        path: String,
        /// Why.
        source: TrackerError,
    },
    /// A value in the DAQ file that the recording's readers refuse.
    #[error("{0}")]
    Value(String),
    /// The DAQ's clock: a stretch between jumps too short to align.
    #[error(transparent)]
    Stretch(#[from] StretchError),
    /// The tracker's clock jumps by more than the whole recording.
    #[error("{path} line {line}: the tracker's clock jumps by {seconds:.1} s ({frames:.0} frames absent), longer than the DAQ's whole recording ({duration_s:.1} s): not a gap in one run (a logger restarted, a counter that wrapped, two runs in one file?); cut the log at that line")]
    Jump {
        /// The tracker log.
        path: String,
        /// The line after the jump.
        line: usize,
        /// The jump (s).
        seconds: f64,
        /// Frames absent.
        frames: f64,
        /// The DAQ's duration (s).
        duration_s: f64,
    },
    /// The bending angle.
    #[error(transparent)]
    Angle(#[from] AngleError),
    /// The clocks (`--sync auto`).
    #[error(transparent)]
    Align(#[from] AlignError),
    /// The clocks (`--sync CH`).
    #[error(transparent)]
    Sync(#[from] SyncError),
    /// The check after the alignment.
    #[error(transparent)]
    Check(#[from] CheckError),
    /// `--rate-hz`.
    #[error(transparent)]
    Resample(#[from] resample::ResampleError),
    /// The recording to be written breaks its readers' rules.
    #[error("the recording to be written would be refused by its readers: {0}")]
    Recording(#[from] RecordingError),
    /// A robot joint's angle ([`robot`]).
    #[error("joint {joint} (tool {tool}, in the frame of {frame})")]
    Joint {
        /// The joint (1-based, 1 distal).
        joint: usize,
        /// Its tool.
        tool: usize,
        /// The frame its angle is taken in.
        frame: String,
        /// Why.
        source: AngleError,
    },
    /// Bad options.
    #[error("{0}")]
    Options(String),
}

/// What to import.
#[derive(Debug, Clone)]
pub struct ImportRequest<'a> {
    /// The DAQ file's path (for messages and provenance) and bytes.
    pub daq: (&'a str, &'a [u8]),
    /// The DAQ file's format.
    pub daq_format: DaqFormat,
    /// The voltage channels, sensor 1 first.
    pub voltage_channels: Vec<String>,
    /// The divider resistors, one per voltage channel (Ω).
    pub divider_ohm: Vec<f64>,
    /// The divider supply (V).
    pub supply_v: f64,
    /// The stroke channel and its scale (mm per V).
    pub stroke: (String, f64),
    /// The DAQ's time column, if not found by name.
    pub time_column: Option<String>,
    /// The DAQ's rate when it has no time column (Hz).
    pub daq_rate_hz: Option<f64>,
    /// The tracker log's path and text.
    pub tracker: (&'a str, &'a str),
    /// How to read the tracker log (`None`: NDI's own layout).
    pub tracker_map: Option<&'a TrackerMap>,
    /// The tip tool (1-based, in the log's order).
    pub tool: usize,
    /// A reference tool on the base.
    pub reference_tool: Option<usize>,
    /// The tracker's frame rate (Hz), when given; else measured from the log's time columns,
    /// else [`tracker::DEFAULT_TRACKER_HZ`].
    pub tracker_hz: Option<f64>,
    /// The still start the rest axis is averaged over (s of tracker time).
    pub rest_s: f64,
    /// How the clocks are aligned.
    pub sync: SyncMethod,
    /// The largest clock offset `--sync auto` searches (s).
    pub max_offset_s: f64,
    /// The recording's rate, when not the DAQ's (Hz).
    pub rate_hz: Option<f64>,
}

/// What an import found: its JSON ([`ImportSummary::to_json`]) is `dlw import-recording
/// --json`, its [`ImportSummary::summary`] the command's line.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ImportSummary {
    /// Where the recording was written, as the caller names it (set by the caller that writes
    /// it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<String>,
    /// Rows written.
    pub samples: usize,
    /// Length (s).
    pub duration_s: f64,
    /// The clocks.
    pub alignment: AlignmentJson,
    /// The tracker.
    pub tracker: TrackerJson,
    /// The check after the alignment.
    pub check: AlignmentCheck,
    /// Rows whose angle is not a tracker measurement (`tracker_valid = 0`).
    pub invalid_rows: usize,
    /// Warnings.
    pub warnings: Vec<String>,
    /// What the report draws (not in the JSON).
    #[serde(skip)]
    pub trace: ImportTrace,
}

impl ImportSummary {
    /// The JSON `dlw import-recording --json` prints: the summary, its keys sorted as every
    /// analysis's (`serde_json`'s map), the report's trace left out.
    ///
    /// # Errors
    /// When the summary does not serialize.
    pub fn to_json(&self) -> Result<serde_json::Value, serde_json::Error> {
        serde_json::to_value(self)
    }

    /// The line `dlw import-recording` prints: where the recording went, its length, the
    /// clocks, the check and the tracker, every number taken from the summary.
    pub fn summary(&self) -> String {
        let a = &self.alignment;
        format!(
            "wrote {}: {} samples over {:.1} s; clocks: offset {:.4} ± {:.4} s, drift {:.1} ± {:.1} ppm ({}{}); checked in {} windows (worst {:.2}° RMS, limit {:.2}°); tracker: {} frames, {} missing, {} gaps, out of plane {:.2}° RMS; {} rows without a tracker angle (tracker_valid = 0)\n",
            self.recording.as_deref().unwrap_or("the recording"),
            self.samples,
            self.duration_s,
            a.offset_s,
            a.offset_uncertainty_s,
            a.drift_ppm,
            a.drift_uncertainty_ppm,
            match (a.correlation, a.sync_edges) {
                (Some(r), _) => format!("r = {r:.3}"),
                (None, Some(n)) => format!("{n} sync edges"),
                (None, None) => String::new(),
            },
            if a.stretches.len() > 1 {
                format!(
                    "; {} stretches of the DAQ's clock, each aligned on its own",
                    a.stretches.len()
                )
            } else {
                String::new()
            },
            self.check.windows,
            self.check.worst.rms_deg,
            self.check.worst.limit_deg,
            self.tracker.frames,
            self.tracker.missing_frames,
            self.tracker.gaps,
            self.tracker.out_of_plane_rms_deg,
            self.invalid_rows
        )
    }
}

/// The tracker's side of an import, for the report ([`report`]).
#[derive(Debug, Clone, Default)]
pub struct ImportTrace {
    /// Each frame's tracker time `τ` (s from its first frame).
    pub tau_s: Vec<f64>,
    /// Each frame's bending angle (°, signed as in the recording; `None`: the tool missing).
    pub angle_deg: Vec<Option<f64>>,
}

/// `alignment` in the JSON.
#[derive(Debug, Clone, serde::Serialize)]
pub struct AlignmentJson {
    /// `t_daq = offset_s + τ·(1 + drift_ppm·10⁻⁶)`.
    pub offset_s: f64,
    /// Drift (ppm).
    pub drift_ppm: f64,
    /// Standard error (s).
    pub offset_uncertainty_s: f64,
    /// Standard error (ppm).
    pub drift_uncertainty_ppm: f64,
    /// `auto` (cross-correlation) or `pulse` (a sync channel).
    pub method: &'static str,
    /// `auto`: the whole-recording correlation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub correlation: Option<f64>,
    /// `pulse`: the sync edges paired.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sync_edges: Option<usize>,
    /// The stretches of the DAQ's clock, each aligned on its own (one when the DAQ's time
    /// column never jumps); the figures above are the longest stretch's.
    pub stretches: Vec<StretchJson>,
    /// The measured lags `t_daq − τ` (s) against `τ` (s) the lines were fitted through: the
    /// windows (`auto`) or the edge pairs (`pulse`). For the report, not in the JSON.
    #[serde(skip)]
    pub lags: Vec<(f64, f64)>,
}

/// One stretch of the DAQ's clock and its alignment, in the JSON.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StretchJson {
    /// Its first sample's DAQ time (s).
    pub from_s: f64,
    /// Its last sample's DAQ time (s).
    pub to_s: f64,
    /// `t_daq = offset_s + τ·(1 + drift_ppm·10⁻⁶)` in this stretch.
    pub offset_s: f64,
    /// Drift (ppm).
    pub drift_ppm: f64,
    /// Standard error (s).
    pub offset_uncertainty_s: f64,
    /// Standard error (ppm).
    pub drift_uncertainty_ppm: f64,
}

impl StretchJson {
    /// The DAQ time of tracker time `tau_s` by this stretch's clocks.
    pub fn daq_time(&self, tau_s: f64) -> f64 {
        self.offset_s + tau_s * (1.0 + self.drift_ppm * 1e-6)
    }

    /// The tracker time of DAQ time `t_s` by this stretch's clocks.
    pub fn tracker_time(&self, t_s: f64) -> f64 {
        (t_s - self.offset_s) / (1.0 + self.drift_ppm * 1e-6)
    }

    /// Whether DAQ time `t_s` lies in this stretch.
    pub fn holds(&self, t_s: f64) -> bool {
        (self.from_s..=self.to_s).contains(&t_s)
    }
}

/// How the clocks are aligned.
#[derive(Debug, Clone, PartialEq)]
pub enum SyncMethod {
    /// Cross-correlating the angle with sensor 1's voltage ([`align`]).
    Auto,
    /// A TTL pulse on a DAQ channel and in a tracker log column ([`sync`]).
    Pulse {
        /// The DAQ channel.
        daq_channel: String,
        /// The tracker log's column.
        tracker_column: String,
    },
}

/// `tracker` in the JSON.
#[derive(Debug, Clone, serde::Serialize)]
pub struct TrackerJson {
    /// Frames logged.
    pub frames: usize,
    /// Frames with the tool (or the reference) missing.
    pub missing_frames: usize,
    /// Steps of the log where frames are absent (more than 1.5 frame periods).
    pub gaps: usize,
    /// Frames absent in them.
    pub absent_frames: f64,
    /// The tracker's frame rate used (Hz).
    pub rate_hz: f64,
    /// Out-of-plane RMS (°).
    pub out_of_plane_rms_deg: f64,
    /// Out-of-plane maximum (°).
    pub out_of_plane_max_deg: f64,
}

fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// Runs an import: the recording (not yet written, every value checked by its readers' rules)
/// and its summary.
///
/// # Errors
/// [`ImportError`].
pub fn import(req: &ImportRequest<'_>) -> Result<(Recording, ImportSummary), ImportError> {
    values::check_options(req)?;
    let columns = DaqColumns::of(req, &[req.stroke.0.as_str()]);
    let daq = read_daq(req, &columns.names).map_err(|source| ImportError::Daq {
        path: req.daq.0.to_owned(),
        source,
    })?;
    values::check_daq(req, &daq, &columns.names, &[req.stroke.1])?;
    values::check_rate(req, &daq)?;
    let stretches = stretch::stretches(&daq.time_s)?;
    let mut tools = vec![req.tool];
    tools.extend(req.reference_tool);
    let log = read_tracker(req, &tools, columns.sync_column)?;
    refuse_jumps(req, &log, daq.time_s[daq.time_s.len() - 1])?;
    let angles: BendingAngles = angle::bending_angles(
        &log.tools[0],
        log.tools.get(1).map(Vec::as_slice),
        &log.tau_s,
        req.rest_s,
    )?;
    let alignment = clocks(req, &log, &angles, &daq, &stretches)?;
    let check = check::check(
        &place::aligned_frames(&log, &angles, &alignment.stretches),
        &Signal {
            time_s: &daq.time_s,
            values: &daq.channels[0],
            period_s: stretches.period_s,
        },
    )?;
    let (daq, rate_hz) = match req.rate_hz {
        Some(hz) => (resample::resample(&daq, hz)?, hz),
        None => {
            let hz = daq.rate_hz();
            (daq, hz)
        }
    };
    let (mut angle_deg, valid) =
        place::angle_on_daq(&daq.time_s, &log, &angles, &alignment.stretches);
    let stroke_mm: Vec<f64> = daq.channels[columns.stroke_at]
        .iter()
        .map(|v| v * req.stroke.1)
        .collect();
    let sign = if pulls_positive(&angle_deg, &valid, &stroke_mm) {
        1.0
    } else {
        -1.0
    };
    angle_deg.iter_mut().for_each(|a| *a *= sign);
    let invalid_rows = valid.iter().filter(|v| !**v).count();
    let summary = summary(
        &daq.time_s,
        &log,
        &angles,
        sign,
        &alignment,
        check,
        invalid_rows,
    );
    let rig = Rig {
        sample_hz: rate_hz,
        supply_v: req.supply_v,
        divider_ohm: req.divider_ohm.clone(),
        notes: None,
        protocol: None,
        simulation: None,
        design: None,
        scenario: None,
        import: Some(provenance(
            req,
            &alignment,
            summary.tracker.frames,
            summary.tracker.missing_frames,
        )),
    };
    let samples = Samples {
        volts: daq.channels[..columns.stroke_at].to_vec(),
        time_s: daq.time_s,
        stroke_mm,
        angle_deg,
        tracker_valid: if invalid_rows > 0 { valid } else { Vec::new() },
    };
    let recording = Recording { rig, samples };
    recording.check()?;
    let mut summary = summary;
    summary.warnings.extend(refused_by_analyses(
        recording.check_measured(Path::new(IMPORTED)),
    ));
    Ok((recording, summary))
}

/// How an import's warnings name the recording it wrote (the folder is the caller's).
pub(crate) const IMPORTED: &str = "the imported recording";

/// A warning for what `fit`, `discover` and `characterize` will refuse in an imported recording
/// (`Recording::check_measured`: a column clipped or frozen, the tracker's clock off the
/// DAQ's). The import writes it all the same: it is what the instruments gave, and `estimate`
/// reads it.
pub(crate) fn refused_by_analyses(check: Result<(), RecordingError>) -> Option<String> {
    check.err().map(|e| {
        format!("{e}. The recording is written as the instruments gave it, and the analyses that fit a model to it (`dlw fit`, `discover`, `characterize`) will refuse it")
    })
}

/// The DAQ channels an import reads, in the DAQ table's order: the voltages, the strokes (one
/// for a joint, one per joint for a robot), then a sync pulse's channel.
struct DaqColumns<'a> {
    /// The channels' names.
    names: Vec<&'a str>,
    /// The first stroke's index in `names` (the voltages come before it).
    stroke_at: usize,
    /// With a sync pulse: the tracker log's column holding it.
    sync_column: Option<&'a str>,
}

impl<'a> DaqColumns<'a> {
    /// The channels the request names, with the stroke channels `strokes`.
    fn of(req: &'a ImportRequest<'_>, strokes: &[&'a str]) -> Self {
        let mut names: Vec<&str> = req.voltage_channels.iter().map(String::as_str).collect();
        let stroke_at = names.len();
        names.extend_from_slice(strokes);
        let sync_column = match &req.sync {
            SyncMethod::Pulse {
                daq_channel,
                tracker_column,
            } => {
                names.push(daq_channel);
                Some(tracker_column.as_str())
            }
            SyncMethod::Auto => None,
        };
        DaqColumns {
            names,
            stroke_at,
            sync_column,
        }
    }
}

/// The request's tracker log: the tools `tools` (1-based, the first the tip, whose frame
/// counter is read), and the sync pulse's column.
fn read_tracker(
    req: &ImportRequest<'_>,
    tools: &[usize],
    sync_column: Option<&str>,
) -> Result<TrackerLog, ImportError> {
    TrackerLog::parse(
        req.tracker.1,
        req.tracker_map,
        &tracker::ReadOptions {
            tools,
            frame_hz: req.tracker_hz,
            extra_column: sync_column,
        },
    )
    .map_err(|source| ImportError::Tracker {
        path: req.tracker.0.to_owned(),
        source,
    })
}

/// Refuses a jump of the tracker's clock longer than the DAQ's whole recording (`duration_s`).
fn refuse_jumps(
    req: &ImportRequest<'_>,
    log: &TrackerLog,
    duration_s: f64,
) -> Result<(), ImportError> {
    match log.gaps.iter().find(|g| g.seconds > duration_s) {
        Some(g) => Err(ImportError::Jump {
            path: req.tracker.0.to_owned(),
            line: g.line,
            seconds: g.seconds,
            frames: g.frames,
            duration_s,
        }),
        None => Ok(()),
    }
}

/// The summary of an import whose rows are at `time_s` and whose angle is signed by `sign`.
fn summary(
    time_s: &[f64],
    log: &TrackerLog,
    angles: &BendingAngles,
    sign: f64,
    alignment: &AlignmentJson,
    check: AlignmentCheck,
    invalid_rows: usize,
) -> ImportSummary {
    let n = time_s.len();
    let mut warnings = log.warnings.clone();
    warnings.extend(out_of_plane_warning(angles));
    ImportSummary {
        recording: None,
        samples: n,
        duration_s: time_s[n - 1],
        alignment: alignment.clone(),
        tracker: TrackerJson {
            frames: log.tau_s.len(),
            missing_frames: angles.angle_deg.iter().filter(|a| a.is_none()).count(),
            gaps: log.gaps.len(),
            absent_frames: log.gaps.iter().fold(0.0, |n, g| n + g.frames),
            rate_hz: log.rate_hz,
            out_of_plane_rms_deg: angles.out_of_plane_rms_deg,
            out_of_plane_max_deg: angles.out_of_plane_max_deg,
        },
        check,
        invalid_rows,
        warnings,
        trace: ImportTrace {
            tau_s: log.tau_s.clone(),
            angle_deg: angles
                .angle_deg
                .iter()
                .map(|a| a.map(|a| a * sign))
                .collect(),
        },
    }
}

/// Whether the angle rises with the stroke over the valid rows (pulling the tendon bends
/// positive), by the sign of their covariance.
fn pulls_positive(angle_deg: &[f64], valid: &[bool], stroke_mm: &[f64]) -> bool {
    let rows: Vec<usize> = (0..angle_deg.len()).filter(|&i| valid[i]).collect();
    let mean = |x: &[f64]| rows.iter().map(|&i| x[i]).sum::<f64>() / rows.len().max(1) as f64;
    let (ma, ms) = (mean(angle_deg), mean(stroke_mm));
    rows.iter()
        .map(|&i| (angle_deg[i] - ma) * (stroke_mm[i] - ms))
        .sum::<f64>()
        >= 0.0
}

/// The warning when the tip leaves its bending plane by more than [`OUT_OF_PLANE_WARNING`] of
/// the in-plane range.
fn out_of_plane_warning(angles: &BendingAngles) -> Option<String> {
    (angles.out_of_plane_rms_deg > OUT_OF_PLANE_WARNING * angles.in_plane_range_deg).then(|| {
        format!(
            "the tip moves out of its bending plane by {:.2}° RMS ({:.2}° at most), more than {:.0} % of the in-plane range of {:.1}°: is the joint twisting, or the tool loose?",
            angles.out_of_plane_rms_deg,
            angles.out_of_plane_max_deg,
            OUT_OF_PLANE_WARNING * 100.0,
            angles.in_plane_range_deg
        )
    })
}

/// The `[import]` table: the sources with their SHA-256, the tools, the clocks (the longest
/// stretch's, and every stretch when there are several), the frames.
fn provenance(
    req: &ImportRequest<'_>,
    alignment: &AlignmentJson,
    frames: usize,
    missing: usize,
) -> ImportInfo {
    ImportInfo {
        dlw_version: env!("CARGO_PKG_VERSION").to_owned(),
        sources: vec![
            ImportSource {
                role: "daq".into(),
                path: req.daq.0.to_owned(),
                sha256: sha256(req.daq.1),
            },
            ImportSource {
                role: "tracker".into(),
                path: req.tracker.0.to_owned(),
                sha256: sha256(req.tracker.1.as_bytes()),
            },
        ],
        tool: req.tool as u32,
        reference_tool: req.reference_tool.map(|t| t as u32),
        alignment_method: alignment.method.into(),
        offset_s: alignment.offset_s,
        drift_ppm: alignment.drift_ppm,
        offset_uncertainty_s: alignment.offset_uncertainty_s,
        drift_uncertainty_ppm: alignment.drift_uncertainty_ppm,
        tracker_frames: frames as u64,
        missing_frames: missing as u64,
        stretches: if alignment.stretches.len() > 1 {
            alignment
                .stretches
                .iter()
                .map(|s| ImportStretch {
                    from_s: s.from_s,
                    to_s: s.to_s,
                    offset_s: s.offset_s,
                    drift_ppm: s.drift_ppm,
                })
                .collect()
        } else {
            Vec::new()
        },
        joint_tools: Vec::new(),
    }
}

/// The channels `names` of the request's DAQ file, in its format.
fn read_daq(req: &ImportRequest<'_>, names: &[&str]) -> Result<DaqTable, DaqError> {
    let (time_column, rate_hz) = (req.time_column.as_deref(), req.daq_rate_hz);
    Ok(match req.daq_format {
        DaqFormat::Csv => DaqTable::parse(&text(req.daq.1)?, names, time_column, rate_hz)?,
        DaqFormat::Tdms => tdms::daq_table(req.daq.1, names, time_column, rate_hz)?,
        DaqFormat::Lvm => lvm::daq_table(&text(req.daq.1)?, names, time_column, rate_hz)?,
    })
}

/// A text DAQ file's bytes as text, without a UTF-8 byte-order mark (which Windows programs
/// write before the header).
pub(crate) fn text(bytes: &[u8]) -> Result<std::borrow::Cow<'_, str>, DaqError> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(std::borrow::Cow::Borrowed(
            text.strip_prefix(crate::output::UTF8_BOM).unwrap_or(text),
        )),
        // LabVIEW on Windows writes the system's code page (a µ, a ° in a comment): read as
        // Latin-1, one character per byte, when the file is plain ASCII text but for a few
        // bytes; the numbers are ASCII either way.
        Err(e) => {
            let ascii = bytes.iter().filter(|b| b.is_ascii()).count();
            if ascii * 100 >= bytes.len() * 99 && !bytes.contains(&0) {
                Ok(std::borrow::Cow::Owned(
                    bytes.iter().map(|&b| char::from(b)).collect(),
                ))
            } else {
                Err(DaqError::NotText(e))
            }
        }
    }
}

/// The clocks, by the request's method: `--sync auto` aligns each stretch of the DAQ's clock
/// on its own; a sync pulse gives one alignment (its edges are timed on the DAQ's time column
/// as it is), which every stretch shares. The sync channel is the DAQ table's last.
fn clocks(
    req: &ImportRequest<'_>,
    log: &TrackerLog,
    angles: &BendingAngles,
    daq: &DaqTable,
    stretches: &Stretches,
) -> Result<AlignmentJson, ImportError> {
    let span = |rows: &std::ops::Range<usize>| (daq.time_s[rows.start], daq.time_s[rows.end - 1]);
    match &req.sync {
        SyncMethod::Auto => {
            let mut parts = Vec::with_capacity(stretches.rows.len());
            let mut lags = Vec::new();
            let mut main: Option<(f64, align::Alignment)> = None;
            for rows in &stretches.rows {
                let signal = Signal {
                    time_s: &daq.time_s[rows.clone()],
                    values: &daq.channels[0][rows.clone()],
                    period_s: stretches.period_s,
                };
                let a = align::auto(&log.tau_s, &angles.angle_deg, &signal, req.max_offset_s)?;
                let (from_s, to_s) = span(rows);
                parts.push(StretchJson {
                    from_s,
                    to_s,
                    offset_s: a.offset_s,
                    drift_ppm: a.drift_ppm,
                    offset_uncertainty_s: a.offset_uncertainty_s,
                    drift_uncertainty_ppm: a.drift_uncertainty_ppm,
                });
                lags.extend(a.lags.iter().copied());
                if main
                    .as_ref()
                    .map_or(true, |(length, _)| to_s - from_s > *length)
                {
                    main = Some((to_s - from_s, a));
                }
            }
            let Some((_, a)) = main else {
                unreachable!("a DAQ table has at least one stretch")
            };
            Ok(AlignmentJson {
                offset_s: a.offset_s,
                drift_ppm: a.drift_ppm,
                offset_uncertainty_s: a.offset_uncertainty_s,
                drift_uncertainty_ppm: a.drift_uncertainty_ppm,
                method: "auto",
                correlation: Some(a.correlation),
                sync_edges: None,
                stretches: parts,
                lags,
            })
        }
        SyncMethod::Pulse { .. } => {
            let daq_levels = daq.channels.last().map_or(&[][..], Vec::as_slice);
            let daq_edges = sync::rising_edges(&daq.time_s, daq_levels, "DAQ")?;
            let tracker_edges = sync::rising_edges(&log.tau_s, &log.extra, "tracker")?;
            let a = sync::align(&daq_edges, &tracker_edges, 1.0 / log.rate_hz)?;
            let parts = stretches
                .rows
                .iter()
                .map(|rows| {
                    let (from_s, to_s) = span(rows);
                    StretchJson {
                        from_s,
                        to_s,
                        offset_s: a.offset_s,
                        drift_ppm: a.drift_ppm,
                        offset_uncertainty_s: a.offset_uncertainty_s,
                        drift_uncertainty_ppm: a.drift_uncertainty_ppm,
                    }
                })
                .collect();
            Ok(AlignmentJson {
                offset_s: a.offset_s,
                drift_ppm: a.drift_ppm,
                offset_uncertainty_s: a.offset_uncertainty_s,
                drift_uncertainty_ppm: a.drift_uncertainty_ppm,
                method: "pulse",
                correlation: None,
                sync_edges: Some(a.edges),
                stretches: parts,
                lags: a.lags,
            })
        }
    }
}
