//! What `dlw inspect ROBOT --json` reports (issue 33 §3, `ROBOT.md`): the joints, each with
//! the keys `dlw inspect` gives for its design alone plus its place on the robot, and the
//! sensors with their trace lengths and crosstalk. The keys are part of the interface: the
//! robot's runtime (issue 34) reads them.

use serde::Serialize;

use crate::rules::Inspection;

use super::checked::CheckedRobot;

/// A robot's numbers.
#[derive(Debug, Clone, Serialize)]
pub struct RobotInspection {
    /// The robot's name.
    pub name: String,
    /// Its checksum (program headers carry it).
    pub checksum: String,
    /// Part length from the distal end to the parting cut (mm).
    pub length_mm: f64,
    /// Rows of pads after the last joint's own.
    pub pad_rows: usize,
    /// One object per joint, distal first.
    pub joints: Vec<JointInspection>,
    /// One object per sensor, by joint, then sensor 1 before 2.
    pub sensors: Vec<SensorInspection>,
    /// Every warning: each joint's own, then crosstalk above 5 % with what would lower it.
    pub warnings: Vec<String>,
}

/// One joint: its design's own inspection, and where it sits on the robot.
#[derive(Debug, Clone, Serialize)]
pub struct JointInspection {
    /// `dlw inspect`'s keys for the design alone.
    #[serde(flatten)]
    pub design: Inspection,
    /// The design file as the robot file names it.
    pub design_file: String,
    /// Its bending plane about the tube axis (°).
    pub rotation_deg: f64,
    /// Uncut tube before it (mm); absent for joint 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gap_mm: Option<f64>,
    /// Start of its notched section on the robot's tube, drawing `x` (mm).
    pub x_start_mm: f64,
    /// End of its notched section (mm).
    pub x_end_mm: f64,
}

/// One sensor.
#[derive(Debug, Clone, Serialize)]
pub struct SensorInspection {
    /// Its joint, 1-based.
    pub joint: usize,
    /// Within its joint, 1 or 2.
    pub sensor: usize,
    /// Its circuit without the pads: U-trace and both leads (mm).
    pub trace_length_mm: f64,
    /// Its U-trace (mm).
    pub u_trace_length_mm: f64,
    /// Its two leads (mm).
    pub leads_length_mm: f64,
    /// The share of each joint's bending it reads, relative to its own joint's
    /// (`crosstalk[own] = 1`; `docs/robots.md`).
    pub crosstalk: Vec<f64>,
}

impl RobotInspection {
    /// The numbers of a checked robot.
    pub fn of(checked: &CheckedRobot) -> Self {
        let robot = &checked.robot;
        let joints = robot
            .joints
            .iter()
            .map(|j| JointInspection {
                design: Inspection::of(&j.checked),
                design_file: j.design_path.display().to_string(),
                rotation_deg: j.rotation_deg,
                gap_mm: j.gap_mm,
                x_start_mm: j.x_start_mm(),
                x_end_mm: j.x_end_mm(),
            })
            .collect();
        let sensors = checked
            .sensors
            .iter()
            .map(|s| SensorInspection {
                joint: s.sensor.joint + 1,
                sensor: s.sensor.sensor + 1,
                trace_length_mm: s.trace_length_mm,
                u_trace_length_mm: s.u_trace_length_mm,
                leads_length_mm: s.leads_length_mm,
                crosstalk: s.crosstalk.clone(),
            })
            .collect();
        Self {
            name: robot.name.clone(),
            checksum: robot.checksum.clone(),
            length_mm: checked.layout.length_mm,
            pad_rows: checked.pad_rows,
            joints,
            sensors,
            warnings: checked.warnings_with_advice(),
        }
    }
}
