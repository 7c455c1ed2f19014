//! The robot estimator on robots whose sensors follow the sensing model exactly: with the
//! crosstalk undone the joint angles come back to rounding (linear and continuous PI sensors,
//! and the paper's PI away from its flagged reversals); ignoring the crosstalk costs exactly
//! what the matrix predicts; a one-joint robot is the one-joint estimator; every sensor's
//! flags reach the joints that depend on it; nothing NaN leaves it.

use dlw_estimator::{
    nominal_divider, Coeffs, ContinuousPiConfig, Estimator, EstimatorConfig, Flags, ModelConfig,
    PiConfig, RobotError, RobotEstimator, RobotEstimatorConfig, RobotJointConfig,
    RobotSensorConfig,
};
use proptest::prelude::*;

#[path = "common/robot.rs"]
mod robot;
use robot::{bbb_linear, bcb_linear, joint_b, joint_c, trajectory, with_models, Sensors};

/// Largest joint-angle error accepted where the estimate is exact in exact arithmetic (rad):
/// rounding through the divider, the model and the unmixing is about 1e-13.
const EXACT_RAD: f64 = 1e-9;

/// Runs `samples` samples of the trajectory through the sensors and the estimator; returns the
/// worst error over samples `keep` accepts (given the joint flags), and how many it accepted.
fn worst_error(
    config: &RobotEstimatorConfig,
    samples: usize,
    peak_rad: f64,
    keep: impl Fn(&[Flags]) -> bool,
) -> (f64, usize) {
    let mut sensors = Sensors::new(config);
    let mut estimator = Box::new(RobotEstimator::new(config).unwrap());
    let n = config.joint_count();
    let (mut worst, mut kept) = (0.0f64, 0);
    for k in 0..samples {
        let theta = trajectory(k, n, peak_rad);
        let e = estimator.step(&sensors.volts(&theta));
        if keep(e.flags()) {
            kept += 1;
            for (got, want) in e.angles_rad().iter().zip(&theta) {
                worst = worst.max((got - want).abs());
            }
        }
    }
    (worst, kept)
}

#[test]
fn linear_sensors_recover_the_angles_with_crosstalk_undone() {
    // docs/robot-runtime.md: one sensor per joint gives κ near 1, a BSN pair near √2.
    let kappa = |c| {
        RobotEstimator::new(&c)
            .unwrap()
            .unmixing()
            .condition_number()
    };
    let (bbb, bcb) = (kappa(bbb_linear()), kappa(bcb_linear()));
    assert!(bbb > 1.0 && bbb < 1.1, "{bbb}");
    assert!((bcb - 2f64.sqrt()).abs() < 0.05, "{bcb}");
    for config in [bcb_linear(), bbb_linear()] {
        let (worst, kept) = worst_error(&config, 2000, 0.5, |f| f.iter().all(|f| f.is_empty()));
        assert_eq!(kept, 2000, "no sample flagged");
        assert!(worst < EXACT_RAD, "worst {worst:e} rad");
    }
}

/// Configured without crosstalk (C = I), the estimate is each sensor's mixed angle, so the
/// error is exactly `(C − I)·θ`, which the matrix predicts.
#[test]
fn ignoring_the_crosstalk_costs_what_the_matrix_predicts() {
    let config = bcb_linear();
    let mut ignoring = config;
    for s in ignoring.sensor.as_mut_slice() {
        for (j, c) in s.crosstalk.as_mut_slice().iter_mut().enumerate() {
            *c = if j + 1 == s.joint as usize { 1.0 } else { 0.0 };
        }
    }
    let mut sensors = Sensors::new(&config);
    let mut estimator = Box::new(RobotEstimator::new(&ignoring).unwrap());
    let mut largest_cost = 0.0f64;
    for k in 0..500 {
        let theta = trajectory(k, 3, 0.5);
        let e = estimator.step(&sensors.volts(&theta));
        let mixed = sensors.mixed(&theta);
        // C⁺·a with C = I and two sensors on joint 2: joint 2 gets the pair's mean.
        let predicted = [mixed[0], 0.5 * (mixed[1] + mixed[2]), mixed[3]];
        for j in 0..3 {
            let cost = e.angles_rad()[j] - theta[j];
            assert!(
                (cost - (predicted[j] - theta[j])).abs() < EXACT_RAD,
                "joint {}: cost {cost} vs predicted {}",
                j + 1,
                predicted[j] - theta[j]
            );
            largest_cost = largest_cost.max(cost.abs());
        }
    }
    // The crosstalk is a few percent of angles up to 0.5 rad: a cost well above rounding.
    assert!(largest_cost > 0.01, "{largest_cost}");
}

/// Each sensor's hysteresis acts on its own mixed strain: the continuous PI model with equal
/// envelopes (hysteretic plays, an inverse that is exact on every sample) gives the angles back.
#[test]
fn continuous_pi_sensors_recover_the_angles() {
    let config = with_models(bcb_linear(), |i| {
        ModelConfig::ContinuousPi(ContinuousPiConfig {
            weights: Coeffs::from_slice("weights", &[0.5, 0.2, 0.2, 0.1]).unwrap(),
            radii: Coeffs::from_slice("radii", &[0.0, 2.0e3, 4.0e3, 6.0e3]).unwrap(),
            loading_envelope: [20.0e3, 100.0, 0.0, 0.0],
            unloading_envelope: [20.0e3, 100.0, 0.0, 0.0],
            center_strain: 0.0,
            center_ohm: 100.0e3 + 10.0e3 * i as f64,
            min_strain: -0.03,
            max_strain: 0.03,
            strain_tolerance: 1e-14,
            resistance_tolerance_ohm: 0.0,
            initial_state: 0.0,
        })
    });
    let (worst, kept) = worst_error(&config, 2000, 0.5, |f| {
        f.iter()
            .all(|f| !f.intersects(Flags::RESISTANCE_CLAMPED | Flags::NOT_CONVERGED))
    });
    assert_eq!(kept, 2000);
    assert!(worst < EXACT_RAD, "worst {worst:e} rad");
}

fn paper_pi(center_ohm: f64) -> ModelConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 2.5e3).collect();
    ModelConfig::Pi(PiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).unwrap(),
        radii: Coeffs::from_slice("radii", &radii).unwrap(),
        loading_tanh: [26.0e3, 98.77, 0.0, 0.0],
        unloading_tanh: [26.0e3, 118.5, 0.05, -150.0],
        center_strain: 0.0,
        center_ohm,
        min_ohm: center_ohm - 1.0e5,
        max_ohm: center_ohm + 1.0e5,
        min_strain: None,
        max_strain: None,
        initial_state: 0.0,
    })
}

/// The paper's PI model (Eqs. 10-14): its inverse is exact except on the sample where a
/// sensor's strain turns (off by up to the branch gap there, `tests/pi_inverse.rs`), so the
/// joint angles are exact on every sample where no sensor they depend on turns.
#[test]
fn paper_pi_sensors_recover_the_angles_away_from_reversals() {
    let config = with_models(bcb_linear(), |i| paper_pi(224.0e3 + 5.0e3 * i as f64));
    let mut sensors = Sensors::new(&config);
    let mut estimator = Box::new(RobotEstimator::new(&config).unwrap());
    let signs: Vec<f64> = config.sensor.iter().map(|s| s.plane().sign()).collect();
    let mut previous = [f64::NEG_INFINITY; 4];
    let mut loading = [true; 4];
    let (mut worst, mut kept, mut turned) = (0.0f64, 0, 0);
    for k in 0..3000 {
        let theta = trajectory(k, 3, 0.5);
        let volts = sensors.volts(&theta);
        let switched: Vec<bool> = sensors
            .mixed(&theta)
            .iter()
            .zip(&signs)
            .enumerate()
            .map(|(i, (a, sign))| {
                let strain = sign * a;
                let now = strain >= previous[i];
                let switched = now != loading[i];
                (previous[i], loading[i]) = (strain, now);
                switched
            })
            .collect();
        let e = estimator.step(&volts);
        for (j, want) in theta.iter().enumerate() {
            let exact = (0..4).all(|i| {
                !estimator.unmixing().depends_on(j, i)
                    || !(switched[i] || e.sensor_flags()[i].contains(Flags::ATANH_CLAMPED))
            });
            if exact {
                kept += 1;
                worst = worst.max((e.angles_rad()[j] - want).abs());
            } else {
                turned += 1;
            }
        }
    }
    assert!(worst < EXACT_RAD, "worst {worst:e} rad");
    assert!(kept > 9 * turned, "{kept} exact, {turned} at a turn");
}

/// A one-joint robot without crosstalk is the one-joint estimator: UAN sample for sample, and
/// BSN's two sensors by least squares equal Eq. 7 (the joint is symmetric, ȳ = 0).
#[test]
fn a_one_joint_robot_is_the_one_joint_estimator() {
    let joint = |geometry| RobotJointConfig {
        rotation_deg: 0.0,
        x_start_mm: 0.5,
        x_end_mm: 10.0,
        geometry,
    };
    let d = nominal_divider();
    let uan = RobotEstimatorConfig::new(
        &[joint(joint_b())],
        &[RobotSensorConfig::linear(1, 1, 15.3, 215.0e3, d, &[1.0]).unwrap()],
    )
    .unwrap();
    let bsn = RobotEstimatorConfig::new(
        &[joint(joint_c())],
        &[
            RobotSensorConfig::linear(1, 1, 1.28, 74.0e3, d, &[1.0]).unwrap(),
            RobotSensorConfig::linear(1, 2, 0.68, 88.9e3, d, &[1.0]).unwrap(),
        ],
    )
    .unwrap();
    let mut single = EstimatorConfig::nominal_linear(joint_b(), 15.3, 215.0e3, d).unwrap();
    let mut one = Box::new(Estimator::new(&single).unwrap());
    let mut robot = Box::new(RobotEstimator::new(&uan).unwrap());
    for v in [2.6, 2.4, 5.0, 2.55, f64::NAN, 2.45] {
        let (a, b) = (one.step(v), robot.step(&[v]));
        assert_eq!(a.angle_rad.to_bits(), b.angles_rad()[0].to_bits());
        assert_eq!(a.flags, b.flags()[0]);
    }
    single = EstimatorConfig::nominal_linear(joint_c(), 1.28, 74.0e3, d).unwrap();
    single.second_sensor = Some(dlw_estimator::SensorConfig::new(
        d,
        ModelConfig::Linear(dlw_estimator::LinearModel::new(0.68, 88.9e3).unwrap()),
    ));
    let mut two = Box::new(Estimator::new(&single).unwrap());
    let mut robot = Box::new(RobotEstimator::new(&bsn).unwrap());
    for (v1, v2) in [(2.6, 2.4), (2.3, 2.7), (2.5, 2.5)] {
        let (a, b) = (two.step2(v1, v2), robot.step(&[v1, v2]));
        assert!(
            (a.angle_rad - b.angles_rad()[0]).abs() < 1e-12,
            "{} vs {}",
            a.angle_rad,
            b.angles_rad()[0]
        );
    }
}

/// A rail on a sensor flags exactly the joints whose angle depends on it: sensor 1 (joint 1's
/// own, whose leads cross joints 2 and 3) only joint 1; sensor 4 (joint 3's) every joint, since
/// joints 1 and 2 are corrected by joint 3's angle. Missing voltages are NaN; a sensor's
/// non-convergence reaches its joints the same way.
#[test]
fn flags_reach_the_joints_that_depend_on_the_sensor() {
    let config = bcb_linear();
    let mut estimator = Box::new(RobotEstimator::new(&config).unwrap());
    let mut sensors = Sensors::new(&config);
    let good = sensors.volts(&[0.2, -0.1, 0.3]);
    let before = estimator.step(&good);
    assert_eq!(before.any_flags(), Flags::empty());

    let mut volts = good.clone();
    volts[0] = 5.0;
    let e = estimator.step(&volts);
    assert_eq!(e.flags()[0], Flags::RAIL | Flags::HELD);
    assert_eq!(&e.flags()[1..], &[Flags::empty(); 2]);
    assert_eq!(e.angles_rad()[0], before.angles_rad()[0], "sensor 1 held");

    let mut volts = good.clone();
    volts[3] = 0.0;
    let e = estimator.step(&volts);
    assert_eq!(e.flags(), &[Flags::RAIL | Flags::HELD; 3]);
    assert_eq!(e.sensor_flags()[3], Flags::RAIL | Flags::HELD);

    let e = estimator.step(&good[..2]);
    assert_eq!(e.sensor_flags()[2], Flags::NON_FINITE | Flags::HELD);
    assert_eq!(
        e.flags()[2],
        Flags::NON_FINITE | Flags::HELD,
        "joint 3 uses sensor 3"
    );

    // Sensor 2 (joint 2's sensor 1) with a tolerance no search can reach.
    let unreachable = with_models(config, |i| {
        let mut m = ContinuousPiConfig {
            weights: Coeffs::from_slice("weights", &[1.0]).unwrap(),
            radii: Coeffs::from_slice("radii", &[0.0]).unwrap(),
            loading_envelope: [20.0e3, 100.0, 0.0, 0.0],
            unloading_envelope: [20.0e3, 100.0, 0.0, 0.0],
            center_strain: 0.0,
            center_ohm: 100.0e3,
            min_strain: -0.03,
            max_strain: 0.03,
            strain_tolerance: 1e-14,
            resistance_tolerance_ohm: 0.0,
            initial_state: 0.0,
        };
        if i == 1 {
            m.strain_tolerance = 1e-300;
        }
        ModelConfig::ContinuousPi(m)
    });
    let mut estimator = Box::new(RobotEstimator::new(&unreachable).unwrap());
    let mut sensors = Sensors::new(&unreachable);
    let e = estimator.step(&sensors.volts(&[0.2, -0.1, 0.3]));
    assert!(e.sensor_flags()[1].contains(Flags::NOT_CONVERGED));
    assert!(!e.sensor_flags()[0].contains(Flags::NOT_CONVERGED));
    for j in 0..3 {
        assert_eq!(
            e.flags()[j].contains(Flags::NOT_CONVERGED),
            estimator.unmixing().depends_on(j, 1),
            "joint {}",
            j + 1
        );
    }
    assert!(e.flags()[1].contains(Flags::NOT_CONVERGED));
}

/// Two BSN sensors disagreeing shows in the residual; agreeing, it is rounding.
#[test]
fn the_residual_measures_disagreement() {
    let config = bcb_linear();
    let mut estimator = Box::new(RobotEstimator::new(&config).unwrap());
    let mut sensors = Sensors::new(&config);
    let volts = sensors.volts(&[0.2, -0.1, 0.3]);
    assert!(estimator.step(&volts).residual_rad() < 1e-12);
    let mut off = volts;
    off[2] += 0.05;
    assert!(estimator.step(&off).residual_rad() > 1e-3);
}

#[test]
fn tip_of_the_estimate_is_the_tip_of_the_truth() {
    let config = bcb_linear();
    let mut estimator = Box::new(RobotEstimator::new(&config).unwrap());
    let mut sensors = Sensors::new(&config);
    let kinematics = config.kinematics().unwrap();
    for k in [0, 100, 200] {
        let theta = trajectory(k, 3, 0.8);
        let e = estimator.step(&sensors.volts(&theta));
        let (got, want) = (estimator.tip(&e).unwrap(), kinematics.tip(&theta).unwrap());
        for (g, w) in got.position_mm.iter().zip(want.position_mm) {
            assert!((g - w).abs() < 1e-8, "{g} vs {w}");
        }
    }
    estimator.reset();
    assert_eq!(estimator.last().angles_rad(), &[0.0; 3]);
}

#[test]
fn refusals_name_the_sensor_the_value_and_the_limit() {
    let base = bcb_linear();
    let cases: Vec<(RobotEstimatorConfig, &str)> = vec![
        (
            {
                let mut c = base;
                c.joint.as_mut_slice()[1].geometry.inner_radius_mm = 1.5;
                c
            },
            "joint 2: inner_radius_mm = 1.5 must be smaller than outer_radius_mm = 0.8",
        ),
        (
            {
                let mut c = base;
                c.sensor.as_mut_slice()[1].joint = 4;
                c
            },
            "sensor 2: joint = 4 must lie between 1 and 3",
        ),
        (
            {
                let mut c = base;
                c.sensor.as_mut_slice()[0].sensor = 2;
                c
            },
            "sensor 1: sensor = 2 must be 1 (the uan joint 1 carries 1)",
        ),
        (
            {
                let mut c = base;
                c.sensor.as_mut_slice()[2].sensor = 1;
                c
            },
            "sensor 3: it is sensor 1 of joint 2, as sensor 2 already is",
        ),
        (
            {
                let mut c = base;
                c.sensor.as_mut_slice()[3].crosstalk.as_mut_slice()[2] = 0.9;
                c
            },
            "sensor 4: crosstalk[3] = 0.9 is its own joint's and must be 1",
        ),
        (
            {
                let mut c = base;
                c.sensor.as_mut_slice()[0].crosstalk.as_mut_slice()[1] = f64::INFINITY;
                c
            },
            "sensor 1: crosstalk[2] = inf is not a finite number",
        ),
        (
            {
                let mut c = base;
                c.sensor.as_mut_slice()[0].divider_ohm = -1.0;
                c
            },
            "sensor 1: divider_ohm = -1 must be greater than 0",
        ),
        (
            {
                let mut c = base;
                c.joint.as_mut_slice()[1].x_start_mm = 9.0;
                c
            },
            "joint 2: x_start_mm = 9 must be at least joint 1's x_end_mm = 10",
        ),
        (
            {
                let mut c = base;
                // Joint 3's sensor reads joint 2 as strongly, and the pair on joint 2 reads
                // joint 3 alike: joints 2 and 3 cannot be told apart.
                c.sensor.as_mut_slice()[3].crosstalk =
                    dlw_estimator::List::from_slice("crosstalk", &[0.0, 1.0, 1.0]).unwrap();
                for i in [1, 2] {
                    c.sensor.as_mut_slice()[i].crosstalk =
                        dlw_estimator::List::from_slice("crosstalk", &[0.0, 1.0, 1.0]).unwrap();
                }
                c.sensor.as_mut_slice()[0].crosstalk =
                    dlw_estimator::List::from_slice("crosstalk", &[1.0, 0.0, 0.0]).unwrap();
                c
            },
            "rank deficient",
        ),
        (
            {
                let mut c = base;
                c.max_condition_number = 1.01;
                c
            },
            "exceeds max_condition_number = 1.01",
        ),
    ];
    for (config, text) in cases {
        let error = config.validate().unwrap_err();
        let message = error.to_string();
        assert!(message.contains(text), "{message:?} lacks {text:?}");
        assert!(RobotEstimator::new(&config).is_err());
    }
    let mut too_few = base;
    too_few.sensor = dlw_estimator::List::from_slice("sensor", &base.sensor[..2]).unwrap();
    assert_eq!(
        too_few.validate(),
        Err(RobotError::TooFewSensors {
            sensors: 2,
            joints: 3
        })
    );
    assert_eq!(
        too_few.validate().unwrap_err().to_string(),
        "2 sensors cannot tell 3 joint angles apart (needs at least 3 sensors)"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Whatever the voltages (rails, NaN, ±∞, huge, subnormal, too few), every angle, mixed
    /// angle and residual is finite, and a joint whose sensors are all unflagged has no flags.
    #[test]
    fn never_nan(samples in prop::collection::vec(
        prop::collection::vec(prop_oneof![
            0.0..5.0f64,
            Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY),
            Just(0.0), Just(5.0), Just(1e300), Just(-1e300), Just(5e-324),
        ], 0..6), 1..40)) {
        let pi = with_models(bcb_linear(), |i| paper_pi(224.0e3 + 5.0e3 * i as f64));
        for config in [bcb_linear(), pi] {
            let mut estimator = Box::new(RobotEstimator::new(&config).unwrap());
            for volts in &samples {
                let e = estimator.step(volts);
                prop_assert!(e.angles_rad().iter().all(|a| a.is_finite()));
                prop_assert!(e.mixed_rad().iter().all(|a| a.is_finite()));
                prop_assert!(e.residual_rad().is_finite());
                for j in 0..3 {
                    let mut from_sensors = Flags::empty();
                    for i in 0..4 {
                        if estimator.unmixing().depends_on(j, i) {
                            from_sensors |= e.sensor_flags()[i];
                        }
                    }
                    prop_assert_eq!(e.flags()[j], from_sensors);
                }
            }
        }
    }
}
