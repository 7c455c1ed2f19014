//! The joint length agrees with the notch pattern.

use crate::design::DesignFile;

use super::Violation;

/// How far `L` may differ from `N·h + (N−1)·c` (mm): 1 µm, absolute. Table I's lengths are
/// given to 0.01 mm and agree exactly; a real mismatch is a typo, far larger than this.
pub const LENGTH_TOLERANCE_MM: f64 = 1e-3;

/// `|L − (N·h + (N−1)·c)| ≤ 1 µm`.
pub(crate) fn check(file: &DesignFile, out: &mut Vec<Violation>) {
    let n = f64::from(file.notch_count);
    if n < 1.0 {
        return;
    }
    let expected_mm = n * file.notch_width_mm + (n - 1.0) * file.notch_spacing_mm;
    let length_mm = file.joint_length_mm;
    if expected_mm.is_finite()
        && length_mm.is_finite()
        && (length_mm - expected_mm).abs() > LENGTH_TOLERANCE_MM
    {
        out.push(Violation::Length {
            length_mm,
            expected_mm,
            tolerance_mm: LENGTH_TOLERANCE_MM,
        });
    }
}
