//! Warnings on strain at the notch-closing angle.

use crate::design::Design;

use super::Warning;

/// Warns when the sensor strain at the notch-closing angle passes the sensor's saturation
/// strain, and when the backbone's peak strain there (at its farthest fibre, from the
/// mechanics) passes its limit, each with the angle at which the limit is reached.
pub(crate) fn check(design: &Design, out: &mut Vec<Warning>) {
    let joint = &design.joint;
    let mat = &design.file.materials;
    let closing_rad = joint.closing_angle_rad();
    let sensor = joint.strain_at_closing().abs();
    if sensor > mat.sensor_saturation_strain {
        out.push(Warning::SensorSaturates {
            strain_pct: sensor * 100.0,
            closing_deg: closing_rad.to_degrees(),
            limit_pct: mat.sensor_saturation_strain * 100.0,
            from_deg: joint
                .angle_at_strain(mat.sensor_saturation_strain)
                .abs()
                .to_degrees(),
        });
    }
    let mechanics = &design.mechanics;
    let backbone = mechanics.material_strain(closing_rad);
    if backbone > mat.backbone_strain_limit {
        out.push(Warning::BackboneStrain {
            strain_pct: backbone * 100.0,
            side: mechanics.farthest_fibre().1.describe(),
            closing_deg: closing_rad.to_degrees(),
            limit_pct: mat.backbone_strain_limit * 100.0,
            from_deg: mechanics
                .angle_at_material_strain_rad(mat.backbone_strain_limit)
                .to_degrees(),
        });
    }
}
