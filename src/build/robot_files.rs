//! What `dlw draw` and `dlw build` write for a robot: the DXF (a joint's drawing for a
//! one-joint robot, else titled as a robot with each joint labelled above the tube), the robot
//! sheet, one section sheet per joint, the program and the setup sheet.

use super::robot_svg::robot_svg;
use crate::drawing::svg::{section_svg, SvgError};
use crate::drawing::{layout_to_dxf, layout_to_dxf_with, DxfExportError, DxfNotes};
use crate::job::{program_file_name, JobError};
use crate::layout::Layout;
use crate::machine::MachineProfile;
use crate::process::ProcessSets;

use crate::robot::CheckedRobot;

/// Why a robot's files could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FilesError {
    /// The DXF writer refused.
    #[error("drawing the DXF: {0}")]
    Dxf(#[from] DxfExportError),
    /// An SVG could not be drawn.
    #[error("drawing an SVG: {0}")]
    Svg(#[from] SvgError),
    /// The laser job could not be made.
    #[error(transparent)]
    Job(#[from] JobError),
}

/// The robot's DXF of `layout` (its own, or one read back).
///
/// # Errors
/// [`DxfExportError`] from the writer.
pub fn dxf(robot: &CheckedRobot, layout: &Layout) -> Result<Vec<u8>, DxfExportError> {
    let clearance = robot.robot.clearance_mm();
    if robot.robot.joints.len() == 1 {
        return layout_to_dxf(layout, clearance);
    }
    let notes = DxfNotes {
        title: Some(format!(
            "unrolled robot, {} joints (sensor numbers robot-wide)",
            robot.robot.joints.len()
        )),
        labels: robot
            .robot
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| {
                (
                    j.x_start_mm(),
                    format!(
                        "joint {}: {} ({}), rotated {} deg",
                        i + 1,
                        j.design().file.name,
                        j.style_name(),
                        j.rotation_deg
                    ),
                )
            })
            .collect(),
    };
    layout_to_dxf_with(layout, clearance, &notes)
}

/// The section sheets: one per joint, `STEM-section.svg` for a one-joint robot (as a joint's
/// build names it) and `STEM-joint-N-section.svg` otherwise.
///
/// # Errors
/// [`SvgError`] from a section.
pub fn sections(robot: &CheckedRobot, stem: &str) -> Result<Vec<(String, Vec<u8>)>, SvgError> {
    let one = robot.robot.joints.len() == 1;
    robot
        .robot
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let name = if one {
                format!("{stem}-section.svg")
            } else {
                format!("{stem}-joint-{}-section.svg", i + 1)
            };
            Ok((name, section_svg(j.design())?.into_bytes()))
        })
        .collect()
}

/// Everything `dlw build` writes for a robot, named after `stem`: the DXF, the robot sheet,
/// the section sheets, the program for `profile` and its setup sheet.
///
/// # Errors
/// [`FilesError`] from a writer or the planner; nothing is written here.
pub fn build_files(
    robot: &CheckedRobot,
    stem: &str,
    sets: &ProcessSets,
    profile: &MachineProfile,
) -> Result<Vec<(String, Vec<u8>)>, FilesError> {
    let program_file = program_file_name(stem, profile);
    let job = super::robot_job::make_job(robot, &robot.layout, sets, profile, &program_file, None)?;
    let mut files = vec![
        (format!("{stem}.dxf"), dxf(robot, &robot.layout)?),
        (format!("{stem}-layout.svg"), robot_svg(robot)?.into_bytes()),
    ];
    files.extend(sections(robot, stem)?);
    files.push((program_file, job.program.into_bytes()));
    files.push((format!("{stem}-setup.md"), job.sheet.into_bytes()));
    Ok(files)
}
