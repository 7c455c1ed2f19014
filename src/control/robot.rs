//! Closed-loop control of a robot's joints on the simulated robot (issue 34 §4, `dlw control
//! --design ROBOT --config ROBOT_CFG`): each joint runs the joint's scheme ([`super::Scheme`]:
//! feed-forward `θ_d/m_t` plus the runtime PID's correction on `θ_d − θ_sensed`) on its own
//! tendon, and every joint's sensed angle comes from one runtime [`RobotEstimator`] fed every
//! sensor's voltage.
//!
//! ```text
//!  θ_d,j ─(1/m_t)─▶ s_ff,j ─(+)─▶ s_j ─▶ robot bench ─▶ θ (tracker), V_1…V_M
//!  θ_d,j − θ_sensed,j ─PID_j─▶ u_j ┘     (coupling,          │
//!        ▲                                crosstalk)         ▼
//!        └──────────── θ_sensed,1…N ◀── RobotEstimator (each model inverted, C undone)
//! ```
//!
//! The bench is [`crate::sim::robot::RobotBench`], the one `dlw simulate --design ROBOT` records
//! with: every joint's plant, the York/Swaney tendon coupling (switchable) and each sensor's
//! crosstalk, with the scenario's effects and noise and each joint's seed
//! (`seed + 7919·(K − 1)`). So a distal joint's tendon bends the proximal joints, which their
//! feed-forward does not know: their PID takes it out. Each joint's correction limit therefore
//! covers its own peak plus the coupling's share of the distal joints' peaks. The estimator
//! undoes the crosstalk with the config's matrix; a config with `C = I` closes each loop on its
//! sensor's mixed angle, and the joint then tracks `θ_d − Σ_{m≠j} C[j][m]·θ_m`.

use std::path::PathBuf;

use dlw_estimator::{
    FilterConfig, Flags, Pid, PidConfig, RobotError, RobotEstimator, RobotEstimatorConfig,
};

use crate::design::Design;
use crate::robot::CheckedRobot;
use crate::sim::robot::{Coupling, CouplingMatrix, RobotBench, RobotSimError, JOINT_SEED_STEP};
use crate::sim::Scenario;

use super::{
    ControlError, Desired, DesiredSource, Gains, MtSource, Scheme, SchemeMetrics, Trace,
    MIN_CORRECTION_MM,
};

/// Why a robot's control simulation could not run.
#[derive(Debug, thiserror::Error)]
pub enum RobotControlError {
    /// A joint's desired angle, scenario or PID was refused.
    #[error("joint {joint}: {source}")]
    Joint {
        /// 1-based joint.
        joint: usize,
        /// What the joint's control said.
        source: ControlError,
    },
    /// Desired-angle profiles given neither once nor once per joint.
    #[error("--profile is given {given} times; the robot has {joints} joints: give it once for every joint, or once per joint (joint 1, the distal one, first)")]
    Profiles {
        /// Profiles given.
        given: usize,
        /// Joints in the robot.
        joints: usize,
    },
    /// The config is for another robot.
    #[error("the estimator config is for {config_joints} joints and {config_sensors} sensors; robot {robot:?} has {joints} joints and {sensors} sensors")]
    Shape {
        /// Joints in the config.
        config_joints: usize,
        /// Sensors in the config.
        config_sensors: usize,
        /// The robot's name.
        robot: String,
        /// Joints in the robot.
        joints: usize,
        /// Sensors in the robot.
        sensors: usize,
    },
    /// The config's sensor `index` is not the robot's.
    #[error("the estimator config's sensor {index} is joint {config_joint} sensor {config_sensor}; robot {robot:?}'s sensor {index} is joint {joint} sensor {sensor} (dlw inspect's order)")]
    SensorOrder {
        /// 1-based sensor.
        index: usize,
        /// The config's joint (1-based).
        config_joint: u32,
        /// The config's sensor within its joint (1-based).
        config_sensor: u32,
        /// The robot's name.
        robot: String,
        /// The robot's joint (1-based).
        joint: usize,
        /// The robot's sensor within its joint (1-based).
        sensor: usize,
    },
    /// The runtime refused the config.
    #[error("cannot build the robot estimator: {0}")]
    Estimator(RobotError),
    /// The robot's bench refused a joint, or a joint's sensor left the physical range.
    #[error(transparent)]
    Sim(#[from] RobotSimError),
    /// The feed-forward slope is not a positive number.
    #[error("m_t = {value} °/mm must be finite and greater than 0")]
    Mt {
        /// The value given.
        value: f64,
    },
}

/// One joint of a validated robot control simulation.
#[derive(Debug, Clone)]
pub struct ControlledJoint {
    /// The joint's design.
    pub design: Design,
    /// Its desired angle and its resolved scenario (its own seed).
    pub desired: Desired,
    /// Its PID: gains, `dt`, correction limits.
    pub pid: PidConfig,
    /// Its feed-forward slope (°/mm).
    pub mt_deg_per_mm: f64,
}

/// A validated robot control simulation.
#[derive(Debug, Clone)]
pub struct RobotControl {
    /// The robot's name.
    pub robot: String,
    /// Its joints, joint 1 (distal) first.
    pub joints: Vec<ControlledJoint>,
    /// The estimator config every loop senses through.
    pub config: RobotEstimatorConfig,
    /// The PID gains, the same for every joint (°, mm).
    pub gains: Gains,
    /// Where `m_t` came from.
    pub mt_source: MtSource,
    /// The crosstalk the simulated sensors read (one row per sensor), the robot's geometry's.
    /// Public so that a study can give the plant another matrix than the config undoes.
    pub crosstalk: Vec<Vec<f64>>,
    /// Each sensor's joint and its number within the joint (0-based).
    pub sensors: Vec<(usize, usize)>,
    /// The tendon coupling.
    pub coupling: Coupling,
    /// Its coefficients.
    pub coefficients: CouplingMatrix,
    /// Things the user should know.
    pub warnings: Vec<String>,
}

/// What one scheme did on every joint.
#[derive(Debug, Clone)]
pub struct RobotTrace {
    /// The scheme.
    pub scheme: Scheme,
    /// Each joint's trace, joint 1 first.
    pub joints: Vec<Trace>,
}

/// Both schemes' traces and each joint's metrics.
#[derive(Debug, Clone)]
pub struct RobotControlRun {
    /// Open loop, then closed loop.
    pub traces: [RobotTrace; 2],
    /// Each joint's metrics: open loop, then closed loop.
    pub metrics: Vec<[SchemeMetrics; 2]>,
    /// Things the user should know about the result (a saturated loop).
    pub warnings: Vec<String>,
}

impl RobotControl {
    /// Validates and resolves a robot's control simulation. `scenario` has the CLI's overrides
    /// applied; joint `K` runs it with seed `seed + 7919·(K − 1)` and joint 1's duration.
    /// `profiles` are the desired-angle CSVs: none (the protocol), one for every joint, or one
    /// per joint.
    ///
    /// # Errors
    /// [`RobotControlError`] for any refused input, before anything runs.
    pub fn new(
        robot: &CheckedRobot,
        scenario: Scenario,
        profiles: &[PathBuf],
        config: RobotEstimatorConfig,
        gains: Gains,
        mt_deg_per_mm: Option<f64>,
        coupling: Coupling,
    ) -> Result<Self, RobotControlError> {
        let name = robot.robot.name.clone();
        let designs: Vec<&Design> = robot.robot.joints.iter().map(|j| j.design()).collect();
        let n = designs.len();
        let sensors: Vec<(usize, usize)> = robot
            .robot
            .sensors()
            .iter()
            .map(|s| (s.joint, s.sensor))
            .collect();
        check_shape(&config, &name, n, &sensors)?;
        let sources: Vec<DesiredSource> = match profiles.len() {
            0 => vec![DesiredSource::Protocol; n],
            1 => vec![DesiredSource::Csv(profiles[0].clone()); n],
            k if k == n => profiles.iter().cloned().map(DesiredSource::Csv).collect(),
            given => return Err(RobotControlError::Profiles { given, joints: n }),
        };
        let mut desired: Vec<Desired> = Vec::with_capacity(n);
        for (j, (design, source)) in designs.iter().zip(&sources).enumerate() {
            let mut sc = scenario.clone();
            sc.seed = scenario
                .seed
                .wrapping_add(JOINT_SEED_STEP * j as u64)
                .min(i64::MAX as u64);
            if let Some(first) = desired.first() {
                sc.duration_s = first.scenario.duration_s;
            }
            let d = Desired::resolve(design, sc, source).map_err(|source| {
                RobotControlError::Joint {
                    joint: j + 1,
                    source,
                }
            })?;
            desired.push(d);
        }
        RobotEstimator::new(&config).map_err(RobotControlError::Estimator)?;
        let coefficients = CouplingMatrix::of(robot, coupling);
        let peaks: Vec<f64> = desired.iter().map(Desired::peak_deg).collect();
        let mut joints = Vec::with_capacity(n);
        let mut warnings = Vec::new();
        let mt_source = match mt_deg_per_mm {
            Some(_) => MtSource::Given,
            None => MtSource::PlantGain,
        };
        for (p, (design, d)) in designs.iter().zip(desired).enumerate() {
            let mt = mt_deg_per_mm.unwrap_or(d.scenario.plant.gain_deg_per_mm);
            if !(mt.is_finite() && mt > 0.0) {
                return Err(RobotControlError::Mt { value: mt });
            }
            // The correction must be able to take out the distal tendons' bending too.
            let coupled_deg: f64 = (0..p)
                .map(|j| {
                    coefficients.positive[p][j]
                        .abs()
                        .max(coefficients.negative[p][j].abs())
                        * peaks[j]
                })
                .sum();
            let limit = ((peaks[p] + coupled_deg) / mt).max(MIN_CORRECTION_MM);
            let pid = PidConfig {
                kp: gains.kp_mm_per_deg,
                ki: gains.ki_mm_per_deg_s,
                kd: gains.kd_mm_s_per_deg,
                ..PidConfig::paper(1.0 / d.scenario.sample_hz, limit)
            };
            Pid::new(&pid).map_err(|e| RobotControlError::Joint {
                joint: p + 1,
                source: ControlError::Gains(e),
            })?;
            let loop_gain = gains.kp_mm_per_deg * mt;
            let unfiltered = config.input_filter == FilterConfig::None
                && config.output_filter == FilterConfig::None;
            if unfiltered && loop_gain >= 1.0 {
                warnings.push(format!(
                    "joint {}: K_p·m_t = {loop_gain:.2} ≥ 1 with an unfiltered sensed angle: with the one-sample \
                     measurement delay the loop oscillates and diverges; filter the sensed angle (e.g. --filter ma:50) \
                     or lower K_p",
                    p + 1
                ));
            }
            joints.push(ControlledJoint {
                design: (*design).clone(),
                desired: d,
                pid,
                mt_deg_per_mm: mt,
            });
        }
        warnings.extend(divider_warnings(&config, &joints, &sensors));
        warnings.dedup();
        Ok(Self {
            robot: name,
            joints,
            config,
            gains,
            mt_source,
            crosstalk: robot.crosstalk_matrix(),
            sensors,
            coupling,
            coefficients,
            warnings,
        })
    }

    /// Samples per scheme (joint 1's).
    pub fn samples(&self) -> usize {
        self.joints[0].desired.angle_deg.len()
    }

    /// The bench's sample rate (Hz), joint 1's.
    pub fn sample_hz(&self) -> f64 {
        self.joints[0].desired.scenario.sample_hz
    }

    /// Runs `scheme` on every joint from rest. Each sample `i` at `t = i/f_s`: each joint's
    /// controller computes its stroke from its `θ_d[i]` and its sensed angle of sample `i − 1`
    /// (straight before the first), the robot moves and reads, and the estimator turns every
    /// voltage into every joint's `θ_sensed[i]`.
    ///
    /// # Errors
    /// [`RobotControlError::Sim`] when a joint's sensor leaves the physical range.
    pub fn run_scheme(&self, scheme: Scheme) -> Result<RobotTrace, RobotControlError> {
        let n = self.joints.len();
        let rows = self.samples();
        let hz = self.sample_hz();
        let benches: Vec<(&Scenario, &dlw_geometry::Joint)> = self
            .joints
            .iter()
            .map(|j| (&j.desired.scenario, &j.design.joint))
            .collect();
        let mut bench =
            RobotBench::new(&benches, &self.crosstalk, &self.sensors, &self.coefficients)?;
        let mut estimator =
            Box::new(RobotEstimator::new(&self.config).map_err(RobotControlError::Estimator)?);
        let mut pids = self
            .joints
            .iter()
            .enumerate()
            .map(|(j, c)| {
                Pid::new(&c.pid).map_err(|e| RobotControlError::Joint {
                    joint: j + 1,
                    source: ControlError::Gains(e),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut traces: Vec<Trace> = (0..n)
            .map(|_| Trace {
                scheme,
                actual_deg: Vec::with_capacity(rows),
                true_deg: Vec::with_capacity(rows),
                sensed_deg: Vec::with_capacity(rows),
                stroke_mm: Vec::with_capacity(rows),
                held_samples: 0,
                saturated_samples: 0,
            })
            .collect();
        let mut sensed = vec![0.0; n];
        let mut out_of_range = vec![false; n];
        let mut stroke = vec![0.0; n];
        for i in 0..rows {
            for (j, c) in self.joints.iter().enumerate() {
                let desired = c.desired.angle_deg[i];
                let feed_forward = desired / c.mt_deg_per_mm;
                stroke[j] = match scheme {
                    Scheme::OpenLoop => feed_forward,
                    Scheme::ClosedLoop => {
                        let u = if out_of_range[j] {
                            pids[j].step_out_of_range(desired, sensed[j])
                        } else {
                            pids[j].step(desired, sensed[j])
                        };
                        traces[j].saturated_samples +=
                            usize::from(u <= c.pid.output_min || u >= c.pid.output_max);
                        feed_forward + u
                    }
                };
            }
            bench.step(i as f64 / hz, &stroke)?;
            let estimate = estimator.step(&bench.volts);
            for (j, trace) in traces.iter_mut().enumerate() {
                let flags = estimate.flags()[j];
                sensed[j] = estimate.angle_deg(j);
                out_of_range[j] =
                    flags.intersects(Flags::RESISTANCE_CLAMPED | Flags::ATANH_CLAMPED);
                trace.held_samples += usize::from(flags.contains(Flags::HELD));
                trace.actual_deg.push(bench.tracked_deg[j]);
                trace.true_deg.push(bench.angle_rad[j].to_degrees());
                trace.sensed_deg.push(sensed[j]);
                trace.stroke_mm.push(stroke[j]);
            }
        }
        Ok(RobotTrace {
            scheme,
            joints: traces,
        })
    }

    /// Simulates both schemes (from the same seeds, so both see the same noise) and computes
    /// each joint's metrics; a joint whose closed-loop correction sat at its limit for more than
    /// a tenth of the samples gets a warning.
    ///
    /// # Errors
    /// As [`Self::run_scheme`].
    pub fn run(&self) -> Result<RobotControlRun, RobotControlError> {
        let traces = [
            self.run_scheme(Scheme::OpenLoop)?,
            self.run_scheme(Scheme::ClosedLoop)?,
        ];
        let metrics: Vec<[SchemeMetrics; 2]> = self
            .joints
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let d = &c.desired.angle_deg;
                [
                    SchemeMetrics::of(&traces[0].joints[j], d),
                    SchemeMetrics::of(&traces[1].joints[j], d),
                ]
            })
            .collect();
        let rows = self.samples();
        let warnings = metrics
            .iter()
            .zip(&self.joints)
            .enumerate()
            .filter(|(_, (m, _))| m[1].saturated_samples * 10 > rows)
            .map(|(j, (m, c))| {
                format!(
                    "joint {}: the closed loop's PID correction was at its limit (±{:.3} mm) for {} of {rows} samples: \
                     the loop is unstable or cannot reach the desired angle",
                    j + 1,
                    c.pid.output_max,
                    m[1].saturated_samples
                )
            })
            .collect();
        Ok(RobotControlRun {
            traces,
            metrics,
            warnings,
        })
    }
}

/// The config must list the robot's joints and sensors in the robot's order.
fn check_shape(
    config: &RobotEstimatorConfig,
    robot: &str,
    joints: usize,
    sensors: &[(usize, usize)],
) -> Result<(), RobotControlError> {
    if config.joint_count() != joints || config.sensor_count() != sensors.len() {
        return Err(RobotControlError::Shape {
            config_joints: config.joint_count(),
            config_sensors: config.sensor_count(),
            robot: robot.to_string(),
            joints,
            sensors: sensors.len(),
        });
    }
    for (i, (c, &(joint, sensor))) in config.sensor.iter().zip(sensors).enumerate() {
        if c.joint as usize != joint + 1 || c.sensor as usize != sensor + 1 {
            return Err(RobotControlError::SensorOrder {
                index: i + 1,
                config_joint: c.joint,
                config_sensor: c.sensor,
                robot: robot.to_string(),
                joint: joint + 1,
                sensor: sensor + 1,
            });
        }
    }
    Ok(())
}

/// A config divider or supply other than the bench's, per sensor.
fn divider_warnings(
    config: &RobotEstimatorConfig,
    joints: &[ControlledJoint],
    sensors: &[(usize, usize)],
) -> Vec<String> {
    let mut out = Vec::new();
    for (i, (c, &(j, s))) in config.sensor.iter().zip(sensors).enumerate() {
        let sc = &joints[j].desired.scenario;
        if let Some(bench_ohm) = sc.sensors().nth(s).and_then(|p| p.divider_ohm) {
            if (c.divider_ohm - bench_ohm).abs() > 1e-9 * bench_ohm.abs() {
                out.push(format!(
                    "sensor {} divider_ohm is {} Ω in the config but {} Ω on the simulated bench",
                    i + 1,
                    c.divider_ohm,
                    bench_ohm
                ));
            }
        }
        if (c.supply_v - sc.supply_v).abs() > 1e-9 * sc.supply_v {
            out.push(format!(
                "sensor {} supply_v is {} V in the config but {} V on the simulated bench",
                i + 1,
                c.supply_v,
                sc.supply_v
            ));
        }
    }
    out
}
