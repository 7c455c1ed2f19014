//! What `dlw inspect` reports about a checked design: the section's planes (Eqs. 1-2), the strain
//! per degree (Eq. 3) and where the notches close. The JSON keys are part of the interface
//! (`dlw inspect --json`, and `dlw.Design.geometry()` in Python).

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
    /// The rules' warnings.
    pub warnings: Vec<String>,
}

impl Inspection {
    /// The numbers of `checked`.
    pub fn of(checked: &Checked) -> Self {
        let design = &checked.design;
        let joint = &design.joint;
        let section = joint.section();
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
            warnings: checked.warnings.iter().map(ToString::to_string).collect(),
        }
    }
}
