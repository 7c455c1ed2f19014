//! LabVIEW measurement files (`.lvm`): text, written by LabVIEW's "Write To Measurement File".
//!
//! - **The file header:** a first line `LabVIEW Measurement`, then `key<sep>value` lines up to
//!   `***End_of_Header***`; read here: `Separator` (`Tab` or `Comma`: the character between
//!   every field of the file) and `Decimal_Separator` (`.` or `,`).
//! - **Segments:** each a header from `Channels` to `***End_of_Header***` with one value per
//!   channel on its `Samples`, `X0` and `Delta_X` lines, then a row of column names that
//!   starts with `X_Value`, then the data rows. With `X_Columns` `Multi` each channel has its
//!   own `X_Value` column before it; with `No` the `X_Value` fields are empty. A file without
//!   per-segment headers (`Multi_Headings` `No` after the first) runs its rows on.
//! - **Time:** `--time-column CH` if given, else `--daq-rate-hz`, else the `X_Value` column
//!   before the first channel asked for, or where its fields are empty `X0 + i·Delta_X` of that
//!   channel (`i` counting the segment's rows); zero is the first sample.

use super::daq_csv::{DaqTable, MIN_ROWS};

/// The first line of a LabVIEW measurement file.
const MAGIC: &str = "LabVIEW Measurement";
/// The line that ends the file header and each segment header.
const END_OF_HEADER: &str = "***End_of_Header***";
/// The name of a time column.
const X_VALUE: &str = "X_Value";
/// The keys that can open a segment header (NI's LVM description: `Notes`, `Test_Name`, …
/// may come before `Channels`; LabVIEW writes `Notes` there).
const SEGMENT_KEYS: [&str; 8] = [
    "Channels",
    "Notes",
    "Test_Name",
    "Test_Numbers",
    "Test_Series",
    "UUT_Name",
    "UUT_M/N",
    "UUT_S/N",
];
/// The name of LabVIEW's comment column.
const COMMENT: &str = "Comment";

/// Why a LabVIEW measurement file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum LvmError {
    /// The first line is not `LabVIEW Measurement`.
    #[error("the first line is {found:?}, not \"LabVIEW Measurement\" (is this an .lvm file?)")]
    NotLvm {
        /// The first line, at most 80 characters.
        found: String,
    },
    /// A header value dlw does not know.
    #[error("line {line}: {key} {value:?} is not one of {known}")]
    Header {
        /// 1-based line.
        line: usize,
        /// The key.
        key: &'static str,
        /// Its value.
        value: String,
        /// The values known.
        known: &'static str,
    },
    /// A header without its end.
    #[error("the {what} starting on line {line} has no {END_OF_HEADER} line")]
    NoEndOfHeader {
        /// `file header` or `segment header`.
        what: &'static str,
        /// 1-based line.
        line: usize,
    },
    /// A segment without a row of column names.
    #[error("the segment header ending on line {line} is not followed by a row of column names")]
    NoColumns {
        /// 1-based line.
        line: usize,
    },
    /// A channel asked for is not in a segment's columns.
    #[error("line {line}: the segment has no channel {channel:?} (its columns: {found})")]
    NoChannel {
        /// The column-name row's line.
        line: usize,
        /// The name asked for.
        channel: String,
        /// The columns.
        found: String,
    },
    /// A field that is not a finite number.
    #[error(
        "line {line}: {column} = {text:?} is not a finite number (decimal separator {decimal:?})"
    )]
    Number {
        /// 1-based line.
        line: usize,
        /// The column.
        column: String,
        /// The field, at most 200 characters.
        text: String,
        /// The decimal separator in force.
        decimal: char,
    },
    /// Time that does not increase.
    #[error("line {line}: time {time_s} s does not come after {previous_s} s")]
    Time {
        /// 1-based line.
        line: usize,
        /// This row's time (s).
        time_s: f64,
        /// The previous row's (s).
        previous_s: f64,
    },
    /// No time for a row.
    #[error("line {line}: the X_Value field is empty and the segment header gives no X0 and Delta_X for {channel:?}; give --daq-rate-hz")]
    NoTime {
        /// 1-based line.
        line: usize,
        /// The channel whose X0 was looked for.
        channel: String,
    },
    /// A bad `Delta_X` or rate.
    #[error("{what} {value} is not a sample interval (finite and above 0)")]
    Rate {
        /// Which value.
        what: String,
        /// The value.
        value: f64,
    },
    /// No channel was asked for.
    #[error("no LVM channel was asked for")]
    NothingAsked,
    /// Fewer rows than an import needs.
    #[error("the LVM file has {rows} data rows; an import needs at least {min}")]
    TooShort {
        /// Rows read.
        rows: usize,
        /// Needed.
        min: usize,
    },
}

/// The file header's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Format {
    separator: char,
    decimal: char,
}

impl Format {
    fn number(&self, field: &str) -> Option<f64> {
        let field = field.trim();
        let parsed = if self.decimal == ',' {
            field.replace(',', ".").parse::<f64>()
        } else {
            field.parse::<f64>()
        };
        parsed.ok().filter(|v| v.is_finite())
    }
}

/// One segment's timing, per channel in the header's order.
#[derive(Debug, Clone, Default, PartialEq)]
struct SegmentTiming {
    x0: Vec<String>,
    delta_x: Vec<String>,
}

/// Where the channels asked for are in the current segment's columns.
#[derive(Debug, Clone)]
struct Columns {
    names: Vec<String>,
    channels: Vec<usize>,
    /// The `X_Value` column before the first channel asked for.
    x: Option<usize>,
    /// The first channel's index among the segment header's channels.
    header_index: usize,
    time: Option<usize>,
}

/// The channels of the LVM text `text`, in the order of its first row of column names
/// (without `X_Value` and `Comment` columns).
///
/// # Errors
/// [`LvmError`] for a file header that cannot be read, or no row of column names.
pub fn channel_names(text: &str) -> Result<Vec<String>, LvmError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let format = file_header(&mut lines)?;
    let (_, row) = lines
        .find(|(_, l)| l.split(format.separator).next().map(str::trim) == Some(X_VALUE))
        .ok_or(LvmError::NoColumns { line: 1 })?;
    Ok(row
        .split(format.separator)
        .map(str::trim)
        .filter(|n| !n.is_empty() && *n != X_VALUE && *n != COMMENT)
        .map(str::to_owned)
        .collect())
}

/// The units the first segment header gives the channels of [`channel_names`], in its order
/// (`Y_Unit_Label`, whose fields stand above the columns they describe, an `X_Value` column's
/// empty; `None` for an empty field or a file without the line).
///
/// # Errors
/// [`LvmError`] for a file header that cannot be read.
pub fn units(text: &str) -> Result<Vec<Option<String>>, LvmError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let format = file_header(&mut lines)?;
    let mut labels: Vec<&str> = Vec::new();
    for (_, l) in lines {
        let fields: Vec<&str> = l.split(format.separator).map(str::trim).collect();
        match fields[0] {
            "Y_Unit_Label" => labels = fields,
            X_VALUE => {
                return Ok(fields
                    .iter()
                    .enumerate()
                    .filter(|(_, n)| !n.is_empty() && **n != X_VALUE && **n != COMMENT)
                    .map(|(p, _)| {
                        labels
                            .get(p)
                            .filter(|u| !u.is_empty() && p > 0)
                            .map(|u| (*u).to_owned())
                    })
                    .collect())
            }
            _ => {}
        }
    }
    Ok(Vec::new())
}

/// The channels asked for from the LVM text `text`, on one time base starting at 0.
///
/// # Errors
/// [`LvmError`] naming the line, the column and the value.
pub fn daq_table(
    text: &str,
    channels: &[&str],
    time_column: Option<&str>,
    rate_hz: Option<f64>,
) -> Result<DaqTable, LvmError> {
    let table = read(text, channels, time_column, rate_hz)?;
    if table.time_s.len() < MIN_ROWS {
        return Err(LvmError::TooShort {
            rows: table.time_s.len(),
            min: MIN_ROWS,
        });
    }
    Ok(table)
}

/// [`daq_table`] without the import's least number of rows (for `dlw daq-info`).
///
/// # Errors
/// As [`daq_table`].
pub fn read(
    text: &str,
    channels: &[&str],
    time_column: Option<&str>,
    rate_hz: Option<f64>,
) -> Result<DaqTable, LvmError> {
    if channels.is_empty() {
        return Err(LvmError::NothingAsked);
    }
    if let Some(hz) = rate_hz {
        if !(hz.is_finite() && hz > 0.0) {
            return Err(LvmError::Rate {
                what: "--daq-rate-hz gives an interval of".into(),
                value: 1.0 / hz,
            });
        }
    }
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let format = file_header(&mut lines)?;
    let mut table = DaqTable {
        time_s: Vec::new(),
        channels: vec![Vec::new(); channels.len()],
    };
    let mut raw_time = Vec::new();
    let mut timing = SegmentTiming::default();
    let mut columns: Option<Columns> = None;
    let mut row_in_segment = 0usize;
    while let Some((line, l)) = lines.next() {
        let fields: Vec<&str> = l.split(format.separator).collect();
        let first = fields[0].trim();
        if fields.iter().all(|f| f.trim().is_empty()) {
            continue;
        }
        if SEGMENT_KEYS.contains(&first) {
            timing = segment_header(&mut lines, &format, line)?;
            let (names_line, names) =
                next_nonempty(&mut lines).ok_or(LvmError::NoColumns { line })?;
            columns = Some(locate(&format, names_line, names, channels, time_column)?);
            row_in_segment = 0;
            continue;
        }
        if first == X_VALUE {
            // Column names without a segment header before them: no X0 or Delta_X.
            timing = SegmentTiming::default();
            columns = Some(locate(&format, line, l, channels, time_column)?);
            row_in_segment = 0;
            continue;
        }
        let cols = columns.as_ref().ok_or(LvmError::NoColumns { line })?;
        let number = |col: usize| -> Result<f64, LvmError> {
            let text = fields.get(col).copied().unwrap_or("");
            format.number(text).ok_or_else(|| LvmError::Number {
                line,
                column: cols.names.get(col).cloned().unwrap_or_default(),
                text: text.chars().take(200).collect(),
                decimal: format.decimal,
            })
        };
        for (k, &col) in cols.channels.iter().enumerate() {
            table.channels[k].push(number(col)?);
        }
        let t = match (cols.time, rate_hz) {
            (Some(col), _) => number(col)?,
            (None, Some(hz)) => table.time_s.len() as f64 / hz,
            (None, None) => row_time(
                &format,
                cols,
                &timing,
                &fields,
                row_in_segment,
                line,
                channels[0],
            )?,
        };
        raw_time.push((line, t));
        table.time_s.push(t);
        row_in_segment += 1;
    }
    let Some(&(_, t0)) = raw_time.first() else {
        return Ok(table);
    };
    for (i, &(line, t)) in raw_time.iter().enumerate() {
        table.time_s[i] = t - t0;
        if i > 0 && table.time_s[i] <= table.time_s[i - 1] {
            return Err(LvmError::Time {
                line,
                time_s: table.time_s[i],
                previous_s: table.time_s[i - 1],
            });
        }
    }
    Ok(table)
}

/// Reads the file header up to its end line: the separator and the decimal separator.
fn file_header<'a, I: Iterator<Item = (usize, &'a str)>>(
    lines: &mut I,
) -> Result<Format, LvmError> {
    let first = lines.next().map_or("", |(_, l)| l);
    if !first.trim_start_matches('\u{feff}').starts_with(MAGIC) {
        return Err(LvmError::NotLvm {
            found: first.chars().take(80).collect(),
        });
    }
    let mut format = Format {
        separator: '\t',
        decimal: '.',
    };
    for (line, l) in lines.by_ref() {
        if l.trim_end_matches(['\t', ',', ' ', '\r']) == END_OF_HEADER {
            return Ok(format);
        }
        if let Some(rest) = l.strip_prefix("Separator") {
            let value = rest
                .trim_start_matches(['\t', ','])
                .split(['\t', ','])
                .next()
                .unwrap_or("")
                .trim();
            format.separator = match value {
                "Tab" => '\t',
                "Comma" => ',',
                _ => {
                    return Err(LvmError::Header {
                        line,
                        key: "Separator",
                        value: value.to_owned(),
                        known: "Tab, Comma",
                    })
                }
            };
        } else if let Some(rest) = l.strip_prefix("Decimal_Separator") {
            let value = rest
                .strip_prefix(format.separator)
                .unwrap_or(rest)
                .split(format.separator)
                .next()
                .unwrap_or("")
                .trim();
            format.decimal = match value {
                "." => '.',
                "," => ',',
                _ => {
                    return Err(LvmError::Header {
                        line,
                        key: "Decimal_Separator",
                        value: value.to_owned(),
                        known: "., ,",
                    })
                }
            };
        }
    }
    Err(LvmError::NoEndOfHeader {
        what: "file header",
        line: 1,
    })
}

/// Reads a segment header (after its `Channels` line) up to its end line.
fn segment_header<'a, I: Iterator<Item = (usize, &'a str)>>(
    lines: &mut I,
    format: &Format,
    start: usize,
) -> Result<SegmentTiming, LvmError> {
    let mut timing = SegmentTiming::default();
    for (_, l) in lines.by_ref() {
        let mut fields = l.split(format.separator);
        let key = fields.next().unwrap_or("").trim();
        let values = || {
            fields
                .clone()
                .map(|f| f.trim().to_owned())
                .filter(|f| !f.is_empty())
                .collect::<Vec<_>>()
        };
        match key {
            END_OF_HEADER => return Ok(timing),
            "X0" => timing.x0 = values(),
            "Delta_X" => timing.delta_x = values(),
            _ => {}
        }
    }
    Err(LvmError::NoEndOfHeader {
        what: "segment header",
        line: start,
    })
}

fn next_nonempty<'a, I: Iterator<Item = (usize, &'a str)>>(
    lines: &mut I,
) -> Option<(usize, &'a str)> {
    lines.find(|(_, l)| !l.trim().is_empty())
}

/// Finds the channels asked for, the time column and the X column in a column-name row.
fn locate(
    format: &Format,
    line: usize,
    row: &str,
    channels: &[&str],
    time_column: Option<&str>,
) -> Result<Columns, LvmError> {
    let names: Vec<String> = row
        .split(format.separator)
        .map(|f| f.trim().to_owned())
        .collect();
    let find = |name: &str| {
        names
            .iter()
            .position(|n| n == name)
            .ok_or_else(|| LvmError::NoChannel {
                line,
                channel: name.to_owned(),
                found: names
                    .iter()
                    .filter(|n| !n.is_empty() && *n != X_VALUE && *n != COMMENT)
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    };
    let at: Vec<usize> = channels.iter().map(|c| find(c)).collect::<Result<_, _>>()?;
    let time = time_column.map(find).transpose()?;
    let first = at[0];
    let x = names[..first].iter().rposition(|n| n == X_VALUE);
    let header_index = names[..first]
        .iter()
        .filter(|n| *n != X_VALUE && !n.is_empty())
        .count();
    Ok(Columns {
        names,
        channels: at,
        x,
        header_index,
        time,
    })
}

/// A row's time from its `X_Value` field, or from the segment's `X0` and `Delta_X`.
fn row_time(
    format: &Format,
    cols: &Columns,
    timing: &SegmentTiming,
    fields: &[&str],
    row: usize,
    line: usize,
    channel: &str,
) -> Result<f64, LvmError> {
    let x_field = cols.x.and_then(|c| fields.get(c)).map_or("", |f| f.trim());
    if !x_field.is_empty() {
        return format.number(x_field).ok_or_else(|| LvmError::Number {
            line,
            column: X_VALUE.to_owned(),
            text: x_field.chars().take(200).collect(),
            decimal: format.decimal,
        });
    }
    let pick = |v: &[String]| {
        v.get(cols.header_index)
            .or_else(|| v.first())
            .and_then(|f| format.number(f))
    };
    let (Some(x0), Some(dx)) = (pick(&timing.x0), pick(&timing.delta_x)) else {
        return Err(LvmError::NoTime {
            line,
            channel: channel.to_owned(),
        });
    };
    if dx <= 0.0 {
        return Err(LvmError::Rate {
            what: format!("line {line}: the segment's Delta_X"),
            value: dx,
        });
    }
    Ok(x0 + row as f64 * dx)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lvm(sep: &str, decimal: &str, x: bool, rows: usize) -> String {
        let mut s = format!(
            "LabVIEW Measurement{sep}\nWriter_Version{sep}2\nReader_Version{sep}2\nSeparator{sep}{}\nDecimal_Separator{sep}{decimal}\nMulti_Headings{sep}No\nX_Columns{sep}{}\n***End_of_Header***{sep}\n{sep}\n",
            if sep == "\t" { "Tab" } else { "Comma" },
            if x { "One" } else { "No" },
        );
        s += &format!("Channels{sep}2{sep}\nSamples{sep}{rows}{sep}{rows}\nX0{sep}1{d}5{sep}1{d}5\nDelta_X{sep}0{d}002{sep}0{d}002\n***End_of_Header***{sep}\nX_Value{sep}A{sep}B{sep}Comment\n", d = decimal);
        for i in 0..rows {
            let t = if x {
                format!("{}", 1.5 + i as f64 * 0.002)
            } else {
                String::new()
            };
            let a = format!("{}", i as f64 * 0.25);
            let b = format!("{}", -(i as f64));
            let fix = |v: String| {
                if decimal == "," {
                    v.replace('.', ",")
                } else {
                    v
                }
            };
            s += &format!("{}{sep}{}{sep}{}\n", fix(t), fix(a), fix(b));
        }
        s
    }

    #[test]
    fn tab_comma_and_decimal_comma_read_alike() {
        for (sep, decimal, x) in [("\t", ".", true), (",", ".", true), ("\t", ",", false)] {
            let text = lvm(sep, decimal, x, 150);
            let t = daq_table(&text, &["B", "A"], None, None).unwrap();
            assert_eq!(t.time_s.len(), 150, "{sep:?} {decimal}");
            assert!(
                (t.time_s[149] - 149.0 * 0.002).abs() < 1e-9,
                "{}",
                t.time_s[149]
            );
            assert_eq!(t.channels[0][3], -3.0);
            assert_eq!(t.channels[1][3], 0.75);
        }
    }

    /// `X_Columns` `Multi`: each channel's time is the `X_Value` column before it.
    #[test]
    fn multi_x_columns_give_each_channel_its_own_time() {
        let mut text = String::from(
            "LabVIEW Measurement\nSeparator\tTab\nDecimal_Separator\t.\nX_Columns\tMulti\n***End_of_Header***\n\nChannels\t2\nX0\t0\t0\nDelta_X\t1\t1\n***End_of_Header***\nX_Value\tA\tX_Value\tB\tComment\n",
        );
        for i in 0..120 {
            text += &format!(
                "{}\t{i}\t{}\t{}\n",
                i as f64 * 0.01,
                5.0 + i as f64 * 0.02,
                -i
            );
        }
        let a = daq_table(&text, &["A"], None, None).unwrap();
        assert!((a.time_s[100] - 1.0).abs() < 1e-12, "{}", a.time_s[100]);
        let b = daq_table(&text, &["B"], None, None).unwrap();
        assert!((b.time_s[100] - 2.0).abs() < 1e-12, "{}", b.time_s[100]);
        assert_eq!(b.channels[0][7], -7.0);
    }

    #[test]
    fn bad_files_name_the_problem() {
        let err = daq_table("time,a\n1,2\n", &["a"], None, None).unwrap_err();
        assert!(matches!(err, LvmError::NotLvm { .. }), "{err}");
        let text = lvm("\t", ".", true, 150);
        let err = daq_table(&text, &["C"], None, None)
            .unwrap_err()
            .to_string();
        assert!(err.contains("\"C\"") && err.contains("A, B"), "{err}");
        let bad = text.replacen("0.25\t", "0.2x5\t", 1);
        let err = daq_table(&bad, &["A"], None, None).unwrap_err().to_string();
        assert!(err.contains("0.2x5") && err.contains("line"), "{err}");
        let err = daq_table(&lvm("\t", ".", true, 20), &["A"], None, None).unwrap_err();
        assert!(matches!(err, LvmError::TooShort { rows: 20, .. }), "{err}");
        let cut = &text[..text.find("X0").unwrap()];
        let err = daq_table(cut, &["A"], None, None).unwrap_err();
        assert!(matches!(err, LvmError::NoEndOfHeader { .. }), "{err}");
    }
}
