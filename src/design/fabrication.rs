//! The fabrication tables of a design file, each key with its documented default.

use serde::{Deserialize, Serialize};

use super::material::TubeMaterial;

/// Trace, pad, margin and cutting parameters (`[fabrication]`). Lengths in mm.
///
/// | key | default | meaning |
/// |---|---|---|
/// | `trace_width_mm` | 0.05 | width of one laser-written graphene line (sensor, leads, pads) |
/// | `kerf_mm` | 0.03 | width of material the cutting beam removes |
/// | `clearance_mm` | kerf + trace width | least gap between any trace and any notch, and between traces |
/// | `distal_margin_mm` | 1.0 | uncut tube between the distal end (x = 0) and the first notch; the sensor's bridge runs here |
/// | `lead_length_mm` | 1.0 | lead from the end of a sensor arm (half a distal margin past the last notch) to its pad |
/// | `pad_pitch_mm` | 0.1 | pitch of the square-spiral contact pads (≥ trace width) |
/// | `pad_turns` | 4 | turns of each square spiral |
/// | `pad_gap_mm` | 0.3 | gap between neighbouring pads along the circumference |
/// | `proximal_margin_mm` | 0.5 | uncut tube between the pads and the parting cut |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Fabrication {
    /// Width of one laser-written graphene line (mm).
    pub trace_width_mm: f64,
    /// Width of material the cutting beam removes (mm).
    pub kerf_mm: f64,
    /// Least gap between traces and notches and between traces (mm); `None` means kerf + trace
    /// width.
    pub clearance_mm: Option<f64>,
    /// Uncut tube between the distal end and the first notch (mm).
    pub distal_margin_mm: f64,
    /// Lead from the end of a sensor arm to its pad, along the tube (mm).
    pub lead_length_mm: f64,
    /// Pitch of the square-spiral contact pads (mm).
    pub pad_pitch_mm: f64,
    /// Turns of each square spiral.
    pub pad_turns: u32,
    /// Gap between neighbouring pads along the circumference (mm).
    pub pad_gap_mm: f64,
    /// Uncut tube between the pads and the parting cut (mm).
    pub proximal_margin_mm: f64,
}

impl Default for Fabrication {
    fn default() -> Self {
        Self {
            trace_width_mm: 0.05,
            kerf_mm: 0.03,
            clearance_mm: None,
            distal_margin_mm: 1.0,
            lead_length_mm: 1.0,
            pad_pitch_mm: 0.1,
            pad_turns: 4,
            pad_gap_mm: 0.3,
            proximal_margin_mm: 0.5,
        }
    }
}

impl Fabrication {
    /// The clearance in force: the set value, or kerf + trace width.
    pub fn clearance_mm(&self) -> f64 {
        self.clearance_mm
            .unwrap_or(self.kerf_mm + self.trace_width_mm)
    }
}

/// The tube's material and the limits on strain (`[materials]`), strains as fractions.
///
/// | key | default | source |
/// |---|---|---|
/// | `tube` | `"polyimide"` | the tube material, from the table in [`TubeMaterial`] (`"polyimide"` or `"nitinol"`) |
/// | `sensor_saturation_strain` | 0.02 | the paper's conclusion: saturation below 2 % strain |
/// | `backbone_strain_limit` | the tube material's strain limit (polyimide 0.03) | peak strain the backbone may take; set it to override the material's |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(from = "MaterialsFile")]
pub struct Materials {
    /// The tube material (Young's modulus and strain limit from its table entry). Not written
    /// when it is the default, so a design's canonical TOML (and checksum) is as before.
    #[serde(skip_serializing_if = "TubeMaterial::is_default")]
    pub tube: TubeMaterial,
    /// Strain at which the DLW sensor saturates.
    pub sensor_saturation_strain: f64,
    /// Peak backbone strain the tube may take: the file's value, or the material's limit.
    pub backbone_strain_limit: f64,
}

/// `[materials]` as written: the backbone limit may be left to the material.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialsFile {
    #[serde(default)]
    tube: TubeMaterial,
    #[serde(default = "default_saturation")]
    sensor_saturation_strain: f64,
    #[serde(default)]
    backbone_strain_limit: Option<f64>,
}

/// The paper's conclusion: the DLW sensor saturates below 2 % strain.
const DEFAULT_SENSOR_SATURATION_STRAIN: f64 = 0.02;

fn default_saturation() -> f64 {
    DEFAULT_SENSOR_SATURATION_STRAIN
}

impl From<MaterialsFile> for Materials {
    fn from(f: MaterialsFile) -> Self {
        Self {
            tube: f.tube,
            sensor_saturation_strain: f.sensor_saturation_strain,
            backbone_strain_limit: f
                .backbone_strain_limit
                .unwrap_or_else(|| f.tube.strain_limit()),
        }
    }
}

impl Default for Materials {
    fn default() -> Self {
        Self::from(MaterialsFile {
            tube: TubeMaterial::default(),
            sensor_saturation_strain: DEFAULT_SENSOR_SATURATION_STRAIN,
            backbone_strain_limit: None,
        })
    }
}

impl Materials {
    /// Young's modulus of the tube material (Pa).
    pub fn youngs_modulus_pa(&self) -> f64 {
        self.tube.youngs_modulus_pa()
    }
}

/// Which laser process parameter sets the design uses (`[process]`), by file stem under
/// `designs/process/`.
///
/// | key | default | the paper's Table II |
/// |---|---|---|
/// | `sensor` | `"sensor"` | column (a): 1030 nm, 160 mW, 1 mm/s, 200 kHz, 550 fs, 1 repetition |
/// | `notches` | `"notches"` | column (b): 1030 nm, 2 W, 25 mm/s, 60 kHz, 215 fs, 32 repetitions |
/// | `parting` | same as `notches` | the paper parts the joint with set (b) |
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProcessChoice {
    /// Parameter set for writing the sensor, leads and pads.
    pub sensor: String,
    /// Parameter set for cutting the notches.
    pub notches: String,
    /// Parameter set for the parting cut; `None` means the notch set.
    pub parting: Option<String>,
}

impl Default for ProcessChoice {
    fn default() -> Self {
        Self {
            sensor: "sensor".into(),
            notches: "notches".into(),
            parting: None,
        }
    }
}
