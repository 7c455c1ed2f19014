//! Finding parameter sets by name: searched folders first, then the sets built into the binary.

use std::path::{Path, PathBuf};

use super::{ProcessError, ProcessSet};
use crate::design::ProcessChoice;

/// The shipped sets, built in so that a design outside this repository still finds them.
const BUILT_IN: [(&str, &str); 2] = [
    ("sensor", include_str!("../../designs/process/sensor.toml")),
    (
        "notches",
        include_str!("../../designs/process/notches.toml"),
    ),
];

/// Where parameter sets are looked up: `DIR/NAME.toml` for each folder in order, then the
/// built-in `sensor` and `notches`.
#[derive(Debug, Clone, Default)]
pub struct ProcessLibrary {
    dirs: Vec<PathBuf>,
}

/// The three sets a job uses, one per operation.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcessSets {
    /// Writing the sensor, leads and pads (Table II (a)).
    pub sensor: ProcessSet,
    /// Cutting the notches (Table II (b)).
    pub notches: ProcessSet,
    /// Parting the joint off the stock (the notch set unless the design names another).
    pub parting: ProcessSet,
}

impl ProcessLibrary {
    /// A library searching `dirs` in order, then the built-in sets.
    pub fn new(dirs: Vec<PathBuf>) -> Self {
        Self { dirs }
    }

    /// The library a design file uses: the `process/` folder next to it, then the built-ins.
    pub fn beside(design_path: &Path) -> Self {
        let dir = design_path.parent().unwrap_or(Path::new("."));
        Self::new(vec![dir.join("process")])
    }

    /// Finds the set called `name`.
    ///
    /// # Errors
    /// [`ProcessError::BadName`] for a name that is not a plain file stem,
    /// [`ProcessError::NotFound`] listing the files looked for, or the set's own errors.
    pub fn find(&self, name: &str) -> Result<ProcessSet, ProcessError> {
        let plain = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
        if !plain {
            return Err(ProcessError::BadName {
                name: name.to_string(),
            });
        }
        let mut searched = Vec::new();
        for dir in &self.dirs {
            let path = dir.join(format!("{name}.toml"));
            if path.is_file() {
                let text = crate::output::read_limited(&path, crate::limits::MAX_TEXT_INPUT_BYTES)
                    .map_err(|source| ProcessError::Read { path, source })?;
                return ProcessSet::from_toml(name, &text);
            }
            searched.push(path);
        }
        match BUILT_IN.iter().find(|(n, _)| *n == name) {
            Some((_, text)) => ProcessSet::from_toml(name, text),
            None => Err(ProcessError::NotFound {
                name: name.to_string(),
                searched,
            }),
        }
    }

    /// The files [`resolve`](Self::resolve) reads for `choice` (sets found in the searched
    /// folders; a built-in set has none): inputs that no output may replace.
    pub fn files(&self, choice: &ProcessChoice) -> Vec<PathBuf> {
        let names = [
            Some(&choice.sensor),
            Some(&choice.notches),
            choice.parting.as_ref(),
        ];
        let mut files: Vec<PathBuf> = names
            .into_iter()
            .flatten()
            .filter_map(|name| {
                self.dirs
                    .iter()
                    .map(|dir| dir.join(format!("{name}.toml")))
                    .find(|path| path.is_file())
            })
            .collect();
        files.dedup();
        files
    }

    /// Resolves a design's `[process]` choice into the three sets.
    ///
    /// # Errors
    /// As [`ProcessLibrary::find`], for the first set that fails.
    pub fn resolve(&self, choice: &ProcessChoice) -> Result<ProcessSets, ProcessError> {
        let sensor = self.find(&choice.sensor)?;
        let notches = self.find(&choice.notches)?;
        let parting = match &choice.parting {
            Some(name) => self.find(name)?,
            None => notches.clone(),
        };
        Ok(ProcessSets {
            sensor,
            notches,
            parting,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folder_first_then_built_in_then_clear_error() {
        let dir = tempfile::tempdir().unwrap();
        let slow = include_str!("../../designs/process/sensor.toml")
            .replace("scan_speed_mm_s = 1.0", "scan_speed_mm_s = 0.5");
        std::fs::write(dir.path().join("sensor.toml"), slow).unwrap();
        let lib = ProcessLibrary::new(vec![dir.path().to_path_buf()]);
        assert_eq!(lib.find("sensor").unwrap().scan_speed_mm_s, 0.5);
        assert_eq!(lib.find("notches").unwrap().repetitions, 32);
        let err = lib.find("engrave").unwrap_err().to_string();
        assert!(
            err.contains("\"engrave\" not found") && err.contains("engrave.toml"),
            "{err}"
        );
        let err = lib.find("../etc/passwd").unwrap_err().to_string();
        assert!(err.contains("not a plain file stem"), "{err}");
    }

    #[test]
    fn parting_defaults_to_the_notch_set() {
        let lib = ProcessLibrary::default();
        let sets = lib.resolve(&ProcessChoice::default()).unwrap();
        assert_eq!(sets.parting, sets.notches);
        let choice = ProcessChoice {
            parting: Some("sensor".into()),
            ..ProcessChoice::default()
        };
        assert_eq!(lib.resolve(&choice).unwrap().parting.power_mw, 160.0);
    }
}
