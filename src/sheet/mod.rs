//! The operator's setup sheet (Markdown): an emitter like the post-processors ([`crate::post`]),
//! it turns a dialect-free [`crate::toolpath::Plan`] and the machine profile into the page the
//! operator follows: laser safety, stock and mandrel, fixturing, zeroing against the drawing's frame, the
//! parameter sets and times, and the steps after the laser.

mod robot;
mod safety;
mod setup;

/// The setup sheet of a robot: the joint's sheet with the robot's zeroing and a joint table.
pub use robot::{robot_sheet, SheetJoint};
/// The sheet's laser-safety section.
pub use safety::safety_lines;
/// The operator's setup sheet and the mandrel it picks.
pub use setup::{mandrel_mm, setup_sheet, SheetContext, MANDREL_CLEARANCE_MM, MANDREL_SIZES_MM};
