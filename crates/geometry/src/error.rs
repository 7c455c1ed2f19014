use core::fmt;

/// Why a geometry value was refused. Every variant carries the offending value and the limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GeometryError {
    /// A length or count that must be a finite number is not.
    NotFinite {
        /// Parameter name as written in design files.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A length that must be positive is zero or negative.
    NotPositive {
        /// Parameter name as written in design files.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The inner radius is not smaller than the outer radius.
    InnerRadiusTooLarge {
        /// Inner radius r_i (mm).
        inner_mm: f64,
        /// Outer radius r_o (mm).
        outer_mm: f64,
    },
    /// The notches take the whole circumference (for BSN, the pair overlaps).
    NotchTooLong {
        /// Total notch arc at one level (s_n, or 2·s_n for BSN) in mm.
        total_arc_mm: f64,
        /// Circumference 2π·r_o (mm).
        circumference_mm: f64,
    },
    /// The sensor's arms do not sit on the backbone between the notches (for BSN, also:
    /// sensor 1's arms must stay on the `+y` side, else both sensor planes coincide).
    SensorArcOutOfRange {
        /// Sensor arc s_s (mm).
        sensor_arc_mm: f64,
        /// Smallest allowed arc, exclusive (mm).
        min_mm: f64,
        /// Largest allowed arc, exclusive (mm).
        max_mm: f64,
    },
    /// A joint needs at least one notch.
    NoNotches,
    /// The sensor sits on the neutral plane, so its strain does not depend on the angle.
    ZeroOffset {
        /// Δy = y_s − ȳ (mm).
        offset_mm: f64,
    },
    /// The tendon does not run inside the tube's lumen.
    TendonOutsideLumen {
        /// r_t (mm).
        tendon_offset_mm: f64,
        /// r_i (mm).
        inner_mm: f64,
    },
    /// A divider reading at or beyond a rail has no finite resistance.
    VoltageAtRail {
        /// The reading (V).
        volts: f64,
        /// The supply V+ (V); the rails are 0 and V+.
        supply_v: f64,
    },
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NotFinite { name, value } => write!(f, "{name} = {value} is not a finite number"),
            Self::NotPositive { name, value } => write!(f, "{name} = {value} must be greater than 0"),
            Self::InnerRadiusTooLarge { inner_mm, outer_mm } => write!(
                f,
                "inner_radius_mm = {inner_mm} must be smaller than outer_radius_mm = {outer_mm}"
            ),
            Self::NotchTooLong { total_arc_mm, circumference_mm } => write!(
                f,
                "notch arc at one level is {total_arc_mm:.4} mm, must be less than the circumference {circumference_mm:.4} mm"
            ),
            Self::SensorArcOutOfRange { sensor_arc_mm, min_mm, max_mm } => write!(
                f,
                "sensor_arc_mm = {sensor_arc_mm} must lie between {min_mm:.4} and {max_mm:.4} mm so both arms sit on the backbone"
            ),
            Self::NoNotches => write!(f, "notch_count = 0 must be at least 1"),
            Self::ZeroOffset { offset_mm } => write!(
                f,
                "sensor plane is {offset_mm:.3e} mm from the neutral plane, so it senses no strain (must not be 0)"
            ),
            Self::TendonOutsideLumen { tendon_offset_mm, inner_mm } => write!(
                f,
                "tendon_offset_mm = {tendon_offset_mm} must be at most the inner radius inner_radius_mm = {inner_mm} (the tendon runs in the lumen)"
            ),
            Self::VoltageAtRail { volts, supply_v } => write!(
                f,
                "divider reading {volts} V is at or beyond a rail (must lie strictly between 0 and {supply_v} V)"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for GeometryError {}

/// Checks that `value` is finite and positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, GeometryError> {
    if !value.is_finite() {
        return Err(GeometryError::NotFinite { name, value });
    }
    if value <= 0.0 {
        return Err(GeometryError::NotPositive { name, value });
    }
    Ok(value)
}
