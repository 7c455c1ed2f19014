//! Robot fixtures shared by the robot tests and benchmarks (through `#[path]` module
//! declarations, next to `table_one`): a three-joint robot on Joint B/C's 1.6 mm tube, its
//! crosstalk, and a forward model that turns joint angles into the sensors' voltages under the
//! sensing model of `docs/robot-runtime.md` (each sensor's model on its own mixed angle).
#![allow(dead_code)]

use dlw_estimator::{
    nominal_divider, ContinuousPi, GeneralizedPi, JointConfig, LinearModel, ModelConfig,
    RobotEstimatorConfig, RobotJointConfig, RobotSensorConfig, MAX_JOINTS,
};
use dlw_geometry::{Divider, Joint, NotchStyle};

/// Joint B of Table I: UAN on the 1.6 mm tube.
pub fn joint_b() -> JointConfig {
    JointConfig {
        style: NotchStyle::Uan,
        outer_radius_mm: 0.8,
        inner_radius_mm: 0.61,
        notch_arc_mm: 3.52,
        notch_width_mm: 0.5,
        notch_spacing_mm: 0.5,
        notch_count: 10,
        joint_length_mm: 9.5,
        sensor_arc_mm: 0.4,
    }
}

/// Joint C of Table I: BSN on the same tube.
pub fn joint_c() -> JointConfig {
    JointConfig {
        style: NotchStyle::Bsn,
        notch_arc_mm: 1.65,
        sensor_arc_mm: 2.13,
        ..joint_b()
    }
}

/// Joints at rotations 0°, 90° and 225°, 9.5 mm sections with 3 mm gaps.
fn joints(geometry: [JointConfig; 3]) -> [RobotJointConfig; 3] {
    let rotations = [0.0, 90.0, 225.0];
    core::array::from_fn(|j| {
        let start = 0.5 + 12.5 * j as f64;
        RobotJointConfig {
            rotation_deg: rotations[j],
            x_start_mm: start,
            x_end_mm: start + 9.5,
            geometry: geometry[j],
        }
    })
}

/// A sensor's joint (1-based), number within the joint, crosstalk row and linear model.
type SensorSpec = (u32, u32, [f64; 3], f64, f64);

/// Joint B, Joint C (both sensors, Table III's models) and Joint B: four sensors whose leads
/// cross the proximal joints, so the crosstalk is upper triangular by joint.
pub const BCB_SENSORS: [SensorSpec; 4] = [
    (1, 1, [1.0, 0.03, -0.02], 15.3, 215.0e3),
    (2, 1, [0.0, 1.0, 0.04], 1.28, 74.0e3),
    (2, 2, [0.0, 1.0, -0.035], 0.68, 88.9e3),
    (3, 1, [0.0, 0.0, 1.0], 15.3, 215.0e3),
];

/// Three Joint Bs, one sensor each: the benchmark's three-joint robot.
pub const BBB_SENSORS: [SensorSpec; 3] = [
    (1, 1, [1.0, 0.03, -0.02], 15.3, 215.0e3),
    (2, 1, [0.0, 1.0, 0.04], 15.3, 215.0e3),
    (3, 1, [0.0, 0.0, 1.0], 15.3, 215.0e3),
];

fn config(geometry: [JointConfig; 3], sensors: &[SensorSpec]) -> RobotEstimatorConfig {
    let sensors: Vec<RobotSensorConfig> = sensors
        .iter()
        .map(|&(joint, sensor, crosstalk, gf, r0)| {
            RobotSensorConfig::linear(joint, sensor, gf, r0, nominal_divider(), &crosstalk).unwrap()
        })
        .collect();
    RobotEstimatorConfig::new(&joints(geometry), &sensors).unwrap()
}

/// The B-C-B robot with linear sensors.
pub fn bcb_linear() -> RobotEstimatorConfig {
    config([joint_b(), joint_c(), joint_b()], &BCB_SENSORS)
}

/// The B-B-B robot with linear sensors.
pub fn bbb_linear() -> RobotEstimatorConfig {
    config([joint_b(), joint_b(), joint_b()], &BBB_SENSORS)
}

/// `config` with every sensor's model replaced by `model(sensor index)`.
pub fn with_models(
    mut config: RobotEstimatorConfig,
    model: impl Fn(usize) -> ModelConfig,
) -> RobotEstimatorConfig {
    for (i, s) in config.sensor.as_mut_slice().iter_mut().enumerate() {
        s.model = model(i);
    }
    config
}

/// A sensor's forward model: strain in, resistance out.
enum Forward {
    Linear(LinearModel),
    Pi(GeneralizedPi),
    ContinuousPi(ContinuousPi),
}

/// The robot's sensors as the sensing model has them: sensor `i` reads the mixed angle
/// `a_i = Σ_j C[i][j]·θ_j` through its own joint's geometry (Eq. 3, with its plane's sign), its
/// own model (forward) and its divider (Eq. 4).
pub struct Sensors {
    sensors: Vec<(Joint, f64, [f64; MAX_JOINTS], Forward, Divider)>,
}

impl Sensors {
    pub fn new(config: &RobotEstimatorConfig) -> Self {
        let sensors = config
            .sensor
            .iter()
            .map(|s| {
                let joint = config.joint[s.joint as usize - 1]
                    .geometry
                    .to_joint()
                    .unwrap();
                let forward = match &s.model {
                    ModelConfig::Linear(m) => Forward::Linear(*m),
                    ModelConfig::Pi(m) => Forward::Pi(GeneralizedPi::new(m).unwrap()),
                    ModelConfig::ContinuousPi(m) => {
                        Forward::ContinuousPi(ContinuousPi::new(m).unwrap())
                    }
                };
                let mut row = [0.0; MAX_JOINTS];
                row[..s.crosstalk.len()].copy_from_slice(&s.crosstalk);
                (
                    joint,
                    s.plane().sign(),
                    row,
                    forward,
                    Divider::new(s.divider_ohm, s.supply_v).unwrap(),
                )
            })
            .collect();
        Self { sensors }
    }

    /// Each sensor's mixed angle at joint angles `theta` (rad).
    pub fn mixed(&self, theta: &[f64]) -> Vec<f64> {
        self.sensors
            .iter()
            .map(|(_, _, row, _, _)| row.iter().zip(theta).map(|(c, t)| c * t).sum())
            .collect()
    }

    /// The divider voltages at joint angles `theta` (rad); advances the PI models' state.
    pub fn volts(&mut self, theta: &[f64]) -> Vec<f64> {
        let mixed = self.mixed(theta);
        self.sensors
            .iter_mut()
            .zip(mixed)
            .map(|((joint, sign, _, forward, divider), a)| {
                let strain = *sign * joint.strain(a);
                let ohm = match forward {
                    Forward::Linear(m) => m.resistance(strain),
                    Forward::Pi(m) => m.step(strain),
                    Forward::ContinuousPi(m) => m.step(strain),
                };
                divider.voltage(ohm)
            })
            .collect()
    }
}

/// Smooth, incommensurate joint trajectories within ±`peak_rad`, sample `k`.
pub fn trajectory(k: usize, joints: usize, peak_rad: f64) -> Vec<f64> {
    (0..joints)
        .map(|j| {
            let t = k as f64 * 0.01;
            let f = 1.0 + 0.37 * j as f64;
            peak_rad * (0.7 * (f * t).sin() + 0.3 * (2.3 * f * t + j as f64).cos())
        })
        .collect()
}
