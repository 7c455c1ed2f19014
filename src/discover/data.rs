//! The recording as discovery sees it: block-averaged to about [`TARGET_HZ`], the rest at the
//! start found, and the samples after it split into interleaved training and held-out blocks.
//!
//! A block holding a row the tracker did not measure (`tracker_valid = 0`) is no observation:
//! it is left out of the training and held-out masks and of the rest the noise is frozen from,
//! and its angle is interpolated between the measured blocks around it (held at the ends), so
//! that the models' inputs and the noise model's whitening over the whole series never see the
//! number a recording writes on such rows.

use dlw_geometry::Joint;

use super::DiscoverError;
use crate::recording::clock::Timeline;
use crate::recording::Recording;
use crate::signal::MIN_ANGLE_SPAN_DEG;

/// Rate discovery works at (Hz): each sample is the mean of `sample_hz/TARGET_HZ` recorded
/// samples ([`Timeline`], the recording's block averages, which the clock check works on too).
/// The effects live at seconds; averaging cuts the white noise and the work.
pub use crate::recording::clock::TARGET_HZ;
/// Shortest rest at the start (s) the noise model is frozen from.
pub const MIN_REST_S: f64 = 4.0;
/// The time before the first motion left out of the rest (s): the stroke may start moving
/// before it leaves its tolerance.
pub const REST_MARGIN_S: f64 = 1.0;
/// Interleaved blocks after the rest: the even ones (from 0) train, the odd ones are held out.
/// Odd, so that the first and the last block train and every held-out block lies between two
/// training ones: a term in time (`drift`, `gain_drift`, the time spline) is then judged on how
/// it interpolates, never on how it extrapolates past the last training sample. With 10 it was
/// (docs/discovery.md, "The last held-out block").
/// The fewest blocks; a longer recording gets more ([`Data::blocks`]).
pub const BLOCKS: usize = 11;
const _: () = assert!(BLOCKS % 2 == 1, "the last block must train");
/// Shortest block (s): a block must span several noise correlation times.
pub const MIN_BLOCK_S: f64 = 8.0;
/// Longest block (s): half the time spline's knot spacing
/// ([`super::unexplained::TIME_KNOT_S`]). A change in time the spline can follow is then
/// interpolated across every held-out block from the training blocks on both sides. With 11
/// blocks whatever the length, a 3000 s recording's held-out blocks were 273 s long, longer
/// than half a gain cycling at a period of 250-700 s: no term in time could predict them, and
/// such a gain was never seen on a BSN joint (docs/discovery.md, "Blocks no longer than half
/// a knot").
pub const MAX_BLOCK_S: f64 = super::unexplained::TIME_KNOT_S / 2.0;

/// One recording, decimated.
#[derive(Debug, Clone)]
pub struct Data {
    /// Time (s).
    pub time_s: Vec<f64>,
    /// Tendon stroke (mm).
    pub stroke_mm: Vec<f64>,
    /// Tracker angle (°).
    pub angle_deg: Vec<f64>,
    /// Strain at sensor 1's plane, `ε(θ)` (Eq. 3).
    pub strain: Vec<f64>,
    /// Each sensor's resistance (Ω, Eq. 4).
    pub ohm: Vec<Vec<f64>>,
    /// Samples `0..rest` are the rest at the start.
    pub rest: usize,
    /// Whether every row of each sample's block has a tracker angle (`tracker_valid`).
    pub measured: Vec<bool>,
    /// Sample spacing (s).
    pub dt_s: f64,
}

impl Data {
    /// Block-averages `recording`; strain through `joint`.
    ///
    /// # Errors
    /// A voltage with no finite resistance, an angle that spans less than
    /// [`MIN_ANGLE_SPAN_DEG`], or less than [`MIN_REST_S`] at rest at the start.
    pub fn new(recording: &Recording, joint: &Joint) -> Result<Self, DiscoverError> {
        let s = &recording.samples;
        let Timeline {
            time_s,
            stroke_mm,
            mut angle_deg,
            ohm,
            measured,
            rest: moved,
            dt_s,
        } = Timeline::of(recording).map_err(|r| DiscoverError::Rail {
            column: r.column,
            time_s: r.time_s,
            volts: r.volts,
        })?;
        if !measured.contains(&true) {
            return Err(DiscoverError::NoAngle {
                rows: s.invalid_angle_rows(),
            });
        }
        let (lo, hi) = s.valid_angle_range();
        if hi - lo < MIN_ANGLE_SPAN_DEG {
            return Err(DiscoverError::NoMotion {
                span_deg: hi - lo,
                min_deg: MIN_ANGLE_SPAN_DEG,
            });
        }
        fill_unmeasured(&mut angle_deg, &measured);
        let strain = angle_deg
            .iter()
            .map(|a| joint.strain(a.to_radians()))
            .collect();
        let rest = moved.saturating_sub((REST_MARGIN_S / dt_s) as usize);
        if (rest as f64) * dt_s < MIN_REST_S {
            return Err(DiscoverError::NoRest {
                rest_s: moved as f64 * dt_s,
                margin_s: REST_MARGIN_S,
                min_s: MIN_REST_S,
                needs_s: MIN_REST_S + REST_MARGIN_S,
            });
        }
        Ok(Self {
            time_s,
            stroke_mm,
            angle_deg,
            strain,
            ohm,
            rest: moved,
            measured,
            dt_s,
        })
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// The interleaved split of the samples after the rest: `(training, held out)` masks.
    ///
    /// # Errors
    /// [`DiscoverError::TooShort`] when a block would be shorter than [`MIN_BLOCK_S`].
    pub fn split(&self) -> Result<(Vec<bool>, Vec<bool>), DiscoverError> {
        let n = self.len();
        let moving = n - self.rest;
        let blocks = self.blocks();
        let block = moving / blocks;
        if (block as f64) * self.dt_s < MIN_BLOCK_S {
            return Err(DiscoverError::TooShort {
                moving_s: moving as f64 * self.dt_s,
                min_s: BLOCKS as f64 * MIN_BLOCK_S,
                blocks: BLOCKS,
                block_s: MIN_BLOCK_S,
            });
        }
        let mut train = vec![false; n];
        let mut test = vec![false; n];
        for i in (self.rest..n).filter(|&i| self.measured[i]) {
            let b = ((i - self.rest) / block).min(blocks - 1);
            if b % 2 == 0 {
                train[i] = true;
            } else {
                test[i] = true;
            }
        }
        Ok((train, test))
    }

    /// How many blocks the motion is cut into: the fewest odd number from [`BLOCKS`] up whose
    /// blocks are no longer than [`MAX_BLOCK_S`].
    pub fn blocks(&self) -> usize {
        let moving_s = (self.len() - self.rest) as f64 * self.dt_s;
        let needed = (moving_s / MAX_BLOCK_S).ceil();
        let needed = if needed.is_finite() && needed > 0.0 {
            needed as usize
        } else {
            0
        };
        let blocks = needed.max(BLOCKS);
        blocks + (1 - blocks % 2)
    }

    /// Every measured sample after the rest (a holdout recording is held out whole).
    pub fn moving(&self) -> Vec<bool> {
        (0..self.len())
            .map(|i| i >= self.rest && self.measured[i])
            .collect()
    }

    /// The rest's samples the noise model is frozen from: from the first measured sample to
    /// the end of the rest (a recording imported from a tracker starting after the DAQ begins
    /// unmeasured).
    pub fn measured_rest(&self) -> std::ops::Range<usize> {
        let first = self.measured.iter().position(|&m| m).unwrap_or(0);
        first.min(self.rest)..self.rest
    }
}

pub use crate::recording::rest::spread;

/// Replaces the values of the samples not `measured` by linear interpolation between the
/// measured ones around them, held at the ends. At least one sample must be measured.
fn fill_unmeasured(values: &mut [f64], measured: &[bool]) {
    let mut last: Option<usize> = None;
    let n = values.len();
    let mut i = 0;
    while i < n {
        if measured[i] {
            last = Some(i);
            i += 1;
            continue;
        }
        let next = (i..n).find(|&j| measured[j]);
        for k in i..next.unwrap_or(n) {
            values[k] = match (last, next) {
                (Some(a), Some(b)) => {
                    let f = (k - a) as f64 / (b - a) as f64;
                    values[a] + (values[b] - values[a]) * f
                }
                (Some(a), None) => values[a],
                (None, Some(b)) => values[b],
                (None, None) => values[k],
            };
        }
        i = next.unwrap_or(n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn data(n: usize, rest: usize) -> Data {
        Data {
            time_s: (0..n).map(|i| i as f64 * 0.04).collect(),
            stroke_mm: vec![0.0; n],
            angle_deg: vec![0.0; n],
            strain: vec![0.0; n],
            ohm: Vec::new(),
            rest,
            measured: vec![true; n],
            dt_s: 0.04,
        }
    }

    /// Every held-out sample lies between two training samples, at any length and rest, so
    /// that no term in time (`drift`, `gain_drift`, the time spline) is judged on how it
    /// extrapolates past the last training sample. Failed with 10 blocks (the last held out:
    /// at n 2500 and rest 100, samples held out up to 2499 while training ended at 2259).
    #[test]
    fn every_held_out_block_lies_between_training_blocks() {
        for n in [2500, 2501, 2517, 7500, 7517, 75_000, 75_013] {
            for rest in [100, 137, 250] {
                let (train, test) = data(n, rest).split().unwrap();
                let first = train.iter().position(|t| *t).unwrap();
                let last = train.iter().rposition(|t| *t).unwrap();
                let held: Vec<usize> = (0..n).filter(|&i| test[i]).collect();
                assert!(!held.is_empty());
                assert!(
                    held.iter().all(|&i| i > first && i < last),
                    "n {n}, rest {rest}: held out up to sample {}, training ends at {last}",
                    held[held.len() - 1]
                );
            }
        }
    }

    /// A held-out block is never longer than half the time spline's knot spacing, whatever the
    /// recording's length, and no fewer blocks would do: with 11 blocks at any length a 3000 s
    /// recording held out 273 s at a time, and a gain cycling at 250-700 s was never seen.
    #[test]
    fn no_held_out_block_is_longer_than_half_a_knot() {
        for n in [2500, 7500, 7517, 30_000, 75_000, 75_013, 150_000] {
            for rest in [100, 250] {
                let d = data(n, rest);
                let blocks = d.blocks();
                let moving_s = (n - rest) as f64 * d.dt_s;
                assert!(
                    blocks >= BLOCKS && blocks % 2 == 1,
                    "n {n}: {blocks} blocks"
                );
                assert!(
                    blocks == BLOCKS || moving_s / (blocks - 2) as f64 > MAX_BLOCK_S,
                    "n {n}: {blocks} blocks are more than needed"
                );
                let (_, test) = d.split().unwrap();
                let mut run = 0usize;
                let mut longest = 0usize;
                for &t in &test {
                    run = if t { run + 1 } else { 0 };
                    longest = longest.max(run);
                }
                assert!(
                    longest as f64 * d.dt_s <= MAX_BLOCK_S,
                    "n {n}, rest {rest}: a held-out block of {} s",
                    longest as f64 * d.dt_s
                );
            }
        }
    }

    #[test]
    fn unmeasured_samples_are_interpolated_and_held_at_the_ends() {
        let mut v = [9.0, 1.0, 9.0, 9.0, 4.0, 9.0];
        let m = [false, true, false, false, true, false];
        fill_unmeasured(&mut v, &m);
        assert_eq!(v, [1.0, 1.0, 2.0, 3.0, 4.0, 4.0]);
    }
}
