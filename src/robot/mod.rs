//! A sensing robot: several joints on one tube, their leads routed past each other to one pad
//! section, one program in one setup (issue 33; `docs/robots.md`).
//!
//! A robot is a concept beside [`crate::design`]: it reads a robot file ([`RobotFile`]), takes
//! each joint's design and its own layout ([`crate::layout::Unrolled`]), places them along the
//! tube and turns them ([`Robot`]), routes every lead ([`CheckedRobot`]) and hands back one
//! [`crate::layout::Layout`]. From there the flow is a joint's: the same layout rules, the same
//! DXF and SVG writers, the same toolpath planner and posts (`crate::build`, which sits above
//! the job; this module is the robot's description, below it, so the sensing side can read a
//! robot without reaching the laser job).
//!
//! # Frame
//! The joint's (`docs/frames.md`): `x` along the tube from the distal end (joint 1's free end,
//! `x = 0`) toward the collet; `s = r_o·φ` on the outer surface, `φ` from the tube's `+y`.
//! Joint `j`'s own `+y` lies at `s = r_o·rotation_j`; its notched section is
//! `[x_start_mm, x_end_mm]`.
//!
//! # Identities
//! Sensors are numbered robot-wide by joint, then sensor 1 before 2 ([`RobotSensor`]); a
//! layout's `Trace::sensor` is that index. Leads are [`LeadName`]s. Joints are 0-based inside,
//! 1-based in messages.
//!
//! # Examples
//! ```
//! use dlw::robot::CheckedRobot;
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let path = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/designs/robot-bc.toml"));
//! let robot = CheckedRobot::load(path)?;
//! assert_eq!(robot.robot.joints.len(), 2);
//! let c = robot.crosstalk_matrix();          // sensors × joints, C[i][own] = 1
//! assert_eq!(c.len(), 3);
//! assert_eq!(c[0][0], 1.0);
//! # Ok(()) }
//! ```
//!
//! # Errors
//! [`RobotError`]: the file, a joint's own design rules, or a robot rule
//! ([`RobotViolation`]), each naming the joint, the sensor or lead and the shortfall.

mod assemble;
mod checked;
mod crosstalk;
mod error;
pub mod estimator_config;
mod file;
mod inspect;
mod jogs;
mod lanes;
mod pads;
mod property;
mod route;
mod sensors;
mod suggest;

/// A validated robot and its joints, placed.
pub use assemble::{Robot, RobotJoint};
/// A routed, checked robot: the layout, the crosstalk, the warnings.
pub use checked::CheckedRobot;
/// Crosstalk: what each sensor reads of each joint's bending.
pub use crosstalk::{findings, reports, CrosstalkFinding, SensorReport, CROSSTALK_WARNING};
/// Why a robot was refused.
pub use error::{RobotError, RobotViolation};
/// The robot file.
pub use file::{design_inputs, is_robot_file, is_robot_toml, JointEntry, RobotFile, MAX_JOINTS};
/// What `dlw inspect ROBOT --json` prints.
pub use inspect::{JointInspection, RobotInspection, SensorInspection};
/// The router's property.
pub use property::check_property;
/// Sensor and lead identities.
pub use sensors::{Arm, LeadName, RobotSensor};

#[cfg(test)]
mod tests;
