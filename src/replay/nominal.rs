//! A joint's nominal linear estimator config from its design's geometry, before any
//! characterization (`dlw estimator-config DESIGN`): Eq. 5's model per sensor, the divider it is
//! read through, and the note the config file carries.

use dlw_estimator::{
    EstimatorConfig, EstimatorError, JointConfig, LinearModel, ModelConfig, SensorConfig,
};
use dlw_geometry::{Divider, GeometryError, NotchStyle};

use crate::design::Design;

/// One sensor's nominal numbers.
#[derive(Debug, Clone, Copy)]
pub struct NominalSensor {
    /// Gauge factor GF (Eq. 5).
    pub gauge_factor: f64,
    /// Unstrained resistance R0 (Ω).
    pub r0_ohm: f64,
    /// The divider's fixed resistor (Ω).
    pub divider_ohm: f64,
}

/// Why a nominal config could not be made.
#[derive(Debug, thiserror::Error)]
pub enum NominalError {
    /// Sensor 1's divider.
    #[error("divider")]
    Divider(#[source] GeometryError),
    /// Sensor 1's model.
    #[error("linear model")]
    Model(#[source] EstimatorError),
    /// Sensor 2's numbers were given for a UAN design.
    #[error("--second-* options need a BSN design, but {0:?} is UAN with one sensor")]
    SecondOnUan(String),
    /// Sensor 2's divider.
    #[error("sensor 2 divider")]
    SecondDivider(#[source] GeometryError),
    /// Sensor 2's model.
    #[error("sensor 2 linear model")]
    SecondModel(#[source] EstimatorError),
    /// The config with sensor 2 was refused.
    #[error("sensor 2")]
    Second(#[source] EstimatorError),
}

/// `design`'s nominal linear config: sensor 1 from `first`, and a BSN joint's sensor 2 from
/// `second` when given (a UAN joint refuses it), both read at `supply_v`. A BSN joint without
/// `second` has sensor 1 alone.
///
/// # Errors
/// [`NominalError`] naming the sensor and the part refused.
pub fn nominal_config(
    design: &Design,
    first: NominalSensor,
    second: Option<NominalSensor>,
    supply_v: f64,
) -> Result<EstimatorConfig, NominalError> {
    let divider = Divider::new(first.divider_ohm, supply_v).map_err(NominalError::Divider)?;
    let joint = JointConfig::from_joint(&design.joint);
    let mut config =
        EstimatorConfig::nominal_linear(joint, first.gauge_factor, first.r0_ohm, divider)
            .map_err(NominalError::Model)?;
    match (design.joint.style(), second) {
        (NotchStyle::Uan, Some(_)) => {
            return Err(NominalError::SecondOnUan(design.file.name.clone()))
        }
        (NotchStyle::Bsn, Some(s)) => {
            let divider =
                Divider::new(s.divider_ohm, supply_v).map_err(NominalError::SecondDivider)?;
            let model =
                LinearModel::new(s.gauge_factor, s.r0_ohm).map_err(NominalError::SecondModel)?;
            config.second_sensor = Some(SensorConfig::new(divider, ModelConfig::Linear(model)));
            config.validate().map_err(NominalError::Second)?;
        }
        _ => {}
    }
    Ok(config)
}

/// The note a nominal config carries; `more` (a robot's joint: what the config leaves out) on
/// the lines after it.
pub fn nominal_note(design: &Design, more: Option<&str>) -> String {
    let mut note = format!(
        "Nominal linear estimator config for {} (design checksum {}),\nwritten by dlw estimator-config before any characterization.",
        design.file.name, design.checksum
    );
    if let Some(extra) = more {
        note.push('\n');
        note.push_str(extra);
    }
    note
}
