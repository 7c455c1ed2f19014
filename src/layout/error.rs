/// Why a design could not be laid out.
///
/// Only values that make the geometry itself impossible land here; everything else a design can
/// get wrong (clearances, kerf, length consistency) is a design rule, checked by `rules` on the
/// finished layout so that every violation is listed at once.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LayoutError {
    /// A fabrication length that must be a positive, finite number is not.
    #[error("{name} = {value} must be a finite number greater than 0")]
    NotPositive {
        /// Key as written in the design file's `[fabrication]` table.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A square-spiral pad needs at least one turn.
    #[error("pad_turns = 0 must be at least 1")]
    NoPadTurns,
    /// A pad is wider than the tube is round.
    #[error("a pad of pad_turns = {turns} at pad_pitch_mm = {pitch_mm} is {size_mm} mm wide, more than the circumference {circumference_mm:.4} mm")]
    PadTooLarge {
        /// Spiral turns.
        turns: u32,
        /// Spiral pitch (mm).
        pitch_mm: f64,
        /// Pad size `2·turns·pitch` (mm).
        size_mm: f64,
        /// Circumference (mm).
        circumference_mm: f64,
    },
}

/// Checks that a fabrication length is finite and positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, LayoutError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(LayoutError::NotPositive { name, value })
    }
}
