//! Drawings of a joint: writers that turn the layout and the design into files for people and
//! for CAD.

/// SVG drawings for people: the unrolled layout and the cross-section through a notch.
pub mod svg;
