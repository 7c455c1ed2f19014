//! The dialect-free laser job: from a layout to a plan of operations, paths and passes.
//!
//! # Frame
//! The program's frame is the drawing's frame ([`crate::layout`]): `X = x` along the tube,
//! 0 at the distal (free) end, and the rotary axis `A = s/r_o` (radians inside the plan,
//! degrees or revolutions in programs), so a program overlays its drawing exactly. `A` is
//! continuous: a feature the drawing splits at its seam is joined again and cut in one go with
//! `A` running past the seam, and a rapid to the next path goes the short way round (the path
//! is shifted by whole turns to start within half a turn of the beam).
//!
//! # Operations
//! Sensor (set (a): traces, leads, pads) → notches (set (b)) → parting (set (b), or the
//! design's parting set), as in the paper's Section II-B. Within an operation paths run in
//! greedy nearest-neighbour order, each entered the nearest way; [`Travel`] reports the rapid
//! travel before and after ordering.
//!
//! - Written lines follow the layout's centre lines; pieces that meet end to end are joined so
//!   the beam writes them without a break. With more than one pass, odd passes run back.
//! - Notch outlines are offset inward by `kerf/2`, so the notch cut has the designed size; each
//!   cut starts with a lead-in from inside the notch (the scrap) to the midpoint of an edge.
//! - The parting cut runs all the way round at the parting line moved `kerf/2` into the stock,
//!   so the joint keeps its length `L`; its lead-in starts on the stock side, and odd passes
//!   turn back, so the tube never unwinds.
//!
//! # Feeds
//! Every beam-on move runs at its set's scan speed `v` over the surface: a move covering
//! `Δx` and `ΔA` (rad) travels `d = sqrt(Δx² + (r_o·ΔA)²)` and takes `d/v`. How a dialect
//! commands that is the post-processor's business ([`crate::post`]).
//!
//! # Errors
//! [`ToolpathError`] names the feature, the value and the limit of whatever the planner refused.

mod check;
mod estimate;
mod offset;
mod order;
mod plan;
mod planner;
mod seam;

/// Safety invariants of a plan.
pub use check::check_plan;
/// Estimated run time per operation.
pub use estimate::{estimate, format_duration, OperationTime};
/// Inward offset of a closed outline.
pub use offset::{offset_inward, OffsetError};
/// Nearest-neighbour ordering and rapid distances.
pub use order::rapid_distance_mm;
/// The plan's types.
pub use plan::{
    Feature, Move, MoveKind, Operation, OperationKind, Path, Plan, Point, TraceKind, Travel,
};
/// Building a plan from a layout.
pub use planner::{plan, plan_part, Part, PlanOptions};
/// Joining pieces across the drawing's seam.
pub use seam::{chain_lines, join_outline, short_way_mm, SeamError};

/// Why the planner refused a job.
#[derive(Debug, thiserror::Error)]
pub enum ToolpathError {
    /// The design breaks a rule that needs the process sets (the wall thickness).
    #[error(transparent)]
    Rules(#[from] crate::rules::RulesError),
    /// The layout is not usable as it stands.
    #[error("layout: {0}")]
    Layout(String),
    /// A notch outline could not be joined or offset.
    #[error("{feature}: {reason}")]
    Outline {
        /// The notch.
        feature: String,
        /// What went wrong.
        reason: String,
    },
    /// No room for a lead-in inside a notch.
    #[error("{feature}: no room inside the kerf-offset outline for a lead-in of {lead_in_mm} mm (nor of an eighth of it)")]
    NoLeadIn {
        /// The notch.
        feature: String,
        /// The lead-in asked for.
        lead_in_mm: f64,
    },
    /// A set asks for more power than the machine allows.
    #[error("{operation}: process set {set:?} asks for {power_mw} mW, above the machine's maximum of {max_mw} mW")]
    Power {
        /// The operation.
        operation: &'static str,
        /// The set.
        set: String,
        /// Its power.
        power_mw: f64,
        /// The profile's maximum.
        max_mw: f64,
    },
    /// The Z step would take the focus through the wall.
    #[error("process set {set:?}: its Z step lowers the focus {depth_mm} mm over its passes, more than the {wall_mm} mm wall")]
    FocusDepth {
        /// The set.
        set: String,
        /// Total lowering.
        depth_mm: f64,
        /// Wall thickness `r_o − r_i`.
        wall_mm: f64,
    },
    /// A move leaves the X travel.
    #[error("{operation}: {feature} reaches x = {x_mm:.4} mm, outside the machine's X travel {min_mm} mm to {max_mm} mm")]
    Travel {
        /// The operation.
        operation: &'static str,
        /// The path.
        feature: String,
        /// The offending X.
        x_mm: f64,
        /// Travel minimum.
        min_mm: f64,
        /// Travel maximum.
        max_mm: f64,
    },
    /// A beam-on move needs an axis faster than the stage allows.
    #[error("{0}")]
    Speed(Box<SpeedViolation>),
    /// A cut comes too close to a written line.
    #[error("a cutting path would touch a written line (kerf {kerf_mm} mm):{}", .found.iter().map(|f| format!("\n  - {f}")).collect::<String>())]
    Clearance {
        /// The kerf (mm).
        kerf_mm: f64,
        /// Each clearance the design rules found broken between a cut and a line.
        found: Vec<String>,
    },
}

/// A beam-on move that needs an axis faster than the stage allows (boxed in
/// [`ToolpathError::Speed`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{operation}: {feature}, pass {pass}, move {index} from {from} to {to} needs {axis} at {needed:.1} {unit} to keep {surface_mm_s} mm/s on the surface, above the stage's limit of {limit} {unit}")]
pub struct SpeedViolation {
    /// The operation.
    pub operation: &'static str,
    /// The path.
    pub feature: String,
    /// Pass number, from 0.
    pub pass: u32,
    /// Index of the move in the whole job.
    pub index: usize,
    /// Start of the move.
    pub from: String,
    /// End of the move.
    pub to: String,
    /// The axis letter.
    pub axis: char,
    /// The speed the move needs.
    pub needed: f64,
    /// The stage's limit.
    pub limit: f64,
    /// Unit of both.
    pub unit: &'static str,
    /// The set's surface speed.
    pub surface_mm_s: f64,
}
