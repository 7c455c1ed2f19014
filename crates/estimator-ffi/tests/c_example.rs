//! examples/c/estimate_recording.c, compiled with the system's `cc` against the static library,
//! prints the angles `dlw estimate` computes over the same recording (to 1e-9), for a one-sensor
//! (UAN) and a two-sensor (BSN) joint; and refuses a bad config with the reason.

use std::path::{Path, PathBuf};
use std::process::Command;

use dlw::design::Design;
use dlw::replay::{config_text, replay, ConfigFormat};
use dlw::sim::{self, ProtocolKind, Recording, Scenario};
use runtime::{
    nominal_divider, EstimatorConfig, JointConfig, LinearModel, ModelConfig, SensorConfig,
};

/// Agreement demanded between the C library and `dlw estimate` (degrees).
const TOLERANCE_DEG: f64 = 1e-9;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// target/<profile>/, where cargo put libdlw_estimator.a for this test.
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps/<test>")
        .to_path_buf()
}

fn compile(dir: &Path) -> PathBuf {
    let exe = dir.join("estimate_recording");
    // `cargo test` builds only the rlib: build the static library (a no-op when current).
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let built = Command::new(cargo)
        .args(["build", "--quiet", "--lib", "-p", "dlw-estimator-ffi"])
        .current_dir(workspace())
        .status()
        .expect("cargo runs");
    assert!(built.success(), "cargo build -p dlw-estimator-ffi failed");
    let lib = profile_dir().join("libdlw_estimator.a");
    assert!(lib.exists(), "{} was not built", lib.display());
    let out = Command::new("cc")
        .arg("-I")
        .arg(workspace().join("crates/estimator-ffi/include"))
        .arg(workspace().join("examples/c/estimate_recording.c"))
        .arg(&lib)
        .args(["-lm", "-lpthread", "-ldl", "-o"])
        .arg(&exe)
        .output()
        .expect("cc runs");
    assert!(
        out.status.success(),
        "cc failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

fn check(design_name: &str, two_sensors: bool) {
    let dir = tempfile::tempdir().unwrap();
    let design = Design::load(&workspace().join("designs").join(design_name)).unwrap();
    let scenario = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(20.0),
        ..Scenario::default()
    };
    let plan = sim::plan(&design, scenario, None).unwrap();
    let run = plan.run().unwrap();
    let recording = Recording {
        rig: plan.rig(),
        samples: run.samples,
    };
    let rec_dir = dir.path().join("rec");
    recording.write(&rec_dir, false).unwrap();

    let joint = JointConfig::from_joint(&design.joint);
    let mut config =
        EstimatorConfig::nominal_linear(joint, 15.3, 215.0e3, nominal_divider()).unwrap();
    if two_sensors {
        let model = LinearModel::new(15.3, 215.0e3).unwrap();
        config.second_sensor = Some(SensorConfig::new(
            nominal_divider(),
            ModelConfig::Linear(model),
        ));
    }
    let config_path = dir.path().join("config.toml");
    std::fs::write(
        &config_path,
        config_text(&config, ConfigFormat::Toml, "test").unwrap(),
    )
    .unwrap();

    // What `dlw estimate --precision 15` writes (its library call and CSV writer).
    let recording = Recording::read(&rec_dir).unwrap();
    let loaded = dlw::replay::load_config(&config_path).unwrap();
    let csv = String::from_utf8(
        replay(&loaded, &recording)
            .unwrap()
            .csv_bytes_with(&recording, 15),
    )
    .unwrap();
    let expected: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();

    let exe = compile(dir.path());
    let out = Command::new(&exe)
        .arg(&config_path)
        .arg(rec_dir.join("data.csv"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let got: Vec<f64> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(got.len(), expected.len(), "one angle per sample");
    let worst = got
        .iter()
        .zip(&expected)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        worst <= TOLERANCE_DEG,
        "{design_name}: C and dlw estimate differ by {worst:e}°"
    );
    let peak = expected.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    assert!(peak > 1.0, "the recording bends the joint (peak {peak}°)");
}

#[test]
fn c_example_matches_dlw_estimate_one_sensor() {
    check("joint-a.toml", false);
}

#[test]
fn c_example_matches_dlw_estimate_two_sensors() {
    let design = Design::load(&workspace().join("designs/joint-c.toml")).unwrap();
    assert_eq!(
        design.joint.style(),
        dlw_geometry_style_bsn(),
        "joint C is BSN"
    );
    check("joint-c.toml", true);
}

fn dlw_geometry_style_bsn() -> dlw_geometry::NotchStyle {
    dlw_geometry::NotchStyle::Bsn
}

#[test]
fn c_example_reports_a_bad_config() {
    let dir = tempfile::tempdir().unwrap();
    let exe = compile(dir.path());
    let config = dir.path().join("bad.toml");
    std::fs::write(&config, "not = [valid").unwrap();
    let data = dir.path().join("data.csv");
    std::fs::write(&data, "time_s,stroke_mm,angle_deg,v1_V\n0,0,0,2.5\n").unwrap();
    let out = Command::new(&exe).arg(&config).arg(&data).output().unwrap();
    assert!(!out.status.success());
    assert!(out.stdout.is_empty(), "no partial output");
    assert!(String::from_utf8_lossy(&out.stderr).contains("estimator config"));
}
