use dlw_geometry::{CrossSection, Divider, GeometryError, Joint, NotchStyle};

use crate::continuous_pi::ContinuousPiConfig;
use crate::error::EstimatorError;
use crate::filter::FilterConfig;
use crate::linear::LinearModel;
use crate::pi_model::PiConfig;

/// Fixed divider resistor of the paper's bench, 99.6 kΩ (the CLI's default `--divider-ohm`).
pub const DEFAULT_DIVIDER_OHM: f64 = 99.6e3;
/// Divider supply of the paper's bench, 5 V (the CLI's default `--supply-v`).
pub const DEFAULT_SUPPLY_V: f64 = 5.0;

/// A joint's design parameters, as in the paper's Table I and the planner's design files.
///
/// Validated into a [`Joint`] when the estimator is built, with the same geometry code the
/// planner cuts it with.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct JointConfig {
    /// Notch style: `uan` (one sensor) or `bsn` (two sensors).
    pub style: NotchStyle,
    /// Outer radius `r_o` (mm).
    pub outer_radius_mm: f64,
    /// Inner radius `r_i` (mm).
    pub inner_radius_mm: f64,
    /// Arc of one notch on the outer surface `s_n` (mm).
    pub notch_arc_mm: f64,
    /// Notch width `h` along the tube (mm).
    pub notch_width_mm: f64,
    /// Uncut length `c` between notches (mm).
    pub notch_spacing_mm: f64,
    /// Notch count `N` (per side for BSN).
    pub notch_count: u32,
    /// Joint length `L`, the sensor's gauge length (mm).
    pub joint_length_mm: f64,
    /// Arc between the sensor's arms `s_s` (mm).
    pub sensor_arc_mm: f64,
}

impl JointConfig {
    /// The validated joint.
    ///
    /// # Errors
    /// Whatever [`CrossSection::new`] or [`Joint::new`] refuses.
    pub fn to_joint(&self) -> Result<Joint, GeometryError> {
        let section = CrossSection::new(
            self.style,
            self.outer_radius_mm,
            self.inner_radius_mm,
            self.notch_arc_mm,
            self.sensor_arc_mm,
        )?;
        Joint::new(
            section,
            self.notch_width_mm,
            self.notch_spacing_mm,
            self.notch_count,
            self.joint_length_mm,
        )
    }

    /// The parameters of an already validated joint (for instance, the planner's design).
    pub fn from_joint(joint: &Joint) -> Self {
        let s = joint.section();
        Self {
            style: s.style(),
            outer_radius_mm: s.outer_radius_mm(),
            inner_radius_mm: s.inner_radius_mm(),
            notch_arc_mm: s.notch_arc_mm(),
            notch_width_mm: joint.notch_width_mm(),
            notch_spacing_mm: joint.notch_spacing_mm(),
            notch_count: joint.notch_count(),
            joint_length_mm: joint.length_mm(),
            sensor_arc_mm: s.sensor_arc_mm(),
        }
    }
}

/// How a sensor's resistance becomes strain.
///
/// In TOML a table named after the kind: `[sensor.model.linear]`, `[sensor.model.pi]` or
/// `[sensor.model.continuous_pi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum ModelConfig {
    /// Linear gauge-factor model (Eqs. 5-6).
    Linear(LinearModel),
    /// The paper's generalized PI model with direction-switched tanh input (Eqs. 10-14).
    Pi(PiConfig),
    /// The continuous generalized PI model (envelopes inside the plays).
    ContinuousPi(ContinuousPiConfig),
}

impl ModelConfig {
    /// Checks the model's parameters.
    ///
    /// # Errors
    /// As the model's own `validate`.
    pub fn validate(&self) -> Result<(), EstimatorError> {
        match self {
            Self::Linear(m) => m.validate(),
            Self::Pi(m) => m.validate(),
            Self::ContinuousPi(m) => m.validate(),
        }
    }
}

/// The plane a sensor lies in, which fixes the sign of its strain (Eq. 3) and, in a bench
/// recording, its voltage column.
///
/// In files: `plus_ys` (sensor 1, stretched by a positive angle, recorded as `v1_V`) or
/// `minus_ys` (sensor 2 of a BSN joint, compressed by a positive angle: its strain is `−ε`,
/// recorded as `v2_V`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum SensorPlane {
    /// Plane `+y_s`: strain `+ε`.
    #[default]
    PlusYs,
    /// Plane `−y_s`: strain `−ε`.
    MinusYs,
}

impl SensorPlane {
    /// `+1` for `+y_s`, `−1` for `−y_s`: the sensor's strain is `sign·ε`.
    pub fn sign(self) -> f64 {
        match self {
            Self::PlusYs => 1.0,
            Self::MinusYs => -1.0,
        }
    }

    /// The 1-based voltage column a bench recording keeps this sensor in (`v1_V`, `v2_V`).
    pub fn column(self) -> u32 {
        match self {
            Self::PlusYs => 1,
            Self::MinusYs => 2,
        }
    }
}

/// One sensor: its divider, its model and the plane it reads.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct SensorConfig {
    /// Fixed divider resistor `R_k` (Ω) from the supply to the sensor's node.
    pub divider_ohm: f64,
    /// Divider supply `V+` (V).
    pub supply_v: f64,
    /// The plane the sensor lies in. Unset, it follows the sensor's place: `plus_ys` for
    /// `sensor`, `minus_ys` for `second_sensor`. A one-sensor config for a BSN joint's
    /// compression sensor says `minus_ys`: it reads `v2_V` and its strain is `−ε`.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub plane: Option<SensorPlane>,
    /// Resistance to strain.
    pub model: ModelConfig,
}

impl SensorConfig {
    /// A sensor read through `divider` with `model`.
    pub fn new(divider: Divider, model: ModelConfig) -> Self {
        Self {
            divider_ohm: divider.fixed_ohm,
            supply_v: divider.supply_v,
            plane: None,
            model,
        }
    }

    /// The validated divider.
    ///
    /// # Errors
    /// Either value not finite or not positive.
    pub fn divider(&self) -> Result<Divider, EstimatorError> {
        Ok(Divider::new(self.divider_ohm, self.supply_v)?)
    }

    /// The same sensor on another plane.
    pub fn on_plane(mut self, plane: SensorPlane) -> Self {
        self.plane = Some(plane);
        self
    }

    /// Checks the divider and the model.
    ///
    /// # Errors
    /// As [`SensorConfig::divider`] and [`ModelConfig::validate`].
    pub fn validate(&self) -> Result<(), EstimatorError> {
        self.divider()?;
        self.model.validate()
    }
}

/// Everything an [`crate::Estimator`] is built from.
///
/// `sensor` is sensor 1 (plane `+y_s`, stretched by a positive angle); `second_sensor`, only for
/// BSN joints, is sensor 2 (plane `−y_s`). Filters default to none.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct EstimatorConfig {
    /// Joint geometry.
    pub joint: JointConfig,
    /// Sensor 1.
    pub sensor: SensorConfig,
    /// Sensor 2 of a BSN joint; with it the angle comes from both (Eq. 7).
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub second_sensor: Option<SensorConfig>,
    /// Filter on each sensor's resistance, before the model.
    #[cfg_attr(feature = "serde", serde(default))]
    pub input_filter: FilterConfig,
    /// Filter on the angle, after the model.
    #[cfg_attr(feature = "serde", serde(default))]
    pub output_filter: FilterConfig,
}

impl EstimatorConfig {
    /// A linear-model configuration for a designed joint, as `dlw estimator-config` writes it:
    /// every sensor of the joint (one for UAN, both for BSN) gets gauge factor `GF`, unstrained
    /// resistance `R₀` and `divider` (see [`nominal_divider`] for the bench's 99.6 kΩ and 5 V),
    /// and no filters. Edit the file for per-sensor values.
    ///
    /// # Errors
    /// Anything [`EstimatorConfig::validate`] refuses.
    pub fn nominal_linear(
        joint: JointConfig,
        gauge_factor: f64,
        r0_ohm: f64,
        divider: Divider,
    ) -> Result<Self, EstimatorError> {
        let sensor = SensorConfig::new(
            divider,
            ModelConfig::Linear(LinearModel::new(gauge_factor, r0_ohm)?),
        );
        let config = Self {
            joint,
            sensor,
            second_sensor: (joint.style == NotchStyle::Bsn).then_some(sensor),
            input_filter: FilterConfig::None,
            output_filter: FilterConfig::None,
        };
        config.validate()?;
        Ok(config)
    }

    /// The plane `sensor` reads: its own `plane`, or `plus_ys`.
    pub fn first_plane(&self) -> SensorPlane {
        self.sensor.plane.unwrap_or(SensorPlane::PlusYs)
    }

    /// Number of sensors configured (1 or 2).
    pub fn sensor_count(&self) -> u32 {
        1 + u32::from(self.second_sensor.is_some())
    }

    /// Checks the whole configuration without building the estimator.
    ///
    /// # Errors
    /// The joint geometry, either sensor, either filter, or a second sensor on a UAN joint.
    pub fn validate(&self) -> Result<Joint, EstimatorError> {
        let joint = self.joint.to_joint()?;
        self.sensor.validate()?;
        if let Some(second) = &self.second_sensor {
            second.validate()?;
            let planes = (self.sensor.plane, second.plane);
            let plus = matches!(planes.0, None | Some(SensorPlane::PlusYs));
            let minus = matches!(planes.1, None | Some(SensorPlane::MinusYs));
            if !(plus && minus) {
                return Err(EstimatorError::SensorPlanes);
            }
        }
        let carries = joint.style().sensor_count();
        if self.sensor_count() > carries {
            return Err(EstimatorError::TooManySensors {
                configured: self.sensor_count(),
                joint_carries: carries,
            });
        }
        self.input_filter.validate()?;
        self.output_filter.validate()?;
        Ok(joint)
    }
}

/// The paper's bench divider: [`DEFAULT_DIVIDER_OHM`] from a [`DEFAULT_SUPPLY_V`] supply.
pub fn nominal_divider() -> Divider {
    Divider {
        fixed_ohm: DEFAULT_DIVIDER_OHM,
        supply_v: DEFAULT_SUPPLY_V,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::table_one::joint_a;

    #[test]
    fn joint_round_trips_through_geometry() {
        let joint = joint_a().to_joint().unwrap();
        assert_eq!(JointConfig::from_joint(&joint), joint_a());
    }

    #[test]
    fn nominal_linear_fills_every_sensor() {
        let uan =
            EstimatorConfig::nominal_linear(joint_a(), 15.3, 215.0e3, nominal_divider()).unwrap();
        assert_eq!(uan.sensor_count(), 1);
        assert_eq!(uan.sensor.divider_ohm, 99.6e3);
        assert_eq!(uan.sensor.supply_v, 5.0);
        let bsn_joint = JointConfig {
            style: NotchStyle::Bsn,
            outer_radius_mm: 0.8,
            inner_radius_mm: 0.61,
            notch_arc_mm: 1.65,
            sensor_arc_mm: 2.13,
            ..joint_a()
        };
        let bsn =
            EstimatorConfig::nominal_linear(bsn_joint, 1.28, 74.0e3, nominal_divider()).unwrap();
        assert_eq!(bsn.sensor_count(), 2);
        assert_eq!(bsn.second_sensor, Some(bsn.sensor));
    }

    #[test]
    fn refusals_name_the_part() {
        let d = nominal_divider();
        assert_eq!(
            EstimatorConfig::nominal_linear(joint_a(), 0.0, 1.0, d),
            Err(EstimatorError::Zero {
                name: "gauge_factor"
            })
        );
        let mut bad_joint = joint_a();
        bad_joint.notch_count = 0;
        assert_eq!(
            EstimatorConfig::nominal_linear(bad_joint, 1.0, 1.0, d),
            Err(EstimatorError::Geometry(GeometryError::NoNotches))
        );
        let mut c = EstimatorConfig::nominal_linear(joint_a(), 1.0, 1.0, d).unwrap();
        c.second_sensor = Some(c.sensor);
        assert_eq!(
            c.validate(),
            Err(EstimatorError::TooManySensors {
                configured: 2,
                joint_carries: 1
            })
        );
        let mut c = EstimatorConfig::nominal_linear(joint_a(), 1.0, 1.0, d).unwrap();
        c.sensor.supply_v = 0.0;
        assert!(matches!(c.validate(), Err(EstimatorError::Geometry(_))));
        let mut c = EstimatorConfig::nominal_linear(joint_a(), 1.0, 1.0, d).unwrap();
        c.output_filter = FilterConfig::MovingAverage { samples: 5000 };
        assert!(matches!(
            c.validate(),
            Err(EstimatorError::CountOutOfRange { value: 5000, .. })
        ));
    }
}
