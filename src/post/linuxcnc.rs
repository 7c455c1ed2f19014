//! LinuxCNC RS-274/NGC, the reference dialect.
//!
//! Frame: `X` mm along the tube (0 at the free end), `A` = s/r_o in the profile's rotary units,
//! `Z` the focus. Feeds are inverse time (`G93`): each beam-on `G1` carries `F = 60/t`, `t` the
//! move's time in seconds, so the controller finishes the move in exactly `t` whatever mix of
//! `X` and `A` it has — the surface speed `d/t` is the set's scan speed on pure rotations, pure
//! `X` moves and helices alike. Repetitions are `o<n> repeat [k]` … `o<n> endrepeat` loops, with a
//! named parameter `#<focus_z>` for a Z step per pass.

use super::{fixed, AxisWords, FeedMove, Post};
use crate::machine::{MachineProfile, Settle, SettleMode};

/// The LinuxCNC post.
#[derive(Debug, Clone, Copy, Default)]
pub struct LinuxCnc;

impl Post for LinuxCnc {
    fn name(&self) -> &'static str {
        "linuxcnc"
    }

    fn extension(&self) -> &'static str {
        "ngc"
    }

    fn comment(&self, text: &str) -> String {
        let clean: String = text
            .chars()
            .map(|c| match c {
                '(' => '[',
                ')' => ']',
                c if c.is_ascii() && !c.is_ascii_control() => c,
                _ => '?',
            })
            .collect();
        format!("({clean})")
    }

    fn preamble(&self, _profile: &MachineProfile) -> Vec<String> {
        vec![
            "G21 G90 G40 G49 G54 G80 (mm, absolute, no compensation, work offset G54)".into(),
            "G64 P0.001 (blend corners within 1 um)".into(),
            "G93 (inverse-time feeds: F = 1 / minutes per move)".into(),
        ]
    }

    fn settle(&self, settle: &Settle) -> Vec<String> {
        match settle.mode {
            SettleMode::Dwell => vec![format!(
                "G4 P{} (dwell: the source settles at its new pulse frequency and width)",
                fixed(settle.dwell_s, 3)
            )],
            SettleMode::OptionalStop => vec![
                "M1 (optional stop: resume when the source has settled at its new pulse frequency and width)".into(),
            ],
            SettleMode::Stop => vec![
                "M0 (stop: resume when the source has settled at its new pulse frequency and width)".into(),
            ],
            SettleMode::None => Vec::new(),
        }
    }

    fn postamble(&self, _profile: &MachineProfile) -> Vec<String> {
        vec!["G94 (feed per minute again)".into(), "M2".into()]
    }

    fn rapid(&self, profile: &MachineProfile, words: &AxisWords) -> String {
        format!("G0{}", self.axis_words(profile, words))
    }

    fn feed(&self, profile: &MachineProfile, mv: &FeedMove) -> String {
        let f = 60.0 / mv.seconds;
        let decimals = if f >= 10.0 { 4 } else { 6 };
        format!(
            "G1{} F{}",
            self.axis_words(profile, &mv.words),
            fixed(f, decimals)
        )
    }

    fn loop_begin(&self, id: u32, count: u32) -> Option<Vec<String>> {
        Some(vec![format!("o{id} repeat [{count}]")])
    }

    fn loop_end(&self, id: u32) -> Vec<String> {
        vec![format!("o{id} endrepeat")]
    }

    fn z_variable_set(&self, z_mm: f64) -> Option<Vec<String>> {
        Some(vec![format!("#<focus_z> = {}", fixed(z_mm, 4))])
    }

    fn z_variable_rapid_and_step(&self, profile: &MachineProfile, step_mm: f64) -> Vec<String> {
        vec![
            format!("G0 {}#<focus_z>", profile.axes.focus),
            format!("#<focus_z> = [#<focus_z> - {}]", fixed(step_mm, 4)),
        ]
    }
}
