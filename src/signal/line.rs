//! The linear gauge-factor model (Eqs. 5-6) by least squares: `R = R₀·GF·ε + R₀`.

use serde::Serialize;

use super::SignalError;
use crate::stats::{moments, Moments};

/// A resistance that explains less than this share of its variance by strain (r²) is taken as
/// not responding to strain.
pub const MIN_R2: f64 = 0.05;

/// A fitted linear model. The JSON keys are part of `dlw fit --json`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearFit {
    /// Gauge factor `GF` (Eq. 5).
    pub gauge_factor: f64,
    /// Unstrained resistance `R₀` (Ω), the intercept.
    pub r0_ohm: f64,
    /// Coefficient of determination of the regression.
    pub r2: f64,
    /// Root mean square of the residuals `R_model − R` (Ω).
    pub rmse_ohm: f64,
}

impl LinearFit {
    /// The model's resistance at `strain`.
    pub fn resistance(&self, strain: f64) -> f64 {
        self.r0_ohm * (1.0 + self.gauge_factor * strain)
    }
}

/// Least squares of `ohm` on `strain`.
///
/// # Errors
/// [`SignalError::TooFewSamples`] under 3 samples; [`SignalError::NotIncreasing`] when the slope is
/// not positive or r² is under [`MIN_R2`]; [`SignalError::NonPhysical`] for `R₀ ≤ 0`.
pub fn fit_linear(strain: &[f64], ohm: &[f64]) -> Result<LinearFit, SignalError> {
    let n = strain.len().min(ohm.len());
    if n < 3 {
        return Err(SignalError::TooFewSamples { samples: n, min: 3 });
    }
    let Moments {
        mean_x: mx,
        mean_y: my,
        sxx,
        syy,
        sxy,
        ..
    } = moments(strain, ohm);
    // Variance below rounding of the mean: the strain is constant.
    let rounding = 1e-12 * mx.abs().max(1e-12);
    if sxx.is_nan() || sxx / n as f64 <= rounding * rounding {
        // 0/0 would be the slope and r² (the error printed "r² = NaN").
        return Err(SignalError::FlatStrain { samples: n });
    }
    let nf = n as f64;
    let slope = sxy / sxx;
    let r2 = if syy > 0.0 {
        sxy * sxy / (sxx * syy)
    } else {
        0.0
    };
    if !(slope > 0.0 && r2 >= MIN_R2) {
        return Err(SignalError::NotIncreasing {
            slope_ohm_per_strain: slope,
            r2,
            min_r2: MIN_R2,
        });
    }
    let r0 = my - slope * mx;
    if !(r0 > 0.0) {
        return Err(SignalError::NonPhysical {
            what: "r0_ohm",
            value: r0,
        });
    }
    let sse: f64 = (0..n)
        .map(|i| (ohm[i] - r0 - slope * strain[i]).powi(2))
        .sum();
    Ok(LinearFit {
        gauge_factor: slope / r0,
        r0_ohm: r0,
        r2,
        rmse_ohm: (sse / nf).sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn a_joint_that_never_moves_is_named_not_nan() {
        let err = fit_linear(&[0.001; 50], &(0..50).map(f64::from).collect::<Vec<_>>())
            .unwrap_err()
            .to_string();
        assert!(err.contains("never moves") && !err.contains("NaN"), "{err}");
    }

    #[test]
    fn recovers_gf_and_r0_exactly_from_a_line() {
        let strain: Vec<f64> = (0..100).map(|i| i as f64 * 1.5e-4).collect();
        let ohm: Vec<f64> = strain.iter().map(|e| 215e3 * (1.0 + 15.3 * e)).collect();
        let fit = fit_linear(&strain, &ohm).unwrap();
        assert_relative_eq!(fit.gauge_factor, 15.3, max_relative = 1e-10);
        assert_relative_eq!(fit.r0_ohm, 215e3, max_relative = 1e-12);
        assert_relative_eq!(fit.r2, 1.0, max_relative = 1e-12);
        assert!(fit.rmse_ohm < 1e-6);
    }

    #[test]
    fn flat_or_falling_resistance_is_refused() {
        let strain: Vec<f64> = (0..100).map(|i| i as f64 * 1e-4).collect();
        let flat: Vec<f64> = (0..100).map(|i| 1e5 + (i % 7) as f64).collect();
        let falling: Vec<f64> = strain.iter().map(|e| 1e5 * (1.0 - 5.0 * e)).collect();
        for ohm in [flat, falling] {
            let err = fit_linear(&strain, &ohm).unwrap_err();
            assert!(matches!(err, SignalError::NotIncreasing { .. }), "{err}");
        }
    }
}
