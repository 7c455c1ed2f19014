//! Importing real bench files (issue 18): a DAQ's file (a CSV export, [`daq_csv`], NI's TDMS,
//! [`tdms`], or a LabVIEW measurement file, [`lvm`]) and an NDI Aurora tracker log ([`ndi`]) become one recording on the DAQ's clock: the bending angle from the
//! tip tool's orientation ([`angle`]), the clocks aligned ([`align`]), the angle resampled onto
//! the DAQ's samples (never across a gap of more than [`MAX_GAP_FRAMES`] missing frames: such
//! rows are written with `tracker_valid = 0`), and an `[import]` table saying where it all came
//! from (`docs/import.md`).

pub mod align;
pub mod angle;
pub mod daq_csv;
pub mod lvm;
pub mod ndi;
pub mod report;
pub mod resample;
pub mod sync;
pub mod tdms;

pub use ndi::{NdiError, ToolFrame, TrackerLog};

use sha2::{Digest, Sha256};

use crate::recording::{ImportInfo, ImportSource, Recording, Rig, Samples};
use align::AlignError;
use angle::{AngleError, BendingAngles};
use daq_csv::{DaqCsvError, DaqTable};
use sync::SyncError;
use tdms::TdmsError;

/// The most missing tracker frames interpolated across.
pub const MAX_GAP_FRAMES: usize = 3;
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
        source: NdiError,
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
    /// `--rate-hz`.
    #[error(transparent)]
    Resample(#[from] resample::ResampleError),
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
    /// The tip tool (1-based, in the log's order).
    pub tool: usize,
    /// A reference tool on the base.
    pub reference_tool: Option<usize>,
    /// The tracker's frame rate (Hz).
    pub tracker_hz: f64,
    /// The still start the rest axis is averaged over (s of tracker time).
    pub rest_s: f64,
    /// How the clocks are aligned.
    pub sync: SyncMethod,
    /// The recording's rate, when not the DAQ's (Hz).
    pub rate_hz: Option<f64>,
}

/// What an import found, as `dlw import-recording --json` prints it.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ImportSummary {
    /// Rows written.
    pub samples: usize,
    /// Length (s).
    pub duration_s: f64,
    /// The clocks.
    pub alignment: AlignmentJson,
    /// The tracker.
    pub tracker: TrackerJson,
    /// Rows whose angle is not a tracker measurement (`tracker_valid = 0`).
    pub invalid_rows: usize,
    /// Warnings.
    pub warnings: Vec<String>,
    /// What the report draws (not in the JSON).
    #[serde(skip)]
    pub trace: ImportTrace,
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
    /// The measured lags `t_daq − τ` (s) against `τ` (s) the line was fitted through: the
    /// windows (`auto`) or the edge pairs (`pulse`). For the report, not in the JSON.
    #[serde(skip)]
    pub lags: Vec<(f64, f64)>,
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

/// Runs an import: the recording (not yet written) and its summary.
///
/// # Errors
/// [`ImportError`].
pub fn import(req: &ImportRequest<'_>) -> Result<(Recording, ImportSummary), ImportError> {
    check_options(req)?;
    let mut names: Vec<&str> = req.voltage_channels.iter().map(String::as_str).collect();
    let stroke_at = names.len();
    names.push(&req.stroke.0);
    if let SyncMethod::Pulse { daq_channel, .. } = &req.sync {
        names.push(daq_channel);
    }
    let daq = read_daq(req, &names).map_err(|source| ImportError::Daq {
        path: req.daq.0.to_owned(),
        source,
    })?;
    let mut tools = vec![req.tool];
    tools.extend(req.reference_tool);
    let log = TrackerLog::parse(req.tracker.1, &tools, req.tracker_hz).map_err(|source| {
        ImportError::Tracker {
            path: req.tracker.0.to_owned(),
            source,
        }
    })?;
    let rest_frames = (req.rest_s * req.tracker_hz).round().max(1.0) as usize;
    let angles: BendingAngles = angle::bending_angles(
        &log.tools[0],
        log.tools.get(1).map(Vec::as_slice),
        rest_frames,
    )?;
    let alignment = clocks(req, &log, &angles, &daq)?;
    let (daq, rate_hz) = match req.rate_hz {
        Some(hz) => (resample::resample(&daq, hz)?, hz),
        None => {
            let hz = daq.rate_hz();
            (daq, hz)
        }
    };
    let (mut angle_deg, valid) = angle_on_daq(&daq.time_s, &log.tau_s, &angles, &alignment);
    let stroke_mm: Vec<f64> = daq.channels[stroke_at]
        .iter()
        .map(|v| v * req.stroke.1)
        .collect();
    let sign = if pulls_positive(&angle_deg, &valid, &stroke_mm) {
        1.0
    } else {
        -1.0
    };
    angle_deg.iter_mut().for_each(|a| *a *= sign);
    let frames = log.tau_s.len();
    let missing = angles.angle_deg.iter().filter(|a| a.is_none()).count();
    let invalid_rows = valid.iter().filter(|v| !**v).count();
    let n = daq.time_s.len();
    let summary = ImportSummary {
        samples: n,
        duration_s: daq.time_s[n - 1],
        alignment: alignment.clone(),
        tracker: TrackerJson {
            frames,
            missing_frames: missing,
            out_of_plane_rms_deg: angles.out_of_plane_rms_deg,
            out_of_plane_max_deg: angles.out_of_plane_max_deg,
        },
        invalid_rows,
        warnings: out_of_plane_warning(&angles).into_iter().collect(),
        trace: ImportTrace {
            tau_s: log.tau_s.clone(),
            angle_deg: angles
                .angle_deg
                .iter()
                .map(|a| a.map(|a| a * sign))
                .collect(),
        },
    };
    let rig = Rig {
        sample_hz: rate_hz,
        supply_v: req.supply_v,
        divider_ohm: req.divider_ohm.clone(),
        notes: None,
        protocol: None,
        simulation: None,
        design: None,
        scenario: None,
        import: Some(provenance(req, &alignment, frames, missing)),
    };
    let samples = Samples {
        volts: daq.channels[..stroke_at].to_vec(),
        time_s: daq.time_s,
        stroke_mm,
        angle_deg,
        tracker_valid: if invalid_rows > 0 { valid } else { Vec::new() },
    };
    Ok((Recording { rig, samples }, summary))
}

/// Checks the options that need no file.
fn check_options(req: &ImportRequest<'_>) -> Result<(), ImportError> {
    let bad = |message: String| Err(ImportError::Options(message));
    if req.voltage_channels.is_empty() || req.voltage_channels.len() > 2 {
        return bad(format!(
            "--voltage names {} channels; a joint has 1 or 2 sensors",
            req.voltage_channels.len()
        ));
    }
    if req.divider_ohm.len() != req.voltage_channels.len() {
        return bad(format!(
            "--divider-ohm gives {} resistors for {} voltage channels",
            req.divider_ohm.len(),
            req.voltage_channels.len()
        ));
    }
    if !(req.supply_v.is_finite() && req.supply_v > 0.0) {
        return bad(format!(
            "--supply-v {} is not a supply voltage (finite and above 0)",
            req.supply_v
        ));
    }
    if !(req.stroke.1.is_finite() && req.stroke.1 != 0.0) {
        return bad(format!(
            "--stroke-mm-per-v {} is not a scale (finite and not 0)",
            req.stroke.1
        ));
    }
    Ok(())
}

/// The tracker's angle at each DAQ time `time_s`, linearly between the frames around it, and
/// whether it is a measurement: not past the log's ends, nor across more than
/// [`MAX_GAP_FRAMES`] missing frames (such rows get 0°, marked invalid).
fn angle_on_daq(
    time_s: &[f64],
    tau_s: &[f64],
    angles: &BendingAngles,
    alignment: &AlignmentJson,
) -> (Vec<f64>, Vec<bool>) {
    let frames = tau_s.len();
    let scale = 1.0 + alignment.drift_ppm * 1e-6;
    let seen = |i: usize| angles.angle_deg[i].is_some();
    let at = |t: f64| {
        let tau = (t - alignment.offset_s) / scale;
        let k = tau_s.partition_point(|&x| x <= tau);
        if k == 0 || k >= frames {
            return None;
        }
        let p = (0..k).rev().find(|&i| seen(i))?;
        let q = (k..frames).find(|&i| seen(i))?;
        if q - p - 1 > MAX_GAP_FRAMES {
            return None;
        }
        let (a, b) = (angles.angle_deg[p]?, angles.angle_deg[q]?);
        let f = (tau - tau_s[p]) / (tau_s[q] - tau_s[p]);
        Some(a + (b - a) * f.clamp(0.0, 1.0))
    };
    time_s
        .iter()
        .map(|&t| at(t).map_or((0.0, false), |a| (a, true)))
        .unzip()
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

/// The `[import]` table: the sources with their SHA-256, the tools, the clocks, the frames.
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
    }
}

/// The channels `names` of the request's DAQ file, in its format.
fn read_daq(req: &ImportRequest<'_>, names: &[&str]) -> Result<DaqTable, DaqError> {
    let (time_column, rate_hz) = (req.time_column.as_deref(), req.daq_rate_hz);
    Ok(match req.daq_format {
        DaqFormat::Csv => {
            let text = std::str::from_utf8(req.daq.1).map_err(DaqError::NotText)?;
            DaqTable::parse(text, names, time_column, rate_hz)?
        }
        DaqFormat::Tdms => tdms::daq_table(req.daq.1, names, time_column, rate_hz)?,
        DaqFormat::Lvm => {
            let text = std::str::from_utf8(req.daq.1).map_err(DaqError::NotText)?;
            lvm::daq_table(text, names, time_column, rate_hz)?
        }
    })
}

/// The clocks, by the request's method: the sync channel is the DAQ table's last.
fn clocks(
    req: &ImportRequest<'_>,
    log: &TrackerLog,
    angles: &BendingAngles,
    daq: &DaqTable,
) -> Result<AlignmentJson, ImportError> {
    let dt_s = 1.0 / daq.rate_hz();
    match &req.sync {
        SyncMethod::Auto => {
            let a = align::auto(&log.tau_s, &angles.angle_deg, &daq.channels[0], dt_s)?;
            Ok(AlignmentJson {
                offset_s: a.offset_s,
                drift_ppm: a.drift_ppm,
                offset_uncertainty_s: a.offset_uncertainty_s,
                drift_uncertainty_ppm: a.drift_uncertainty_ppm,
                method: "auto",
                correlation: Some(a.correlation),
                sync_edges: None,
                lags: a.lags,
            })
        }
        SyncMethod::Pulse { tracker_column, .. } => {
            let levels = sync::tracker_column(req.tracker.1, tracker_column)?;
            let daq_levels = daq.channels.last().map_or(&[][..], Vec::as_slice);
            let daq_edges = sync::rising_edges(&daq.time_s, daq_levels, "DAQ")?;
            let tracker_edges = sync::rising_edges(&log.tau_s, &levels, "tracker")?;
            let a = sync::align(&daq_edges, &tracker_edges, 1.0 / req.tracker_hz)?;
            Ok(AlignmentJson {
                offset_s: a.offset_s,
                drift_ppm: a.drift_ppm,
                offset_uncertainty_s: a.offset_uncertainty_s,
                drift_uncertainty_ppm: a.drift_uncertainty_ppm,
                method: "pulse",
                correlation: None,
                sync_edges: Some(a.edges),
                lags: a.lags,
            })
        }
    }
}
