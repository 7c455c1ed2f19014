use crate::error::EstimatorError;

/// Longest moving average, in samples. The paper filters with 500 and 1000 samples; 4096 keeps
/// one filter at 32 KiB.
pub const MAX_MOVING_AVERAGE: usize = 4096;

/// A streaming moving average over the last `N ≤ MAX_MOVING_AVERAGE` samples, O(1) per sample.
///
/// Until `N` samples have arrived it averages those it has. Once full its group delay is
/// `(N − 1)/2` samples (a ramp comes out `(N − 1)/2` samples late) and it divides white noise's
/// variance by `N`.
///
/// The running sum is kept with compensated (Neumaier) summation, and replaced by a sum of the
/// buffer's current contents built up without subtraction each time the ring wraps, so that a
/// huge sample cannot leave rounding error behind once it has left the window.
#[derive(Clone, PartialEq)]
pub struct MovingAverage {
    buffer: [f64; MAX_MOVING_AVERAGE],
    len: usize,
    head: usize,
    count: usize,
    sum: f64,
    compensation: f64,
    fresh: f64,
    fresh_compensation: f64,
}

impl MovingAverage {
    /// An average over `samples` samples.
    ///
    /// # Errors
    /// [`EstimatorError::CountOutOfRange`] unless `1 ≤ samples ≤ MAX_MOVING_AVERAGE`.
    pub fn new(samples: u32) -> Result<Self, EstimatorError> {
        let len = samples as usize;
        if !(1..=MAX_MOVING_AVERAGE).contains(&len) {
            return Err(EstimatorError::CountOutOfRange {
                name: "samples",
                value: u64::from(samples),
                min: 1,
                max: MAX_MOVING_AVERAGE as u64,
            });
        }
        Ok(Self {
            buffer: [0.0; MAX_MOVING_AVERAGE],
            len,
            head: 0,
            count: 0,
            sum: 0.0,
            compensation: 0.0,
            fresh: 0.0,
            fresh_compensation: 0.0,
        })
    }

    /// Window length `N`.
    pub fn samples(&self) -> usize {
        self.len
    }

    /// Group delay once full, `(N − 1)/2` samples.
    pub fn delay_samples(&self) -> f64 {
        (self.len as f64 - 1.0) / 2.0
    }

    /// Feeds one sample and returns the mean of the last `min(N, samples seen)` samples.
    #[inline]
    pub fn step(&mut self, x: f64) -> f64 {
        let old = if self.count == self.len {
            self.buffer[self.head]
        } else {
            self.count += 1;
            0.0
        };
        self.buffer[self.head] = x;
        neumaier(&mut self.sum, &mut self.compensation, x);
        neumaier(&mut self.sum, &mut self.compensation, -old);
        neumaier(&mut self.fresh, &mut self.fresh_compensation, x);
        self.head += 1;
        if self.head == self.len {
            // The buffer now holds exactly the samples summed into `fresh`.
            self.head = 0;
            self.sum = self.fresh;
            self.compensation = self.fresh_compensation;
            self.fresh = 0.0;
            self.fresh_compensation = 0.0;
        }
        (self.sum + self.compensation) / self.count as f64
    }

    /// Forgets every sample.
    pub fn reset(&mut self) {
        self.head = 0;
        self.count = 0;
        self.sum = 0.0;
        self.compensation = 0.0;
        self.fresh = 0.0;
        self.fresh_compensation = 0.0;
    }
}

impl core::fmt::Debug for MovingAverage {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MovingAverage")
            .field("samples", &self.len)
            .field("count", &self.count)
            .finish_non_exhaustive()
    }
}

/// Adds `x` to `sum` with Neumaier's compensation.
#[inline(always)]
fn neumaier(sum: &mut f64, compensation: &mut f64, x: f64) {
    let t = *sum + x;
    *compensation += if sum.abs() >= x.abs() {
        (*sum - t) + x
    } else {
        (x - t) + *sum
    };
    *sum = t;
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use approx::assert_relative_eq;
    use std::boxed::Box;

    #[test]
    fn averages_what_it_has_then_the_window() {
        let mut ma = MovingAverage::new(3).unwrap();
        let table = [
            (3.0, 3.0),
            (6.0, 4.5),
            (9.0, 6.0),
            (0.0, 5.0),
            (0.0, 3.0),
            (0.0, 0.0),
        ];
        for (x, mean) in table {
            assert_relative_eq!(ma.step(x), mean, epsilon = 1e-15);
        }
    }

    /// A ramp `x_k = k` comes out `(N − 1)/2` samples late once the window is full.
    #[test]
    fn group_delay_is_half_the_window() {
        for n in [1u32, 2, 500, 1000] {
            let mut ma = MovingAverage::new(n).unwrap();
            let mut y = 0.0;
            for k in 0..3000 {
                y = ma.step(f64::from(k));
            }
            assert_relative_eq!(2999.0 - y, ma.delay_samples(), epsilon = 1e-9);
            assert_relative_eq!(ma.delay_samples(), (f64::from(n) - 1.0) / 2.0);
        }
    }

    /// A huge glitch leaves no residue once it has left the window (checked between two
    /// wraps of the ring, where only the compensated running sum carries the mean).
    #[test]
    fn glitch_leaves_no_residue() {
        let mut ma = Box::new(MovingAverage::new(4).unwrap());
        let outputs: std::vec::Vec<f64> = [1.0, 1e300, 1.0, 1.0, 1.0, 1.0]
            .iter()
            .map(|&x| ma.step(x))
            .collect();
        assert_eq!(outputs[5], 1.0);
        let mut ma = MovingAverage::new(5).unwrap();
        for x in [0.1, 1e17, -1e17, 0.1, 0.1, 0.1, 0.1] {
            ma.step(x);
        }
        assert_relative_eq!(ma.step(0.1), 0.1, epsilon = 1e-15);
    }

    #[test]
    fn reset_forgets() {
        let mut ma = MovingAverage::new(10).unwrap();
        ma.step(100.0);
        ma.reset();
        assert_eq!(ma.step(2.0), 2.0);
    }

    #[test]
    fn refuses_windows_beyond_the_limit() {
        assert_eq!(
            MovingAverage::new(4097).unwrap_err(),
            EstimatorError::CountOutOfRange {
                name: "samples",
                value: 4097,
                min: 1,
                max: 4096
            }
        );
        assert!(MovingAverage::new(0).is_err());
        assert!(MovingAverage::new(4096).is_ok());
    }
}
