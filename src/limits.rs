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

/// The largest recording file (`data.csv`, a DAQ export, a tracker log) read, in bytes: 4 GiB.
/// A 3000 s, two-sensor recording at 500 Hz is about 80 MB.
pub const MAX_RECORDING_BYTES: u64 = 4 << 30;
/// The largest small text input read (a design, an estimator config, a machine profile, a
/// process set, a scenario, a protocol, a desired-angle or stroke profile, `rig.toml`), in
/// bytes: 64 MiB. The shipped ones are a few kB.
pub const MAX_TEXT_INPUT_BYTES: u64 = 64 << 20;
/// The largest drawing read (`import-dxf`, `program --from-dxf`), in bytes: 512 MiB. The
/// shipped joints' DXFs are under 1 MB.
pub const MAX_DRAWING_BYTES: u64 = 512 << 20;
/// The largest image frame read (`fluoro`), in bytes: 256 MiB (a 16-bit 8k × 8k frame is
/// 128 MiB).
pub const MAX_FRAME_BYTES: u64 = 256 << 20;
/// How long the bounded reader waits for a pipe to have data before refusing it (ms): a
/// program feeding dlw (`<(zcat log.gz)`) writes its first bytes well within it; a FIFO that
/// nothing writes would otherwise block forever.
pub const PIPE_WAIT_MS: u64 = 1000;
/// The most characters of a user's input an error message quotes.
pub const MAX_QUOTED_CHARS: usize = 200;
/// The longest line of an error message `dlw` prints, in characters: a message longer than
/// this is quoting more than it should, and is cut.
pub const MAX_MESSAGE_LINE_CHARS: usize = 600;

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

/// `text` as an error message quotes it: at most [`MAX_QUOTED_CHARS`] characters, then how many
/// were left out.
pub fn quote(text: &str) -> String {
    clip(text, MAX_QUOTED_CHARS)
}

/// A parser's message (TOML, JSON) as an error carries it: trimmed, each line cut to
/// [`MAX_QUOTED_CHARS`], since the parser quotes the input line it failed on.
pub fn parser_message(message: &impl std::fmt::Display) -> String {
    message
        .to_string()
        .trim_end()
        .split('\n')
        .map(quote)
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every line of `message` cut to [`MAX_MESSAGE_LINE_CHARS`] characters: the last guard before
/// an error is printed, for messages of other libraries (a TOML parser quotes the whole line it
/// failed on).
pub fn clip_message(message: &str) -> String {
    message
        .split('\n')
        .map(|line| clip(line, MAX_MESSAGE_LINE_CHARS))
        .collect::<Vec<_>>()
        .join("\n")
}

fn clip(text: &str, chars: usize) -> String {
    match text.char_indices().nth(chars) {
        None => text.to_string(),
        Some((cut, _)) => {
            let left_out = text[cut..].chars().count();
            format!("{}… ({left_out} more characters)", &text[..cut])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_are_cut_at_the_limit_and_say_how_much_is_left_out() {
        assert_eq!(quote("short"), "short");
        let long = "é".repeat(MAX_QUOTED_CHARS + 5);
        let q = quote(&long);
        assert!(q.starts_with(&"é".repeat(MAX_QUOTED_CHARS)), "{q}");
        assert!(q.ends_with("… (5 more characters)"), "{q}");
        let message = format!("first\n{}", "x".repeat(10 * MAX_MESSAGE_LINE_CHARS));
        let clipped = clip_message(&message);
        assert!(clipped.starts_with("first\n"));
        assert!(
            clipped.len() < 2 * MAX_MESSAGE_LINE_CHARS,
            "{}",
            clipped.len()
        );
    }

    #[test]
    fn values_outside_are_named_with_the_limits() {
        assert_eq!(within("--fps", 2.0, MIN_FPS, MAX_FPS, "fps"), Ok(2.0));
        let e = within("--fps", 1e308, MIN_FPS, MAX_FPS, "fps").unwrap_err();
        assert!(e.contains("--fps 1e308") && e.contains("10000"), "{e}");
        assert!(within("--fps", f64::NAN, MIN_FPS, MAX_FPS, "fps").is_err());
        assert!(within("--fps", 1e-320, MIN_FPS, MAX_FPS, "fps").is_err());
    }
}
