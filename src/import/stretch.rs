//! The DAQ's clock, checked: where its time column jumps (a DAQ that dropped samples, a logger
//! that paused), the recording falls into stretches of even sampling, and each stretch is
//! aligned with the tracker on its own (`--sync auto`), never as if the clock ran evenly
//! through the jump.

use std::ops::Range;

use super::align::JUMP_PERIODS;

/// The shortest stretch aligned on its own (s): the windows of the alignment need motion in
/// at least three of them; a shorter stretch is refused, naming the jump before or after it.
pub const MIN_STRETCH_S: f64 = 30.0;

/// Why the DAQ's clock cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum StretchError {
    /// A stretch between jumps too short to align.
    #[error("the DAQ's time column jumps{jumps}; the stretch from {from_s:.3} s to {to_s:.3} s (rows {first_row} to {last_row}) is {length_s:.1} s long, too short to align on its own (at least {MIN_STRETCH_S} s): cut the file at the jump, or align with --sync CH and a sync pulse")]
    Short {
        /// The jumps, in words.
        jumps: String,
        /// Its start (s).
        from_s: f64,
        /// Its end (s).
        to_s: f64,
        /// Its first row (1-based).
        first_row: usize,
        /// Its last row (1-based).
        last_row: usize,
        /// Its length (s).
        length_s: f64,
    },
}

/// A step of the DAQ's time column longer than [`JUMP_PERIODS`] sample periods.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Jump {
    /// The row after the jump (1-based).
    pub row: usize,
    /// The time before the jump (s).
    pub from_s: f64,
    /// The time after it (s).
    pub to_s: f64,
}

/// The DAQ's samples as stretches of even sampling.
#[derive(Debug, Clone, PartialEq)]
pub struct Stretches {
    /// Each stretch's rows (0-based, end exclusive).
    pub rows: Vec<Range<usize>>,
    /// The jumps between them.
    pub jumps: Vec<Jump>,
    /// The sample period (s): the median step.
    pub period_s: f64,
}

/// The median step of `time_s` (s).
pub fn median_step(time_s: &[f64]) -> f64 {
    let mut d: Vec<f64> = time_s.windows(2).map(|w| w[1] - w[0]).collect();
    if d.is_empty() {
        return f64::NAN;
    }
    let middle = d.len() / 2;
    *d.select_nth_unstable_by(middle, f64::total_cmp).1
}

/// Splits the DAQ's rows at every step of `time_s` longer than [`JUMP_PERIODS`] periods.
///
/// # Errors
/// [`StretchError::Short`] when a stretch is shorter than [`MIN_STRETCH_S`] (only checked when
/// there is a jump).
pub fn stretches(time_s: &[f64]) -> Result<Stretches, StretchError> {
    let period_s = median_step(time_s);
    let mut rows = Vec::new();
    let mut jumps = Vec::new();
    let mut start = 0;
    for i in 1..time_s.len() {
        if time_s[i] - time_s[i - 1] > JUMP_PERIODS * period_s {
            rows.push(start..i);
            jumps.push(Jump {
                row: i + 1,
                from_s: time_s[i - 1],
                to_s: time_s[i],
            });
            start = i;
        }
    }
    rows.push(start..time_s.len());
    if !jumps.is_empty() {
        let words: String = jumps
            .iter()
            .map(|j| format!(" from {:.3} s to {:.3} s (row {})", j.from_s, j.to_s, j.row))
            .collect::<Vec<_>>()
            .join(" and");
        for r in &rows {
            let length_s = time_s[r.end - 1] - time_s[r.start];
            if length_s < MIN_STRETCH_S {
                return Err(StretchError::Short {
                    jumps: words,
                    from_s: time_s[r.start],
                    to_s: time_s[r.end - 1],
                    first_row: r.start + 1,
                    last_row: r.end,
                    length_s,
                });
            }
        }
    }
    Ok(Stretches {
        rows,
        jumps,
        period_s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_jump_splits_and_a_short_stretch_is_refused() {
        let mut t: Vec<f64> = (0..50_000).map(|i| f64::from(i) * 0.002).collect();
        let even = stretches(&t).unwrap();
        assert_eq!(even.rows, vec![0..50_000]);
        for v in &mut t[30_000..] {
            *v += 1.0;
        }
        let s = stretches(&t).unwrap();
        assert_eq!(s.rows, vec![0..30_000, 30_000..50_000]);
        assert_eq!(s.jumps[0].row, 30_001);
        for v in &mut t[45_000..] {
            *v += 1.0;
        }
        let err = stretches(&t).unwrap_err().to_string();
        assert!(
            err.contains("rows 30001 to 45000") && err.contains("too short"),
            "{err}"
        );
    }
}
