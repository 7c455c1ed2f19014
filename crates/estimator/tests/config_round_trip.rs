//! Configs survive TOML and JSON round trips, read the documented TOML shape, and refuse
//! unknown fields and over-long lists.

use dlw_estimator::{
    nominal_divider, Coeffs, ContinuousPiConfig, Estimator, EstimatorConfig, FilterConfig,
    JointConfig, ModelConfig, PiConfig, SensorConfig, MAX_PLAYS,
};
use dlw_geometry::Divider;

#[path = "common/table_one.rs"]
mod table_one;
use table_one::{joint_a, joint_c};

fn pi() -> PiConfig {
    PiConfig {
        weights: Coeffs::from_slice("weights", &[0.4, 0.3, 0.2, 0.1]).unwrap(),
        radii: Coeffs::from_slice("radii", &[0.0, 1.0e3, 2.0e3, 3.0e3]).unwrap(),
        loading_tanh: [26.0e3, 98.77, 0.0, 0.0],
        unloading_tanh: [26.0e3, 118.5, 0.05, -150.0],
        center_strain: 0.00307,
        center_ohm: 224.0e3,
        min_ohm: 205.0e3,
        max_ohm: 250.0e3,
        min_strain: None,
        max_strain: None,
        initial_state: 0.0,
    }
}

fn continuous_pi() -> ContinuousPiConfig {
    ContinuousPiConfig {
        weights: Coeffs::from_slice("weights", &[0.5, 0.5]).unwrap(),
        radii: Coeffs::from_slice("radii", &[0.0, 500.0]).unwrap(),
        loading_envelope: [20.0e3, 100.0, 0.0, 0.0],
        unloading_envelope: [20.0e3, 100.0, 0.2, 0.0],
        center_strain: 0.005,
        center_ohm: 100.0e3,
        min_strain: -0.01,
        max_strain: 0.02,
        strain_tolerance: 1e-12,
        resistance_tolerance_ohm: 0.5,
        initial_state: 12.5,
    }
}

/// One config of every shape: each model kind, one and two sensors, each filter.
fn configs() -> Vec<EstimatorConfig> {
    let linear =
        EstimatorConfig::nominal_linear(joint_a(), 15.3, 215.0e3, nominal_divider()).unwrap();
    let mut with_pi = linear;
    with_pi.sensor.model = ModelConfig::Pi(pi());
    with_pi.output_filter = FilterConfig::MovingAverage { samples: 1000 };
    let mut with_continuous = linear;
    with_continuous.sensor.model = ModelConfig::ContinuousPi(continuous_pi());
    with_continuous.input_filter = FilterConfig::LowPass {
        time_constant_samples: 12.5,
    };
    let mut two =
        EstimatorConfig::nominal_linear(joint_c(), 1.28, 74.0e3, nominal_divider()).unwrap();
    // With the characterized strain range `dlw fit` writes (the first PI config has none, as
    // older configs do).
    two.second_sensor = Some(SensorConfig::new(
        Divider::new(102.5e3, 5.0).unwrap(),
        ModelConfig::Pi(PiConfig {
            min_strain: Some(-0.001),
            max_strain: Some(0.0146),
            ..pi()
        }),
    ));
    two.input_filter = FilterConfig::MovingAverage { samples: 500 };
    vec![linear, with_pi, with_continuous, two]
}

#[test]
fn toml_round_trips() {
    for config in configs() {
        let text = toml::to_string(&config).unwrap();
        let back: EstimatorConfig = toml::from_str(&text).unwrap();
        assert_eq!(back, config, "{text}");
        assert!(Estimator::new(&back).is_ok());
    }
}

#[test]
fn json_round_trips() {
    for config in configs() {
        let text = serde_json::to_string_pretty(&config).unwrap();
        let back: EstimatorConfig = serde_json::from_str(&text).unwrap();
        assert_eq!(back, config, "{text}");
    }
}

/// The shape `docs/estimator.md` shows, written by hand.
const DOCUMENTED: &str = r#"
output_filter = "none"

[joint]
style = "uan"
outer_radius_mm = 1.24
inner_radius_mm = 0.875
notch_arc_mm = 5.61
notch_width_mm = 0.5
notch_spacing_mm = 0.5
notch_count = 10
joint_length_mm = 9.5
sensor_arc_mm = 0.4

[sensor]
divider_ohm = 99600.0
supply_v = 5.0

[sensor.model.linear]
gauge_factor = 15.3
r0_ohm = 215000.0

[input_filter.moving_average]
samples = 500
"#;

#[test]
fn reads_the_documented_shape() {
    let config: EstimatorConfig = toml::from_str(DOCUMENTED).unwrap();
    let mut expected =
        EstimatorConfig::nominal_linear(joint_a(), 15.3, 215.0e3, nominal_divider()).unwrap();
    expected.input_filter = FilterConfig::MovingAverage { samples: 500 };
    assert_eq!(config, expected);
    // The nominal config writes the same keys.
    let written = toml::to_string(&expected).unwrap();
    for key in [
        "[sensor.model.linear]",
        "divider_ohm = 99600.0",
        "r0_ohm = 215000.0",
        "style = \"uan\"",
    ] {
        assert!(written.contains(key), "{written} lacks {key}");
    }
}

#[test]
fn refuses_unknown_fields() {
    let typos = [
        DOCUMENTED.replace("r0_ohm", "r0"),
        DOCUMENTED.replace("supply_v", "supply_volts"),
        DOCUMENTED.replace("notch_count", "notches"),
        DOCUMENTED.replace("samples = 500", "samples = 500\nwidth = 3"),
        DOCUMENTED.replace("[sensor.model.linear]", "[sensor.model.cubic]"),
        format!("{DOCUMENTED}\n[extra]\nx = 1\n"),
    ];
    for text in typos {
        assert!(toml::from_str::<EstimatorConfig>(&text).is_err(), "{text}");
    }
    let json = serde_json::to_string(&configs()[0])
        .unwrap()
        .replace("\"gauge_factor\"", "\"gf\"");
    assert!(serde_json::from_str::<EstimatorConfig>(&json).is_err());
}

#[test]
fn refuses_more_plays_than_the_limit() {
    let mut config = configs()[1];
    config.sensor.model = ModelConfig::Pi(pi());
    let text = toml::to_string(&config).unwrap();
    let too_many: Vec<String> = (0..=MAX_PLAYS).map(|i| format!("{i}.0")).collect();
    let text = text.replace(
        "weights = [0.4, 0.3, 0.2, 0.1]",
        &format!("weights = [{}]", too_many.join(", ")),
    );
    let error = toml::from_str::<EstimatorConfig>(&text)
        .unwrap_err()
        .to_string();
    assert!(error.contains("more than 16 values"), "{error}");
}

/// Values that parse but are invalid are refused when the estimator is built, by name.
#[test]
fn invalid_values_are_refused_at_build_time() {
    let text = DOCUMENTED.replace("samples = 500", "samples = 5000");
    let config: EstimatorConfig = toml::from_str(&text).unwrap();
    let error = Estimator::new(&config).unwrap_err().to_string();
    assert!(
        error.contains("samples = 5000") && error.contains("4096"),
        "{error}"
    );
    let text = DOCUMENTED.replace("inner_radius_mm = 0.875", "inner_radius_mm = 1.5");
    let config: EstimatorConfig = toml::from_str(&text).unwrap();
    let error = Estimator::new(&config).unwrap_err().to_string();
    assert!(error.contains("inner_radius_mm = 1.5"), "{error}");
}
