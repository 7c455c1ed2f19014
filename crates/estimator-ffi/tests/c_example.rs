//! examples/c/estimate_recording.c, compiled with the system's `cc` against the static library,
//! prints the angles `dlw estimate` computes over the same recording (to 1e-9), for a one-sensor
//! (UAN) and a two-sensor (BSN) joint; and refuses a bad config with the reason.
//! examples/c/estimate_robot.c prints the joint angles, flags and tip the Rust robot estimator
//! computes over the same robot recording (to 1e-9), and refuses a bad config likewise.

// The shared robot fixture names the runtime crate by its own name.
extern crate runtime as dlw_estimator;

#[path = "../../estimator/tests/common/robot.rs"]
mod robot;

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
    compile_example(dir, "estimate_recording")
}

/// examples/c/`name`.c compiled against the static library, into `dir`.
fn compile_example(dir: &Path, name: &str) -> PathBuf {
    let exe = dir.join(name);
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
        .arg(workspace().join(format!("examples/c/{name}.c")))
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

/// A robot recording of the B-C-B fixture robot (four sensors, crosstalk), written as the
/// robot recording's columns, with a rail and a NaN sample: the C example's angles, flags and
/// tip against the Rust runtime's on the voltages as read back from the file.
#[test]
fn c_robot_example_matches_the_rust_runtime() {
    use runtime::{RobotEstimator, RobotEstimatorConfig};
    let dir = tempfile::tempdir().unwrap();
    let config = robot::bcb_linear();
    let mut sensors = robot::Sensors::new(&config);
    let mut csv = String::from(
        "time_s,stroke1_mm,stroke2_mm,stroke3_mm,angle1_deg,angle2_deg,angle3_deg,v1_V,v2_V,v3_V,v4_V\n",
    );
    for k in 0..400 {
        let theta = robot::trajectory(k, 3, 0.6);
        let mut volts = sensors.volts(&theta);
        if k == 100 {
            volts[0] = 5.0;
        }
        if k == 200 {
            volts[3] = f64::NAN;
        }
        let degrees: Vec<String> = theta.iter().map(|t| t.to_degrees().to_string()).collect();
        let volts: Vec<String> = volts.iter().map(|v| v.to_string()).collect();
        csv.push_str(&format!(
            "{},0,0,0,{},{}\n",
            k as f64 * 0.002,
            degrees.join(","),
            volts.join(",")
        ));
    }
    let data = dir.path().join("data.csv");
    std::fs::write(&data, &csv).unwrap();
    let config_path = dir.path().join("robot.toml");
    std::fs::write(&config_path, toml::to_string(&config).unwrap()).unwrap();

    // The Rust runtime on the voltages as the file holds them.
    let read: RobotEstimatorConfig =
        toml::from_str(&std::fs::read_to_string(&config_path).unwrap()).unwrap();
    let mut estimator = Box::new(RobotEstimator::new(&read).unwrap());
    let expected: Vec<(Vec<f64>, [f64; 3], Vec<u32>)> = csv
        .lines()
        .skip(1)
        .map(|line| {
            let volts: Vec<f64> = line
                .split(',')
                .skip(7)
                .map(|v| v.parse().unwrap())
                .collect();
            let e = estimator.step(&volts);
            let tip = estimator.tip(&e).unwrap();
            (
                (0..3).map(|j| e.angle_deg(j)).collect(),
                tip.position_mm,
                e.flags().iter().map(|f| u32::from(f.bits())).collect(),
            )
        })
        .collect();

    let exe = compile_example(dir.path(), "estimate_robot");
    let out = Command::new(&exe)
        .arg(&config_path)
        .arg(&data)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<String> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect();
    assert_eq!(lines.len(), expected.len(), "one line per sample");
    let (mut worst_deg, mut worst_mm, mut flagged) = (0.0f64, 0.0f64, 0);
    for (line, (angles, tip, flags)) in lines.iter().zip(&expected) {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), 9, "{line}");
        for j in 0..3 {
            let got: f64 = fields[j].parse().unwrap();
            worst_deg = worst_deg.max((got - angles[j]).abs());
            let got_flags: u32 = fields[6 + j].parse().unwrap();
            assert_eq!(got_flags, flags[j], "{line}");
            flagged += usize::from(got_flags != 0);
        }
        for i in 0..3 {
            let got: f64 = fields[3 + i].parse().unwrap();
            worst_mm = worst_mm.max((got - tip[i]).abs());
        }
    }
    assert!(
        worst_deg <= TOLERANCE_DEG,
        "C and Rust differ by {worst_deg:e}°"
    );
    assert!(
        worst_mm <= 1e-9,
        "C and Rust tips differ by {worst_mm:e} mm"
    );
    // The rail flags joint 1 (one sample), the NaN every joint (one sample).
    assert_eq!(flagged, 1 + 3, "flags set");
    let peak = expected
        .iter()
        .flat_map(|e| e.0.clone())
        .fold(0.0f64, |m, a| m.max(a.abs()));
    assert!(peak > 10.0, "the recording bends the joints (peak {peak}°)");
}

#[test]
fn c_robot_example_reports_a_bad_config() {
    let dir = tempfile::tempdir().unwrap();
    let exe = compile_example(dir.path(), "estimate_robot");
    let mut config = robot::bcb_linear();
    config.sensor.as_mut_slice()[1].crosstalk.as_mut_slice()[0] = f64::NAN;
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, toml::to_string(&config).unwrap()).unwrap();
    let data = dir.path().join("data.csv");
    std::fs::write(&data, "time_s,v1_V,v2_V,v3_V,v4_V\n0,2.5,2.5,2.5,2.5\n").unwrap();
    let out = Command::new(&exe).arg(&path).arg(&data).output().unwrap();
    assert!(!out.status.success());
    assert!(out.stdout.is_empty(), "no partial output");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("sensor 2: crosstalk[1] = NaN is not a finite number"),
        "{stderr}"
    );
}
