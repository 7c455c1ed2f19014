//! One control scheme run on the simulated bench: open loop (feed-forward only) or closed loop
//! (feed-forward plus the runtime PID on the sensed angle).

use dlw_estimator::{Estimator, EstimatorConfig, Flags, Pid, PidConfig};

use dlw_geometry::Joint;

use super::ControlError;
use crate::sim::{Bench, Scenario};

/// The two schemes of the paper's Section IV-C.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// Stroke `s = θ_d/m_t`; the sensor is read but unused.
    OpenLoop,
    /// Stroke `s = θ_d/m_t + u`, `u` the PID's correction on `θ_d − θ_sensed`.
    ClosedLoop,
}

impl Scheme {
    /// Both, in the paper's order.
    pub const BOTH: [Self; 2] = [Self::OpenLoop, Self::ClosedLoop];

    /// Name in the report, the CSV and the JSON (`open_loop`, `closed_loop`).
    pub fn key(self) -> &'static str {
        match self {
            Self::OpenLoop => "open_loop",
            Self::ClosedLoop => "closed_loop",
        }
    }

    /// Name for people.
    pub fn title(self) -> &'static str {
        match self {
            Self::OpenLoop => "Open-loop control",
            Self::ClosedLoop => "Closed-loop control",
        }
    }
}

/// What one scheme did, per sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// The scheme.
    pub scheme: Scheme,
    /// The angle the EM tracker recorded (°), the paper's "actual" angle.
    pub actual_deg: Vec<f64>,
    /// The true angle (°), without tracker noise.
    pub true_deg: Vec<f64>,
    /// The runtime estimator's angle (°), the "sensed" angle.
    pub sensed_deg: Vec<f64>,
    /// The commanded tendon stroke (mm).
    pub stroke_mm: Vec<f64>,
    /// Samples the estimator held (a voltage it could not use).
    pub held_samples: usize,
    /// Samples at which the PID output was at a limit (closed loop only).
    pub saturated_samples: usize,
}

/// Everything a scheme run needs, already validated.
#[derive(Debug, Clone, Copy)]
pub struct Loop<'a> {
    /// The resolved scenario: the plant, sensors and noise.
    pub scenario: &'a Scenario,
    /// The joint.
    pub joint: &'a Joint,
    /// The estimator config.
    pub config: &'a EstimatorConfig,
    /// The PID (dt = 1/sample_hz).
    pub pid: &'a PidConfig,
    /// Stroke-to-angle slope of the feed-forward (°/mm).
    pub mt_deg_per_mm: f64,
    /// Desired angle per sample (°).
    pub desired_deg: &'a [f64],
}

impl Loop<'_> {
    /// Runs `scheme` from rest over every desired sample.
    ///
    /// Each sample `i` at `t = i/f_s`: the controller computes the stroke from `θ_d[i]` and the
    /// sensed angle of sample `i − 1` (the latest the DAQ has delivered; 0, a straight joint,
    /// before the first), the bench moves and reads, and the estimator turns the new voltage(s)
    /// into `θ_sensed[i]`.
    ///
    /// # Errors
    /// [`ControlError::Sim`] when the scenario drives a sensor out of the physical range;
    /// [`ControlError::Estimator`] or [`ControlError::Gains`] for a refused config.
    pub fn run(&self, scheme: Scheme) -> Result<Trace, ControlError> {
        let mut bench = Bench::new(self.scenario, self.joint)?;
        // About 100 KiB of filter buffers: on the heap.
        let mut estimator = Box::new(Estimator::new(self.config).map_err(ControlError::Estimator)?);
        let mut pid = Pid::new(self.pid).map_err(ControlError::Gains)?;
        let two = self.config.second_sensor.is_some();
        let hz = self.scenario.sample_hz;
        let inv_mt = 1.0 / self.mt_deg_per_mm;
        let n = self.desired_deg.len();
        let mut trace = Trace {
            scheme,
            actual_deg: Vec::with_capacity(n),
            true_deg: Vec::with_capacity(n),
            sensed_deg: Vec::with_capacity(n),
            stroke_mm: Vec::with_capacity(n),
            held_samples: 0,
            saturated_samples: 0,
        };
        let (lo, hi) = (self.pid.output_min, self.pid.output_max);
        let mut sensed = estimator.last().angle_deg;
        let mut out_of_range = false;
        for (i, &desired) in self.desired_deg.iter().enumerate() {
            let time_s = i as f64 / hz;
            let feed_forward = desired * inv_mt;
            let stroke = match scheme {
                Scheme::OpenLoop => feed_forward,
                Scheme::ClosedLoop => {
                    // At the end of its range the sensor cannot tell how far beyond the
                    // joint is: the integral holds (`Pid::step_out_of_range`).
                    let u = if out_of_range {
                        pid.step_out_of_range(desired, sensed)
                    } else {
                        pid.step(desired, sensed)
                    };
                    trace.saturated_samples += usize::from(u <= lo || u >= hi);
                    feed_forward + u
                }
            };
            let reading = bench.step(time_s, stroke)?;
            let estimate = if two {
                estimator.step2(reading.volts[0], reading.volts[1])
            } else {
                estimator.step(reading.volts[0])
            };
            sensed = estimate.angle_deg;
            out_of_range = estimate
                .flags
                .intersects(Flags::RESISTANCE_CLAMPED | Flags::ATANH_CLAMPED);
            trace.held_samples += usize::from(estimate.flags.contains(Flags::HELD));
            trace.actual_deg.push(reading.tracked_deg);
            trace.true_deg.push(reading.angle_rad.to_degrees());
            trace.sensed_deg.push(sensed);
            trace.stroke_mm.push(stroke);
        }
        Ok(trace)
    }
}
