//! `dlw daq-info` on files LabVIEW wrote (issue 30, section 4): `../shared/real-files/`
//! (see its README: 47 TDMS files from LabVIEW 2010 with what npTDMS 1.13 reads from each, and
//! 7 LVM files). The tests skip, saying so, when the folder is absent.

use crate::common;
use common::{arg, dlw};

use serde_json::Value;
use std::path::{Path, PathBuf};

fn real_files() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/real-files");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipped: {} is absent", dir.display());
        None
    }
}

fn info(path: &Path) -> Value {
    let o = dlw(&["daq-info", &arg(path), "--json"]);
    assert!(
        o.status.success(),
        "{}: {}",
        path.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

/// A value as compared: numbers as f64 (npTDMS's 64-bit integers are exact, dlw's are the f64
/// the import reads, so both go through f64), text, booleans and timestamps as written.
fn same(ours: &Value, theirs: &Value) -> bool {
    match (ours, theirs) {
        (Value::Number(a), Value::Number(b)) => a.as_f64() == b.as_f64(),
        (a, b) => a == b,
    }
}

/// Every channel of every LabVIEW TDMS file: the name `Group/Channel`, npTDMS's type name, the
/// length, the first 5 and last 2 values (scaled) equal what npTDMS reads.
#[test]
fn labview_tdms_files_list_as_nptdms_reads_them() {
    let Some(dir) = real_files() else { return };
    let dir = dir.join("tdms-labview2010");
    let expected: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected-nptdms.json")).unwrap())
            .unwrap();
    let files = expected["files"].as_object().unwrap();
    assert_eq!(files.len(), 47);
    let mut channels = 0;
    for (file, want) in files {
        let j = info(&dir.join(file));
        assert_eq!(j["format"], "tdms");
        let listed = j["channels"].as_array().unwrap();
        for group in want["groups"].as_array().unwrap() {
            for c in group["channels"].as_array().unwrap() {
                let name = format!(
                    "{}/{}",
                    group["name"].as_str().unwrap(),
                    c["name"].as_str().unwrap()
                );
                let ours = listed
                    .iter()
                    .find(|l| l["name"] == name.as_str())
                    .unwrap_or_else(|| panic!("{file}: no {name} in {j}"));
                assert_eq!(ours["type"], c["dtype"], "{file} {name}");
                assert_eq!(ours["length"], c["length"], "{file} {name}");
                for (key, theirs) in [("first", "first5_scaled"), ("last", "last2_scaled")] {
                    let (a, b) = (ours[key].as_array().unwrap(), c[theirs].as_array().unwrap());
                    assert!(
                        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(x, y)),
                        "{file} {name} {key}: dlw {a:?}, npTDMS {b:?}"
                    );
                }
                channels += 1;
            }
        }
    }
    assert_eq!(channels, 63, "channels compared");
}

fn channel<'a>(j: &'a Value, name: &str) -> &'a Value {
    j["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == name)
        .unwrap_or_else(|| panic!("no {name} in {j}"))
}

/// LabVIEW's LVM files: the channels by column name with their `Y_Unit_Label` (whose fields
/// stand above their columns, with or without an X column per channel), every data row
/// (16384 rows under one header that says 8192), the first and last values as written, and
/// channels of empty fields listed empty with a warning naming them.
#[test]
fn labview_lvm_files_list_their_channels_units_and_values() {
    let Some(dir) = real_files() else { return };
    let dir = dir.join("lvm");

    let j = info(&dir.join("long_single_header_multi_ch.lvm"));
    assert_eq!(j["format"], "lvm");
    for (name, unit) in [("F", "g"), ("m_1", "m/s^2"), ("m_2", "m/s^2")] {
        let c = channel(&j, name);
        assert_eq!(c["unit"], unit, "{c}");
        assert_eq!(c["length"], 16384, "{c}");
    }
    assert_eq!(channel(&j, "F")["first"][0].as_f64(), Some(0.05253));
    assert_eq!(channel(&j, "m_2")["first"][1].as_f64(), Some(0.247439));
    assert!((channel(&j, "F")["increment_s"].as_f64().unwrap() - 0.000977).abs() < 1e-12);

    let j = info(&dir.join("multi_time_column.lvm"));
    assert_eq!(channel(&j, "Voltage")["unit"], "Volts");
    assert_eq!(channel(&j, "Acceleration")["unit"], "g");
    assert_eq!(
        channel(&j, "Acceleration")["last"][1].as_f64(),
        Some(0.467541)
    );

    let j = info(&dir.join("no_decimal_separator.lvm"));
    let names: Vec<&str> = j["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["ax", "ay", "az"]);
    for n in names {
        assert_eq!(channel(&j, n)["unit"], "g");
        assert_eq!(channel(&j, n)["length"], 4);
    }
    assert_eq!(channel(&j, "ax")["first"][0].as_f64(), Some(-0.008807));
    assert_eq!(channel(&j, "az")["last"][1].as_f64(), Some(-0.009433));

    let j = info(&dir.join("short.lvm"));
    assert_eq!(channel(&j, "Excitation (Trigger)")["unit"], "Newtons");
    assert_eq!(channel(&j, "Response (Trigger)")["length"], 10);

    let j = info(&dir.join("with_empty_fields.lvm"));
    assert_eq!(channel(&j, "Dev0/Ai0")["length"], 7);
    assert_eq!(channel(&j, "Untitled")["length"], 0);
    let warnings = j["warnings"].to_string();
    assert!(warnings.contains("Untitled 3"), "{warnings}");

    // Every file is listed (a Latin-1 comment included).
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "lvm") {
            let j = info(&path);
            assert!(!j["channels"].as_array().unwrap().is_empty(), "{j}");
        }
    }
}
