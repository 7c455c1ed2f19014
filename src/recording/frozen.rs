//! A column the instrument stopped updating while the joint moved: a tracker that lost the tool
//! and holds its last reading (without marking the rows `tracker_valid = 0`), or a DAQ channel
//! that repeats its last sample while it stalls.
//!
//! What tells a frozen stretch from a quiet one is again a property, not a level: the reading
//! holds one value while the stroke that drives the joint moves over at least [`MOVED_SHARE`]
//! of its range, and the run of that value is at least [`RUN_RATIO`] times as long as the
//! column's runs of one value are otherwise (their 99th percentile: one or two samples for a
//! reading with noise, the hold for a slow tracker written at the DAQ's rate). A rest or a
//! hold, where the stroke does not move, is never a frozen stretch, whatever the resolution.
//!
//! Before this check, Joint A's clean recording of seed 4 (third generator) with its tracker
//! angle held for three stretches of 4 s was named `hysteresis` and `rate` on sensor 1 with
//! exit 0, and `fit` wrote a gauge factor 2.6 % low at four times the RMSE.
//!
//! A hold that starts where the stroke turns is physics, not a frozen instrument: a tendon's
//! slack or a joint's static friction keeps the joint still after the stroke reverses, until
//! the slack is taken up ([`starts_at_turn`]). A reading without noise (an encoder) shows it as
//! one value held while the stroke moves back; a frozen instrument holds wherever the stroke
//! is, mid-way through its motion. A frozen hold that happens to start at a turn is accepted:
//! it cannot be told from the slack.

/// How many times as long as the column's other runs (their 99th percentile) a run must be.
pub const RUN_RATIO: usize = 10;
/// The least share of the stroke's range the stroke must move over during the run.
pub const MOVED_SHARE: f64 = 0.05;

/// How close to the extreme of the stroke around a hold (before it, as long as the hold, and
/// during it) the stroke at the hold's start must be, as a share of the stroke's range, for the
/// hold to start at a turn ([`starts_at_turn`]): 1 %. A frozen reading mid-way through a motion
/// that moves [`MOVED_SHARE`] during it is far from both extremes.
pub const TURN_SHARE: f64 = 0.01;

/// Whether a hold of the rows `first..=last` starts where the `stroke` turns (or rests): the
/// stroke at `first` is within [`TURN_SHARE`] of its range (`range`) of the largest or the
/// smallest stroke over the hold and as many rows before it. After a turn a joint with slack or
/// static friction holds still while the stroke moves back; a rest holds too.
pub fn starts_at_turn(stroke: &[f64], first: usize, last: usize, range: f64) -> bool {
    let from = first.saturating_sub(last - first + 1);
    let around = &stroke[from..=last];
    let hi = around.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let lo = around.iter().copied().fold(f64::INFINITY, f64::min);
    let tolerance = TURN_SHARE * range;
    stroke[first] >= hi - tolerance || stroke[first] <= lo + tolerance
}

/// The runs of one value of `values` on consecutive `rows`, each as its first index and length.
pub fn runs(values: &[f64], rows: &[usize]) -> Vec<(usize, usize)> {
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for i in 0..values.len() {
        let continues = i > 0 && values[i] == values[i - 1] && rows[i] == rows[i - 1] + 1;
        match runs.last_mut() {
            Some((_, len)) if continues => *len += 1,
            _ => runs.push((i, 1)),
        }
    }
    runs
}

/// The 99th percentile of the runs' lengths (0 for none): how long the column holds one value
/// otherwise.
pub fn typical_run(runs: &[(usize, usize)]) -> usize {
    let mut lengths: Vec<usize> = runs.iter().map(|r| r.1).collect();
    lengths.sort_unstable();
    lengths
        .get(((lengths.len().max(1) - 1) as f64 * 0.99).round() as usize)
        .copied()
        .unwrap_or(0)
}

/// A stretch of one value while the stroke moved.
#[derive(Debug, Clone, PartialEq)]
pub struct Frozen {
    /// Index (into the values) of its first sample.
    pub first: usize,
    /// How many samples it holds.
    pub len: usize,
    /// The value held.
    pub value: f64,
    /// The 99th percentile of the column's runs of one value.
    pub typical: usize,
    /// How far the stroke moved during it, as a share of the stroke's range.
    pub moved: f64,
}

/// The longest frozen stretch of `values`, where `values[i]` was read at row `rows[i]` of
/// `stroke` (rows increasing; a run ends where rows are not consecutive), if one passes the
/// rule of the module docs.
pub fn frozen(values: &[f64], rows: &[usize], stroke: &[f64]) -> Option<Frozen> {
    let lo = stroke.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = stroke.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let range = hi - lo;
    if values.len() != rows.len() || range.is_nan() || range <= 0.0 {
        return None;
    }
    // Runs of one value over consecutive rows, as (first index, length).
    let runs = runs(values, rows);
    let typical = typical_run(&runs);
    runs.iter()
        .filter(|(_, len)| *len >= RUN_RATIO * typical)
        .filter_map(|&(first, len)| {
            let (start, end) = (rows[first], rows[first + len - 1]);
            let during = &stroke[start..=end];
            let moved = (during.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - during.iter().copied().fold(f64::INFINITY, f64::min))
                / range;
            let slack = starts_at_turn(stroke, start, end, range);
            (moved >= MOVED_SHARE && !slack).then_some(Frozen {
                first,
                len,
                value: values[first],
                typical,
                moved,
            })
        })
        .max_by_key(|f| f.len)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recording::clipping::tests::uniform;

    /// A stroke that rests, then cycles; a reading of it with noise from a fixed sequence.
    fn bench(n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut state = 99_u64;
        let stroke: Vec<f64> = (0..n)
            .map(|i| {
                if i < 1000 {
                    0.0
                } else {
                    1.0 - ((i - 1000) as f64 * 0.005).cos()
                }
            })
            .collect();
        let reading = stroke
            .iter()
            // Four decimals, as data.csv writes an angle.
            .map(|s| ((30.0 * s + 0.2 * uniform(&mut state)) * 1e4).round() / 1e4)
            .collect();
        (stroke, reading)
    }

    #[test]
    fn a_reading_held_while_the_stroke_moves_is_frozen() {
        let (stroke, mut reading) = bench(20_000);
        let rows: Vec<usize> = (0..reading.len()).collect();
        assert_eq!(frozen(&reading, &rows, &stroke), None);
        let held = reading[5000];
        for v in &mut reading[5000..7000] {
            *v = held;
        }
        let found = frozen(&reading, &rows, &stroke).expect("a frozen stretch");
        assert_eq!((found.first, found.len, found.value), (5000, 2000, held));
        assert!(found.moved > 0.5, "{found:?}");
    }

    #[test]
    fn a_rest_a_slow_tracker_and_a_gap_are_not_frozen() {
        let (stroke, reading) = bench(20_000);
        // A reading without noise holds one value through the rest: the stroke does not move.
        let quiet: Vec<f64> = stroke
            .iter()
            .map(|s| (30.0 * s * 10.0).round() / 10.0)
            .collect();
        let rows: Vec<usize> = (0..quiet.len()).collect();
        assert_eq!(frozen(&quiet, &rows, &stroke), None);
        // A tracker at a tenth of the DAQ's rate, each reading held ten rows.
        let slow: Vec<f64> = (0..reading.len()).map(|i| reading[i - i % 10]).collect();
        assert_eq!(frozen(&slow, &rows, &stroke), None);
        // The same hold on rows marked invalid (left out): nothing is left frozen.
        let mut marked = reading.clone();
        let held = marked[5000];
        for v in &mut marked[5000..7000] {
            *v = held;
        }
        let kept: Vec<usize> = (0..marked.len())
            .filter(|i| !(5000..7000).contains(i))
            .collect();
        let values: Vec<f64> = kept.iter().map(|&i| marked[i]).collect();
        assert_eq!(frozen(&values, &kept, &stroke), None);
    }
}
