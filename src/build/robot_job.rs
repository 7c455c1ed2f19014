//! A robot's laser job: one program for the whole robot in one setup (issue 33 §4). The
//! robot's layout goes through the joint's planner and posts unchanged: every sensor and lead
//! is written first (the sensor set, Table II (a): 160 mW, 1 mm/s), then every joint's notches,
//! then the parting cut; the same safety invariants are checked on the plan. The program header
//! lists the joints, and the setup sheet adds the robot's zeroing and a table of its joints.

use crate::drawing::Provenance;
use crate::job::{make_part_job, Job, JobError};
use crate::layout::Layout;
use crate::machine::MachineProfile;
use crate::process::ProcessSets;
use crate::rules;
use crate::sheet::{robot_sheet, setup_sheet, SheetJoint};
use crate::toolpath::{Part, ToolpathError};

use crate::robot::CheckedRobot;

/// The part a robot's plan is of: its name and checksum, the sum of its joints' bending
/// lengths, and header lines naming each joint (none for a one-joint robot, whose program is
/// its joint's).
pub fn part(robot: &CheckedRobot) -> Part {
    let r = &robot.robot;
    let notes = if r.joints.len() == 1 {
        Vec::new()
    } else {
        let mut notes = vec![format!(
            "robot of {} joints on one tube, distal first; each joint's notched section in X:",
            r.joints.len()
        )];
        let sensors = r.sensors();
        for (i, j) in r.joints.iter().enumerate() {
            let mine: Vec<String> = sensors
                .iter()
                .filter(|s| s.joint == i)
                .map(|s| (s.index + 1).to_string())
                .collect();
            notes.push(format!(
                "joint {}: \"{}\" ({}, checksum {}), rotated {} deg, X{:.4} to X{:.4}, sensor{} {}",
                i + 1,
                j.design().file.name,
                j.style_name(),
                j.design().checksum,
                j.rotation_deg,
                j.x_start_mm(),
                j.x_end_mm(),
                if mine.len() == 1 { "" } else { "s" },
                mine.join(" and ")
            ));
        }
        notes
    };
    Part {
        name: r.name.clone(),
        checksum: r.checksum.clone(),
        inner_radius_mm: r.inner_radius_mm(),
        bending_length_mm: r
            .joints
            .iter()
            .map(|j| j.design().file.joint_length_mm)
            .sum(),
        notes,
    }
}

/// Plans `layout` (the robot's own, or one read from its drawing) and writes the program and
/// the setup sheet for `profile`.
///
/// # Errors
/// [`JobError`] from the planner (the tube wall against the sets, every safety invariant) or
/// the post-processor; nothing is written here.
pub fn make_job(
    robot: &CheckedRobot,
    layout: &Layout,
    sets: &ProcessSets,
    profile: &MachineProfile,
    program_file: &str,
    provenance: Option<Provenance>,
) -> Result<Job, JobError> {
    for j in &robot.robot.joints {
        let violations = rules::check_wall(&j.design().file, sets);
        if !violations.is_empty() {
            return Err(JobError::Toolpath(ToolpathError::Rules(
                rules::RulesError {
                    name: j.design().file.name.clone(),
                    violations,
                },
            )));
        }
    }
    let joints = sheet_joints(robot);
    let one = robot.robot.joints.len() == 1;
    make_part_job(
        &part(robot),
        layout,
        sets,
        profile,
        program_file,
        provenance,
        &|plan, ctx| {
            if one {
                setup_sheet(plan, ctx)
            } else {
                robot_sheet(plan, ctx, &joints)
            }
        },
    )
}

/// The joints as the sheet lists them.
fn sheet_joints(robot: &CheckedRobot) -> Vec<SheetJoint> {
    let sensors = robot.robot.sensors();
    robot
        .robot
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| SheetJoint {
            name: j.design().file.name.clone(),
            style: j.style_name(),
            rotation_deg: j.rotation_deg,
            x_start_mm: j.x_start_mm(),
            x_end_mm: j.x_end_mm(),
            bending_length_mm: j.design().file.joint_length_mm,
            sensors: sensors
                .iter()
                .filter(|s| s.joint == i)
                .map(|s| s.index + 1)
                .collect(),
        })
        .collect()
}
