//! Whatever the estimator is fed (NaN, ±∞, rails, huge, tiny or subnormal voltages) it returns
//! finite numbers, and a sample it cannot use returns the last good estimate, flagged.

use dlw_estimator::{
    nominal_divider, Coeffs, ContinuousPiConfig, Estimate, Estimator, EstimatorConfig,
    FilterConfig, Flags, JointConfig, ModelConfig, PiConfig,
};
use dlw_geometry::NotchStyle;
use proptest::prelude::*;

#[path = "common/table_one.rs"]
mod table_one;
use table_one::joint;

fn pi() -> ModelConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 2.5e3).collect();
    ModelConfig::Pi(PiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).unwrap(),
        radii: Coeffs::from_slice("radii", &radii).unwrap(),
        loading_tanh: [26.0e3, 98.77, 0.0, 0.0],
        unloading_tanh: [26.0e3, 118.5, 0.05, -150.0],
        center_strain: 0.00307,
        center_ohm: 224.0e3,
        min_ohm: 205.0e3,
        max_ohm: 250.0e3,
        min_strain: None,
        max_strain: None,
        initial_state: 0.0,
    })
}

fn continuous_pi() -> ModelConfig {
    ModelConfig::ContinuousPi(ContinuousPiConfig {
        weights: Coeffs::from_slice("weights", &[0.5, 0.3, 0.2]).unwrap(),
        radii: Coeffs::from_slice("radii", &[0.0, 1.0e3, 2.0e3]).unwrap(),
        loading_envelope: [20.0e3, 100.0, 0.0, 0.0],
        unloading_envelope: [20.0e3, 100.0, 0.2, 0.0],
        center_strain: 0.005,
        center_ohm: 224.0e3,
        min_strain: -0.01,
        max_strain: 0.02,
        strain_tolerance: 1e-12,
        resistance_tolerance_ohm: 0.5,
        initial_state: 0.0,
    })
}

/// Every model kind, on one and two sensors, without and with each filter.
fn estimators() -> Vec<(&'static str, Box<Estimator>)> {
    let mut out = Vec::new();
    let models: [(&str, ModelConfig); 3] = [
        (
            "linear",
            EstimatorConfig::nominal_linear(
                joint(NotchStyle::Uan),
                15.3,
                215.0e3,
                nominal_divider(),
            )
            .unwrap()
            .sensor
            .model,
        ),
        ("pi", pi()),
        ("continuous_pi", continuous_pi()),
    ];
    let filters = [
        FilterConfig::None,
        FilterConfig::MovingAverage { samples: 7 },
        FilterConfig::LowPass {
            time_constant_samples: 3.0,
        },
    ];
    for (name, model) in models {
        for (style, filter) in [
            (NotchStyle::Uan, filters[0]),
            (NotchStyle::Uan, filters[1]),
            (NotchStyle::Bsn, filters[2]),
        ] {
            let mut config =
                EstimatorConfig::nominal_linear(joint(style), 15.3, 215.0e3, nominal_divider())
                    .unwrap();
            config.sensor.model = model;
            if let Some(second) = config.second_sensor.as_mut() {
                second.model = model;
            }
            config.input_filter = filter;
            config.output_filter = filter;
            out.push((name, Box::new(Estimator::new(&config).unwrap())));
        }
    }
    out
}

/// Voltages of every kind: plausible readings, the rails, beyond them, and any f64 at all.
fn volts() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => 1.5f64..3.5,
        1 => Just(0.0),
        1 => Just(5.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(f64::MIN_POSITIVE),
        1 => Just(f64::from_bits(5.0f64.to_bits() - 1)),
        1 => prop::num::f64::ANY,
        1 => -1e300f64..1e300,
    ]
}

fn check(name: &str, previous: &Estimate, e: &Estimate) -> Result<(), TestCaseError> {
    for value in [
        e.angle_rad,
        e.angle_deg,
        e.strain[0],
        e.strain[1],
        e.resistance_ohm[0],
        e.resistance_ohm[1],
    ] {
        prop_assert!(value.is_finite(), "{name}: {e:?}");
    }
    if e.flags.contains(Flags::HELD) {
        prop_assert!(
            e.flags.intersects(Flags::RAIL | Flags::NON_FINITE),
            "{name}: held without a reason: {e:?}"
        );
        prop_assert_eq!(
            e.angle_rad,
            previous.angle_rad,
            "{}: held estimate moved",
            name
        );
        prop_assert_eq!(e.strain, previous.strain);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn one_sensor_never_returns_non_finite(inputs in prop::collection::vec(volts(), 1..200)) {
        for (name, mut est) in estimators() {
            let mut previous = *est.last();
            for &v in &inputs {
                let e = est.step(v);
                check(name, &previous, &e)?;
                previous = e;
            }
        }
    }

    #[test]
    fn two_sensors_never_return_non_finite(inputs in prop::collection::vec((volts(), volts()), 1..200)) {
        for (name, mut est) in estimators() {
            let mut previous = *est.last();
            for &(v1, v2) in &inputs {
                let e = est.step2(v1, v2);
                check(name, &previous, &e)?;
                previous = e;
            }
        }
    }
}

/// Rails and NaN are held; a good reading after them is used again.
#[test]
fn recovers_after_bad_samples() {
    for (name, mut est) in estimators() {
        let good = est.step2(2.6, 2.4);
        assert!(!good.flags.contains(Flags::HELD), "{name}");
        for bad in [0.0, 5.0, f64::NAN, -3.0] {
            let e = est.step2(bad, 2.4);
            assert!(e.flags.contains(Flags::HELD), "{name}: {bad}");
            assert_eq!(e.angle_rad, good.angle_rad, "{name}");
        }
        assert!(!est.step2(2.6, 2.4).flags.contains(Flags::HELD), "{name}");
    }
}
