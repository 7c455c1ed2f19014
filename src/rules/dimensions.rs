//! Rules on plain dimensions: positive lengths, counts of at least one, cuts wider than the kerf.

use crate::design::DesignFile;

use super::Violation;

/// Every length, strain limit and optional clearance is a positive, finite number;
/// `1 ≤ N ≤ MAX_NOTCH_COUNT` and at least one pad turn; the notch width `h` and spacing `c` are larger than the kerf.
pub(crate) fn check(file: &DesignFile, out: &mut Vec<Violation>) {
    let fab = &file.fabrication;
    let mat = &file.materials;
    let mut positive = |name: &'static str, value: f64| {
        if !(value.is_finite() && value > 0.0) {
            out.push(Violation::NotPositive { name, value });
        }
    };
    positive("outer_radius_mm", file.outer_radius_mm);
    positive("inner_radius_mm", file.inner_radius_mm);
    positive("notch_arc_mm", file.notch_arc_mm);
    positive("notch_width_mm", file.notch_width_mm);
    positive("notch_spacing_mm", file.notch_spacing_mm);
    positive("joint_length_mm", file.joint_length_mm);
    positive("sensor_arc_mm", file.sensor_arc_mm);
    positive("trace_width_mm", fab.trace_width_mm);
    positive("kerf_mm", fab.kerf_mm);
    if let Some(c) = fab.clearance_mm {
        positive("clearance_mm", c);
    }
    positive("distal_margin_mm", fab.distal_margin_mm);
    positive("lead_length_mm", fab.lead_length_mm);
    positive("pad_pitch_mm", fab.pad_pitch_mm);
    positive("pad_gap_mm", fab.pad_gap_mm);
    positive("proximal_margin_mm", fab.proximal_margin_mm);
    positive("sensor_saturation_strain", mat.sensor_saturation_strain);
    positive("backbone_strain_limit", mat.backbone_strain_limit);
    if file.notch_count == 0 {
        out.push(Violation::Zero {
            name: "notch_count",
        });
    }
    if let Err(crate::design::DesignError::TooManyNotches { count, max, .. }) =
        file.check_notch_count()
    {
        out.push(Violation::TooMany {
            name: "notch_count",
            value: count,
            max,
        });
    }
    if fab.pad_turns == 0 {
        out.push(Violation::Zero { name: "pad_turns" });
    }
    let kerf_mm = fab.kerf_mm;
    if kerf_mm.is_finite() && kerf_mm > 0.0 {
        for (name, value_mm) in [
            ("notch_width_mm", file.notch_width_mm),
            ("notch_spacing_mm", file.notch_spacing_mm),
        ] {
            if value_mm > 0.0 && value_mm <= kerf_mm {
                out.push(Violation::NarrowerThanKerf {
                    name,
                    value_mm,
                    kerf_mm,
                });
            }
        }
    }
}
