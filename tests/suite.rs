//! The integration tests that run quickly, in one binary: each file is a module here, as it
//! was a binary of its own before, so that a clean build compiles and links one test binary
//! for them instead of one apiece (about 5 s each on two cores). The slow ones, those with
//! snapshots and those the docs run by name (`cargo test --test NAME`) keep their own:
//! `[[test]]` in Cargo.toml. One file's tests: `cargo test --test suite FILE::`.

mod canon;
mod common;

#[path = "aerobasic_programs.rs"]
mod aerobasic_programs;
#[path = "architecture.rs"]
mod architecture;
#[path = "characterize_cli.rs"]
mod characterize_cli;
#[path = "characterize_second_generator.rs"]
mod characterize_second_generator;
#[path = "cli_draw.rs"]
mod cli_draw;
#[path = "clipped_recordings.rs"]
mod clipped_recordings;
#[path = "control_cli.rs"]
mod control_cli;
#[path = "daq_info.rs"]
mod daq_info;
#[path = "design_rules.rs"]
mod design_rules;
#[path = "dxf_cad_import.rs"]
mod dxf_cad_import;
#[path = "dxf_ezdxf.rs"]
mod dxf_ezdxf;
#[path = "dxf_roundtrip.rs"]
mod dxf_roundtrip;
#[path = "estimate_precision.rs"]
mod estimate_precision;
#[path = "estimator_config.rs"]
mod estimator_config;
#[path = "explore_cli.rs"]
mod explore_cli;
#[path = "fluoro_errors.rs"]
mod fluoro_errors;
#[path = "fluoro_phantom.rs"]
mod fluoro_phantom;
#[path = "fluoro_synthetic.rs"]
mod fluoro_synthetic;
#[path = "geometry_centroid.rs"]
mod geometry_centroid;
#[path = "geometry_doc.rs"]
mod geometry_doc;
#[path = "import_faults.rs"]
mod import_faults;
#[path = "import_tdms.rs"]
mod import_tdms;
#[path = "input_limits.rs"]
mod input_limits;
#[path = "mechanics_independent.rs"]
mod mechanics_independent;
#[path = "nonfinite.rs"]
mod nonfinite;
#[path = "outputs.rs"]
mod outputs;
#[path = "program_cli.rs"]
mod program_cli;
#[path = "recording_errors.rs"]
mod recording_errors;
#[path = "robot_cli.rs"]
mod robot_cli;
#[path = "robot_control.rs"]
mod robot_control;
#[path = "robot_router.rs"]
mod robot_router;
#[path = "robot_rs274.rs"]
mod robot_rs274;
#[path = "robot_sensing.rs"]
mod robot_sensing;
#[path = "robot_tip_fit.rs"]
mod robot_tip_fit;
#[path = "rs274_programs.rs"]
mod rs274_programs;
#[path = "simulate_estimate.rs"]
mod simulate_estimate;
#[path = "simulate_noise.rs"]
mod simulate_noise;
#[path = "simulate_protocols.rs"]
mod simulate_protocols;
#[path = "tracker_map.rs"]
mod tracker_map;
#[path = "tracker_valid.rs"]
mod tracker_valid;
