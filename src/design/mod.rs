//! Design files: the paper's Table I quantities plus the fabrication tables, read from TOML and
//! validated once into a [`Design`].
//!
//! A design file holds the Table I keys at the top level and three optional tables whose every
//! key has a documented default ([`Fabrication`], [`Materials`], [`ProcessChoice`]):
//!
//! ```toml
//! name = "Joint A"
//! style = "uan"            # or "bsn"
//! outer_radius_mm = 1.24
//! inner_radius_mm = 0.875
//! notch_arc_mm = 5.61      # s_n: arc length of one notch on the outer surface
//! notch_width_mm = 0.5     # h
//! notch_spacing_mm = 0.5   # c
//! notch_count = 10         # N (per side for BSN)
//! joint_length_mm = 9.5    # L
//! sensor_arc_mm = 0.4      # s_s: arc between the two arms of a sensor
//! tendon_offset_mm = 0.735 # optional r_t (default r_i − 0.14 mm; docs/mechanics.md)
//!
//! [fabrication]            # optional; see `Fabrication` for every key
//! kerf_mm = 0.03
//!
//! [materials]              # optional; see `Materials`
//! tube = "polyimide"       # or "nitinol": Young's modulus and default backbone_strain_limit
//! ```
//!
//! Unknown keys are refused, so a misspelt parameter never silently takes its default.

mod count;
mod fabrication;
mod material;

use std::path::{Path, PathBuf};

use dlw_geometry::{CrossSection, GeometryError, Joint, Mechanics, NotchStyle};
use serde::{Deserialize, Serialize};

pub use fabrication::{Fabrication, Materials, ProcessChoice};
/// The tube materials and their sources.
pub use material::{
    TubeMaterial, NITINOL_STRAIN_LIMIT, NITINOL_YOUNGS_MODULUS_PA, POLYIMIDE_STRAIN_LIMIT,
    POLYIMIDE_YOUNGS_MODULUS_PA,
};

/// Most notches (levels, per side for BSN) a design may have: far more than a tube on a rotary
/// stage carries, and within what a DXF can number (16-bit XDATA integers). Defined here, with
/// the design, so the layout and the rules depend on the design and not the other way round.
pub const MAX_NOTCH_COUNT: u32 = 10_000;

/// The longest design name (characters): it titles drawings, sheets and program headers.
pub const MAX_NAME_CHARS: usize = 200;

/// A design file as written, before validation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignFile {
    /// Human-readable name, printed on drawings and programs.
    pub name: String,
    /// Notch style: `uan` or `bsn`.
    pub style: NotchStyle,
    /// Outer radius `r_o` (mm).
    pub outer_radius_mm: f64,
    /// Inner radius `r_i` (mm).
    pub inner_radius_mm: f64,
    /// Arc length of one notch on the outer surface, `s_n` (mm).
    pub notch_arc_mm: f64,
    /// Notch width `h` along the tube (mm).
    pub notch_width_mm: f64,
    /// Uncut length `c` between neighbouring notches (mm).
    pub notch_spacing_mm: f64,
    /// Notch count `N` (per side for BSN). Read from an integer or a whole float (`1e9`), so
    /// both get the design rule's message about the 10000 limit.
    #[serde(deserialize_with = "count::deserialize_notch_count")]
    pub notch_count: u32,
    /// Joint length `L` (mm).
    pub joint_length_mm: f64,
    /// Arc between the two arms of a sensor, `s_s` (mm).
    pub sensor_arc_mm: f64,
    /// Tendon offset `r_t` from the tube axis, on the notch side (mm). `None` means at the
    /// inner wall less half the paper's 0.28 mm tendon, `r_i − 0.14 mm`. Not written when
    /// absent, so existing designs keep their checksum.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tendon_offset_mm: Option<f64>,
    /// Trace, pad, margin and cutting parameters.
    #[serde(default)]
    pub fabrication: Fabrication,
    /// Material limits.
    #[serde(default)]
    pub materials: Materials,
    /// Which laser process parameter sets the design uses.
    #[serde(default)]
    pub process: ProcessChoice,
}

impl DesignFile {
    /// The tendon offset in force (mm): the file's, or `r_i − 0.14 mm`.
    pub fn tendon_offset_mm(&self) -> f64 {
        self.tendon_offset_mm
            .unwrap_or_else(|| Mechanics::default_tendon_offset_mm(self.inner_radius_mm))
    }

    /// Reads a design file without validating its values (the design rules do that, listing
    /// every problem at once).
    ///
    /// # Errors
    /// [`DesignError::Read`] or [`DesignError::Parse`] naming the file.
    pub fn read(path: &Path) -> Result<Self, DesignError> {
        let text = crate::output::read_limited(path, crate::limits::MAX_TEXT_INPUT_BYTES).map_err(
            |source| DesignError::Read {
                path: path.to_path_buf(),
                source,
            },
        )?;
        Self::from_toml(&text).map_err(|e| match e {
            DesignError::Parse { message, .. } => DesignError::Parse {
                path: path.to_path_buf(),
                message,
            },
            other => other,
        })
    }

    /// Parses a design from TOML text without validating its values.
    ///
    /// # Errors
    /// [`DesignError::Parse`] for malformed TOML or unknown keys.
    pub fn from_toml(text: &str) -> Result<Self, DesignError> {
        let file: Self = toml::from_str(text).map_err(|e| DesignError::Parse {
            path: PathBuf::from("<text>"),
            message: if lists_joints(text) {
                "this is a robot file (it lists [[joint]] tables), not a joint design: this command takes one joint's design; inspect, draw, program, build, import-dxf and estimator-config --joint take robot files (docs/robots.md)".into()
            } else {
                crate::limits::parser_message(&e)
            },
        })?;
        file.check_name().map_err(|reason| DesignError::Parse {
            path: PathBuf::from("<text>"),
            message: reason,
        })?;
        Ok(file)
    }

    /// The one check of the notch count against [`MAX_NOTCH_COUNT`]: [`Design::from_file`]
    /// refuses a file that fails it, and the design rules list it with every other problem.
    ///
    /// # Errors
    /// [`DesignError::TooManyNotches`].
    pub fn check_notch_count(&self) -> Result<(), DesignError> {
        if self.notch_count > MAX_NOTCH_COUNT {
            return Err(DesignError::TooManyNotches {
                name: self.name.clone(),
                count: self.notch_count,
                max: MAX_NOTCH_COUNT,
            });
        }
        Ok(())
    }

    /// The name must be printable text of at most [`MAX_NAME_CHARS`] characters: it is written
    /// into SVG (XML, where a control character makes the file unreadable), DXF and G-code
    /// comments.
    fn check_name(&self) -> Result<(), String> {
        let quoted = || format!("{:?}", crate::limits::quote(&self.name));
        if let Some(c) = self.name.chars().find(|c| c.is_control()) {
            return Err(format!(
                "name {} has the control character U+{:04X}: a design's name must be printable text",
                quoted(),
                u32::from(c)
            ));
        }
        let chars = self.name.chars().count();
        if chars > MAX_NAME_CHARS {
            return Err(format!(
                "name {} has {chars} characters, more than the limit of {MAX_NAME_CHARS}",
                quoted()
            ));
        }
        Ok(())
    }
}

/// Why a design file was refused.
#[derive(Debug, thiserror::Error)]
pub enum DesignError {
    /// The file could not be read.
    #[error("cannot read design {path}")]
    Read {
        /// The design file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file is not valid TOML for a design (unknown key, wrong type, missing key).
    #[error("design {path}: {message}")]
    Parse {
        /// The design file.
        path: PathBuf,
        /// The TOML parser's message, which names the key and line.
        message: String,
    },
    /// More notches than a layout holds ([`MAX_NOTCH_COUNT`]).
    #[error("design {name:?}: notch_count = {count} must be at most {max}")]
    TooManyNotches {
        /// The design's name.
        name: String,
        /// The count given.
        count: u32,
        /// The limit.
        max: u32,
    },
    /// A Table I quantity is not physical.
    #[error("design {name:?}: {reason}")]
    Geometry {
        /// The design's name.
        name: String,
        /// Which value broke which limit.
        reason: GeometryError,
    },
}

/// A validated design: the file as written and the joint geometry built from it.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// The design as written (with defaults filled in).
    pub file: DesignFile,
    /// The joint geometry shared with the estimator.
    pub joint: Joint,
    /// The joint's tendon mechanics (`docs/mechanics.md`).
    pub mechanics: Mechanics,
    /// A checksum of the design's canonical TOML (FNV-1a 64, hex), printed in program headers
    /// so an operator can tell which design a program was made from.
    pub checksum: String,
}

impl Design {
    /// Reads and validates a design file.
    ///
    /// # Errors
    /// [`DesignError`] naming the file, key or value.
    pub fn load(path: &Path) -> Result<Self, DesignError> {
        Self::from_file(DesignFile::read(path)?)
    }

    /// Parses and validates a design from TOML text.
    ///
    /// # Errors
    /// [`DesignError::Parse`] for malformed TOML or unknown keys, [`DesignError::Geometry`] for
    /// unphysical Table I values.
    pub fn from_toml(text: &str) -> Result<Self, DesignError> {
        Self::from_file(DesignFile::from_toml(text)?)
    }

    /// Validates a design already in memory.
    ///
    /// # Errors
    /// [`DesignError::Geometry`] for unphysical Table I values.
    pub fn from_file(file: DesignFile) -> Result<Self, DesignError> {
        // A `Design` never holds more notches than the limit, so the layout and everything
        // after it can rely on it.
        file.check_notch_count()?;
        let geometry = |reason| DesignError::Geometry {
            name: file.name.clone(),
            reason,
        };
        let section = CrossSection::new(
            file.style,
            file.outer_radius_mm,
            file.inner_radius_mm,
            file.notch_arc_mm,
            file.sensor_arc_mm,
        )
        .map_err(geometry)?;
        let joint = Joint::new(
            section,
            file.notch_width_mm,
            file.notch_spacing_mm,
            file.notch_count,
            file.joint_length_mm,
        )
        .map_err(geometry)?;
        let mechanics = Mechanics::new(joint, file.tendon_offset_mm()).map_err(geometry)?;
        let canonical = toml::to_string(&file).unwrap_or_default();
        let checksum = format!("{:016x}", fnv1a64(canonical.as_bytes()));
        Ok(Self {
            file,
            joint,
            mechanics,
            checksum,
        })
    }
}

/// Whether `text` is TOML with a `joint` array, the mark of a robot file (`crate::robot`), so
/// that a command that reads one design says so rather than "unknown field `joint`".
fn lists_joints(text: &str) -> bool {
    toml::from_str::<toml::Table>(text)
        .ok()
        .is_some_and(|t| t.get("joint").is_some_and(toml::Value::is_array))
}

/// FNV-1a, 64 bit: a stable, dependency-free fingerprint (not a security hash).
pub(crate) fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const JOINT_A: &str = r#"
name = "Joint A"
style = "uan"
outer_radius_mm = 1.24
inner_radius_mm = 0.875
notch_arc_mm = 5.61
notch_width_mm = 0.5
notch_spacing_mm = 0.5
notch_count = 10
joint_length_mm = 9.5
sensor_arc_mm = 0.4
"#;

    #[test]
    fn reads_table_one_keys_with_defaults() {
        let d = Design::from_toml(JOINT_A).unwrap();
        assert_eq!(d.file.name, "Joint A");
        assert_eq!(d.joint.notch_count(), 10);
        assert_eq!(d.file.fabrication, Fabrication::default());
        assert_eq!(d.checksum.len(), 16);
    }

    #[test]
    fn refuses_unknown_keys_everywhere() {
        let top = format!("{JOINT_A}\nnotch_depth_mm = 1.0\n");
        let err = Design::from_toml(&top).unwrap_err().to_string();
        assert!(err.contains("notch_depth_mm"), "{err}");
        let nested = format!("{JOINT_A}\n[fabrication]\nkerf = 0.03\n");
        let err = Design::from_toml(&nested).unwrap_err().to_string();
        assert!(err.contains("kerf"), "{err}");
    }

    #[test]
    fn refuses_unphysical_geometry_with_value() {
        let bad = JOINT_A.replace("inner_radius_mm = 0.875", "inner_radius_mm = 1.3");
        let err = Design::from_toml(&bad).unwrap_err().to_string();
        assert!(
            err.contains("inner_radius_mm = 1.3") && err.contains("1.24"),
            "{err}"
        );
    }

    #[test]
    fn the_tube_material_sets_the_backbone_limit_unless_given() {
        let d = Design::from_toml(JOINT_A).unwrap();
        assert_eq!(d.file.materials.tube, TubeMaterial::Polyimide);
        assert_eq!(
            d.file.materials.backbone_strain_limit,
            POLYIMIDE_STRAIN_LIMIT
        );
        let niti =
            Design::from_toml(&format!("{JOINT_A}\n[materials]\ntube = \"nitinol\"\n")).unwrap();
        assert_eq!(
            niti.file.materials.backbone_strain_limit,
            NITINOL_STRAIN_LIMIT
        );
        assert_eq!(
            niti.file.materials.youngs_modulus_pa(),
            NITINOL_YOUNGS_MODULUS_PA
        );
        let own =
            format!("{JOINT_A}\n[materials]\ntube = \"nitinol\"\nbackbone_strain_limit = 0.05\n");
        assert_eq!(
            Design::from_toml(&own)
                .unwrap()
                .file
                .materials
                .backbone_strain_limit,
            0.05
        );
        let err = Design::from_toml(&format!("{JOINT_A}\n[materials]\ntube = \"steel\"\n"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("steel") && err.contains("nitinol"), "{err}");
        let err = Design::from_toml(&format!("{JOINT_A}\n[materials]\nbackbone = 0.1\n"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("backbone"), "{err}");
    }

    /// New optional keys left out keep a design's canonical TOML, so its checksum (printed in
    /// every program header) does not change.
    #[test]
    fn defaults_keep_the_canonical_text() {
        let d = Design::from_toml(JOINT_A).unwrap();
        let text = toml::to_string(&d.file).unwrap();
        assert!(
            !text.contains("tendon_offset_mm") && !text.contains("tube"),
            "{text}"
        );
        assert!(text.contains("backbone_strain_limit = 0.03"), "{text}");
        let with = format!("{JOINT_A}tendon_offset_mm = 0.5\n");
        let d2 = Design::from_toml(&with).unwrap();
        assert_eq!(d2.mechanics.tendon_offset_mm(), 0.5);
        assert_ne!(d2.checksum, d.checksum);
        // Written designs read back the same.
        let back = DesignFile::from_toml(&toml::to_string(&d2.file).unwrap()).unwrap();
        assert_eq!(back, d2.file);
    }

    #[test]
    fn checksum_follows_content() {
        let a = Design::from_toml(JOINT_A).unwrap();
        let b = Design::from_toml(&JOINT_A.replace("0.4\n", "0.41\n")).unwrap();
        assert_ne!(a.checksum, b.checksum);
        assert_eq!(a.checksum, Design::from_toml(JOINT_A).unwrap().checksum);
    }
}
