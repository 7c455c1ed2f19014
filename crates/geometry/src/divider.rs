use crate::error::{positive, GeometryError};

/// The voltage divider that reads a sensor: a fixed resistor `R_k` from the supply `V+` to the
/// output node, and the sensor from the output node to ground, so `V = V+·R/(R + R_k)` and
/// (Eq. 4) `R = R_k/((V+/V) − 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Divider {
    /// Fixed resistor `R_k` (Ω); the paper's bench uses 99.6 kΩ (102.5 kΩ for a second sensor).
    pub fixed_ohm: f64,
    /// Supply `V+` (V).
    pub supply_v: f64,
}

impl Divider {
    /// A divider with fixed resistor `R_k` and supply `V+`.
    ///
    /// # Errors
    /// Either value not finite or not positive.
    pub fn new(fixed_ohm: f64, supply_v: f64) -> Result<Self, GeometryError> {
        positive("divider_ohm", fixed_ohm)?;
        positive("supply_v", supply_v)?;
        Ok(Self {
            fixed_ohm,
            supply_v,
        })
    }

    /// Output voltage for a sensor resistance `R` (Ω).
    pub fn voltage(&self, resistance_ohm: f64) -> f64 {
        self.supply_v * resistance_ohm / (resistance_ohm + self.fixed_ohm)
    }

    /// Sensor resistance for an output voltage (Eq. 4).
    ///
    /// # Errors
    /// [`GeometryError::VoltageAtRail`] when the reading is not strictly between 0 and `V+`
    /// (or not a number): no finite, positive resistance explains it.
    pub fn resistance(&self, volts: f64) -> Result<f64, GeometryError> {
        if !(volts > 0.0 && volts < self.supply_v) {
            return Err(GeometryError::VoltageAtRail {
                volts,
                supply_v: self.supply_v,
            });
        }
        Ok(self.fixed_ohm / (self.supply_v / volts - 1.0))
    }

    /// `dV/dR` at sensor resistance `R` (V/Ω): `V+·R_k/(R + R_k)²`.
    pub fn slope_v_per_ohm(&self, resistance_ohm: f64) -> f64 {
        let total = resistance_ohm + self.fixed_ohm;
        self.supply_v * self.fixed_ohm / (total * total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn eq4_round_trips() {
        let d = Divider::new(99.6e3, 5.0).unwrap();
        for r in [1.0, 74.0e3, 215.0e3, 1.0e7] {
            assert_relative_eq!(d.resistance(d.voltage(r)).unwrap(), r, max_relative = 1e-12);
        }
    }

    #[test]
    fn rails_are_refused() {
        let d = Divider::new(99.6e3, 5.0).unwrap();
        for v in [0.0, -0.1, 5.0, 5.1, f64::NAN, f64::INFINITY] {
            assert!(d.resistance(v).is_err(), "{v}");
        }
    }

    #[test]
    fn slope_matches_finite_difference() {
        let d = Divider::new(99.6e3, 5.0).unwrap();
        let (r, dr) = (215.0e3, 1.0);
        let numeric = (d.voltage(r + dr) - d.voltage(r - dr)) / (2.0 * dr);
        assert_relative_eq!(d.slope_v_per_ohm(r), numeric, max_relative = 1e-8);
    }
}
