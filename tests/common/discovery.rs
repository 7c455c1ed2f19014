//! `dlw discover --json` from the tests: run it, and read the names and gaps of its report.
#![allow(dead_code)]

use std::path::Path;

/// Runs `dlw discover --design DESIGN REC -o OUT --json`, asserts success, returns the JSON.
pub fn discover_json(design: &str, rec: &Path, out: &Path) -> serde_json::Value {
    let o = super::dlw(&[
        "discover".as_ref(),
        "--design".as_ref(),
        design.as_ref(),
        rec.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--json".as_ref(),
    ]);
    assert!(
        o.status.success(),
        "discover {} failed: {}",
        rec.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("discover --json prints JSON")
}

/// The (effect, channel) pairs a report names, in its order.
pub fn named(report: &serde_json::Value) -> Vec<(String, String)> {
    report["discovered"]
        .as_array()
        .expect("a discovered array")
        .iter()
        .map(|d| {
            (
                d["effect"].as_str().unwrap().to_owned(),
                d["channel"].as_str().unwrap().to_owned(),
            )
        })
        .collect()
}

/// Per channel, the held-out RMSE before and after.
pub fn gaps(report: &serde_json::Value) -> Vec<(String, f64, f64)> {
    report["gaps"]
        .as_array()
        .expect("a gaps array")
        .iter()
        .map(|g| {
            (
                g["channel"].as_str().unwrap().to_owned(),
                g["before"].as_f64().unwrap(),
                g["after"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// The gap above the noise floor: `√(RMSE² − floor²)`, 0 below it.
pub fn above(rmse: f64, floor: f64) -> f64 {
    (rmse * rmse - floor * floor).max(0.0).sqrt()
}
