//! Sensor, lead and pad pieces grouped into traces.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use geo::{Coord, LineString};

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
