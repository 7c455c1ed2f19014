//! The colours of the drawings: the paper's Fig. 1 convention for features, greys for
//! annotation.

/// Notch fill: orange, as in the paper's Fig. 1.
pub const NOTCH_FILL: &str = "#f39c35";
/// Notch outline: a darker orange, so neighbouring notches stay distinct when printed.
pub const NOTCH_EDGE: &str = "#b35f00";
/// Sensor U-trace: blue, as in Fig. 1.
pub const SENSOR: &str = "#1f5fd6";
/// Leads and contact pads: green, as in Fig. 1.
pub const LEADS_PADS: &str = "#1e9e3a";
/// Parting cut: dark grey, dashed.
pub const PARTING: &str = "#3c3c3c";
/// Tube surface (uncut polyimide) in the unrolled drawing.
pub const TUBE_FILL: &str = "#fbf3e4";
/// Tube material in the cross-section.
pub const SECTION_FILL: &str = "#d8d2c4";
/// Outlines of the tube and the section.
pub const OUTLINE: &str = "#202020";
/// Dimension lines, arrows and their text.
pub const DIMENSION: &str = "#202020";
/// Extension lines, ticks and centre lines: lighter, so they never compete with features.
pub const GUIDE: &str = "#8a8a8a";
/// The neutral plane in the cross-section.
pub const NEUTRAL: &str = "#b0006a";
/// Material a notch removes, in the cross-section: a pale orange "ghost" of the tube.
pub const NOTCH_GHOST: &str = "#fcd9ad";
