//! Robot estimator configs survive TOML and JSON round trips, read the shape
//! `docs/robot-runtime.md` documents, and refuse unknown fields and over-long lists.

use dlw_estimator::{
    Coeffs, FilterConfig, ModelConfig, PiConfig, RobotEstimator, RobotEstimatorConfig, MAX_JOINTS,
};

#[path = "common/robot.rs"]
mod robot;
use robot::{bbb_linear, bcb_linear, with_models};

fn configs() -> Vec<RobotEstimatorConfig> {
    let mut filtered = bbb_linear();
    filtered.input_filter = FilterConfig::MovingAverage { samples: 10 };
    filtered.output_filter = FilterConfig::LowPass {
        time_constant_samples: 4.0,
    };
    filtered.max_condition_number = 3.5;
    let pi = with_models(bcb_linear(), |i| {
        ModelConfig::Pi(PiConfig {
            weights: Coeffs::from_slice("weights", &[0.4, 0.3, 0.2, 0.1]).unwrap(),
            radii: Coeffs::from_slice("radii", &[0.0, 1.0e3, 2.0e3, 3.0e3]).unwrap(),
            loading_tanh: [26.0e3, 98.77, 0.0, 0.0],
            unloading_tanh: [26.0e3, 118.5, 0.05, -150.0],
            center_strain: 0.0,
            center_ohm: 224.0e3 + i as f64,
            min_ohm: 205.0e3,
            max_ohm: 250.0e3,
            min_strain: Some(-0.01),
            max_strain: Some(0.01),
            initial_state: 0.0,
        })
    });
    vec![bcb_linear(), filtered, pi]
}

#[test]
fn toml_and_json_round_trip() {
    for config in configs() {
        let text = toml::to_string(&config).unwrap();
        let back: RobotEstimatorConfig = toml::from_str(&text).unwrap();
        assert_eq!(back, config, "{text}");
        assert!(RobotEstimator::new(&back).is_ok());
        let json = serde_json::to_string_pretty(&config).unwrap();
        let back: RobotEstimatorConfig = serde_json::from_str(&json).unwrap();
        assert_eq!(back, config, "{json}");
    }
}

/// The shape `docs/robot-runtime.md` shows, written by hand: two joints, the second BSN with
/// both sensors.
pub const DOCUMENTED: &str = r#"
max_condition_number = 10.0

[[joint]]
rotation_deg = 0.0
x_start_mm = 0.5
x_end_mm = 10.0

[joint.geometry]
style = "uan"
outer_radius_mm = 0.8
inner_radius_mm = 0.61
notch_arc_mm = 3.52
notch_width_mm = 0.5
notch_spacing_mm = 0.5
notch_count = 10
joint_length_mm = 9.5
sensor_arc_mm = 0.4

[[joint]]
rotation_deg = 90.0
x_start_mm = 13.0
x_end_mm = 22.5

[joint.geometry]
style = "bsn"
outer_radius_mm = 0.8
inner_radius_mm = 0.61
notch_arc_mm = 1.65
notch_width_mm = 0.5
notch_spacing_mm = 0.5
notch_count = 10
joint_length_mm = 9.5
sensor_arc_mm = 2.13

[[sensor]]
joint = 1
sensor = 1
divider_ohm = 99600.0
supply_v = 5.0
crosstalk = [1.0, 0.031]

[sensor.model.linear]
gauge_factor = 15.3
r0_ohm = 215000.0

[[sensor]]
joint = 2
sensor = 1
divider_ohm = 99600.0
supply_v = 5.0
crosstalk = [0.0, 1.0]

[sensor.model.linear]
gauge_factor = 1.28
r0_ohm = 74000.0

[[sensor]]
joint = 2
sensor = 2
divider_ohm = 102500.0
supply_v = 5.0
crosstalk = [0.0, 1.0]

[sensor.model.linear]
gauge_factor = 0.68
r0_ohm = 88900.0
"#;

#[test]
fn reads_the_documented_shape() {
    let config: RobotEstimatorConfig = toml::from_str(DOCUMENTED).unwrap();
    config.validate().unwrap();
    assert_eq!((config.joint_count(), config.sensor_count()), (2, 3));
    assert_eq!(config.sensor[0].crosstalk.as_slice(), &[1.0, 0.031]);
    assert_eq!(config.output_filter, FilterConfig::None);
    let estimator = RobotEstimator::new(&config).unwrap();
    // Joint 2's pair of rows gives it sqrt(2) the gain of joint 1's one: κ ≈ √2.
    let kappa = estimator.unmixing().condition_number();
    assert!((kappa - 2f64.sqrt()).abs() < 0.03, "{kappa}");
    // The defaults are what a config without them reads.
    let without = DOCUMENTED.replace("max_condition_number = 10.0", "");
    let config: RobotEstimatorConfig = toml::from_str(&without).unwrap();
    assert_eq!(
        config.max_condition_number,
        dlw_estimator::DEFAULT_MAX_CONDITION_NUMBER
    );
}

#[test]
fn refuses_unknown_fields_and_too_many_entries() {
    let typos = [
        DOCUMENTED.replace("rotation_deg = 90.0", "rotation = 90.0"),
        DOCUMENTED.replace("crosstalk = [0.0, 1.0]", "cross_talk = [0.0, 1.0]"),
        DOCUMENTED.replace("r0_ohm = 74000.0", "r0 = 74000.0"),
        DOCUMENTED.replace("x_end_mm = 22.5", "x_end_mm = 22.5\nlength_mm = 9.5"),
    ];
    for text in typos {
        assert!(
            toml::from_str::<RobotEstimatorConfig>(&text).is_err(),
            "{text}"
        );
    }
    let long: Vec<String> = (0..=MAX_JOINTS).map(|_| "0.0".to_string()).collect();
    let text = DOCUMENTED.replace(
        "crosstalk = [1.0, 0.031]",
        &format!("crosstalk = [{}]", long.join(", ")),
    );
    let error = toml::from_str::<RobotEstimatorConfig>(&text)
        .unwrap_err()
        .to_string();
    assert!(error.contains("more than 8 entries"), "{error}");
}

/// Values that parse but are invalid are refused when the estimator is built, by sensor.
#[test]
fn invalid_values_are_refused_by_sensor() {
    let text = DOCUMENTED.replace(
        "crosstalk = [0.0, 1.0]\n\n[sensor.model.linear]\ngauge_factor = 0.68",
        "crosstalk = [0.0]\n\n[sensor.model.linear]\ngauge_factor = 0.68",
    );
    let config: RobotEstimatorConfig = toml::from_str(&text).unwrap();
    let error = RobotEstimator::new(&config).unwrap_err().to_string();
    assert_eq!(
        error,
        "sensor 3: crosstalk has 1 entries, must have one per joint (2)"
    );
}
