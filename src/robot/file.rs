//! The robot file: a name and its joints, distal first, each a joint design placed on the
//! robot's tube (issue 33 §1; `docs/robots.md`).
//!
//! ```toml
//! name = "Robot BC"
//! [[joint]]
//! design = "joint-b.toml"      # a joint design file, relative to this file
//! rotation_deg = 0.0           # its +y (backbone, sensor side) at s = r_o·rotation
//! [[joint]]
//! design = "joint-c.toml"
//! rotation_deg = 90.0
//! gap_mm = 3.0                 # uncut tube between the previous joint's last notch and this one's first
//! ```

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::error::RobotError;

/// Most joints a robot may have: far more than a tube on a rotary stage carries, and few
/// enough that the router's search stays small.
pub const MAX_JOINTS: usize = 16;

/// A robot file as written, before its designs are read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotFile {
    /// Human-readable name, printed on drawings and programs.
    pub name: String,
    /// The joints, distal first (`[[joint]]`).
    #[serde(rename = "joint", default)]
    pub joints: Vec<JointEntry>,
}

/// One `[[joint]]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointEntry {
    /// The joint's design file, relative to the robot file.
    pub design: PathBuf,
    /// Its bending plane about the tube axis (°): its `+y` (backbone, sensor side) lies at
    /// `s = r_o·rotation` on the robot's tube.
    pub rotation_deg: f64,
    /// Uncut tube between the previous joint's last notch and this joint's first (mm); every
    /// joint after the first has one, the first has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gap_mm: Option<f64>,
}

impl RobotFile {
    /// Reads a robot file through the bounded reader.
    ///
    /// # Errors
    /// [`RobotError::Read`] or [`RobotError::Parse`] naming the file.
    pub fn read(path: &Path) -> Result<Self, RobotError> {
        let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
            |source| RobotError::Read {
                path: path.to_path_buf(),
                source,
            },
        )?;
        Self::from_toml(&text).map_err(|message| RobotError::Parse {
            path: path.to_path_buf(),
            message,
        })
    }

    /// Parses a robot file from TOML text.
    ///
    /// # Errors
    /// The parser's message (unknown key, wrong type, missing key), or what is wrong with the
    /// name or the number of joints.
    pub fn from_toml(text: &str) -> Result<Self, String> {
        let file: Self = toml::from_str(text).map_err(|e| crate::limits::parser_message(&e))?;
        let quoted = crate::limits::quote(&file.name);
        if let Some(c) = file.name.chars().find(|c| c.is_control()) {
            return Err(format!(
                "name {quoted:?} has the control character U+{:04X}: a robot's name must be printable text",
                u32::from(c)
            ));
        }
        let chars = file.name.chars().count();
        if chars > crate::design::MAX_NAME_CHARS {
            return Err(format!(
                "name {quoted:?} has {chars} characters, more than the limit of {}",
                crate::design::MAX_NAME_CHARS
            ));
        }
        if file.joints.is_empty() {
            return Err("a robot needs at least one [[joint]] table".into());
        }
        if file.joints.len() > MAX_JOINTS {
            return Err(format!(
                "{} [[joint]] tables, more than the limit of {MAX_JOINTS}",
                file.joints.len()
            ));
        }
        Ok(file)
    }
}

/// Whether `text` is a robot file rather than a joint design: TOML with a `joint` array of
/// tables. Anything else (a design, or text that is not TOML) is left to the design reader and
/// its messages.
pub fn is_robot_toml(text: &str) -> bool {
    toml::from_str::<toml::Table>(text)
        .ok()
        .is_some_and(|t| t.get("joint").is_some_and(toml::Value::is_array))
}

/// Whether the file at `path` is a robot file ([`is_robot_toml`]); `false` when it cannot be
/// read, so that the design reader reports why. Only a regular file is looked into: reading a
/// pipe would consume what the design reader needs, so a design given through a pipe is read
/// as a joint's.
pub fn is_robot_file(path: &Path) -> bool {
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return false;
    }
    crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES)
        .map(|text| is_robot_toml(&text))
        .unwrap_or(false)
}

/// The files a command given `path` as its design reads: `path` itself and, for a robot file,
/// each joint's design file it names (resolved beside it, as the robot is assembled). Every
/// command claims its outputs against these (docs/outputs.md), so that `--force` never
/// replaces a joint design a robot names. A robot file that cannot be read gives `path` alone:
/// the command then refuses it with the reader's message.
pub fn design_inputs(path: &Path) -> Vec<std::path::PathBuf> {
    let mut files = vec![path.to_path_buf()];
    if is_robot_file(path) {
        if let Ok(file) = RobotFile::read(path) {
            let base = path.parent().unwrap_or_else(|| Path::new(""));
            files.extend(file.joints.iter().map(|entry| base.join(&entry.design)));
        }
    }
    files
}

#[cfg(test)]
mod tests {
    use super::*;

    const BC: &str = r#"
name = "Robot BC"
[[joint]]
design = "joint-b.toml"
rotation_deg = 0.0
[[joint]]
design = "joint-c.toml"
rotation_deg = 90.0
gap_mm = 3.0
"#;

    #[test]
    fn reads_the_fixed_keys_and_tells_robots_from_designs() {
        let f = RobotFile::from_toml(BC).unwrap();
        assert_eq!(f.joints.len(), 2);
        assert_eq!(f.joints[1].gap_mm, Some(3.0));
        assert!(is_robot_toml(BC));
        assert!(!is_robot_toml(include_str!("../../designs/joint-a.toml")));
        assert!(!is_robot_toml("not = [toml"));
        let err = RobotFile::from_toml(&BC.replace("gap_mm", "gap")).unwrap_err();
        assert!(err.contains("gap"), "{err}");
        let err = RobotFile::from_toml("name = \"x\"\njoint = []\n").unwrap_err();
        assert!(err.contains("at least one [[joint]]"), "{err}");
    }
}
