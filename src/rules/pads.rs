//! The square-spiral pads' pitch.

use core::f64::consts::PI;

use crate::design::DesignFile;

use super::Violation;

/// The pads fit round the tube: the `2k` pads of `k` sensors, each `2·turns·pitch` wide, with
/// `pad_gap_mm` between neighbours, `2k·(P + gap) ≤ 2π·r_o`. (Tighter placement problems are
/// left to the clearance rule, which sees the real positions.)
pub(crate) fn check_size(file: &DesignFile, out: &mut Vec<Violation>) {
    let fab = &file.fabrication;
    let ok = |v: f64| v.is_finite() && v > 0.0;
    if !(ok(fab.pad_pitch_mm) && ok(fab.pad_gap_mm) && ok(file.outer_radius_mm))
        || fab.pad_turns == 0
    {
        return;
    }
    let count = 2 * file.style.sensor_count();
    let size_mm = 2.0 * f64::from(fab.pad_turns) * fab.pad_pitch_mm;
    let circumference_mm = 2.0 * PI * file.outer_radius_mm;
    let max_mm = circumference_mm / f64::from(count) - fab.pad_gap_mm;
    if size_mm > max_mm {
        out.push(Violation::PadSize {
            turns: fab.pad_turns,
            pitch_mm: fab.pad_pitch_mm,
            size_mm,
            count,
            circumference_mm,
            max_mm,
        });
    }
}

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
