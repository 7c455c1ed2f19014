//! The bench, one sample at a time: stroke in, true angle, tracker angle and ADC voltages out.
//!
//! [`super::Plan::run`] drives it with a stroke profile; a controller (`dlw::control`) drives it
//! with the stroke it computes from the previous samples. Both go through this one copy of the
//! chain, so a closed-loop run sees exactly the plant, sensors, noise and draws a recording of
//! the same scenario and seed would.

use dlw_geometry::{Divider, Joint};

use super::correlated::Ar1;
use super::measure::{Adc, Tracker};
use super::plant::Plant;
use super::rng::{streams, Stream};
use super::scenario::{Scenario, ScenarioError};
use super::sensor::Sensor;
use super::SimError;

/// One sample of the bench.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// The true joint angle (rad).
    pub angle_rad: f64,
    /// The angle the EM tracker records (°): the true angle plus the tracker's noise.
    pub tracked_deg: f64,
    /// The recorded divider voltage of sensor 1 and sensor 2 (V); sensor 2's is 0 on a
    /// one-sensor joint.
    pub volts: [f64; 2],
}

/// One sensor's chain: sensor model, its temperature coefficient, divider, ADC.
#[derive(Debug, Clone)]
struct Channel {
    sensor: Sensor,
    tcr_per_k: f64,
    divider: Divider,
    adc: Adc,
}

/// The simulated bench for a resolved scenario: plant, sensors, dividers, ADC and tracker,
/// each with its own random stream.
#[derive(Debug, Clone)]
pub struct Bench {
    joint: Joint,
    plant: Plant,
    channels: Vec<Channel>,
    tracker: Tracker,
    /// The bench's temperature deviation (K), shared by the sensors, when `[temperature]` is on.
    temperature: Option<Ar1>,
    supply_v: f64,
}

impl Bench {
    /// The bench of `scenario` (resolved with [`Scenario::resolve`]) for `joint`.
    ///
    /// # Errors
    /// [`SimError::Scenario`] for sensor model parameters the estimator crate refuses.
    pub fn new(scenario: &Scenario, joint: &Joint) -> Result<Self, SimError> {
        let sc = scenario;
        let dt_s = 1.0 / sc.sample_hz;
        let channels = sc
            .sensors()
            .enumerate()
            .map(|(i, p)| {
                let i = i as u64;
                let drift = Stream::new(sc.seed, streams::DRIFT + i);
                let noise = Stream::new(sc.seed, streams::SENSOR_NOISE + i);
                Ok(Channel {
                    sensor: Sensor::new(p, i as usize + 1, dt_s, drift, noise)?,
                    tcr_per_k: p.tcr_per_k,
                    divider: Divider {
                        fixed_ohm: p.divider_ohm.unwrap_or(f64::NAN),
                        supply_v: sc.supply_v,
                    },
                    adc: Adc::for_channel(&sc.adc, sc.seed, i, dt_s),
                })
            })
            .collect::<Result<_, ScenarioError>>()?;
        Ok(Self {
            joint: *joint,
            plant: Plant::new(&sc.plant, joint, dt_s),
            channels,
            tracker: Tracker::for_seed(&sc.tracker, sc.seed, dt_s),
            temperature: sc.temperature.enabled.then(|| {
                let w = &sc.temperature;
                Ar1::new(
                    w.sigma_k,
                    w.tau_s,
                    dt_s,
                    Stream::new(sc.seed, streams::TEMPERATURE),
                )
            }),
            supply_v: sc.supply_v,
        })
    }

    /// Sensors on the bench (1 or 2), the recording's voltage columns.
    pub fn channels(&self) -> usize {
        self.channels.len()
    }

    /// Advances one sample at `time_s` with tendon stroke `stroke_mm`.
    ///
    /// # Errors
    /// [`SimError::Resistance`] when a sensor model leaves the physical range,
    /// [`SimError::Rail`] when a recorded voltage reaches a rail.
    #[inline]
    pub fn step(&mut self, time_s: f64, stroke_mm: f64) -> Result<Reading, SimError> {
        let angle_rad = self.plant.step(stroke_mm);
        self.read(time_s, angle_rad, |_| angle_rad)
    }

    /// Advances the plant alone one sample: the joint's angle (rad) at stroke `stroke_mm`. A
    /// robot's simulator ([`super::robot`]) adds the other tendons' bending to it, then calls
    /// [`Self::read`].
    #[inline]
    pub fn plant_step(&mut self, stroke_mm: f64) -> f64 {
        self.plant.step(stroke_mm)
    }

    /// The sensors, ADC and tracker at `time_s` for a joint at `angle_rad`, sensor `c` (0-based)
    /// reading the strain of the angle `sensed_rad(c)`: `angle_rad` itself on a joint alone, the
    /// mixed angle `Σ_j C[i][j]·θ_j` on a robot (`docs/robot-runtime.md`'s sensing model).
    ///
    /// # Errors
    /// As [`Self::step`].
    #[inline]
    pub fn read(
        &mut self,
        time_s: f64,
        angle_rad: f64,
        sensed_rad: impl Fn(usize) -> f64,
    ) -> Result<Reading, SimError> {
        let mut volts = [0.0; 2];
        let kelvin = self.temperature.as_mut().map_or(0.0, Ar1::next_value);
        for (c, ch) in self.channels.iter_mut().enumerate() {
            let strain = self.joint.strain(sensed_rad(c));
            let ohm = ch.sensor.step(strain) * (1.0 + ch.tcr_per_k * kelvin);
            if !(ohm.is_finite() && ohm > 0.0) {
                return Err(SimError::Resistance {
                    sensor: c + 1,
                    time_s,
                    ohm,
                    strain,
                });
            }
            let v = ch.adc.read(ch.divider.voltage(ohm));
            if !(v > 0.0 && v < self.supply_v) {
                return Err(SimError::Rail {
                    sensor: c + 1,
                    time_s,
                    volts: v,
                    supply_v: self.supply_v,
                });
            }
            volts[c] = v;
        }
        Ok(Reading {
            angle_rad,
            tracked_deg: self.tracker.read(angle_rad.to_degrees()),
            volts,
        })
    }
}
