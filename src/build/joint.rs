//! The drawings `dlw draw` writes and the folder `dlw build` writes: everything is made before
//! anything is written, so a failure leaves no file behind (the caller writes).

use std::path::PathBuf;

use crate::drawing::layout_to_dxf;
use crate::drawing::svg::{layout_svg, section_svg};
use crate::job::program_file_name;
use crate::robot::CheckedRobot;
use crate::rules::Checked;

use super::{robot_files, robot_svg, BuildError, JointInputs};

/// Which drawings to make, and where each goes.
#[derive(Debug, Clone, Default)]
pub struct Drawings {
    /// The unrolled layout as an AutoCAD DXF (mm).
    pub dxf: Option<PathBuf>,
    /// The unrolled layout as an SVG sheet (a robot's: the robot sheet).
    pub svg: Option<PathBuf>,
    /// The cross-section through a notch (the paper's Fig. 3), of a joint or a one-joint robot.
    pub section: Option<PathBuf>,
}

impl Drawings {
    /// No drawing asked for.
    pub fn is_empty(&self) -> bool {
        self.dxf.is_none() && self.svg.is_none() && self.section.is_none()
    }
}

/// A checked design's drawings, each with the path it goes to.
///
/// # Errors
/// [`BuildError::Dxf`] or [`BuildError::Svg`].
pub fn joint_drawings(
    checked: &Checked,
    wanted: &Drawings,
) -> Result<Vec<(PathBuf, Vec<u8>)>, BuildError> {
    let (design, layout) = (&checked.design, &checked.layout);
    let mut out = Vec::new();
    if let Some(path) = &wanted.dxf {
        let clearance_mm = design.file.fabrication.clearance_mm();
        let bytes = layout_to_dxf(layout, clearance_mm).map_err(BuildError::Dxf)?;
        out.push((path.clone(), bytes));
    }
    if let Some(path) = &wanted.svg {
        let svg = layout_svg(layout, design).map_err(BuildError::svg("layout"))?;
        out.push((path.clone(), svg.into_bytes()));
    }
    if let Some(path) = &wanted.section {
        let svg = section_svg(design).map_err(BuildError::svg("section"))?;
        out.push((path.clone(), svg.into_bytes()));
    }
    Ok(out)
}

/// A robot's drawings, each with the path it goes to: its DXF, the robot sheet, and the
/// cross-section of a one-joint robot.
///
/// # Errors
/// [`BuildError::Dxf`], [`BuildError::Svg`], or [`BuildError::Section`] for a section of a
/// robot of several joints.
pub fn robot_drawings(
    robot: &CheckedRobot,
    wanted: &Drawings,
) -> Result<Vec<(PathBuf, Vec<u8>)>, BuildError> {
    let mut out = Vec::new();
    if let Some(path) = &wanted.dxf {
        let bytes = robot_files::dxf(robot, &robot.layout).map_err(BuildError::Dxf)?;
        out.push((path.clone(), bytes));
    }
    if let Some(path) = &wanted.svg {
        let svg = robot_svg::robot_svg(robot).map_err(BuildError::svg("robot"))?;
        out.push((path.clone(), svg.into_bytes()));
    }
    if let Some(path) = &wanted.section {
        let [only] = robot.robot.joints.as_slice() else {
            return Err(BuildError::Section {
                robot: robot.robot.name.clone(),
                joints: robot.robot.joints.len(),
            });
        };
        let svg = section_svg(only.design()).map_err(BuildError::svg("section"))?;
        out.push((path.clone(), svg.into_bytes()));
    }
    Ok(out)
}

/// Everything `dlw build` writes for a joint, named after `stem`: the DXF, the layout and
/// section sheets, the program for the inputs' machine profile and its setup sheet.
///
/// # Errors
/// [`BuildError::Job`], [`BuildError::Dxf`] or [`BuildError::Svg`].
pub fn joint_build_files(
    inputs: &JointInputs,
    stem: &str,
) -> Result<Vec<(String, Vec<u8>)>, BuildError> {
    let program_file = program_file_name(stem, &inputs.profile);
    let job = inputs.job(&program_file)?;
    let dxf = layout_to_dxf(&inputs.layout, inputs.clearance_mm).map_err(BuildError::Dxf)?;
    let layout = layout_svg(&inputs.layout, &inputs.design).map_err(BuildError::svg("layout"))?;
    let section = section_svg(&inputs.design).map_err(BuildError::svg("section"))?;
    Ok(vec![
        (format!("{stem}.dxf"), dxf),
        (format!("{stem}-layout.svg"), layout.into_bytes()),
        (format!("{stem}-section.svg"), section.into_bytes()),
        (program_file, job.program.into_bytes()),
        (format!("{stem}-setup.md"), job.sheet.into_bytes()),
    ])
}
