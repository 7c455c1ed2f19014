//! Recording directories: what the bench (real or simulated) writes, read back and checked.
//!
//! A recording is a folder with two files (the format is documented in
//! `docs/recording-format.md`):
//!
//! - `rig.toml`: `sample_hz`, `supply_v`, `divider_ohm` (one entry per sensor), an optional
//!   `notes` string, and for simulated recordings `[simulation]`, `[design]` and `[scenario]`;
//! - `data.csv`: the header `time_s,stroke_mm,angle_deg,v1_V` (plus `,v2_V` for a second
//!   sensor), then one row per sample; an imported recording whose tracker lost frames adds a
//!   last column `tracker_valid` (`1` or `0`): where it is `0`, `angle_deg` holds a number that
//!   no analysis may use (every reader stays a plain CSV reader; see [`Samples::tracker_valid`]).
//!
//! Reading refuses, naming the file, line and value: a wrong header, a row with missing or extra
//! fields, a field that is not a number or not finite, a time that does not increase, and a
//! voltage at or beyond a rail (`≤ 0` or `≥ supply_v`), which no finite sensor resistance
//! explains.
//!
//! A recording without a tracker (the phantom demonstration, whose ground truth comes from
//! fluoroscopy) leaves the `angle_deg` field empty in every row. [`Recording::read`] refuses
//! such a recording, so every reader that needs the tracker angle keeps its check;
//! [`Recording::read_allowing_empty_angle`] reads it, with an empty `Samples::angle_deg`. Writing builds the folder under a temporary name next to the destination and
//! renames it into place, so a failure never leaves a partial recording.
//!
//! This module is the sensing side's ground floor: it depends on nothing above it (not on the
//! simulator, not on design files). A simulated recording keeps its design and scenario as TOML
//! tables, which the simulator reads back with its own types.

pub mod clipping;
pub mod clock;
pub mod frozen;
mod protocol;
pub mod provenance;
pub mod rest;
pub mod robot;
mod truth;

pub use protocol::ProtocolKind;
pub use provenance::{ImportInfo, ImportSource, ImportStretch, Provenance, SimulationInfo};
/// A ground-truth angle series (`angles.csv`) to compare a recording's estimates with.
pub use truth::{parse_angles, read_angles, TruthAngles, TruthError};

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::fixed::push_fixed;
use crate::output::{stage_folder, OutputError, StagedFolder};

/// The data file's name inside a recording.
pub const DATA_FILE: &str = "data.csv";
/// The rig file's name inside a recording.
pub const RIG_FILE: &str = "rig.toml";

/// Why a recording could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum RecordingError {
    /// A file could not be read.
    #[error("cannot read {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// `rig.toml` is not valid TOML for a rig (unknown key, wrong type, missing key).
    #[error("{path}: {message}")]
    RigParse {
        /// The rig file.
        path: PathBuf,
        /// The TOML parser's message, which names the key and line.
        message: String,
    },
    /// A rig value is out of range.
    #[error("{path}: {key} = {value} is out of range ({limit})")]
    RigValue {
        /// The rig file.
        path: PathBuf,
        /// The key.
        key: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        limit: &'static str,
    },
    /// The header line is not the one the rig implies.
    #[error("{path} line 1: header is {found:?}, expected {expected:?} ({sensors} sensor(s) in rig.toml's divider_ohm)")]
    Header {
        /// The data file.
        path: PathBuf,
        /// The header found.
        found: String,
        /// The header expected.
        expected: String,
        /// Sensors listed in the rig.
        sensors: usize,
    },
    /// A row has missing or extra fields.
    #[error("{path} line {line}: has {found} fields, expected {expected} ({header})")]
    Fields {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Fields found.
        found: usize,
        /// Fields expected.
        expected: usize,
        /// The header, naming the expected fields.
        header: String,
    },
    /// A field is not a number.
    #[error("{path} line {line}: {column} = {text:?} is not a number")]
    Number {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Column name.
        column: String,
        /// The field as written.
        text: String,
    },
    /// A field is NaN or infinite.
    #[error("{path} line {line}: {column} = {value} is not finite")]
    NotFinite {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Column name.
        column: String,
        /// The value.
        value: f64,
    },
    /// A field beyond what a bench can record.
    #[error("{path} line {line}: {column} = {value:e} is beyond the limit of ±{limit} {unit}")]
    OutOfRange {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Column name.
        column: String,
        /// The value.
        value: f64,
        /// The largest magnitude the column may hold.
        limit: f64,
        /// Its unit.
        unit: &'static str,
    },
    /// Time does not strictly increase.
    #[error(
        "{path} line {line}: time_s = {time_s} does not increase (previous row: {previous_s})"
    )]
    TimeNotIncreasing {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// This row's time.
        time_s: f64,
        /// The previous row's time.
        previous_s: f64,
    },
    /// A voltage at or beyond a rail.
    #[error("{path} line {line}: {column} = {volts} V is at or beyond a rail (must lie strictly between 0 and supply_v = {supply_v} V)")]
    Rail {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// Column name.
        column: String,
        /// The reading.
        volts: f64,
        /// The rig's supply.
        supply_v: f64,
    },
    /// The `angle_deg` column is empty in some rows and not in others.
    #[error("{path} line {line}: angle_deg is {found} but line {first_line} {first} (the column must be empty in every row, for a recording without a tracker, or in none)")]
    MixedAngle {
        /// The data file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// `empty` or `a number`.
        found: &'static str,
        /// The first data line.
        first_line: usize,
        /// What the first data line has, in words.
        first: &'static str,
    },
    /// The `angle_deg` column is empty and the reader needs the tracker angle.
    #[error("{path}: the angle_deg column is empty (a recording without a tracker angle); compare its estimates with a ground truth instead: dlw estimate --truth angles.csv")]
    NoTrackerAngle {
        /// The data file.
        path: PathBuf,
    },
    /// `rig.toml`'s `sample_hz` is not the rate of the `time_s` column.
    #[error("{rig}: sample_hz = {sample_hz} Hz, but {data}'s time_s column runs at {measured_hz:.6} Hz (median spacing); they must agree within {tolerance_percent} %")]
    SampleRate {
        /// The rig file.
        rig: PathBuf,
        /// The data file.
        data: PathBuf,
        /// `sample_hz` as stated.
        sample_hz: f64,
        /// The reciprocal of the median spacing of `time_s`.
        measured_hz: f64,
        /// The tolerance (%).
        tolerance_percent: f64,
    },
    /// The data file has a header but no rows.
    #[error("{path} has no data rows")]
    NoRows {
        /// The data file.
        path: PathBuf,
    },
    /// A column piles up at one end of its range: the instrument's range clipped it
    /// ([`clipping`]).
    #[error(transparent)]
    Clipped(Box<ClippedColumn>),
    /// A column holds one value while the stroke moves: the instrument stopped updating it
    /// ([`frozen`]).
    #[error(transparent)]
    Frozen(Box<FrozenColumn>),
    /// The tracker's angle is late (or early) against the stroke and the voltages alike: its
    /// clock is off the DAQ's ([`clock`]).
    #[error(transparent)]
    TrackerDelay(Box<clock::TrackerDelay>),
    /// The destination exists and replacing it was not asked for.
    #[error("output folder {path} already exists and is not empty (pass --force to replace it)")]
    Exists {
        /// The destination.
        path: PathBuf,
    },
    /// The rig could not be written as TOML.
    #[error("cannot write rig.toml: {message}")]
    RigWrite {
        /// The serializer's message.
        message: String,
    },
    /// A file or folder could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The recording, written, does not read back (a value the fixed decimals of `data.csv`
    /// round onto a rail, or two times onto one): nothing was committed.
    #[error(
        "the recording for {dest}, written, does not read back ({reason}); nothing was written"
    )]
    ReadBack {
        /// The destination.
        dest: PathBuf,
        /// The reader's message (it names the staging folder's file and line).
        reason: String,
    },
}

/// A column the instrument's range clipped ([`RecordingError::Clipped`]).
#[derive(Debug, thiserror::Error)]
#[error("{path} line {line}: {column} holds its {end} value, {value}, in {count} of {rows} rows ({share:.1} %), {ratio:.0} times as often as any of the next {neighbours} values ({next_count} at most): the instrument's range clipped it, and an analysis would take the clip for the sensor's or the joint's response (record again with a wider input range, or cut the clipped stretch out)")]
pub struct ClippedColumn {
    /// The data file.
    pub path: PathBuf,
    /// The first 1-based line holding the value.
    pub line: usize,
    /// Column name.
    pub column: String,
    /// `largest` or `smallest`.
    pub end: &'static str,
    /// The value held.
    pub value: f64,
    /// How many rows hold it.
    pub count: usize,
    /// How many rows were looked at.
    pub rows: usize,
    /// `count` as a percentage of `rows`.
    pub share: f64,
    /// `count` over `next_count` (or `count` when that is 0).
    pub ratio: f64,
    /// How many neighbouring values were compared.
    pub neighbours: usize,
    /// How many rows the most held neighbour holds.
    pub next_count: usize,
}

/// A column the instrument stopped updating ([`RecordingError::Frozen`]).
#[derive(Debug, thiserror::Error)]
#[error("{path} line {line}: {column} holds {value} for {count} rows ({seconds:.2} s) while the stroke moves over {moved:.0} % of its range, where its other runs of one value last at most {typical} row(s) (99th percentile): the instrument stopped updating it (a tracker that lost the tool and holds its last reading, a stalled DAQ), and an analysis would take the hold for the sensor's or the joint's response (mark the rows tracker_valid = 0 for an angle, or cut the stretch out)")]
pub struct FrozenColumn {
    /// The data file.
    pub path: PathBuf,
    /// The first 1-based line of the stretch.
    pub line: usize,
    /// Column name.
    pub column: String,
    /// The value held.
    pub value: f64,
    /// How many rows hold it.
    pub count: usize,
    /// How long it holds (s).
    pub seconds: f64,
    /// How far the stroke moved meanwhile (% of its range).
    pub moved: f64,
    /// The 99th percentile of the column's other runs.
    pub typical: usize,
}

/// `rig.toml`: how the bench was set up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rig {
    /// Sample rate (Hz).
    pub sample_hz: f64,
    /// Divider supply `V+` (V).
    pub supply_v: f64,
    /// The divider's fixed resistor `R_k` for each sensor, in column order (Ω).
    pub divider_ohm: Vec<f64>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub notes: Option<String>,
    /// The protocol the recording follows, by the simulator's protocol name (`characterization`,
    /// `rate-dependence`, `relaxation`, `random`, `custom`), when the bench states it. A
    /// simulated recording states it in `[scenario]` instead; [`Rig::protocol`] reads either.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub protocol: Option<String>,
    /// What made a simulated recording.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulation: Option<SimulationInfo>,
    /// The design simulated, as its design file's table (with defaults filled in).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design: Option<toml::Table>,
    /// The resolved scenario simulated (every parameter, seed included), as its TOML table; the
    /// simulator reads it back as its `Scenario`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scenario: Option<toml::Table>,
    /// Where an imported recording came from: its source files and the alignment.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub import: Option<ImportInfo>,
}

/// The samples of a recording, one vector per column.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Samples {
    /// `time_s` (s).
    pub time_s: Vec<f64>,
    /// `stroke_mm`: tendon stroke (mm).
    pub stroke_mm: Vec<f64>,
    /// `angle_deg`: the angle the EM tracker recorded (°). Empty, while the other columns have
    /// rows, for a recording without a tracker (read with
    /// [`Recording::read_allowing_empty_angle`]).
    pub angle_deg: Vec<f64>,
    /// `v1_V`, `v2_V`: one vector of divider voltages (V) per sensor.
    pub volts: Vec<Vec<f64>>,
    /// `tracker_valid`: whether row `i`'s `angle_deg` is a tracker measurement. Empty when the
    /// column is absent (every angle valid); otherwise one entry per row, `false` where the
    /// tracker lost the tool for more than the importer's gap limit. Use
    /// [`Samples::angle_valid`] or [`Samples::valid_angle_rows`] rather than reading it directly.
    pub tracker_valid: Vec<bool>,
}

impl Samples {
    /// Empty columns for `sensors` sensors (one voltage column each) with room for `rows`.
    pub fn with_capacity(sensors: usize, rows: usize) -> Self {
        Self {
            time_s: Vec::with_capacity(rows),
            stroke_mm: Vec::with_capacity(rows),
            angle_deg: Vec::with_capacity(rows),
            volts: (0..sensors).map(|_| Vec::with_capacity(rows)).collect(),
            tracker_valid: Vec::new(),
        }
    }

    /// Whether row `i` has a usable tracker angle: the angle column is present and the row is
    /// not marked invalid.
    pub fn angle_valid(&self, i: usize) -> bool {
        i < self.angle_deg.len() && self.tracker_valid.get(i).copied().unwrap_or(true)
    }

    /// The rows with a usable tracker angle, in order.
    pub fn valid_angle_rows(&self) -> Vec<usize> {
        (0..self.angle_deg.len())
            .filter(|&i| self.angle_valid(i))
            .collect()
    }

    /// The smallest and the largest tracker angle over the rows with a usable one (°);
    /// `(∞, −∞)` when there is none.
    pub fn valid_angle_range(&self) -> (f64, f64) {
        (0..self.angle_deg.len())
            .filter(|&i| self.angle_valid(i))
            .map(|i| self.angle_deg[i])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
                (lo.min(a), hi.max(a))
            })
    }

    /// Rows marked invalid by the `tracker_valid` column.
    pub fn invalid_angle_rows(&self) -> usize {
        self.tracker_valid.iter().filter(|v| !**v).count()
    }

    /// Rows.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// Whether the recording has the tracker's angle (its `angle_deg` column is not empty).
    pub fn has_tracker_angle(&self) -> bool {
        self.angle_deg.len() == self.time_s.len()
    }
}

/// A recording: rig and samples.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// `rig.toml`.
    pub rig: Rig,
    /// `data.csv`.
    pub samples: Samples,
}

/// What the optional `tracker_valid` column adds to the header.
pub const VALID_COLUMN_SUFFIX: &str = ",tracker_valid";

/// The header line for `sensors` sensors.
pub fn header(sensors: usize) -> String {
    let mut h = String::from("time_s,stroke_mm,angle_deg");
    for c in 1..=sensors {
        h.push_str(&format!(",v{c}_V"));
    }
    h
}

impl Rig {
    /// The voltage divider `sensor` is read through (Eq. 4): its fixed resistor and the supply;
    /// `None` when the rig has no divider for it.
    pub fn divider(&self, sensor: crate::sensor::Sensor) -> Option<dlw_geometry::Divider> {
        Some(dlw_geometry::Divider {
            fixed_ohm: *self.divider_ohm.get(sensor.index())?,
            supply_v: self.supply_v,
        })
    }

    /// The protocol the rig states: the top-level `protocol`, else the simulated scenario's
    /// `protocol`; `None` when neither states one.
    pub fn protocol(&self) -> Option<&str> {
        self.protocol.as_deref().or_else(|| {
            self.scenario
                .as_ref()
                .and_then(|s| s.get("protocol"))
                .and_then(toml::Value::as_str)
        })
    }

    /// [`Self::protocol`] as a [`ProtocolKind`]: `Ok(None)` when none is stated, `Err(name)`
    /// for a name that is no protocol.
    pub fn protocol_kind(&self) -> Result<Option<ProtocolKind>, &str> {
        self.protocol()
            .map(|name| ProtocolKind::from_name(name).ok_or(name))
            .transpose()
    }

    /// Where the recording came from.
    pub fn provenance(&self) -> Provenance<'_> {
        match (&self.simulation, &self.import) {
            (Some(sim), _) => Provenance::Simulated {
                info: sim,
                design: self.design.as_ref(),
                scenario: self.scenario.as_ref(),
            },
            (None, Some(import)) => Provenance::Imported(import),
            (None, None) => Provenance::Unknown,
        }
    }

    fn check(&self, path: &Path) -> Result<(), RecordingError> {
        self.check_with(path, 2, "one or two sensors")
    }

    /// The checks of [`Self::check`] with at most `max_sensors` entries in `divider_ohm`.
    pub(crate) fn check_with(
        &self,
        path: &Path,
        max_sensors: usize,
        sensors_limit: &'static str,
    ) -> Result<(), RecordingError> {
        let bad = |key, value, limit| {
            Err(RecordingError::RigValue {
                path: path.to_path_buf(),
                key,
                value,
                limit,
            })
        };
        let positive = |v: f64| v.is_finite() && v > 0.0;
        if !positive(self.sample_hz) {
            return bad(
                "sample_hz",
                self.sample_hz,
                "must be finite and greater than 0",
            );
        }
        if !positive(self.supply_v) {
            return bad(
                "supply_v",
                self.supply_v,
                "must be finite and greater than 0",
            );
        }
        let n = self.divider_ohm.len();
        if !(1..=max_sensors).contains(&n) {
            return bad("divider_ohm (entries)", n as f64, sensors_limit);
        }
        if let Some(&r) = self.divider_ohm.iter().find(|r| !positive(**r)) {
            return bad("divider_ohm", r, "must be finite and greater than 0");
        }
        Ok(())
    }
}

impl Recording {
    /// Reads and checks a recording folder, which must have the tracker's angle.
    ///
    /// # Errors
    /// [`RecordingError`] naming the file, the line and the value;
    /// [`RecordingError::NoTrackerAngle`] when the `angle_deg` column is empty.
    pub fn read(dir: &Path) -> Result<Self, RecordingError> {
        let rec = Self::read_allowing_empty_angle(dir)?;
        if !rec.samples.has_tracker_angle() {
            return Err(RecordingError::NoTrackerAngle {
                path: dir.join(DATA_FILE),
            });
        }
        Ok(rec)
    }

    /// Reads and checks a recording folder whose `angle_deg` column may be empty in every row
    /// (a recording without a tracker); `samples.angle_deg` is then empty. Every other check
    /// of [`read`](Self::read) applies.
    ///
    /// # Errors
    /// [`RecordingError`] naming the file, the line and the value;
    /// [`RecordingError::MixedAngle`] when the column is empty in some rows only.
    pub fn read_allowing_empty_angle(dir: &Path) -> Result<Self, RecordingError> {
        let rig_path = dir.join(RIG_FILE);
        let rig_text = read_text(&rig_path, crate::limits::MAX_TEXT_INPUT_BYTES)?;
        let rig: Rig = toml::from_str(&rig_text).map_err(|e| RecordingError::RigParse {
            path: rig_path.clone(),
            message: crate::limits::parser_message(&e),
        })?;
        rig.check(&rig_path)?;
        let data_path = dir.join(DATA_FILE);
        let text = read_text(&data_path, crate::limits::MAX_RECORDING_BYTES)?;
        let samples = parse_data(&text, &rig, &data_path)?;
        check_sample_rate(&rig, &samples.time_s, &rig_path, &data_path)?;
        Ok(Self { rig, samples })
    }

    /// [`read`](Self::read)s a recording a model will be fitted to, and refuses it when a
    /// column was not measured throughout or its tracker is late ([`check_measured`](Self::check_measured)).
    ///
    /// # Errors
    /// Those of [`read`](Self::read) and of [`check_measured`](Self::check_measured).
    pub fn read_measured(dir: &Path) -> Result<Self, RecordingError> {
        let rec = Self::read(dir)?;
        rec.check_measured(dir)?;
        Ok(rec)
    }

    /// Refuses a recording one of whose columns was not measured throughout: the tracker's
    /// angle (on its valid rows) or a voltage clipped by the instrument's range
    /// ([`clipping`]), or holding one value while the stroke moves ([`frozen`]); or whose
    /// tracker's clock is off the DAQ's, its angle late against the stroke and the voltages
    /// alike ([`clock`]). An analysis that fits a model (`fit`, `discover`, `characterize`,
    /// and the Python binding's) calls it after reading; `dir` is the folder read, for the
    /// message.
    ///
    /// # Errors
    /// [`RecordingError::Clipped`] or [`RecordingError::Frozen`], naming the column, the value,
    /// how many rows hold it and the first line; [`RecordingError::TrackerDelay`] with both
    /// delays and their standard errors.
    pub fn check_measured(&self, dir: &Path) -> Result<(), RecordingError> {
        let s = &self.samples;
        let valid = s.valid_angle_rows();
        let mut columns = Vec::new();
        if !valid.is_empty() {
            columns.push(Measured {
                name: "angle_deg".to_string(),
                values: valid.iter().map(|&i| s.angle_deg[i]).collect(),
                rows: valid,
                stroke: Some(&s.stroke_mm),
            });
        }
        for (c, v) in s.volts.iter().enumerate() {
            columns.push(Measured {
                name: format!("v{}_V", c + 1),
                values: v.clone(),
                rows: (0..v.len()).collect(),
                stroke: Some(&s.stroke_mm),
            });
        }
        refuse_unmeasured(dir, &s.time_s, columns)?;
        clock::check(self, dir)
    }

    /// Writes the recording as folder `dest`, atomically: it is built under a temporary name
    /// next to `dest` and renamed into place. An existing non-empty `dest` is replaced only
    /// with `replace`.
    ///
    /// # Errors
    /// [`RecordingError::Exists`], or an I/O error naming the path; `dest` is then untouched.
    pub fn write(&self, dest: &Path, replace: bool) -> Result<(), RecordingError> {
        self.stage(dest, replace)?.commit()?;
        Ok(())
    }

    /// Checks every value with the rules [`Recording::read`] applies (the rig's values, the
    /// time increasing, each column's magnitude limit, every voltage strictly between the rails),
    /// naming the row (as the `data.csv` line it would be written on) and the column.
    ///
    /// # Errors
    /// The [`RecordingError`] that reading the written recording would give.
    pub fn check(&self) -> Result<(), RecordingError> {
        let data = Path::new(DATA_FILE);
        self.rig.check(Path::new(RIG_FILE))?;
        let s = &self.samples;
        let sensors = self.rig.divider_ohm.len();
        if s.volts.len() != sensors {
            return Err(RecordingError::Header {
                path: data.to_path_buf(),
                found: header(s.volts.len()),
                expected: header(sensors),
                sensors,
            });
        }
        if s.is_empty() {
            return Err(RecordingError::NoRows {
                path: data.to_path_buf(),
            });
        }
        for i in 0..s.len() {
            let line = i + 2;
            let mut columns = vec![("time_s".to_string(), s.time_s[i])];
            columns.push(("stroke_mm".to_string(), s.stroke_mm[i]));
            if let Some(&a) = s.angle_deg.get(i) {
                columns.push(("angle_deg".to_string(), a));
            }
            for (c, v) in s.volts.iter().enumerate() {
                columns.push((format!("v{}_V", c + 1), v[i]));
            }
            for (column, value) in &columns {
                check_value(*value, line, column, data)?;
            }
            if i > 0 && s.time_s[i] <= s.time_s[i - 1] {
                return Err(RecordingError::TimeNotIncreasing {
                    path: data.to_path_buf(),
                    line,
                    time_s: s.time_s[i],
                    previous_s: s.time_s[i - 1],
                });
            }
            for (c, v) in s.volts.iter().enumerate() {
                if !within_rails(v[i], self.rig.supply_v) {
                    return Err(RecordingError::Rail {
                        path: data.to_path_buf(),
                        line,
                        column: format!("v{}_V", c + 1),
                        volts: v[i],
                        supply_v: self.rig.supply_v,
                    });
                }
            }
        }
        Ok(())
    }

    /// [`check`](Self::check)s the recording, writes it into a staging folder beside `dest`
    /// and reads it back through [`Recording::read`] (or, without a tracker angle,
    /// [`Recording::read_allowing_empty_angle`]): what is committed is what every command will
    /// read. [`StagedFolder::commit`] puts it in place.
    ///
    /// # Errors
    /// [`RecordingError`] from the check, the write, or [`RecordingError::ReadBack`].
    pub fn stage_checked(
        &self,
        dest: &Path,
        replace: bool,
    ) -> Result<StagedFolder, RecordingError> {
        self.check()?;
        let staged = self.stage(dest, replace)?;
        let back = if self.samples.has_tracker_angle() {
            Self::read(staged.path())
        } else {
            Self::read_allowing_empty_angle(staged.path())
        };
        match back {
            Ok(_) => Ok(staged),
            Err(source) => Err(RecordingError::ReadBack {
                dest: dest.to_path_buf(),
                reason: source.to_string(),
            }),
        }
    }

    /// The recording written into a staging folder beside `dest`, not yet in place.
    fn stage(&self, dest: &Path, replace: bool) -> Result<StagedFolder, RecordingError> {
        let files = folder_files(dest, replace, &self.rig, self.csv_bytes())?;
        Ok(stage_folder(dest, &files)?)
    }

    /// `data.csv` as bytes: fixed decimals (time and stroke to 1e-6, angle to 1e-4°, voltage to
    /// 1 µV), `.` as decimal point, `\n` line ends; empty `angle_deg` fields when the samples
    /// have no tracker angle.
    pub fn csv_bytes(&self) -> Vec<u8> {
        let s = &self.samples;
        let sensors = s.volts.len();
        let mut out = Vec::with_capacity(s.len() * (40 + 10 * sensors) + 64);
        out.extend_from_slice(header(sensors).as_bytes());
        let marked = !s.tracker_valid.is_empty();
        if marked {
            out.extend_from_slice(VALID_COLUMN_SUFFIX.as_bytes());
        }
        out.push(b'\n');
        for i in 0..s.len() {
            push_fixed(&mut out, s.time_s[i], 6);
            out.push(b',');
            push_fixed(&mut out, s.stroke_mm[i], 6);
            out.push(b',');
            if let Some(&a) = s.angle_deg.get(i) {
                push_fixed(&mut out, a, 4);
            }
            for v in &s.volts {
                out.push(b',');
                push_fixed(&mut out, v[i], 6);
            }
            if marked {
                out.extend_from_slice(if s.tracker_valid[i] { b",1" } else { b",0" });
            }
            out.push(b'\n');
        }
        out
    }
}

/// How closely `sample_hz` must match the time column's rate (relative): 1 %.
pub const SAMPLE_RATE_TOLERANCE: f64 = 0.01;

/// `Ok` when `rig.sample_hz` is the rate of `time_s` (the reciprocal of its median spacing)
/// within [`SAMPLE_RATE_TOLERANCE`], or when there are too few rows to tell; else
/// [`RecordingError::SampleRate`] naming the rig at `rig_path`, the data at `data_path`, both
/// rates and the tolerance.
pub(crate) fn check_sample_rate(
    rig: &Rig,
    time_s: &[f64],
    rig_path: &Path,
    data_path: &Path,
) -> Result<(), RecordingError> {
    if time_s.len() < 3 {
        return Ok(());
    }
    let mut spacing: Vec<f64> = time_s.windows(2).map(|w| w[1] - w[0]).collect();
    let middle = spacing.len() / 2;
    let (_, median, _) = spacing.select_nth_unstable_by(middle, f64::total_cmp);
    let measured_hz = 1.0 / *median;
    if (measured_hz / rig.sample_hz - 1.0).abs() <= SAMPLE_RATE_TOLERANCE {
        Ok(())
    } else {
        Err(RecordingError::SampleRate {
            rig: rig_path.to_path_buf(),
            data: data_path.to_path_buf(),
            sample_hz: rig.sample_hz,
            measured_hz,
            tolerance_percent: SAMPLE_RATE_TOLERANCE * 100.0,
        })
    }
}

/// A recording folder's two files, `rig.toml` and `data.csv` (`csv`), once `dest` may take
/// them: absent or empty, or `replace` (then the output policy is told it may be replaced).
///
/// # Errors
/// [`RecordingError::Exists`] for an occupied `dest` without `replace`;
/// [`RecordingError::RigWrite`].
pub(crate) fn folder_files(
    dest: &Path,
    replace: bool,
    rig: &Rig,
    csv: Vec<u8>,
) -> Result<[(String, Vec<u8>); 2], RecordingError> {
    let occupied = match std::fs::read_dir(dest) {
        Ok(mut entries) => entries.next().is_some(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
        // A file, or a folder we may not list: not ours to replace silently.
        Err(_) => true,
    };
    if occupied && !replace {
        return Err(RecordingError::Exists {
            path: dest.to_path_buf(),
        });
    }
    if replace {
        crate::output::allow_replace(dest);
    }
    let rig = toml::to_string(rig).map_err(|e| RecordingError::RigWrite {
        message: e.to_string(),
    })?;
    Ok([
        (RIG_FILE.to_string(), rig.into_bytes()),
        (DATA_FILE.to_string(), csv),
    ])
}

pub(crate) fn read_text(path: &Path, limit: u64) -> Result<String, RecordingError> {
    crate::output::read_limited(path, limit).map_err(|source| RecordingError::Read {
        path: path.to_path_buf(),
        source,
    })
}

fn parse_data(text: &str, rig: &Rig, path: &Path) -> Result<Samples, RecordingError> {
    let sensors = rig.divider_ohm.len();
    let mut lines = text.split('\n').enumerate();
    let first = lines.next().map_or("", |(_, l)| l.trim_end_matches('\r'));
    let header = DataHeader::read(first, sensors, path)?;
    let mut samples = Samples::with_capacity(sensors, text.len() / (30 + 9 * sensors));
    let mut blank = None;
    // Whether the first data row's angle_deg is empty, and its line.
    let mut angle_empty: Option<(usize, bool)> = None;
    for (i, raw) in lines {
        let line = i + 1;
        let text = raw.trim_end_matches('\r');
        if text.is_empty() {
            // Blank lines are tolerated only at the end (a final newline leaves one).
            blank.get_or_insert(line);
            continue;
        }
        if let Some(line) = blank {
            return Err(header.fields_error(path, line, 0));
        }
        let (row, empty) = header.parse_row(text, line, path)?;
        same_angle_column(&mut angle_empty, line, empty, path)?;
        header.push_row(&mut samples, &row, empty, line, rig, path)?;
    }
    if samples.is_empty() {
        return Err(RecordingError::NoRows {
            path: path.to_path_buf(),
        });
    }
    Ok(samples)
}

/// `data.csv`'s header line, as the rig's sensors and the file's first line make it.
struct DataHeader {
    /// The columns' names.
    columns: Vec<String>,
    /// The header line expected.
    expected: String,
    /// Whether the file has a `tracker_valid` column.
    marked: bool,
    /// The sensors: voltage columns.
    sensors: usize,
}

impl DataHeader {
    /// The header for `sensors` voltage columns, with a `tracker_valid` column when the
    /// file's `first` line has one.
    ///
    /// # Errors
    /// [`RecordingError::Header`] when `first` is not the header expected.
    fn read(first: &str, sensors: usize, path: &Path) -> Result<Self, RecordingError> {
        let expected = header(sensors);
        let mut columns: Vec<String> = expected.split(',').map(str::to_string).collect();
        let marked = first.strip_suffix(VALID_COLUMN_SUFFIX) == Some(expected.as_str());
        let expected = if marked {
            format!("{expected}{VALID_COLUMN_SUFFIX}")
        } else {
            expected
        };
        if marked {
            columns.push("tracker_valid".to_string());
        }
        if first != expected {
            return Err(RecordingError::Header {
                path: path.to_path_buf(),
                found: crate::limits::quote(first),
                expected,
                sensors,
            });
        }
        Ok(DataHeader {
            columns,
            expected,
            marked,
            sensors,
        })
    }

    /// The `tracker_valid` column's index.
    fn valid_at(&self) -> usize {
        3 + self.sensors
    }

    /// A line with `found` fields where the header has more or fewer.
    fn fields_error(&self, path: &Path, line: usize, found: usize) -> RecordingError {
        RecordingError::Fields {
            path: path.to_path_buf(),
            line,
            found,
            expected: self.columns.len(),
            header: self.expected.clone(),
        }
    }

    /// The numbers of one data line, in the columns' order, and whether its `angle_deg` is
    /// empty.
    ///
    /// # Errors
    /// [`RecordingError::Number`] for a field that is not a number in range (or a
    /// `tracker_valid` other than 0 or 1), [`RecordingError::Fields`] for a line with the
    /// wrong number of fields.
    fn parse_row(
        &self,
        text: &str,
        line: usize,
        path: &Path,
    ) -> Result<([f64; 6], bool), RecordingError> {
        let mut row = [0.0f64; 6];
        let mut n = 0;
        let mut empty = false;
        for field in text.split(',') {
            if n == 2 && field.is_empty() {
                empty = true;
            } else if self.marked && n == self.valid_at() {
                row[n] = match field.trim() {
                    "1" => 1.0,
                    "0" => 0.0,
                    _ => {
                        return Err(RecordingError::Number {
                            path: path.to_path_buf(),
                            line,
                            column: "tracker_valid (must be 0 or 1)".to_string(),
                            text: crate::limits::quote(field),
                        })
                    }
                };
            } else if n < self.columns.len() {
                row[n] = parse_field(field, line, &self.columns[n], path)?;
            }
            n += 1;
        }
        if n != self.columns.len() {
            return Err(self.fields_error(path, line, n));
        }
        Ok((row, empty))
    }

    /// Appends one parsed line to `samples`.
    ///
    /// # Errors
    /// [`RecordingError::TimeNotIncreasing`], [`RecordingError::Rail`].
    fn push_row(
        &self,
        samples: &mut Samples,
        row: &[f64; 6],
        empty: bool,
        line: usize,
        rig: &Rig,
        path: &Path,
    ) -> Result<(), RecordingError> {
        if let Some(&previous_s) = samples.time_s.last() {
            if row[0] <= previous_s {
                return Err(RecordingError::TimeNotIncreasing {
                    path: path.to_path_buf(),
                    line,
                    time_s: row[0],
                    previous_s,
                });
            }
        }
        for c in 0..self.sensors {
            let volts = row[3 + c];
            if !within_rails(volts, rig.supply_v) {
                return Err(RecordingError::Rail {
                    path: path.to_path_buf(),
                    line,
                    column: self.columns[3 + c].clone(),
                    volts,
                    supply_v: rig.supply_v,
                });
            }
            samples.volts[c].push(volts);
        }
        samples.time_s.push(row[0]);
        samples.stroke_mm.push(row[1]);
        if !empty {
            samples.angle_deg.push(row[2]);
        }
        if self.marked {
            samples.tracker_valid.push(row[self.valid_at()] == 1.0);
        }
        Ok(())
    }
}

/// Refuses a data line whose `angle_deg` is empty where the first data line's has a number, or
/// the other way round; `angle_empty` holds the first data line's and its line number.
fn same_angle_column(
    angle_empty: &mut Option<(usize, bool)>,
    line: usize,
    empty: bool,
    path: &Path,
) -> Result<(), RecordingError> {
    let words = |e: bool| if e { "empty" } else { "a number" };
    match *angle_empty {
        None => *angle_empty = Some((line, empty)),
        Some((first_line, first)) if first != empty => {
            return Err(RecordingError::MixedAngle {
                path: path.to_path_buf(),
                line,
                found: words(empty),
                first_line,
                first: if first {
                    "has it empty"
                } else {
                    "has a number"
                },
            });
        }
        Some(_) => {}
    }
    Ok(())
}

/// The largest magnitude of a recording's time (s): 30 years of logging.
pub const MAX_ABS_TIME_S: f64 = 1e9;
/// The largest stroke magnitude (mm): a tendon pulled a metre.
pub const MAX_ABS_STROKE_MM: f64 = 1e3;
/// The largest angle magnitude (°): a joint bent a full turn.
pub const MAX_ABS_ANGLE_DEG: f64 = 360.0;
/// The largest voltage magnitude (V) before the supply check.
pub const MAX_ABS_VOLTS: f64 = 1e3;

/// The limit and unit of a column's magnitude: values past it are refused at the edge, since
/// every analysis of them only produces overflows (an angle of 1e308° made an RMSE of inf°).
pub fn column_limit(column: &str) -> (f64, &'static str) {
    // A robot recording numbers its columns (`stroke2_mm`, `angle2_deg`) and may add the
    // tracker's tip (`tip_x_mm`), which is bounded like a stroke.
    match column {
        "time_s" => (MAX_ABS_TIME_S, "s"),
        c if c.starts_with("stroke") || c.starts_with("tip_") => (MAX_ABS_STROKE_MM, "mm"),
        c if c.starts_with("angle") => (MAX_ABS_ANGLE_DEG, "°"),
        _ => (MAX_ABS_VOLTS, "V"),
    }
}

/// A column an analysis will fit a model to, for [`refuse_unmeasured`]: its name, its values,
/// the row each is from, and the stroke that drives it (none: not checked for a frozen
/// stretch).
pub(crate) struct Measured<'a> {
    pub name: String,
    pub values: Vec<f64>,
    pub rows: Vec<usize>,
    pub stroke: Option<&'a [f64]>,
}

/// The first of `columns` that the instrument clipped ([`clipping::pile_up`],
/// [`clipping::pile_up_moving`] for a column with a stroke) or stopped
/// updating while its stroke moved ([`frozen::frozen`]), as [`RecordingError::Clipped`] or
/// [`RecordingError::Frozen`] naming `dir`'s data file and the line (`time_s` gives a frozen
/// stretch's length in seconds).
pub(crate) fn refuse_unmeasured(
    dir: &Path,
    time_s: &[f64],
    columns: Vec<Measured<'_>>,
) -> Result<(), RecordingError> {
    let path = dir.join(DATA_FILE);
    for c in columns {
        let clip = match c.stroke {
            Some(stroke) => clipping::pile_up_moving(&c.values, &c.rows, stroke),
            None => clipping::pile_up(&c.values),
        };
        if let Some(p) = clip {
            return Err(RecordingError::Clipped(Box::new(ClippedColumn {
                path,
                line: c.rows.get(p.first).map_or(2, |r| r + 2),
                column: c.name,
                end: p.end.word(),
                value: p.value,
                count: p.count,
                rows: p.rows,
                share: 100.0 * p.count as f64 / p.rows as f64,
                ratio: p.count as f64 / p.next_count.max(1) as f64,
                neighbours: clipping::NEIGHBOURS,
                next_count: p.next_count,
            })));
        }
        let Some(f) = c.stroke.and_then(|s| frozen::frozen(&c.values, &c.rows, s)) else {
            continue;
        };
        let (start, end) = (c.rows[f.first], c.rows[f.first + f.len - 1]);
        return Err(RecordingError::Frozen(Box::new(FrozenColumn {
            path,
            line: start + 2,
            column: c.name,
            value: f.value,
            count: f.len,
            seconds: time_s[end] - time_s[start],
            moved: 100.0 * f.moved,
            typical: f.typical,
        })));
    }
    Ok(())
}

/// Whether a divider voltage lies strictly between the rails `0` and `supply_v`, where a
/// finite sensor resistance explains it.
pub fn within_rails(volts: f64, supply_v: f64) -> bool {
    volts > 0.0 && volts < supply_v
}

#[inline]
pub(crate) fn parse_field(
    field: &str,
    line: usize,
    column: &str,
    path: &Path,
) -> Result<f64, RecordingError> {
    let v: f64 = field.trim().parse().map_err(|_| RecordingError::Number {
        path: path.to_path_buf(),
        line,
        column: column.to_string(),
        text: crate::limits::quote(field),
    })?;
    check_value(v, line, column, path)
}

/// `v` if it is finite and within its column's magnitude limit ([`column_limit`]).
fn check_value(v: f64, line: usize, column: &str, path: &Path) -> Result<f64, RecordingError> {
    if !v.is_finite() {
        return Err(RecordingError::NotFinite {
            path: path.to_path_buf(),
            line,
            column: column.to_string(),
            value: v,
        });
    }
    let (limit, unit) = column_limit(column);
    if v.abs() > limit {
        return Err(RecordingError::OutOfRange {
            path: path.to_path_buf(),
            line,
            column: column.to_string(),
            value: v,
            limit,
            unit,
        });
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rig(sensors: usize) -> Rig {
        Rig {
            sample_hz: 500.0,
            supply_v: 5.0,
            divider_ohm: vec![99.6e3; sensors],
            notes: None,
            simulation: None,
            design: None,
            scenario: None,
            protocol: None,
            import: None,
        }
    }

    #[test]
    fn parses_good_data_and_names_bad_lines() {
        let path = Path::new("data.csv");
        let good = "time_s,stroke_mm,angle_deg,v1_V\n0,0,0,1.5\n0.002,0.1,1.2,1.6\n";
        let s = parse_data(good, &rig(1), path).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s.volts[0], vec![1.5, 1.6]);
        let table = [
            ("time_s,stroke_mm,angle_deg\n0,0,0\n", "line 1"),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n0,0,0,1\n0.1,0,0\n",
                "line 3: has 3 fields",
            ),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n0,0,0,1,2\n",
                "line 2: has 5 fields",
            ),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n0,0,NaN,1\n",
                "angle_deg = NaN",
            ),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n0,0,inf,1\n",
                "angle_deg = inf",
            ),
            ("time_s,stroke_mm,angle_deg,v1_V\n0,0,0,x\n", "v1_V = \"x\""),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n1,0,0,1\n1,0,0,1\n",
                "line 3: time_s = 1 does not increase",
            ),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n0,0,0,5\n",
                "v1_V = 5 V is at or beyond a rail",
            ),
            ("time_s,stroke_mm,angle_deg,v1_V\n0,0,0,0\n", "v1_V = 0 V"),
            ("time_s,stroke_mm,angle_deg,v1_V\n", "no data rows"),
            (
                "time_s,stroke_mm,angle_deg,v1_V\n0,0,0,1\n\n1,0,0,1\n",
                "line 3: has 0 fields",
            ),
        ];
        for (text, needle) in table {
            let err = parse_data(text, &rig(1), path).unwrap_err().to_string();
            assert!(err.contains(needle), "{text:?}: {err}");
        }
        let two = "time_s,stroke_mm,angle_deg,v1_V,v2_V\n0,0,0,1,6\n";
        let err = parse_data(two, &rig(2), path).unwrap_err().to_string();
        assert!(err.contains("v2_V = 6 V"), "{err}");
    }

    #[test]
    fn the_tracker_valid_column_marks_gaps_and_round_trips() {
        let path = Path::new("data.csv");
        let text = "time_s,stroke_mm,angle_deg,v1_V,tracker_valid\n0,0,1,1.5,1\n0.002,0.1,1.1,1.6,0\n0.004,0.2,1.2,1.7,1\n";
        let s = parse_data(text, &rig(1), path).unwrap();
        assert_eq!(s.tracker_valid, vec![true, false, true]);
        assert_eq!(s.valid_angle_rows(), vec![0, 2]);
        assert_eq!(s.invalid_angle_rows(), 1);
        assert!(!s.angle_valid(1) && s.angle_valid(2) && !s.angle_valid(3));
        let bad = "time_s,stroke_mm,angle_deg,v1_V,tracker_valid\n0,0,1,1.5,yes\n";
        let err = parse_data(bad, &rig(1), path).unwrap_err().to_string();
        assert!(
            err.contains("line 2") && err.contains("tracker_valid"),
            "{err}"
        );
        // Without the column every angle is valid.
        let plain = parse_data(
            "time_s,stroke_mm,angle_deg,v1_V\n0,0,1,1.5\n",
            &rig(1),
            path,
        );
        assert_eq!(plain.unwrap().valid_angle_rows(), vec![0]);

        let dir = tempfile::tempdir().unwrap();
        let dest = dir.path().join("rec");
        let rec = Recording {
            rig: rig(1),
            samples: s,
        };
        rec.write(&dest, false).unwrap();
        let written = std::fs::read_to_string(dest.join(DATA_FILE)).unwrap();
        assert_eq!(
            written.lines().next(),
            Some("time_s,stroke_mm,angle_deg,v1_V,tracker_valid")
        );
        assert_eq!(
            written.lines().nth(2),
            Some("0.002000,0.100000,1.1000,1.600000,0")
        );
        assert_eq!(Recording::read(&dest).unwrap(), rec);
    }

    #[test]
    fn an_empty_angle_column_is_read_only_when_allowed() {
        let path = Path::new("data.csv");
        let empty = "time_s,stroke_mm,angle_deg,v1_V\n0,0,,1.5\n0.002,0.1,,1.6\n";
        let s = parse_data(empty, &rig(1), path).unwrap();
        assert_eq!((s.len(), s.angle_deg.len()), (2, 0));
        assert!(!s.has_tracker_angle());
        let mixed = "time_s,stroke_mm,angle_deg,v1_V\n0,0,,1.5\n0.002,0.1,2,1.6\n";
        let err = parse_data(mixed, &rig(1), path).unwrap_err().to_string();
        assert!(
            err.contains("line 3: angle_deg is a number but line 2 has it empty"),
            "{err}"
        );
        let mixed = "time_s,stroke_mm,angle_deg,v1_V\n0,0,1,1.5\n0.002,0.1,,1.6\n";
        let err = parse_data(mixed, &rig(1), path).unwrap_err().to_string();
        assert!(
            err.contains("line 3: angle_deg is empty but line 2 has a number"),
            "{err}"
        );
        // Every other column keeps its checks.
        let bad = "time_s,stroke_mm,angle_deg,v1_V\n0,,,1.5\n";
        let err = parse_data(bad, &rig(1), path).unwrap_err().to_string();
        assert!(err.contains("stroke_mm = \"\""), "{err}");
        let rail = "time_s,stroke_mm,angle_deg,v1_V\n0,0,,5\n";
        assert!(parse_data(rail, &rig(1), path).is_err());

        let dir = tempfile::tempdir().unwrap();
        let dest = dir.path().join("rec");
        let rec = Recording {
            rig: rig(1),
            samples: s,
        };
        rec.write(&dest, false).unwrap();
        let text = std::fs::read_to_string(dest.join(DATA_FILE)).unwrap();
        assert_eq!(text.lines().nth(1), Some("0.000000,0.000000,,1.500000"));
        assert_eq!(Recording::read_allowing_empty_angle(&dest).unwrap(), rec);
        let err = Recording::read(&dest).unwrap_err().to_string();
        assert!(
            err.contains("angle_deg column is empty") && err.contains("--truth"),
            "{err}"
        );
    }

    #[test]
    fn write_then_read_round_trips_and_refuses_to_clobber() {
        let dir = tempfile::tempdir().unwrap();
        let dest = dir.path().join("rec");
        let rec = Recording {
            rig: rig(2),
            samples: Samples {
                tracker_valid: Vec::new(),
                time_s: vec![0.0, 0.002],
                stroke_mm: vec![0.0, 0.001],
                angle_deg: vec![0.0, 0.0355],
                volts: vec![vec![2.0, 2.1], vec![2.2, 2.3]],
            },
        };
        rec.write(&dest, false).unwrap();
        assert_eq!(Recording::read(&dest).unwrap(), rec);
        let err = rec.write(&dest, false).unwrap_err().to_string();
        assert!(err.contains("already exists"), "{err}");
        let mut other = rec.clone();
        other.samples.volts[0][0] = 1.0;
        other.write(&dest, true).unwrap();
        assert_eq!(Recording::read(&dest).unwrap(), other);
        // Only the recording is left next to it: no staging or set-aside folders.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
