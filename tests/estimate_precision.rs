//! `dlw estimate --precision N`: estimates.csv to N decimals (enough to compare the C and Python
//! estimators to 1e-9), and a refused N names the value and the limit, writing nothing.

use crate::common;
use common::shipped_design as design_path;

use std::process::{Command, Output};

fn dlw(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args(args)
        .output()
        .expect("the dlw binary runs")
}

#[test]
fn precision_sets_the_estimate_decimals_and_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let d = |p: &str| dir.path().join(p).display().to_string();
    let design = design_path("joint-a.toml");
    let ok = |o: Output| assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    ok(dlw(&[
        "simulate",
        "--design",
        &design,
        "--protocol",
        "random",
        "--duration-s",
        "5",
        "-o",
        &d("rec"),
    ]));
    ok(dlw(&[
        "estimator-config",
        &design,
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215000",
        "-o",
        &d("c.toml"),
    ]));
    ok(dlw(&[
        "estimate",
        "--config",
        &d("c.toml"),
        &d("rec"),
        "--precision",
        "12",
        "-o",
        &d("e.csv"),
    ]));
    let text = std::fs::read_to_string(d("e.csv")).unwrap();
    let estimate = text.lines().nth(1).unwrap().split(',').nth(2).unwrap();
    let decimals = estimate.split_once('.').map_or(0, |(_, f)| f.len());
    assert_eq!(decimals, 12, "estimate_deg {estimate:?}");

    let o = dlw(&[
        "estimate",
        "--config",
        &d("c.toml"),
        &d("rec"),
        "--precision",
        "16",
        "-o",
        &d("f.csv"),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("\"16\"") && err.contains("0 to 15"), "{err}");
    assert!(
        !dir.path().join("f.csv").exists(),
        "no output for a refused precision"
    );
}
