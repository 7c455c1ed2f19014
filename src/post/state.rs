//! What the controller has been told so far, so nothing is said twice.

use super::AxisWords;

/// The machine state as the program has set it: written positions, beam gate, laser commands.
///
/// Positions are the values as written (rounded to the post's decimals), so that feeds are
/// computed from exactly the coordinates the controller reads. `None` means unknown (program
/// start, or the top of a loop body whose iterations start from different places).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MachineState {
    /// Linear axis as written (mm).
    pub x: Option<f64>,
    /// Rotary axis as written (rotary units).
    pub a: Option<f64>,
    /// Focus axis as written (mm).
    pub z: Option<f64>,
    /// Whether the beam gate is open.
    pub beam_on: bool,
    /// The last lines written for each laser parameter (power, frequency, width, wavelength).
    pub laser: [Option<Vec<String>>; 4],
}

impl MachineState {
    /// The words that change to reach `target` (each already rounded); records the new position.
    pub fn words_to(&mut self, target: AxisWords) -> AxisWords {
        let mut words = AxisWords::default();
        if let Some(x) = target.x {
            if self.x != Some(x) {
                words.x = Some(x);
                self.x = Some(x);
            }
        }
        if let Some(a) = target.a {
            if self.a != Some(a) {
                words.a = Some(a);
                self.a = Some(a);
            }
        }
        if let Some(z) = target.z {
            if self.z != Some(z) {
                words.z = Some(z);
                self.z = Some(z);
            }
        }
        words
    }

    /// Forgets the position (top of a loop body, or after a variable focus move).
    pub fn forget_position(&mut self) {
        self.x = None;
        self.a = None;
    }

    /// Records a laser parameter's lines; true when they differ from what was last written.
    pub fn laser_changed(&mut self, which: usize, lines: &[String]) -> bool {
        let slot = &mut self.laser[which];
        if slot.as_deref() == Some(lines) {
            false
        } else {
            *slot = Some(lines.to_vec());
            true
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suppresses_unchanged_words_and_laser_lines() {
        let mut s = MachineState::default();
        let w = s.words_to(AxisWords {
            x: Some(1.0),
            a: Some(0.0),
            z: None,
        });
        assert_eq!((w.x, w.a), (Some(1.0), Some(0.0)));
        let w = s.words_to(AxisWords {
            x: Some(1.0),
            a: Some(2.0),
            z: None,
        });
        assert_eq!((w.x, w.a), (None, Some(2.0)));
        assert!(s.laser_changed(0, &["S160".into()]));
        assert!(!s.laser_changed(0, &["S160".into()]));
        assert!(s.laser_changed(0, &["S2000".into()]));
        s.forget_position();
        assert_eq!(
            s.words_to(AxisWords {
                x: Some(1.0),
                a: Some(2.0),
                z: None
            })
            .x,
            Some(1.0)
        );
    }
}
