//! `dlw explore` through the binary: the designs it writes pass `dlw build`, a spec nothing
//! meets is refused naming the binding constraint and writes nothing, the output policy holds,
//! and `--json` prints the front.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dlw(args: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args(args)
        .output()
        .unwrap()
}

fn designs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs")
}

/// A small spec in `dir` on Joint D with the shipped catalogue.
fn spec(dir: &Path, constraints: &str) -> PathBuf {
    let text = format!(
        r#"base = "{base}"
tubes = "{tubes}"
gauge_factor = 15.3
r0_ohm = 215e3
[vary]
tube = ["paper-1.6", "paper-2.5", "od2.0-id1.6"]
notch_arc_mm = {{ from = 2.0, to = 7.0, step = 0.5 }}
notch_count = [6, 10]
notch_width_mm = [0.4, 0.6, 0.8]
[constraints]
{constraints}
[objectives]
maximize = ["sensitivity_ohm_per_deg", "range_deg"]
minimize = ["tendon_force_per_deg_n"]
"#,
        base = designs().join("joint-d.toml").display(),
        tubes = designs().join("tubes.toml").display(),
    );
    let path = dir.join("spec.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn every_written_design_passes_dlw_build() {
    let dir = tempfile::tempdir().unwrap();
    let spec = spec(dir.path(), "min_range_deg = 20");
    let out_dir = dir.path().join("explored");
    let out = dlw(&[
        "explore".as_ref(),
        spec.as_os_str(),
        "-o".as_ref(),
        out_dir.as_os_str(),
        "--top".as_ref(),
        "4".as_ref(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["designs.csv", "front.csv", "report.html"] {
        assert!(out_dir.join(f).is_file(), "{f}");
    }
    let written: Vec<PathBuf> = (1..=4)
        .map(|k| out_dir.join(format!("best-{k}.toml")))
        .filter(|p| p.exists())
        .collect();
    assert_eq!(written.len(), 4);
    for (k, design) in written.iter().enumerate() {
        let build = dir.path().join(format!("build-{k}"));
        let out = dlw(&[
            "build".as_ref(),
            design.as_os_str(),
            "-o".as_ref(),
            build.as_os_str(),
        ]);
        assert!(
            out.status.success(),
            "{}: {}",
            design.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(build.read_dir().unwrap().count() >= 5);
    }
    // The report marks the paper's joints and highlights the front.
    let svg = std::fs::read_to_string(out_dir.join("scatter-1.svg")).unwrap();
    assert!(svg.contains("Pareto front") && svg.contains("Joint A") && svg.contains("Joint C"));
    // Every row of designs.csv meets the spec's range.
    let csv = std::fs::read_to_string(out_dir.join("designs.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let range = header.iter().position(|h| *h == "range_deg").unwrap();
    for line in csv.lines().skip(1) {
        let v: f64 = line.split(',').nth(range).unwrap().parse().unwrap();
        assert!(v >= 20.0, "{line}");
    }
}

#[test]
fn a_spec_nothing_meets_names_the_binding_constraint_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let spec = spec(dir.path(), "min_range_deg = 120");
    let out_dir = dir.path().join("explored");
    let out = dlw(&[
        "explore".as_ref(),
        spec.as_os_str(),
        "-o".as_ref(),
        out_dir.as_os_str(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("no candidate is feasible: the binding constraint is material strain within backbone_strain_limit = 0.03 up to min_range_deg = 120°"),
        "{err}"
    );
    assert!(err.contains("the best of all candidates reaches"), "{err}");
    assert!(!out_dir.exists());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "only the spec"
    );
}

#[test]
fn a_bad_spec_value_is_named_and_an_existing_folder_is_kept() {
    let dir = tempfile::tempdir().unwrap();
    let spec_path = spec(dir.path(), "min_range_deg = 20");
    let text = std::fs::read_to_string(&spec_path).unwrap();
    std::fs::write(
        &spec_path,
        text.replace("notch_count = [6, 10]", "notch_count = [6, 2.5]"),
    )
    .unwrap();
    let out_dir = dir.path().join("explored");
    let out = dlw(&[
        "explore".as_ref(),
        spec_path.as_os_str(),
        "-o".as_ref(),
        out_dir.as_os_str(),
    ]);
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("vary.notch_count = 2.5 must be a whole number from 1 to 10000"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::write(&spec_path, text).unwrap();
    std::fs::create_dir(&out_dir).unwrap();
    std::fs::write(out_dir.join("keep.txt"), "mine").unwrap();
    let out = dlw(&[
        "explore".as_ref(),
        spec_path.as_os_str(),
        "-o".as_ref(),
        out_dir.as_os_str(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("pass --force"));
    assert_eq!(
        std::fs::read_to_string(out_dir.join("keep.txt")).unwrap(),
        "mine"
    );
    let out = dlw(&[
        "explore".as_ref(),
        spec_path.as_os_str(),
        "-o".as_ref(),
        out_dir.as_os_str(),
        "--force".as_ref(),
        "--json".as_ref(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!out_dir.join("keep.txt").exists());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let front = json["front"].as_array().unwrap();
    assert!(!front.is_empty());
    assert_eq!(front[0]["file"], "best-1.toml");
    assert!(json["feasible"].as_u64().unwrap() >= front.len() as u64);
}

/// `predicted_rmse_deg` and `predicted_closed_loop_rmse_deg` as objectives: only the grid's
/// front is simulated (here the two candidates of a one-axis grid whose sensitivity and force
/// trade off), every front row carries its prediction in `--json`, the report plots the
/// predicted error against the sensitivity with the paper's joints at their measured errors,
/// and says what the prediction cost.
#[test]
fn predicted_accuracy_objectives_simulate_the_front() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!(
        r#"base = "{base}"
gauge_factor = 15.3
r0_ohm = 215e3
[vary]
notch_count = [5, 6]
[objectives]
maximize = ["sensitivity_ohm_per_deg"]
minimize = ["predicted_rmse_deg", "predicted_closed_loop_rmse_deg"]
"#,
        base = designs().join("joint-a.toml").display(),
    );
    let spec = dir.path().join("spec.toml");
    std::fs::write(&spec, text).unwrap();
    let out_dir = dir.path().join("explored");
    let out = dlw(&[
        "explore".as_ref(),
        spec.as_os_str(),
        "-o".as_ref(),
        out_dir.as_os_str(),
        "--json".as_ref(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let front = j["front"].as_array().unwrap();
    assert!(!front.is_empty());
    for row in front {
        let p = &row["predicted"];
        for key in ["linear_rmse_deg", "pi_rmse_deg", "closed_loop_rmse_deg"] {
            let v = p[key].as_f64().unwrap_or(f64::NAN);
            assert!(v.is_finite() && v > 0.0 && v < 30.0, "{key} = {v} in {row}");
        }
        assert_eq!(p["borrowed"], "A", "{row}");
    }
    let html = std::fs::read_to_string(out_dir.join("report.html")).unwrap();
    for needle in [
        "Predicted accuracy",
        "per front candidate",
        "predicted-accuracy.svg",
    ] {
        assert!(html.contains(needle), "{needle} not in the report");
    }
    let svg = std::fs::read_to_string(out_dir.join("predicted-accuracy.svg")).unwrap();
    assert!(
        svg.contains("measured (Table IV)"),
        "the paper's joints not marked"
    );
}
