//! Why a part's files could not be made: each message names the file or the part, and carries
//! the cause below it.

use crate::design::DesignError;
use crate::drawing::svg::SvgError;
use crate::drawing::{DxfExportError, DxfImportError};
use crate::job::JobError;
use crate::machine::MachineError;
use crate::process::ProcessError;
use crate::robot::RobotError;
use crate::rules::RulesError;

use super::robot_files::FilesError;

/// Why a part's inputs, drawings, job or files could not be had.
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// The design file.
    #[error(transparent)]
    Design(#[from] DesignError),
    /// The design breaks its design rules.
    #[error(transparent)]
    Rules(#[from] RulesError),
    /// The robot file, or a robot rule.
    #[error(transparent)]
    Robot(Box<RobotError>),
    /// The process sets.
    #[error(transparent)]
    Process(#[from] ProcessError),
    /// The machine profile.
    #[error(transparent)]
    Machine(#[from] MachineError),
    /// The join tolerance is outside (0, 0.1] mm.
    #[error("--join-tolerance {0} mm must be greater than 0 and at most 0.1 mm")]
    JoinTolerance(f64),
    /// The drawing could not be read from disk.
    #[error("cannot read drawing {path}")]
    ReadDrawing {
        /// The drawing's path.
        path: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The drawing is not a DXF dlw can read.
    #[error("reading {path}")]
    ImportDxf {
        /// The drawing's path.
        path: String,
        /// Why.
        #[source]
        source: DxfImportError,
    },
    /// The drawing breaks the design's rules.
    #[error("drawing {path} checked against the design")]
    DesignDrawing {
        /// The drawing's path.
        path: String,
        /// Every broken rule.
        #[source]
        source: RulesError,
    },
    /// The drawing is not of the robot, or breaks its rules.
    #[error("drawing {path} checked against the robot")]
    RobotDrawing {
        /// The drawing's path.
        path: String,
        /// Why.
        #[source]
        source: Box<RobotError>,
    },
    /// The laser job could not be planned.
    #[error("planning the laser job for {name:?}")]
    Job {
        /// The part's name.
        name: String,
        /// Why.
        #[source]
        source: JobError,
    },
    /// A robot's build folder could not be made.
    #[error("building {name:?}")]
    Files {
        /// The robot's name.
        name: String,
        /// Why.
        #[source]
        source: FilesError,
    },
    /// The DXF writer refused.
    #[error("drawing the DXF")]
    Dxf(#[source] DxfExportError),
    /// An SVG sheet could not be drawn.
    #[error("drawing the {sheet} SVG")]
    Svg {
        /// Which sheet: `layout`, `section` or `robot`.
        sheet: &'static str,
        /// Why.
        #[source]
        source: SvgError,
    },
    /// A cross-section was asked of a robot of several joints.
    #[error("--section draws one joint's cross-section, and {robot:?} has {joints} joints: draw each joint's design with --section, or dlw build the robot (one section sheet per joint)")]
    Section {
        /// The robot's name.
        robot: String,
        /// Its joints.
        joints: usize,
    },
}

impl From<RobotError> for BuildError {
    fn from(e: RobotError) -> Self {
        Self::Robot(Box::new(e))
    }
}

impl BuildError {
    /// An SVG error on the sheet named `sheet`.
    pub(crate) fn svg(sheet: &'static str) -> impl FnOnce(SvgError) -> Self {
        move |source| Self::Svg { sheet, source }
    }
}
