//! A robot's bench (issue 34 §4, `dlw simulate --design ROBOT`): every joint's tendon and
//! sensors, each joint simulated by the one-joint chain ([`Bench`]: plant, sensors, dividers,
//! ADC, tracker, with the scenario's effects and noise), with two things a robot adds:
//!
//! 1. **Tendon coupling** ([`Coupling::YorkSwaney`], switchable). Joint `j`'s tendon runs
//!    through the lumens of every proximal joint `p > j` to the base. Its tension is the one
//!    that holds joint `j` at its plant angle, `F_j = k_j·θ_j/(r_t,j + ȳ_j)` (`docs/mechanics.md`,
//!    `k = E·I/h` per notch over `N` notches, friction ignored), and at joint `p` it acts at the
//!    tendon's place in `p`'s plane, `y = −r_t,j·cos(rot_j − rot_p)`, so it bends `p` by
//!    `F_j·(ȳ_p + r_t,j·cos Δ)/k_p` (the moment about `p`'s neutral plane over its stiffness;
//!    linear-elastic). A BSN joint bent negative pulls its other tendon (at `+r_t,j`, force
//!    `k_j·|θ_j|/r_t,j`); a UAN joint bent negative (opened) pulls none. The component out of
//!    `p`'s bending plane, which its uncut backbone carries, is not modelled, nor the tendon's
//!    stretch or friction. Each joint's angle is its own plant's plus the distal tendons' share.
//! 2. **Crosstalk**: sensor `i` reads the mixed angle `a_i = Σ_j C[i][j]·θ_j` through its own
//!    joint's geometry and model (`docs/robot-runtime.md`), `C` from the robot's routing.
//!
//! Each joint runs the same scenario (protocol, effects, noise) with its own seed,
//! `seed + 7919·j` for joint `j + 1` (0-based `j`), so their strokes and noise are independent;
//! the sample rate, supply and duration are joint 1's. The tracker records each joint's angle;
//! the tip columns are the kinematics (`docs/robot-runtime.md`) of the tracked angles.

use dlw_geometry::{BendingSection, Kinematics, NotchStyle};

use crate::recording::robot::{RobotRecording, RobotSamples};
use crate::recording::{Rig, SimulationInfo};
use crate::robot::CheckedRobot;

use super::{plan, Bench, Plan, ProtocolKind, Scenario, SimError};

/// The seed step between joints.
pub const JOINT_SEED_STEP: u64 = 7919;

/// Whether a distal tendon's tension bends the proximal joints it runs through.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coupling {
    /// No coupling: each joint's angle is its own plant's.
    None,
    /// The York/Swaney moment of each distal tendon's tension on each proximal joint.
    YorkSwaney,
}

impl Coupling {
    /// Its name on the command line and in `rig.toml`'s notes.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::YorkSwaney => "york-swaney",
        }
    }
}

/// Why a robot simulation failed.
#[derive(Debug, thiserror::Error)]
pub enum RobotSimError {
    /// A joint's own simulation was refused or failed.
    #[error("joint {joint}: {source}")]
    Joint {
        /// 1-based joint.
        joint: usize,
        /// What the one-joint simulator said.
        source: SimError,
    },
    /// The kinematics refused the robot's sections.
    #[error("the robot's kinematics: {0}")]
    Kinematics(String),
}

/// The coupling coefficients: joint `p`'s extra angle is `Σ_j pos[p][j]·max(θ_j, 0) +
/// neg[p][j]·max(−θ_j, 0)` over the distal joints `j < p`.
#[derive(Debug, Clone, PartialEq)]
pub struct CouplingMatrix {
    /// Per unit of a distal joint's positive angle.
    pub positive: Vec<Vec<f64>>,
    /// Per unit of a distal joint's negative angle (its magnitude).
    pub negative: Vec<Vec<f64>>,
}

impl CouplingMatrix {
    /// The coefficients of `coupling` for `robot` (all zero for [`Coupling::None`]).
    pub fn of(robot: &CheckedRobot, coupling: Coupling) -> Self {
        let joints = &robot.robot.joints;
        let n = joints.len();
        let mut positive = vec![vec![0.0; n]; n];
        let mut negative = vec![vec![0.0; n]; n];
        if coupling == Coupling::YorkSwaney {
            let stiffness = |j: usize| {
                let d = joints[j].design();
                d.mechanics
                    .moment_nmm(1.0, d.file.materials.youngs_modulus_pa())
            };
            for p in 0..n {
                let mp = &joints[p].design().mechanics;
                let ybar_p = mp.moment_arm_mm() - mp.tendon_offset_mm();
                for j in 0..p {
                    let mj = &joints[j].design().mechanics;
                    let r_t = mj.tendon_offset_mm();
                    let delta = (joints[j].rotation_deg - joints[p].rotation_deg).to_radians();
                    let ratio = stiffness(j) / stiffness(p);
                    positive[p][j] = ratio * (ybar_p + r_t * delta.cos()) / mj.moment_arm_mm();
                    if joints[j].design().joint.style() == NotchStyle::Bsn {
                        negative[p][j] = ratio * (ybar_p - r_t * delta.cos()) / r_t;
                    }
                }
            }
        }
        Self { positive, negative }
    }

    /// Each joint's angle (rad) from its own plant's `plant_rad`.
    pub fn apply(&self, plant_rad: &[f64], out_rad: &mut [f64]) {
        for (p, out) in out_rad.iter_mut().enumerate() {
            let mut a = plant_rad[p];
            for (j, &t) in plant_rad.iter().enumerate().take(p) {
                a += self.positive[p][j] * t.max(0.0) + self.negative[p][j] * (-t).max(0.0);
            }
            *out = a;
        }
    }
}

/// The robot's bench, one sample at a time: every joint's stroke in, every joint's true and
/// tracked angle and every sensor's voltage out. [`RobotPlan::run`] drives it with the
/// protocol's strokes; a controller (`dlw::control::robot`) with the strokes it computes, so a
/// closed loop sees exactly the plant, coupling, crosstalk and noise a recording would.
#[derive(Debug, Clone)]
pub struct RobotBench {
    benches: Vec<Bench>,
    crosstalk: Vec<Vec<f64>>,
    /// Each joint's sensors' rows of `C`, in the order of its bench's channels.
    rows_of: Vec<Vec<usize>>,
    coefficients: CouplingMatrix,
    plant_rad: Vec<f64>,
    /// Each joint's true angle at the last step (rad): its plant's plus the coupling.
    pub angle_rad: Vec<f64>,
    /// Each joint's tracked angle at the last step (°).
    pub tracked_deg: Vec<f64>,
    /// Each sensor's recorded voltage at the last step (V), in the robot's sensor order.
    pub volts: Vec<f64>,
}

impl RobotBench {
    /// The bench of each joint's resolved scenario and joint, sensors `sensors` (joint, sensor
    /// within it, 0-based, robot order) reading through `crosstalk` (one row per sensor), the
    /// tendons coupled by `coefficients`.
    ///
    /// # Errors
    /// [`RobotSimError::Joint`] naming the joint whose bench was refused.
    pub fn new(
        joints: &[(&Scenario, &dlw_geometry::Joint)],
        crosstalk: &[Vec<f64>],
        sensors: &[(usize, usize)],
        coefficients: &CouplingMatrix,
    ) -> Result<Self, RobotSimError> {
        let n = joints.len();
        let benches = joints
            .iter()
            .enumerate()
            .map(|(j, (sc, joint))| {
                Bench::new(sc, joint).map_err(|source| RobotSimError::Joint {
                    joint: j + 1,
                    source,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let rows_of = (0..n)
            .map(|j| {
                let mut r: Vec<(usize, usize)> = sensors
                    .iter()
                    .enumerate()
                    .filter(|(_, s)| s.0 == j)
                    .map(|(i, s)| (s.1, i))
                    .collect();
                r.sort_unstable();
                r.into_iter().map(|(_, i)| i).collect()
            })
            .collect();
        Ok(Self {
            benches,
            crosstalk: crosstalk.to_vec(),
            rows_of,
            coefficients: coefficients.clone(),
            plant_rad: vec![0.0; n],
            angle_rad: vec![0.0; n],
            tracked_deg: vec![0.0; n],
            volts: vec![0.0; sensors.len()],
        })
    }

    /// Advances every joint one sample at `time_s` with tendon strokes `stroke_mm` (one per
    /// joint); the results are in [`Self::angle_rad`], [`Self::tracked_deg`], [`Self::volts`].
    ///
    /// # Errors
    /// [`RobotSimError::Joint`] when a joint's sensors leave the physical range.
    pub fn step(&mut self, time_s: f64, stroke_mm: &[f64]) -> Result<(), RobotSimError> {
        for (j, bench) in self.benches.iter_mut().enumerate() {
            self.plant_rad[j] = bench.plant_step(stroke_mm[j]);
        }
        self.coefficients
            .apply(&self.plant_rad, &mut self.angle_rad);
        let theta = &self.angle_rad;
        for (j, bench) in self.benches.iter_mut().enumerate() {
            let rows = &self.rows_of[j];
            let crosstalk = &self.crosstalk;
            let mixed = |c: usize| {
                rows.get(c).map_or(theta[j], |&i| {
                    crosstalk[i].iter().zip(theta).map(|(c, t)| c * t).sum()
                })
            };
            let reading =
                bench
                    .read(time_s, theta[j], mixed)
                    .map_err(|source| RobotSimError::Joint {
                        joint: j + 1,
                        source,
                    })?;
            for (c, &i) in rows.iter().enumerate() {
                self.volts[i] = reading.volts[c];
            }
            self.tracked_deg[j] = reading.tracked_deg;
        }
        Ok(())
    }
}

/// A resolved robot simulation.
#[derive(Debug, Clone)]
pub struct RobotPlan {
    /// Each joint's one-joint plan (its design, its resolved scenario with its seed, its stroke).
    pub joints: Vec<Plan>,
    /// The crosstalk matrix: one row per sensor (robot order), one entry per joint.
    pub crosstalk: Vec<Vec<f64>>,
    /// Each sensor's joint and its number within the joint (0-based).
    pub sensors: Vec<(usize, usize)>,
    /// The tendon coupling.
    pub coupling: Coupling,
    /// Its coefficients.
    pub coefficients: CouplingMatrix,
    /// The robot's bending sections, for the tip.
    pub sections: Vec<BendingSection>,
    /// The robot's name and checksum.
    pub robot: (String, String),
}

/// The output of a robot run.
#[derive(Debug, Clone)]
pub struct RobotRun {
    /// The recording's columns.
    pub samples: RobotSamples,
    /// Each joint's true angle (°), before the tracker's noise.
    pub true_angle_deg: Vec<Vec<f64>>,
}

/// Resolves `scenario` against every joint of `robot`.
///
/// # Errors
/// [`RobotSimError::Joint`] naming the joint whose scenario or profile was refused.
pub fn plan_robot(
    robot: &CheckedRobot,
    scenario: Scenario,
    coupling: Coupling,
) -> Result<RobotPlan, RobotSimError> {
    let mut joints: Vec<Plan> = Vec::new();
    for (j, joint) in robot.robot.joints.iter().enumerate() {
        let mut sc = scenario.clone();
        sc.seed = scenario
            .seed
            .wrapping_add(JOINT_SEED_STEP * j as u64)
            .min(i64::MAX as u64);
        if let Some(first) = joints.first() {
            sc.duration_s = first.scenario.duration_s;
        }
        let p = plan(joint.design(), sc, None).map_err(|source| RobotSimError::Joint {
            joint: j + 1,
            source,
        })?;
        joints.push(p);
    }
    let sections = robot
        .robot
        .joints
        .iter()
        .map(|j| j.bending_section())
        .collect();
    Ok(RobotPlan {
        joints,
        crosstalk: robot.crosstalk_matrix(),
        sensors: robot
            .robot
            .sensors()
            .iter()
            .map(|s| (s.joint, s.sensor))
            .collect(),
        coupling,
        coefficients: CouplingMatrix::of(robot, coupling),
        sections,
        robot: (robot.robot.name.clone(), robot.robot.checksum.clone()),
    })
}

impl RobotPlan {
    /// Samples in the recording (joint 1's).
    pub fn samples(&self) -> usize {
        self.joints[0].samples
    }

    /// Generates every sample in memory.
    ///
    /// # Errors
    /// [`RobotSimError::Joint`] at the first sample where a joint's sensors leave the physical
    /// range; [`RobotSimError::Kinematics`] for sections the kinematics refuse.
    pub fn run(&self) -> Result<RobotRun, RobotSimError> {
        let n_joints = self.joints.len();
        let hz = self.joints[0].scenario.sample_hz;
        let rows = self.samples();
        let kinematics = Kinematics::new(&self.sections)
            .map_err(|e| RobotSimError::Kinematics(e.to_string()))?;
        let mut bench = self.bench()?;
        let mut strokes: Vec<_> = self.joints.iter().map(|p| p.profile.sampler()).collect();
        let mut samples = RobotSamples::new(n_joints, self.sensors.len(), true);
        let mut true_angle_deg = vec![Vec::with_capacity(rows); n_joints];
        let mut stroke_mm = vec![0.0; n_joints];
        for k in 0..rows {
            let time_s = k as f64 / hz;
            for (j, s) in stroke_mm.iter_mut().enumerate() {
                *s = strokes[j].at(time_s);
                samples.stroke_mm[j].push(*s);
            }
            bench.step(time_s, &stroke_mm)?;
            for (i, &v) in bench.volts.iter().enumerate() {
                samples.volts[i].push(v);
            }
            for (j, truth) in true_angle_deg.iter_mut().enumerate() {
                samples.angle_deg[j].push(bench.tracked_deg[j]);
                truth.push(bench.angle_rad[j].to_degrees());
            }
            let tracked_rad: Vec<f64> = bench.tracked_deg.iter().map(|a| a.to_radians()).collect();
            let pose = kinematics
                .tip(&tracked_rad)
                .map_err(|e| RobotSimError::Kinematics(e.to_string()))?;
            if let Some(tip) = &mut samples.tip_mm {
                for (c, v) in tip.iter_mut().zip(pose.position_mm) {
                    c.push(v);
                }
            }
            samples.time_s.push(time_s);
        }
        Ok(RobotRun {
            samples,
            true_angle_deg,
        })
    }

    /// The robot's bench for this plan's scenarios, crosstalk and coupling.
    ///
    /// # Errors
    /// [`RobotSimError::Joint`] naming the joint whose bench was refused.
    pub fn bench(&self) -> Result<RobotBench, RobotSimError> {
        let joints: Vec<(&Scenario, &dlw_geometry::Joint)> = self
            .joints
            .iter()
            .map(|p| (&p.scenario, &p.design.joint))
            .collect();
        RobotBench::new(&joints, &self.crosstalk, &self.sensors, &self.coefficients)
    }

    /// The recording's `rig.toml`: joint 1's bench settings, every sensor's divider, and the
    /// robot, coupling and seeds in the notes; joint 1's resolved scenario as `[scenario]`.
    pub fn rig(&self) -> Rig {
        let first = &self.joints[0];
        let divider_ohm = self
            .sensors
            .iter()
            .map(|&(j, c)| {
                self.joints[j]
                    .scenario
                    .sensors()
                    .nth(c)
                    .and_then(|s| s.divider_ohm)
                    .unwrap_or(f64::NAN)
            })
            .collect();
        let seeds: Vec<String> = self
            .joints
            .iter()
            .map(|p| p.scenario.seed.to_string())
            .collect();
        Rig {
            sample_hz: first.scenario.sample_hz,
            supply_v: first.scenario.supply_v,
            divider_ohm,
            notes: Some(format!(
                "simulated robot {:?} by dlw {}: {} protocol, seeds {} (joint 1 to {}), tendon coupling {}",
                self.robot.0,
                env!("CARGO_PKG_VERSION"),
                first.scenario.protocol.map_or("?", ProtocolKind::name),
                seeds.join(", "),
                self.joints.len(),
                self.coupling.name()
            )),
            protocol: first.scenario.protocol.map(|p| p.name().to_string()),
            simulation: Some(SimulationInfo {
                dlw_version: env!("CARGO_PKG_VERSION").to_string(),
                design_checksum: self.robot.1.clone(),
            }),
            design: None,
            scenario: toml::Table::try_from(&first.scenario).ok(),
            import: None,
        }
    }

    /// The terminal's line for `run`, written to `output`: samples, duration and rate, joints
    /// and sensors, protocol, seed, coupling, and each joint's peak true angle.
    pub fn summary(&self, run: &RobotRun, output: &std::path::Path) -> String {
        let peaks: Vec<String> = run
            .true_angle_deg
            .iter()
            .map(|a| format!("{:.1}°", a.iter().fold(0.0f64, |m, x| m.max(x.abs()))))
            .collect();
        let first = &self.joints[0].scenario;
        format!(
            "wrote {}: {} samples ({} s at {} Hz), {} joints, {} sensors, {} protocol, seed {}, tendon coupling {}, peak angles {}\n",
            output.display(),
            self.samples(),
            first.duration_s.unwrap_or(0.0),
            first.sample_hz,
            self.joints.len(),
            self.sensors.len(),
            first.protocol.map_or("?", |p| p.name()),
            first.seed,
            self.coupling.name(),
            peaks.join(", ")
        )
    }

    /// The recording of `run`.
    pub fn recording(&self, run: RobotRun) -> RobotRecording {
        RobotRecording {
            rig: self.rig(),
            samples: run.samples,
        }
    }
}
