//! The noise model: an autoregressive process frozen from the rest at the start of the
//! recording, and the whitening filter it gives.
//!
//! At the bench's rate the noise is correlated from sample to sample (the ADC's and the
//! tracker's slow wander). Least squares that treats the samples as independent then sees
//! structure in noise and names effects that are not there. Discovery instead fits and scores
//! on `w(t) = e(t) − Σₖ φₖ·e(t−k)`, the residual passed through the AR model's inverse, whose
//! samples are close to independent.
//!
//! The model is frozen from the rest, where the joint does not move and the residual is noise
//! alone. Frozen from the base model's residuals during motion instead, it would absorb slow
//! effects such as drift as "noise".

/// Largest AR order tried.
pub const MAX_AR_ORDER: usize = 3;

/// An AR(p) noise model.
#[derive(Debug, Clone, PartialEq)]
pub struct ArNoise {
    /// `φ₁ … φ_p`.
    pub phi: Vec<f64>,
    /// Standard deviation of the residual during the rest (channel unit).
    pub sigma: f64,
}

impl ArNoise {
    /// No correlation: whitening changes nothing.
    pub fn white(sigma: f64) -> Self {
        Self {
            phi: Vec::new(),
            sigma,
        }
    }

    /// Yule-Walker (Levinson-Durbin) fit of order up to [`MAX_AR_ORDER`] to `e` (its mean
    /// removed). The order stops growing when a coefficient's partial correlation is under
    /// `2/√n`, the usual significance bound.
    pub fn fit(e: &[f64]) -> Self {
        let n = e.len();
        if n < 8 {
            return Self::white(0.0);
        }
        let mean = e.iter().sum::<f64>() / n as f64;
        let acov = |k: usize| -> f64 {
            (k..n)
                .map(|t| (e[t] - mean) * (e[t - k] - mean))
                .sum::<f64>()
                / n as f64
        };
        let r: Vec<f64> = (0..=MAX_AR_ORDER).map(acov).collect();
        let sigma = r[0].max(0.0).sqrt();
        if r[0].is_nan() || r[0] <= 0.0 {
            return Self::white(sigma);
        }
        let bound = 2.0 / (n as f64).sqrt();
        let mut phi: Vec<f64> = Vec::new();
        let mut err = r[0];
        for k in 1..=MAX_AR_ORDER {
            let acc: f64 = (1..k).map(|j| phi[j - 1] * r[k - j]).sum();
            let reflection = (r[k] - acc) / err;
            if !reflection.is_finite() || reflection.abs() < bound || reflection.abs() >= 1.0 {
                break;
            }
            let previous = phi.clone();
            for j in 1..k {
                phi[j - 1] = previous[j - 1] - reflection * previous[k - j - 1];
            }
            phi.push(reflection);
            err *= 1.0 - reflection * reflection;
        }
        Self { phi, sigma }
    }

    /// `w(t) = x(t) − Σ φₖ·x(t−k)`, with `x` taken as 0 before the start.
    pub fn whiten(&self, x: &[f64]) -> Vec<f64> {
        (0..x.len())
            .map(|t| {
                let past: f64 = self
                    .phi
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| t > *k)
                    .map(|(k, p)| p * x[t - k - 1])
                    .sum();
                x[t] - past
            })
            .collect()
    }

    /// The lag-one correlation the model implies (for the report).
    pub fn lag_one(&self) -> f64 {
        self.phi.first().copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn ar1(phi: f64, n: usize) -> Vec<f64> {
        let mut seed = 7u64;
        let mut x = 0.0;
        (0..n)
            .map(|_| {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let u = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                x = phi * x + u;
                x
            })
            .collect()
    }

    #[test]
    fn recovers_an_ar1_coefficient_and_whitens_it() {
        let x = ar1(0.9, 20_000);
        let model = ArNoise::fit(&x);
        assert!((model.lag_one() - 0.9).abs() < 0.02, "{model:?}");
        let w = model.whiten(&x);
        let again = ArNoise::fit(&w[1..]);
        assert!(again.lag_one().abs() < 0.05, "{again:?}");
    }

    #[test]
    fn white_noise_gets_no_coefficients() {
        let x = ar1(0.0, 5000);
        assert!(ArNoise::fit(&x).phi.len() <= 1);
    }
}
