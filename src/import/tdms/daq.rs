//! A TDMS file's channels as a DAQ table for an import: one time base starting at 0.

use super::super::daq_csv::{DaqTable, MIN_ROWS, TIME_NAMES};
use super::{ChannelId, TdmsError, TdmsFile};

/// How channels' `wf_increment` may differ, relatively, and still be one clock.
const INCREMENT_TOLERANCE: f64 = 1e-9;

/// The channels asked for from the TDMS file `bytes`, on one time base starting at 0: from
/// `time_column` (a channel) if given, else `rate_hz` if given, else the channels'
/// `wf_increment`, else a channel named `time_s`, `time`, `Time` or `t`.
///
/// # Errors
/// [`TdmsError`] naming the channel and the value.
pub fn daq_table(
    bytes: &[u8],
    channels: &[&str],
    time_column: Option<&str>,
    rate_hz: Option<f64>,
) -> Result<DaqTable, TdmsError> {
    if channels.is_empty() {
        return Err(TdmsError::NothingAsked);
    }
    let file = TdmsFile::parse(bytes)?;
    let ids: Vec<ChannelId> = channels
        .iter()
        .map(|c| file.find(c))
        .collect::<Result<_, _>>()?;
    let mut columns = Vec::with_capacity(ids.len());
    for &id in &ids {
        let values = file.values(id)?;
        if let Some(first) = columns.first().map(Vec::len) {
            if values.len() != first {
                return Err(TdmsError::Lengths {
                    first: file.name(ids[0]),
                    first_len: first,
                    other: file.name(id),
                    other_len: values.len(),
                });
            }
        }
        columns.push(values);
    }
    let n = columns.first().map_or(0, Vec::len);
    if n < MIN_ROWS {
        return Err(TdmsError::TooShort {
            rows: n,
            min: MIN_ROWS,
        });
    }
    let time_s = time_base(&file, &ids, n, time_column, rate_hz)?;
    Ok(DaqTable {
        time_s,
        channels: columns,
    })
}

/// The time of `n` samples of channels `ids` (s from the first), as [`daq_table`] chooses it.
fn time_base(
    file: &TdmsFile<'_>,
    ids: &[ChannelId],
    n: usize,
    time_column: Option<&str>,
    rate_hz: Option<f64>,
) -> Result<Vec<f64>, TdmsError> {
    let regular = |dt: f64, what: String| {
        if dt.is_finite() && dt > 0.0 {
            Ok((0..n).map(|i| i as f64 * dt).collect())
        } else {
            Err(TdmsError::Rate { what, value: dt })
        }
    };
    if let Some(name) = time_column {
        return time_channel(file, file.find(name)?, n, &file.name(ids[0]));
    }
    if let Some(hz) = rate_hz {
        return regular(1.0 / hz, format!("--daq-rate-hz {hz} gives an interval of"));
    }
    let increments: Vec<Option<f64>> = ids
        .iter()
        .map(|&id| file.waveform(id).increment_s)
        .collect();
    if let Some(dt) = increments[0] {
        for (k, inc) in increments.iter().enumerate().skip(1) {
            let other = inc.unwrap_or(f64::NAN);
            if other.is_nan() || (other - dt).abs() > INCREMENT_TOLERANCE * dt.abs() {
                return Err(TdmsError::Increments {
                    first: file.name(ids[0]),
                    first_s: dt,
                    other: file.name(ids[k]),
                    other_s: other,
                });
            }
        }
        return regular(dt, format!("{}'s wf_increment", file.name(ids[0])));
    }
    let named = TIME_NAMES.iter().find_map(|t| file.find(t).ok());
    match named {
        Some(id) => time_channel(file, id, n, &file.name(ids[0])),
        None => Err(TdmsError::NoTime),
    }
}

/// A time channel's values from its first, checked to increase and to match the data's length.
fn time_channel(
    file: &TdmsFile<'_>,
    id: ChannelId,
    n: usize,
    data_channel: &str,
) -> Result<Vec<f64>, TdmsError> {
    let raw = file.values(id)?;
    if raw.len() != n {
        return Err(TdmsError::Lengths {
            first: data_channel.to_owned(),
            first_len: n,
            other: file.name(id),
            other_len: raw.len(),
        });
    }
    let t0 = raw[0];
    let time_s: Vec<f64> = raw.iter().map(|t| t - t0).collect();
    if let Some(i) = time_s.windows(2).position(|w| w[1] <= w[0]) {
        return Err(TdmsError::Time {
            channel: file.name(id),
            index: i + 1,
            time_s: time_s[i + 1],
            previous_s: time_s[i],
        });
    }
    Ok(time_s)
}
