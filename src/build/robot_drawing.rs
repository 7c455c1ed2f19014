//! A robot's drawing read back (`dlw import-dxf ROBOT.dxf --design ROBOT`, `dlw program
//! --from-dxf ROBOT.dxf --design ROBOT`): the layout the DXF reader made, told which joint each
//! notch belongs to and which sensor each trace, then checked against the robot the way a
//! joint's drawing is checked against its design.
//!
//! - Each notch belongs to the joint whose notched section holds its centre; its level ranks
//!   its distal edge among that joint's (edges within 1 µm share one), its side is the nearer
//!   of the joint's turned `s = π·r_o` (0) and `s = 0` (1). So an edited drawing still
//!   describes itself.
//! - Traces keep the sensor their XDATA gives (the robot-wide number); when the drawing has
//!   lost its XDATA, each trace takes the sensor of the robot's own trace of its kind whose ends
//!   are nearest its ends.
//! - The drawing must be of this robot (name, radius, sensor count, a notch in every joint),
//!   and keeps the layout rules at the robot's clearance and the router's property.

use geo::{Area, BoundingRect, Coord};

use crate::drawing::{ImportedDxf, Provenance};
use crate::layout::{Layout, Trace};
use crate::rules;

use crate::robot::check_property;
use crate::robot::CheckedRobot;
use crate::robot::{RobotError, RobotViolation};

/// Notch edges closer than this share a level (mm), as the DXF reader's.
const SAME_LEVEL_MM: f64 = 1e-3;

/// A piece of a drawing without XDATA farther than this from every trace of the robot's own
/// (mm) is taken as drawn by hand: it keeps the reader's sensor and stays a trace of its own.
/// A millimetre is several trace pitches: far more than an edit that moves a trace a little.
const SAME_TRACE_MM: f64 = 1.0;

/// A robot drawing that passed every rule of its robot.
#[derive(Debug, Clone)]
pub struct CheckedRobotDrawing {
    /// The drawn layout, with the robot's kerf and trace width, notches and traces labelled.
    pub layout: Layout,
    /// Where it came from, how it differs from the robot's own layout, each joint as drawn.
    pub provenance: Provenance,
    /// Warnings for the joints as drawn.
    pub warnings: Vec<String>,
}

/// Labels `imported`'s layout by `robot`'s joints and sensors and checks it.
///
/// # Errors
/// [`RobotError::Rules`] listing what does not match the robot and every rule broken.
pub fn check_robot_drawing(
    robot: &CheckedRobot,
    imported: &ImportedDxf,
    file_name: &str,
    bytes: &[u8],
) -> Result<CheckedRobotDrawing, RobotError> {
    let refuse = |v: Vec<String>| RobotError::Rules {
        robot: robot.robot.name.clone(),
        violations: v.into_iter().map(RobotViolation::Drawing).collect(),
    };
    let mut layout = imported.layout.clone();
    layout.kerf_mm = robot.layout.kerf_mm;
    layout.trace_width_mm = robot.layout.trace_width_mm;
    if imported.untagged > 0 {
        label_traces(&robot.layout, &mut layout);
    }
    let mut errors = mismatches(robot, &layout);
    if !errors.is_empty() {
        return Err(refuse(errors));
    }
    errors.extend(label_notches(robot, &mut layout));
    if !errors.is_empty() {
        return Err(refuse(errors));
    }
    errors.extend(
        rules::check_layout(&layout, robot.robot.clearance_mm())
            .iter()
            .map(|v| format!("breaks a rule: {v}")),
    );
    errors.extend(
        check_property(&layout)
            .into_iter()
            .map(|v| format!("breaks the router's property: {v}")),
    );
    let mut derived = Vec::new();
    let mut warnings = Vec::new();
    for (j, joint) in robot.robot.joints.iter().enumerate() {
        let mut sub = layout.clone();
        sub.notches.retain(|n| n.joint.unwrap_or(0) == j);
        match rules::derive(joint.design(), &sub) {
            Ok(d) => {
                for line in d.summary(joint.design()) {
                    derived.push(format!("joint {} {line}", j + 1));
                }
                let mut w = Vec::new();
                rules::strain_warnings(&d.design, &mut w);
                warnings.extend(w.iter().map(|w| format!("joint {} as drawn: {w}", j + 1)));
            }
            Err(v) => errors.push(format!("joint {}: {v}", j + 1)),
        }
    }
    if !errors.is_empty() {
        return Err(refuse(errors));
    }
    let mut labelled = imported.clone();
    labelled.layout = layout.clone();
    let provenance =
        Provenance::new(file_name, bytes, &labelled, &robot.layout).with_derived(derived);
    Ok(CheckedRobotDrawing {
        layout,
        provenance,
        warnings,
    })
}

/// The drawing must be of this robot.
fn mismatches(robot: &CheckedRobot, layout: &Layout) -> Vec<String> {
    let mut out = Vec::new();
    if layout.name != robot.robot.name {
        out.push(format!(
            "is of {:?}, not of the robot {:?}",
            layout.name, robot.robot.name
        ));
    }
    if (layout.outer_radius_mm - robot.layout.outer_radius_mm).abs() > 1e-9 {
        out.push(format!(
            "has outer radius {} mm, the robot's tube {} mm",
            layout.outer_radius_mm, robot.layout.outer_radius_mm
        ));
    }
    let (drawn, own) = (layout.sensor_count(), robot.layout.sensor_count());
    if drawn != own {
        out.push(format!("has {drawn} sensors, the robot {own}"));
    }
    out
}

/// Gives each notch its joint, level and side.
fn label_notches(robot: &CheckedRobot, layout: &mut Layout) -> Vec<String> {
    let r = &robot.robot;
    let multi = r.joints.len() > 1;
    let r_o = layout.outer_radius_mm;
    let mut errors = Vec::new();
    let mut edges: Vec<Vec<f64>> = vec![Vec::new(); r.joints.len()];
    let mut placed: Vec<Option<(usize, f64)>> = Vec::new();
    for n in &layout.notches {
        let boxes: Vec<_> = n.outline.iter().filter_map(|p| p.bounding_rect()).collect();
        let x0 = boxes
            .iter()
            .map(|b| b.min().x)
            .fold(f64::INFINITY, f64::min);
        let x1 = boxes
            .iter()
            .map(|b| b.max().x)
            .fold(f64::NEG_INFINITY, f64::max);
        let centre = (x0 + x1) / 2.0;
        let joint = r
            .joints
            .iter()
            .position(|j| centre >= j.x_start_mm() - 1e-9 && centre <= j.x_end_mm() + 1e-9);
        match joint {
            Some(j) => {
                edges[j].push(x0);
                placed.push(Some((j, x0)));
            }
            None => {
                errors.push(format!(
                    "has a notch at x = {x0:.4} … {x1:.4} mm outside every joint's notched section"
                ));
                placed.push(None);
            }
        }
    }
    for e in &mut edges {
        e.sort_by(f64::total_cmp);
        e.dedup_by(|a, b| (*a - *b).abs() <= SAME_LEVEL_MM);
    }
    for (n, place) in layout.notches.iter_mut().zip(placed) {
        let Some((j, x0)) = place else { continue };
        let joint = &r.joints[j];
        let level = edges[j].partition_point(|e| *e < x0 - SAME_LEVEL_MM);
        // Area-weighted: the notch's centre nearer the joint's s = 0 (side 1) or s = π·r_o.
        let rot = joint.rotation_rad();
        let cos: f64 = n
            .outline
            .iter()
            .filter_map(|p| p.bounding_rect().map(|b| (b, p.unsigned_area())))
            .map(|(b, a)| a * (b.center().y / r_o - rot).cos())
            .sum();
        let bsn = joint.design().joint.style().notches_per_level() == 2;
        n.joint = multi.then_some(j);
        n.level = level;
        n.side = usize::from(bsn && cos > 0.0);
    }
    for (j, joint) in r.joints.iter().enumerate() {
        if edges[j].is_empty() {
            errors.push(format!(
                "has no notch in joint {}'s notched section (x = {:.4} … {:.4} mm): it would not bend",
                j + 1,
                joint.x_start_mm(),
                joint.x_end_mm()
            ));
        }
    }
    errors
}

/// Gives the traces of a drawing that lost its XDATA back their robot identity: each piece
/// belongs to the robot's own trace of its kind that it lies on (the one from which its
/// farthest point is nearest, round the cylinder), and takes its sensor; the pieces of one own
/// trace (a drawing holds a lead split at the seam as pieces of their own) become one trace
/// again, in order along it, in the robot's order of traces. Pieces that lie on none stay
/// traces of their own, after the others.
fn label_traces(own: &Layout, layout: &mut Layout) {
    let c = own.circumference_mm;
    // Distance from p to segment a-b round the cylinder, and where along the segment.
    let to_segment = |p: Coord, a: Coord, b: Coord| {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((p.x - a.x) * dx + (p.y - a.y) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (qx, qy) = (a.x + t * dx, a.y + t * dy);
        let ds = (p.y - qy + c / 2.0).rem_euclid(c) - c / 2.0;
        ((p.x - qx).hypot(ds), t * len2.sqrt())
    };
    // Distance from p to a trace, and how far along it (mm) the nearest point is.
    let to_trace = |p: Coord, t: &Trace| {
        let mut along = 0.0;
        let mut best = (f64::INFINITY, 0.0);
        for w in t.pieces.iter().flat_map(|l| l.0.windows(2)) {
            let (d, at) = to_segment(p, w[0], w[1]);
            if d < best.0 {
                best = (d, along + at);
            }
            along += (w[1].x - w[0].x).hypot(w[1].y - w[0].y);
        }
        best
    };
    for (mine, theirs) in [
        (&own.sensors, &mut layout.sensors),
        (&own.leads, &mut layout.leads),
        (&own.pads, &mut layout.pads),
    ] {
        let mut groups: Vec<Vec<(f64, geo::LineString<f64>)>> = vec![Vec::new(); mine.len()];
        let mut strays = Vec::new();
        for t in theirs.drain(..) {
            for piece in t.pieces {
                let n = piece.0.len().max(1) as f64;
                let best = mine
                    .iter()
                    .enumerate()
                    .map(|(i, m)| {
                        let far = piece
                            .0
                            .iter()
                            .map(|p| to_trace(*p, m).0)
                            .fold(0.0, f64::max);
                        let along = piece.0.iter().map(|p| to_trace(*p, m).1).sum::<f64>() / n;
                        (i, far, along)
                    })
                    .min_by(|x, y| x.1.total_cmp(&y.1));
                match best {
                    Some((i, far, along)) if far < SAME_TRACE_MM => groups[i].push((along, piece)),
                    _ => strays.push(Trace {
                        sensor: t.sensor,
                        pieces: vec![piece],
                    }),
                }
            }
        }
        for (i, mut pieces) in groups.into_iter().enumerate() {
            if pieces.is_empty() {
                continue;
            }
            pieces.sort_by(|a, b| a.0.total_cmp(&b.0));
            theirs.push(Trace {
                sensor: mine[i].sensor,
                pieces: pieces.into_iter().map(|(_, p)| p).collect(),
            });
        }
        theirs.extend(strays);
    }
}
