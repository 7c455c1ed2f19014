//! Per-sample cost of the robot's runtime on the shipped robot `designs/robot-bdb.toml` (three
//! joints, three sensors): `RobotEstimator::step` on the config `dlw estimator-config ROBOT
//! --gauge-factor 15.3 --r0-ohm 215e3` writes (built in process by the same library function,
//! [`nominal_linear`]), the same with every sensor's model the paper's N = 10 PI guess, and the
//! tip pose from the robot's kinematics. Targets (issue 34): at most 150 ns per sample with
//! linear sensors, 400 ns with PI.
//!
//! Each benchmark feeds a block of 1000 samples: smooth incommensurate joint trajectories
//! between 0.3° and 14° (so the PI models see reversals), turned into the sensors' voltages by
//! each sensor's own forward model on its mixed angle (`crates/estimator/tests/common/robot.rs`).
//! Criterion reports the time per block; divide by 1000 for the time per sample.
//!
//! `cargo bench --bench robot_runtime -- --warm-up-time 1 --measurement-time 3`; results in
//! `docs/performance.md`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dlw::robot::estimator_config::nominal_linear;
use dlw::robot::CheckedRobot;
use dlw_estimator::{
    Coeffs, Flags, ModelConfig, PiConfig, RobotEstimator, RobotEstimatorConfig, DEFAULT_SUPPLY_V,
};

#[path = "../crates/estimator/tests/common/robot.rs"]
mod fixtures;
use fixtures::{trajectory, with_models, Sensors};

const BLOCK: usize = 1000;

/// The shipped three-joint robot's config, as `dlw estimator-config designs/robot-bdb.toml
/// --gauge-factor 15.3 --r0-ohm 215e3` writes it (the README tour's command).
fn bdb_linear() -> RobotEstimatorConfig {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/robot-bdb.toml");
    let robot = CheckedRobot::load(&path).expect("the shipped robot is valid");
    nominal_linear(&robot, &[15.3], &[215e3], &[], DEFAULT_SUPPLY_V).expect("its config")
}

/// The paper's initial PI guess for Joint A (N = 10 plays), as in the one-joint benchmark
/// (`crates/estimator/benches/estimator.rs`).
fn pi_n10() -> ModelConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 2.5e3).collect();
    ModelConfig::Pi(PiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).expect("ten weights"),
        radii: Coeffs::from_slice("radii", &radii).expect("ten radii"),
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

/// Joint angles of one block (rad): 0.125 ± 0.12 on each joint.
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
    let linear = bdb_linear();
    assert_eq!((linear.joint_count(), linear.sensor_count()), (3, 3));
    let mut group = c.benchmark_group("robot_bdb_per_block_of_1000");
    group.throughput(Throughput::Elements(BLOCK as u64));
    let pi = with_models(linear, |_| pi_n10());
    for (name, config) in [("step_linear", linear), ("step_pi_n10", pi)] {
        let block = volts(&config);
        let mut estimator = Box::new(RobotEstimator::new(&config).expect("a valid config"));
        // The block must exercise the estimator, not its refusals: no sample clamped, held or
        // non-finite (a PI sensor's reversals are flagged and expected).
        for v in &block {
            let e = estimator.step(v);
            let refused = e
                .flags()
                .iter()
                .any(|f| f.bits() & !Flags::REVERSAL.bits() != 0);
            assert!(!refused, "{name}: {e:?}");
        }
        estimator.reset();
        group.bench_function(name, |b| {
            b.iter(|| {
                for v in &block {
                    black_box(estimator.step(black_box(v)));
                }
            })
        });
        group.bench_function(format!("{name}_with_tip"), |b| {
            b.iter(|| {
                for v in &block {
                    let e = estimator.step(black_box(v));
                    black_box(estimator.tip(&e).expect("finite angles"));
                }
            })
        });
    }
    let kinematics = linear.kinematics().expect("the robot's kinematics");
    let block = angles(3);
    group.bench_function("kinematics_tip", |b| {
        b.iter(|| {
            for theta in &block {
                black_box(kinematics.tip(black_box(theta)).expect("finite angles"));
            }
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
