//! A tracker log read through a [`TrackerMap`]: NDI's own layout (the built-in map,
//! [`TrackerMap::ndi`]) or a lab's logger (`--tracker-map`).
//!
//! - **Rows**: the lines after the map's header line; blank lines are skipped. Fields are split
//!   at commas and trimmed; empty fields past the header's last column (a trailing comma) are
//!   ignored. A last line that has no line end, fewer fields than the header, or a field that
//!   is not a number was cut off by the logger: it is dropped, with a warning. Any other bad
//!   line is refused, naming it.
//! - **Tools**: each quaternion is **scalar first**; one off unit length by more than
//!   [`MAX_QUATERNION_NORM_ERROR`] is refused, naming the line. A tool written as lost (empty
//!   fields, or every field 0, as the map says) is `None`.
//! - **Clock**: with a frame counter, `τ = (frame − first frame) / rate`, following NDI's
//!   guidance that frame numbers are regular and a host clock is not; the rate is
//!   `--tracker-hz`, else measured from the log's time columns (the least-squares slope of time
//!   against frame), else [`DEFAULT_TRACKER_HZ`]. Without a frame counter, `τ` is the time
//!   columns' sum from its first row. A time that wraps past midnight (an hour column going
//!   from 23 to 0) gets a day added.
//! - **Gaps**: two rows whose frame counter differs by more than [`GAP_PERIODS`] frames, or
//!   (without a counter) whose times differ by more than [`GAP_PERIODS`] periods, have frames
//!   missing from the log between them: a [`Gap`], across which no angle is interpolated.

use super::map::{Missing, TrackerMap};

/// How far a quaternion's norm may be from 1 before the row is refused.
pub const MAX_QUATERNION_NORM_ERROR: f64 = 1e-3;
/// The frame rate of an Aurora (Hz), taken when neither `--tracker-hz` nor the log's own time
/// columns give one.
pub const DEFAULT_TRACKER_HZ: f64 = 40.0;
/// A step between two rows longer than this many frame periods is a gap (frames absent from the
/// log): one frame lost makes a step of 2 periods; a host clock's jitter stays well inside it.
pub const GAP_PERIODS: f64 = 1.5;
/// How far (frame periods) the time columns may stray from the frame counter's line before a
/// warning says the counter may be the logger's line number rather than the tracker's frame.
pub const CLOCK_AGREEMENT_PERIODS: f64 = 2.0;
/// How far (relative) `--tracker-hz` may differ from the rate the log's time columns measure
/// before a warning says so.
pub const RATE_AGREEMENT: f64 = 0.01;

/// Errors reading a tracker log.
#[derive(Debug, thiserror::Error)]
pub enum TrackerError {
    /// The log has no header row.
    #[error("tracker log is empty (no header row)")]
    Empty,
    /// The map's header line is past the end of the log.
    #[error("tracker log has {lines} lines; the map's header_line is {header_line}")]
    HeaderLine {
        /// The map's header line.
        header_line: usize,
        /// Lines in the log.
        lines: usize,
    },
    /// A column the reader needs is not in the header.
    #[error("tracker log header (line {line}) has no {column:?} column (found: {found}){hint}")]
    NoColumn {
        /// The header's line.
        line: usize,
        /// The column looked for.
        column: String,
        /// The header's columns.
        found: String,
        /// What to do, when the log is not NDI's layout.
        hint: &'static str,
    },
    /// A name the header holds fewer times than the map needs.
    #[error("tracker log header has {count} column(s) named {column:?}; {who} needs occurrence {needed}")]
    Occurrence {
        /// The name.
        column: String,
        /// How often the header has it.
        count: usize,
        /// The occurrence needed (1-based).
        needed: usize,
        /// What needs it.
        who: String,
    },
    /// The tool asked for is not in the log.
    #[error("tracker log has no tool {tool} (its map lists {tools} tool(s))")]
    NoTool {
        /// The tool asked for (1-based).
        tool: usize,
        /// The tools in the map.
        tools: usize,
    },
    /// A field is not a number.
    #[error("tracker log line {line}: {column} = {text:?} is not a number")]
    Number {
        /// The file's line (1-based).
        line: usize,
        /// The column.
        column: String,
        /// The field.
        text: String,
    },
    /// A quaternion is not of unit length.
    #[error("tracker log line {line}: tool {tool}'s quaternion has norm {norm:.6} (must be 1 within {MAX_QUATERNION_NORM_ERROR})")]
    NotUnit {
        /// The file's line (1-based).
        line: usize,
        /// The tool (1-based).
        tool: usize,
        /// The norm found.
        norm: f64,
    },
    /// Frame numbers or times do not increase.
    #[error("tracker log line {line}: time {tau_s} s does not increase (previous {previous_s} s)")]
    TimeNotIncreasing {
        /// The file's line (1-based).
        line: usize,
        /// Its time.
        tau_s: f64,
        /// The previous row's time.
        previous_s: f64,
    },
    /// The frame rate is not positive and finite.
    #[error("tracker frame rate {hz} Hz must be finite and greater than 0")]
    FrameRate {
        /// The rate given.
        hz: f64,
    },
    /// A map with neither a frame counter nor time columns.
    #[error(
        "the tracker map names neither a frame counter nor time columns: the log has no clock"
    )]
    NoClock,
    /// Too few rows to read a clock from.
    #[error("tracker log has {rows} data row(s); at least 2 are needed")]
    TooFew {
        /// Rows read.
        rows: usize,
    },
}

/// One tool's orientation at one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolFrame {
    /// The unit quaternion, scalar first: `[q0, qx, qy, qz]`.
    pub quaternion: [f64; 4],
}

impl ToolFrame {
    /// The tool's z axis (the axis a 5-DOF Aurora sensor reports) in the tracker's frame: the
    /// third column of the rotation matrix of `quaternion`.
    pub fn z_axis(&self) -> [f64; 3] {
        let [w, x, y, z] = self.quaternion;
        [
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
        ]
    }
}

/// Frames missing from the log between two rows.
#[derive(Debug, Clone, PartialEq)]
pub struct Gap {
    /// The row after the gap (0-based, into [`TrackerLog::tau_s`]).
    pub row: usize,
    /// Its line in the file.
    pub line: usize,
    /// The step from the row before (s of tracker time).
    pub seconds: f64,
    /// Frames absent: the step in frame periods, less one.
    pub frames: f64,
}

/// Where the clock's rate came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RateSource {
    /// `--tracker-hz`.
    Given,
    /// The log's time columns against its frame counter, or the median step of its time.
    Measured,
    /// [`DEFAULT_TRACKER_HZ`].
    Default,
}

/// What to read from a log.
#[derive(Debug, Clone, Copy)]
pub struct ReadOptions<'a> {
    /// The tools to keep (1-based, in the map's order); the first is the tip.
    pub tools: &'a [usize],
    /// `--tracker-hz`, when given.
    pub frame_hz: Option<f64>,
    /// A further column to read per row (a sync pulse's level), by header name.
    pub extra_column: Option<&'a str>,
}

/// The frames of the tools asked for, one entry per logged row.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerLog {
    /// The tracker's own time from its first logged row (s).
    pub tau_s: Vec<f64>,
    /// Per tool asked for, per row: the frame, or `None` where the log says the tool is lost.
    pub tools: Vec<Vec<Option<ToolFrame>>>,
    /// Each row's line in the file.
    pub lines: Vec<usize>,
    /// Steps where frames are missing from the log.
    pub gaps: Vec<Gap>,
    /// The frame rate (Hz): the clock's, or the median step's for a log timed by its clock.
    pub rate_hz: f64,
    /// Where the rate came from.
    pub rate_source: RateSource,
    /// The tools the map lists (the log's tools).
    pub tool_count: usize,
    /// The header's columns.
    pub header: Vec<String>,
    /// The `extra_column` per row, when asked for.
    pub extra: Vec<f64>,
    /// Things the reader noticed (a truncated last line, a counter that is not the clock).
    pub warnings: Vec<String>,
}

/// The columns of one tool.
#[derive(Clone)]
struct ToolAt {
    quaternion: [usize; 4],
    position: Option<[usize; 3]>,
    missing: Missing,
}

/// A name's columns in the header.
fn positions(header: &[String], name: &str) -> Vec<usize> {
    let name = name.trim();
    (0..header.len())
        .filter(|&i| header[i].eq_ignore_ascii_case(name))
        .collect()
}

impl TrackerLog {
    /// Parses `text` with `map` (`None`: NDI's layout, [`TrackerMap::ndi`]).
    ///
    /// # Errors
    /// [`TrackerError`] naming the line, the column and the value.
    pub fn parse(
        text: &str,
        map: Option<&TrackerMap>,
        options: &ReadOptions<'_>,
    ) -> Result<Self, TrackerError> {
        if let Some(hz) = options.frame_hz {
            if !(hz.is_finite() && hz > 0.0) {
                return Err(TrackerError::FrameRate { hz });
            }
        }
        let text = text.strip_prefix(crate::output::UTF8_BOM).unwrap_or(text);
        let all: Vec<&str> = text
            .split('\n')
            .map(|l| l.strip_suffix('\r').unwrap_or(l))
            .collect();
        let builtin;
        let map = match map {
            Some(m) => m,
            None => {
                let at = all
                    .iter()
                    .position(|l| !l.trim().is_empty())
                    .ok_or(TrackerError::Empty)?;
                let header: Vec<&str> = all[at].split(',').map(str::trim).collect();
                builtin = TrackerMap::ndi(at + 1, &header).ok_or_else(|| {
                    let missing = if header.iter().any(|h| h.eq_ignore_ascii_case("Frame#")) {
                        "Q0"
                    } else {
                        "Frame#"
                    };
                    TrackerError::NoColumn {
                        line: at + 1,
                        column: missing.to_owned(),
                        found: crate::limits::quote(&header.join(",")),
                        hint: "; a log in another layout than NDI's needs --tracker-map MAP.toml (docs/import.md)",
                    }
                })?;
                &builtin
            }
        };
        let header_at = map.header_line - 1;
        let header: Vec<String> = all
            .get(header_at)
            .ok_or(TrackerError::HeaderLine {
                header_line: map.header_line,
                lines: all.len(),
            })?
            .split(',')
            .map(|h| h.trim().to_owned())
            .collect();
        let reader = Reader::new(map, &header, map.header_line, options)?;
        reader.read(&all[header_at + 1..], header_at + 2, header, options)
    }

    /// Rows where tool `k` (index into the tools asked for) is lost.
    pub fn missing(&self, k: usize) -> usize {
        self.tools
            .get(k)
            .map_or(0, |t| t.iter().filter(|f| f.is_none()).count())
    }

    /// Whether a gap lies between rows `p` and `q` (`p < q`).
    pub fn gap_between(&self, p: usize, q: usize) -> bool {
        let first = self.gaps.partition_point(|g| g.row <= p);
        self.gaps.get(first).is_some_and(|g| g.row <= q)
    }
}

/// The resolved columns of a map against a header.
struct Reader {
    map_tools: usize,
    frame: Option<usize>,
    time: Vec<(usize, f64)>,
    tools: Vec<(usize, ToolAt)>,
    extra: Option<usize>,
    uses_hours: bool,
}

impl Reader {
    fn new(
        map: &TrackerMap,
        header: &[String],
        header_line: usize,
        options: &ReadOptions<'_>,
    ) -> Result<Self, TrackerError> {
        let no_column = |name: &str| TrackerError::NoColumn {
            line: header_line,
            column: name.to_owned(),
            found: crate::limits::quote(&header.join(",")),
            hint: "",
        };
        let nth = |name: &str, n: usize, who: String| -> Result<usize, TrackerError> {
            let at = positions(header, name);
            if at.is_empty() {
                return Err(no_column(name));
            }
            at.get(n).copied().ok_or(TrackerError::Occurrence {
                column: name.to_owned(),
                count: at.len(),
                needed: n + 1,
                who,
            })
        };
        for &tool in options.tools {
            if tool == 0 || tool > map.tools.len() {
                return Err(TrackerError::NoTool {
                    tool,
                    tools: map.tools.len(),
                });
            }
        }
        // The tip tool's own frame counter and time: the occurrence with its number, or the
        // last when the header has fewer.
        let tip = options.tools.first().map_or(0, |t| t - 1);
        let own = |name: &str| -> Result<usize, TrackerError> {
            let at = positions(header, name);
            at.get(tip.min(at.len().saturating_sub(1)))
                .copied()
                .ok_or_else(|| no_column(name))
        };
        let frame = map.frame.as_deref().map(own).transpose()?;
        let time = map
            .time
            .iter()
            .map(|(name, unit)| Ok((own(name)?, unit.seconds())))
            .collect::<Result<Vec<_>, TrackerError>>()?;
        // The n-th [[tool]] naming a column takes its n-th occurrence.
        let mut named: std::collections::HashMap<String, usize> = Default::default();
        let mut all_tools = Vec::with_capacity(map.tools.len());
        for (k, t) in map.tools.iter().enumerate() {
            let mut take = |name: &String| {
                let key = name.trim().to_ascii_lowercase();
                let n = *named.get(&key).unwrap_or(&0);
                named.insert(key, n + 1);
                nth(name, n, format!("tool {}", k + 1))
            };
            let mut quaternion = [0; 4];
            for (slot, name) in quaternion.iter_mut().zip(&t.quaternion) {
                *slot = take(name)?;
            }
            let position = match &t.position_mm {
                Some(p) => {
                    let mut at = [0; 3];
                    for (slot, name) in at.iter_mut().zip(p) {
                        *slot = take(name)?;
                    }
                    Some(at)
                }
                None => None,
            };
            all_tools.push(ToolAt {
                quaternion,
                position,
                missing: t.missing,
            });
        }
        let tools = options
            .tools
            .iter()
            .map(|&t| (t, all_tools[t - 1].clone()))
            .collect();
        let extra = options
            .extra_column
            .map(|name| {
                positions(header, name)
                    .first()
                    .copied()
                    .ok_or_else(|| no_column(name))
            })
            .transpose()?;
        Ok(Self {
            map_tools: map.tools.len(),
            frame,
            time,
            tools,
            extra,
            uses_hours: map.time.iter().any(|(_, u)| u.seconds() >= 3600.0),
        })
    }

    /// Reads the data lines `lines` (the first is file line `first_line`).
    fn read(
        self,
        lines: &[&str],
        first_line: usize,
        header: Vec<String>,
        options: &ReadOptions<'_>,
    ) -> Result<TrackerLog, TrackerError> {
        let rows: Vec<(usize, &str)> = lines
            .iter()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty())
            .map(|(i, l)| (first_line + i, *l))
            .collect();
        // `split('\n')` leaves an empty last piece when the text ends with a line end.
        let ends_with_line_end = lines.last().is_some_and(|l| l.is_empty());
        let mut warnings = Vec::new();
        let mut stamps: Vec<(Option<f64>, Option<f64>)> = Vec::with_capacity(rows.len());
        let mut log = TrackerLog {
            tau_s: Vec::new(),
            tools: vec![Vec::with_capacity(rows.len()); self.tools.len()],
            lines: Vec::with_capacity(rows.len()),
            gaps: Vec::new(),
            rate_hz: 0.0,
            rate_source: RateSource::Default,
            tool_count: 0,
            header,
            extra: Vec::new(),
            warnings: Vec::new(),
        };
        let mut day_s = 0.0;
        for (k, &(line, text)) in rows.iter().enumerate() {
            let last = k + 1 == rows.len();
            let fields: Vec<&str> = text.split(',').map(str::trim).collect();
            let parsed = self.row(line, &fields, &log.header);
            let cut = last && (!ends_with_line_end || fields.len() < log.header.len());
            match parsed {
                Err(e) if last => {
                    warnings.push(format!(
                        "tracker log line {line}, the last, is cut short ({e}): dropped as a truncated line"
                    ));
                    break;
                }
                Err(e) => return Err(e),
                Ok(_) if cut => {
                    warnings.push(format!(
                        "tracker log line {line}, the last, {}: dropped as a truncated line",
                        if ends_with_line_end {
                            format!(
                                "has {} of the header's {} fields",
                                fields.len(),
                                log.header.len()
                            )
                        } else {
                            "has no line end (the logger stopped mid-line)".to_owned()
                        }
                    ));
                    break;
                }
                Ok((frame, time, tools, extra)) => {
                    let time = time.map(|t| {
                        // An hour column that goes from 23 back to 0: the next day.
                        let previous = stamps.last().and_then(|s| s.1);
                        if let Some(p) = previous {
                            if self.uses_hours && t + day_s < p - 43_200.0 {
                                day_s += 86_400.0;
                            }
                        }
                        t + day_s
                    });
                    stamps.push((frame, time));
                    for (k, f) in tools.into_iter().enumerate() {
                        log.tools[k].push(f);
                    }
                    if let Some(v) = extra {
                        log.extra.push(v);
                    }
                    log.lines.push(line);
                }
            }
        }
        if stamps.len() < 2 {
            return Err(TrackerError::TooFew { rows: stamps.len() });
        }
        self.clock(&mut log, &stamps, options, &mut warnings)?;
        log.warnings = warnings;
        Ok(log)
    }

    /// One row: its frame, its time (s), each tool asked for, the extra column.
    #[allow(clippy::type_complexity)]
    fn row(
        &self,
        line: usize,
        fields: &[&str],
        header: &[String],
    ) -> Result<
        (
            Option<f64>,
            Option<f64>,
            Vec<Option<ToolFrame>>,
            Option<f64>,
        ),
        TrackerError,
    > {
        let field = |c: usize| fields.get(c).copied().unwrap_or("");
        let number = |c: usize| -> Result<f64, TrackerError> {
            field(c)
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| TrackerError::Number {
                    line,
                    column: header.get(c).cloned().unwrap_or_else(|| "?".into()),
                    text: crate::limits::quote(field(c)),
                })
        };
        let frame = self.frame.map(number).transpose()?;
        let time = if self.time.is_empty() {
            None
        } else {
            let mut t = 0.0;
            for &(c, unit) in &self.time {
                t += number(c)? * unit;
            }
            Some(t)
        };
        let mut tools = Vec::with_capacity(self.tools.len());
        for (tool, at) in &self.tools {
            let lost = match at.missing {
                Missing::Empty => at.quaternion.iter().any(|&c| field(c).is_empty()),
                Missing::AllZero => at
                    .quaternion
                    .iter()
                    .chain(at.position.iter().flatten())
                    .all(|&c| field(c).parse::<f64>() == Ok(0.0)),
            };
            if lost {
                tools.push(None);
                continue;
            }
            let mut q = [0.0; 4];
            for (v, &c) in q.iter_mut().zip(&at.quaternion) {
                *v = number(c)?;
            }
            if let Some(p) = at.position {
                for c in p {
                    number(c)?;
                }
            }
            let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            if (norm - 1.0).abs() > MAX_QUATERNION_NORM_ERROR {
                return Err(TrackerError::NotUnit {
                    line,
                    tool: *tool,
                    norm,
                });
            }
            tools.push(Some(ToolFrame { quaternion: q }));
        }
        let extra = self.extra.map(number).transpose()?;
        Ok((frame, time, tools, extra))
    }

    /// The clock `τ`, the rate and the gaps, from the rows' frames and times.
    fn clock(
        &self,
        log: &mut TrackerLog,
        stamps: &[(Option<f64>, Option<f64>)],
        options: &ReadOptions<'_>,
        warnings: &mut Vec<String>,
    ) -> Result<(), TrackerError> {
        let frames: Option<Vec<f64>> = stamps.iter().map(|s| s.0).collect();
        let times: Option<Vec<f64>> = stamps.iter().map(|s| s.1).collect();
        let increasing = |values: &[f64], scale: f64| -> Result<(), TrackerError> {
            for i in 1..values.len() {
                if values[i] <= values[i - 1] {
                    return Err(TrackerError::TimeNotIncreasing {
                        line: log.lines[i],
                        tau_s: (values[i] - values[0]) * scale,
                        previous_s: (values[i - 1] - values[0]) * scale,
                    });
                }
            }
            Ok(())
        };
        match (frames, times) {
            (Some(frames), times) => {
                let measured = times.as_deref().and_then(|t| {
                    increasing(t, 1.0).ok()?;
                    let slope = slope(&frames, t)?;
                    (slope.is_finite() && slope > 0.0).then_some(1.0 / slope)
                });
                let (rate, source) = match (options.frame_hz, measured) {
                    (Some(hz), _) => (hz, RateSource::Given),
                    (None, Some(hz)) => (hz, RateSource::Measured),
                    (None, None) => (DEFAULT_TRACKER_HZ, RateSource::Default),
                };
                increasing(&frames, 1.0 / rate)?;
                if let (Some(hz), Some(m)) = (options.frame_hz, measured) {
                    if (hz / m - 1.0).abs() > RATE_AGREEMENT {
                        warnings.push(format!(
                            "--tracker-hz {hz} differs from the {m:.3} Hz the log's time columns measure against its frame counter"
                        ));
                    }
                }
                if let Some(t) = &times {
                    let worst = worst_residual(&frames, t, 1.0 / rate);
                    if worst > CLOCK_AGREEMENT_PERIODS / rate {
                        warnings.push(format!(
                            "the log's time columns stray up to {:.1} ms from its frame counter at {rate:.3} Hz: if the counter is the logger's line number rather than the tracker's frame, leave `frame` out of the map so that the time columns are the clock",
                            worst * 1e3
                        ));
                    }
                }
                log.tau_s = frames.iter().map(|f| (f - frames[0]) / rate).collect();
                log.rate_hz = rate;
                log.rate_source = source;
                for i in 1..frames.len() {
                    let step = frames[i] - frames[i - 1];
                    if step > GAP_PERIODS {
                        log.gaps.push(Gap {
                            row: i,
                            line: log.lines[i],
                            seconds: step / rate,
                            frames: step - 1.0,
                        });
                    }
                }
            }
            (None, Some(times)) => {
                increasing(&times, 1.0)?;
                log.tau_s = times.iter().map(|t| t - times[0]).collect();
                let mut steps: Vec<f64> = log.tau_s.windows(2).map(|w| w[1] - w[0]).collect();
                steps.sort_by(f64::total_cmp);
                let period = steps[steps.len() / 2];
                log.rate_hz = 1.0 / period;
                log.rate_source = match options.frame_hz {
                    Some(_) => RateSource::Given,
                    None => RateSource::Measured,
                };
                for i in 1..log.tau_s.len() {
                    let step = log.tau_s[i] - log.tau_s[i - 1];
                    if step > GAP_PERIODS * period {
                        log.gaps.push(Gap {
                            row: i,
                            line: log.lines[i],
                            seconds: step,
                            frames: step / period - 1.0,
                        });
                    }
                }
            }
            (None, None) => return Err(TrackerError::NoClock),
        }
        log.tool_count = self.map_tools;
        Ok(())
    }
}

/// The least-squares slope of `y` against `x`; `None` when `x` does not vary.
fn slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The largest |residual| (s) of `time` about the line `time = a + frame·period`, `a` the
/// least-squares intercept for that period.
fn worst_residual(frames: &[f64], time: &[f64], period: f64) -> f64 {
    let n = frames.len() as f64;
    let a = frames
        .iter()
        .zip(time)
        .map(|(f, t)| t - f * period)
        .sum::<f64>()
        / n;
    frames
        .iter()
        .zip(time)
        .map(|(f, t)| (t - a - f * period).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const HEADER: &str = "#Tools,ToolInfo,Frame#,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error";

    fn log() -> String {
        let h = (10f64.to_radians() / 2.0).sin_cos();
        format!(
            "{HEADER}\n\
             2,x,100,Port:1,0,OK,1,0,0,0,1,2,3,0.1,Port:2,0,OK,{c},{s},0,0,0,0,0,0.1\n\
             2,x,101,Port:1,0,Missing,,,,,,,,,Port:2,0,OK,1,0,0,0,0,0,0,0.1\n\
             2,x,102,Port:1,0,OK,{c},0,{s},0,1,2,3,0.1,Port:2,0,OK,1,0,0,0,0,0,0,0.1\n",
            c = h.1,
            s = h.0
        )
    }

    fn parse(text: &str, tools: &[usize]) -> Result<TrackerLog, TrackerError> {
        TrackerLog::parse(
            text,
            None,
            &ReadOptions {
                tools,
                frame_hz: Some(40.0),
                extra_column: None,
            },
        )
    }

    #[test]
    fn reads_tools_by_header_names_with_missing_frames_and_frame_time() {
        let log = parse(&log(), &[1, 2]).unwrap();
        assert_eq!(log.tau_s, vec![0.0, 0.025, 0.05]);
        assert_eq!(log.missing(0), 1);
        assert_eq!(log.missing(1), 0);
        assert!(log.tools[0][1].is_none());
        assert!(log.gaps.is_empty());
        // Tool 1, row 3: 10° about y tilts z towards +x.
        let z = log.tools[0][2].unwrap().z_axis();
        assert_relative_eq!(z[0], 10f64.to_radians().sin(), epsilon = 1e-12);
        assert_relative_eq!(z[2], 10f64.to_radians().cos(), epsilon = 1e-12);
        // Tool 2, row 1: 10° about x tilts z towards −y.
        let z = log.tools[1][0].unwrap().z_axis();
        assert_relative_eq!(z[1], -10f64.to_radians().sin(), epsilon = 1e-12);
    }

    #[test]
    fn absent_frames_are_gaps_and_empty_fields_are_missing() {
        let text = log().replace(",102,", ",105,");
        let log = parse(&text, &[1]).unwrap();
        assert_eq!(log.gaps.len(), 1);
        assert_eq!(log.gaps[0].row, 2);
        assert_eq!(log.gaps[0].frames, 3.0);
        assert!(log.gap_between(1, 2) && !log.gap_between(0, 1));
        let text = "Frame#,TransformStatus,Q0,Qx,Qy,Qz\n1,OK,,,,\n2,OK,1,0,0,0\n";
        assert_eq!(parse(text, &[1]).unwrap().missing(0), 1);
    }

    #[test]
    fn timespec_columns_measure_the_rate_of_the_frame_counter() {
        let text = "Frame#,timespec_s,timespec_ns,TransformStatus,Q0,Qx,Qy,Qz\n\
                    7,1000,500000000,OK,1,0,0,0\n9,1000,550000000,OK,1,0,0,0\n10,1000,575000000,OK,1,0,0,0\n";
        let log = TrackerLog::parse(
            text,
            None,
            &ReadOptions {
                tools: &[1],
                frame_hz: None,
                extra_column: None,
            },
        )
        .unwrap();
        assert_relative_eq!(log.rate_hz, 40.0, epsilon = 1e-6);
        assert_eq!(log.rate_source, RateSource::Measured);
        assert_relative_eq!(log.tau_s[1], 0.05, epsilon = 1e-9);
    }

    #[test]
    fn a_cut_last_line_is_dropped_with_a_warning() {
        let mut text = log();
        text.truncate(text.len() - 12);
        let log = parse(&text, &[1]).unwrap();
        assert_eq!(log.tau_s.len(), 2);
        assert!(
            log.warnings[0].contains("line 4, the last"),
            "{:?}",
            log.warnings
        );
    }

    #[test]
    fn the_sync_column_is_found_by_name() {
        let text = "Frame#,Sync,Q0,Qx,Qy,Qz\n1,0,1,0,0,0\n\n2,1,1,0,0,0\n";
        let read = |text: &str, column: &str| {
            TrackerLog::parse(
                text,
                None,
                &ReadOptions {
                    tools: &[1],
                    frame_hz: Some(40.0),
                    extra_column: Some(column),
                },
            )
        };
        assert_eq!(read(text, "sync").unwrap().extra, [0.0, 1.0]);
        let err = read(text, "TTL").unwrap_err().to_string();
        assert!(
            err.contains("\"TTL\"") && err.contains("Frame#,Sync,Q0"),
            "{err}"
        );
        let err = read(&text.replace(",0,1,0,0,0", ",high,1,0,0,0"), "Sync")
            .unwrap_err()
            .to_string();
        assert!(err.contains("line 2") && err.contains("high"), "{err}");
    }

    #[test]
    fn bad_logs_name_the_line_and_value() {
        let table = [
            (
                log().replacen(",OK,1,0,0,0,1,2,3", ",OK,1.01,0,0,0,1,2,3", 1),
                "line 2: tool 1's quaternion has norm 1.01",
            ),
            (
                log().replacen(",102,", ",100,", 1),
                "line 4: time 0 s does not increase",
            ),
            (
                log().replacen(",OK,1,0,0,0,1,2,3", ",OK,one,0,0,0,1,2,3", 1),
                "line 2: Q0 = \"one\"",
            ),
            ("Frame\n1\n".to_string(), "no \"Frame#\" column"),
            ("Sample:,qoa\n1,1\n".to_string(), "--tracker-map"),
        ];
        for (text, needle) in table {
            let err = parse(&text, &[1]).unwrap_err().to_string();
            assert!(err.contains(needle), "{needle}: {err}");
        }
        let err = parse(&log(), &[3]).unwrap_err().to_string();
        assert!(err.contains("no tool 3 (its map lists 2"), "{err}");
        assert!(TrackerLog::parse(
            &log(),
            None,
            &ReadOptions {
                tools: &[1],
                frame_hz: Some(0.0),
                extra_column: None
            }
        )
        .is_err());
    }
}
