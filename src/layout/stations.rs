use crate::design::Design;

use super::error::{positive, LayoutError};

/// Where each feature sits along the tube (`x`, mm from the distal end), the layout's plan.
///
/// ```text
/// x = 0        bridge_x     first_notch_x            notched_end_x   arm_end_x   pad_x      parting_x
///  |  distal margin d       | N·h + (N−1)·c           | d/2 overrun   | lead      | pad P    | proximal
///  |----- d/2 -----|- d/2 --|------------------------|---------------|-----------|----------| margin
/// ```
///
/// The sensor arms overrun the notched section by `d/2` at both ends (the bridge sits `d/2`
/// before the first notch), so the gauge is centred on the notches. The joint length is
/// `d + (N·h + (N−1)·c) + d/2 + lead + P + proximal margin`, with `P = 2·turns·pitch` the pad
/// size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stations {
    /// Axial position of the sensor's distal bridge, `d/2` (mm).
    pub bridge_x_mm: f64,
    /// Distal edge of the first notch, `d` (mm).
    pub first_notch_x_mm: f64,
    /// Notch pitch along the tube, `h + c` (mm).
    pub notch_pitch_mm: f64,
    /// Proximal edge of the last notch, `d + N·h + (N−1)·c` (mm).
    pub notched_end_x_mm: f64,
    /// Where the sensor arms end and the leads begin (mm).
    pub arm_end_x_mm: f64,
    /// Distal edge of the pads, where the leads end (mm).
    pub pad_x_mm: f64,
    /// Side of one square-spiral pad, `2·turns·pitch`, centre line to centre line (mm).
    pub pad_size_mm: f64,
    /// The parting cut, the joint's total length (mm).
    pub parting_x_mm: f64,
}

impl Stations {
    /// The plan for a design.
    ///
    /// # Errors
    /// [`LayoutError`] when a fabrication length is not positive, the pads have no turns or
    /// are wider than the tube is round. (A `Design` never has more than
    /// [`crate::design::MAX_NOTCH_COUNT`] notches: `Design::from_file` checks it, once.)
    pub fn from_design(design: &Design) -> Result<Self, LayoutError> {
        let fab = &design.file.fabrication;
        let joint = &design.joint;
        let margin_mm = positive("distal_margin_mm", fab.distal_margin_mm)?;
        let lead_mm = positive("lead_length_mm", fab.lead_length_mm)?;
        let pitch_mm = positive("pad_pitch_mm", fab.pad_pitch_mm)?;
        let proximal_mm = positive("proximal_margin_mm", fab.proximal_margin_mm)?;
        if fab.pad_turns == 0 {
            return Err(LayoutError::NoPadTurns);
        }
        let pad_size_mm = 2.0 * f64::from(fab.pad_turns) * pitch_mm;
        let circumference_mm = joint.section().circumference_mm();
        if pad_size_mm >= circumference_mm {
            return Err(LayoutError::PadTooLarge {
                turns: fab.pad_turns,
                pitch_mm,
                size_mm: pad_size_mm,
                circumference_mm,
            });
        }
        let notched_end_x_mm = margin_mm + joint.notched_length_mm();
        let arm_end_x_mm = notched_end_x_mm + margin_mm / 2.0;
        let pad_x_mm = arm_end_x_mm + lead_mm;
        Ok(Self {
            bridge_x_mm: margin_mm / 2.0,
            first_notch_x_mm: margin_mm,
            notch_pitch_mm: joint.notch_width_mm() + joint.notch_spacing_mm(),
            notched_end_x_mm,
            arm_end_x_mm,
            pad_x_mm,
            pad_size_mm,
            parting_x_mm: pad_x_mm + pad_size_mm + proximal_mm,
        })
    }

    /// Distal edge of notch level `k` (0 at the distal end): `d + k·(h + c)`.
    pub fn notch_x_mm(&self, level: usize) -> f64 {
        self.first_notch_x_mm + level as f64 * self.notch_pitch_mm
    }
}
