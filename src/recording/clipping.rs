//! A column clipped by its instrument's range: a DAQ input range set too narrow for the divider's
//! voltage, or a tracker that reports its limit when the tool leaves its field.
//!
//! What tells a clip from the signal is a property of the values, not a level: a measured
//! signal with noise reaches its extreme value in a few samples, and the values next to it are
//! held about as often (the tail of its distribution; with a converter's steps, each step a few
//! times). A clipped signal piles up at the extreme: every sample past the range reads the
//! range's end. So a column is clipped at an end when that end's value is held by at least
//! [`PILE_UP_RATIO`] times as many samples as the most held of the next [`NEIGHBOURS`]
//! distinct values, and by at least [`MIN_SHARE`] of the rows (and [`MIN_SAMPLES`]).
//!
//! A sensor that saturates physically does not pile up (its plateau carries the noise), so
//! `discover` still names a true `saturation`. Before this check, Joint A's clean recording with
//! its voltage clipped at the 90th percentile was named `saturation` with exit 0, and `fit`
//! wrote a gauge factor of 13.44 where the unclipped recording gives 13.92.
//!
//! A column driven by the stroke counts at its end only the holds that do not start where the
//! stroke turns or rests ([`pile_up_moving`]): an angle read without noise (an encoder) holds
//! its smallest value exactly through the rest at the start, and its largest while a tendon's
//! slack is taken up after each turn at the top. A clip holds while the stroke goes on past the
//! clip's level and comes back. Before, such an encoder recording of a joint with slack was
//! refused as clipped at the rest's 0° (5.9 % of its rows), and, without the rest, at the
//! top's 23.45° (0.9 %, the slack at the largest turn).
//!
//! The stroke is not checked: a commanded or encoder position holds one value exactly during a
//! rest or a hold. The angle is checked on the rows whose tracker angle is valid.

/// How many times as many samples the extreme value must hold as the most held of its
/// neighbours (a tail's extreme holds fewer than its neighbours).
pub const PILE_UP_RATIO: usize = 10;
/// How many distinct values next to the extreme are compared with it.
pub const NEIGHBOURS: usize = 5;
/// The least share of the rows a pile-up must hold to count (0.1 %).
pub const MIN_SHARE: f64 = 0.001;
/// The least number of samples a pile-up must hold to count.
pub const MIN_SAMPLES: usize = 10;

/// Which end of a column's range a pile-up is at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    /// The largest value.
    Largest,
    /// The smallest value.
    Smallest,
}

impl End {
    /// The end, in words.
    pub fn word(self) -> &'static str {
        match self {
            End::Largest => "largest",
            End::Smallest => "smallest",
        }
    }
}

/// A pile-up at one end of a column.
#[derive(Debug, Clone, PartialEq)]
pub struct PileUp {
    /// Which end.
    pub end: End,
    /// The value held.
    pub value: f64,
    /// How many samples hold it (on a column with a stroke, outside the holds that start at a
    /// turn: [`pile_up_moving`]).
    pub count: usize,
    /// Index (into the values) of the first sample counted.
    pub first: usize,
    /// How many samples the most held of its [`NEIGHBOURS`] holds.
    pub next_count: usize,
    /// How many samples were looked at.
    pub rows: usize,
}

/// The pile-up at either end of `values`, if one passes the rule of the module docs (the
/// largest end first); `None` for a column of one distinct value (a constant is not a clip).
pub fn pile_up(values: &[f64]) -> Option<PileUp> {
    pile_up_counting(values, |value, count| {
        (count, values.iter().position(|v| *v == value).unwrap_or(0))
    })
}

/// [`pile_up`] of a column driven by `stroke` (indexed by row; `rows` the row of each value):
/// the end's value is not counted on its long holds (at least
/// [`super::frozen::RUN_RATIO`] times the column's typical run, as a frozen stretch's) that
/// start where the stroke turns or rests ([`super::frozen::starts_at_turn`]; module docs). A
/// clip read with noise is many short runs, each counted.
pub fn pile_up_moving(values: &[f64], rows: &[usize], stroke: &[f64]) -> Option<PileUp> {
    let lo = stroke.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = stroke.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let range = hi - lo;
    if values.len() != rows.len() || range.is_nan() || range <= 0.0 {
        return pile_up(values);
    }
    let runs = super::frozen::runs(values, rows);
    let long = super::frozen::RUN_RATIO * super::frozen::typical_run(&runs);
    pile_up_counting(values, |value, _| {
        let counted: Vec<&(usize, usize)> = runs
            .iter()
            .filter(|&&(first, _)| values[first] == value)
            .filter(|&&(first, len)| {
                let (start, end) = (rows[first], rows[first + len - 1]);
                len < long || !super::frozen::starts_at_turn(stroke, start, end, range)
            })
            .collect();
        let first = counted.first().map_or(0, |r| r.0);
        (counted.iter().map(|r| r.1).sum(), first)
    })
}

/// [`pile_up`] with the end's value counted by `count` (given the value and how many samples
/// hold it; it returns the count and the index of the first sample counted).
fn pile_up_counting(
    values: &[f64],
    count: impl Fn(f64, usize) -> (usize, usize),
) -> Option<PileUp> {
    let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    sorted.sort_by(f64::total_cmp);
    let rows = sorted.len();
    if rows == 0 || sorted[0] == sorted[rows - 1] {
        return None;
    }
    let least = MIN_SAMPLES.max((MIN_SHARE * rows as f64).ceil() as usize);
    let descending: Vec<f64> = sorted.iter().rev().copied().collect();
    let at_end = |end: End, ordered: &[f64]| {
        let runs = runs(ordered, NEIGHBOURS + 1);
        let (value, held) = runs[0];
        let (count, first) = count(value, held);
        let next_count = runs[1..].iter().map(|r| r.1).max().unwrap_or(0);
        (count >= least && count >= PILE_UP_RATIO * next_count.max(1)).then_some(PileUp {
            end,
            value,
            count,
            first,
            next_count,
            rows,
        })
    };
    at_end(End::Largest, &descending).or_else(|| at_end(End::Smallest, &sorted))
}

/// The first `k` runs of equal values of `ordered` (sorted), each as its value and length.
fn runs(ordered: &[f64], k: usize) -> Vec<(f64, usize)> {
    let mut out: Vec<(f64, usize)> = Vec::with_capacity(k);
    for &v in ordered {
        if let Some((value, count)) = out.last_mut() {
            if *value == v {
                *count += 1;
                continue;
            }
        }
        if out.len() == k {
            break;
        }
        out.push((v, 1));
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The next of a fixed sequence uniform on [-0.5, 0.5) (no random crate in the unit tests).
    pub(crate) fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }

    /// A sine with noise, on a converter's `step` if given.
    fn noisy(n: usize, step: Option<f64>) -> Vec<f64> {
        let mut state = 12345_u64;
        (0..n)
            .map(|i| {
                let v = 2.5 + (i as f64 * 0.01).sin() + 0.01 * uniform(&mut state);
                step.map_or(v, |s| (v / s).round() * s)
            })
            .collect()
    }

    #[test]
    fn a_clip_at_either_end_piles_up_and_a_tail_does_not() {
        let clean = noisy(20_000, None);
        assert_eq!(pile_up(&clean), None);
        let top: Vec<f64> = clean.iter().map(|v| v.min(3.2)).collect();
        let found = pile_up(&top).expect("a clip at 3.2 V");
        assert_eq!((found.end, found.value), (End::Largest, 3.2));
        assert!(found.count > 2000, "{found:?}");
        let bottom: Vec<f64> = clean.iter().map(|v| v.max(1.7)).collect();
        let found = pile_up(&bottom).expect("a clip at 1.7 V");
        assert_eq!((found.end, found.value), (End::Smallest, 1.7));
    }

    #[test]
    fn a_converter_s_steps_and_held_samples_are_not_a_clip() {
        // Steps of a 12-bit converter over 5 V, finer than the noise: no pile-up at the ends.
        assert_eq!(pile_up(&noisy(20_000, Some(5.0 / 4096.0))), None);
        // Each sample held five times (a slow tracker on a fast DAQ): the ends are held five
        // times, as every value is.
        let held: Vec<f64> = noisy(4_000, None)
            .into_iter()
            .flat_map(|v| [v; 5])
            .collect();
        assert_eq!(pile_up(&held), None);
        // A saturating response: its plateau carries the noise.
        let saturating: Vec<f64> = noisy(20_000, None)
            .iter()
            .map(|v| 2.5 + 0.6 * ((v - 2.5) / 0.6).tanh())
            .collect();
        assert_eq!(pile_up(&saturating), None);
    }

    #[test]
    fn a_constant_or_a_few_clipped_samples_are_not_reported() {
        assert_eq!(pile_up(&[2.0; 100]), None);
        assert_eq!(pile_up(&[]), None);
        let mut few = noisy(20_000, None);
        let top = few.iter().copied().fold(f64::MIN, f64::max);
        // Five samples at the end's value: under the least count.
        for v in few.iter_mut().take(5) {
            *v = top;
        }
        assert_eq!(pile_up(&few), None);
    }
}
