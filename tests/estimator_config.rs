//! `dlw estimator-config` through the binary: TOML or JSON by extension, the design's geometry,
//! and clear refusals that write nothing.

use crate::common;
use common::{dlw, shipped_design as design};

use std::path::Path;

use dlw::design::Design;
use dlw_estimator::{EstimatorConfig, JointConfig, ModelConfig};

#[test]
fn toml_and_json_carry_the_same_config_from_the_design() {
    let dir = tempfile::tempdir().unwrap();
    let mut configs = Vec::new();
    for name in ["c.toml", "c.json"] {
        let out = dir.path().join(name).display().to_string();
        let o = dlw(&[
            "estimator-config",
            &design("joint-a.toml"),
            "--gauge-factor",
            "15.3",
            "--r0-ohm",
            "215e3",
            "-o",
            &out,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(&out).unwrap();
        let config: EstimatorConfig = if name.ends_with("toml") {
            assert!(
                text.starts_with("# Nominal linear estimator config for Joint A"),
                "{text}"
            );
            toml::from_str(&text).unwrap()
        } else {
            serde_json::from_str(&text).unwrap()
        };
        configs.push(config);
    }
    assert_eq!(configs[0], configs[1]);
    let c = &configs[0];
    let d = Design::load(Path::new(&design("joint-a.toml"))).unwrap();
    assert_eq!(c.joint, JointConfig::from_joint(&d.joint));
    assert_eq!(c.sensor.divider_ohm, 99.6e3);
    assert_eq!(c.sensor.supply_v, 5.0);
    match c.sensor.model {
        ModelConfig::Linear(m) => assert_eq!((m.gauge_factor, m.r0_ohm), (15.3, 215e3)),
        other => panic!("{other:?}"),
    }
    assert!(c.second_sensor.is_none());
}

#[test]
fn bsn_design_gets_two_sensors_and_per_sensor_values() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.toml").display().to_string();
    let o = dlw(&[
        "estimator-config",
        &design("joint-c.toml"),
        "--gauge-factor",
        "1.28",
        "--r0-ohm",
        "74e3",
        "--second-gauge-factor",
        "0.68",
        "--second-r0-ohm",
        "88.9e3",
        "--second-divider-ohm",
        "102.5e3",
        "--supply-v",
        "3.3",
        "-o",
        &out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let c: EstimatorConfig = toml::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let s2 = c.second_sensor.unwrap();
    assert_eq!((s2.divider_ohm, s2.supply_v), (102.5e3, 3.3));
    match s2.model {
        ModelConfig::Linear(m) => assert_eq!((m.gauge_factor, m.r0_ohm), (0.68, 88.9e3)),
        other => panic!("{other:?}"),
    }
}

#[test]
fn refusals_name_the_problem_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str], &str); 5] = [
        (
            "c.yaml",
            &["--gauge-factor", "15.3", "--r0-ohm", "215e3"],
            ".toml or .json",
        ),
        ("c.toml", &["--gauge-factor", "15.3", "--r0-ohm=-5"], "-5"),
        (
            "c.toml",
            &[
                "--gauge-factor",
                "15.3",
                "--r0-ohm",
                "215e3",
                "--divider-ohm",
                "0",
            ],
            "divider_ohm = 0",
        ),
        (
            "c.toml",
            &["--gauge-factor", "nan", "--r0-ohm", "215e3"],
            "NaN",
        ),
        (
            "c.toml",
            &[
                "--gauge-factor",
                "15.3",
                "--r0-ohm",
                "215e3",
                "--second-r0-ohm",
                "9e4",
            ],
            "need a BSN design",
        ),
    ];
    for (name, extra, needle) in cases {
        let out = dir.path().join(name).display().to_string();
        let mut args = vec!["estimator-config", "--output", &out];
        let d = design("joint-a.toml");
        args.push(&d);
        args.extend_from_slice(extra);
        let o = dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{extra:?} succeeded");
        assert!(err.contains(needle), "{extra:?}: {err}");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{extra:?} wrote a file"
        );
    }
}
