//! Loading and unloading phases: the strain's runs between turning points.
//!
//! A turning point is an extreme of the strain that the strain then leaves by more than a
//! threshold (a zigzag filter), so noise and small wiggles do not split a phase. A cycle is a
//! loading phase and the unloading phase after it, as in the paper's Fig. 4.

/// A turning point of the strain needs the strain to come back by this share of its span.
pub const TURN_THRESHOLD: f64 = 0.1;

/// One monotone run of the strain, `start..=end` (sample indices).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Phase {
    /// First sample.
    pub start: usize,
    /// Last sample (the turning point that ends the phase).
    pub end: usize,
    /// Strain rises (`true`) or falls.
    pub loading: bool,
}

/// A loading phase and the unloading phase that follows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cycle {
    /// The rise.
    pub loading: Phase,
    /// The fall.
    pub unloading: Phase,
}

impl Cycle {
    /// Samples `loading.start..=unloading.end`.
    pub fn range(&self) -> std::ops::RangeInclusive<usize> {
        self.loading.start..=self.unloading.end
    }
}

/// The phases of `strain`: a turning point needs the strain to come back from it by more than
/// `threshold` (same unit as the strain). The last run counts only if it moved by more than
/// `threshold` too.
pub fn phases(strain: &[f64], threshold: f64) -> Vec<Phase> {
    let mut turns: Vec<usize> = Vec::new();
    let Some(&first) = strain.first() else {
        return Vec::new();
    };
    let (mut lo, mut hi) = ((0usize, first), (0usize, first));
    // Direction of the run being followed: None until the strain has left the start by more
    // than the threshold.
    let mut rising: Option<bool> = None;
    for (i, &x) in strain.iter().enumerate() {
        if !x.is_finite() {
            continue;
        }
        if x > hi.1 {
            hi = (i, x);
        }
        if x < lo.1 {
            lo = (i, x);
        }
        match rising {
            None => {
                if hi.1 - lo.1 > threshold {
                    // The first run starts at the extreme reached first.
                    let up = hi.0 > lo.0;
                    turns.push(if up { lo.0 } else { hi.0 });
                    rising = Some(up);
                    if up {
                        lo = hi;
                    } else {
                        hi = lo;
                    }
                }
            }
            Some(true) => {
                if hi.1 - x > threshold {
                    turns.push(hi.0);
                    rising = Some(false);
                    lo = (i, x);
                }
            }
            Some(false) => {
                if x - lo.1 > threshold {
                    turns.push(lo.0);
                    rising = Some(true);
                    hi = (i, x);
                }
            }
        }
    }
    // Close the last run at its extreme if it went far enough.
    match rising {
        Some(true) if hi.1 - strain[*turns.last().unwrap_or(&0)] > threshold => turns.push(hi.0),
        Some(false) if strain[*turns.last().unwrap_or(&0)] - lo.1 > threshold => turns.push(lo.0),
        _ => {}
    }
    turns
        .windows(2)
        .map(|w| Phase {
            start: w[0],
            end: w[1],
            loading: strain[w[1]] > strain[w[0]],
        })
        .collect()
}

/// Pairs each loading phase with the unloading phase right after it.
pub fn cycles(phases: &[Phase]) -> Vec<Cycle> {
    phases
        .windows(2)
        .filter(|w| w[0].loading && !w[1].loading)
        .map(|w| Cycle {
            loading: w[0],
            unloading: w[1],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle(peaks: &[f64], per_ramp: usize) -> Vec<f64> {
        let mut out = vec![0.0];
        for &p in peaks {
            for i in 1..=per_ramp {
                out.push(p * i as f64 / per_ramp as f64);
            }
            for i in (0..per_ramp).rev() {
                out.push(p * i as f64 / per_ramp as f64);
            }
        }
        out
    }

    #[test]
    fn finds_each_cycle_of_a_staircase_of_amplitudes() {
        let x = triangle(&[1.0, 2.0, 0.5, 3.0], 50);
        let ph = phases(&x, 0.1);
        assert_eq!(ph.len(), 8);
        let c = cycles(&ph);
        assert_eq!(c.len(), 4);
        assert_eq!(c[1].loading.start, 100);
        assert_eq!(c[1].loading.end, 150);
        assert_eq!(c[1].unloading.end, 200);
        assert!(c.iter().all(|c| c.loading.loading && !c.unloading.loading));
    }

    #[test]
    fn noise_below_the_threshold_splits_nothing() {
        let mut x = triangle(&[1.0, 1.0], 200);
        for (i, v) in x.iter_mut().enumerate() {
            *v += 0.02 * ((i * 7919 % 13) as f64 / 13.0 - 0.5);
        }
        assert_eq!(cycles(&phases(&x, 0.1)).len(), 2);
        // A still signal has no phase at all.
        assert!(phases(&[0.0; 100], 0.1).is_empty());
    }

    #[test]
    fn a_run_that_does_not_return_is_a_phase_but_not_a_cycle() {
        let x: Vec<f64> = (0..100).map(|i| i as f64 / 100.0).collect();
        let ph = phases(&x, 0.1);
        assert_eq!(ph.len(), 1);
        assert!(ph[0].loading);
        assert!(cycles(&ph).is_empty());
    }
}
