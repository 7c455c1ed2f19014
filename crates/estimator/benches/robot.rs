//! Per-sample cost of the robot estimator and the kinematics, for a robot of three joints.
//! Each benchmark feeds a block of 1000 samples (smooth incommensurate joint trajectories
//! between 0 and 14°, so the PI models see reversals); criterion reports the time per block,
//! divide by 1000 for the time per sample.
//!
//! Run: `cargo bench -p dlw-estimator --bench robot -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dlw_estimator::{
    Coeffs, ContinuousPiConfig, ModelConfig, PiConfig, RobotEstimator, RobotEstimatorConfig,
};

#[path = "../tests/common/robot.rs"]
mod robot;
use robot::{bbb_linear, bcb_linear, trajectory, with_models, Sensors};

const BLOCK: usize = 1000;

/// The paper's initial PI guess for Joint A (N = 10 plays), as in the one-joint benchmark.
fn pi_n10() -> ModelConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 2.5e3).collect();
    ModelConfig::Pi(PiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).unwrap(),
        radii: Coeffs::from_slice("radii", &radii).unwrap(),
        loading_tanh: [26.0e3, 98.77, 0.0, 0.0],
        unloading_tanh: [26.0e3, 118.5, 0.05, -150.0],
        center_strain: 0.00307,
        center_ohm: 224.0e3,
        min_ohm: 200.0e3,
        max_ohm: 250.0e3,
        min_strain: None,
        max_strain: None,
        initial_state: 0.0,
    })
}

fn continuous_pi_n10() -> ModelConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 1.0e3).collect();
    ModelConfig::ContinuousPi(ContinuousPiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).unwrap(),
        radii: Coeffs::from_slice("radii", &radii).unwrap(),
        loading_envelope: [26.0e3, 98.77, 0.0, 0.0],
        unloading_envelope: [26.0e3, 98.77, 0.1, 0.0],
        center_strain: 0.00307,
        center_ohm: 224.0e3,
        min_strain: -0.01,
        max_strain: 0.03,
        strain_tolerance: 1e-12,
        resistance_tolerance_ohm: 0.0,
        initial_state: 0.0,
    })
}

/// Joint angles of one block: 0.125 ± 0.12 rad on each joint.
fn angles(joints: usize) -> Vec<Vec<f64>> {
    (0..BLOCK)
        .map(|k| {
            trajectory(k, joints, 0.12)
                .into_iter()
                .map(|t| 0.125 + t)
                .collect()
        })
        .collect()
}

/// The sensors' voltages over one block of `config`'s robot.
fn volts(config: &RobotEstimatorConfig) -> Vec<Vec<f64>> {
    let mut sensors = Sensors::new(config);
    angles(config.joint_count())
        .iter()
        .map(|theta| sensors.volts(theta))
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("robot_per_block_of_1000");
    group.throughput(Throughput::Elements(BLOCK as u64));

    let cases = [
        ("robot3_linear", bbb_linear()),
        ("robot3_pi_n10", with_models(bbb_linear(), |_| pi_n10())),
        (
            "robot3_continuous_pi_n10",
            with_models(bbb_linear(), |_| continuous_pi_n10()),
        ),
        ("robot3_bsn_4_sensors_linear", bcb_linear()),
    ];
    for (name, config) in cases {
        let block = volts(&config);
        let mut estimator = Box::new(RobotEstimator::new(&config).unwrap());
        group.bench_function(name, |b| {
            b.iter(|| {
                for v in &block {
                    black_box(estimator.step(black_box(v)));
                }
            })
        });
        if name == "robot3_bsn_4_sensors_linear" || name == "robot3_continuous_pi_n10" {
            continue;
        }
        group.bench_function(format!("{name}_with_tip"), |b| {
            b.iter(|| {
                for v in &block {
                    let e = estimator.step(black_box(v));
                    black_box(estimator.tip(&e).unwrap());
                }
            })
        });
    }

    let kinematics = bbb_linear().kinematics().unwrap();
    let block = angles(3);
    group.bench_function("kinematics3_tip", |b| {
        b.iter(|| {
            for theta in &block {
                black_box(kinematics.tip(black_box(theta)).unwrap());
            }
        })
    });
    let mut points = [[0.0; 3]; 20];
    group.bench_function("kinematics3_backbone_20_points", |b| {
        b.iter(|| {
            for theta in &block {
                kinematics.backbone(black_box(theta), &mut points).unwrap();
                black_box(&points);
            }
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
