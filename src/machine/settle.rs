//! Settling between operations: what the program does after it changes the laser's parameters
//! (the sensor set → the notch set) and before the beam opens again.
//!
//! A femtosecond source that changes its pulse frequency and pulse width takes a moment to
//! deliver stable pulses at the new setting (its pulse picker, amplifier and compressor settle).
//! The profile's optional `[settle]` table says how the program waits for that; without it the
//! program dwells [`DEFAULT_DWELL_S`] seconds. Measure your source and set the table.

use serde::{Deserialize, Serialize};

use crate::process::ProcessSet;

/// The dwell used when a profile has no `[settle]` table (s): a conservative wait, not a
/// measured property of any particular source.
pub const DEFAULT_DWELL_S: f64 = 5.0;

/// Longest dwell a profile may ask for (s); more is surely a unit mistake (ms for s).
pub const MAX_DWELL_S: f64 = 600.0;

/// How the program waits for the source to settle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SettleMode {
    /// A dwell of `dwell_s` seconds (`G4 P…` in LinuxCNC, `DWELL …` in AeroBasic).
    Dwell,
    /// An optional stop (`M1`): the program pauses only when the controller's optional-stop
    /// switch is on, so the operator can check the source and resume.
    OptionalStop,
    /// A program stop (`M0`): the program always pauses until the operator resumes it.
    Stop,
    /// No wait: the source settles faster than the rapid to the first path.
    None,
}

/// The `[settle]` table of a machine profile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settle {
    /// How to wait.
    pub mode: SettleMode,
    /// Length of the dwell (s), for [`SettleMode::Dwell`].
    pub dwell_s: f64,
}

impl Default for Settle {
    fn default() -> Self {
        Self {
            mode: SettleMode::Dwell,
            dwell_s: DEFAULT_DWELL_S,
        }
    }
}

impl Settle {
    /// Whether the program waits before an operation with set `next` that follows one with
    /// set `prev`: only when a laser parameter the source must settle at changes (power, pulse
    /// frequency, pulse width, wavelength), never before the first operation.
    pub fn needed(&self, prev: Option<&ProcessSet>, next: &ProcessSet) -> bool {
        if self.mode == SettleMode::None {
            return false;
        }
        prev.is_some_and(|p| {
            p.power_mw != next.power_mw
                || p.pulse_frequency_khz != next.pulse_frequency_khz
                || p.pulse_width_fs != next.pulse_width_fs
                || p.wavelength_nm != next.wavelength_nm
        })
    }

    /// The operations the program waits before, in program order: each of `operations` whose
    /// set (`set_of`) [needs](Settle::needed) a wait after the set of the one before it. The
    /// program header and the setup sheet both list these.
    pub fn waits_before<'p, T>(
        &self,
        operations: &'p [T],
        set_of: impl Fn(&T) -> &ProcessSet,
    ) -> Vec<&'p T> {
        operations
            .iter()
            .enumerate()
            .filter(|(i, op)| {
                let prev = i.checked_sub(1).map(|j| set_of(&operations[j]));
                self.needed(prev, set_of(op))
            })
            .map(|(_, op)| op)
            .collect()
    }

    /// Time the wait adds to an estimate (s): the dwell, 0 for stops (they last as long as
    /// the operator takes).
    pub fn estimated_s(&self) -> f64 {
        match self.mode {
            SettleMode::Dwell => self.dwell_s,
            _ => 0.0,
        }
    }

    /// What the program does, for headers and the setup sheet.
    pub fn describe(&self) -> String {
        match self.mode {
            SettleMode::Dwell => format!(
                "a dwell of {} s",
                crate::machine::format_number(self.dwell_s)
            ),
            SettleMode::OptionalStop => "an optional stop (M1)".into(),
            SettleMode::Stop => "a program stop (M0)".into(),
            SettleMode::None => "no wait".into(),
        }
    }

    /// Checks the dwell; `Err((value, limit))` names what is wrong.
    pub(crate) fn check(&self) -> Result<(), (String, String)> {
        if !(self.dwell_s.is_finite() && self.dwell_s > 0.0 && self.dwell_s <= MAX_DWELL_S) {
            return Err((
                self.dwell_s.to_string(),
                format!("must be finite, > 0 and at most {MAX_DWELL_S} s"),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(khz: f64, fs: f64) -> ProcessSet {
        ProcessSet {
            name: "s".into(),
            description: None,
            wavelength_nm: 1030.0,
            power_mw: 100.0,
            scan_speed_mm_s: 1.0,
            pulse_frequency_khz: khz,
            pulse_width_fs: fs,
            repetitions: 1,
            z_step_mm: None,
            min_wall_mm: crate::process::DEFAULT_MIN_WALL_MM,
        }
    }

    #[test]
    fn waits_only_when_the_laser_changes() {
        let s = Settle::default();
        let (a, b) = (set(200.0, 550.0), set(60.0, 215.0));
        assert!(!s.needed(None, &a), "never before the first operation");
        assert!(s.needed(Some(&a), &b));
        assert!(!s.needed(Some(&b), &b), "same set: nothing to settle");
        assert!(s.needed(Some(&a), &set(200.0, 215.0)), "width alone");
        let none = Settle {
            mode: SettleMode::None,
            ..Settle::default()
        };
        assert!(!none.needed(Some(&a), &b));
        assert_eq!(s.estimated_s(), DEFAULT_DWELL_S);
    }

    #[test]
    fn lists_the_operations_it_waits_before() {
        let (a, b) = (set(200.0, 550.0), set(60.0, 215.0));
        let sets = [a.clone(), b.clone(), b.clone(), a];
        let waits = Settle::default().waits_before(&sets, |s| s);
        let at: Vec<usize> = waits
            .iter()
            .map(|w| sets.iter().position(|s| std::ptr::eq(s, *w)).unwrap())
            .collect();
        assert_eq!(
            at,
            vec![1, 3],
            "not before the first, nor between equal sets"
        );
        let none = Settle {
            mode: SettleMode::None,
            ..Settle::default()
        };
        assert!(none.waits_before(&sets, |s| s).is_empty());
    }

    #[test]
    fn refuses_dwells_out_of_range() {
        for bad in [0.0, -1.0, f64::NAN, 601.0] {
            let s = Settle {
                dwell_s: bad,
                ..Settle::default()
            };
            assert!(s.check().is_err(), "{bad}");
        }
        assert!(Settle::default().check().is_ok());
    }
}
