//! One frame, from pixels to a fitted pin or the reason it has none: crop → threshold → largest
//! component → second-moment ellipse.
//!
//! A frame with no plausible pin is reported and skipped, not guessed: a mask with no pixel
//! (`no_pin`), a largest component smaller than `min_area_px` (`too_small`), one that touches
//! the crop's border (`edge`: the pin is cut off by the crop, or the threshold split the
//! background, as Otsu does on a frame without a pin), or one too round for its axis to mean
//! anything (`a/b < min_axis_ratio`, `too_round`).

use super::frames::Frame;
use super::{largest_component, pin_mask, Crop, Ellipse, FluoroError, Threshold};

/// How frames are analyzed; every tolerance is explicit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The region searched; `None` for the whole frame.
    pub crop: Option<Crop>,
    /// Otsu or a fixed level.
    pub threshold: Threshold,
    /// The pin is bright on a dark background.
    pub invert: bool,
    /// The smallest plausible pin (px).
    pub min_area_px: u32,
    /// The smallest plausible `a/b`.
    pub min_axis_ratio: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            crop: None,
            threshold: Threshold::Otsu,
            invert: false,
            min_area_px: 20,
            min_axis_ratio: 1.5,
        }
    }
}

impl Settings {
    /// Checks the settings against frames of `width`×`height` px at `bits` bits.
    ///
    /// # Errors
    /// [`FluoroError::CropOutside`], [`FluoroError::ThresholdRange`], [`FluoroError::Setting`].
    pub fn check(&self, width: u32, height: u32, bits: u32) -> Result<(), FluoroError> {
        if let Some(c) = self.crop {
            c.check_inside(width, height)?;
        }
        let max = (1u32 << bits) - 1;
        if let Threshold::Value(v) = self.threshold {
            if u32::from(v) > max {
                return Err(FluoroError::ThresholdRange {
                    value: v.into(),
                    bits,
                    max,
                });
            }
        }
        if !(self.min_axis_ratio.is_finite() && self.min_axis_ratio >= 1.0) {
            return Err(FluoroError::Setting {
                name: "--min-axis-ratio",
                value: self.min_axis_ratio,
                limit: "finite and at least 1",
            });
        }
        if self.min_area_px < 2 {
            return Err(FluoroError::Setting {
                name: "--min-area-px",
                value: self.min_area_px.into(),
                limit: "at least 2 pixels, or no axis can be fitted",
            });
        }
        Ok(())
    }
}

/// Why a frame has no pin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Skip {
    /// Nothing passed the threshold.
    NoPin,
    /// The largest component is smaller than `min_area_px`.
    TooSmall,
    /// The largest component touches the crop's border.
    Edge,
    /// The largest component's `a/b` is below `min_axis_ratio`.
    TooRound,
}

impl Skip {
    /// The flag written in `angles.csv`.
    pub fn flag(self) -> &'static str {
        match self {
            Self::NoPin => "no_pin",
            Self::TooSmall => "too_small",
            Self::Edge => "edge",
            Self::TooRound => "too_round",
        }
    }
}

/// What one frame gave.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameFit {
    /// The fitted ellipse of the largest component (also for a skipped frame, when it has one,
    /// so that the overlay can show what was refused).
    pub ellipse: Option<Ellipse>,
    /// Pixels of the largest component (0 without one).
    pub area_px: u64,
    /// Why the frame is skipped; `None` when the pin counts.
    pub skip: Option<Skip>,
    /// The threshold level used, in the frame's units.
    pub level: f64,
}

impl FrameFit {
    /// The pin's axis angle (°), `None` for a skipped frame.
    pub fn angle_deg(&self) -> Option<f64> {
        match self.skip {
            None => self.ellipse.map(|e| e.angle_deg),
            Some(_) => None,
        }
    }
}

/// Analyzes one frame; the settings must have been checked against it.
pub fn analyze_frame(frame: &Frame, settings: &Settings) -> FrameFit {
    let (w, h) = frame.dimensions();
    let crop = settings.crop.unwrap_or(Crop::whole(w, h));
    let (mask, level) = pin_mask(&frame.image, crop, settings.threshold, settings.invert);
    let Some(c) = largest_component(&mask) else {
        return FrameFit {
            ellipse: None,
            area_px: 0,
            skip: Some(Skip::NoPin),
            level,
        };
    };
    let ellipse = Ellipse::from_component(&c, f64::from(crop.x), f64::from(crop.y));
    let skip = if c.area_px < u64::from(settings.min_area_px) {
        Some(Skip::TooSmall)
    } else if c.touches_border {
        Some(Skip::Edge)
    } else if ellipse.axis_ratio() < settings.min_axis_ratio {
        Some(Skip::TooRound)
    } else {
        None
    };
    FrameFit {
        ellipse: Some(ellipse),
        area_px: c.area_px,
        skip,
        level,
    }
}
