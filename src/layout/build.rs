use crate::design::Design;

use super::error::LayoutError;
use super::{Layout, Unrolled};

impl Layout {
    /// Lays out a design: notches, sensor U-traces, leads, square-spiral pads and the parting
    /// line, placed along `x` by [`super::Stations`] and wrapped round the seam chosen so that
    /// as little as possible is split (see `docs/frames.md`): [`Unrolled::from_design`], then
    /// [`Unrolled::wrap`].
    ///
    /// Order of the features: notches by level, then side; one sensor trace per sensor (0, then
    /// BSN's 1); leads and pads per sensor, arm A's (smaller `s`) before arm B's, so lead `2j+a`
    /// runs from sensor `j`'s arm `a` to pad `2j+a`.
    ///
    /// The layout is built whether or not it passes the design rules; `rules::check` judges it.
    ///
    /// # Errors
    /// [`LayoutError`] when a fabrication length is not positive or the pads have no turns.
    pub fn from_design(design: &Design) -> Result<Self, LayoutError> {
        Ok(Unrolled::from_design(design)?.wrap())
    }
}
