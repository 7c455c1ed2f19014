//! Table VI of the paper: the three RMSEs of one control scheme.

use serde::Serialize;

use super::scheme::Trace;

/// The paper's Table VI ("Joint Control Results", Joint D), for comparison:
/// `(sensed vs actual, actual vs desired, sensed vs desired)` in degrees, open loop then
/// closed loop.
pub const PAPER_TABLE_VI: [(f64, f64, f64); 2] = [(1.88, 8.14, 8.46), (2.29, 2.92, 2.93)];

/// Table VI's numbers for one scheme, and a few more. The JSON keys are part of the interface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SchemeMetrics {
    /// RMSE of `sensed − actual` (°): how well the estimator tracks the joint.
    pub sensed_vs_actual_rmse_deg: f64,
    /// RMSE of `actual − desired` (°): the tracking error of the scheme.
    pub actual_vs_desired_rmse_deg: f64,
    /// RMSE of `sensed − desired` (°): the tracking error the controller sees.
    pub sensed_vs_desired_rmse_deg: f64,
    /// Largest `|actual − desired|` (°).
    pub max_abs_actual_error_deg: f64,
    /// RMSE of `true − desired` (°), the tracking error without the tracker's noise.
    pub true_vs_desired_rmse_deg: f64,
    /// Samples the estimator held.
    pub held_samples: usize,
    /// Samples at which the PID correction was at a limit.
    pub saturated_samples: usize,
}

impl SchemeMetrics {
    /// Table VI's three RMSEs in its order: sensed vs actual, actual vs desired, sensed vs
    /// desired (°).
    pub fn table_vi(&self) -> [f64; 3] {
        [
            self.sensed_vs_actual_rmse_deg,
            self.actual_vs_desired_rmse_deg,
            self.sensed_vs_desired_rmse_deg,
        ]
    }

    /// The metrics of `trace` against `desired_deg`.
    pub fn of(trace: &Trace, desired_deg: &[f64]) -> Self {
        let max_abs = trace
            .actual_deg
            .iter()
            .zip(desired_deg)
            .fold(0.0f64, |m, (a, d)| m.max((a - d).abs()));
        Self {
            sensed_vs_actual_rmse_deg: rmse(&trace.sensed_deg, &trace.actual_deg),
            actual_vs_desired_rmse_deg: rmse(&trace.actual_deg, desired_deg),
            sensed_vs_desired_rmse_deg: rmse(&trace.sensed_deg, desired_deg),
            max_abs_actual_error_deg: max_abs,
            true_vs_desired_rmse_deg: rmse(&trace.true_deg, desired_deg),
            held_samples: trace.held_samples,
            saturated_samples: trace.saturated_samples,
        }
    }
}

/// Moved to [`crate::stats`] (one NaN policy); re-exported here this round.
pub use crate::stats::rmse;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::Scheme;
    use approx::assert_relative_eq;

    #[test]
    fn rmse_by_hand() {
        assert_relative_eq!(
            rmse(&[1.0, 2.0, 3.0], &[1.0, 0.0, 7.0]),
            (20.0f64 / 3.0).sqrt()
        );
        assert_eq!(rmse(&[], &[]), 0.0);
    }

    #[test]
    fn metrics_pair_the_right_columns() {
        let trace = Trace {
            scheme: Scheme::OpenLoop,
            actual_deg: vec![1.0, 1.0],
            true_deg: vec![1.0, 3.0],
            sensed_deg: vec![2.0, 2.0],
            stroke_mm: vec![0.0, 0.0],
            held_samples: 1,
            saturated_samples: 0,
        };
        let m = SchemeMetrics::of(&trace, &[0.0, 0.0]);
        assert_relative_eq!(m.sensed_vs_actual_rmse_deg, 1.0);
        assert_relative_eq!(m.actual_vs_desired_rmse_deg, 1.0);
        assert_relative_eq!(m.sensed_vs_desired_rmse_deg, 2.0);
        assert_relative_eq!(m.true_vs_desired_rmse_deg, 5.0f64.sqrt());
        assert_eq!(m.held_samples, 1);
    }
}
