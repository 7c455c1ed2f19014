//! The router's property (issue 33 §2), checked on every routed robot before it is returned
//! and on any robot layout (for example one read back from a drawing):
//!
//! 1. no written line comes within `trace_width/2 + kerf/2` of any notch: the kerf's edge and
//!    the line's edge never touch, round the cylinder;
//! 2. every sensor's pieces chain, end to end across the seam, into one path from one pad
//!    through one lead, its U-trace and the other lead to its other pad.

use geo::{BoundingRect, Contains, Coord, Distance, Euclidean, Intersects, Line, Polygon, Rect};

use crate::layout::Layout;
use crate::toolpath::{chain_lines, TraceKind};

/// Pieces that meet within this are one line (mm).
const JOIN_TOLERANCE_MM: f64 = 1e-6;

/// What breaks the property, one message per finding.
pub fn check_property(layout: &Layout) -> Vec<String> {
    let mut out = clear_of_notches(layout);
    out.extend(chained(layout));
    out
}

/// Part 1: every written segment at least `w/2 + kerf/2` from every notch piece.
fn clear_of_notches(layout: &Layout) -> Vec<String> {
    let c = layout.circumference_mm;
    let reach = layout.trace_width_mm / 2.0 + layout.kerf_mm / 2.0;
    let pieces: Vec<(String, &Polygon<f64>, Rect<f64>)> = layout
        .notches
        .iter()
        .flat_map(|n| {
            let label = n.label(true);
            n.outline
                .iter()
                .filter_map(move |p| p.bounding_rect().map(|r| (label.clone(), p, r)))
        })
        .collect();
    let mut out = Vec::new();
    for (kind, traces) in [
        ("U-trace", &layout.sensors),
        ("lead", &layout.leads),
        ("pad", &layout.pads),
    ] {
        for t in traces {
            for piece in &t.pieces {
                for w in piece.0.windows(2) {
                    for (label, poly, rect) in &pieces {
                        for k in [-1.0, 0.0, 1.0] {
                            let shift = |p: Coord| Coord {
                                x: p.x,
                                y: p.y + k * c,
                            };
                            let seg = Line::new(shift(w[0]), shift(w[1]));
                            let (lo, hi) = (seg.start.y.min(seg.end.y), seg.start.y.max(seg.end.y));
                            let (xl, xh) = (seg.start.x.min(seg.end.x), seg.start.x.max(seg.end.x));
                            if hi < rect.min().y - reach
                                || lo > rect.max().y + reach
                                || xh < rect.min().x - reach
                                || xl > rect.max().x + reach
                            {
                                continue;
                            }
                            let d = distance(&seg, poly);
                            if d < reach - 1e-9 {
                                out.push(format!(
                                    "sensor {} {kind} at x = {:.4} mm, s = {:.4} mm comes {d:.4} mm from {label}, less than trace width/2 + kerf/2 = {reach:.4} mm",
                                    t.sensor + 1,
                                    w[0].x,
                                    w[0].y
                                ));
                            }
                        }
                    }
                }
            }
        }
    }
    out
}

/// Distance from a segment to a filled polygon (0 when it touches or enters it).
fn distance(seg: &Line<f64>, poly: &Polygon<f64>) -> f64 {
    if poly.contains(&seg.start) || poly.exterior().lines().any(|e| e.intersects(seg)) {
        return 0.0;
    }
    poly.exterior()
        .lines()
        .map(|e| Euclidean::distance(seg, &e))
        .fold(f64::INFINITY, f64::min)
}

/// Part 2: each sensor's pieces form one chain pad, lead, U-trace, lead, pad.
fn chained(layout: &Layout) -> Vec<String> {
    let mut out = Vec::new();
    for sensor in 0..layout.sensor_count() {
        let mut lines: Vec<(TraceKind, Vec<Coord>)> = Vec::new();
        for (kind, traces) in [
            (TraceKind::Sensor, &layout.sensors),
            (TraceKind::Lead, &layout.leads),
            (TraceKind::Pad, &layout.pads),
        ] {
            for t in traces.iter().filter(|t| t.sensor == sensor) {
                lines.extend(t.pieces.iter().map(|p| (kind, p.0.clone())));
            }
        }
        let chains = chain_lines(lines, layout.circumference_mm, JOIN_TOLERANCE_MM);
        let shape = |kinds: &[TraceKind]| {
            let mut collapsed: Vec<TraceKind> = Vec::new();
            for k in kinds {
                if collapsed.last() != Some(k) {
                    collapsed.push(*k);
                }
            }
            collapsed
        };
        let want = [
            TraceKind::Pad,
            TraceKind::Lead,
            TraceKind::Sensor,
            TraceKind::Lead,
            TraceKind::Pad,
        ];
        match chains.as_slice() {
            [(kinds, _)] if shape(kinds) == want => {}
            _ => out.push(format!(
                "sensor {}'s pieces form {} chain{} ({}), not one path pad, lead, U-trace, lead, pad",
                sensor + 1,
                chains.len(),
                if chains.len() == 1 { "" } else { "s" },
                chains
                    .iter()
                    .map(|(k, _)| format!("{:?}", shape(k)))
                    .collect::<Vec<_>>()
                    .join("; ")
            )),
        }
    }
    out
}
