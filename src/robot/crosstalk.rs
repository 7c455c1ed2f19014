//! Crosstalk: how much of each joint's bending a sensor reads through its leads (issue 33 §3).
//!
//! For sensor `i` and joint `j`, take the axial pieces of `i`'s circuit (its U-trace and its
//! two leads) that lie over `j`'s notched section `[x_start_j, x_end_j]`, and sum
//!
//! ```text
//! S_i(j) = Σ ℓ·(y − ȳ_j)/L_j,   y = r_o·cos(s/r_o − rotation_j),   L_j = x_end_j − x_start_j
//! ```
//!
//! with `ℓ` the piece's length over the section and `y` its height in `j`'s bending plane
//! (pieces round the tube carry no axial strain and count for nothing). Then
//! `crosstalk_i[j] = S_i(j) / S_i^U(J(i))`, the same sum for `i`'s own U-trace over its own
//! joint `J(i)`, so `crosstalk_i[J(i)] = 1` and `crosstalk_i[j]` is the share of `j`'s bending
//! that `i` reads, relative to its own joint's. A surface strip at height `y` over a section
//! bent by `θ` stretches by `θ·(y − ȳ)` over the section (the paper's Eq. 3 with `L` the
//! section's length): this is the mixing matrix `C` of `ROBOT.md`'s sensing model.

use geo::Coord;
use serde::Serialize;

use crate::layout::{Layout, Unrolled};

use super::assemble::Robot;
use super::sensors::{Arm, LeadName, RobotSensor};

/// A segment that moves less than this round the tube is axial (mm).
const AXIAL_TOL_MM: f64 = 1e-9;

/// Crosstalk above this share of a joint's bending is warned about (5 %, issue 33).
pub const CROSSTALK_WARNING: f64 = 0.05;

/// One sensor's circuit and what it reads.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SensorReport {
    /// Which sensor.
    #[serde(skip)]
    pub sensor: RobotSensor,
    /// Length of its U-trace's centre line (mm).
    pub u_trace_length_mm: f64,
    /// Length of its two leads' centre lines (mm).
    pub leads_length_mm: f64,
    /// Its circuit from pad to pad without the pads, U-trace and leads (mm).
    pub trace_length_mm: f64,
    /// `crosstalk[j]` for every joint `j`, distal first (`crosstalk[own] = 1`).
    pub crosstalk: Vec<f64>,
    /// The share of `crosstalk[j]` each lead carries, `[lead A, lead B]` per joint (the
    /// sensor's first lead in the layout, and the others).
    #[serde(skip)]
    pub by_lead: Vec<[f64; 2]>,
}

/// A sensor's pieces: its U-trace, and its leads in the layout's order, each a list of
/// polylines (a drawing read back may hold a lead in several pieces; the first is lead A's).
struct Circuit<'a> {
    u: Vec<&'a [Coord]>,
    leads: Vec<Vec<&'a [Coord]>>,
}

/// `Σ ℓ·(y − ȳ_j)/L_j` over the axial segments of `lines` over joint `j` of `robot`.
fn sum_over(robot: &Robot, j: usize, lines: &[&[Coord]]) -> f64 {
    let joint = &robot.joints[j];
    let (x0, x1) = (joint.x_start_mm(), joint.x_end_mm());
    let r_o = robot.outer_radius_mm();
    let rot = joint.rotation_rad();
    let y_bar = joint.neutral_axis_mm();
    let length = x1 - x0;
    let mut sum = 0.0;
    for line in lines {
        for w in line.windows(2) {
            if (w[1].y - w[0].y).abs() > AXIAL_TOL_MM {
                continue;
            }
            let (a, b) = (w[0].x.min(w[1].x), w[0].x.max(w[1].x));
            let over = (b.min(x1) - a.max(x0)).max(0.0);
            if over > 0.0 {
                let y = r_o * (w[0].y / r_o - rot).cos();
                sum += over * (y - y_bar) / length;
            }
        }
    }
    sum
}

fn length(lines: &[&[Coord]]) -> f64 {
    lines
        .iter()
        .flat_map(|l| l.windows(2))
        .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
        .sum()
}

/// What every sensor of `robot` reads, from its circuit in `layout` (the robot's own, or one
/// read from a drawing); the leads of a sensor are its first and second in the layout's order.
///
/// # Errors
/// The sensor whose own U-trace reads no bending over its own joint (its arms on the neutral
/// plane), where the ratio cannot be told.
pub fn reports(robot: &Robot, layout: &Layout) -> Result<Vec<SensorReport>, RobotSensor> {
    fn pieces(traces: &[crate::layout::Trace], sensor: usize) -> Vec<Vec<&[Coord]>> {
        traces
            .iter()
            .filter(|t| t.sensor == sensor)
            .map(|t| t.pieces.iter().map(|p| p.0.as_slice()).collect())
            .collect()
    }
    let circuits = robot
        .sensors()
        .iter()
        .map(|s| Circuit {
            u: pieces(&layout.sensors, s.index)
                .into_iter()
                .flatten()
                .collect(),
            leads: pieces(&layout.leads, s.index),
        })
        .collect::<Vec<_>>();
    compute(robot, &circuits)
}

/// [`reports`] on a routed robot before its seam is chosen (for the router's suggestions).
pub(crate) fn reports_unrolled(
    robot: &Robot,
    unrolled: &Unrolled,
) -> Result<Vec<SensorReport>, RobotSensor> {
    let circuits = robot
        .sensors()
        .iter()
        .map(|s| Circuit {
            u: unrolled
                .sensors
                .iter()
                .filter(|l| l.sensor == s.index)
                .map(|l| l.points.as_slice())
                .collect(),
            leads: unrolled
                .leads
                .iter()
                .filter(|l| l.sensor == s.index)
                .map(|l| vec![l.points.as_slice()])
                .collect(),
        })
        .collect::<Vec<_>>();
    compute(robot, &circuits)
}

fn compute(robot: &Robot, circuits: &[Circuit]) -> Result<Vec<SensorReport>, RobotSensor> {
    let n = robot.joints.len();
    robot
        .sensors()
        .into_iter()
        .zip(circuits)
        .map(|(sensor, circuit)| {
            let own = sum_over(robot, sensor.joint, &circuit.u);
            if own.abs() < 1e-12 {
                return Err(sensor);
            }
            let mut crosstalk = Vec::with_capacity(n);
            let mut by_lead = Vec::with_capacity(n);
            for j in 0..n {
                let u = sum_over(robot, j, &circuit.u);
                let per_lead: Vec<f64> = circuit
                    .leads
                    .iter()
                    .map(|l| sum_over(robot, j, l))
                    .collect();
                let a = per_lead.first().copied().unwrap_or(0.0);
                let b: f64 = per_lead.iter().skip(1).sum();
                // `+ 0.0` turns a −0 (no piece over the joint, a negative own sum) into 0.
                crosstalk.push((u + a + b) / own + 0.0);
                by_lead.push([a / own + 0.0, b / own + 0.0]);
            }
            let u_len = length(&circuit.u);
            let leads_len: f64 = circuit.leads.iter().map(|l| length(l)).sum();
            Ok(SensorReport {
                sensor,
                u_trace_length_mm: u_len,
                leads_length_mm: leads_len,
                trace_length_mm: u_len + leads_len,
                crosstalk,
                by_lead,
            })
        })
        .collect()
}

/// A crosstalk above [`CROSSTALK_WARNING`]: the sensor, the joint it reads, and the lead that
/// carries most of it.
#[derive(Debug, Clone, PartialEq)]
pub struct CrosstalkFinding {
    /// The sensor.
    pub sensor: RobotSensor,
    /// The joint whose bending it reads, 0-based.
    pub joint: usize,
    /// `crosstalk[joint]`.
    pub value: f64,
    /// The lead that carries the larger share.
    pub lead: LeadName,
    /// That lead's share.
    pub lead_value: f64,
}

/// Every crosstalk above [`CROSSTALK_WARNING`] in `reports`.
pub fn findings(reports: &[SensorReport]) -> Vec<CrosstalkFinding> {
    let mut out = Vec::new();
    for r in reports {
        for (j, &value) in r.crosstalk.iter().enumerate() {
            if j == r.sensor.joint || value.abs() <= CROSSTALK_WARNING {
                continue;
            }
            let [a, b] = r.by_lead[j];
            let (arm, lead_value) = if a.abs() >= b.abs() {
                (Arm::A, a)
            } else {
                (Arm::B, b)
            };
            out.push(CrosstalkFinding {
                sensor: r.sensor,
                joint: j,
                value,
                lead: LeadName {
                    sensor: r.sensor,
                    arm,
                },
                lead_value,
            });
        }
    }
    out
}
