//! Designs beyond the paper's Table I, shared by the integration tests (`common::designs`).
#![allow(dead_code)]

/// A BSN joint with other radii, arcs and notch pattern than Joint C.
pub const BSN_WIDE: &str = r#"
name = "BSN r_o 1.0"
style = "bsn"
outer_radius_mm = 1.0
inner_radius_mm = 0.8
notch_arc_mm = 1.5
notch_width_mm = 0.4
notch_spacing_mm = 0.6
notch_count = 6
joint_length_mm = 5.4
sensor_arc_mm = 2.4
"#;

/// A short UAN joint with three notches, a small tube and a non-ASCII name.
pub const UAN_THREE: &str = r#"
name = "Gelenk Ü, N = 3"
style = "uan"
outer_radius_mm = 0.6
inner_radius_mm = 0.45
notch_arc_mm = 2.4
notch_width_mm = 0.3
notch_spacing_mm = 0.4
notch_count = 3
joint_length_mm = 1.7
sensor_arc_mm = 0.3

[fabrication]
trace_width_mm = 0.04
kerf_mm = 0.02
pad_turns = 3
pad_pitch_mm = 0.08
"#;

/// The shipped designs' paths.
pub fn shipped() -> Vec<std::path::PathBuf> {
    ["a", "b", "c", "d"]
        .iter()
        .map(|j| {
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("designs/joint-{j}.toml"))
        })
        .collect()
}

/// The shipped robot files (`designs/robot-*.toml`, docs/robots.md).
pub fn robots() -> Vec<std::path::PathBuf> {
    ["robot-bc", "robot-bdb"]
        .iter()
        .map(|r| std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("designs/{r}.toml")))
        .collect()
}
