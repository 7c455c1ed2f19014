//! Where a recording came from: simulated (the `dlw` version, the design's checksum, and the
//! design and scenario as TOML tables in `rig.toml`) or imported (the source files with their
//! SHA-256, the tracker tool, the clock alignment and the missing tracker frames).
//!
//! Both are plain data: this module knows nothing of the simulator or the importer.

use serde::{Deserialize, Serialize};

/// `[simulation]` of a simulated recording.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationInfo {
    /// The `dlw` version that simulated.
    pub dlw_version: String,
    /// The design's checksum (as in program headers).
    pub design_checksum: String,
}

/// One source file of an imported recording.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportSource {
    /// What the file held: `daq`, `tracker` or `stroke`.
    pub role: String,
    /// The path as given on the command line.
    pub path: String,
    /// The file's SHA-256, lowercase hex.
    pub sha256: String,
}

/// `[import]` of an imported recording.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportInfo {
    /// The `dlw` version that imported.
    pub dlw_version: String,
    /// The source files.
    pub sources: Vec<ImportSource>,
    /// The tracker's tip tool (port handle or tool number).
    pub tool: u32,
    /// The tracker's reference tool, when the angle is relative to one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_tool: Option<u32>,
    /// How the clocks were aligned: `auto` or the sync channel's name.
    pub alignment_method: String,
    /// `t_daq = offset_s + τ·(1 + drift_ppm·10⁻⁶)` (s).
    pub offset_s: f64,
    /// The tracker clock's drift against the DAQ's (ppm).
    pub drift_ppm: f64,
    /// The offset's standard uncertainty (s).
    pub offset_uncertainty_s: f64,
    /// The drift's standard uncertainty (ppm).
    pub drift_uncertainty_ppm: f64,
    /// Tracker frames in the log.
    pub tracker_frames: u64,
    /// Tracker frames with the tip (or reference) tool missing.
    pub missing_frames: u64,
    /// When the DAQ's time column jumps: each stretch of its clock and that stretch's own
    /// alignment (the figures above are the longest stretch's). Absent for one stretch.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stretches: Vec<ImportStretch>,
    /// A robot's import: each joint's tool, joint 1 (distal) first; `tool` is then joint 1's.
    /// Absent for a joint's import.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joint_tools: Vec<u32>,
}

/// One stretch of an imported recording's DAQ clock, aligned on its own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImportStretch {
    /// Its first sample's DAQ time (s).
    pub from_s: f64,
    /// Its last sample's DAQ time (s).
    pub to_s: f64,
    /// `t_daq = offset_s + τ·(1 + drift_ppm·10⁻⁶)` in it (s).
    pub offset_s: f64,
    /// Its drift (ppm).
    pub drift_ppm: f64,
}

/// Where a recording came from, as [`Rig::provenance`](super::Rig::provenance) reads it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Provenance<'a> {
    /// Made by `dlw simulate`.
    Simulated {
        /// `[simulation]`.
        info: &'a SimulationInfo,
        /// `[design]`, the design file's table.
        design: Option<&'a toml::Table>,
        /// `[scenario]`, the resolved scenario's table.
        scenario: Option<&'a toml::Table>,
    },
    /// Made by `dlw import-recording`.
    Imported(&'a ImportInfo),
    /// Written by hand or by another tool: neither table is present.
    Unknown,
}
