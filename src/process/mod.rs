//! Laser process parameter sets: the paper's Table II columns as data files.
//!
//! A set is a TOML file under `designs/process/` whose keys carry their units:
//!
//! ```toml
//! wavelength_nm = 1030
//! power_mw = 160            # average power
//! scan_speed_mm_s = 1.0     # speed of the focus over the tube's surface
//! pulse_frequency_khz = 200
//! pulse_width_fs = 550
//! repetitions = 1           # passes over every path
//! z_step_mm = 0.0           # optional: focus lowered by this much after each pass
//! min_wall_mm = 0.1         # optional: thinnest wall r_o − r_i it cuts cleanly (default 0.1)
//! ```
//!
//! A design names the sets it uses in its `[process]` table ([`crate::design::ProcessChoice`]);
//! [`ProcessLibrary`] finds them by name, first in the folders it is given, then among the two
//! sets built into the binary (`sensor` and `notches`, copies of the shipped files).
//!
//! # Errors
//! [`ProcessError`] names the set, the key and the limit it broke; unknown keys are refused.

mod library;
mod set;

use std::path::PathBuf;

/// Finds parameter sets by name and resolves a design's choice of sets.
pub use library::{ProcessLibrary, ProcessSets};
/// One laser parameter set (a Table II column), and the default thinnest wall it cuts.
pub use set::{ProcessSet, DEFAULT_MIN_WALL_MM};

/// Why a parameter set could not be used.
#[derive(Debug, thiserror::Error)]
pub enum ProcessError {
    /// No file of that name in any searched folder and no built-in set of that name.
    #[error(
        "process set {name:?} not found (looked for {})",
        display_paths(searched)
    )]
    NotFound {
        /// The set's name as the design wrote it.
        name: String,
        /// The files looked for, in order.
        searched: Vec<PathBuf>,
    },
    /// A set's name would leave its folder or is empty.
    #[error("process set name {name:?} is not a plain file stem (letters, digits, '-', '_')")]
    BadName {
        /// The offending name.
        name: String,
    },
    /// The file could not be read.
    #[error("cannot read process set {path}")]
    Read {
        /// The set's file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file is not valid TOML for a set (unknown key, wrong type, missing key).
    #[error("process set {name:?}: {message}")]
    Parse {
        /// The set's name.
        name: String,
        /// The TOML parser's message, which names the key and line.
        message: String,
    },
    /// A value is out of its range.
    #[error("process set {name:?}: {key} = {value} {limit}")]
    Value {
        /// The set's name.
        name: String,
        /// The offending key.
        key: &'static str,
        /// Its value.
        value: f64,
        /// The limit it broke, as a phrase.
        limit: &'static str,
    },
}

fn display_paths(paths: &[PathBuf]) -> String {
    if paths.is_empty() {
        return "no folders given, and it is not built in".into();
    }
    let list: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
    format!("{}, and it is not built in", list.join(", "))
}
