//! The setup sheet of a robot (several joints on one tube, `crate::robot`): the sheet
//! [`setup_sheet`] writes for the plan, with the zeroing line that says where each joint is
//! turned, and a table of the joints with the time their notches take. The sheet's own text is
//! fixed by the golden files in `toolpaths/`, so the lines changed here are found by their
//! fixed beginnings.

use crate::machine::format_number;
use crate::toolpath::{format_duration, Feature, MoveKind, OperationKind, Plan};

use super::setup::{setup_sheet, SheetContext};

/// One joint of a robot as the sheet lists it.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetJoint {
    /// The design's name.
    pub name: String,
    /// `UAN` or `BSN`.
    pub style: &'static str,
    /// Its rotation about the tube (°).
    pub rotation_deg: f64,
    /// Its notched section along `x` (mm).
    pub x_start_mm: f64,
    /// Its notched section's proximal end (mm).
    pub x_end_mm: f64,
    /// Its bending length `L` (mm).
    pub bending_length_mm: f64,
    /// Its sensors' robot-wide numbers, from 1 (the program's `sensor N line` comments).
    pub sensors: Vec<usize>,
}

/// The setup sheet for a robot's plan (notch features carry their joint).
pub fn robot_sheet(plan: &Plan, ctx: &SheetContext<'_>, joints: &[SheetJoint]) -> String {
    let text = setup_sheet(plan, ctx);
    let profile = ctx.profile;
    let al = profile.axes.rotary;
    let units = profile.axes.rotary_units;
    let per_rad = units.per_rad();
    let zero = format!("- **{al}0 at s = 0**");
    let turned: Vec<String> = joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            format!(
                "joint {} ({}) at {al}{}",
                i + 1,
                j.style,
                format_number(round6(j.rotation_deg.to_radians() * per_rad))
            )
        })
        .collect();
    let zeroing = format!(
        "{zero}: on a fresh tube any orientation will do; the line under the beam at {al}0 becomes s = 0. This is a robot of {} joints on one tube, each turned about it: the backbone (+y, sensor 1's centre line) of {}. The program cuts each joint's notches where its own drawing puts them, turned by that angle.",
        joints.len(),
        turned.join(", ")
    );
    let times = notch_times(plan, profile, joints.len());
    let mut table = vec![
        "### The robot's joints (distal first)".to_string(),
        String::new(),
        format!(
            "| joint | design | style | rotation | notched section | L | sensors (program numbers) | notch time |"
        ),
        "|---|---|---|---|---|---|---|---|".to_string(),
    ];
    for (i, j) in joints.iter().enumerate() {
        table.push(format!(
            "| {} | {} | {} | {}° ({al}{} {}) | X{} … X{} | {} mm | {} | {} |",
            i + 1,
            j.name,
            j.style,
            format_number(j.rotation_deg),
            format_number(round6(j.rotation_deg.to_radians() * per_rad)),
            units.symbol(),
            format_number(round3(j.x_start_mm)),
            format_number(round3(j.x_end_mm)),
            format_number(round3(j.bending_length_mm)),
            j.sensors
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            format_duration(times[i])
        ));
    }
    table.push(String::new());
    table.push("Notch time per joint: its notches' beam-on moves at the set's surface speed and the rapids into them, all passes (the operations table above has the time per step).".into());
    table.push(String::new());
    let mut out: Vec<String> = Vec::new();
    for line in text.lines() {
        if line.starts_with("## 5. Run") {
            out.extend(table.iter().cloned());
        }
        if line.starts_with(&zero) {
            out.push(zeroing.clone());
        } else {
            out.push(line.to_string());
        }
    }
    let mut s = out.join("\n");
    s.push('\n');
    s
}

fn round3(v: f64) -> f64 {
    (v * 1e3).round() / 1e3
}

fn round6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

/// Time of each joint's notch paths (s): beam-on moves at the set's speed, rapids at the
/// profile's limits (as [`crate::toolpath::estimate`]), each rapid counted with the path it
/// leads into.
fn notch_times(plan: &Plan, profile: &crate::machine::MachineProfile, joints: usize) -> Vec<f64> {
    let mut out = vec![0.0; joints];
    let limits = &profile.limits;
    for mv in plan.moves() {
        let op = &plan.operations[mv.operation];
        if op.kind != OperationKind::Notches {
            continue;
        }
        let Feature::Notch { joint, .. } = op.paths[mv.path].feature else {
            continue;
        };
        let j = joint.unwrap_or(0).min(joints.saturating_sub(1));
        out[j] += match mv.kind {
            MoveKind::Feed => {
                mv.from.surface_distance_mm(&mv.to, plan.outer_radius_mm)
                    / op.process.scan_speed_mm_s
            }
            MoveKind::Rapid => {
                let tx = (mv.to.x_mm - mv.from.x_mm).abs() / limits.x_speed_max_mm_s;
                let ta =
                    (mv.to.a_rad - mv.from.a_rad).abs().to_degrees() / limits.a_speed_max_deg_s;
                tx.max(ta)
            }
        };
    }
    out
}
