use super::error::SvgError;

/// Smallest print scale accepted (1:100).
pub const MIN_SCALE: f64 = 0.01;
/// Largest print scale accepted (1000:1).
pub const MAX_SCALE: f64 = 1000.0;

/// The standard scales a sheet picks from, largest first.
const STANDARD_SCALES: [f64; 12] = [
    100.0, 50.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1, 0.05, 0.02,
];

/// Options shared by the SVG drawings.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SvgOptions {
    /// Print scale in paper mm per part mm (`10.0` is 10:1). `None` picks the largest standard
    /// scale (100:1, 50:1, 20:1, 10:1, 5:1, …) at which the whole sheet fits A4 landscape.
    pub print_scale: Option<f64>,
}

impl SvgOptions {
    /// The scale asked for, checked, or the largest standard scale for which `fits` holds.
    pub(crate) fn scale(&self, fits: impl Fn(f64) -> bool) -> Result<f64, SvgError> {
        match self.print_scale {
            Some(value) if value.is_finite() && (MIN_SCALE..=MAX_SCALE).contains(&value) => {
                Ok(value)
            }
            Some(value) => Err(SvgError::BadScale {
                value,
                min: MIN_SCALE,
                max: MAX_SCALE,
            }),
            None => Ok(STANDARD_SCALES
                .into_iter()
                .find(|s| fits(*s))
                .unwrap_or(STANDARD_SCALES[STANDARD_SCALES.len() - 1])),
        }
    }
}

/// Usable area of an A4 landscape sheet inside 10 mm borders (paper mm).
pub(crate) const A4_LANDSCAPE_MM: (f64, f64) = (277.0, 190.0);
