//! SVG drawings for people: the unrolled layout ([`layout_svg`]) and the cross-section through
//! a notch ([`section_svg`]).
//!
//! # Frames
//! - Layout sheet: the layout's frame (see [`crate::layout`]): `x` along the tube from the
//!   distal end, drawn to the right; `s`, arc length on the outer surface, drawn upward over
//!   the window `[seam_s_mm, seam_s_mm + circumference_mm)`. The tube's top and bottom edges
//!   are both the seam.
//! - Section sheet: the `dlw_geometry` cross-section frame: origin on the tube axis, `y` up
//!   toward the UAN backbone, `φ` measured from `+y`.
//!
//! # Units and scale
//! SVG user units are millimetres of the part. The root `width` and `height` are the viewBox
//! times a print scale (by default the largest of 100:1, 50:1, 20:1, 10:1, 5:1, … at which the
//! sheet fits A4 landscape), in mm, so the file prints to scale; the scale is written under
//! the scale bar. Text and arrows are sized in paper millimetres, so they read the same at any
//! scale.
//!
//! # Colours
//! The paper's Fig. 1: notches orange, the sensor blue, leads and contact pads green; the
//! parting cut dark grey and dashed. Each feature kind is one `<g>` layer (`notches`,
//! `sensor`, `leads-pads`, `parting`, …) and each feature's element has a `class` naming it
//! (`notch`, `sensor`, `lead`, `pad`, `parting`), so a reader or a test can pick them out.
//!
//! # Examples
//! ```
//! use dlw::design::Design;
//! use dlw::drawing::svg::section_svg;
//!
//! let design = Design::from_toml(r#"
//! name = "Joint C"
//! style = "bsn"
//! outer_radius_mm = 0.8
//! inner_radius_mm = 0.61
//! notch_arc_mm = 1.65
//! notch_width_mm = 0.5
//! notch_spacing_mm = 0.5
//! notch_count = 10
//! joint_length_mm = 9.5
//! sensor_arc_mm = 2.13
//! "#)?;
//! let svg = section_svg(&design)?;
//! assert!(svg.contains("Δy"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Errors
//! [`SvgError`] names a non-finite or non-positive layout value, or an unusable print scale.

pub(crate) mod annotate;
#[cfg(test)]
mod collisions;
mod error;
#[cfg(test)]
mod fixture;
pub(crate) mod layout;
pub(crate) mod options;
pub(crate) mod palette;
mod section;
pub(crate) mod sheet;
#[cfg(test)]
mod tests;

/// Why an SVG drawing could not be made.
pub use error::SvgError;
/// The unrolled layout as an SVG sheet.
pub use layout::{layout_svg, layout_svg_with};
/// Options shared by the drawings (print scale).
pub use options::{SvgOptions, MAX_SCALE, MIN_SCALE};
/// The cross-section through a notch (Fig. 3) as an SVG sheet.
pub use section::{section_svg, section_svg_with};
