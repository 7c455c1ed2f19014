//! The unrolled joint: every feature the laser writes or cuts, in the drawing frame.
//!
//! # Frame
//! - `x` (mm) runs along the tube axis from the joint's distal end (`x = 0`, the free end of
//!   the stock tube) towards the collet; the parting cut is at `x = length_mm`.
//! - `s` (mm) is arc length on the outer surface, `s = r_o·φ`, with `φ` measured from the
//!   cross-section's `+y` axis (the sensor centre line of a UAN joint, see `dlw_geometry`).
//!   UAN notches are centred at `s = π·r_o`; BSN notch pairs at `s = 0` and `s = π·r_o`.
//! - The drawing shows `s` in the window `[seam_s_mm, seam_s_mm + circumference_mm)`. A laser
//!   program uses the same numbers: its X is `x` and its A is `s/r_o` in degrees, so a program
//!   overlays its drawing exactly.
//!
//! Geometry is held in `geo` types with `x` as the first coordinate and `s` as the second.
//! Notches are designed outlines (the kerf is applied by the toolpath planner); traces, leads,
//! pads and the parting line are the centre lines the beam follows.

use geo::{LineString, Polygon};

/// The unrolled layout of one joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The design's name.
    pub name: String,
    /// Outer radius `r_o` (mm): converts `s` to the rotary axis, `A = s/r_o`.
    pub outer_radius_mm: f64,
    /// Outer circumference `2π·r_o` (mm).
    pub circumference_mm: f64,
    /// Lower edge of the drawing's `s` window (mm); the window is one circumference tall.
    pub seam_s_mm: f64,
    /// Width of a laser-written line (mm).
    pub trace_width_mm: f64,
    /// Width the cutting beam removes (mm).
    pub kerf_mm: f64,
    /// Joint length from the distal end to the parting cut (mm).
    pub length_mm: f64,
    /// Notches, as closed designed outlines.
    pub notches: Vec<Notch>,
    /// Sensor U-traces: arm, distal bridge, arm, as one centre line per piece.
    pub sensors: Vec<Trace>,
    /// Leads from the sensor arms to the pads.
    pub leads: Vec<Trace>,
    /// Square-spiral contact pads, each one continuous centre line.
    pub pads: Vec<Trace>,
    /// The parting cut all the way round at `x = length_mm`, split at the seam.
    pub parting: Vec<LineString<f64>>,
}

/// One notch.
#[derive(Debug, Clone, PartialEq)]
pub struct Notch {
    /// Position along the tube, 0 at the distal end.
    pub level: usize,
    /// Side: 0 for the notch centred at `s = π·r_o`, 1 for the BSN notch centred at `s = 0`.
    pub side: usize,
    /// Closed outline in `(x, s)`, mm. A notch that crosses the seam is split into two pieces,
    /// each closed at the seam.
    pub outline: Vec<Polygon<f64>>,
}

/// A laser-written line.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// The sensor it belongs to: 0 (the `+y_s` sensor) or 1 (BSN's `−y_s` sensor).
    pub sensor: usize,
    /// Centre line pieces in `(x, s)`, mm, split at the seam where they cross it.
    pub pieces: Vec<LineString<f64>>,
}
