//! `--rate-hz`: the DAQ's channels on a new, uniform timeline `t_j = j / rate_hz` from the first
//! DAQ sample to its last.
//!
//! - **Down** (a rate below the DAQ's): each output sample is the mean of the DAQ samples within
//!   half an output interval of it, `[t_j − ½/rate_hz, t_j + ½/rate_hz)`: a boxcar that keeps
//!   what lies above the new Nyquist frequency from folding back as slow error, centred so it
//!   adds no lag.
//! - **Up** (a rate above the DAQ's, up to [`MAX_UPSAMPLING`] times it): linear interpolation
//!   between the DAQ samples around each output time; nothing is measured there that was not
//!   measured before.

use super::align::JUMP_PERIODS;
use super::daq_csv::{DaqTable, MIN_ROWS};

/// The most an output rate may exceed the DAQ's: beyond it, interpolation only adds rows.
pub const MAX_UPSAMPLING: f64 = 10.0;
/// The relative rounding allowed when comparing a rate with [`MAX_UPSAMPLING`] times the DAQ's.
pub const RATE_ROUNDING: f64 = 1e-9;

/// Why the DAQ could not be resampled.
#[derive(Debug, thiserror::Error)]
pub enum ResampleError {
    /// Not a rate.
    #[error("--rate-hz {hz} is not a rate (finite and above 0)")]
    Rate {
        /// The rate given.
        hz: f64,
    },
    /// Too far above the DAQ's rate.
    #[error("--rate-hz {hz} is {ratio:.1} times the DAQ's {daq_hz:.3} Hz; at most {MAX_UPSAMPLING} times is interpolated")]
    TooHigh {
        /// The rate given.
        hz: f64,
        /// The DAQ's rate.
        daq_hz: f64,
        /// Their ratio.
        ratio: f64,
    },
    /// Too few samples at the new rate.
    #[error("--rate-hz {hz} leaves {rows} samples over the DAQ's {duration_s:.3} s; an import needs at least {MIN_ROWS}")]
    TooFew {
        /// The rate given.
        hz: f64,
        /// Samples left.
        rows: usize,
        /// The DAQ's duration (s).
        duration_s: f64,
    },
}

/// `table` on the timeline `j / rate_hz`.
///
/// # Errors
/// [`ResampleError`] naming the rate and the limit.
pub fn resample(table: &DaqTable, rate_hz: f64) -> Result<DaqTable, ResampleError> {
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        return Err(ResampleError::Rate { hz: rate_hz });
    }
    let daq_hz = table.rate_hz();
    // Exactly 10 times is allowed: the rate measured from the time column's median step is
    // off by rounding (500.00000000001 Hz from steps written to 0.1 ms).
    if rate_hz > MAX_UPSAMPLING * daq_hz * (1.0 + RATE_ROUNDING) {
        return Err(ResampleError::TooHigh {
            hz: rate_hz,
            daq_hz,
            ratio: rate_hz / daq_hz,
        });
    }
    let duration_s = table.time_s.last().copied().unwrap_or(0.0);
    // The last DAQ sample's time times the rate is often a whole number off by rounding.
    let rows = (duration_s * rate_hz * (1.0 + 1e-12)).floor() as usize + 1;
    if rows < MIN_ROWS {
        return Err(ResampleError::TooFew {
            hz: rate_hz,
            rows,
            duration_s,
        });
    }
    // No output sample inside a jump of the DAQ's clock: nothing was recorded there.
    let jump = JUMP_PERIODS / daq_hz;
    let recorded = |t: f64| {
        let k = table.time_s.partition_point(|&x| x <= t);
        k == 0 || k >= table.time_s.len() || table.time_s[k] - table.time_s[k - 1] <= jump
    };
    let time_s: Vec<f64> = (0..rows)
        .map(|j| j as f64 / rate_hz)
        .filter(|&t| recorded(t))
        .collect();
    let down = rate_hz < daq_hz;
    let channels = table
        .channels
        .iter()
        .map(|values| {
            time_s
                .iter()
                .map(|&t| {
                    let boxcar = if down {
                        mean_within(&table.time_s, values, t, 0.5 / rate_hz)
                    } else {
                        None
                    };
                    boxcar.unwrap_or_else(|| held(&table.time_s, values, t))
                })
                .collect()
        })
        .collect();
    Ok(DaqTable { time_s, channels })
}

/// The mean of `values` whose times lie in `[t − half, t + half)`; `None` if none do.
fn mean_within(time_s: &[f64], values: &[f64], t: f64, half: f64) -> Option<f64> {
    let a = time_s.partition_point(|&x| x < t - half);
    let b = time_s.partition_point(|&x| x < t + half);
    (b > a).then(|| values[a..b].iter().sum::<f64>() / (b - a) as f64)
}

/// `values` at `t`, linearly between the samples around it (the end value beyond the ends);
/// the DAQ table is never empty here.
fn held(time_s: &[f64], values: &[f64], t: f64) -> f64 {
    crate::stats::interpolate_held(time_s, values, t).unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(n: usize, hz: f64) -> DaqTable {
        let time_s: Vec<f64> = (0..n).map(|i| i as f64 / hz).collect();
        let ramp = time_s.iter().map(|t| 3.0 * t - 1.0).collect();
        DaqTable {
            time_s,
            channels: vec![ramp],
        }
    }

    #[test]
    fn down_averages_and_up_interpolates() {
        let t = table(1000, 500.0);
        let down = resample(&t, 100.0).unwrap();
        assert_eq!(down.time_s.len(), 200);
        // Sample 10 (t = 0.1 s) is the mean of the DAQ's samples 48..52 (0.096..0.104 s).
        let want: f64 = (48..53).map(|i| 3.0 * i as f64 / 500.0 - 1.0).sum::<f64>() / 5.0;
        assert!((down.channels[0][10] - want).abs() < 1e-12);
        let up = resample(&t, 1000.0).unwrap();
        assert_eq!(up.time_s.len(), 1999);
        assert!((up.channels[0][3] - (3.0 * 0.003 - 1.0)).abs() < 1e-12);
    }

    #[test]
    fn rates_out_of_bounds_are_named() {
        let t = table(1000, 500.0);
        for hz in [0.0, -5.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(resample(&t, hz), Err(ResampleError::Rate { .. })));
        }
        assert!(resample(&t, 5000.0).is_ok(), "exactly 10 times");
        let err = resample(&t, 6000.0).unwrap_err().to_string();
        assert!(err.contains("6000") && err.contains("at most 10"), "{err}");
        let err = resample(&t, 10.0).unwrap_err().to_string();
        assert!(err.contains("leaves 20 samples"), "{err}");
    }
}
