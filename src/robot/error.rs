//! Why a robot was refused: the file, a joint's own design rules, or the robot's rules (same
//! tube, gaps, the router's rules). Every message names the joint, the sensor or lead, and the
//! shortfall.

use std::path::PathBuf;

use crate::design::DesignError;
use crate::rules::RulesError;

/// Why a robot could not be read, checked or routed.
#[derive(Debug, thiserror::Error)]
pub enum RobotError {
    /// The robot file could not be read.
    #[error("cannot read robot {path}")]
    Read {
        /// The robot file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The robot file is not valid TOML for a robot.
    #[error("robot {path}: {message}")]
    Parse {
        /// The robot file.
        path: PathBuf,
        /// The parser's message, naming the key.
        message: String,
    },
    /// A joint's design file could not be read. (The cause is the error's source, so that a
    /// chain printed with its causes, `{:#}`, does not repeat it.)
    #[error("robot {robot:?}, joint {joint} ({path})")]
    Design {
        /// The robot's name.
        robot: String,
        /// The joint, 1-based.
        joint: usize,
        /// The design file.
        path: PathBuf,
        /// Why.
        source: DesignError,
    },
    /// A joint's design breaks its own design rules (the rules are the source, as above).
    #[error("robot {robot:?}, joint {joint} ({path})")]
    JointRules {
        /// The robot's name.
        robot: String,
        /// The joint, 1-based.
        joint: usize,
        /// The design file.
        path: PathBuf,
        /// Every rule it breaks.
        source: RulesError,
    },
    /// The robot breaks one or more robot rules; the message lists every one.
    #[error("robot {robot:?} breaks {} robot rule{}:{}", .violations.len(), if .violations.len() == 1 { "" } else { "s" }, .violations.iter().map(|v| format!("\n  - {v}")).collect::<String>())]
    Rules {
        /// The robot's name.
        robot: String,
        /// Every broken rule.
        violations: Vec<RobotViolation>,
    },
}

/// A robot rule a robot breaks.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RobotViolation {
    /// A joint's `rotation_deg` is not a usable angle.
    #[error("joint {joint}: rotation_deg = {value} must be a finite number from -360 to 360")]
    Rotation {
        /// The joint, 1-based.
        joint: usize,
        /// The value given.
        value: f64,
    },
    /// The first joint has a gap.
    #[error(
        "joint 1 is the distal joint, at x = 0: gap_mm = {gap_mm} belongs to the joints after it"
    )]
    GapOnFirst {
        /// The value given (mm).
        gap_mm: f64,
    },
    /// A joint after the first has no gap.
    #[error("joint {joint} ({name:?}) has no gap_mm: give the uncut tube between joint {}'s last notch and its first (mm)", .joint - 1)]
    NoGap {
        /// The joint, 1-based.
        joint: usize,
        /// Its design's name.
        name: String,
    },
    /// A gap that is not a positive, finite length.
    #[error("joint {joint}: gap_mm = {gap_mm} must be a finite number greater than 0")]
    BadGap {
        /// The joint, 1-based.
        joint: usize,
        /// The value given (mm).
        gap_mm: f64,
    },
    /// Two joints are not cut from the same tube.
    #[error("joint {joint} ({name:?}) is not on the same tube as joint 1 ({first:?}): its {quantity} is {value}, joint 1's is {first_value}")]
    Tube {
        /// The joint, 1-based.
        joint: usize,
        /// Its design's name.
        name: String,
        /// Joint 1's design's name.
        first: String,
        /// What differs.
        quantity: &'static str,
        /// The joint's value.
        value: String,
        /// Joint 1's value.
        first_value: String,
    },
    /// Two joints ask for different laser settings, which one program in one setup cannot give.
    #[error("joint {joint} ({name:?}) has {quantity} {value}, joint 1 ({first:?}) has {first_value}: the robot is written and cut in one setup by one program, so every joint must agree")]
    Laser {
        /// The joint, 1-based.
        joint: usize,
        /// Its design's name.
        name: String,
        /// Joint 1's design's name.
        first: String,
        /// What differs.
        quantity: &'static str,
        /// The joint's value.
        value: String,
        /// Joint 1's value.
        first_value: String,
    },
    /// A joint's backbone cannot carry the leads that cross it.
    #[error("joint {joint} ({name:?}, {style}, rotated {rotation_deg}°) cannot carry the {count} leads that cross it ({leads}): beside its own sensor{plural} its backbone has room for {room} at {pitch_mm:.3} mm pitch (trace width + clearance), in {corridors}; {short} lead{short_plural} too many", plural = if *.own_sensors == 1 { "" } else { "s" }, short_plural = if *.short == 1 { "" } else { "s" })]
    Backbone {
        /// The joint, 1-based.
        joint: usize,
        /// Its design's name.
        name: String,
        /// `UAN` or `BSN`.
        style: &'static str,
        /// Its rotation (°).
        rotation_deg: f64,
        /// Its own sensors.
        own_sensors: usize,
        /// Leads that must cross it.
        count: usize,
        /// Which leads.
        leads: String,
        /// How many leads fit.
        room: usize,
        /// The corridors, described (`2 corridors, 0.123 and 0.123 mm wide`).
        corridors: String,
        /// Lead pitch (mm).
        pitch_mm: f64,
        /// How many do not fit.
        short: usize,
    },
    /// A gap is too short for the jogs that must happen in it.
    #[error("gap_mm = {gap_mm} before joint {joint} ({name:?}) is too short for the leads that move round the tube there ({leads}): {steps} jog step{plural} need {prev_half_mm} + {}·{pitch_mm:.3} + {half_mm} = {needed_mm:.3} mm (half of each joint's distal margin, and a trace width + clearance before, between and after the steps); {short_mm:.3} mm short", .steps + 1, plural = if *.steps == 1 { "" } else { "s" }, short_mm = .needed_mm - .gap_mm)]
    Gap {
        /// The joint after the gap, 1-based.
        joint: usize,
        /// Its design's name.
        name: String,
        /// The gap given (mm).
        gap_mm: f64,
        /// Which leads jog.
        leads: String,
        /// Jog steps along `x`.
        steps: usize,
        /// Half the previous joint's distal margin (the arms' overrun) (mm).
        prev_half_mm: f64,
        /// Half this joint's distal margin (the bridge's place) (mm).
        half_mm: f64,
        /// Lead pitch (mm).
        pitch_mm: f64,
        /// The least gap (mm).
        needed_mm: f64,
    },
    /// The leads cannot move round the tube at one place without crossing.
    #[error("{place}: {lead} cannot move round the tube to its place without crossing {other}; no order of jogs keeps them apart ({advice})")]
    Crossing {
        /// Where (`before joint 2`, `before the pads`).
        place: String,
        /// The lead that would cross.
        lead: String,
        /// The lead it would cross.
        other: String,
        /// What would let them pass.
        advice: String,
    },
    /// The pad section does not fit round the tube.
    #[error("the pad section cannot hold the pads of {leads}: {reason}")]
    PadSection {
        /// Which leads' pads.
        leads: String,
        /// Why, with the shortfall.
        reason: String,
    },
    /// A drawing read back is not of this robot, or breaks a rule the robot keeps.
    #[error("the drawing {0}")]
    Drawing(String),
    /// The routed robot failed the router's own check, so it is not drawn.
    #[error("the routed robot breaks a rule it must keep, so nothing is drawn (please report this): {0}")]
    Unsafe(String),
}
