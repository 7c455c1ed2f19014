//! Limits on numbers given at the command line, where a value outside them could only produce
//! overflows downstream (an infinite time, a frame count past `usize`, a filter delay of `inf`
//! samples). Each is named with its unit and documented in `docs/outputs.md`.

/// The lowest frame rate (frames per second): one frame in about 17 minutes.
pub const MIN_FPS: f64 = 1e-3;
/// The highest frame rate (frames per second): a fast X-ray detector runs at hundreds.
pub const MAX_FPS: f64 = 1e4;
/// The largest start time magnitude (s).
pub const MAX_ABS_START_S: f64 = 1e9;
/// The longest low-pass time constant (samples): 1e7 samples is 5.6 hours at 500 Hz.
pub const MAX_LOW_PASS_SAMPLES: f64 = 1e7;

/// `value` if it lies in `[low, high]`, else a message that names the option, the value and
/// the limits.
///
/// # Errors
/// The message.
pub fn within(option: &str, value: f64, low: f64, high: f64, unit: &str) -> Result<f64, String> {
    if value.is_finite() && (low..=high).contains(&value) {
        Ok(value)
    } else {
        Err(format!(
            "{option} {} is out of range: from {low} to {high} {unit}",
            short(value)
        ))
    }
}

/// A number as a person reads it in a message: plain when moderate, in exponent form when very
/// large or very small (1e308, not 309 digits).
pub fn short(value: f64) -> String {
    let a = value.abs();
    if a != 0.0 && !(1e-4..1e6).contains(&a) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_outside_are_named_with_the_limits() {
        assert_eq!(within("--fps", 2.0, MIN_FPS, MAX_FPS, "fps"), Ok(2.0));
        let e = within("--fps", 1e308, MIN_FPS, MAX_FPS, "fps").unwrap_err();
        assert!(e.contains("--fps 1e308") && e.contains("10000"), "{e}");
        assert!(within("--fps", f64::NAN, MIN_FPS, MAX_FPS, "fps").is_err());
        assert!(within("--fps", 1e-320, MIN_FPS, MAX_FPS, "fps").is_err());
    }
}
