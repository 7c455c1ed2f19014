use dlw_geometry::{Divider, Joint};

use crate::config::{EstimatorConfig, ModelConfig, SensorConfig};
use crate::continuous_pi::ContinuousPiInverse;
use crate::divider::divider_resistance;
use crate::error::EstimatorError;
use crate::filter::Filter;
use crate::flags::Flags;
use crate::linear::LinearModel;
use crate::pi_model::PiInverse;

/// One sample's estimate. Always finite: a sample that cannot be used returns the last good
/// estimate with [`Flags::HELD`] and the reason.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Bending angle `θ` (rad), after the output filter.
    pub angle_rad: f64,
    /// Bending angle `θ` (degrees), after the output filter.
    pub angle_deg: f64,
    /// Strain of sensor 1 and sensor 2 (fractions), before the output filter; sensor 2's entry
    /// is 0 on a one-sensor estimator.
    pub strain: [f64; 2],
    /// Resistance of sensor 1 and sensor 2 (Ω), after the input filter; sensor 2's entry is 0
    /// on a one-sensor estimator.
    pub resistance_ohm: [f64; 2],
    /// What happened to this sample.
    pub flags: Flags,
}

impl Estimate {
    fn is_finite(&self) -> bool {
        self.angle_rad.is_finite()
            && self.angle_deg.is_finite()
            && self.strain.iter().all(|s| s.is_finite())
            && self.resistance_ohm.iter().all(|r| r.is_finite())
    }
}

/// A sensor's resistance-to-strain model, ready to run.
#[derive(Debug, Clone, PartialEq)]
enum Model {
    Linear(LinearModel),
    Pi(PiInverse),
    ContinuousPi(ContinuousPiInverse),
}

/// One sensor's divider, input filter and model.
#[derive(Debug, Clone, PartialEq)]
struct Channel {
    divider: Divider,
    filter: Filter,
    model: Model,
    nominal_ohm: f64,
}

impl Channel {
    fn new(config: &SensorConfig, filter: Filter) -> Result<Self, EstimatorError> {
        let (model, nominal_ohm) = match &config.model {
            ModelConfig::Linear(m) => {
                m.validate()?;
                (Model::Linear(*m), m.r0_ohm)
            }
            ModelConfig::Pi(m) => (Model::Pi(PiInverse::new(m)?), m.center_ohm),
            ModelConfig::ContinuousPi(m) => (
                Model::ContinuousPi(ContinuousPiInverse::new(m)?),
                m.center_ohm,
            ),
        };
        Ok(Self {
            divider: config.divider()?,
            filter,
            model,
            nominal_ohm,
        })
    }

    /// Voltage to (filtered) resistance, or the flags saying why there is none.
    #[inline]
    fn resistance(&self, volts: f64) -> Result<f64, Flags> {
        divider_resistance(&self.divider, volts)
    }

    /// Filtered resistance to strain.
    #[inline]
    fn strain(&mut self, ohm: f64) -> (f64, Flags) {
        match &mut self.model {
            Model::Linear(m) => (m.strain(ohm), Flags::empty()),
            Model::Pi(m) => m.step(ohm),
            Model::ContinuousPi(m) => m.step(ohm),
        }
    }

    fn reset(&mut self) {
        self.filter.reset();
        match &mut self.model {
            Model::Linear(_) => {}
            Model::Pi(m) => m.reset(),
            Model::ContinuousPi(m) => m.reset(),
        }
    }
}

/// Divider voltage(s) in, joint angle out: the runtime estimator.
///
/// Built from an [`EstimatorConfig`]; `step` (one sensor) or `step2` (both BSN sensors, Eq. 7)
/// once per sample. Per sample it reads the divider (Eq. 4), filters each resistance, runs each
/// sensor's model (Eq. 6 or Eqs. 12-14), turns strain into angle with the joint's geometry
/// (Eq. 3, or Eq. 7 for two sensors) and filters the angle.
///
/// It never allocates and never returns NaN or ∞. An `Estimator` holds up to three moving
/// average buffers inline (about 100 KiB); keep it in a `static` or a `Box` on small stacks.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimator {
    joint: Joint,
    /// `dθ/dε` of Eq. 3, asked of the joint once: the per-sample path does no trigonometry.
    angle_per_strain: f64,
    /// `dθ/d(ε₁ − ε₂)` of Eq. 7 (BSN only).
    angle_per_strain_difference: f64,
    first_sign: f64,
    first: Channel,
    second: Option<Channel>,
    output_filter: Filter,
    last: Estimate,
}

impl Estimator {
    /// An estimator for `config`.
    ///
    /// # Errors
    /// Whatever [`EstimatorConfig::validate`] refuses.
    pub fn new(config: &EstimatorConfig) -> Result<Self, EstimatorError> {
        let joint = config.validate()?;
        let first = Channel::new(&config.sensor, Filter::new(&config.input_filter)?)?;
        let second = match &config.second_sensor {
            Some(s) => Some(Channel::new(s, Filter::new(&config.input_filter)?)?),
            None => None,
        };
        let mut estimator = Self {
            joint,
            // Eqs. 3 and 6 are linear in strain, so their slopes are the geometry crate's own
            // answers at unit strain.
            angle_per_strain: joint.angle_from_strain(1.0),
            angle_per_strain_difference: joint.two_sensor_angle(1.0, 0.0).unwrap_or(0.0),
            first_sign: config.first_plane().sign(),
            first,
            second,
            output_filter: Filter::new(&config.output_filter)?,
            last: Estimate {
                angle_rad: 0.0,
                angle_deg: 0.0,
                strain: [0.0; 2],
                resistance_ohm: [0.0; 2],
                flags: Flags::empty(),
            },
        };
        estimator.reset();
        Ok(estimator)
    }

    /// The joint the angle is computed for.
    pub fn joint(&self) -> &Joint {
        &self.joint
    }

    /// Sensors configured (1 or 2).
    pub fn sensor_count(&self) -> usize {
        1 + usize::from(self.second.is_some())
    }

    /// Delay of a ramp through the input and output filters once settled (samples).
    pub fn delay_samples(&self) -> f64 {
        self.first.filter.delay_samples() + self.output_filter.delay_samples()
    }

    /// The last estimate returned (or the initial one: straight joint, nominal resistances).
    pub fn last(&self) -> &Estimate {
        &self.last
    }

    /// Estimates the angle from sensor 1's divider voltage alone (Eq. 3).
    ///
    /// On a two-sensor estimator this reads sensor 1 as if it were alone; sensor 2's filter
    /// and model do not advance.
    pub fn step(&mut self, volts: f64) -> Estimate {
        let ohm = match self.first.resistance(volts) {
            Ok(ohm) => self.first.filter.step(ohm),
            Err(flags) => return self.hold(flags),
        };
        let (strain, flags) = self.first.strain(ohm);
        // A sensor on −y_s reads −ε (Eq. 3 with −Δy).
        let angle = strain * self.first_sign * self.angle_per_strain;
        self.finish(angle, [strain, 0.0], [ohm, 0.0], flags)
    }

    /// Estimates the angle from both sensors' divider voltages (Eq. 7): `v1` from sensor 1
    /// (plane `+y_s`), `v2` from sensor 2 (plane `−y_s`).
    ///
    /// If either voltage is unusable the whole sample is held (and neither sensor's state
    /// advances). On a one-sensor estimator `v2` is ignored and this is [`Estimator::step`].
    pub fn step2(&mut self, v1: f64, v2: f64) -> Estimate {
        let Some(second) = self.second.as_mut() else {
            return self.step(v1);
        };
        let (r1, r2) = match (self.first.resistance(v1), second.resistance(v2)) {
            (Ok(r1), Ok(r2)) => (r1, r2),
            (Err(f1), Err(f2)) => return self.hold(f1 | f2),
            (Err(f), _) | (_, Err(f)) => return self.hold(f),
        };
        let (r1, r2) = (self.first.filter.step(r1), second.filter.step(r2));
        let (e1, f1) = self.first.strain(r1);
        let (e2, f2) = second.strain(r2);
        // A second channel exists only for BSN joints (validated), which have Δy^(1,2).
        let angle = (e1 - e2) * self.angle_per_strain_difference;
        self.finish(angle, [e1, e2], [r1, r2], f1 | f2)
    }

    /// Filters the angle, checks that everything is finite and remembers the estimate.
    #[inline]
    fn finish(
        &mut self,
        angle_rad: f64,
        strain: [f64; 2],
        ohm: [f64; 2],
        flags: Flags,
    ) -> Estimate {
        if flags.contains(Flags::HELD) {
            return self.hold(flags);
        }
        let angle_rad = self.output_filter.step(angle_rad);
        let estimate = Estimate {
            angle_rad,
            angle_deg: angle_rad.to_degrees(),
            strain,
            resistance_ohm: ohm,
            flags,
        };
        if !estimate.is_finite() {
            return self.hold(flags | Flags::NON_FINITE);
        }
        self.last = estimate;
        estimate
    }

    /// The last good estimate, flagged with why this sample was not used.
    #[cold]
    fn hold(&self, flags: Flags) -> Estimate {
        Estimate {
            flags: flags | Flags::HELD,
            ..self.last
        }
    }

    /// Returns every filter and model to its initial state and forgets past estimates.
    pub fn reset(&mut self) {
        self.first.reset();
        if let Some(second) = self.second.as_mut() {
            second.reset();
        }
        self.output_filter.reset();
        self.last = Estimate {
            angle_rad: 0.0,
            angle_deg: 0.0,
            strain: [0.0; 2],
            resistance_ohm: [
                self.first.nominal_ohm,
                self.second.as_ref().map_or(0.0, |s| s.nominal_ohm),
            ],
            flags: Flags::empty(),
        };
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::config::nominal_divider;
    use crate::FilterConfig;
    use approx::assert_relative_eq;
    use std::boxed::Box;

    use crate::table_one::{joint_a, joint_c};

    /// Joint A at 26° with Table II's linear model, through the divider and back.
    #[test]
    fn linear_joint_a_recovers_the_angle() {
        let config =
            EstimatorConfig::nominal_linear(joint_a(), 15.3, 215.0e3, nominal_divider()).unwrap();
        let mut est = Box::new(Estimator::new(&config).unwrap());
        let joint = joint_a().to_joint().unwrap();
        let model = LinearModel::new(15.3, 215.0e3).unwrap();
        for deg in [0.0, 5.0, 26.0, -3.0] {
            let r = model.resistance(joint.strain(f64::to_radians(deg)));
            let e = est.step(nominal_divider().voltage(r));
            assert!(e.flags.is_empty());
            assert_relative_eq!(e.angle_deg, deg, epsilon = 1e-9);
            assert_relative_eq!(e.angle_rad, deg.to_radians(), epsilon = 1e-11);
            assert_relative_eq!(e.resistance_ohm[0], r, max_relative = 1e-12);
        }
    }

    /// The precomputed slopes give the geometry crate's angles.
    #[test]
    fn angles_match_geometry() {
        for (config, e1, e2) in [(joint_a(), 0.0123, 0.0), (joint_c(), 0.004, -0.0031)] {
            let c = EstimatorConfig::nominal_linear(config, 1.0, 1.0, nominal_divider()).unwrap();
            let est = Box::new(Estimator::new(&c).unwrap());
            let joint = config.to_joint().unwrap();
            assert_relative_eq!(
                e1 * est.angle_per_strain,
                joint.angle_from_strain(e1),
                max_relative = 1e-15
            );
            if let Some(theta) = joint.two_sensor_angle(e1, e2) {
                assert_relative_eq!(
                    (e1 - e2) * est.angle_per_strain_difference,
                    theta,
                    max_relative = 1e-15
                );
            }
        }
    }

    /// Joint C with Table III's per-sensor models and unequal dividers (99.6 and 102.5 kΩ).
    #[test]
    fn two_sensors_use_eq6() {
        let (d1, d2) = (nominal_divider(), Divider::new(102.5e3, 5.0).unwrap());
        let (m1, m2) = (
            LinearModel::new(1.28, 74.0e3).unwrap(),
            LinearModel::new(0.68, 88.9e3).unwrap(),
        );
        let mut config = EstimatorConfig::nominal_linear(joint_c(), 1.0, 1.0, d1).unwrap();
        config.sensor = SensorConfig::new(d1, ModelConfig::Linear(m1));
        config.second_sensor = Some(SensorConfig::new(d2, ModelConfig::Linear(m2)));
        let mut est = Box::new(Estimator::new(&config).unwrap());
        assert_eq!(est.sensor_count(), 2);
        let joint = joint_c().to_joint().unwrap();
        let theta = 40f64.to_radians();
        let v1 = d1.voltage(m1.resistance(joint.strain(theta)));
        let v2 = d2.voltage(m2.resistance(-joint.strain(theta)));
        let e = est.step2(v1, v2);
        assert_relative_eq!(e.angle_rad, theta, max_relative = 1e-10);
        assert_relative_eq!(e.strain[0], -e.strain[1], max_relative = 1e-10);
        // Sensor 1 alone gives the same angle through Eq. 3.
        assert_relative_eq!(est.step(v1).angle_rad, theta, max_relative = 1e-10);
    }

    #[test]
    fn rails_hold_the_last_good_estimate() {
        let config =
            EstimatorConfig::nominal_linear(joint_c(), 1.28, 74.0e3, nominal_divider()).unwrap();
        let mut est = Box::new(Estimator::new(&config).unwrap());
        let initial = *est.last();
        assert_eq!(initial.resistance_ohm, [74.0e3, 74.0e3]);
        let held = est.step2(0.0, 2.0);
        assert_eq!(held.flags, Flags::RAIL | Flags::HELD);
        assert_eq!(held.angle_rad, 0.0);
        let good = est.step2(2.6, 2.4);
        assert!(good.flags.is_empty() && good.angle_rad != 0.0);
        let held = est.step2(2.6, f64::NAN);
        assert_eq!(held.flags, Flags::NON_FINITE | Flags::HELD);
        assert_eq!(held.angle_rad, good.angle_rad);
        assert_eq!(
            est.step2(f64::INFINITY, 5.0).flags,
            Flags::NON_FINITE | Flags::RAIL | Flags::HELD
        );
    }

    /// A computed value that overflows is held and flagged, not returned.
    #[test]
    fn overflow_is_held() {
        let mut config =
            EstimatorConfig::nominal_linear(joint_a(), 1e-300, 1e-300, nominal_divider()).unwrap();
        config.sensor.divider_ohm = 1e300;
        let mut est = Box::new(Estimator::new(&config).unwrap());
        let e = est.step(4.999);
        assert_eq!(e.flags, Flags::NON_FINITE | Flags::HELD);
        assert!(e.angle_rad.is_finite());
    }

    #[test]
    fn output_filter_delays_and_reset_forgets() {
        let mut config =
            EstimatorConfig::nominal_linear(joint_a(), 15.3, 215.0e3, nominal_divider()).unwrap();
        config.output_filter = FilterConfig::MovingAverage { samples: 3 };
        let mut est = Box::new(Estimator::new(&config).unwrap());
        assert_eq!(est.delay_samples(), 1.0);
        let d = nominal_divider();
        let v0 = d.voltage(215.0e3);
        let v1 = d.voltage(230.0e3);
        let first = est.step(v1).angle_rad;
        let second = est.step(v0).angle_rad;
        assert_relative_eq!(second, first / 2.0, max_relative = 1e-12);
        est.reset();
        assert_eq!(est.last().angle_rad, 0.0);
        assert_relative_eq!(est.step(v1).angle_rad, first, max_relative = 1e-12);
    }
}
