//! `dlw control` for a robot (issue 34 §4): every joint's closed loop on its estimated angle,
//! the tendons coupled, the crosstalk undone; the same loops on a config that does not undo it;
//! the command line's outputs and refusals.

// Index loops over joints read as the matrix formulas they check.
#![allow(clippy::needless_range_loop)]

use crate::common;

use std::path::{Path, PathBuf};

use common::{arg, dlw, dlw_ok};
use dlw::control::robot::RobotControl;
use dlw::control::{Scheme, PAPER_GAINS};
use dlw::robot::estimator_config::{estimator_config, SensorSetting};
use dlw::robot::CheckedRobot;
use dlw::sim::robot::Coupling;
use dlw::sim::{ProtocolKind, Scenario};
use dlw_estimator::{FilterConfig, LinearModel, ModelConfig, RobotEstimatorConfig};
use dlw_geometry::Divider;

fn designs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs")
}

fn robot(name: &str) -> CheckedRobot {
    CheckedRobot::load(&designs().join(name)).unwrap()
}

/// A crosstalk matrix well above the shipped robots' (under 1 %), so that not undoing it costs
/// degrees (the one `tests/robot_sensing.rs` estimates with).
const STRONG: [[f64; 3]; 3] = [[1.0, 0.08, -0.05], [0.0, 1.0, 0.06], [0.0, 0.0, 1.0]];

/// The paper's moving average on the sensed angle, which its gains need (`docs/robots.md`).
const FILTER: FilterConfig = FilterConfig::MovingAverage { samples: 50 };

/// The simulator's bench sensor for every sensor (GF 15.3, R₀ 215 kΩ, 99.6 kΩ divider), the
/// crosstalk `c` undone, the sensed angle filtered.
fn config(robot: &CheckedRobot, c: &[Vec<f64>]) -> RobotEstimatorConfig {
    let settings: Vec<SensorSetting> = robot
        .sensors
        .iter()
        .map(|_| SensorSetting {
            model: ModelConfig::Linear(LinearModel::new(15.3, 215e3).unwrap()),
            divider: Divider::new(99.6e3, 5.0).unwrap(),
        })
        .collect();
    let mut config = estimator_config(robot, &settings, c).unwrap();
    config.output_filter = FILTER;
    config
}

fn identity(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect()
}

fn random(seconds: f64, noise: bool) -> Scenario {
    let mut sc = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(seconds),
        seed: 5,
        ..Scenario::default()
    };
    sc.adc.enabled = noise;
    sc.tracker.enabled = noise;
    sc
}

fn rms(v: impl Iterator<Item = f64>) -> f64 {
    let (mut s, mut n) = (0.0, 0usize);
    for x in v {
        s += x * x;
        n += 1;
    }
    (s / n.max(1) as f64).sqrt()
}

fn control(robot: &CheckedRobot, scenario: Scenario, c: &[Vec<f64>]) -> RobotControl {
    RobotControl::new(
        robot,
        scenario,
        &[],
        config(robot, c),
        PAPER_GAINS,
        None,
        Coupling::YorkSwaney,
    )
    .unwrap()
}

/// The bound: with the coupling on, each joint's closed loop on its estimate tracks its desired
/// angle within its noise-free loop's error plus 1.5 times the noise the estimator passes
/// (`σ_n`, the RMS of the estimate with noise minus the estimate without it, measured in open
/// loop, where the joint moves the same with and without noise). Minkowski: the noisy loop's
/// error is at most the quiet loop's plus the RMS the noise moves the joint by, and a stable
/// loop moves it by about the sensing noise within its bandwidth, not more (1.5 allows its
/// resonance). The open loop, which does not know the coupling, is ten times worse on the
/// coupled joints.
#[test]
fn each_joint_tracks_its_estimate_within_the_noise_with_the_coupling_on() {
    let robot = robot("robot-bdb.toml");
    let geometric = robot.crosstalk_matrix();
    let quiet = control(&robot, random(20.0, false), &geometric);
    let noisy = control(&robot, random(20.0, true), &geometric);
    let (q, n) = (quiet.run().unwrap(), noisy.run().unwrap());
    for j in 0..3 {
        let desired = &noisy.joints[j].desired.angle_deg;
        assert_eq!(desired, &quiet.joints[j].desired.angle_deg);
        let peak = desired.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        assert!(peak > 10.0, "joint {} moves: {peak}°", j + 1);
        let [q_open, q_closed] = [&q.traces[0].joints[j], &q.traces[1].joints[j]];
        let [n_open, n_closed] = [&n.traces[0].joints[j], &n.traces[1].joints[j]];
        // Open loop: the same joint motion with and without noise.
        assert_eq!(q_open.true_deg, n_open.true_deg);
        let sigma_n = rms(n_open
            .sensed_deg
            .iter()
            .zip(&q_open.sensed_deg)
            .map(|(a, b)| a - b));
        assert!(
            sigma_n > 0.05,
            "joint {}: the noise reaches the estimate: {sigma_n}°",
            j + 1
        );
        let err = |t: &dlw::control::Trace| rms(t.true_deg.iter().zip(desired).map(|(a, b)| a - b));
        let (quiet_err, noisy_err) = (err(q_closed), err(n_closed));
        let bound = quiet_err + 1.5 * sigma_n;
        eprintln!(
            "joint {}: closed loop {noisy_err:.3}° (quiet {quiet_err:.3}°, σ_n {sigma_n:.3}°, bound {bound:.3}°), open loop {:.3}°",
            j + 1,
            err(n_open)
        );
        assert!(
            noisy_err <= bound,
            "joint {}: {noisy_err}° > {bound}°",
            j + 1
        );
        assert_eq!(n.metrics[j][1].true_vs_desired_rmse_deg, noisy_err);
        if j > 0 {
            // Joints 2 and 3 carry the distal tendons: the open loop misses by their bending.
            assert!(
                err(n_open) > 10.0 * noisy_err,
                "joint {}: open {}°",
                j + 1,
                err(n_open)
            );
        }
    }
}

/// Closing the loops on a config that does not undo the crosstalk (`C = I`, the crosstalk
/// matrix of up to 8 %): each joint tracks its sensor's mixed angle instead of its own, so it
/// ends `Σ_{m≠j} C[j][m]·θ_m` away from where the loop with the crosstalk undone puts it, and
/// tracks measurably worse; a joint whose sensor reads no other joint (joint 3) does not.
/// Noise off, so the difference is the crosstalk's alone.
#[test]
fn not_undoing_the_crosstalk_tracks_worse_by_what_the_matrix_predicts() {
    let robot = robot("robot-bdb.toml");
    let strong: Vec<Vec<f64>> = STRONG.iter().map(|r| r.to_vec()).collect();
    let mut undone = control(&robot, random(20.0, false), &strong);
    undone.crosstalk = strong.clone();
    let mut ignored = control(&robot, random(20.0, false), &identity(3));
    ignored.crosstalk = strong.clone();
    let u = undone.run_scheme(Scheme::ClosedLoop).unwrap();
    let i = ignored.run_scheme(Scheme::ClosedLoop).unwrap();
    for j in 0..3 {
        let desired = &undone.joints[j].desired.angle_deg;
        let err = |t: &dlw::control::Trace| rms(t.true_deg.iter().zip(desired).map(|(a, b)| a - b));
        let rows = desired.len();
        // The loop on the mixed angle holds θ_j + Σ C θ_m where the other holds θ_j.
        let predicted: Vec<f64> = (0..rows)
            .map(|k| {
                (0..3)
                    .filter(|&m| m != j)
                    .map(|m| STRONG[j][m] * i.joints[m].true_deg[k])
                    .sum()
            })
            .collect();
        let predicted_rms = rms(predicted.iter().copied());
        let miss =
            rms((0..rows)
                .map(|k| (u.joints[j].true_deg[k] - i.joints[j].true_deg[k]) - predicted[k]));
        eprintln!(
            "joint {}: undone {:.3}°, ignored {:.3}°, predicted shift {predicted_rms:.3}°, shift − prediction {miss:.3}°",
            j + 1,
            err(&u.joints[j]),
            err(&i.joints[j])
        );
        if j < 2 {
            assert!(predicted_rms > 0.3, "joint {}: {predicted_rms}°", j + 1);
            assert!(
                miss < 0.25 * predicted_rms,
                "joint {}: {miss}° of {predicted_rms}°",
                j + 1
            );
            assert!(
                err(&i.joints[j]) > 1.5 * err(&u.joints[j]),
                "joint {}: ignored {}°, undone {}°",
                j + 1,
                err(&i.joints[j]),
                err(&u.joints[j])
            );
        } else {
            assert_eq!(predicted_rms, 0.0);
            let (a, b) = (err(&i.joints[j]), err(&u.joints[j]));
            assert!((a - b).abs() < 0.1 * b, "joint 3: {a}° against {b}°");
        }
    }
}

fn estimator_config_cli(dir: &Path, name: &str) -> PathBuf {
    let cfg = dir.join(name);
    dlw_ok(&[
        "estimator-config",
        &arg(&designs().join("robot-bdb.toml")),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&cfg),
    ]);
    cfg
}

fn csv_columns(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let mut columns = vec![Vec::new(); header.len()];
    for line in lines {
        for (c, v) in columns.iter_mut().zip(line.split(',')) {
            c.push(v.parse::<f64>().unwrap());
        }
    }
    (header, columns)
}

/// The command line: `--json` has each joint's tracking RMSE and max, `control.csv` each
/// joint's columns, and they agree (the JSON's RMSE recomputed from the CSV's rounded columns).
#[test]
fn the_command_writes_every_joints_columns_and_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = estimator_config_cli(dir.path(), "robot.toml");
    let out = dir.path().join("ctl");
    let o = dlw_ok(&[
        "control",
        "--design",
        &arg(&designs().join("robot-bdb.toml")),
        "--config",
        &arg(&cfg),
        "--protocol",
        "random",
        "--duration-s",
        "10",
        "--filter",
        "ma:50",
        "-o",
        &arg(&out),
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["coupling"], "york-swaney");
    let joints = json["joints"].as_array().unwrap();
    assert_eq!(joints.len(), 3);
    let text = std::fs::read_to_string(out.join("control.csv")).unwrap();
    let (header, columns) = csv_columns(&text);
    assert_eq!(json["samples"], columns[0].len());
    let col = |name: &str| {
        let i = header.iter().position(|h| h == name).unwrap_or_else(|| {
            panic!("{name} in {header:?}");
        });
        &columns[i]
    };
    for (j, joint) in joints.iter().enumerate() {
        let k = j + 1;
        assert_eq!(joint["joint"], k);
        let closed = &joint["closed_loop"];
        let rmse = closed["actual_vs_desired_rmse_deg"].as_f64().unwrap();
        let max = closed["max_abs_actual_error_deg"].as_f64().unwrap();
        let open = joint["open_loop"]["actual_vs_desired_rmse_deg"]
            .as_f64()
            .unwrap();
        let desired = col(&format!("desired{k}_deg"));
        let actual = col(&format!("closed_angle{k}_deg"));
        let from_csv = rms(actual.iter().zip(desired).map(|(a, d)| a - d));
        assert!(
            (from_csv - rmse).abs() < 1e-3,
            "joint {k}: {from_csv} vs {rmse}"
        );
        let max_csv = actual
            .iter()
            .zip(desired)
            .fold(0.0f64, |m, (a, d)| m.max((a - d).abs()));
        assert!(
            (max_csv - max).abs() < 1e-3,
            "joint {k}: {max_csv} vs {max}"
        );
        for name in ["sensed", "angle"] {
            for scheme in ["open", "closed"] {
                col(&format!("{scheme}_{name}{k}_deg"));
            }
        }
        col(&format!("closed_stroke{k}_mm"));
        // The library test bounds the tracking by the noise; here a degree says the command
        // ran the loops it claims to (the open loop of a coupled joint may miss by 10°).
        assert!(rmse < 1.0, "joint {k}: {rmse}°");
        assert!(open.is_finite());
    }
    assert!(out.join("report.html").is_file());
    assert!(out.join("joint-3.svg").is_file());
}

/// One desired-angle profile for every joint, or one per joint; any other count, a joint's
/// config on a robot, a robot's config on a joint, and `--coupling` on a joint are refused,
/// naming the value, with no output.
#[test]
fn profiles_and_refusals() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = estimator_config_cli(dir.path(), "robot.toml");
    let robot = arg(&designs().join("robot-bdb.toml"));
    let ramp = dir.path().join("ramp.csv");
    std::fs::write(&ramp, "time_s,angle_deg\n0,0\n2,20\n4,20\n").unwrap();
    let hold = dir.path().join("hold.csv");
    std::fs::write(&hold, "time_s,angle_deg\n0,0\n1,-10\n4,-10\n").unwrap();
    let run = |profiles: &[&Path], out: &str| {
        let mut args = vec![
            "control".to_string(),
            "--design".into(),
            robot.clone(),
            "--config".into(),
            arg(&cfg),
            "--filter".into(),
            "ma:50".into(),
            "--json".into(),
            "-o".into(),
            arg(&dir.path().join(out)),
        ];
        for p in profiles {
            args.push("--profile".into());
            args.push(arg(p));
        }
        dlw(&args)
    };
    let one = run(&[&ramp], "one");
    assert!(
        one.status.success(),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&one.stdout).unwrap();
    assert_eq!(json["samples"], 2000);
    for j in json["joints"].as_array().unwrap() {
        assert!(j["desired"].as_str().unwrap().contains("ramp.csv"));
    }
    let each = run(&[&ramp, &hold, &ramp], "each");
    assert!(
        each.status.success(),
        "{}",
        String::from_utf8_lossy(&each.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&each.stdout).unwrap();
    assert!(json["joints"][1]["desired"]
        .as_str()
        .unwrap()
        .contains("hold.csv"));
    let two = run(&[&ramp, &hold], "two");
    let err = String::from_utf8_lossy(&two.stderr);
    assert!(!two.status.success());
    assert!(
        err.contains("--profile is given 2 times; the robot has 3 joints"),
        "{err}"
    );
    assert!(!dir.path().join("two").exists());
    // A joint's config on the robot, the robot's config on a joint.
    let joint_cfg = dir.path().join("b.toml");
    dlw_ok(&[
        "estimator-config",
        &common::shipped_design("joint-b.toml"),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&joint_cfg),
    ]);
    for (design, config) in [
        (robot.clone(), arg(&joint_cfg)),
        (common::shipped_design("joint-b.toml"), arg(&cfg)),
    ] {
        let out = dir.path().join("mixed");
        let o = dlw(&[
            "control",
            "--design",
            &design,
            "--config",
            &config,
            "--protocol",
            "random",
            "-o",
            &arg(&out),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success());
        assert!(
            err.contains("a robot takes the config dlw estimator-config ROBOT writes"),
            "{err}"
        );
        assert!(!out.exists());
    }
    let o = dlw(&[
        "control",
        "--design",
        &common::shipped_design("joint-b.toml"),
        "--config",
        &arg(&joint_cfg),
        "--protocol",
        "random",
        "--coupling",
        "none",
        "-o",
        &arg(&dir.path().join("c")),
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--coupling is for a robot's tendons"));
    // A config for another robot.
    let bc = dir.path().join("bc.toml");
    dlw_ok(&[
        "estimator-config",
        &arg(&designs().join("robot-bc.toml")),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&bc),
    ]);
    let o = dlw(&[
        "control",
        "--design",
        &robot,
        "--config",
        &arg(&bc),
        "--protocol",
        "random",
        "-o",
        &arg(&dir.path().join("d")),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("the estimator config is for 2 joints and 3 sensors; robot \"Robot BDB\" has 3 joints and 3 sensors"),
        "{err}"
    );
    assert!(!dir.path().join("d").exists());
}

/// `dlw estimate --report DIR --design ROBOT`: the crosstalk figure draws the config's matrix
/// against the geometry's; a config holding the geometry's says so; another robot is refused.
#[test]
fn the_estimate_report_draws_the_crosstalk_against_the_geometry() {
    let dir = tempfile::tempdir().unwrap();
    let robot = designs().join("robot-bdb.toml");
    let rec = dir.path().join("rec");
    dlw_ok(&[
        "simulate",
        "--design",
        &arg(&robot),
        "--protocol",
        "random",
        "--duration-s",
        "20",
        "-o",
        &arg(&rec),
    ]);
    let cfg = estimator_config_cli(dir.path(), "robot.toml");
    let report = |config: &Path, out: &str, design: &Path| {
        dlw(&[
            "estimate",
            "--config",
            &arg(config),
            &arg(&rec),
            "-o",
            &arg(&dir.path().join(format!("{out}.csv"))),
            "--report",
            &arg(&dir.path().join(out)),
            "--design",
            &arg(design),
        ])
    };
    let o = report(&cfg, "same", &robot);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let html = std::fs::read_to_string(dir.path().join("same/report.html")).unwrap();
    assert!(
        html.contains("The config holds the geometry&#39;s crosstalk matrix")
            || html.contains("The config holds the geometry's crosstalk matrix"),
        "{html}"
    );
    assert!(dir.path().join("same/crosstalk.svg").is_file());
    // A config whose matrix differs from the geometry's: the largest difference, named.
    let text = std::fs::read_to_string(&cfg).unwrap();
    let mut value: toml::Table = toml::from_str(&text).unwrap();
    value["sensor"].as_array_mut().unwrap()[0]["crosstalk"] =
        toml::Value::try_from(vec![1.0, 0.0312, -0.02]).unwrap();
    let fitted = dir.path().join("fitted.toml");
    std::fs::write(&fitted, toml::to_string(&value).unwrap()).unwrap();
    let o = report(&fitted, "fitted", &robot);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let html = std::fs::read_to_string(dir.path().join("fitted/report.html")).unwrap();
    assert!(
        html.contains("Largest difference 0.0312 (sensor 1, joint 2)"),
        "{html}"
    );
    let svg = std::fs::read_to_string(dir.path().join("fitted/crosstalk.svg")).unwrap();
    assert!(svg.contains("config = geometric"));
    // Another robot's file.
    let o = report(&cfg, "other", &designs().join("robot-bc.toml"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("is not the config's robot"), "{err}");
    assert!(!dir.path().join("other").exists());
    assert!(!dir.path().join("other.csv").exists());
}
