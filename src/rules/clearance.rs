//! Every arm, lead and pad keeps the clearance from every cut and from every other trace.
//!
//! What "clearance" means: the edge-to-edge gap between what the laser writes and what it
//! cuts, or between two written lines, in the unrolled drawing, round the cylinder (the seam is
//! not a gap).
//!
//! - trace to cut: `gap = d − w/2`, with `d` the Euclidean distance from the trace's centre line
//!   to the designed notch outline (0 if the line enters the notch), `w` the trace width. The cuts
//!   are the notches, the parting cut and the tube's distal end `x = 0`.
//! - trace to trace: `gap = d − w`, `d` the distance between centre lines. A pad counts as its
//!   whole square (the convex hull of its spiral), since it is a contact area.
//!
//! Which pairs: every trace of one sensor against every trace of another; and within one
//! sensor, the two sides of its circuit against each other: side A is the U-trace from its start
//! to its middle (arm A, half the bridge) with the lead and pad attached there, side B the rest.
//! A short between the sides bypasses the gauge. Near the middle of the bridge, where the two
//! sides meet, a length `clearance + w` of each side is left out, so a bridge that is long enough
//! never reports itself; a U whose arms are closer than the clearance still does.

use geo::{ConvexHull, Coord, LineString, Polygon};

use crate::layout::Layout;

use super::parts::{closest_on_cylinder, join_pieces, polyline_length, sub_polyline, Part};
use super::Violation;

/// Pieces that meet within this are one line (mm).
const JOIN_TOLERANCE_MM: f64 = 1e-6;
/// Gaps this far below the clearance are float noise, not violations (mm).
const NOISE_MM: f64 = 1e-9;

/// One sensor's circuit, as parts.
struct Circuit {
    whole: Vec<Part>,
    side_a: Vec<Part>,
    side_b: Vec<Part>,
}

/// Checks the layout's clearances, `clearance_mm` edge to edge.
pub(crate) fn check(layout: &Layout, clearance_mm: f64, out: &mut Vec<Violation>) {
    let c_mm = layout.circumference_mm;
    let w_mm = layout.trace_width_mm;
    let cuts = cuts(layout);
    let circuits = circuits(layout, clearance_mm + w_mm);
    let mut report = |a: &Part, b: &Part, allowance_mm: f64| {
        let reach_mm = clearance_mm + allowance_mm;
        if let Some(hit) = closest_on_cylinder(a, b, c_mm, reach_mm) {
            let gap_mm = hit.distance_mm - allowance_mm;
            if gap_mm < clearance_mm - NOISE_MM {
                out.push(Violation::Clearance {
                    what: hit.label,
                    x_mm: hit.at.x,
                    s_mm: layout.seam_s_mm + (hit.at.y - layout.seam_s_mm).rem_euclid(c_mm),
                    gap_mm,
                    crossing: hit.distance_mm <= 0.0,
                    other: hit.other,
                    required_mm: clearance_mm,
                });
            }
        }
    };
    for circuit in &circuits {
        for trace in &circuit.whole {
            for cut in &cuts {
                report(trace, cut, w_mm / 2.0);
            }
        }
    }
    for (i, one) in circuits.iter().enumerate() {
        for other in &circuits[i + 1..] {
            for a in &one.whole {
                for b in &other.whole {
                    report(a, b, w_mm);
                }
            }
        }
        for a in &one.side_a {
            for b in &one.side_b {
                report(a, b, w_mm);
            }
        }
    }
}

/// Notches, the parting cut and the distal end, as filled or line parts.
fn cuts(layout: &Layout) -> Vec<Part> {
    let bsn = layout.notches.iter().any(|n| n.side == 1);
    let mut cuts: Vec<Part> = layout
        .notches
        .iter()
        .map(|n| Part::from_polygons(&n.outline, &n.label(bsn)))
        .collect();
    cuts.push(Part::from_lines(&layout.parting, |_| {
        "the parting cut".into()
    }));
    let end = LineString::new(vec![
        Coord {
            x: 0.0,
            y: layout.seam_s_mm,
        },
        Coord {
            x: 0.0,
            y: layout.seam_s_mm + layout.circumference_mm,
        },
    ]);
    cuts.push(Part::from_lines([&end], |_| {
        "the distal end (x = 0)".into()
    }));
    cuts
}

/// Each sensor's traces as parts: the whole circuit and its two sides.
fn circuits(layout: &Layout, trim_mm: f64) -> Vec<Circuit> {
    let c_mm = layout.circumference_mm;
    (0..layout.sensor_count())
        .map(|sensor| {
            let name = |what: &str| format!("sensor {} {what}", sensor + 1);
            let u_lines: Vec<Vec<Coord>> = layout
                .sensors
                .iter()
                .filter(|t| t.sensor == sensor)
                .flat_map(|t| join_pieces(&t.pieces, c_mm, JOIN_TOLERANCE_MM))
                .collect();
            let arm_or_bridge = |l: &geo::Line<f64>| {
                let d = l.delta();
                name(if d.x.abs() >= d.y.abs() {
                    "arm"
                } else {
                    "bridge"
                })
            };
            let to_ls = |pts: &Vec<Coord>| LineString::new(pts.clone());
            let mut circuit = Circuit {
                whole: vec![Part::from_lines(
                    u_lines.iter().map(to_ls).collect::<Vec<_>>().iter(),
                    arm_or_bridge,
                )],
                side_a: Vec::new(),
                side_b: Vec::new(),
            };
            // The U's ends, for telling which side a lead or pad is on.
            let ends = u_lines
                .first()
                .and_then(|u| Some((*u.first()?, *u.last()?)));
            if let Some(u) = u_lines.first() {
                let half = polyline_length(u) / 2.0;
                let a = sub_polyline(u, 0.0, (half - trim_mm).max(0.0));
                let b = sub_polyline(u, half + trim_mm, 2.0 * half);
                for (pts, side) in [(a, &mut circuit.side_a), (b, &mut circuit.side_b)] {
                    if pts.len() >= 2 {
                        side.push(Part::from_lines([&LineString::new(pts)], arm_or_bridge));
                    }
                }
            }
            let leads: Vec<Vec<Coord>> =
                joined(layout.leads.iter().filter(|t| t.sensor == sensor), c_mm);
            let pads: Vec<Vec<Coord>> =
                joined(layout.pads.iter().filter(|t| t.sensor == sensor), c_mm);
            let mut lead_sides = Vec::new();
            for lead in &leads {
                let part = Part::from_lines([&LineString::new(lead.clone())], |_| name("lead"));
                let on_a = ends.map_or(true, |(a, b)| {
                    nearest(lead, a, c_mm) <= nearest(lead, b, c_mm)
                });
                lead_sides.push((lead, on_a));
                circuit.whole.push(part.clone());
                if on_a {
                    circuit.side_a.push(part)
                } else {
                    circuit.side_b.push(part)
                }
            }
            for pad in &pads {
                let mut part = Part::from_lines([&LineString::new(pad.clone())], |_| name("pad"));
                let hull: Polygon<f64> = LineString::new(pad.clone()).convex_hull();
                part.fills.push((hull, name("pad")));
                let on_a = lead_sides
                    .iter()
                    .min_by(|p, q| {
                        let dp = pad
                            .iter()
                            .map(|c| nearest(p.0, *c, c_mm))
                            .fold(f64::INFINITY, f64::min);
                        let dq = pad
                            .iter()
                            .map(|c| nearest(q.0, *c, c_mm))
                            .fold(f64::INFINITY, f64::min);
                        dp.total_cmp(&dq)
                    })
                    .map_or(true, |(_, on_a)| *on_a);
                circuit.whole.push(part.clone());
                if on_a {
                    circuit.side_a.push(part)
                } else {
                    circuit.side_b.push(part)
                }
            }
            circuit
        })
        .collect()
}

fn joined<'a>(
    traces: impl Iterator<Item = &'a crate::layout::Trace>,
    c_mm: f64,
) -> Vec<Vec<Coord>> {
    traces
        .flat_map(|t| join_pieces(&t.pieces, c_mm, JOIN_TOLERANCE_MM))
        .collect()
}

/// Distance on the cylinder from the nearer end of `line` to `p` (mm).
fn nearest(line: &[Coord], p: Coord, c_mm: f64) -> f64 {
    [line.first(), line.last()]
        .into_iter()
        .flatten()
        .map(|e| {
            let ds = (e.y - p.y + c_mm / 2.0).rem_euclid(c_mm) - c_mm / 2.0;
            (e.x - p.x).hypot(ds)
        })
        .fold(f64::INFINITY, f64::min)
}
