//! Bad recordings given to `dlw estimate`: each fails with a message naming the line and the
//! value, a non-zero exit, and no estimates file.

use crate::common;
use common::dlw;

use std::path::Path;

const RIG: &str = "sample_hz = 500.0\nsupply_v = 5.0\ndivider_ohm = [99600.0]\n";
const HEADER: &str = "time_s,stroke_mm,angle_deg,v1_V";
const ROWS: [&str; 4] = [
    "0.000000,0.000000,0.0000,3.417",
    "0.002000,0.010000,0.3500,3.420",
    "0.004000,0.020000,0.7100,3.424",
    "0.006000,0.030000,1.0600,3.427",
];

/// A recording folder with `rig` and `data`.
fn recording(root: &Path, name: &str, rig: &str, data: Option<&str>) -> String {
    let dir = root.join(name);
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("rig.toml"), rig).unwrap();
    if let Some(data) = data {
        std::fs::write(dir.join("data.csv"), data).unwrap();
    }
    dir.display().to_string()
}

/// data.csv with row `index` (0-based, line index + 2) replaced by `row`.
fn data_with(index: usize, row: &str) -> String {
    let mut rows: Vec<&str> = ROWS.to_vec();
    rows[index] = row;
    format!("{HEADER}\n{}\n", rows.join("\n"))
}

fn config(root: &Path) -> String {
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let config = root.join("config.toml").display().to_string();
    let o = dlw(&[
        "estimator-config",
        &design.display().to_string(),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &config,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    config
}

#[test]
fn a_good_recording_is_estimated() {
    let root = tempfile::tempdir().unwrap();
    let config = config(root.path());
    let dir = recording(root.path(), "good", RIG, Some(&data_with(0, ROWS[0])));
    let o = dlw(&["estimate", "--config", &config, &dir, "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["samples"], 4);
    assert!(Path::new(&dir).join("estimates.csv").exists());
}

#[test]
fn bad_recordings_name_the_line_and_value_and_write_nothing() {
    let root = tempfile::tempdir().unwrap();
    let config = config(root.path());
    let two_columns = format!("{HEADER},v2_V\n0,0,0,1,1\n");
    let cases: Vec<(&str, String, String, &str)> = vec![
        ("nan", RIG.into(), data_with(1, "0.002000,0.01,NaN,3.42"), "line 3: angle_deg = NaN is not finite"),
        ("inf", RIG.into(), data_with(2, "0.004000,0.02,0.71,inf"), "line 4: v1_V = inf is not finite"),
        ("minus-inf", RIG.into(), data_with(0, "0,-inf,0,3.4"), "line 2: stroke_mm = -inf is not finite"),
        ("not-a-number", RIG.into(), data_with(3, "0.006,0.03,abc,3.4"), "line 5: angle_deg = \"abc\" is not a number"),
        ("time-back", RIG.into(), data_with(2, "0.001000,0.02,0.71,3.424"), "line 4: time_s = 0.001 does not increase (previous row: 0.002)"),
        ("time-repeat", RIG.into(), data_with(2, "0.002000,0.02,0.71,3.424"), "line 4: time_s = 0.002 does not increase"),
        ("missing-column", RIG.into(), data_with(1, "0.002000,0.01,0.35"), "line 3: has 3 fields, expected 4 (time_s,stroke_mm,angle_deg,v1_V)"),
        ("extra-column", RIG.into(), data_with(3, "0.006,0.03,1.06,3.427,1.0"), "line 5: has 5 fields, expected 4"),
        ("blank-line", RIG.into(), format!("{HEADER}\n{}\n\n{}\n", ROWS[0], ROWS[1]), "line 3: has 0 fields"),
        ("wrong-header", RIG.into(), format!("time,stroke,angle,v1\n{}\n", ROWS[0]), "line 1: header is \"time,stroke,angle,v1\", expected \"time_s,stroke_mm,angle_deg,v1_V\""),
        ("header-vs-rig", RIG.into(), two_columns, "line 1: header is \"time_s,stroke_mm,angle_deg,v1_V,v2_V\""),
        ("rail-zero", RIG.into(), data_with(1, "0.002,0.01,0.35,0"), "line 3: v1_V = 0 V is at or beyond a rail (must lie strictly between 0 and supply_v = 5 V)"),
        ("rail-negative", RIG.into(), data_with(1, "0.002,0.01,0.35,-0.2"), "line 3: v1_V = -0.2 V is at or beyond a rail"),
        ("rail-supply", RIG.into(), data_with(3, "0.006,0.03,1.06,5.000"), "line 5: v1_V = 5 V is at or beyond a rail"),
        ("rail-beyond", RIG.into(), data_with(0, "0,0,0,5.3"), "line 2: v1_V = 5.3 V is at or beyond a rail"),
        ("no-rows", RIG.into(), format!("{HEADER}\n"), "has no data rows"),
        ("rig-missing-key", "sample_hz = 500.0\ndivider_ohm = [99600.0]\n".into(), data_with(0, ROWS[0]), "missing field `supply_v`"),
        ("rig-unknown-key", format!("{RIG}sample_rate = 500\n"), data_with(0, ROWS[0]), "unknown field `sample_rate`"),
        ("rig-bad-supply", "sample_hz = 500.0\nsupply_v = 0.0\ndivider_ohm = [99600.0]\n".into(), data_with(0, ROWS[0]), "supply_v = 0 is out of range"),
        ("rig-no-divider", "sample_hz = 500.0\nsupply_v = 5.0\ndivider_ohm = []\n".into(), data_with(0, ROWS[0]), "divider_ohm (entries) = 0"),
    ];
    for (name, rig, data, needle) in cases {
        let dir = recording(root.path(), name, &rig, Some(&data));
        let elsewhere = root.path().join(format!("{name}.csv"));
        for extra in [
            vec![],
            vec!["-o".to_string(), elsewhere.display().to_string()],
        ] {
            let mut args = vec!["estimate", "--config", &config, &dir];
            args.extend(extra.iter().map(String::as_str));
            let o = dlw(&args);
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(!o.status.success(), "{name}: succeeded");
            assert!(err.contains(needle), "{name}: {err}");
            assert!(
                err.contains("data.csv") || err.contains("rig.toml"),
                "{name}: {err}"
            );
            assert!(!Path::new(&dir).join("estimates.csv").exists(), "{name}");
            assert!(!elsewhere.exists(), "{name}");
        }
    }
}

#[test]
fn missing_files_and_bad_filters_are_named() {
    let root = tempfile::tempdir().unwrap();
    let config = config(root.path());
    let dir = recording(root.path(), "no-data", RIG, None);
    let o = dlw(&["estimate", "--config", &config, &dir]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("cannot read") && err.contains("data.csv"),
        "{err}"
    );
    let good = recording(root.path(), "good", RIG, Some(&data_with(0, ROWS[0])));
    for (filter, needle) in [
        ("ma:0", "0"),
        ("wobble", "unknown filter \"wobble\""),
        ("ma:x", "unknown filter"),
    ] {
        let o = dlw(&["estimate", "--config", &config, &good, "--filter", filter]);
        assert!(!o.status.success(), "{filter}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(needle), "{filter}: {err}");
    }
    assert!(!Path::new(&good).join("estimates.csv").exists());
}
