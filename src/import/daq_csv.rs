//! A DAQ's CSV export: a header row naming the channels, then one row per sample. Time comes
//! from a column named `time_s`, `time`, `Time` or `t` (or `--time-column NAME`), or from a
//! stated rate.

/// Why a DAQ CSV could not be read.
#[derive(Debug, thiserror::Error)]
pub enum DaqCsvError {
    /// No header row.
    #[error("the DAQ file is empty")]
    Empty,
    /// A channel asked for is not in the header.
    #[error("the DAQ file has no channel {channel:?} (its columns: {found})")]
    NoChannel {
        /// The name asked for.
        channel: String,
        /// The header.
        found: String,
    },
    /// No time column and no rate.
    #[error("the DAQ file has no time column (time_s, time, Time or t; or name it with --time-column) and no --daq-rate-hz was given")]
    NoTime,
    /// A field that is not a finite number.
    #[error("DAQ line {line}: {column} = {text:?} is not a finite number")]
    Number {
        /// 1-based line.
        line: usize,
        /// Column.
        column: String,
        /// The field, at most 200 characters.
        text: String,
    },
    /// Time does not increase.
    #[error("DAQ line {line}: time {time_s} does not increase (previous {previous_s})")]
    Time {
        /// 1-based line.
        line: usize,
        /// This row's time (s).
        time_s: f64,
        /// The previous row's (s).
        previous_s: f64,
    },
    /// Fewer rows than an import needs.
    #[error("the DAQ file has {rows} rows; an import needs at least {min}")]
    TooShort {
        /// Rows read.
        rows: usize,
        /// Needed.
        min: usize,
    },
    /// A bad rate.
    #[error("--daq-rate-hz {hz} is not a rate (finite and above 0)")]
    Rate {
        /// The rate.
        hz: f64,
    },
}

/// The fewest rows an import accepts.
pub const MIN_ROWS: usize = 100;

/// Names a time column may have, in the order they are looked for.
pub const TIME_NAMES: [&str; 4] = ["time_s", "time", "Time", "t"];

/// The channels asked for, on one time base starting at 0 (the first DAQ sample).
#[derive(Debug, Clone, PartialEq)]
pub struct DaqTable {
    /// Time from the first sample (s).
    pub time_s: Vec<f64>,
    /// Per channel asked for, in the order asked: its samples.
    pub channels: Vec<Vec<f64>>,
}

impl DaqTable {
    /// Parses `text`, keeping `channels` by header name.
    ///
    /// # Errors
    /// [`DaqCsvError`] naming the line, the column and the value.
    pub fn parse(
        text: &str,
        channels: &[&str],
        time_column: Option<&str>,
        rate_hz: Option<f64>,
    ) -> Result<Self, DaqCsvError> {
        if let Some(hz) = rate_hz {
            if !(hz.is_finite() && hz > 0.0) {
                return Err(DaqCsvError::Rate { hz });
            }
        }
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, head) = lines.next().ok_or(DaqCsvError::Empty)?;
        let header: Vec<&str> = head.split(',').map(str::trim).collect();
        let find = |name: &str| header.iter().position(|h| *h == name);
        let at: Vec<usize> = channels
            .iter()
            .map(|c| {
                find(c).ok_or_else(|| DaqCsvError::NoChannel {
                    channel: (*c).to_owned(),
                    found: header.join(","),
                })
            })
            .collect::<Result<_, _>>()?;
        let time_at = match time_column {
            Some(name) => Some(find(name).ok_or_else(|| DaqCsvError::NoChannel {
                channel: name.to_owned(),
                found: header.join(","),
            })?),
            None => TIME_NAMES.iter().find_map(|n| find(n)),
        };
        if time_at.is_none() && rate_hz.is_none() {
            return Err(DaqCsvError::NoTime);
        }
        let mut table = DaqTable {
            time_s: Vec::new(),
            channels: vec![Vec::new(); channels.len()],
        };
        let mut first_time = None;
        for (index, line) in lines {
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            let number = |col: usize| -> Result<f64, DaqCsvError> {
                let text = fields.get(col).copied().unwrap_or("");
                text.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| DaqCsvError::Number {
                        line: index + 1,
                        column: header.get(col).copied().unwrap_or("?").to_owned(),
                        text: text.chars().take(200).collect(),
                    })
            };
            let t = match (time_at, rate_hz) {
                (Some(col), _) => {
                    let raw = number(col)?;
                    raw - *first_time.get_or_insert(raw)
                }
                (None, Some(hz)) => table.time_s.len() as f64 / hz,
                (None, None) => return Err(DaqCsvError::NoTime),
            };
            if let Some(&previous_s) = table.time_s.last() {
                if t <= previous_s {
                    return Err(DaqCsvError::Time {
                        line: index + 1,
                        time_s: t,
                        previous_s,
                    });
                }
            }
            table.time_s.push(t);
            for (k, &col) in at.iter().enumerate() {
                table.channels[k].push(number(col)?);
            }
        }
        if table.time_s.len() < MIN_ROWS {
            return Err(DaqCsvError::TooShort {
                rows: table.time_s.len(),
                min: MIN_ROWS,
            });
        }
        Ok(table)
    }

    /// The sample rate from the time column: the median spacing's inverse (Hz).
    pub fn rate_hz(&self) -> f64 {
        let mut d: Vec<f64> = self.time_s.windows(2).map(|w| w[1] - w[0]).collect();
        d.sort_by(f64::total_cmp);
        1.0 / d[d.len() / 2]
    }
}
