//! Closed-loop control of a sensing joint on the simulated bench (the paper's Section IV-C,
//! Fig. 9, Fig. 10, Table VI).
//!
//! Two schemes drive the same bench (plant, sensors, noise and seed; `crate::sim::Bench`):
//!
//! ```text
//! open loop:    θ_d ─(1/m_t)─▶ s ─▶ bench ─▶ θ (tracker), V ─estimator─▶ θ_sensed (unused)
//! closed loop:  θ_d ─(1/m_t)─▶ s_ff ─(+)─▶ s ─▶ bench ─▶ θ (tracker), V ─estimator─▶ θ_sensed
//!               θ_d − θ_sensed ─PID─▶ u ──┘                                          │
//!                      ▲──────────────────────────────────────────────────────────────┘
//! ```
//!
//! - **Feed-forward** `s_ff = θ_d/m_t`: the paper's empirical stroke-angle model (Fig. 9 (b)),
//!   `m_t` = the scenario's nominal plant gain (`plant.gain_deg_per_mm`, the paper's
//!   35.49 °/mm by default) unless given.
//! - **PID correction** `u`: the runtime `dlw_estimator::Pid` on `θ_d − θ_sensed` (°), output in
//!   millimetres of stroke, added to the feed-forward. The paper does not say whether its PID
//!   output is the whole command or a correction; its Fig. 9 keeps the stroke model (b) in the
//!   closed loop, which only makes sense as feed-forward, so the PID corrects it. With the
//!   feed-forward the integral only has to hold the plant's deviation from `m_t` (relaxation,
//!   backlash), not the whole stroke, and the loop still tracks if the sensor fails to a
//!   constant. The correction is limited to `±max(peak |θ_d|/m_t, 0.1 mm)`, with clamping
//!   anti-windup.
//! - **Sensed angle**: the runtime `dlw_estimator::Estimator` built from the config file, fed the
//!   simulated ADC voltage(s), one sample behind the command (the DAQ delivers sample `i − 1`
//!   when stroke `i` is computed).
//!
//! **Stability.** The simulated plant has no actuator dynamics: the paper's low-level motor
//! control (Fig. 9 (c)) is taken as ideal, reaching each commanded stroke within the sample.
//! With the one-sample measurement delay, a proportional loop gain `K_p·m_t` at or above 1
//! (the paper's gains: 0.1 mm/° · 35.49 °/mm = 3.55) then makes the loop oscillate at the
//! sample rate and diverge, unless the sensed angle is filtered: a moving average of `N`
//! samples has no gain at that frequency, and the paper's estimation procedure filters
//! (Section IV-B). [`Control::new`] warns about an unfiltered config at such gains, and
//! [`Control::run`] about a correction that sat at its limit.
//!
//! [`Control::new`] validates everything; [`Control::run`] simulates both schemes and computes
//! Table VI ([`SchemeMetrics`]); [`ControlResult`] gathers both into the analysis `dlw control`
//! prints ([`crate::analysis::Analysis`]: its `--json`, its summary, its report section);
//! [`report`] draws `report.html`, its figures and `control.csv`.
//!
//! A robot's joints run the same scheme, each on its own tendon and its estimated angle from
//! the robot estimator, on the robot simulator's bench ([`robot`], [`RobotControlResult`]).

mod desired;
mod metrics;
pub mod report;
mod result;
pub mod robot;
mod robot_result;
mod scheme;

use std::path::PathBuf;

use dlw_estimator::{EstimatorConfig, EstimatorError, Pid, PidConfig};

use crate::design::Design;
use crate::replay::divider_warnings;
use crate::sim::{Scenario, SimError};

/// The desired angle: from a protocol or a CSV, sampled once per bench sample.
pub use desired::{Desired, DesiredSource};
/// Table VI's RMSEs per scheme, and the paper's values.
pub use metrics::{rmse, SchemeMetrics, PAPER_TABLE_VI};
/// A control simulation's result: JSON, summary and report section.
pub use result::{ControlResult, PaperRow, PaperTableVi};
/// A robot's control simulation's result: JSON, summary, CSV and report.
pub use robot_result::{JointControl, RobotControlResult};
/// The two schemes and what each did per sample.
pub use scheme::{Loop, Scheme, Trace};

/// The paper's PID gains (Section IV-C): `K_p` = 0.1 mm/°, `K_i` = 0.1 mm/(°·s), `K_d` = 0.
pub const PAPER_GAINS: Gains = Gains {
    kp_mm_per_deg: 0.1,
    ki_mm_per_deg_s: 0.1,
    kd_mm_s_per_deg: 0.0,
};

/// Smallest PID correction limit (mm), for a desired angle that hardly moves.
pub const MIN_CORRECTION_MM: f64 = 0.1;

/// Why a control simulation could not run.
#[derive(Debug, thiserror::Error)]
pub enum ControlError {
    /// The scenario, the protocol or the simulation was refused.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// Neither a desired profile nor a protocol was given.
    #[error("no desired angle: pass --profile FILE.csv (time_s,angle_deg) or --protocol NAME, or set protocol in the scenario")]
    NoDesired,
    /// Protocol `custom` without a stroke profile in the scenario.
    #[error("protocol custom needs a stroke profile in the scenario (protocols.custom.profile); for a desired-angle CSV pass --profile without --protocol")]
    CustomWithoutStroke,
    /// The desired profile could not be read.
    #[error("cannot read desired-angle profile {path}")]
    ProfileRead {
        /// The CSV file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The desired profile is malformed at one line.
    #[error("desired-angle profile {path} line {line}: {reason}")]
    Profile {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong, naming the value.
        reason: String,
    },
    /// The desired profile has no data rows.
    #[error("desired-angle profile {path} has no data rows (expected a header time_s,angle_deg and rows of numbers)")]
    ProfileEmpty {
        /// The CSV file.
        path: PathBuf,
    },
    /// The PID gains or limits were refused.
    #[error("PID gains: {0}")]
    Gains(EstimatorError),
    /// The estimator could not be built from the config.
    #[error("cannot build the estimator: {0}")]
    Estimator(EstimatorError),
    /// The config reads more sensors than the design carries.
    #[error("the estimator config reads {config} sensors but design {design:?} carries {carries} (its notch style is {style})")]
    SensorCount {
        /// Sensors in the config.
        config: u32,
        /// The design's name.
        design: String,
        /// Sensors the design carries.
        carries: usize,
        /// `uan` or `bsn`.
        style: &'static str,
    },
    /// The feed-forward slope is not a positive number.
    #[error("m_t = {value} °/mm must be finite and greater than 0")]
    Mt {
        /// The value given.
        value: f64,
    },
}

/// PID gains on the angle error (°) with the stroke correction (mm) as output.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Gains {
    /// `K_p` (mm/°).
    pub kp_mm_per_deg: f64,
    /// `K_i` (mm/(°·s)).
    pub ki_mm_per_deg_s: f64,
    /// `K_d` (mm·s/°), on the sensed angle.
    pub kd_mm_s_per_deg: f64,
}

/// Where `m_t` came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MtSource {
    /// The scenario's nominal plant gain, `plant.gain_deg_per_mm`.
    PlantGain,
    /// Given by the user (`--mt-deg-per-mm`).
    Given,
}

/// A validated control simulation: design, bench, estimator, PID and desired angle.
#[derive(Debug, Clone)]
pub struct Control {
    /// The design.
    pub design: Design,
    /// The desired angle and the resolved scenario.
    pub desired: Desired,
    /// The estimator config.
    pub config: EstimatorConfig,
    /// The PID gains (°, mm).
    pub gains: Gains,
    /// The PID as built: gains, `dt = 1/sample_hz`, correction limits.
    pub pid: PidConfig,
    /// Feed-forward slope (°/mm).
    pub mt_deg_per_mm: f64,
    /// Where `m_t` came from.
    pub mt_source: MtSource,
    /// Things the user should know (a divider or geometry that differs from the bench's).
    pub warnings: Vec<String>,
}

/// Both schemes' traces and Table VI.
#[derive(Debug, Clone)]
pub struct ControlRun {
    /// Open loop, then closed loop.
    pub traces: [Trace; 2],
    /// Their metrics, in the same order.
    pub metrics: [SchemeMetrics; 2],
    /// Things the user should know about the result (a saturated, diverging loop).
    pub warnings: Vec<String>,
}

impl Control {
    /// Validates and resolves a control simulation. `scenario` has the CLI's overrides
    /// (protocol, seed, duration) applied; `mt_deg_per_mm` overrides the plant gain as `m_t`.
    ///
    /// # Errors
    /// [`ControlError`] for any refused input, before anything runs.
    pub fn new(
        design: &Design,
        scenario: Scenario,
        source: &DesiredSource,
        config: EstimatorConfig,
        gains: Gains,
        mt_deg_per_mm: Option<f64>,
    ) -> Result<Self, ControlError> {
        let desired = Desired::resolve(design, scenario, source)?;
        let sc = &desired.scenario;
        let carries = sc.sensors().count();
        if config.sensor_count() as usize > carries {
            return Err(ControlError::SensorCount {
                config: config.sensor_count(),
                design: design.file.name.clone(),
                carries,
                style: match design.joint.style() {
                    dlw_geometry::NotchStyle::Uan => "uan",
                    dlw_geometry::NotchStyle::Bsn => "bsn",
                },
            });
        }
        dlw_estimator::Estimator::new(&config).map_err(ControlError::Estimator)?;
        let (mt, mt_source) = match mt_deg_per_mm {
            Some(v) => (v, MtSource::Given),
            None => (sc.plant.gain_deg_per_mm, MtSource::PlantGain),
        };
        if !(mt.is_finite() && mt > 0.0) {
            return Err(ControlError::Mt { value: mt });
        }
        let limit = (desired.peak_deg() / mt).max(MIN_CORRECTION_MM);
        let pid = PidConfig {
            kp: gains.kp_mm_per_deg,
            ki: gains.ki_mm_per_deg_s,
            kd: gains.kd_mm_s_per_deg,
            ..PidConfig::paper(1.0 / sc.sample_hz, limit)
        };
        Pid::new(&pid).map_err(ControlError::Gains)?;
        let mut warnings = Vec::new();
        if carries > 1 && config.second_sensor.is_none() {
            warnings.push(format!(
                "design {:?} carries {carries} sensors; the config reads only sensor 1",
                design.file.name
            ));
        }
        let dividers: Vec<f64> = sc
            .sensors()
            .map(|s| s.divider_ohm.unwrap_or(f64::NAN))
            .collect();
        warnings.extend(divider_warnings(
            &config,
            &dividers,
            sc.supply_v,
            "the scenario",
        ));
        let loop_gain = gains.kp_mm_per_deg * mt;
        let unfiltered = config.input_filter == dlw_estimator::FilterConfig::None
            && config.output_filter == dlw_estimator::FilterConfig::None;
        if unfiltered && loop_gain >= 1.0 {
            warnings.push(format!(
                "K_p·m_t = {loop_gain:.2} ≥ 1 with an unfiltered sensed angle: the simulated plant reaches \
                 each stroke within the sample, so with the one-sample measurement delay the loop \
                 oscillates and diverges; filter the sensed angle (e.g. --filter ma:50, as the \
                 paper's estimation procedure does) or lower K_p"
            ));
        }
        warnings.extend(crate::replay::geometry_warning(
            &config,
            design,
            &format!("design {:?}", design.file.name),
        ));
        Ok(Self {
            design: design.clone(),
            desired,
            config,
            gains,
            pid,
            mt_deg_per_mm: mt,
            mt_source,
            warnings,
        })
    }

    /// The loop of one scheme.
    pub fn scheme_loop(&self) -> Loop<'_> {
        Loop {
            scenario: &self.desired.scenario,
            joint: &self.design.joint,
            config: &self.config,
            pid: &self.pid,
            mt_deg_per_mm: self.mt_deg_per_mm,
            desired_deg: &self.desired.angle_deg,
        }
    }

    /// Simulates both schemes (from the same seed, so both see the same noise) and computes
    /// Table VI. A closed loop whose correction sat at a limit for more than a tenth of the
    /// samples gets a warning in [`ControlRun::warnings`].
    ///
    /// # Errors
    /// [`ControlError::Sim`] when a scheme drives a sensor out of its physical range.
    pub fn run(&self) -> Result<ControlRun, ControlError> {
        let l = self.scheme_loop();
        let traces = [l.run(Scheme::OpenLoop)?, l.run(Scheme::ClosedLoop)?];
        let metrics = [
            SchemeMetrics::of(&traces[0], &self.desired.angle_deg),
            SchemeMetrics::of(&traces[1], &self.desired.angle_deg),
        ];
        let mut warnings = Vec::new();
        let n = self.desired.angle_deg.len();
        let saturated = metrics[1].saturated_samples;
        if saturated * 10 > n {
            warnings.push(format!(
                "the closed loop's PID correction was at its limit (±{:.3} mm) for {saturated} of {n} samples: \
                 the loop is unstable or cannot reach the desired angle",
                self.pid.output_max
            ));
        }
        Ok(ControlRun {
            traces,
            metrics,
            warnings,
        })
    }
}

#[cfg(test)]
mod tests;
