//! The tube catalogue (`designs/tubes.toml`): stock sizes `dlw explore` may choose, each with
//! its source.

use std::path::Path;

use serde::Deserialize;

use super::spec::{read_toml, SpecError};

/// One tube size.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tube {
    /// The id a spec names it by.
    pub id: String,
    /// Outer radius `r_o` (mm).
    pub outer_radius_mm: f64,
    /// Inner radius `r_i` (mm).
    pub inner_radius_mm: f64,
    /// Where the size comes from.
    pub source: String,
}

/// The catalogue file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Catalogue {
    /// The sizes.
    pub tube: Vec<Tube>,
}

impl Catalogue {
    /// Reads and checks a catalogue: ids unique, radii finite with `0 < r_i < r_o`.
    ///
    /// # Errors
    /// [`SpecError`] naming the file and the bad entry.
    pub fn read(path: &Path) -> Result<Self, SpecError> {
        let cat: Self = read_toml(path)?;
        for (i, t) in cat.tube.iter().enumerate() {
            let ok = t.inner_radius_mm.is_finite()
                && t.outer_radius_mm.is_finite()
                && t.inner_radius_mm > 0.0
                && t.inner_radius_mm < t.outer_radius_mm;
            if !ok {
                return Err(SpecError::Value {
                    name: format!("tube {:?} in {}", t.id, path.display()),
                    value: format!("r_o = {}, r_i = {}", t.outer_radius_mm, t.inner_radius_mm),
                    limit: "must have finite radii with 0 < r_i < r_o".into(),
                });
            }
            if cat.tube[..i].iter().any(|u| u.id == t.id) {
                return Err(SpecError::Value {
                    name: format!("tube id in {}", path.display()),
                    value: format!("{:?}", t.id),
                    limit: "is listed twice (ids must be unique)".into(),
                });
            }
        }
        Ok(cat)
    }

    /// The tubes named by `ids`, in that order.
    ///
    /// # Errors
    /// [`SpecError::UnknownTube`] naming the id and listing the known ones.
    pub fn pick(&self, ids: &[String], path: &Path) -> Result<Vec<Tube>, SpecError> {
        ids.iter()
            .map(|id| {
                self.tube
                    .iter()
                    .find(|t| &t.id == id)
                    .cloned()
                    .ok_or_else(|| SpecError::UnknownTube {
                        id: id.clone(),
                        path: path.to_path_buf(),
                        known: self
                            .tube
                            .iter()
                            .map(|t| t.id.as_str())
                            .collect::<Vec<_>>()
                            .join(", "),
                    })
            })
            .collect()
    }
}
