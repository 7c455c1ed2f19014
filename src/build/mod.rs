//! What `dlw build`, `dlw program`, `dlw draw` and `dlw import-dxf` make of a part, a joint or a
//! robot (`docs/architecture.md`): the part read and checked with what its laser job needs
//! ([`JointInputs`], [`RobotInputs`]), a drawing read back and checked against the part
//! ([`read_drawing`]), and the files: the drawings ([`joint_drawings`], [`robot_drawings`]),
//! the job ([`JointInputs::job`], [`RobotInputs::job`]) and the build folder
//! ([`joint_build_files`], [`robot_files::build_files`]).
//!
//! It sits above [`crate::job`], on the fabrication side: a robot's description
//! ([`crate::robot`]) stays below it, so the sensing side, which reads a robot's description,
//! never reaches the laser job through it.

mod error;
mod inputs;
mod joint;
pub mod robot_drawing;
pub mod robot_files;
pub mod robot_job;
pub mod robot_svg;

/// Why a part's files could not be made.
pub use error::BuildError;
/// A part read and checked with its process sets and machine profile; a drawing read back.
pub use inputs::{
    read_design_drawing, read_drawing, read_robot_drawing, DrawingReading, JointInputs,
    ReadDrawing, RobotInputs, MAX_JOIN_TOLERANCE_MM,
};
/// A joint's drawings and build folder; a robot's drawings.
pub use joint::{joint_build_files, joint_drawings, robot_drawings, Drawings};
/// A robot's drawing read back and checked against it.
pub use robot_drawing::{check_robot_drawing, CheckedRobotDrawing};
/// A robot as an SVG sheet: the unrolled robot, its joints labelled, a side view.
pub use robot_svg::{robot_svg, robot_svg_with, sensor_colour, SENSOR_COLOURS};
