//! The square-spiral pads' pitch.

use crate::design::DesignFile;

use super::Violation;

/// `pad_pitch_mm ≥ trace_width_mm`: neighbouring turns may touch (a pad is a contact area) but
/// a pitch below the line width writes each line over the last.
pub(crate) fn check(file: &DesignFile, out: &mut Vec<Violation>) {
    let fab = &file.fabrication;
    if fab.pad_pitch_mm > 0.0 && fab.trace_width_mm > 0.0 && fab.pad_pitch_mm < fab.trace_width_mm {
        out.push(Violation::Pitch {
            pitch_mm: fab.pad_pitch_mm,
            width_mm: fab.trace_width_mm,
        });
    }
}
