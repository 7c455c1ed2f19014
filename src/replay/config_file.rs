//! Estimator config files: `dlw_estimator::EstimatorConfig` as TOML or JSON, chosen by the
//! file's extension (`.toml`, `.json`).

use std::path::{Path, PathBuf};

use dlw_estimator::{EstimatorConfig, EstimatorError, RobotEstimatorConfig};

/// Why an estimator config file could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum ConfigFileError {
    /// The extension names no supported format.
    #[error("config file {path} must end in .toml or .json (the extension picks the format)")]
    Extension {
        /// The file.
        path: PathBuf,
    },
    /// The file could not be read.
    #[error("cannot read estimator config {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// Not a valid config (unknown key, wrong type, missing key).
    #[error("estimator config {path}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's message, which names the key and line.
        message: String,
    },
    /// Parsed, but a value is out of range.
    #[error("estimator config {path}: {reason}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What the estimator crate refused.
        reason: EstimatorError,
    },
    /// A robot config parsed, but a value is out of range.
    #[error("robot estimator config {path}: {reason}")]
    RobotInvalid {
        /// The file.
        path: PathBuf,
        /// What the estimator crate refused.
        reason: dlw_estimator::RobotError,
    },
    /// The config could not be serialized.
    #[error("cannot serialize the estimator config: {message}")]
    Serialize {
        /// The serializer's message.
        message: String,
    },
}

/// A config file's format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConfigFormat {
    /// `.toml`.
    Toml,
    /// `.json`.
    Json,
}

impl ConfigFormat {
    /// The format `path`'s extension names.
    ///
    /// # Errors
    /// [`ConfigFileError::Extension`] for anything but `.toml` and `.json` (any case).
    pub fn of(path: &Path) -> Result<Self, ConfigFileError> {
        // `-o -` (standard output) writes TOML.
        if path.as_os_str() == "-" {
            return Ok(Self::Toml);
        }
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("toml") => Ok(Self::Toml),
            Some("json") => Ok(Self::Json),
            _ => Err(ConfigFileError::Extension {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// The config file at `path`, read through the bounded reader and parsed as TOML or JSON by
/// its extension (not yet validated).
fn parse_file<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, ConfigFileError> {
    let format = ConfigFormat::of(path)?;
    let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
        |source| ConfigFileError::Read {
            path: path.to_path_buf(),
            source,
        },
    )?;
    let parse = |message: String| ConfigFileError::Parse {
        path: path.to_path_buf(),
        message: message.trim_end().to_string(),
    };
    match format {
        ConfigFormat::Toml => {
            toml::from_str(&text).map_err(|e| parse(crate::limits::parser_message(&e)))
        }
        ConfigFormat::Json => {
            serde_json::from_str(&text).map_err(|e| parse(crate::limits::parser_message(&e)))
        }
    }
}

/// Reads and validates an estimator config.
///
/// # Errors
/// [`ConfigFileError`] naming the file and the key or value.
pub fn load_config(path: &Path) -> Result<EstimatorConfig, ConfigFileError> {
    let config: EstimatorConfig = parse_file(path)?;
    config
        .validate()
        .map_err(|reason| ConfigFileError::Invalid {
            path: path.to_path_buf(),
            reason,
        })?;
    Ok(config)
}

/// Whether the config file at `path` is a robot's (it lists `[[joint]]` tables), read through
/// the bounded reader; `false` for anything unreadable, which [`load_config`] then names, and
/// for anything not a regular file (reading a pipe would consume what [`load_config`] needs).
pub fn is_robot_config(path: &Path) -> bool {
    /// A config's `joint` list, whatever its tables hold.
    #[derive(serde::Deserialize)]
    struct Joints {
        joint: Option<Vec<serde::de::IgnoredAny>>,
    }
    std::fs::metadata(path).is_ok_and(|m| m.is_file())
        && parse_file::<Joints>(path).is_ok_and(|j| j.joint.is_some())
}

/// Reads and validates a robot's estimator config (`docs/robot-runtime.md`).
///
/// # Errors
/// [`ConfigFileError`] naming the file and the key or value.
pub fn load_robot_config(path: &Path) -> Result<RobotEstimatorConfig, ConfigFileError> {
    let config: RobotEstimatorConfig = parse_file(path)?;
    config
        .validate()
        .map_err(|reason| ConfigFileError::RobotInvalid {
            path: path.to_path_buf(),
            reason,
        })?;
    Ok(config)
}

/// The text of a robot's `config` in `format`, with a leading comment `note` for TOML.
///
/// # Errors
/// [`ConfigFileError::Serialize`] if the serializer refuses (it does not for valid configs).
pub fn robot_config_text(
    config: &RobotEstimatorConfig,
    format: ConfigFormat,
    note: &str,
) -> Result<String, ConfigFileError> {
    let err = |e: String| ConfigFileError::Serialize { message: e };
    match format {
        ConfigFormat::Toml => {
            let body = toml::to_string(config).map_err(|e| err(e.to_string()))?;
            let comment: String = note.lines().map(|l| format!("# {l}\n")).collect();
            Ok(format!("{comment}{body}"))
        }
        ConfigFormat::Json => {
            let mut body = serde_json::to_string_pretty(config).map_err(|e| err(e.to_string()))?;
            body.push('\n');
            Ok(body)
        }
    }
}

/// The text of `config` in `format`, with a leading comment `note` for TOML (JSON has none).
///
/// # Errors
/// [`ConfigFileError::Serialize`] if the serializer refuses (it does not for valid configs).
pub fn config_text(
    config: &EstimatorConfig,
    format: ConfigFormat,
    note: &str,
) -> Result<String, ConfigFileError> {
    let err = |e: String| ConfigFileError::Serialize { message: e };
    match format {
        ConfigFormat::Toml => {
            let body = toml::to_string(config).map_err(|e| err(e.to_string()))?;
            let comment: String = note.lines().map(|l| format!("# {l}\n")).collect();
            Ok(format!("{comment}{body}"))
        }
        ConfigFormat::Json => {
            let mut body = serde_json::to_string_pretty(config).map_err(|e| err(e.to_string()))?;
            body.push('\n');
            Ok(body)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use dlw_estimator::{nominal_divider, JointConfig};

    fn config() -> EstimatorConfig {
        let design = crate::sim::test_design(dlw_geometry::NotchStyle::Bsn);
        EstimatorConfig::nominal_linear(
            JointConfig::from_joint(&design.joint),
            1.28,
            74.0e3,
            nominal_divider(),
        )
        .unwrap()
    }

    #[test]
    fn round_trips_in_both_formats() {
        let dir = tempfile::tempdir().unwrap();
        for (name, format) in [
            ("c.toml", ConfigFormat::Toml),
            ("c.JSON", ConfigFormat::Json),
        ] {
            let path = dir.path().join(name);
            assert_eq!(ConfigFormat::of(&path).unwrap(), format);
            std::fs::write(&path, config_text(&config(), format, "a\nb").unwrap()).unwrap();
            assert_eq!(load_config(&path).unwrap(), config());
        }
    }

    #[test]
    fn names_the_file_and_the_problem() {
        let dir = tempfile::tempdir().unwrap();
        let err = ConfigFormat::of(Path::new("c.yaml"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("c.yaml") && err.contains(".toml or .json"),
            "{err}"
        );
        let path = dir.path().join("bad.toml");
        let text = config_text(&config(), ConfigFormat::Toml, "").unwrap();
        std::fs::write(&path, text.replace("divider_ohm", "divider_kohm")).unwrap();
        let err = load_config(&path).unwrap_err().to_string();
        assert!(
            err.contains("bad.toml") && err.contains("divider_kohm"),
            "{err}"
        );
        std::fs::write(&path, text.replace("r0_ohm = 74000.0", "r0_ohm = -1.0")).unwrap();
        let err = load_config(&path).unwrap_err().to_string();
        assert!(err.contains("bad.toml") && err.contains("-1"), "{err}");
    }
}
