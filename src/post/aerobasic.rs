//! Aerotech AeroBasic (A3200), as many femtosecond workstations run.
//!
//! Frame: as [`super::LinuxCnc`]. Feeds are per move in units per second (`G76`), with RS-274
//! semantics: on a move with `X` motion `F` is the `X` component of the speed, `|ΔX|/t`; on a
//! pure rotation `F` is the rotary speed `|ΔA|/t` in rotary units per second. Either way the
//! move takes `t = d/v` and the focus crosses the surface at the set's scan speed. Passes are
//! written out (no loops), which keeps the program free of controller variables.
//!
//! The settle between operations is `DWELL s` (seconds), `M1` (optional pause) or `M0`.
//!
//! No AeroBasic interpreter was available to check these programs; `tests/aerobasic_programs.rs`
//! parses their move syntax and applies the same physical checks as the LinuxCNC tests.

use super::{fixed, AxisWords, FeedMove, Post};
use crate::machine::{MachineProfile, Settle, SettleMode};

/// The AeroBasic post.
#[derive(Debug, Clone, Copy, Default)]
pub struct AeroBasic;

impl Post for AeroBasic {
    fn name(&self) -> &'static str {
        "aerobasic"
    }

    fn extension(&self) -> &'static str {
        "pgm"
    }

    fn comment(&self, text: &str) -> String {
        let clean: String = text
            .chars()
            .map(|c| {
                if c.is_ascii() && !c.is_ascii_control() {
                    c
                } else {
                    '?'
                }
            })
            .collect();
        format!("// {clean}")
    }

    fn preamble(&self, profile: &MachineProfile) -> Vec<String> {
        let a = &profile.axes;
        vec![
            format!("ENABLE {} {} {}", a.linear, a.rotary, a.focus),
            "G71 // millimetres".into(),
            "G76 // feeds in units per second".into(),
            "G90 // absolute coordinates".into(),
        ]
    }

    fn settle(&self, settle: &Settle) -> Vec<String> {
        match settle.mode {
            SettleMode::Dwell => vec![format!(
                "DWELL {} // seconds: the source settles at its new pulse frequency and width",
                fixed(settle.dwell_s, 3)
            )],
            SettleMode::OptionalStop => vec![
                "M1 // optional pause: resume when the source has settled at its new pulse frequency and width".into(),
            ],
            SettleMode::Stop => vec![
                "M0 // program pause: resume when the source has settled at its new pulse frequency and width".into(),
            ],
            SettleMode::None => Vec::new(),
        }
    }

    fn postamble(&self, _profile: &MachineProfile) -> Vec<String> {
        vec!["END PROGRAM".into()]
    }

    fn rapid(&self, profile: &MachineProfile, words: &AxisWords) -> String {
        format!("G0{}", self.axis_words(profile, words))
    }

    fn feed(&self, profile: &MachineProfile, mv: &FeedMove) -> String {
        let f = if mv.dx_mm > 0.0 {
            mv.dx_mm / mv.seconds
        } else {
            mv.da_units / mv.seconds
        };
        format!("G1{} F{}", self.axis_words(profile, &mv.words), fixed(f, 6))
    }

    fn loop_begin(&self, _id: u32, _count: u32) -> Option<Vec<String>> {
        None
    }

    fn loop_end(&self, _id: u32) -> Vec<String> {
        Vec::new()
    }

    fn z_variable_set(&self, _z_mm: f64) -> Option<Vec<String>> {
        None
    }

    fn z_variable_rapid_and_step(&self, _profile: &MachineProfile, _step_mm: f64) -> Vec<String> {
        Vec::new()
    }
}
