//! Where a program's layout came from, when it came from a drawing: the file, its SHA-256,
//! how it was read, the joint as drawn, and every difference from the design's own layout.
//! The program header and the setup sheet print [`Provenance::lines`].
//!
//! # Examples
//! ```
//! use dlw::{design::Design, drawing::{layout_to_dxf, read_dxf, ImportOptions, Provenance}, layout::Layout};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let design = Design::from_toml(include_str!("../../../designs/joint-a.toml"))?;
//! let layout = Layout::from_design(&design)?;
//! let bytes = layout_to_dxf(&layout, 0.08)?;
//! let imported = read_dxf(&bytes, &ImportOptions::default())?;
//! let p = Provenance::new("a.dxf", &bytes, &imported, &layout);
//! assert!(p.lines()[0].starts_with("layout from drawing a.dxf"));
//! assert!(p.differences.is_empty());
//! # Ok(()) }
//! ```

mod differences;
mod sha256;

use crate::layout::Layout;

use super::{ImportedDxf, UnitsSource};

pub use sha256::sha256_hex;

/// Longest line [`Provenance::lines`] gives (characters): G-code comments must stay well under
/// LinuxCNC's 255-character line limit.
pub const MAX_LINE_CHARS: usize = 180;

/// `line` broken at spaces into pieces of at most `max` characters (a word longer than that is
/// cut); continuations are indented by two spaces.
fn wrap(line: &str, max: usize) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in line.split(' ') {
        let mut word = word.to_string();
        loop {
            let sep = usize::from(!current.is_empty() && !current.trim().is_empty());
            if current.chars().count() + sep + word.chars().count() <= max {
                if sep == 1 {
                    current.push(' ');
                }
                current.push_str(&word);
                break;
            }
            if current.trim().is_empty() {
                // A word longer than a line: cut it.
                let room = max - current.chars().count();
                let head: String = word.chars().take(room).collect();
                word = word.chars().skip(room).collect();
                current.push_str(&head);
            }
            out.push(std::mem::replace(&mut current, "  ".into()));
        }
    }
    out.push(current);
    out
}

/// Where a layout came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// The drawing's file name, as the operator will find it.
    pub file_name: String,
    /// SHA-256 of its bytes (hex), as `sha256sum` prints it.
    pub sha256: String,
    /// Its size.
    pub bytes: usize,
    /// How it was read: version, units, where the layout's numbers came from.
    pub read_as: String,
    /// The joint's numbers as drawn and as designed (see [`crate::rules::Derived`]).
    pub derived: Vec<String>,
    /// Every difference from the design's own layout, one line each.
    pub differences: Vec<String>,
}

impl Provenance {
    /// The provenance of `imported`, read from `bytes` of the file `file_name`, compared with
    /// the design's own layout `design_layout`.
    pub fn new(
        file_name: &str,
        bytes: &[u8],
        imported: &ImportedDxf,
        design_layout: &Layout,
    ) -> Self {
        let (units, source) = imported.units;
        let read_as = format!(
            "AutoCAD {}, {} from {}, layout numbers from {}",
            imported.version,
            units.name(),
            match source {
                UnitsSource::Header => "$INSUNITS",
                UnitsSource::Given => "--units",
            },
            if imported.numbers_from_xdata {
                "the drawing's dlw XDATA"
            } else {
                "the design (the drawing has no dlw XDATA)"
            }
        );
        Self {
            file_name: file_name.to_string(),
            sha256: sha256_hex(bytes),
            bytes: bytes.len(),
            read_as,
            derived: Vec::new(),
            differences: differences::differences(design_layout, &imported.layout),
        }
    }

    /// The same, with the joint's numbers as drawn ([`crate::rules::Derived::summary`]).
    pub fn with_derived(mut self, summary: impl IntoIterator<Item = String>) -> Self {
        self.derived = summary.into_iter().collect();
        self
    }

    /// The same lines as a Markdown block for the setup sheet: a warning paragraph, then the
    /// differences as a list (starts and ends with a blank line).
    pub fn markdown(&self) -> String {
        let mut out = String::from("\n> **Layout from a drawing, not from the design.**\n");
        for line in self.lines() {
            if let Some(item) = line.strip_prefix("- ") {
                out.push_str(&format!(">\n> - {item}\n"));
            } else {
                out.push_str(&format!(">\n> {line}\n"));
            }
        }
        out
    }

    /// The lines the program header prints (and the setup sheet, via [`Self::markdown`]).
    pub fn lines(&self) -> Vec<String> {
        let mut out = vec![
            format!(
                "layout from drawing {} ({} bytes)",
                self.file_name, self.bytes
            ),
            format!("read as {}", self.read_as),
            format!("drawing SHA-256 {}", self.sha256),
        ];
        out.extend(self.derived.iter().cloned());
        if self.differences.is_empty() {
            out.push("differences from the design's own layout: none".into());
        } else {
            out.push(format!(
                "differences from the design's own layout ({}):",
                self.differences.len()
            ));
            out.extend(self.differences.iter().map(|d| format!("- {d}")));
        }
        out.into_iter()
            .flat_map(|l| wrap(&l, MAX_LINE_CHARS))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_lines_are_wrapped_without_losing_a_character() {
        let name = format!("{}.dxf", "x".repeat(300));
        let line = format!("layout from drawing {name} (1234 bytes)");
        let wrapped = wrap(&line, MAX_LINE_CHARS);
        assert!(wrapped.len() >= 3, "{wrapped:?}");
        assert!(wrapped.iter().all(|l| l.chars().count() <= MAX_LINE_CHARS));
        let joined: String = wrapped
            .iter()
            .enumerate()
            .map(|(i, l)| {
                if i == 0 {
                    l.clone()
                } else {
                    l[2..].to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("");
        assert_eq!(joined.replace(' ', ""), line.replace(' ', ""));
        assert_eq!(wrap("short line", 180), vec!["short line".to_string()]);
    }
}
