//! `dlw control` for a robot (issue 34 §4): every joint's closed loop on its estimated angle,
//! the tendons coupled, the crosstalk undone; the same loops on a config that does not undo it;
//! the command line's outputs and refusals.

// Index loops over joints read as the matrix formulas they check.
#![allow(clippy::needless_range_loop)]

mod common;

use std::path::{Path, PathBuf};

use common::{arg, dlw, dlw_ok};
use dlw::control::robot::RobotControl;
use dlw::control::{Scheme, PAPER_GAINS};
use dlw::robot::estimator_config::{estimator_config, SensorSetting};
use dlw::robot::CheckedRobot;
use dlw::sim::robot::Coupling;
use dlw::sim::{ProtocolKind, Scenario};
use dlw_estimator::{FilterConfig, LinearModel, ModelConfig, RobotEstimatorConfig};
use dlw_geometry::Divider;

fn designs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs")
}

fn robot(name: &str) -> CheckedRobot {
    CheckedRobot::load(&designs().join(name)).unwrap()
}

/// A crosstalk matrix well above the shipped robots' (under 1 %), so that not undoing it costs
/// degrees (the one `tests/robot_sensing.rs` estimates with).
const STRONG: [[f64; 3]; 3] = [[1.0, 0.08, -0.05], [0.0, 1.0, 0.06], [0.0, 0.0, 1.0]];

/// The paper's moving average on the sensed angle, which its gains need (`docs/robots.md`).
const FILTER: FilterConfig = FilterConfig::MovingAverage { samples: 50 };

/// The simulator's bench sensor for every sensor (GF 15.3, R₀ 215 kΩ, 99.6 kΩ divider), the
/// crosstalk `c` undone, the sensed angle filtered.
fn config(robot: &CheckedRobot, c: &[Vec<f64>]) -> RobotEstimatorConfig {
    let settings: Vec<SensorSetting> = robot
        .sensors
        .iter()
        .map(|_| SensorSetting {
            model: ModelConfig::Linear(LinearModel::new(15.3, 215e3).unwrap()),
            divider: Divider::new(99.6e3, 5.0).unwrap(),
        })
        .collect();
    let mut config = estimator_config(robot, &settings, c).unwrap();
    config.output_filter = FILTER;
    config
}

fn identity(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect()
}

fn random(seconds: f64, noise: bool) -> Scenario {
    let mut sc = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(seconds),
        seed: 5,
        ..Scenario::default()
    };
    sc.adc.enabled = noise;
    sc.tracker.enabled = noise;
    sc
}

fn rms(v: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for x in v {
        s += x * x;
        n += 1;
    }
    (s / n.max(1) as f64).sqrt()
}

#[test]
fn explore() {
    let robot = robot("robot-bdb.toml");
    for noise in [false, true] {
        let control = RobotControl::new(
            &robot,
            random(20.0, noise),
            &[],
            config(&robot, &robot.crosstalk_matrix()),
            PAPER_GAINS,
            None,
            Coupling::YorkSwaney,
        )
        .unwrap();
        let run = control.run().unwrap();
        for j in 0..3 {
            eprintln!("noise {noise} joint {j}: open {:?}\n closed {:?}", run.metrics[j][0], run.metrics[j][1]);
        }
    }
    let mut control = RobotControl::new(
        &robot,
        random(20.0, false),
        &[],
        config(&robot, &identity(3)),
        PAPER_GAINS,
        None,
        Coupling::YorkSwaney,
    )
    .unwrap();
    control.crosstalk = STRONG.iter().map(|r| r.to_vec()).collect();
    let ident = control.run_scheme(Scheme::ClosedLoop).unwrap();
    control.config = config(&robot, &control.crosstalk);
    let undone = control.run_scheme(Scheme::ClosedLoop).unwrap();
    for j in 0..3 {
        let d = &control.joints[j].desired.angle_deg;
        let e = |t: &dlw::control::Trace| rms(t.true_deg.iter().zip(d).map(|(a, b)| a - b));
        eprintln!("joint {j}: identity {} undone {}", e(&ident.joints[j]), e(&undone.joints[j]));
    }
    let _ = (arg, dlw::<&str>, dlw_ok::<&str>);
}
