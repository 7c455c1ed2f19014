//! Sensor, lead and pad pieces grouped into traces.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use geo::{Coord, LineString};

use super::super::dxf_convention::{TAG_LEAD, TAG_PAD, TAG_SENSOR};
use super::loops;
use super::xdata::LayoutNumbers;
use crate::layout::Trace;

/// A tagged trace: its sensor and its numbered pieces.
type TaggedTrace = (usize, Vec<(i16, LineString<f64>)>);

/// A trace entity as read: its tag (list index, sensor, piece) if it had one.
pub(super) struct TracePiece {
    /// `sensor`, `lead` or `pad`.
    pub kind: &'static str,
    /// List index, sensor, piece.
    pub tag: Option<(i16, i16, i16)>,
    /// The centre line (mm).
    pub line: LineString<f64>,
}

/// A polyline that turns through at least a full turn is a spiral.
pub(super) fn is_spiral(points: &[Coord]) -> bool {
    let mut turning = 0.0;
    for w in points.windows(3) {
        let (a, b) = (w[1] - w[0], w[2] - w[1]);
        turning += (a.x * b.y - a.y * b.x).atan2(a.x * b.x + a.y * b.y);
    }
    turning.abs() >= 2.0 * PI - 1e-6
}

/// The traces of one kind: tagged ones by list index (pieces by piece number), then untagged
/// ones, each its own trace.
pub(super) fn group_traces(
    pieces: &[TracePiece],
    kind: &str,
    bsn: bool,
    outer_radius_mm: f64,
) -> Vec<Trace> {
    let mut tagged: BTreeMap<i16, TaggedTrace> = BTreeMap::new();
    let mut untagged = Vec::new();
    for p in pieces.iter().filter(|p| p.kind == kind) {
        match p.tag {
            Some((index, sensor, piece)) => tagged
                .entry(index)
                .or_insert_with(|| (sensor.max(0) as usize, Vec::new()))
                .1
                .push((piece, p.line.clone())),
            None => {
                let mean_s = p.line.0.iter().map(|c| c.y).sum::<f64>() / p.line.0.len() as f64;
                let phi = mean_s / outer_radius_mm;
                let sensor = usize::from(bsn && phi.cos() < 0.0);
                untagged.push(Trace {
                    sensor,
                    pieces: vec![p.line.clone()],
                });
            }
        }
    }
    tagged
        .into_values()
        .map(|(sensor, mut list)| {
            list.sort_by_key(|(piece, _)| *piece);
            Trace {
                sensor,
                pieces: list.into_iter().map(|(_, l)| l).collect(),
            }
        })
        .chain(untagged)
        .collect()
}

/// Chains untagged SENSOR and LEADS_PADS LINEs end to end and adds them as traces: a chain on
/// SENSOR is a U-trace; one on LEADS_PADS that starts at a sensor end (or the seam) and ends in
/// a spiral is split into a lead and a pad, else it is a pad if it is a spiral and a lead if not.
pub(super) fn chain_trace_lines(
    traces: &mut Vec<TracePiece>,
    sensor_lines: Vec<Vec<Coord>>,
    lead_pad_lines: Vec<Vec<Coord>>,
    numbers: &LayoutNumbers,
    tol: f64,
) {
    for chain in loops::chain_open(sensor_lines, tol) {
        traces.push(TracePiece {
            kind: TAG_SENSOR,
            tag: None,
            line: LineString::new(chain),
        });
    }
    let sensor_ends: Vec<Coord> = traces
        .iter()
        .filter(|t| t.kind == TAG_SENSOR)
        .flat_map(|t| [t.line.0[0], t.line.0[t.line.0.len() - 1]])
        .collect();
    let window = [
        numbers.seam_s_mm,
        numbers.seam_s_mm + numbers.circumference_mm,
    ];
    let starts_a_lead = |p: Coord| {
        sensor_ends
            .iter()
            .any(|e| (e.x - p.x).hypot(e.y - p.y) <= tol)
            || window.iter().any(|w| (p.y - w).abs() <= tol)
    };
    for chain in loops::chain_open(lead_pad_lines, tol) {
        for (kind, points) in split_lead_pad(chain, &starts_a_lead) {
            traces.push(TracePiece {
                kind,
                tag: None,
                line: LineString::new(points),
            });
        }
    }
}

/// A LEADS_PADS chain as (kind, points): a lead and a pad when one end starts a lead
/// (`starts_a_lead`: a sensor end, or the seam) and the rest ends in a spiral. The pad is the
/// spiral: from its inner end back to the first vertex that turns the other way (the lead meets
/// the pad's outer corner with a turn against the spiral's sense).
fn split_lead_pad(
    chain: Vec<Coord>,
    starts_a_lead: &dyn Fn(Coord) -> bool,
) -> Vec<(&'static str, Vec<Coord>)> {
    if !is_spiral(&chain) {
        return vec![(TAG_LEAD, chain)];
    }
    let reversed: Vec<Coord> = chain.iter().rev().copied().collect();
    for way in [&chain, &reversed] {
        if !starts_a_lead(way[0]) {
            continue;
        }
        let j = pad_start(way);
        if j > 0 && is_spiral(&way[j..]) {
            return vec![(TAG_LEAD, way[..=j].to_vec()), (TAG_PAD, way[j..].to_vec())];
        }
    }
    vec![(TAG_PAD, chain)]
}

/// Index of the vertex where the spiral at the end of `points` starts: the vertex before the
/// run of turns, back from the end, in the sense of the last turn.
fn pad_start(points: &[Coord]) -> usize {
    let turn = |i: usize| {
        let (a, b) = (points[i] - points[i - 1], points[i + 1] - points[i]);
        let cross = a.x * b.y - a.y * b.x;
        if cross.abs() <= 1e-12 * a.x.hypot(a.y) * b.x.hypot(b.y) {
            0.0
        } else {
            cross.signum()
        }
    };
    let n = points.len();
    if n < 3 {
        return 0;
    }
    let sense = turn(n - 2);
    let mut b = n - 2;
    while b > 1 && turn(b - 1) == sense {
        b -= 1;
    }
    b - 1
}
