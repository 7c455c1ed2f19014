//! The dialect-free plan: operations, paths and passes in the program frame.

use std::fmt;

use crate::process::ProcessSet;

/// A position in the program frame: `x_mm` along the tube (the drawing's `x`) and the rotary
/// angle `a_rad = s/r_o`, continuous (not wrapped), so that `a_rad·r_o` is the drawing's `s`
/// plus a whole number of circumferences.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Along the tube (mm), 0 at the distal (free) end.
    pub x_mm: f64,
    /// Rotary angle (rad), `s/r_o`.
    pub a_rad: f64,
}

impl Point {
    /// A point from `x` and `a`.
    pub fn new(x_mm: f64, a_rad: f64) -> Self {
        Self { x_mm, a_rad }
    }

    /// Distance travelled over the tube's surface on a straight program move to `other`:
    /// `d = sqrt(Δx² + (r_o·Δa)²)`.
    pub fn surface_distance_mm(&self, other: &Point, outer_radius_mm: f64) -> f64 {
        let dx = other.x_mm - self.x_mm;
        let ds = outer_radius_mm * (other.a_rad - self.a_rad);
        dx.hypot(ds)
    }
}

/// The three operations, in the order they run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum OperationKind {
    /// Writing the sensor traces, leads and pads (Table II (a)).
    Sensor,
    /// Cutting the notches (Table II (b)).
    Notches,
    /// Parting the joint off the stock (Table II (b)).
    Parting,
}

impl OperationKind {
    /// Lower-case name used in program comments and sheets.
    pub fn name(self) -> &'static str {
        match self {
            Self::Sensor => "sensor",
            Self::Notches => "notches",
            Self::Parting => "parting",
        }
    }
}

/// What a written line is part of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TraceKind {
    /// The sensor's U-trace.
    Sensor,
    /// A lead from a sensor arm to its pad.
    Lead,
    /// A square-spiral contact pad.
    Pad,
}

/// What a path makes. Displayed the way people count: notches from 1 at the distal end,
/// sensors 1 and 2.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Feature {
    /// One continuous written line of sensor `sensor`: the layout's pieces that meet end to end,
    /// joined so the beam writes them without a break.
    Written {
        /// 0 for the `+y_s` sensor, 1 for BSN's `−y_s` sensor.
        sensor: usize,
        /// The kinds of the pieces joined, in order.
        parts: Vec<TraceKind>,
    },
    /// A notch, cut along its outline offset inward by half the kerf.
    Notch {
        /// The robot joint it belongs to ([`crate::layout::Notch::joint`]); `None` for a joint.
        joint: Option<usize>,
        /// Position along the tube, 0 at the distal end.
        level: usize,
        /// 0 for the notch centred at `s = π·r_o`, 1 for BSN's notch centred at `s = 0`.
        side: usize,
    },
    /// The parting cut, all the way round.
    Parting,
}

impl fmt::Display for Feature {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Written { sensor, parts } => {
                let names: Vec<&str> = parts
                    .iter()
                    .map(|p| match p {
                        TraceKind::Sensor => "trace",
                        TraceKind::Lead => "lead",
                        TraceKind::Pad => "pad",
                    })
                    .collect();
                write!(f, "sensor {} line ({})", sensor + 1, names.join("+"))
            }
            Self::Notch {
                joint: None,
                level,
                side,
            } => write!(f, "notch {} (side {side})", level + 1),
            Self::Notch {
                joint: Some(j),
                level,
                side,
            } => write!(f, "joint {} notch {} (side {side})", j + 1, level + 1),
            Self::Parting => write!(f, "parting cut"),
        }
    }
}

/// One path: the points the beam follows on each pass, with the beam on throughout.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    /// What it makes.
    pub feature: Feature,
    /// The points of an even pass (0, 2, …), lead-in start first when [`Path::lead_in`].
    pub forward: Vec<Point>,
    /// The points of an odd pass, for paths that do not end where they start (they run back
    /// instead of rapiding to the start); `None` when every pass runs [`Path::forward`].
    pub reverse: Option<Vec<Point>>,
    /// The first move of each pass is a lead-in that starts in the scrap.
    pub lead_in: bool,
}

impl Path {
    /// The points of pass `k` (0-based).
    pub fn pass(&self, k: u32) -> &[Point] {
        match (&self.reverse, k % 2) {
            (Some(r), 1) => r,
            _ => &self.forward,
        }
    }

    /// Where the beam is after `passes` passes.
    pub fn end_after(&self, passes: u32) -> Point {
        let last = self.pass(passes.saturating_sub(1));
        last.last().copied().unwrap_or(Point::new(0.0, 0.0))
    }

    /// Where pass 0 starts.
    pub fn start(&self) -> Point {
        self.forward
            .first()
            .copied()
            .unwrap_or(Point::new(0.0, 0.0))
    }

    /// The path shifted by `turns` whole turns of A.
    pub fn shifted(&self, turns: f64) -> Self {
        let shift = |pts: &[Point]| -> Vec<Point> {
            pts.iter()
                .map(|p| Point::new(p.x_mm, p.a_rad + turns * std::f64::consts::TAU))
                .collect()
        };
        Self {
            feature: self.feature.clone(),
            forward: shift(&self.forward),
            reverse: self.reverse.as_deref().map(shift),
            lead_in: self.lead_in,
        }
    }
}

/// One operation: a parameter set and its paths in run order.
#[derive(Debug, Clone, PartialEq)]
pub struct Operation {
    /// Which operation.
    pub kind: OperationKind,
    /// Its parameter set.
    pub process: ProcessSet,
    /// Paths in the order they run; each gets `process.repetitions` passes.
    pub paths: Vec<Path>,
}

/// Rapid travel over the tube's surface, for the ordering report.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Travel {
    /// With the paths in the layout's order, each started at its first point (mm).
    pub layout_order_mm: f64,
    /// With the paths ordered by nearest neighbour (mm).
    pub planned_mm: f64,
}

/// The whole job, format-free: what every post-processor turns into a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The design's name.
    pub design_name: String,
    /// The design's checksum ([`crate::design::Design::checksum`]).
    pub design_checksum: String,
    /// Lines the program header prints after the checksum (a robot's joints); none for a joint.
    pub notes: Vec<String>,
    /// Outer radius `r_o` (mm): `A = s/r_o`.
    pub outer_radius_mm: f64,
    /// Inner radius `r_i` (mm).
    pub inner_radius_mm: f64,
    /// Kerf (mm).
    pub kerf_mm: f64,
    /// Width of a written line (mm).
    pub trace_width_mm: f64,
    /// Part length (mm): the finished joint's proximal face, where the parting cut ends it
    /// (distal margin, notched length, leads, pads and proximal margin).
    pub joint_length_mm: f64,
    /// Bending length `L` (mm), the design's `joint_length_mm` (the paper's Table I): the
    /// length that bends, shorter than the part.
    pub bending_length_mm: f64,
    /// Z of the focus on the tube's surface.
    pub surface_z_mm: f64,
    /// Where the program assumes the stage starts: `X = 0`, `A = 0`.
    pub home: Point,
    /// Sensor, notches, parting, in that order.
    pub operations: Vec<Operation>,
    /// Rapid travel per operation, in operation order.
    pub travel: Vec<Travel>,
    /// The drawing the layout was read from, if it was (`--from-dxf`).
    pub provenance: Option<crate::drawing::Provenance>,
}

/// Whether a move has the beam on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MoveKind {
    /// Beam off, at the stage's rapid speed.
    Rapid,
    /// Beam on, at the operation's surface speed.
    Feed,
}

/// One move of the job with every loop unrolled: what the stage does, in order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    /// Index into [`Plan::operations`].
    pub operation: usize,
    /// Index into that operation's paths.
    pub path: usize,
    /// Pass number, from 0.
    pub pass: u32,
    /// Beam on or off.
    pub kind: MoveKind,
    /// Start.
    pub from: Point,
    /// End.
    pub to: Point,
    /// Focus Z during the move.
    pub z_mm: f64,
}

impl Plan {
    /// The focus Z of pass `k` of operation `op`: the surface, lowered by the set's Z step per pass.
    pub fn pass_z_mm(&self, op: &Operation, k: u32) -> f64 {
        self.surface_z_mm - f64::from(k) * op.process.z_step_or_zero_mm()
    }

    /// Every move of the job in order, loops unrolled; rapids go from where the previous pass
    /// ended to where the next begins.
    pub fn moves(&self) -> Vec<Move> {
        let mut out = Vec::new();
        let mut at = self.home;
        for (oi, op) in self.operations.iter().enumerate() {
            for (pi, path) in op.paths.iter().enumerate() {
                for k in 0..op.process.repetitions {
                    let pts = path.pass(k);
                    let z_mm = self.pass_z_mm(op, k);
                    let Some(&first) = pts.first() else { continue };
                    let mv = |kind, from, to| Move {
                        operation: oi,
                        path: pi,
                        pass: k,
                        kind,
                        from,
                        to,
                        z_mm,
                    };
                    if first != at {
                        out.push(mv(MoveKind::Rapid, at, first));
                    }
                    for w in pts.windows(2) {
                        out.push(mv(MoveKind::Feed, w[0], w[1]));
                    }
                    at = *pts.last().unwrap_or(&first);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alternate_passes_run_back() {
        let p = Path {
            feature: Feature::Parting,
            forward: vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)],
            reverse: Some(vec![Point::new(1.0, 0.0), Point::new(0.0, 0.0)]),
            lead_in: false,
        };
        assert_eq!(p.end_after(1), Point::new(1.0, 0.0));
        assert_eq!(p.end_after(2), Point::new(0.0, 0.0));
        assert_eq!(p.end_after(3), Point::new(1.0, 0.0));
        let s = p.shifted(1.0);
        assert!((s.start().a_rad - std::f64::consts::TAU).abs() < 1e-15);
    }

    #[test]
    fn surface_distance_counts_rotation_at_the_radius() {
        let d = Point::new(0.0, 0.0).surface_distance_mm(&Point::new(3.0, 4.0 / 0.8), 0.8);
        assert!((d - 5.0).abs() < 1e-12);
    }
}
