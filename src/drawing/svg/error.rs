/// Why an SVG drawing could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SvgError {
    /// A coordinate or size in the layout is not a finite number.
    #[error("{what} = {value} is not a finite number")]
    NotFinite {
        /// Which value, e.g. `notch 3 outline x`.
        what: String,
        /// The value found.
        value: f64,
    },
    /// A length that sets the drawing's extent is zero or negative.
    #[error("{what} = {value} mm must be greater than 0")]
    NotPositive {
        /// Which length.
        what: &'static str,
        /// The value found (mm).
        value: f64,
    },
    /// The requested print scale is not usable.
    #[error("print scale {value} must be a finite number from {min} to {max}")]
    BadScale {
        /// The scale asked for (paper mm per part mm).
        value: f64,
        /// Smallest scale accepted.
        min: f64,
        /// Largest scale accepted.
        max: f64,
    },
}
