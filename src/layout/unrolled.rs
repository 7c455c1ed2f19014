//! The layout before its seam is chosen: every feature with `s` unwrapped, as a joint's design
//! places it or as a robot's router placed it (`crate::robot`). [`Unrolled::wrap`] chooses the
//! seam and wraps every feature into the drawing's window, the one step both share.

use geo::{Coord, LineString};

use crate::design::Design;

use super::error::{positive, LayoutError};
use super::leads::lead;
use super::notches::notch_rects;
use super::pads::{pad_offset_mm, pad_terminal, square_spiral, PadSide};
use super::seam::{choose_seam_mm, wrap_polyline, wrap_rectangle, Arc};
use super::sensor::{sensor_centre_s_mm, u_trace};
use super::stations::Stations;
use super::{Layout, Notch, Trace};

pub use super::notches::NotchRect;

/// Gaps narrower than this are not gaps, and rectangle overhangs past the seam below it are not
/// split off (mm). Far below any feature size, far above rounding in `rem_euclid`.
const SEAM_TOLERANCE_MM: f64 = 1e-9;

/// A written line before wrapping: its sensor and its centre line in `(x, s)`, `s` unwrapped
/// (continuous along the line, any number of turns).
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// The sensor it belongs to (robot-wide for a robot).
    pub sensor: usize,
    /// Centre line, mm.
    pub points: Vec<Coord>,
}

/// Every feature of a layout with `s` unwrapped, in the layout's order.
#[derive(Debug, Clone, PartialEq)]
pub struct Unrolled {
    /// The name drawings and programs carry.
    pub name: String,
    /// Outer radius `r_o` (mm).
    pub outer_radius_mm: f64,
    /// Outer circumference `2π·r_o` (mm).
    pub circumference_mm: f64,
    /// Width of a laser-written line (mm).
    pub trace_width_mm: f64,
    /// Width the cutting beam removes (mm).
    pub kerf_mm: f64,
    /// Part length from the distal end to the parting cut (mm).
    pub length_mm: f64,
    /// Notches.
    pub notches: Vec<NotchRect>,
    /// Sensor U-traces: arm A's end, the bridge, arm B's end.
    pub sensors: Vec<Polyline>,
    /// Leads from the arms' ends to the pads' terminals.
    pub leads: Vec<Polyline>,
    /// Square-spiral pads, each from its terminal inwards.
    pub pads: Vec<Polyline>,
}

impl Unrolled {
    /// A design's features, placed along `x` by [`Stations`] and round the tube by the frame
    /// (see [`Layout::from_design`] for the order of the features).
    ///
    /// # Errors
    /// [`LayoutError`] when a fabrication length is not positive or the pads have no turns.
    pub fn from_design(design: &Design) -> Result<Self, LayoutError> {
        let fab = &design.file.fabrication;
        let trace_width_mm = positive("trace_width_mm", fab.trace_width_mm)?;
        let kerf_mm = positive("kerf_mm", fab.kerf_mm)?;
        let pad_gap_mm = positive("pad_gap_mm", fab.pad_gap_mm)?;
        let stations = Stations::from_design(design)?;
        let joint = &design.joint;
        let section = joint.section();
        let outer_radius_mm = section.outer_radius_mm();
        let sensor_count = joint.style().sensor_count();

        let mut sensors = Vec::new();
        let mut leads = Vec::new();
        let mut pads = Vec::new();
        let offset_mm = pad_offset_mm(
            section.sensor_arc_mm(),
            pad_gap_mm,
            stations.pad_size_mm,
            outer_radius_mm,
            sensor_count,
        );
        for sensor in 0..sensor_count as usize {
            let centre_mm = sensor_centre_s_mm(sensor, outer_radius_mm);
            let u = u_trace(centre_mm, section.sensor_arc_mm(), &stations);
            for (arm_end, side) in [(u[0], PadSide::Below), (u[3], PadSide::Above)] {
                let terminal = pad_terminal(stations.pad_x_mm, centre_mm, offset_mm, side);
                leads.push(Polyline {
                    sensor,
                    points: lead(arm_end, terminal),
                });
                pads.push(Polyline {
                    sensor,
                    points: square_spiral(terminal, fab.pad_pitch_mm, fab.pad_turns, side),
                });
            }
            sensors.push(Polyline { sensor, points: u });
        }
        Ok(Self {
            name: design.file.name.clone(),
            outer_radius_mm,
            circumference_mm: section.circumference_mm(),
            trace_width_mm,
            kerf_mm,
            length_mm: stations.parting_x_mm,
            notches: notch_rects(joint, &stations),
            sensors,
            leads,
            pads,
        })
    }

    /// Chooses the seam so that as little as possible is split (see `docs/frames.md`) and wraps
    /// every feature into the window `[seam, seam + C)`; the parting line runs all the way round
    /// at `x = length_mm`.
    pub fn wrap(self) -> Layout {
        let circumference_mm = self.circumference_mm;
        let half_mm = self.trace_width_mm / 2.0;
        let trace_arcs: Vec<Arc> = self
            .sensors
            .iter()
            .chain(&self.leads)
            .chain(&self.pads)
            .map(|line| {
                let (lo, hi) = line
                    .points
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                        (lo.min(p.y), hi.max(p.y))
                    });
                (lo - half_mm, hi + half_mm)
            })
            .collect();
        let notch_arcs: Vec<Arc> = self.notches.iter().map(|r| (r.s0_mm, r.s1_mm)).collect();
        let everything: Vec<Arc> = notch_arcs.iter().chain(&trace_arcs).copied().collect();
        let seam_s_mm = choose_seam_mm(
            &[everything, trace_arcs, notch_arcs],
            circumference_mm,
            SEAM_TOLERANCE_MM,
        );

        let wrap = |list: Vec<Polyline>| -> Vec<Trace> {
            list.into_iter()
                .map(|line| Trace {
                    sensor: line.sensor,
                    pieces: wrap_polyline(&line.points, seam_s_mm, circumference_mm),
                })
                .collect()
        };
        let notches = self
            .notches
            .iter()
            .map(|r| Notch {
                joint: r.joint,
                level: r.level,
                side: r.side,
                outline: wrap_rectangle(
                    (r.x0_mm, r.x1_mm),
                    (r.s0_mm, r.s1_mm),
                    seam_s_mm,
                    circumference_mm,
                    SEAM_TOLERANCE_MM,
                ),
            })
            .collect();
        let length_mm = self.length_mm;
        Layout {
            name: self.name,
            outer_radius_mm: self.outer_radius_mm,
            circumference_mm,
            seam_s_mm,
            trace_width_mm: self.trace_width_mm,
            kerf_mm: self.kerf_mm,
            length_mm,
            notches,
            sensors: wrap(self.sensors),
            leads: wrap(self.leads),
            pads: wrap(self.pads),
            parting: vec![LineString::new(vec![
                Coord {
                    x: length_mm,
                    y: seam_s_mm,
                },
                Coord {
                    x: length_mm,
                    y: seam_s_mm + circumference_mm,
                },
            ])],
        }
    }
}
