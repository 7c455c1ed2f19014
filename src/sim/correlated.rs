//! Correlated measurement noise: a first-order autoregressive process, the exact sampling of an
//! Ornstein-Uhlenbeck process.
//!
//! With stationary standard deviation `σ`, correlation time `τ` and sample period `Δt`:
//!
//! ```text
//! φ = e^(−Δt/τ)
//! c[0]   ~ N(0, σ²)                              (started in its stationary state)
//! c[k+1] = φ·c[k] + σ·√(1 − φ²)·n[k],  n[k] ~ N(0, 1)
//! ```
//!
//! so `var(c[k]) = σ²` at every sample and the lag-`m` autocorrelation is `φ^m = e^(−m·Δt/τ)`.
//! Its power spectral density is flat up to `1/(2πτ)` and falls as `1/f²` above: at the rates of
//! a bench's slow effects (drift, relaxation, creep) it holds far more power than white noise of
//! the same variance, which is what makes it matter to anything that compares a model with a
//! recording.

use super::rng::Stream;

/// A first-order autoregressive noise source, stepped once per sample.
#[derive(Debug, Clone)]
pub struct Ar1 {
    phi: f64,
    innovation_sd: f64,
    value: f64,
    rng: Stream,
}

impl Ar1 {
    /// Noise of stationary standard deviation `sigma` and correlation time `tau_s`, sampled
    /// every `dt_s` seconds, drawing from `rng`. `tau_s` and `dt_s` must be positive, `sigma`
    /// at least 0 (the scenario checks).
    pub fn new(sigma: f64, tau_s: f64, dt_s: f64, mut rng: Stream) -> Self {
        let phi = (-dt_s / tau_s).exp();
        // 1 − φ² = −expm1(−2Δt/τ), exact even when Δt ≪ τ.
        let innovation_sd = sigma * (-(-2.0 * dt_s / tau_s).exp_m1()).sqrt();
        let value = sigma * rng.normal();
        Self {
            phi,
            innovation_sd,
            value,
            rng,
        }
    }

    /// The lag-one autocorrelation `φ = e^(−Δt/τ)`.
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// This sample's value; advances to the next.
    #[inline]
    pub fn next_value(&mut self) -> f64 {
        let v = self.value;
        self.value = self.phi * v + self.innovation_sd * self.rng.normal();
        v
    }
}

/// Sample standard deviation and autocorrelation at lag `lag` of `x` (mean removed), for tests.
#[cfg(test)]
pub(crate) fn sd_and_autocorrelation(x: &[f64], lag: usize) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    let cov = x
        .windows(lag + 1)
        .map(|w| (w[0] - mean) * (w[lag] - mean))
        .sum::<f64>()
        / n;
    (var.sqrt(), cov / var)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A long run has the stated spread and autocorrelation `e^(−m·Δt/τ)`.
    ///
    /// τ = 0.1 s at 500 Hz is 50 samples, so 10⁶ samples hold 10⁴ correlation times: the
    /// sample variance's relative standard error is √(2(1 + φ²)/(n(1 − φ²))) ≈ 1.4 %, the
    /// standard deviation's half that, and the lag-1 autocorrelation's standard error
    /// √((1 − φ²)/n) ≈ 2·10⁻⁴. The tolerances are about five standard errors.
    #[test]
    fn long_run_has_the_stated_spread_and_autocorrelation() {
        let (sigma, tau_s, dt_s) = (0.7, 0.1, 0.002);
        let mut ar = Ar1::new(sigma, tau_s, dt_s, Stream::new(3, 6));
        let x: Vec<f64> = (0..1_000_000).map(|_| ar.next_value()).collect();
        let phi = (-dt_s / tau_s).exp();
        assert_eq!(ar.phi(), phi);
        let (sd, r1) = sd_and_autocorrelation(&x, 1);
        assert!((sd / sigma - 1.0).abs() < 0.035, "sd {sd} vs {sigma}");
        assert!((r1 - phi).abs() < 1e-3, "lag-1 {r1} vs {phi}");
        // One correlation time later: 1/e, standard error ≈ √(1/n_eff) ≈ 0.01.
        let (_, r50) = sd_and_autocorrelation(&x, 50);
        assert!((r50 - (-1.0f64).exp()).abs() < 0.05, "lag-50 {r50}");
    }

    #[test]
    fn starts_stationary_and_follows_the_seed() {
        // Over many independent starts, the first sample already has spread σ.
        let firsts: Vec<f64> = (0..4000)
            .map(|seed| Ar1::new(2.0, 1.0, 0.002, Stream::new(seed, 6)).next_value())
            .collect();
        let rms = (firsts.iter().map(|v| v * v).sum::<f64>() / 4000.0).sqrt();
        // Standard error of an RMS over 4000 draws: 1.1 %.
        assert!((rms / 2.0 - 1.0).abs() < 0.06, "{rms}");
        let path = |seed| {
            let mut a = Ar1::new(1.0, 1.0, 0.002, Stream::new(seed, 6));
            (0..100).map(|_| a.next_value()).collect::<Vec<_>>()
        };
        assert_eq!(path(1), path(1));
        assert_ne!(path(1), path(2));
    }

    #[test]
    fn zero_sigma_is_silent() {
        let mut a = Ar1::new(0.0, 2.0, 0.002, Stream::new(1, 6));
        assert!((0..1000).all(|_| a.next_value() == 0.0));
    }
}
