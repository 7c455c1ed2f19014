//! Helpers shared by the integration tests (`mod common;`): running the real `dlw` binary and
//! finding the shipped designs.
#![allow(dead_code)]

pub mod designs;

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
