//! What `dlw inspect` reports about a checked design: the section's planes (Eqs. 1-2), the strain
//! per degree (Eq. 3), where the notches close, and the tendon mechanics (`docs/mechanics.md`):
//! stroke per degree, the farthest fibre's strain and the angle at the material's limit, the
//! usable range, the notched section's second moment of area and the tendon force. The JSON
//! keys are part of the interface (`dlw inspect --json`, and `dlw.Design.geometry()` in Python);
//! `docs/mechanics.md` lists the mechanics keys.

use serde::Serialize;

use super::Checked;

/// A design's derived numbers.
#[derive(Debug, Clone, Serialize)]
pub struct Inspection {
    /// The design's name.
    pub name: String,
    /// UAN or BSN.
    pub style: dlw_geometry::NotchStyle,
    /// Neutral plane `ȳ` (mm).
    pub neutral_axis_mm: f64,
    /// Sensor plane `y_s` (mm).
    pub sensor_plane_mm: f64,
    /// `Δy = y_s − ȳ` (mm).
    pub offset_mm: f64,
    /// `ȳ` under the paper's symbol (mm), the same number as `neutral_axis_mm`.
    pub y_bar_mm: f64,
    /// `y_s` under the paper's symbol (mm), the same number as `sensor_plane_mm`.
    pub y_s_mm: f64,
    /// `Δy` under the paper's symbol (mm), the same number as `offset_mm`.
    pub delta_y_mm: f64,
    /// Strain per degree of bending (Eq. 3).
    pub strain_per_deg: f64,
    /// BSN: the offset between the two sensors' planes (mm).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub two_sensor_offset_mm: Option<f64>,
    /// Bending angle at which the notches close (°).
    pub closing_angle_deg: f64,
    /// Strain at that angle.
    pub strain_at_closing: f64,
    /// Notch-closing limit per notch, `h/(r_o + ȳ)` (°).
    pub closing_angle_per_notch_deg: f64,
    /// Tendon offset `r_t` from the tube axis (mm).
    pub tendon_offset_mm: f64,
    /// Tendon stroke that bends the straight joint by 1°, `(r_t + ȳ)·π/180` (mm).
    pub stroke_per_deg_mm: f64,
    /// The model's joint angle per mm of stroke (°/mm), the paper's `m_t` measured 35.49 °/mm on
    /// Joint D.
    pub deg_per_stroke_mm: f64,
    /// Tube material (`polyimide` or `nitinol`).
    pub tube_material: &'static str,
    /// Young's modulus of the tube material (Pa).
    pub youngs_modulus_pa: f64,
    /// Strain limit in force (`backbone_strain_limit`, the material's by default).
    pub material_strain_limit: f64,
    /// Distance from the neutral plane to the backbone's farthest fibre (mm).
    pub farthest_fibre_mm: f64,
    /// Where that fibre is: `backbone_crest`, `notch_inner_edge`, `notch_outer_edge` or
    /// `notch_corners`.
    pub farthest_fibre_side: dlw_geometry::FibreSide,
    /// Peak material strain per degree of joint angle.
    pub material_strain_per_deg: f64,
    /// Joint angle at which the farthest fibre reaches the material's strain limit (°).
    pub material_limit_deg: f64,
    /// Joint angle at which the sensor saturates (°).
    pub saturation_limit_deg: f64,
    /// Usable range: the least of notch closing, material limit and saturation (°).
    pub usable_range_deg: f64,
    /// What ends the usable range: `notch_closing`, `material` or `sensor_saturation`.
    pub range_limited_by: dlw_geometry::RangeLimit,
    /// Area of the notched section (mm²).
    pub section_area_mm2: f64,
    /// Second moment of area of the notched section about its neutral axis (mm⁴).
    pub second_moment_mm4: f64,
    /// Bending moment that holds the joint at 1° (N·mm).
    pub moment_per_deg_nmm: f64,
    /// Tendon force that holds the joint at 1° (N), friction ignored.
    pub tendon_force_per_deg_n: f64,
    /// The rules' warnings.
    pub warnings: Vec<String>,
}

impl Inspection {
    /// The numbers of `checked`.
    pub fn of(checked: &Checked) -> Self {
        let design = &checked.design;
        let joint = &design.joint;
        let section = joint.section();
        let mech = &design.mechanics;
        let mat = &design.file.materials;
        let e_pa = mat.youngs_modulus_pa();
        let (fibre_mm, fibre_side) = mech.farthest_fibre();
        let (range_rad, limited_by) =
            mech.usable_range_rad(mat.sensor_saturation_strain, mat.backbone_strain_limit);
        let one_deg_rad = 1f64.to_radians();
        Self {
            name: design.file.name.clone(),
            style: joint.style(),
            neutral_axis_mm: section.neutral_axis_mm(),
            sensor_plane_mm: section.sensor_plane_mm(),
            offset_mm: section.offset_mm(),
            y_bar_mm: section.neutral_axis_mm(),
            y_s_mm: section.sensor_plane_mm(),
            delta_y_mm: section.offset_mm(),
            strain_per_deg: joint.strain_per_deg(),
            two_sensor_offset_mm: section.two_sensor_offset_mm(),
            closing_angle_deg: joint.closing_angle_rad().to_degrees(),
            strain_at_closing: joint.strain_at_closing(),
            closing_angle_per_notch_deg: mech.closing_angle_per_notch_rad().to_degrees(),
            tendon_offset_mm: mech.tendon_offset_mm(),
            stroke_per_deg_mm: mech.stroke_per_deg_mm(),
            deg_per_stroke_mm: 1.0 / mech.stroke_per_deg_mm(),
            tube_material: mat.tube.name(),
            youngs_modulus_pa: e_pa,
            material_strain_limit: mat.backbone_strain_limit,
            farthest_fibre_mm: fibre_mm,
            farthest_fibre_side: fibre_side,
            material_strain_per_deg: mech.material_strain(one_deg_rad),
            material_limit_deg: mech
                .angle_at_material_strain_rad(mat.backbone_strain_limit)
                .to_degrees(),
            saturation_limit_deg: joint
                .angle_at_strain(mat.sensor_saturation_strain)
                .abs()
                .to_degrees(),
            usable_range_deg: range_rad.to_degrees(),
            range_limited_by: limited_by,
            section_area_mm2: mech.section_area_mm2(),
            second_moment_mm4: mech.second_moment_mm4(),
            moment_per_deg_nmm: mech.moment_nmm(one_deg_rad, e_pa),
            tendon_force_per_deg_n: mech.tendon_force_per_deg_n(e_pa),
            warnings: checked.warnings.iter().map(ToString::to_string).collect(),
        }
    }
}
