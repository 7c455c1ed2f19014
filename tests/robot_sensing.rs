//! The robot's sensing commands (issue 34 §1, §4): simulate, estimator-config, estimate and fit
//! on robot files, the crosstalk undone and ignored, and a fit on a recording from a generator
//! written here (other noise, another coupling form), written as files by hand.

// Index loops over joints and sensors read as the matrix formulas they check.
#![allow(clippy::needless_range_loop)]

use crate::common;

use std::path::{Path, PathBuf};

use common::{arg, dlw, dlw_ok, rng};
use dlw::recording::robot::RobotRecording;
use dlw::replay::robot::replay_robot;
use dlw::robot::estimator_config::{estimator_config, SensorSetting};
use dlw::robot::CheckedRobot;
use dlw::sim::robot::{plan_robot, Coupling, CouplingMatrix};
use dlw::sim::{ProtocolKind, Scenario};
use dlw_estimator::{LinearModel, ModelConfig};
use dlw_geometry::Divider;

fn designs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs")
}

fn robot(name: &str) -> CheckedRobot {
    CheckedRobot::load(&designs().join(name)).unwrap()
}

/// A crosstalk matrix well above the shipped robots' (whose routes keep it under 1 %), so that
/// ignoring it costs degrees: upper triangular by joint, as leads crossing proximal joints give.
const STRONG: [[f64; 3]; 3] = [[1.0, 0.08, -0.05], [0.0, 1.0, 0.06], [0.0, 0.0, 1.0]];

fn linear_settings(robot: &CheckedRobot) -> Vec<SensorSetting> {
    // The simulator's defaults for a UAN joint's sensor (Table III): GF 15.3, R0 215 kΩ.
    robot
        .sensors
        .iter()
        .map(|_| SensorSetting {
            model: ModelConfig::Linear(LinearModel::new(15.3, 215e3).unwrap()),
            divider: Divider::new(99.6e3, 5.0).unwrap(),
        })
        .collect()
}

fn quiet_random(seconds: f64) -> Scenario {
    let mut sc = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(seconds),
        ..Scenario::default()
    };
    sc.adc.enabled = false;
    sc.tracker.enabled = false;
    sc
}

#[test]
fn the_crosstalk_undone_gives_the_truth_and_ignoring_it_costs_what_the_matrix_predicts() {
    let robot = robot("robot-bdb.toml");
    let mut plan = plan_robot(&robot, quiet_random(20.0), Coupling::YorkSwaney).unwrap();
    plan.crosstalk = STRONG.iter().map(|r| r.to_vec()).collect();
    let run = plan.run().unwrap();
    let truth = run.true_angle_deg.clone();
    let recording = plan.recording(run);
    let settings = linear_settings(&robot);
    let with = estimator_config(&robot, &settings, &plan.crosstalk).unwrap();
    let undone = replay_robot(&with, &recording).unwrap();
    // Noise-free: the estimate is the truth to rounding.
    for j in 0..3 {
        let worst = undone.angle_est_deg[j]
            .iter()
            .zip(&truth[j])
            .map(|(e, t)| (e - t).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-6, "joint {}: {worst}°", j + 1);
    }
    let peak = truth[1].iter().fold(0.0f64, |m, a| m.max(a.abs()));
    assert!(peak > 10.0, "the joints bend: {peak}°");
    // Configured without the crosstalk (C = I), each joint reads its sensor's mixed angle:
    // the error is exactly (C − I)·θ.
    let identity: Vec<Vec<f64>> = (0..3)
        .map(|i| (0..3).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    let without = estimator_config(&robot, &settings, &identity).unwrap();
    let ignored = replay_robot(&without, &recording).unwrap();
    let mut predicted_sq = [0.0f64; 3];
    for k in 0..truth[0].len() {
        for j in 0..3 {
            let predicted: f64 = (0..3)
                .filter(|&m| m != j)
                .map(|m| STRONG[j][m] * truth[m][k])
                .sum();
            let error = ignored.angle_est_deg[j][k] - truth[j][k];
            assert!((error - predicted).abs() < 1e-6, "row {k} joint {j}");
            predicted_sq[j] += predicted * predicted;
        }
    }
    let n = truth[0].len() as f64;
    let metrics = ignored.joints.unwrap();
    for j in 0..2 {
        let predicted_rmse = (predicted_sq[j] / n).sqrt();
        assert!(predicted_rmse > 0.3, "joint {}: {predicted_rmse}°", j + 1);
        // The tracker is off, so the recorded angle is the truth.
        assert!((metrics[j].rmse_deg - predicted_rmse).abs() < 1e-6);
    }
}

#[test]
fn with_the_scenarios_noise_the_estimates_reach_the_noise_floor() {
    let robot = robot("robot-bdb.toml");
    let sc = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(20.0),
        ..Scenario::default()
    };
    let mut plan = plan_robot(&robot, sc, Coupling::YorkSwaney).unwrap();
    plan.crosstalk = STRONG.iter().map(|r| r.to_vec()).collect();
    let run = plan.run().unwrap();
    let truth = run.true_angle_deg.clone();
    let recording = plan.recording(run);
    let settings = linear_settings(&robot);
    let config = estimator_config(&robot, &settings, &plan.crosstalk).unwrap();
    let result = replay_robot(&config, &recording).unwrap();
    // The noise floor: the same estimator over the same robot with C = I and no crosstalk in
    // the simulation, i.e. each sensor read alone with the ADC's noise.
    let mut alone = plan_robot(
        &robot,
        plan.joints[0].scenario.clone(),
        Coupling::YorkSwaney,
    )
    .unwrap();
    let identity: Vec<Vec<f64>> = (0..3)
        .map(|i| (0..3).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    alone.crosstalk = identity.clone();
    let alone_run = alone.run().unwrap();
    let alone_truth = alone_run.true_angle_deg.clone();
    let alone_rec = alone.recording(alone_run);
    let floor = replay_robot(
        &estimator_config(&robot, &settings, &identity).unwrap(),
        &alone_rec,
    )
    .unwrap();
    let rms = |est: &[f64], t: &[f64]| {
        (est.iter().zip(t).map(|(e, t)| (e - t).powi(2)).sum::<f64>() / t.len() as f64).sqrt()
    };
    for j in 0..3 {
        let got = rms(&result.angle_est_deg[j], &truth[j]);
        let noise = rms(&floor.angle_est_deg[j], &alone_truth[j]);
        // Undoing C mixes the sensors' noise: at most the row sum of |C⁻¹| over the floor.
        assert!(
            got < 1.2 * noise + 1e-3,
            "joint {}: {got}° vs floor {noise}°",
            j + 1
        );
    }
}

#[test]
fn the_york_swaney_coupling_bends_proximal_joints_and_can_be_switched_off() {
    let robot = robot("robot-bdb.toml");
    let c = CouplingMatrix::of(&robot, Coupling::YorkSwaney);
    // Joint B at 0°, Joint D at 120° (same section): the distal tendon at y = −r_t·cos 120°
    // in joint 2's plane, arm ȳ + r_t·cos(120°) = 0.609 − 0.235 over joint 1's own
    // r_t + ȳ = 1.079 (equal stiffness).
    let expected = (0.60901 + 0.47 * (120f64).to_radians().cos()) / (0.47 + 0.60901);
    assert!(
        (c.positive[1][0] - expected).abs() < 1e-4,
        "{:?}",
        c.positive
    );
    assert_eq!(
        c.positive[0],
        vec![0.0; 3],
        "nothing bends the distal joint"
    );
    let none = CouplingMatrix::of(&robot, Coupling::None);
    assert!(none.positive.iter().flatten().all(|&v| v == 0.0));
    let mut out = [0.0; 3];
    c.apply(&[0.2, 0.0, 0.0], &mut out);
    assert!((out[1] - 0.2 * c.positive[1][0]).abs() < 1e-12);
    c.apply(&[-0.2, 0.0, 0.0], &mut out);
    assert_eq!(out[1], 0.0, "an opened UAN joint pulls no tendon");
}

#[test]
fn simulate_estimator_config_and_estimate_run_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bc.toml");
    let rec = d.join("rec");
    dlw_ok(&[
        "simulate",
        "--design",
        &arg(&robot),
        "--protocol",
        "random",
        "--duration-s",
        "10",
        "-o",
        &arg(&rec),
    ]);
    let data = std::fs::read_to_string(rec.join("data.csv")).unwrap();
    assert_eq!(
        data.lines().next().unwrap(),
        "time_s,stroke1_mm,stroke2_mm,angle1_deg,angle2_deg,v1_V,v2_V,v3_V,tip_x_mm,tip_y_mm,tip_z_mm"
    );
    let cfg = d.join("cfg.toml");
    let gf = ["15.3", "1.28", "0.68"];
    let r0 = ["215000", "74000", "88900"];
    let mut args = vec!["estimator-config".to_string(), arg(&robot)];
    for (g, r) in gf.iter().zip(r0) {
        args.extend(["--gauge-factor".into(), g.to_string()]);
        args.extend(["--r0-ohm".into(), r.to_string()]);
    }
    args.extend(["-o".into(), arg(&cfg)]);
    dlw_ok(&args);
    let o = dlw_ok(&[
        "estimate",
        "--config",
        &arg(&cfg),
        &arg(&rec),
        "--json",
        "--precision",
        "12",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let joints = v["joints"].as_array().unwrap();
    assert_eq!(joints.len(), 2);
    // Joint B reads well (a few tenths of a degree of the tracker's and ADC's noise); Joint C's
    // BSN sensors have gauge factors near 1, so the ADC's noise costs degrees, as for Joint C
    // alone.
    assert!(joints[0]["rmse_deg"].as_f64().unwrap() < 2.0, "{v}");
    assert!(v["tip"]["rmse_mm"].as_f64().unwrap() > 0.0, "{v}");
    assert!(v["warnings"].as_array().unwrap().is_empty(), "{v}");
    // The report: the shape's small multiples, the joints' errors, the crosstalk undone, its
    // numbers the run's.
    let report = d.join("report");
    dlw_ok(&[
        "estimate",
        "--config",
        &arg(&cfg),
        &arg(&rec),
        "--report",
        &arg(&report),
        "-o",
        &arg(&d.join("again.csv")),
    ]);
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    let rmse1 = format!("{:.3}", joints[0]["rmse_deg"].as_f64().unwrap());
    assert!(html.contains(&rmse1), "{rmse1} in the report");
    for f in 1..=8 {
        assert!(report.join(format!("shape-{f}.svg")).exists());
    }
    assert!(report.join("joint-errors.svg").exists());
    let est = std::fs::read_to_string(rec.join("estimates.csv")).unwrap();
    let mut lines = est.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time_s,angle1_est_deg,angle2_est_deg,tip_x_mm,tip_y_mm,tip_z_mm,flags"
    );
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        row[1].split('.').nth(1).unwrap().len(),
        12,
        "--precision 12"
    );
    // The library's replay of the same files gives the same numbers.
    let recording = RobotRecording::read(&rec).unwrap();
    let config = dlw::replay::load_robot_config(&cfg).unwrap();
    let replay = replay_robot(&config, &recording).unwrap();
    let last: Vec<f64> = est
        .lines()
        .last()
        .unwrap()
        .split(',')
        .skip(1)
        .take(5)
        .map(|f| f.parse().unwrap())
        .collect();
    let n = recording.samples.len() - 1;
    let lib = [
        replay.angle_est_deg[0][n],
        replay.angle_est_deg[1][n],
        replay.tip_mm[0][n],
        replay.tip_mm[1][n],
        replay.tip_mm[2][n],
    ];
    for (a, b) in last.iter().zip(lib) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
}

#[test]
fn robot_commands_refuse_bad_input_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bc.toml");
    let cfg = d.join("cfg.toml");
    let o = dlw(&[
        "estimator-config",
        &arg(&robot),
        "--gauge-factor",
        "15",
        "--gauge-factor",
        "1.3",
        "--r0-ohm",
        "1e5",
        "-o",
        &arg(&cfg),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success()
            && err.contains("--gauge-factor is given 2 times; the robot has 3 sensors"),
        "{err}"
    );
    assert!(!cfg.exists(), "no partial output");
    dlw_ok(&[
        "estimator-config",
        &arg(&robot),
        "--gauge-factor",
        "15",
        "--r0-ohm",
        "1e5",
        "-o",
        &arg(&cfg),
    ]);
    // A joint's recording given to a robot's config: the header is named.
    let joint_rec = d.join("joint");
    dlw_ok(&[
        "simulate",
        "--design",
        &arg(&designs().join("joint-b.toml")),
        "--protocol",
        "random",
        "--duration-s",
        "2",
        "-o",
        &arg(&joint_rec),
    ]);
    let o = dlw(&["estimate", "--config", &arg(&cfg), &arg(&joint_rec)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("line 1: header is"),
        "{err}"
    );
    assert!(err.contains("stroke1_mm"), "{err}");
    let o = dlw(&[
        "simulate",
        "--design",
        &arg(&designs().join("joint-b.toml")),
        "--protocol",
        "random",
        "--coupling",
        "none",
        "-o",
        &arg(&d.join("x")),
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--coupling is for a robot"));
}

/// The test's own generator: Joint B-D-B's sensors with gauge factors and crosstalk of its
/// own, a coupling of another form (each proximal joint bent by a share of the squared distal
/// angle), uniform (not Gaussian) ADC noise and a tracker with a slow sinusoidal error.
struct Generator {
    gauge_factor: [f64; 3],
    r0_ohm: [f64; 3],
    crosstalk: [[f64; 3]; 3],
}

const GENERATOR: Generator = Generator {
    gauge_factor: [14.2, 16.8, 15.9],
    r0_ohm: [201e3, 230e3, 188e3],
    crosstalk: [[1.0, 0.07, -0.045], [0.0, 1.0, 0.055], [0.0, 0.0, 1.0]],
};

/// `together`: every joint follows joint 1's angle (no coupling), so no recording can tell
/// them apart.
fn write_generated(dir: &Path, strain_per_rad: [f64; 3], together: bool) {
    let mut rng = rng::Rng::new(34);
    let hz = 200.0;
    let rows = 8000;
    let divider = 99.6e3;
    let supply = 5.0;
    // Each joint a sum of two sines of its own frequencies and phases (rad).
    let freqs = [[0.13, 0.71], [0.29, 0.47], [0.19, 0.83]];
    let mut csv = String::from(
        "time_s,stroke1_mm,stroke2_mm,stroke3_mm,angle1_deg,angle2_deg,angle3_deg,v1_V,v2_V,v3_V\n",
    );
    for k in 0..rows {
        let t = k as f64 / hz;
        let mut theta = [0.0f64; 3];
        for j in 0..3 {
            theta[j] = 0.25 * (std::f64::consts::TAU * freqs[j][0] * t + j as f64).sin()
                + 0.12 * (std::f64::consts::TAU * freqs[j][1] * t + 2.0 * j as f64).sin();
        }
        if together {
            theta = [theta[0]; 3];
        } else {
            // Another coupling form: quadratic in the distal angle.
            theta[1] += 0.3 * theta[0] * theta[0];
            theta[2] += 0.2 * theta[1] * theta[1].abs();
        }
        csv.push_str(&format!("{t:.6}"));
        for th in theta {
            csv.push_str(&format!(",{:.6}", th * 2.0));
        }
        for th in theta {
            let tracker_error = 0.05 * (0.5 * t).sin();
            csv.push_str(&format!(",{:.6}", th.to_degrees() + tracker_error));
        }
        for i in 0..3 {
            let a: f64 = (0..3).map(|j| GENERATOR.crosstalk[i][j] * theta[j]).sum();
            let r = GENERATOR.r0_ohm[i] * (1.0 + GENERATOR.gauge_factor[i] * strain_per_rad[i] * a);
            let v = supply * r / (r + divider) + 2e-3 * (rng.uniform() - 0.5);
            csv.push_str(&format!(",{v:.6}"));
        }
        csv.push('\n');
    }
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("data.csv"), csv).unwrap();
    std::fs::write(
        dir.join("rig.toml"),
        format!("sample_hz = {hz}\nsupply_v = {supply}\ndivider_ohm = [{divider}, {divider}, {divider}]\nnotes = \"written by the test's generator\"\n"),
    )
    .unwrap();
}

#[test]
fn fit_recovers_each_sensors_gauge_factor_and_crosstalk_from_another_generator() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bdb.toml");
    // The strain per radian from dlw inspect's numbers (Eq. 3).
    let o = dlw_ok(&["inspect", &arg(&robot), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let k: Vec<f64> = v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["strain_per_deg"].as_f64().unwrap().to_degrees())
        .collect();
    let rec = d.join("rec");
    write_generated(&rec, [k[0], k[1], k[2]], false);
    let cfg = d.join("fitted.toml");
    let o = dlw_ok(&[
        "fit",
        "--design",
        &arg(&robot),
        &arg(&rec),
        "--model",
        "linear",
        "-o",
        &arg(&cfg),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let sensors = v["sensors"].as_array().unwrap();
    assert_eq!(sensors.len(), 3);
    eprintln!("fitted: {}", serde_json::to_string(sensors).unwrap());
    for (i, s) in sensors.iter().enumerate() {
        let gf = s["gauge_factor"].as_f64().unwrap();
        let want = GENERATOR.gauge_factor[i];
        assert!(
            (gf / want - 1.0).abs() < 0.01,
            "sensor {}: GF {gf} vs {want}",
            i + 1
        );
        let r0 = s["r0_ohm"].as_f64().unwrap();
        assert!(
            (r0 / GENERATOR.r0_ohm[i] - 1.0).abs() < 0.01,
            "sensor {}: R0 {r0}",
            i + 1
        );
        let c: Vec<f64> = s["crosstalk"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        for j in 0..3 {
            assert!(
                (c[j] - GENERATOR.crosstalk[i][j]).abs() < 0.02,
                "sensor {} crosstalk[{j}] = {} vs {}",
                i + 1,
                c[j],
                GENERATOR.crosstalk[i][j]
            );
        }
    }
    // The fitted config is one estimate runs, and it reads the generator's angles back.
    let o = dlw_ok(&["estimate", "--config", &arg(&cfg), &arg(&rec), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for j in v["joints"].as_array().unwrap() {
        assert!(j["rmse_deg"].as_f64().unwrap() < 0.5, "{v}");
    }
    // Joints that move together cannot be told apart: the crosstalk stays the geometry's, and
    // the fit says so.
    let same = d.join("same");
    write_generated(&same, [k[0], k[1], k[2]], true);
    let o = dlw_ok(&[
        "fit",
        "--design",
        &arg(&robot),
        &arg(&same),
        "--model",
        "linear",
        "-o",
        &arg(&d.join("same.toml")),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["crosstalk_fitted"], false, "{v}");
    let warning = v["warnings"][0].as_str().unwrap();
    assert!(
        warning.contains("cannot tell the joints apart"),
        "{warning}"
    );
    for (i, s) in v["sensors"].as_array().unwrap().iter().enumerate() {
        assert_eq!(s["crosstalk"], s["crosstalk_geometry"], "{v}");
        // Each sensor's line on its mixed angle through the geometry's row: the joints move
        // alike, so the sensor's gain is the generator's over its row sum against the
        // geometry's (within the 1 % the fit promises).
        let gf = s["gauge_factor"].as_f64().unwrap();
        let c = &GENERATOR.crosstalk[i];
        let geometry: Vec<f64> = s["crosstalk_geometry"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let want = GENERATOR.gauge_factor[i] * c.iter().sum::<f64>() / geometry.iter().sum::<f64>();
        assert!(
            (gf / want - 1.0).abs() < 0.01,
            "sensor {}: {gf} vs {want}",
            i + 1
        );
    }
}

/// `crates/estimator/tests/data/robot-runtime.json` holds a robot config (linear, PI and
/// continuous PI sensors), voltages and the runtime's angles and tip, which the Python tests
/// (`dlw.RobotEstimator`, `dlw.tip`) and, through the same runtime, the C example
/// (`crates/estimator-ffi/tests/c_example.rs`) match to 1e-9. `dlw estimate` over the same
/// voltages, written as a robot recording, matches it to 1e-9 too: its first 30 rows, before the
/// golden's rail and NaN samples, which a recording refuses at the reader.
#[test]
fn dlw_estimate_agrees_with_the_runtime_golden_file_that_c_and_python_match() {
    let golden: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("crates/estimator/tests/data/robot-runtime.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let rows = 30;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cfg = d.join("cfg.toml");
    let config_toml = golden["config_toml"].as_str().unwrap();
    std::fs::write(&cfg, config_toml).unwrap();
    let config = dlw::replay::load_robot_config(&cfg).unwrap();
    let (n, m) = (config.joint_count(), config.sensor_count());
    let rec = d.join("rec");
    std::fs::create_dir(&rec).unwrap();
    let dividers: Vec<String> = config
        .sensor
        .iter()
        .map(|s| format!("{:?}", s.divider_ohm))
        .collect();
    std::fs::write(
        rec.join("rig.toml"),
        format!(
            "sample_hz = 500.0\nsupply_v = 5.0\ndivider_ohm = [{}]\n",
            dividers.join(", ")
        ),
    )
    .unwrap();
    let mut csv = dlw::recording::robot::robot_header(n, m, false);
    csv.push('\n');
    for k in 0..rows {
        csv.push_str(&format!("{:?}", k as f64 / 500.0));
        for _ in 0..n {
            csv.push_str(",0");
        }
        for j in 0..n {
            csv.push_str(&format!(
                ",{:?}",
                golden["angles_deg"][k][j].as_f64().unwrap()
            ));
        }
        for i in 0..m {
            csv.push_str(&format!(",{:?}", golden["volts"][k][i].as_f64().unwrap()));
        }
        csv.push('\n');
    }
    std::fs::write(rec.join("data.csv"), csv).unwrap();
    let out = d.join("estimates.csv");
    dlw_ok(&[
        "estimate",
        "--config",
        &arg(&cfg),
        &arg(&rec),
        "--precision",
        "15",
        "-o",
        &arg(&out),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    let (mut worst_deg, mut worst_mm) = (0.0f64, 0.0f64);
    for (k, line) in text.lines().skip(1).enumerate() {
        let f: Vec<f64> = line
            .split(',')
            .skip(1)
            .take(n + 3)
            .map(|x| x.parse().unwrap())
            .collect();
        for j in 0..n {
            worst_deg = worst_deg.max((f[j] - golden["angles_deg"][k][j].as_f64().unwrap()).abs());
        }
        for c in 0..3 {
            let want = golden["tip_position_mm"][k][c].as_f64().unwrap();
            worst_mm = worst_mm.max((f[n + c] - want).abs());
        }
    }
    assert_eq!(text.lines().count(), rows + 1);
    assert!(
        worst_deg <= 1e-9,
        "dlw estimate and the golden differ by {worst_deg:e}°"
    );
    assert!(worst_mm <= 1e-9, "tips differ by {worst_mm:e} mm");
}

/// A robot recording whose column `column` (0-based in `data.csv`) is rewritten by `edit`,
/// given each row's fields.
fn robot_recording_edited(dir: &Path, column: usize, edit: impl Fn(usize, &mut String)) {
    write_generated(dir, [0.01; 3], false);
    let text = std::fs::read_to_string(dir.join("data.csv")).unwrap();
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        let mut fields: Vec<String> = line.split(',').map(str::to_owned).collect();
        if i > 0 {
            edit(i - 1, &mut fields[column]);
        }
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    std::fs::write(dir.join("data.csv"), out).unwrap();
}

/// `dlw fit --design ROBOT REC --model linear -o OUT`.
fn fit_linear(robot: &Path, rec: &Path, out: &Path) -> std::process::Output {
    dlw(&[
        "fit",
        "--design",
        &arg(robot),
        &arg(rec),
        "--model",
        "linear",
        "-o",
        &arg(out),
    ])
}

#[test]
fn fit_refuses_a_clipped_voltage_and_a_frozen_angle_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bdb.toml");
    // data.csv: time, 3 strokes, 3 angles, 3 voltages.
    let clipped = d.join("clipped");
    write_generated(&clipped, [0.01; 3], false);
    let text = std::fs::read_to_string(clipped.join("data.csv")).unwrap();
    let mut v2: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(8).unwrap().parse().unwrap())
        .collect();
    v2.sort_by(f64::total_cmp);
    // v2 held at its 90th percentile from above.
    let top = v2[v2.len() * 9 / 10];
    robot_recording_edited(&clipped, 8, |_, field| {
        if field.parse::<f64>().unwrap() > top {
            *field = format!("{top:.6}");
        }
    });
    // Joint 2's angle held for 5 s (rows 2000-2999 at 200 Hz) while its stroke moves.
    let frozen = d.join("frozen");
    let held = std::cell::RefCell::new(String::new());
    robot_recording_edited(&frozen, 5, |row, field| {
        if row == 2000 {
            *held.borrow_mut() = field.clone();
        }
        if (2000..3000).contains(&row) {
            *field = held.borrow().clone();
        }
    });
    for (rec, column, what) in [
        (&clipped, "v2_V", "largest"),
        (&frozen, "angle2_deg", "stopped updating"),
    ] {
        let out = d.join("out.toml");
        let o = fit_linear(&robot, rec, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success(),
            "a robot recording with {column} {what} was fitted"
        );
        assert!(err.contains(column) && err.contains(what), "{err}");
        assert!(!out.exists());
    }
}

/// The tracker 200 ms behind the DAQ (every joint's angle, one tracker: one clock): `fit`
/// refuses the recording naming both delays (`src/recording/clock.rs`, `check_robot`); on time
/// it fits.
#[test]
fn fit_refuses_a_tracker_late_against_the_daq() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bdb.toml");
    let (on_time, late) = (d.join("on-time"), d.join("late"));
    write_generated(&on_time, [0.01; 3], false);
    write_generated(&late, [0.01; 3], false);
    // 40 rows at 200 Hz; data.csv: time, 3 strokes, 3 angles (columns 4-6), 3 voltages.
    let rows = 40;
    let text = std::fs::read_to_string(late.join("data.csv")).unwrap();
    let table: Vec<Vec<String>> = text
        .lines()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    // Each row's angles from `rows` rows before; the first `rows` rows, which have none, left
    // out (held, they would be refused as frozen: the generator's joints move from the start).
    let mut out = table[0].join(",") + "\n";
    for i in 1 + rows..table.len() {
        let mut row = table[i].clone();
        row[4..7].clone_from_slice(&table[i - rows][4..7]);
        out.push_str(&row.join(","));
        out.push('\n');
    }
    std::fs::write(late.join("data.csv"), out).unwrap();
    let fit = |rec: &Path, out: &Path| fit_linear(&robot, rec, out);
    let out = d.join("late.toml");
    let o = fit(&late, &out);
    let err = String::from_utf8_lossy(&o.stderr);
    eprintln!("{err}");
    assert!(
        !o.status.success(),
        "a robot recording 200 ms late was fitted"
    );
    for part in [
        "angle is late",
        "against the stroke",
        "against the sensors' voltages",
    ] {
        assert!(err.contains(part), "{part:?} not in {err}");
    }
    assert!(!out.exists());
    let o = fit(&on_time, &d.join("on-time.toml"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
