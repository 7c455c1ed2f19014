//! Helpers shared by the integration tests (`mod common;`): running the real `dlw` binary and
//! finding the shipped designs.
#![allow(dead_code)]

pub mod bench;
pub mod designs;
pub mod discovery;

use std::ffi::OsStr;
use std::path::Path;
use std::process::{Command, Output};

/// Runs the `dlw` binary built for these tests with `args` and returns what it did.
pub fn dlw<S: AsRef<OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args(args)
        .output()
        .expect("the dlw binary runs")
}

/// Runs the `dlw` binary with `args` and asserts it succeeded, showing its stderr if not.
pub fn dlw_ok<S: AsRef<OsStr> + std::fmt::Debug>(args: &[S]) -> Output {
    let o = dlw(args);
    assert!(
        o.status.success(),
        "dlw {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// A path as a command-line argument.
pub fn arg(p: &Path) -> String {
    p.display().to_string()
}

/// `dlw estimator-config` arguments for Joint C's two linear sensors, the paper's Table V:
/// tension GF 1.28, R₀ 74 kΩ; compression GF 0.680, R₀ 88.9 kΩ on a 102.5 kΩ divider.
pub const JOINT_C_TABLE_V: [&str; 10] = [
    "--gauge-factor",
    "1.28",
    "--r0-ohm",
    "74e3",
    "--second-gauge-factor",
    "0.680",
    "--second-r0-ohm",
    "88.9e3",
    "--second-divider-ohm",
    "102.5e3",
];

/// The path of a design shipped under `designs/`, e.g. `shipped_design("joint-a.toml")`.
pub fn shipped_design(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("designs")
        .join(name)
        .display()
        .to_string()
}
pub mod other_forms;
pub mod rng;
pub mod second_generator;
pub mod third_generator;
