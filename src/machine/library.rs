//! Finding machine profiles: a path, a name in searched folders, or a built-in profile.

use std::path::{Path, PathBuf};

use super::{MachineError, MachineProfile};

/// The default profile's name.
pub const DEFAULT_PROFILE: &str = "linuxcnc-reference";

const BUILT_IN: [(&str, &str); 2] = [
    (
        "linuxcnc-reference",
        include_str!("../../designs/machines/linuxcnc-reference.toml"),
    ),
    (
        "aerotech-aerobasic",
        include_str!("../../designs/machines/aerotech-aerobasic.toml"),
    ),
];

/// Where profiles are looked up: a value with a `/` or ending in `.toml` is a path; a name is
/// looked for as `DIR/NAME.toml` in each folder, then among the built-in profiles.
#[derive(Debug, Clone, Default)]
pub struct MachineLibrary {
    dirs: Vec<PathBuf>,
}

impl MachineLibrary {
    /// A library searching `dirs` in order, then the built-ins.
    pub fn new(dirs: Vec<PathBuf>) -> Self {
        Self { dirs }
    }

    /// The library a design file uses: the `machines/` folder next to it, then the built-ins.
    pub fn beside(design_path: &Path) -> Self {
        let dir = design_path.parent().unwrap_or(Path::new("."));
        Self::new(vec![dir.join("machines")])
    }

    /// The file [`find`](Self::find) reads for `spec` (`None` for a built-in profile): an input
    /// that no output may replace.
    pub fn file(&self, spec: Option<&str>) -> Option<PathBuf> {
        let spec = spec.unwrap_or(DEFAULT_PROFILE);
        if spec.contains('/') || spec.contains('\\') || spec.ends_with(".toml") {
            return Some(PathBuf::from(spec));
        }
        self.dirs
            .iter()
            .map(|dir| dir.join(format!("{spec}.toml")))
            .find(|path| path.is_file())
    }

    /// Finds a profile by path or name; `None` means the default, [`DEFAULT_PROFILE`].
    ///
    /// # Errors
    /// [`MachineError::NotFound`] listing what was looked for, or the profile's own errors.
    pub fn find(&self, spec: Option<&str>) -> Result<MachineProfile, MachineError> {
        let spec = spec.unwrap_or(DEFAULT_PROFILE);
        if spec.contains('/') || spec.contains('\\') || spec.ends_with(".toml") {
            return load(Path::new(spec));
        }
        let mut searched = Vec::new();
        for dir in &self.dirs {
            let path = dir.join(format!("{spec}.toml"));
            if path.is_file() {
                return load(&path);
            }
            searched.push(path);
        }
        match BUILT_IN.iter().find(|(n, _)| *n == spec) {
            Some((name, text)) => MachineProfile::from_toml(&format!("built-in {name}"), text),
            None => Err(MachineError::NotFound {
                name: spec.to_string(),
                searched,
                built_in: BUILT_IN.iter().map(|(n, _)| *n).collect(),
            }),
        }
    }
}

fn load(path: &Path) -> Result<MachineProfile, MachineError> {
    let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
        |source| MachineError::Read {
            path: path.to_path_buf(),
            source,
        },
    )?;
    MachineProfile::from_toml(&path.display().to_string(), &text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_the_linuxcnc_reference() {
        let p = MachineLibrary::default().find(None).unwrap();
        assert_eq!(p.name, "LinuxCNC reference");
        assert_eq!(p.source, "built-in linuxcnc-reference");
        let err = MachineLibrary::default()
            .find(Some("haas"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("\"haas\" not found") && err.contains("aerotech-aerobasic"),
            "{err}"
        );
        let err = MachineLibrary::default()
            .find(Some("/no/such/profile.toml"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("/no/such/profile.toml"), "{err}");
    }
}
