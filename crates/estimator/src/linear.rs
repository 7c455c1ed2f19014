use crate::error::{finite, positive, EstimatorError};

/// The linear gauge-factor model (Eqs. 5): `GF = (R − R₀)/(R₀·ε)`, so
/// `R = R₀·GF·ε + R₀` (forward) and `ε = (R − R₀)/(R₀·GF)` (inverse).
///
/// Strain is a fraction (0.01 is 1 %). A negative gauge factor (resistance falling with strain)
/// is allowed; zero is not, as the inverse would not exist.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct LinearModel {
    /// Gauge factor `GF` (dimensionless); the paper fits 15.3, 22.0 and 1.28 for Joints A-C.
    pub gauge_factor: f64,
    /// Unstrained resistance `R₀` (Ω).
    pub r0_ohm: f64,
}

impl LinearModel {
    /// A model with gauge factor `GF` and unstrained resistance `R₀`.
    ///
    /// # Errors
    /// `GF` not finite or zero; `R₀` not finite or not positive.
    pub fn new(gauge_factor: f64, r0_ohm: f64) -> Result<Self, EstimatorError> {
        let model = Self {
            gauge_factor,
            r0_ohm,
        };
        model.validate()?;
        Ok(model)
    }

    /// Checks a model built field by field (for instance, read from a config file).
    ///
    /// # Errors
    /// As [`LinearModel::new`].
    pub fn validate(&self) -> Result<(), EstimatorError> {
        if finite("gauge_factor", self.gauge_factor)? == 0.0 {
            return Err(EstimatorError::Zero {
                name: "gauge_factor",
            });
        }
        positive("r0_ohm", self.r0_ohm)?;
        Ok(())
    }

    /// Resistance at strain `ε` (Eq. 5, forward).
    #[inline]
    pub fn resistance(&self, strain: f64) -> f64 {
        self.r0_ohm * self.gauge_factor * strain + self.r0_ohm
    }

    /// Strain at resistance `R` (Eq. 5, inverse).
    #[inline]
    pub fn strain(&self, resistance_ohm: f64) -> f64 {
        (resistance_ohm - self.r0_ohm) / (self.r0_ohm * self.gauge_factor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use dlw_geometry::{CrossSection, Joint, NotchStyle};

    /// Table II's linear models and hand-computed resistances at 1 % strain.
    #[test]
    fn paper_models_at_one_percent() {
        let table = [
            (15.3, 215.0e3, 215.0e3 * 1.153), // Joint A
            (22.0, 77.2e3, 77.2e3 * 1.22),    // Joint B
            (1.28, 74.0e3, 74.0e3 * 1.0128),  // Joint C
        ];
        for (gf, r0, r_at_1pct) in table {
            let m = LinearModel::new(gf, r0).unwrap();
            assert_relative_eq!(m.resistance(0.01), r_at_1pct, max_relative = 1e-14);
            assert_relative_eq!(m.strain(r_at_1pct), 0.01, max_relative = 1e-12);
            assert_eq!(m.strain(r0), 0.0);
        }
    }

    #[test]
    fn inverse_round_trips() {
        let m = LinearModel::new(-2.0, 1.0e3).unwrap();
        for strain in [-0.3, -1e-6, 0.0, 0.0137, 0.4] {
            assert_relative_eq!(m.strain(m.resistance(strain)), strain, epsilon = 1e-15);
        }
    }

    /// Eq. 6 through geometry, with Table III's two linear models for Joint C: the sensor in
    /// tension (sensor 1, `+y_s`) and the one in compression (sensor 2, `−y_s`).
    #[test]
    fn two_sensor_angle_via_geometry() {
        let section = CrossSection::new(NotchStyle::Bsn, 0.8, 0.61, 1.65, 2.13).unwrap();
        let joint = Joint::new(section, 0.5, 0.5, 10, 9.5).unwrap();
        let tension = LinearModel::new(1.28, 74.0e3).unwrap();
        let compression = LinearModel::new(0.680, 88.9e3).unwrap();
        let theta = 40f64.to_radians();
        let (r1, r2) = (
            tension.resistance(joint.strain(theta)),
            compression.resistance(-joint.strain(theta)),
        );
        let angle = joint
            .two_sensor_angle(tension.strain(r1), compression.strain(r2))
            .unwrap();
        assert_relative_eq!(angle, theta, max_relative = 1e-12);
        // The paper's printed order (ε₂ − ε₁) gives the negated angle with this numbering.
        let printed = joint
            .two_sensor_angle(compression.strain(r2), tension.strain(r1))
            .unwrap();
        assert_relative_eq!(printed, -theta, max_relative = 1e-12);
    }

    #[test]
    fn refuses_bad_models() {
        assert_eq!(
            LinearModel::new(0.0, 1.0),
            Err(EstimatorError::Zero {
                name: "gauge_factor"
            })
        );
        assert!(LinearModel::new(f64::NAN, 1.0).is_err());
        assert!(LinearModel::new(1.0, 0.0).is_err());
        assert!(LinearModel::new(1.0, f64::INFINITY).is_err());
    }
}
