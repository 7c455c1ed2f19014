//! The sensing side's signal floor: what every analysis (fit, characterize, discover, control)
//! sees of a recording, below all of them.
//!
//! - [`observe`]: one sensor's own strain (Eq. 3) and resistance (Eq. 4) per sample, through a
//!   [`Prefilter`] and decimated, keeping only samples whose prefilter window the tracker
//!   measured;
//! - [`FilterSpec`], [`Prefilter`]: the one `none | ma:N | lp:T` grammar of filters;
//! - [`phases`], [`cycles`]: the strain's loading and unloading runs between turning points;
//! - [`fit_linear`]: the line `R = R₀·(1 + GF·ε)` by least squares (Eqs. 5-6).
//!
//! It depends on the recording, the runtime crates and the shared statistics only.
//!
//! # Errors
//! [`SignalError`]: a recording that shows the sensor nothing to analyse (no such column, no
//! motion, a voltage at a rail), or a line that cannot be fitted.

// `!(x > 0.0)` is how a check refuses NaN along with the out-of-range values, on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod cycles;
mod filter;
mod line;
mod observe;

use dlw_estimator::EstimatorError;

/// Loading and unloading phases and cycles of the strain.
pub use cycles::{cycles, phases, Cycle, Phase, TURN_THRESHOLD};
/// Filters by name: the estimator's and the analyses' prefilter.
pub use filter::{FilterSpec, Prefilter};
/// The linear model by least squares.
pub use line::{fit_linear, LinearFit, MIN_R2};
/// A sensor's strain and resistance as an analysis sees them.
pub use observe::{observe, Observations, MAX_FIT_SAMPLES, MIN_ANGLE_SPAN_DEG, RAIL_FRACTION};

/// Why a recording could not be observed, or a line not fitted.
#[derive(Debug, thiserror::Error)]
pub enum SignalError {
    /// The recording has no such voltage column.
    #[error("the recording has {columns} voltage column(s); sensor on that plane is recorded as v{column}_V")]
    NoColumn {
        /// The column needed (1-based).
        column: usize,
        /// Columns present.
        columns: usize,
    },
    /// The joint hardly moved.
    #[error("no motion: the recorded angle spans {span_deg:.3}°, a fit needs at least {min_deg}°")]
    NoMotion {
        /// Span of the recorded angle (°).
        span_deg: f64,
        /// The least span accepted (°).
        min_deg: f64,
    },
    /// A voltage at a rail.
    #[error("v{column}_V is at a rail in {count} sample(s), first at t = {time_s} s ({volts} V, within {margin_v} V of 0 or the supply): the divider resolves no resistance there (saturated ADC, open or shorted sensor)")]
    Rail {
        /// Column (1-based).
        column: usize,
        /// Samples at a rail.
        count: usize,
        /// Time of the first (s).
        time_s: f64,
        /// Its voltage (V).
        volts: f64,
        /// How near a rail counts (V).
        margin_v: f64,
    },
    /// Too few samples for a line.
    #[error("{samples} sample(s) after decimation; a fit needs at least {min}")]
    TooFewSamples {
        /// Samples left.
        samples: usize,
        /// The least accepted.
        min: usize,
    },
    /// The strain never varies over the samples fitted.
    #[error("the strain does not vary over the {samples} samples fitted (the joint never moves there): there is no slope to fit; record motion")]
    FlatStrain {
        /// Samples looked at.
        samples: usize,
    },
    /// The resistance does not rise with strain.
    #[error("the resistance does not increase with strain: slope {slope_ohm_per_strain:.4e} Ω per unit strain, r² = {r2:.3} (needs a positive slope and r² ≥ {min_r2})")]
    NotIncreasing {
        /// Fitted slope (Ω per unit strain).
        slope_ohm_per_strain: f64,
        /// r² of the line.
        r2: f64,
        /// The least r² accepted.
        min_r2: f64,
    },
    /// A fitted value no sensor has.
    #[error("the fit gives {what} = {value}, which no sensor has")]
    NonPhysical {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// The runtime crate refused the prefilter.
    #[error("the fitted model is not one the runtime can run: {0}")]
    Filter(EstimatorError),
}
