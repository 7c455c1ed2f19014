//! `dlw import-recording --design ROBOT --joint-tool K=TOOL` (issue 34 §1): per-joint angles
//! from one tracker tool per joint, on a robot bench written by an independent generator
//! (`tests/scripts/robot_bench.py`, numpy only, its own quaternion algebra and kinematics):
//! Robot BDB's three joints bending about their own axes turned by 0°, 120°, 240°, a 6-DOF tool
//! distal of each joint and one on the base, in an NDI Track log whose tools are not in the
//! joints' order, a tracker clock 0.437 s late and 250 ppm fast, 0.05° RMS orientation noise
//! per axis on every tool, and a burst of 8 frames where joint 2's tool is lost. Needs python3
//! with numpy (installed by `scripts/test.sh`).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{arg, dlw, dlw_ok};
use dlw::recording::robot::RobotRecording;

/// The generator's orientation noise per axis and tool (°, its `NOISE_DEG`): the angle of one
/// tool in another's frame carries √2 times it.
const NOISE_DEG: f64 = 0.05;
/// The generator's lost frames of joint 2's tool, at 40 Hz, on the DAQ's 200 Hz rows: 8 frames
/// and the frames either side they are interpolated from span at most 10 frame periods.
const MOST_INVALID_ROWS: usize = 10 * 5 + 2;

/// The base's sway (°) on the bench that needs the reference tool.
const SWAY_DEG: f64 = 3.0;

/// Writes the bench, its base swaying by up to `sway_deg`, into a fresh folder and returns it.
fn bench(sway_deg: f64) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts/robot_bench.py");
    let out = Command::new("python3")
        .arg(script)
        .arg(dir.path())
        .arg("7")
        .arg(sway_deg.to_string())
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 ({e}): this test needs python3 with numpy"));
    assert!(
        out.status.success(),
        "robot_bench.py: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir
}

fn robot() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/robot-bdb.toml")
}

/// The import's arguments for the bench in `dir`, written to `out`, with `extra` after them.
fn import_args(dir: &Path, out: &Path, extra: &[&str]) -> Vec<String> {
    let mut a: Vec<String> = [
        "import-recording",
        "--design",
        &arg(&robot()),
        "--daq",
        &arg(&dir.join("daq.csv")),
        "--tracker",
        &arg(&dir.join("aurora.csv")),
        "--voltage",
        "AI0",
        "--voltage",
        "AI1",
        "--voltage",
        "AI2",
        "--divider-ohm",
        "99.6e3,99.6e3,99.6e3",
        "--supply-v",
        "5",
        "--stroke-mm-per-v",
        "0.5",
        "--rest-s",
        "4",
        "-o",
        &arg(out),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    a.extend(extra.iter().map(|s| s.to_string()));
    a
}

/// The log's tools: reference 1, joint 3 on port 2, joint 1 on 3, joint 2 on 4.
const JOINT_TOOLS: [&str; 6] = [
    "--joint-tool",
    "1=3",
    "--joint-tool",
    "2=4",
    "--joint-tool",
    "3=2",
];
const STROKES: [&str; 6] = ["--stroke", "S1", "--stroke", "S2", "--stroke", "S3"];

/// The truth's columns at the DAQ's rows: time, then each joint's angle.
fn truth(dir: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(dir.join("truth.csv")).unwrap();
    let mut cols = vec![Vec::new(); 4];
    for line in text.lines().skip(1) {
        for (c, v) in line.split(',').enumerate() {
            cols[c].push(v.parse::<f64>().unwrap());
        }
    }
    cols
}

/// Imports the bench in `dir` with `extra` options into `dir/NAME` and checks every joint's
/// angle against the truth: returns each joint's (RMS, max) error (°) over the valid rows.
fn import_and_compare(
    dir: &tempfile::TempDir,
    name: &str,
    tools: &[&str],
    extra: &[&str],
) -> Vec<(f64, f64)> {
    let out = dir.path().join(name);
    let mut args = import_args(dir.path(), &out, tools);
    args.extend(STROKES.iter().map(|s| s.to_string()));
    args.extend(extra.iter().map(|s| s.to_string()));
    dlw_ok(&args);
    let rec = RobotRecording::read(&out).expect("the robot recording reader reads the import");
    let s = &rec.samples;
    assert_eq!((s.joints(), s.sensors()), (3, 3));
    let truth = truth(dir.path());
    assert_eq!(s.len(), truth[0].len());
    let invalid = (0..s.len()).filter(|&i| !s.tracker_valid_at(i)).count();
    // Inside the log's span (its frames cover DAQ time 0.437 s to about 59 s) only the burst
    // is invalid; before the log's first frame no row is.
    let inside = (0..s.len())
        .filter(|&i| (1.0..57.0).contains(&s.time_s[i]) && !s.tracker_valid_at(i))
        .count();
    assert!(
        (1..=MOST_INVALID_ROWS).contains(&inside),
        "{inside} rows inside the log marked tracker_valid = 0; the lost burst covers at most {MOST_INVALID_ROWS}"
    );
    assert!((0..s.len())
        .filter(|&i| s.time_s[i] < 0.43)
        .all(|i| !s.tracker_valid_at(i)));
    let info = rec.rig.import.as_ref().expect("[import] provenance");
    assert_eq!(info.joint_tools, vec![3, 4, 2]);
    // The recording is read by the robot's estimator: every valid row is estimated.
    let cfg = dir.path().join(format!("{name}-cfg.toml"));
    dlw_ok(&[
        "estimator-config",
        &arg(&robot()),
        "--gauge-factor",
        "15",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&cfg),
    ]);
    let est = dlw_ok(&[
        "estimate",
        "--config",
        &arg(&cfg),
        &arg(&out),
        "--json",
        "-o",
        &arg(&dir.path().join(format!("{name}-est.csv"))),
    ]);
    let json: serde_json::Value = serde_json::from_slice(&est.stdout).unwrap();
    assert_eq!(json["joints"].as_array().unwrap().len(), 3);
    assert_eq!(json["samples"], s.len() - invalid);
    (0..3)
        .map(|k| {
            let errors: Vec<f64> = (0..s.len())
                .filter(|&i| s.tracker_valid_at(i))
                .map(|i| s.angle_deg[k][i] - truth[k + 1][i])
                .collect();
            let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
            let max = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
            (rms, max)
        })
        .collect()
}

/// Each joint's imported angle is the generator's within the tracker's noise: its RMS error at
/// most twice the noise of one tool in another's frame (√2·NOISE_DEG), its largest at most 8
/// times it.
fn assert_within_noise(errors: &[(f64, f64)]) {
    let floor = std::f64::consts::SQRT_2 * NOISE_DEG;
    for (k, &(rms, max)) in errors.iter().enumerate() {
        assert!(
            rms <= 2.0 * floor && max <= 8.0 * floor,
            "joint {}: error {rms:.3}° RMS, {max:.3}° at most; the noise floor is {floor:.3}°",
            k + 1
        );
    }
}

/// On a swaying base, each joint's angle is the truth within the noise with the reference
/// tool; without it, the proximal joint's carries the sway (joints 1 and 2, in their
/// neighbours' frames, do not).
#[test]
fn each_joint_angle_is_the_truth_within_the_tracker_noise_with_a_reference_tool() {
    let dir = bench(SWAY_DEG);
    let errors = import_and_compare(&dir, "ref", &JOINT_TOOLS, &["--reference-tool", "1"]);
    eprintln!("swaying base, with the reference tool: {errors:?}");
    assert_within_noise(&errors);
    let without = import_and_compare(&dir, "noref", &JOINT_TOOLS, &[]);
    eprintln!("swaying base, without it: {without:?}");
    assert_within_noise(&without[..2]);
    assert!(
        without[2].0 > SWAY_DEG / 4.0,
        "joint 3 without the reference tool is off by {:.3}° RMS only: is the reference tool used?",
        without[2].0
    );
}

/// On a still base, the proximal joint's angle against its rest axis is the truth within the
/// noise; the tools named by their port handles, as NDI's log names them.
#[test]
fn the_proximal_joint_is_taken_against_its_rest_axis_without_a_reference_tool() {
    let dir = bench(0.0);
    let by_port = [
        "--joint-tool",
        "1=Port:3",
        "--joint-tool",
        "2=port:4",
        "--joint-tool",
        "3=Port:2",
    ];
    let errors = import_and_compare(&dir, "rec", &by_port, &[]);
    eprintln!("still base, without a reference tool: {errors:?}");
    assert_within_noise(&errors);
    // --json names each joint's tool and the frame its angle is taken in.
    let out = dir.path().join("json");
    let mut args = import_args(dir.path(), &out, &by_port);
    args.extend(STROKES.iter().map(|s| s.to_string()));
    args.push("--json".into());
    let json: serde_json::Value = serde_json::from_slice(&dlw_ok(&args).stdout).unwrap();
    let joints = json["joints"].as_array().unwrap();
    let named: Vec<(u64, &str)> = joints
        .iter()
        .map(|j| (j["tool"].as_u64().unwrap(), j["frame"].as_str().unwrap()))
        .collect();
    assert_eq!(named, [(3, "tool 4"), (4, "tool 2"), (2, "rest axis")]);
    assert_eq!(joints[1]["missing_frames"], 8);
}

/// Each refusal: a non-zero exit, a message naming the value and the limit, no output.
#[test]
fn bad_robot_imports_are_refused_naming_the_value_and_leave_no_output() {
    let dir = bench(0.0);
    let out = dir.path().join("rec");
    let strokes: Vec<&str> = STROKES.to_vec();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            [&JOINT_TOOLS[..], &strokes, &["--tip-tool", "3"]].concat(),
            "base's pose in the tracker's frame",
        ),
        (
            [&JOINT_TOOLS[..4], &strokes].concat(),
            "joint 3 has no --joint-tool; the robot has 3 joints",
        ),
        (
            [
                &[
                    "--joint-tool",
                    "1=3",
                    "--joint-tool",
                    "2=3",
                    "--joint-tool",
                    "3=2",
                ][..],
                &strokes,
            ]
            .concat(),
            "tool 3 is named twice (joint 1 and joint 2)",
        ),
        (
            [
                &[
                    "--joint-tool",
                    "1=3",
                    "--joint-tool",
                    "2=4",
                    "--joint-tool",
                    "3=5",
                ][..],
                &strokes,
            ]
            .concat(),
            "tracker log has no tool 5 (its map lists 4 tool(s))",
        ),
        (
            [
                &[
                    "--joint-tool",
                    "1=3",
                    "--joint-tool",
                    "2=Port:9",
                    "--joint-tool",
                    "3=2",
                ][..],
                &strokes,
            ]
            .concat(),
            r#"tool "Port:9" is not in the tracker log: its first row's PortHandle columns hold ["Port:1", "Port:2", "Port:3", "Port:4"]"#,
        ),
        (
            [&JOINT_TOOLS[..], &strokes, &["--tool", "3"]].concat(),
            "--tool 3 is a joint's tip tool; a robot's tools are --joint-tool K=TOOL",
        ),
        (
            [&JOINT_TOOLS[..], &strokes[..4]].concat(),
            "--stroke names 2 channels; the robot has 3 joints",
        ),
        (
            [&JOINT_TOOLS[..], &strokes, &["--voltage", "S1"]].concat(),
            "--voltage names 4 channels; the robot has 3 sensors",
        ),
        (
            [&JOINT_TOOLS[..], &strokes, &["--joint-tool", "4=1"]].concat(),
            "joint 4 is out of range; the robot has joints 1 to 3",
        ),
    ];
    for (extra, says) in cases {
        let o = dlw(&import_args(dir.path(), &out, &extra));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{extra:?} was accepted");
        assert!(stderr.contains(says), "{extra:?}: {stderr}");
        assert!(!out.exists(), "{extra:?} left {}", out.display());
    }
}
