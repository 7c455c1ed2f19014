//! Nothing is imported that the recording's own readers refuse: the options and every DAQ
//! value are checked, before any work, with the rules [`Recording::read`] applies — a finite,
//! positive divider and supply; each sensor voltage strictly between the rails `0` and
//! `--supply-v` (where a finite sensor resistance explains it) and within ±1000 V; the stroke
//! within ±1000 mm — naming the DAQ row, its time and the channel. The recording is checked
//! again as a whole before it is returned ([`Recording::check`]) and read back before it is
//! committed ([`Recording::stage_checked`]).
//!
//! [`Recording::read`]: crate::recording::Recording::read
//! [`Recording::check`]: crate::recording::Recording::check
//! [`Recording::stage_checked`]: crate::recording::Recording::stage_checked

use crate::limits::short;
use crate::recording::{within_rails, MAX_ABS_STROKE_MM, MAX_ABS_VOLTS};

use super::daq_csv::DaqTable;
use super::{ImportError, ImportRequest};

/// The largest `--max-offset-s` (s): an hour between two clocks is not one bench run.
pub const MAX_OFFSET_LIMIT_S: f64 = 3600.0;

/// Checks the options that need no file.
///
/// # Errors
/// [`ImportError::Options`] naming the option, its value and what it must be.
pub fn check_options(req: &ImportRequest<'_>) -> Result<(), ImportError> {
    if req.voltage_channels.is_empty() || req.voltage_channels.len() > 2 {
        return Err(ImportError::Options(format!(
            "--voltage names {} channels; a joint has 1 or 2 sensors",
            req.voltage_channels.len()
        )));
    }
    check_settings(req)
}

/// Checks the options that need no file but the count of voltage channels (which the caller
/// checks against its joint's or robot's sensors).
///
/// # Errors
/// [`ImportError::Options`] naming the option, its value and what it must be.
pub fn check_settings(req: &ImportRequest<'_>) -> Result<(), ImportError> {
    let bad = |message: String| Err(ImportError::Options(message));
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if req.divider_ohm.len() != req.voltage_channels.len() {
        return bad(format!(
            "--divider-ohm gives {} resistors for {} voltage channels",
            req.divider_ohm.len(),
            req.voltage_channels.len()
        ));
    }
    if let Some(r) = req.divider_ohm.iter().find(|r| !positive(**r)) {
        return bad(format!(
            "--divider-ohm {} is not a resistance (finite and above 0 Ω)",
            short(*r)
        ));
    }
    if !positive(req.supply_v) {
        return bad(format!(
            "--supply-v {} is not a supply voltage (finite and above 0)",
            short(req.supply_v)
        ));
    }
    if !(req.stroke.1.is_finite() && req.stroke.1 != 0.0) {
        return bad(format!(
            "--stroke-mm-per-v {} is not a scale (finite and not 0)",
            short(req.stroke.1)
        ));
    }
    if !positive(req.rest_s) {
        return bad(format!(
            "--rest-s {} is not a duration (finite and above 0 s)",
            short(req.rest_s)
        ));
    }
    if !(positive(req.max_offset_s) && req.max_offset_s <= MAX_OFFSET_LIMIT_S) {
        return bad(format!(
            "--max-offset-s {} is out of range: above 0, at most {MAX_OFFSET_LIMIT_S} s",
            short(req.max_offset_s)
        ));
    }
    Ok(())
}

/// Checks every DAQ value the recording will hold: the voltage channels (the first
/// `req.voltage_channels.len()` of `daq`) and the strokes (the next, one per scale of
/// `mm_per_v`), named by `names`.
///
/// # Errors
/// [`ImportError::Value`] naming the row (1-based, as the DAQ file's samples count), its time,
/// the channel, the value and the rule.
pub fn check_daq(
    req: &ImportRequest<'_>,
    daq: &DaqTable,
    names: &[&str],
    mm_per_v: &[f64],
) -> Result<(), ImportError> {
    let sensors = req.voltage_channels.len();
    let at = |i: usize, name: &str| {
        format!(
            "DAQ row {} (t = {:.4} s), channel {name}",
            i + 1,
            daq.time_s[i]
        )
    };
    for (c, values) in daq
        .channels
        .iter()
        .enumerate()
        .take(sensors + mm_per_v.len())
    {
        let name = names.get(c).copied().unwrap_or("?");
        for (i, &v) in values.iter().enumerate() {
            if v.abs() > MAX_ABS_VOLTS {
                return Err(ImportError::Value(format!(
                    "{}: {} V is beyond the limit of ±{MAX_ABS_VOLTS} V a recording holds",
                    at(i, name),
                    short(v)
                )));
            }
            if c < sensors && !within_rails(v, req.supply_v) {
                return Err(ImportError::Value(format!(
                    "{}: {} V is at or beyond a rail: a divider's voltage lies strictly between 0 and the supply, --supply-v {} V (is --supply-v right, and is {name} a sensor's divider?)",
                    at(i, name),
                    short(v),
                    short(req.supply_v)
                )));
            }
            let scale = c.checked_sub(sensors).and_then(|k| mm_per_v.get(k));
            if let Some(&scale) = scale.filter(|&&k| (v * k).abs() > MAX_ABS_STROKE_MM) {
                return Err(ImportError::Value(format!(
                    "{}: {} V × --stroke-mm-per-v {} is a stroke of {} mm, beyond the limit of ±{MAX_ABS_STROKE_MM} mm",
                    at(i, name),
                    short(v),
                    short(scale),
                    short(v * scale)
                )));
            }
        }
    }
    Ok(())
}

/// With `--daq-rate-hz` given, the DAQ's sample count must agree with its time: a time column
/// that spans more than its samples at that rate do shows samples the DAQ lost (an uneven
/// clock, found before it is aligned as if even).
///
/// # Errors
/// [`ImportError::Value`] naming both spans.
pub fn check_rate(req: &ImportRequest<'_>, daq: &DaqTable) -> Result<(), ImportError> {
    let Some(hz) = req.daq_rate_hz else {
        return Ok(());
    };
    let n = daq.time_s.len();
    let span_s = daq.time_s[n - 1] - daq.time_s[0];
    let counted_s = (n - 1) as f64 / hz;
    if (span_s - counted_s).abs() > super::align::JUMP_PERIODS / hz {
        return Err(ImportError::Value(format!(
            "the DAQ's time spans {span_s:.4} s, but its {n} samples at --daq-rate-hz {} span {counted_s:.4} s: the DAQ lost samples (or the rate is wrong); leave out --daq-rate-hz to align by the time column, stretch by stretch",
            short(hz)
        )));
    }
    Ok(())
}
