//! A part read and checked with everything its laser job needs, and a drawing read back and
//! checked against the part.

use std::path::Path;

use crate::design::{Design, DesignFile};
use crate::drawing::{
    read_dxf, DrawingUnits, ImportOptions, ImportedDxf, LayoutNumbers, Provenance,
};
use crate::job::{make_job_from, Job};
use crate::layout::Layout;
use crate::limits::MAX_DRAWING_BYTES;
use crate::machine::{MachineLibrary, MachineProfile};
use crate::process::{ProcessLibrary, ProcessSets};
use crate::robot::CheckedRobot;
use crate::rules::{self, Checked, CheckedDrawing};

use super::robot_drawing::{check_robot_drawing, CheckedRobotDrawing};
use super::BuildError;

/// The largest join tolerance a drawing is read with (mm).
pub const MAX_JOIN_TOLERANCE_MM: f64 = 0.1;

/// How to read a drawing that does not say everything itself.
#[derive(Debug, Clone, Copy)]
pub struct DrawingReading {
    /// The drawing's unit when it has no `$INSUNITS` (R12 files cannot store it).
    pub units: Option<DrawingUnits>,
    /// Ends of lines and arcs on NOTCHES closer than this are joined into one outline (mm);
    /// also the chord error of arcs. In (0, [`MAX_JOIN_TOLERANCE_MM`]].
    pub join_tolerance_mm: f64,
}

/// A drawing read from disk, not yet checked against a part.
#[derive(Debug)]
pub struct ReadDrawing {
    /// What the DXF holds.
    pub imported: ImportedDxf,
    /// The file's bytes (its checksum goes in the provenance).
    pub bytes: Vec<u8>,
    /// The file's name, as the provenance and the setup sheet give it.
    pub file_name: String,
    /// Entities on layers dlw does not read, one line per layer, the path in front.
    pub warnings: Vec<String>,
}

/// Reads the drawing at `path` through the bounded reader; `numbers`, from the part, stand in
/// for the layout's numbers when the drawing lost dlw's XDATA.
///
/// # Errors
/// [`BuildError::JoinTolerance`], [`BuildError::ReadDrawing`] or [`BuildError::ImportDxf`].
pub fn read_drawing(
    path: &Path,
    reading: &DrawingReading,
    numbers: Option<LayoutNumbers>,
) -> Result<ReadDrawing, BuildError> {
    let tol = reading.join_tolerance_mm;
    if !(tol.is_finite() && tol > 0.0 && tol <= MAX_JOIN_TOLERANCE_MM) {
        return Err(BuildError::JoinTolerance(tol));
    }
    let shown = path.display().to_string();
    let bytes = crate::output::read_limited_bytes(path, MAX_DRAWING_BYTES).map_err(|source| {
        BuildError::ReadDrawing {
            path: shown.clone(),
            source,
        }
    })?;
    let options = ImportOptions {
        units: reading.units,
        numbers,
        join_tolerance_mm: tol,
    };
    let imported = read_dxf(&bytes, &options).map_err(|source| BuildError::ImportDxf {
        path: shown.clone(),
        source,
    })?;
    let warnings = imported
        .ignored_warnings()
        .into_iter()
        .map(|w| format!("{shown}: {w}"))
        .collect();
    let file_name = path
        .file_name()
        .map_or_else(|| shown.clone(), |n| n.to_string_lossy().into_owned());
    Ok(ReadDrawing {
        imported,
        bytes,
        file_name,
        warnings,
    })
}

/// Reads the drawing at `path` for the checked design and checks it against the design: the
/// design gives the layout's numbers when the drawing lost its XDATA, and its kerf, trace
/// width and clearance are the ones used. The reading's warnings come first in the
/// [`CheckedDrawing`]'s, as text in [`ReadDrawing::warnings`].
///
/// # Errors
/// [`read_drawing`]'s, and [`BuildError::DesignDrawing`] listing every rule the drawing breaks.
pub fn read_design_drawing(
    path: &Path,
    reading: &DrawingReading,
    checked: &Checked,
) -> Result<(ReadDrawing, CheckedDrawing), BuildError> {
    let clearance_mm = checked.design.file.fabrication.clearance_mm();
    let numbers = LayoutNumbers::of(&checked.layout, clearance_mm);
    let read = read_drawing(path, reading, Some(numbers))?;
    let drawing = rules::check_imported(checked, &read.imported, &read.file_name, &read.bytes)
        .map_err(|source| BuildError::DesignDrawing {
            path: path.display().to_string(),
            source,
        })?;
    Ok((read, drawing))
}

/// Reads a robot's drawing and checks it against the robot.
///
/// # Errors
/// [`read_drawing`]'s, and [`BuildError::RobotDrawing`].
pub fn read_robot_drawing(
    path: &Path,
    reading: &DrawingReading,
    robot: &CheckedRobot,
) -> Result<(ReadDrawing, CheckedRobotDrawing), BuildError> {
    let numbers = LayoutNumbers::of(&robot.layout, robot.robot.clearance_mm());
    let read = read_drawing(path, reading, Some(numbers))?;
    let drawing = check_robot_drawing(robot, &read.imported, &read.file_name, &read.bytes)
        .map_err(|source| BuildError::RobotDrawing {
            path: path.display().to_string(),
            source: Box::new(source),
        })?;
    Ok((read, drawing))
}

/// What a joint's job is made from, resolved and checked.
#[derive(Debug)]
pub struct JointInputs {
    /// The validated design.
    pub design: Design,
    /// Its layout, or its drawing's.
    pub layout: Layout,
    /// The design's process sets.
    pub sets: ProcessSets,
    /// The machine profile.
    pub profile: MachineProfile,
    /// Warnings to print, in the order they were found.
    pub warnings: Vec<String>,
    /// The clearance the layout was checked with (mm).
    pub clearance_mm: f64,
    /// The drawing the layout was read from.
    pub provenance: Option<Provenance>,
}

impl JointInputs {
    /// Reads and checks the design (every design rule), takes its layout or the drawing's at
    /// `from_dxf` (checked against the design), finds the process sets and the machine profile
    /// (`machine`: a name or a path; the default profile without) beside the design file.
    ///
    /// # Errors
    /// The design's, the drawing's, the process sets' or the profile's [`BuildError`].
    pub fn resolve(
        design_path: &Path,
        from_dxf: Option<(&Path, &DrawingReading)>,
        machine: Option<&str>,
    ) -> Result<Self, BuildError> {
        let checked = rules::check_file(DesignFile::read(design_path)?)?;
        let clearance_mm = checked.design.file.fabrication.clearance_mm();
        let (layout, warnings, provenance) = match from_dxf {
            None => (checked.layout, to_text(&checked.warnings), None),
            Some((dxf, reading)) => {
                let (read, drawing) = read_design_drawing(dxf, reading, &checked)?;
                let mut warnings = read.warnings;
                warnings.extend(to_text(&drawing.warnings));
                (drawing.layout, warnings, Some(drawing.provenance))
            }
        };
        let design = checked.design;
        let sets = ProcessLibrary::beside(design_path).resolve(&design.file.process)?;
        let profile = MachineLibrary::beside(design_path).find(machine)?;
        Ok(Self {
            design,
            layout,
            sets,
            profile,
            warnings,
            clearance_mm,
            provenance,
        })
    }

    /// The joint's laser job, naming the program `program_file` on the sheet.
    ///
    /// # Errors
    /// [`BuildError::Job`].
    pub fn job(&self, program_file: &str) -> Result<Job, BuildError> {
        make_job_from(
            &self.design,
            &self.layout,
            &self.sets,
            &self.profile,
            program_file,
            self.provenance.clone(),
        )
        .map_err(|source| BuildError::Job {
            name: self.design.file.name.clone(),
            source,
        })
    }
}

/// What a robot's job is made from, resolved and checked.
#[derive(Debug)]
pub struct RobotInputs {
    /// The routed, checked robot.
    pub robot: CheckedRobot,
    /// Its layout, or its drawing's.
    pub layout: Layout,
    /// The first joint's process sets (a robot is written in one setup).
    pub sets: ProcessSets,
    /// The machine profile.
    pub profile: MachineProfile,
    /// Warnings to print, in the order they were found: the robot's, then the drawing's.
    pub warnings: Vec<String>,
    /// The drawing the layout was read from.
    pub provenance: Option<Provenance>,
}

impl RobotInputs {
    /// Reads and checks the robot, takes its layout or its drawing's (checked against it),
    /// finds the process sets and the machine profile beside the robot file.
    ///
    /// # Errors
    /// The robot's, the drawing's, the process sets' or the profile's [`BuildError`].
    pub fn resolve(
        path: &Path,
        from_dxf: Option<(&Path, &DrawingReading)>,
        machine: Option<&str>,
    ) -> Result<Self, BuildError> {
        let robot = CheckedRobot::load(path)?;
        let mut warnings = to_text(&robot.warnings);
        let (layout, provenance) = match from_dxf {
            None => (robot.layout.clone(), None),
            Some((dxf, reading)) => {
                let (read, drawing) = read_robot_drawing(dxf, reading, &robot)?;
                warnings.extend(read.warnings);
                warnings.extend(drawing.warnings);
                (drawing.layout, Some(drawing.provenance))
            }
        };
        let sets =
            ProcessLibrary::beside(path).resolve(&robot.robot.joints[0].design().file.process)?;
        let profile = MachineLibrary::beside(path).find(machine)?;
        Ok(Self {
            robot,
            layout,
            sets,
            profile,
            warnings,
            provenance,
        })
    }

    /// The robot's laser job, naming the program `program_file` on the sheet.
    ///
    /// # Errors
    /// [`BuildError::Job`].
    pub fn job(&self, program_file: &str) -> Result<Job, BuildError> {
        super::robot_job::make_job(
            &self.robot,
            &self.layout,
            &self.sets,
            &self.profile,
            program_file,
            self.provenance.clone(),
        )
        .map_err(|source| BuildError::Job {
            name: self.robot.robot.name.clone(),
            source,
        })
    }

    /// The robot's build folder: its files, named after `stem`.
    ///
    /// # Errors
    /// [`BuildError::Files`].
    pub fn build_files(&self, stem: &str) -> Result<Vec<(String, Vec<u8>)>, BuildError> {
        super::robot_files::build_files(&self.robot, stem, &self.sets, &self.profile).map_err(
            |source| BuildError::Files {
                name: self.robot.robot.name.clone(),
                source,
            },
        )
    }
}

/// Warnings as the lines printed.
fn to_text<W: std::fmt::Display>(warnings: &[W]) -> Vec<String> {
    warnings.iter().map(ToString::to_string).collect()
}
