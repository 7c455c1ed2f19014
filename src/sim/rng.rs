//! Seeded random streams, one per source of randomness, so that switching one effect on or off
//! never changes the draws of another.
//!
//! Every stream is ChaCha8 seeded from the scenario's seed, with its own stream number (ChaCha's
//! 64-bit stream id), so runs are identical on every platform for a given seed. Uniform numbers
//! take the top 53 bits of a `u64`; Gaussian numbers come from `rand_distr`'s `StandardNormal`.

use rand_chacha::ChaCha8Rng;
use rand_core::{RngCore, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

/// The stream numbers in use; a new source of randomness takes a new number, so that the
/// existing sources keep their draws (old seeds give the same recordings).
pub mod streams {
    /// The random protocol's pattern.
    pub const PROTOCOL: u64 = 0;
    /// The EM tracker's noise.
    pub const TRACKER: u64 = 1;
    /// ADC noise of sensor 1; sensor 2 uses the next number.
    pub const ADC: u64 = 2;
    /// Baseline drift of sensor 1; sensor 2 uses the next number.
    pub const DRIFT: u64 = 4;
    /// Correlated ADC noise of sensor 1; sensor 2 uses the next number.
    pub const ADC_CORRELATED: u64 = 6;
    /// The EM tracker's correlated error.
    pub const TRACKER_CORRELATED: u64 = 8;
    /// The bench's temperature wander, shared by the sensors.
    pub const TEMPERATURE: u64 = 9;
    /// Sensor 1's own resistance noise (`[sensor1.noise]`); sensor 2 uses the next number.
    pub const SENSOR_NOISE: u64 = 10;
}

/// One seeded random stream.
#[derive(Debug, Clone)]
pub struct Stream(ChaCha8Rng);

impl Stream {
    /// Stream number `stream` of seed `seed`.
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(stream);
        Self(rng)
    }

    /// A uniform number in `[0, 1)`.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A standard normal number (mean 0, variance 1).
    #[inline]
    pub fn normal(&mut self) -> f64 {
        StandardNormal.sample(&mut self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_independent() {
        let draw = |seed, stream| {
            let mut s = Stream::new(seed, stream);
            (0..4).map(|_| s.uniform()).collect::<Vec<_>>()
        };
        assert_eq!(draw(5, 1), draw(5, 1));
        assert_ne!(draw(5, 1), draw(5, 2));
        assert_ne!(draw(5, 1), draw(6, 1));
        assert!(draw(5, 1).iter().all(|u| (0.0..1.0).contains(u)));
    }

    #[test]
    fn normal_has_unit_variance() {
        let mut s = Stream::new(1, 9);
        let n = 100_000;
        let (mut sum, mut sq) = (0.0, 0.0);
        for _ in 0..n {
            let x = s.normal();
            sum += x;
            sq += x * x;
        }
        let mean = sum / n as f64;
        let var = sq / n as f64 - mean * mean;
        // Standard errors: 1/√n = 0.003 for the mean, √(2/n) = 0.0045 for the variance.
        assert!(mean.abs() < 0.015, "{mean}");
        assert!((var - 1.0).abs() < 0.025, "{var}");
    }
}
