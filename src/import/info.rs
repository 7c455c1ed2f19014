//! `dlw daq-info`: what a DAQ file or a tracker log holds, before importing it (as npTDMS's
//! `tdmsinfo` shows a TDMS file).
//!
//! - A DAQ file (TDMS, LVM, CSV): every channel, as `Group/Channel` (TDMS) or its column name,
//!   with its type, length, unit, sample interval, and its first (up to [`FIRST`]) and last
//!   (up to [`LAST`]) values, scaled as the import would read them ([`DaqInfo`]).
//! - A tracker log, through its map (NDI's layout when none is given): each tool's frames with
//!   it and without it, the frames, their span, the frame rate and where it came from, the
//!   gaps, and the reader's warnings ([`TrackerInfo`]).

use serde::Serialize;
use serde_json::Value;

use super::daq_csv::TIME_NAMES;
use super::map::TrackerMap;
use super::stretch::{median_step, stretches};
use super::tdms::{ChannelId, Property, TdmsError, TdmsFile};
use super::tracker::{RateSource, ReadOptions, TrackerError, TrackerLog};
use super::{lvm, DaqError, DaqFormat};

/// How many first values are shown.
pub const FIRST: usize = 5;
/// How many last values are shown.
pub const LAST: usize = 2;

/// One channel of a DAQ file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelInfo {
    /// `Group/Channel` (TDMS) or the column's name.
    pub name: String,
    /// Its type: TDMS's (as npTDMS names it: `DoubleFloat`, `Int16`, `String`, …), or
    /// `number` / `text` for a text file's column.
    #[serde(rename = "type")]
    pub kind: Option<String>,
    /// Its values.
    pub length: usize,
    /// Its unit (TDMS `unit_string`, LVM `Y_Unit_Label`), when the file states one.
    pub unit: Option<String>,
    /// Its sample interval (s): TDMS `wf_increment`, or the median step of the time base.
    pub increment_s: Option<f64>,
    /// The first values (numbers scaled as the import reads them, text, booleans, timestamps
    /// as `YYYY-MM-DD HH:MM:SS` UTC; `null` for a value that is not finite).
    pub first: Vec<Value>,
    /// The last values, as `first`.
    pub last: Vec<Value>,
}

/// A DAQ file's contents: `dlw daq-info --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DaqInfo {
    /// `csv`, `tdms` or `lvm`.
    pub format: &'static str,
    /// Every channel.
    pub channels: Vec<ChannelInfo>,
    /// What would stop or change an import (a time column that jumps, a scale not applied, a
    /// value that is not finite).
    pub warnings: Vec<String>,
}

/// One tool of a tracker log.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToolInfo {
    /// The tool's number, as `--tool` counts it.
    pub tool: usize,
    /// Frames with the tool.
    pub seen: usize,
    /// Frames where the log says it is lost.
    pub missing: usize,
}

/// Frames absent from a tracker log between two rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GapInfo {
    /// The line after the gap.
    pub line: usize,
    /// The step (s).
    pub seconds: f64,
    /// Frames absent.
    pub frames: f64,
}

/// A tracker log's contents: `dlw daq-info --tracker FILE --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TrackerInfo {
    /// `ndi` (the built-in map) or `map` (`--tracker-map`).
    pub format: &'static str,
    /// Each tool the log holds.
    pub tools: Vec<ToolInfo>,
    /// Rows read.
    pub frames: usize,
    /// Tracker time from the first row to the last (s).
    pub span_s: f64,
    /// The frame rate (Hz).
    pub rate_hz: f64,
    /// Where the rate came from: `given` (`--tracker-hz`), `measured` (the log's time columns)
    /// or `default` (40 Hz).
    pub rate_source: RateSource,
    /// Steps where frames are absent.
    pub gaps: Vec<GapInfo>,
    /// The reader's warnings (a truncated last line, a frame counter the time columns do not
    /// follow).
    pub warnings: Vec<String>,
}

impl DaqInfo {
    /// The terminal's lines for the file `name`: each channel's type, length, unit, step and
    /// first and last values, then the warnings.
    pub fn summary(&self, name: &str) -> String {
        let mut out = format!(
            "{name}: {} file, {} channel(s)\n",
            self.format,
            self.channels.len()
        );
        let list = |v: &[Value]| {
            v.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        };
        for c in &self.channels {
            out += &format!(
                "  {}: {}, {} values{}{}; first {}; last {}\n",
                c.name,
                c.kind.as_deref().unwrap_or("no data"),
                c.length,
                c.unit
                    .as_ref()
                    .map_or(String::new(), |u| format!(", unit {u}")),
                c.increment_s
                    .map_or(String::new(), |s| format!(", every {s} s")),
                list(&c.first),
                list(&c.last)
            );
        }
        for w in &self.warnings {
            out += &format!("warning: {w}\n");
        }
        out
    }
}

impl TrackerInfo {
    /// The terminal's lines for the log `name`: its layout, frames, span and rate (and where
    /// the rate came from), each tool's frames, each gap, then the warnings.
    pub fn summary(&self, name: &str) -> String {
        let mut out = format!(
            "{name}: {} layout, {} frames over {:.3} s at {:.3} Hz ({}), {} gap(s)\n",
            self.format,
            self.frames,
            self.span_s,
            self.rate_hz,
            match self.rate_source {
                RateSource::Given => "--tracker-hz",
                RateSource::Measured => "measured from its time columns",
                RateSource::Default => "the Aurora's default",
            },
            self.gaps.len()
        );
        for t in &self.tools {
            out += &format!(
                "  tool {}: seen in {} frames, missing in {}\n",
                t.tool, t.seen, t.missing
            );
        }
        for g in &self.gaps {
            out += &format!(
                "  gap before line {}: {:.3} s, {:.0} frames absent\n",
                g.line, g.seconds, g.frames
            );
        }
        for w in &self.warnings {
            out += &format!("warning: {w}\n");
        }
        out
    }
}

/// What is in the DAQ file `bytes` (of `format`); `time_column` names a CSV's time column when
/// it is not found by name.
///
/// # Errors
/// [`DaqError`] when the file cannot be read at all (not TDMS, not UTF-8, no header).
pub fn daq_info(
    bytes: &[u8],
    format: DaqFormat,
    time_column: Option<&str>,
) -> Result<DaqInfo, DaqError> {
    match format {
        DaqFormat::Tdms => Ok(tdms_info(bytes)?),
        DaqFormat::Csv => csv_info(&super::text(bytes)?, time_column),
        DaqFormat::Lvm => lvm_info(&super::text(bytes)?),
    }
}

/// What is in the tracker log `text`, read through `map` (NDI's layout when `None`).
///
/// # Errors
/// [`TrackerError`] as the import would give it.
pub fn tracker_info(
    text: &str,
    map: Option<&TrackerMap>,
    frame_hz: Option<f64>,
) -> Result<TrackerInfo, TrackerError> {
    let read = |tools: &[usize]| {
        TrackerLog::parse(
            text,
            map,
            &ReadOptions {
                tools,
                frame_hz,
                extra_column: None,
            },
        )
    };
    let count = read(&[1])?.tool_count;
    let tools: Vec<usize> = (1..=count).collect();
    let log = read(&tools)?;
    Ok(TrackerInfo {
        format: if map.is_some() { "map" } else { "ndi" },
        tools: tools
            .iter()
            .enumerate()
            .map(|(k, &tool)| ToolInfo {
                tool,
                seen: log.tau_s.len() - log.missing(k),
                missing: log.missing(k),
            })
            .collect(),
        frames: log.tau_s.len(),
        span_s: log.tau_s.last().copied().unwrap_or(0.0),
        rate_hz: log.rate_hz,
        rate_source: log.rate_source,
        gaps: log
            .gaps
            .iter()
            .map(|g| GapInfo {
                line: g.line,
                seconds: g.seconds,
                frames: g.frames,
            })
            .collect(),
        warnings: log.warnings,
    })
}

/// The first [`FIRST`] and last [`LAST`] of `values`.
fn ends(values: &[Value]) -> (Vec<Value>, Vec<Value>) {
    (
        values.iter().take(FIRST).cloned().collect(),
        values[values.len().saturating_sub(LAST)..].to_vec(),
    )
}

/// A number as JSON: `null` when it is not finite.
fn number(v: f64) -> Value {
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

fn tdms_info(bytes: &[u8]) -> Result<DaqInfo, TdmsError> {
    let file = TdmsFile::parse(bytes)?;
    let mut warnings = Vec::new();
    let channels = file
        .channel_names()
        .iter()
        .filter_map(|name| file.find(name).ok())
        .map(|id| tdms_channel(&file, id, &mut warnings))
        .collect();
    Ok(DaqInfo {
        format: "tdms",
        channels,
        warnings,
    })
}

fn tdms_channel(file: &TdmsFile<'_>, id: ChannelId, warnings: &mut Vec<String>) -> ChannelInfo {
    let name = file.name(id);
    let kind = file.type_name(id);
    let unit = file
        .properties(id)
        .iter()
        .find(|(n, _)| n == "unit_string")
        .and_then(|(_, v)| match v {
            Property::Text(t) => Some(t.clone()),
            _ => None,
        });
    let shown: Vec<Value> = match kind {
        Some("String") => file.texts(id).into_iter().map(Value::String).collect(),
        Some("Boolean") => file
            .raw_values(id)
            .into_iter()
            .map(|v| Value::Bool(v != 0.0))
            .collect(),
        Some("TimeStamp") => file
            .raw_values(id)
            .into_iter()
            .map(|s| Value::String(date_time(s)))
            .collect(),
        _ => match file.values(id) {
            Ok(values) => values.into_iter().map(number).collect(),
            Err(e) => {
                warnings.push(format!("{name}: {e}; its values are shown as written"));
                file.raw_values(id).into_iter().map(number).collect()
            }
        },
    };
    let (first, last) = ends(&shown);
    ChannelInfo {
        name,
        kind: kind.map(str::to_owned),
        length: file.length(id),
        unit,
        increment_s: file.waveform(id).increment_s,
        first,
        last,
    }
}

/// Seconds since 1904-01-01 00:00 UTC as `YYYY-MM-DD HH:MM:SS` (with microseconds when the
/// value has a fraction of a second).
pub fn date_time(seconds_since_1904: f64) -> String {
    // Days from 1904-01-01 to 1970-01-01.
    const EPOCH_DAYS: i64 = 24_107;
    let whole = seconds_since_1904.floor();
    let micros = ((seconds_since_1904 - whole) * 1e6).round() as i64;
    let (whole, micros) = if micros >= 1_000_000 {
        (whole + 1.0, 0)
    } else {
        (whole, micros)
    };
    let total = whole as i64;
    let days = total.div_euclid(86_400) - EPOCH_DAYS;
    let secs = total.rem_euclid(86_400);
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    let clock = format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02}",
        secs / 3600,
        secs / 60 % 60,
        secs % 60
    );
    if micros == 0 {
        clock
    } else {
        format!("{clock}.{micros:06}")
    }
}

fn csv_info(text: &str, time_column: Option<&str>) -> Result<DaqInfo, DaqError> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, head) = lines
        .next()
        .ok_or(DaqError::Csv(super::daq_csv::DaqCsvError::Empty))?;
    let header: Vec<String> = head.split(',').map(|h| h.trim().to_owned()).collect();
    let mut columns: Vec<Vec<&str>> = vec![Vec::new(); header.len()];
    let mut warnings = Vec::new();
    for (i, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != header.len() {
            warnings.push(format!(
                "line {} has {} fields, the header {}",
                i + 1,
                fields.len(),
                header.len()
            ));
        }
        for (c, column) in columns.iter_mut().enumerate() {
            column.push(fields.get(c).copied().unwrap_or(""));
        }
    }
    let numbers = |column: &[&str]| -> Option<Vec<f64>> {
        column
            .iter()
            .map(|f| f.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect()
    };
    let time_at = match time_column {
        Some(name) => header.iter().position(|h| h == name),
        None => TIME_NAMES
            .iter()
            .find_map(|n| header.iter().position(|h| h == n)),
    };
    let time = time_at.and_then(|c| numbers(&columns[c]));
    let increment_s = match (&time, time_at) {
        (Some(t), _) if t.len() > 1 => {
            time_checks(t, &mut warnings);
            Some(median_step(t))
        }
        (None, Some(c)) => {
            warnings.push(format!(
                "the time column {:?} holds a field that is not a number",
                header[c]
            ));
            None
        }
        (_, None) => {
            warnings.push(
                "no time column (time_s, time, Time or t): an import needs --time-column or --daq-rate-hz"
                    .to_owned(),
            );
            None
        }
        _ => None,
    };
    let channels = header
        .iter()
        .zip(&columns)
        .map(|(name, column)| {
            let (kind, shown): (&str, Vec<Value>) = match numbers(column) {
                Some(v) => ("number", v.into_iter().map(number).collect()),
                None => (
                    "text",
                    column
                        .iter()
                        .map(|f| Value::String((*f).to_owned()))
                        .collect(),
                ),
            };
            let (first, last) = ends(&shown);
            ChannelInfo {
                name: name.clone(),
                kind: Some(kind.to_owned()),
                length: column.len(),
                unit: None,
                increment_s,
                first,
                last,
            }
        })
        .collect();
    Ok(DaqInfo {
        format: "csv",
        channels,
        warnings,
    })
}

/// Warnings about a time base: a step that does not increase, and the jumps an import splits
/// its alignment at.
fn time_checks(time_s: &[f64], warnings: &mut Vec<String>) {
    if let Some(i) = time_s.windows(2).position(|w| w[1] <= w[0]) {
        warnings.push(format!(
            "the time does not increase at row {}: {} after {} (an import refuses it)",
            i + 2,
            time_s[i + 1],
            time_s[i]
        ));
        return;
    }
    match stretches(time_s) {
        Ok(s) => {
            for j in &s.jumps {
                warnings.push(format!(
                    "the time jumps from {:.4} s to {:.4} s at row {} ({:.0} sample periods): the DAQ lost samples there; an import aligns each stretch on its own",
                    j.from_s,
                    j.to_s,
                    j.row,
                    (j.to_s - j.from_s) / s.period_s
                ));
            }
        }
        Err(e) => warnings.push(format!("{e} (an import refuses it)")),
    }
}

fn lvm_info(text: &str) -> Result<DaqInfo, DaqError> {
    let names = lvm::channel_names(text)?;
    let units = lvm::units(text)?;
    let mut warnings = Vec::new();
    // Each channel on its own, as an import asking for it reads it (a channel of empty fields
    // does not stop the others).
    let channels = names
        .iter()
        .enumerate()
        .map(|(k, name)| {
            let (shown, increment_s) = match lvm::read(text, &[name.as_str()], None, None) {
                Ok(t) => {
                    if t.time_s.len() > 1 {
                        time_checks(&t.time_s, &mut warnings);
                    }
                    let step = (t.time_s.len() > 1).then(|| median_step(&t.time_s));
                    (t.channels[0].iter().map(|&v| number(v)).collect(), step)
                }
                Err(e) => {
                    warnings.push(format!("{name}: {e}"));
                    (Vec::new(), None)
                }
            };
            let (first, last) = ends(&shown);
            ChannelInfo {
                name: name.clone(),
                kind: Some("number".to_owned()),
                length: shown.len(),
                unit: units.get(k).cloned().flatten(),
                increment_s,
                first,
                last,
            }
        })
        .collect();
    warnings.dedup();
    Ok(DaqInfo {
        format: "lvm",
        channels,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_are_read_as_nptdms_shows_them() {
        assert_eq!(date_time(0.0), "1904-01-01 00:00:00");
        // npTDMS: 2008-06-07 01:23:45 and 1894-03-15 13:23:45 (the real LabVIEW files).
        assert_eq!(date_time(3_295_646_625.0), "2008-06-07 01:23:45");
        assert_eq!(date_time(-309_090_975.0), "1894-03-15 13:23:45");
        assert_eq!(date_time(0.25), "1904-01-01 00:00:00.250000");
    }

    #[test]
    fn a_csv_lists_its_columns_and_its_time_jumps() {
        let mut text = String::from("Time,AI0,Note\n");
        for i in 0..40_000 {
            let t = f64::from(i) * 0.002 + if i >= 20_000 { 1.0 } else { 0.0 };
            text.push_str(&format!("{t:.4},{},x\n", f64::from(i) * 0.5));
        }
        let info = daq_info(text.as_bytes(), DaqFormat::Csv, None).unwrap();
        assert_eq!(info.channels.len(), 3);
        let ai0 = &info.channels[1];
        assert_eq!(ai0.kind.as_deref(), Some("number"));
        assert_eq!(ai0.length, 40_000);
        assert_eq!(ai0.first.len(), 5);
        assert_eq!(ai0.last, vec![number(19_999.0), number(19_999.5)]);
        assert_eq!(info.channels[2].kind.as_deref(), Some("text"));
        assert!((ai0.increment_s.unwrap() - 0.002).abs() < 1e-12);
        assert!(
            info.warnings[0].contains("row 20001"),
            "{:?}",
            info.warnings
        );
    }
}
