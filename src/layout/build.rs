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

/// Gaps narrower than this are not gaps, and rectangle overhangs past the seam below it are not
/// split off (mm). Far below any feature size, far above rounding in `rem_euclid`.
const SEAM_TOLERANCE_MM: f64 = 1e-9;

impl Layout {
    /// Lays out a design: notches, sensor U-traces, leads, square-spiral pads and the parting
    /// line, placed along `x` by [`Stations`] and wrapped round the seam chosen so that as little
    /// as possible is split (see `docs/frames.md`).
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
        let fab = &design.file.fabrication;
        let trace_width_mm = positive("trace_width_mm", fab.trace_width_mm)?;
        let kerf_mm = positive("kerf_mm", fab.kerf_mm)?;
        let pad_gap_mm = positive("pad_gap_mm", fab.pad_gap_mm)?;
        let stations = Stations::from_design(design)?;
        let joint = &design.joint;
        let section = joint.section();
        let outer_radius_mm = section.outer_radius_mm();
        let circumference_mm = section.circumference_mm();
        let sensor_count = joint.style().sensor_count();

        let rects = notch_rects(joint, &stations);
        let mut sensors: Vec<(usize, Vec<Coord>)> = Vec::new();
        let mut leads: Vec<(usize, Vec<Coord>)> = Vec::new();
        let mut pads: Vec<(usize, Vec<Coord>)> = Vec::new();
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
                leads.push((sensor, lead(arm_end, terminal)));
                pads.push((
                    sensor,
                    square_spiral(terminal, fab.pad_pitch_mm, fab.pad_turns, side),
                ));
            }
            sensors.push((sensor, u));
        }

        let half_mm = trace_width_mm / 2.0;
        let trace_arcs: Vec<Arc> = sensors
            .iter()
            .chain(&leads)
            .chain(&pads)
            .map(|(_, pts)| {
                let (lo, hi) = pts
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                        (lo.min(p.y), hi.max(p.y))
                    });
                (lo - half_mm, hi + half_mm)
            })
            .collect();
        let notch_arcs: Vec<Arc> = rects.iter().map(|r| (r.s0_mm, r.s1_mm)).collect();
        let everything: Vec<Arc> = notch_arcs.iter().chain(&trace_arcs).copied().collect();
        let seam_s_mm = choose_seam_mm(
            &[everything, trace_arcs, notch_arcs],
            circumference_mm,
            SEAM_TOLERANCE_MM,
        );

        let wrap = |list: Vec<(usize, Vec<Coord>)>| -> Vec<Trace> {
            list.into_iter()
                .map(|(sensor, pts)| Trace {
                    sensor,
                    pieces: wrap_polyline(&pts, seam_s_mm, circumference_mm),
                })
                .collect()
        };
        let notches = rects
            .iter()
            .map(|r| Notch {
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
        let length_mm = stations.parting_x_mm;
        Ok(Self {
            name: design.file.name.clone(),
            outer_radius_mm,
            circumference_mm,
            seam_s_mm,
            trace_width_mm,
            kerf_mm,
            length_mm,
            notches,
            sensors: wrap(sensors),
            leads: wrap(leads),
            pads: wrap(pads),
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
        })
    }
}
