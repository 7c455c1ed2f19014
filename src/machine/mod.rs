//! Machine profiles: what a rotary laser station can do and how it is told to do it.
//!
//! A profile is a TOML file under `designs/machines/` holding the controller dialect (which
//! post-processor writes the program), the axis letters and rotary units, X travel, the speed
//! limits the stage follows with the beam on, the maximum power, where the focus sits relative
//! to the rotation axis, and a command template for each laser parameter. The reference
//! profile, `linuxcnc-reference`, is the default; see `docs/toolpaths.md` for every key.
//!
//! # Errors
//! [`MachineError`] names the profile, the key and the limit; unknown keys are refused, so a
//! misspelt limit never silently takes a default.

mod library;
mod profile;
mod settle;
mod template;

use std::path::PathBuf;

/// Finds profiles by name or path; the built-in default.
pub use library::{MachineLibrary, DEFAULT_PROFILE};
/// A machine profile and its tables.
pub use profile::{
    Axes, Dialect, Fixture, Focus, LaserCommands, Limits, MachineProfile, RepeatMode, RotaryUnits,
};
/// Waiting for the source to settle between operations (`[settle]`).
pub use settle::{Settle, SettleMode, DEFAULT_DWELL_S, MAX_DWELL_S};
/// Laser command templates with `{placeholder}` values.
pub use template::{format_number, LaserValues, Template};

/// Why a machine profile could not be used.
#[derive(Debug, thiserror::Error)]
pub enum MachineError {
    /// No file of that name in any searched folder and no built-in profile of that name.
    #[error("machine profile {name:?} not found (looked for {}; built in: {})", display_paths(searched), built_in.join(", "))]
    NotFound {
        /// The profile as given.
        name: String,
        /// The files looked for, in order.
        searched: Vec<PathBuf>,
        /// The built-in profiles' names.
        built_in: Vec<&'static str>,
    },
    /// The file could not be read.
    #[error("cannot read machine profile {path}")]
    Read {
        /// The profile's file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file is not valid TOML for a profile (unknown key, wrong type, missing key).
    #[error("machine profile {name:?}: {message}")]
    Parse {
        /// The profile as given.
        name: String,
        /// The TOML parser's message, which names the key and line.
        message: String,
    },
    /// A value is out of its range.
    #[error("machine profile {name:?}: {key} = {value} {limit}")]
    Value {
        /// The profile as given.
        name: String,
        /// The offending key.
        key: String,
        /// Its value, as written.
        value: String,
        /// The limit it broke, as a phrase.
        limit: String,
    },
}

fn display_paths(paths: &[PathBuf]) -> String {
    if paths.is_empty() {
        return "no folders".into();
    }
    let list: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
    list.join(", ")
}
