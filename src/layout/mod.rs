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
//! Cut features are drawn as the finished part's edges: notches are designed outlines and the
//! parting line is the joint's proximal end; the toolpath planner puts the cutting beam kerf/2
//! into the scrap from them (inside a notch, beyond the parting line). Written features (traces,
//! leads, pads) are the centre lines the writing beam follows.
//!
//! [`Layout::from_design`] builds the layout from a design; `docs/frames.md` draws the frame,
//! the stations along `x` and the seam.

mod build;
mod compare;
mod error;
mod leads;
mod measure;
mod notches;
mod pads;
mod seam;
mod sensor;
mod stations;
mod unrolled;

use geo::{LineString, Polygon};

/// The notch-count limit, defined with the design ([`crate::design::MAX_NOTCH_COUNT`]) and
/// re-exported here for the layout's callers.
pub use crate::design::MAX_NOTCH_COUNT;
/// Why a design could not be laid out.
pub use error::LayoutError;
/// The square-spiral pads, for a robot's pad section.
pub(crate) use pads::{square_spiral, PadSide};
/// Where each feature sits along the tube: the layout's plan in `x`.
pub use stations::Stations;
/// The layout before its seam is chosen: every feature with `s` unwrapped.
pub use unrolled::{NotchRect, Polyline, Unrolled};

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
    /// The joint's proximal end all the way round at `x = length_mm`, split at the seam; the
    /// parting beam runs kerf/2 beyond it, in the stock.
    pub parting: Vec<LineString<f64>>,
}

/// One notch.
#[derive(Debug, Clone, PartialEq)]
pub struct Notch {
    /// The joint of a robot it belongs to (0 for the distal joint), `None` in a joint's own
    /// layout and in a one-joint robot's (`crate::robot`); messages then name it
    /// `joint 2 notch 3`.
    pub joint: Option<usize>,
    /// Position along the tube, 0 at the distal end (within its joint, for a robot).
    pub level: usize,
    /// Side: 0 for the notch centred at `s = π·r_o`, 1 for the BSN notch centred at `s = 0`.
    pub side: usize,
    /// Closed outline in `(x, s)`, mm. A notch that crosses the seam is split into two pieces,
    /// each closed at the seam.
    pub outline: Vec<Polygon<f64>>,
}

impl Notch {
    /// How the notch is named in messages: `notch 4`, or `notch 4 (side 1)` on a BSN joint; on
    /// a robot, `joint 2 notch 4`.
    pub fn label(&self, bsn: bool) -> String {
        let joint = self
            .joint
            .map_or_else(String::new, |j| format!("joint {} ", j + 1));
        if bsn {
            format!("{joint}notch {} (side {})", self.level + 1, self.side)
        } else {
            format!("{joint}notch {}", self.level + 1)
        }
    }
}

/// A laser-written line.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// The sensor it belongs to: 0 (the `+y_s` sensor) or 1 (BSN's `−y_s` sensor).
    pub sensor: usize,
    /// Centre line pieces in `(x, s)`, mm, split at the seam where they cross it.
    pub pieces: Vec<LineString<f64>>,
}

#[cfg(test)]
mod tests {
    use core::f64::consts::PI;

    use approx::assert_relative_eq;
    use geo::{Area, BoundingRect};

    use super::*;
    use crate::design::Design;

    fn design(path: &str) -> Design {
        Design::load(std::path::Path::new(&format!(
            "{}/designs/{path}",
            env!("CARGO_MANIFEST_DIR")
        )))
        .unwrap()
    }

    #[test]
    fn shipped_designs_lay_out_with_area_and_counts() {
        for (file, sides) in [
            ("joint-a.toml", 1),
            ("joint-b.toml", 1),
            ("joint-c.toml", 2),
            ("joint-d.toml", 1),
        ] {
            let d = design(file);
            let l = Layout::from_design(&d).unwrap();
            let s = d.joint.section();
            assert_eq!(l.notches.len(), 10 * sides, "{file}");
            assert_eq!(l.sensors.len(), sides, "{file}");
            assert_eq!(l.leads.len(), 2 * sides);
            assert_eq!(l.pads.len(), 2 * sides);
            let expected = 10.0 * 0.5 * s.notch_arc_mm() * sides as f64;
            assert_relative_eq!(l.notch_area_mm2(), expected, max_relative = 1e-12);
            // Everything lies in the window [seam, seam + C].
            let c = l.circumference_mm;
            assert_relative_eq!(c, 2.0 * PI * s.outer_radius_mm());
            let b = l.extents().unwrap();
            assert!(b.min().y >= l.seam_s_mm - 1e-12 && b.max().y <= l.seam_s_mm + c + 1e-12);
            assert_relative_eq!(b.max().x, l.length_mm);
            assert!(b.min().x > 0.0);
            // Each pad and lead is one continuous polyline, and the lead meets its pad.
            for (lead, pad) in l.leads.iter().zip(&l.pads) {
                assert_eq!(lead.pieces.len(), 1, "{file}");
                assert_eq!(pad.pieces.len(), 1, "{file}");
                assert_eq!(lead.pieces[0].0.last(), pad.pieces[0].0.first());
            }
        }
    }

    #[test]
    fn stations_follow_the_documented_plan() {
        let d = design("joint-a.toml");
        let st = Stations::from_design(&d).unwrap();
        // d = 1, notched 9.5, overrun 0.5, lead 1, pad 2·4·0.1 = 0.8, proximal 0.5.
        assert_relative_eq!(
            st.parting_x_mm,
            1.0 + 9.5 + 0.5 + 1.0 + 0.8 + 0.5,
            epsilon = 1e-12
        );
        let l = Layout::from_design(&d).unwrap();
        assert_relative_eq!(l.length_mm, 13.3, epsilon = 1e-12);
        for n in &l.notches {
            let r = n.outline[0].bounding_rect().unwrap();
            assert_relative_eq!(r.min().x, 1.0 + n.level as f64, epsilon = 1e-12);
            assert_relative_eq!(r.width(), 0.5, epsilon = 1e-12);
        }
    }

    #[test]
    fn seam_avoids_everything_when_it_can() {
        // Joint A: room on the backbone beside the pads; nothing is split.
        let a = Layout::from_design(&design("joint-a.toml")).unwrap();
        assert!(a.notches.iter().all(|n| n.outline.len() == 1));
        assert!(a.seam_s_mm < 0.0 && a.seam_s_mm > -PI * 1.24);
        // Joint C (BSN): the backbone centre line between the two sensors, −π·r_o/2.
        let c = Layout::from_design(&design("joint-c.toml")).unwrap();
        assert_relative_eq!(c.seam_s_mm, -PI * 0.8 / 2.0, epsilon = 1e-9);
        assert!(c.notches.iter().all(|n| n.outline.len() == 1));
        // Joint B: the pads are wider than the backbone, so the seam runs through the notch
        // centres and every notch is split into two halves, each closed at the seam.
        let b = Layout::from_design(&design("joint-b.toml")).unwrap();
        assert_relative_eq!(b.seam_s_mm, -PI * 0.8, epsilon = 1e-9);
        for n in &b.notches {
            assert_eq!(n.outline.len(), 2);
            let areas: Vec<f64> = n.outline.iter().map(|p| p.unsigned_area()).collect();
            assert_relative_eq!(areas[0], areas[1], max_relative = 1e-9);
        }
        assert!(b.sensors.iter().chain(&b.pads).all(|t| t.pieces.len() == 1));
    }

    #[test]
    fn sensors_sit_where_the_frame_says() {
        let c = Layout::from_design(&design("joint-c.toml")).unwrap();
        let arms = |t: &Trace| {
            let p = &t.pieces[0].0;
            (p[0].y, p[p.len() - 1].y)
        };
        let wrap = |s: f64| c.seam_s_mm + (s - c.seam_s_mm).rem_euclid(c.circumference_mm);
        let (a, b) = arms(&c.sensors[0]);
        assert_relative_eq!(a, wrap(-2.13 / 2.0), epsilon = 1e-12);
        assert_relative_eq!(b, wrap(2.13 / 2.0), epsilon = 1e-12);
        let (a, b) = arms(&c.sensors[1]);
        assert_relative_eq!(a, wrap(PI * 0.8 - 2.13 / 2.0), epsilon = 1e-12);
        assert_relative_eq!(b, wrap(PI * 0.8 + 2.13 / 2.0), epsilon = 1e-12);
    }

    #[test]
    fn bad_fabrication_values_are_refused_with_value() {
        let mut d = design("joint-a.toml");
        d.file.fabrication.pad_pitch_mm = -0.1;
        let err = Layout::from_design(&d).unwrap_err().to_string();
        assert!(err.contains("pad_pitch_mm = -0.1"), "{err}");
        d.file.fabrication.pad_pitch_mm = 0.1;
        d.file.fabrication.pad_turns = 0;
        assert_eq!(
            Layout::from_design(&d).unwrap_err(),
            LayoutError::NoPadTurns
        );
        d.file.fabrication.pad_turns = 4;
        d.file.fabrication.trace_width_mm = f64::NAN;
        assert!(Layout::from_design(&d).is_err());
    }
}
