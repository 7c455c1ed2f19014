use crate::error::{positive, EstimatorError};

/// A first-order low-pass (exponential moving average), `y_k = y_{k−1} + α·(x_k − y_{k−1})`
/// with `α = 1 − exp(−1/τ)` for a time constant of `τ` samples. It starts at its first input.
///
/// It needs no buffer and any `τ`, so it can filter far less (or more) than a moving average
/// of practical length. Once settled it lags a ramp by `(1 − α)/α ≈ τ − ½` samples and divides
/// white noise's variance by `(2 − α)/α`. At `α = 2/(N + 1)` both match an `N`-sample moving
/// average; what differs is the step response, which starts at once here but settles only
/// exponentially, while the moving average's ends after exactly `N` samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowPass {
    alpha: f64,
    state: f64,
    started: bool,
}

impl LowPass {
    /// A low-pass with time constant `τ` samples.
    ///
    /// # Errors
    /// `τ` not finite or not positive.
    pub fn new(time_constant_samples: f64) -> Result<Self, EstimatorError> {
        positive("time_constant_samples", time_constant_samples)?;
        Ok(Self {
            alpha: 1.0 - libm::exp(-1.0 / time_constant_samples),
            state: 0.0,
            started: false,
        })
    }

    /// Smoothing factor `α = 1 − exp(−1/τ)`.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Lag behind a ramp once settled, `(1 − α)/α` samples.
    pub fn delay_samples(&self) -> f64 {
        (1.0 - self.alpha) / self.alpha
    }

    /// Ratio of output to input variance for white noise, `α/(2 − α)`.
    pub fn noise_variance_ratio(&self) -> f64 {
        self.alpha / (2.0 - self.alpha)
    }

    /// Feeds one sample and returns the filtered value.
    #[inline]
    pub fn step(&mut self, x: f64) -> f64 {
        if self.started && self.state.is_finite() {
            self.state += self.alpha * (x - self.state);
        } else {
            // A state that overflowed would never recover; restart from this sample instead.
            self.state = x;
            self.started = true;
        }
        self.state
    }

    /// Forgets the state; the next sample passes through.
    pub fn reset(&mut self) {
        self.started = false;
        self.state = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn step_response_vectors() {
        let mut lp = LowPass::new(1.0).unwrap();
        let a = 1.0 - (-1.0f64).exp();
        assert_relative_eq!(lp.alpha(), a);
        assert_eq!(lp.step(0.0), 0.0);
        let table = [a, a + a * (1.0 - a), 1.0 - (1.0 - a).powi(3)];
        for y in table {
            assert_relative_eq!(lp.step(1.0), y, epsilon = 1e-15);
        }
    }

    /// A ramp comes out `(1 − α)/α` samples late once settled.
    #[test]
    fn ramp_lag_matches_delay() {
        for tau in [0.5, 3.0, 100.0] {
            let mut lp = LowPass::new(tau).unwrap();
            let mut y = 0.0;
            for k in 0..5000 {
                y = lp.step(f64::from(k));
            }
            assert_relative_eq!(4999.0 - y, lp.delay_samples(), max_relative = 1e-9);
        }
    }

    /// Same white-noise reduction as an N-sample moving average at α = 2/(N + 1), and then the
    /// same ramp lag, (N − 1)/2.
    #[test]
    fn matches_moving_average_at_equal_noise() {
        let n = 500.0;
        let alpha: f64 = 2.0 / (n + 1.0);
        let tau = -1.0 / libm::log(1.0 - alpha);
        let lp = LowPass::new(tau).unwrap();
        assert_relative_eq!(lp.noise_variance_ratio(), 1.0 / n, max_relative = 1e-12);
        assert_relative_eq!(lp.delay_samples(), (n - 1.0) / 2.0, max_relative = 1e-12);
    }

    #[test]
    fn reset_and_refusals() {
        let mut lp = LowPass::new(10.0).unwrap();
        lp.step(5.0);
        lp.step(0.0);
        lp.reset();
        assert_eq!(lp.step(-3.0), -3.0);
        assert!(LowPass::new(0.0).is_err());
        assert!(LowPass::new(f64::INFINITY).is_err());
    }
}
