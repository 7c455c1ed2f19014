//! Post-processors: one interface, [`Post`], and a writer per controller dialect.
//!
//! The driver ([`write_program`]) walks the plan (operations, paths, passes, loops), keeps a
//! [`MachineState`] that drops redundant commands and knows whether the beam is on, and asks the
//! post only for the dialect's words: comments, preamble, rapids, feeds, loops. A new controller
//! is a new `Post`; the planner does not change.
//!
//! | dialect | frame | feeds | repetitions |
//! |---|---|---|---|
//! | `linuxcnc` ([`LinuxCnc`]) | `X` mm, `A` = s/r_o in the profile's rotary units, `Z` focus | inverse time `G93`: `F = 60/t` (t in s) on every beam-on move | `o<n> repeat [k]` loops, or unrolled |
//! | `aerobasic` ([`AeroBasic`]) | same | `G76` units per second: `F` = X speed on moves with X motion, rotary speed on pure rotations (RS-274 semantics) | unrolled |
//!
//! Every program closes the beam gate before every rapid; the laser's parameters are set
//! through the profile's templates before the first pass of each operation. When they change
//! between operations (the sensor set → the notch set), the program then waits for the source
//! to settle as the profile's `[settle]` table says: `G4 P…` / `DWELL …`, or an optional stop
//! `M1`, or a stop `M0` ([`crate::machine::Settle`]).

mod aerobasic;
mod emit;
mod linuxcnc;
mod state;

use crate::machine::{Dialect, MachineProfile, Settle};

/// The Aerotech AeroBasic (A3200) writer.
pub use aerobasic::AeroBasic;
/// The driver that turns a plan into a program with any post.
pub use emit::{header_lines, write_program};
/// The LinuxCNC RS-274/NGC writer (the reference).
pub use linuxcnc::LinuxCnc;
/// What the controller has been told so far.
pub use state::MachineState;

/// Axis words of one move, already in program units; `None` leaves an axis where it is.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AxisWords {
    /// Linear axis (mm).
    pub x: Option<f64>,
    /// Rotary axis (profile units).
    pub a: Option<f64>,
    /// Focus axis (mm).
    pub z: Option<f64>,
}

/// One beam-on move as the post needs it to write its feed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeedMove {
    /// Axis words that change.
    pub words: AxisWords,
    /// |ΔX| (mm), from the written coordinates.
    pub dx_mm: f64,
    /// |ΔA| (rotary units), from the written coordinates.
    pub da_units: f64,
    /// Time the move must take (s): surface distance over scan speed.
    pub seconds: f64,
}

/// A controller dialect: how each element of a program is written.
pub trait Post {
    /// The dialect's name as profiles write it.
    fn name(&self) -> &'static str;
    /// The usual file extension of its programs, without the dot.
    fn extension(&self) -> &'static str;
    /// Decimals written for the linear and focus axes.
    fn linear_decimals(&self) -> usize {
        4
    }
    /// Decimals written for the rotary axis, per rotary unit.
    fn rotary_decimals(&self, profile: &MachineProfile) -> usize {
        match profile.axes.rotary_units {
            crate::machine::RotaryUnits::Deg => 6,
            crate::machine::RotaryUnits::Rev => 9,
        }
    }
    /// The axis words of a move, e.g. ` X1.0000 A90.000000`, in the profile's axis letters;
    /// axes that do not move are left out.
    fn axis_words(&self, profile: &MachineProfile, w: &AxisWords) -> String {
        let (linear, rotary) = (self.linear_decimals(), self.rotary_decimals(profile));
        let mut s = String::new();
        for (letter, value, decimals) in [
            (profile.axes.linear, w.x, linear),
            (profile.axes.rotary, w.a, rotary),
            (profile.axes.focus, w.z, linear),
        ] {
            if let Some(v) = value {
                s.push(' ');
                s.push(letter);
                s.push_str(&fixed(v, decimals));
            }
        }
        s
    }
    /// One comment line (the text has no line breaks).
    fn comment(&self, text: &str) -> String;
    /// Lines before the first move: units, absolute positioning, feed mode.
    fn preamble(&self, profile: &MachineProfile) -> Vec<String>;
    /// The wait for the source to settle after its parameters changed (beam off, axes still):
    /// a dwell, an optional stop or a stop as `settle` says; nothing for
    /// [`SettleMode::None`](crate::machine::SettleMode::None).
    fn settle(&self, settle: &Settle) -> Vec<String>;
    /// Lines after the last move.
    fn postamble(&self, profile: &MachineProfile) -> Vec<String>;
    /// A rapid (beam off) to `words`.
    fn rapid(&self, profile: &MachineProfile, words: &AxisWords) -> String;
    /// A beam-on straight move.
    fn feed(&self, profile: &MachineProfile, mv: &FeedMove) -> String;
    /// Opens loop `id` of `count` iterations; `None` when the dialect writes no loops.
    fn loop_begin(&self, id: u32, count: u32) -> Option<Vec<String>>;
    /// Closes loop `id`.
    fn loop_end(&self, id: u32) -> Vec<String>;
    /// Inside a loop: sets the focus variable to `z_mm` (before the loop) — `None` when the
    /// dialect has no variables (the driver then unrolls passes that step Z).
    fn z_variable_set(&self, z_mm: f64) -> Option<Vec<String>>;
    /// Inside a loop: a rapid of the focus axis to the variable, then the variable lowered by
    /// `step_mm`.
    fn z_variable_rapid_and_step(&self, profile: &MachineProfile, step_mm: f64) -> Vec<String>;
}

/// The post-processor for a dialect.
pub fn post_for(dialect: Dialect) -> Box<dyn Post> {
    match dialect {
        Dialect::Linuxcnc => Box::new(LinuxCnc),
        Dialect::Aerobasic => Box::new(AeroBasic),
    }
}

/// Why a program could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PostError {
    /// The profile asks for something the dialect's post cannot write.
    #[error("machine profile {profile:?}: {what} is not supported by the {post} post; {instead}")]
    Unsupported {
        /// The profile.
        profile: String,
        /// The post.
        post: &'static str,
        /// What was asked.
        what: &'static str,
        /// What to use instead.
        instead: &'static str,
    },
}

/// A number with `decimals` decimals, never `-0.000` (the crate's one formatter).
pub use crate::fixed::fixed;
