//! Design rules: what a design and its layout must satisfy before anything is drawn or cut.
//!
//! They run on every command. Errors ([`Violation`]) block output and are all listed at once in
//! a [`RulesError`]; warnings ([`Warning`]) are printed. Every message names the parameter or
//! feature, its value and the limit, e.g. `sensor 1 arm at x = 3.25 mm, s = 0.60 mm is 0.030 mm
//! from notch 4 (clearance 0.080 mm required)`.
//!
//! | rule | family (file) |
//! |---|---|
//! | lengths, strain limits and clearance positive and finite; `1 ≤ N ≤ 10000`; at least one pad turn; `h` and `c` larger than the kerf | `dimensions` |
//! | `r_i < r_o`; `s_n < 2π·r_o` (UAN) or `s_n < π·r_o` (BSN pair must not overlap); sensor arms on the backbone; what else the geometry crate refuses | `section` |
//! | `L = N·h + (N−1)·c` to [`LENGTH_TOLERANCE_MM`] | `length` |
//! | `pad_pitch_mm ≥ trace_width_mm`; the pads fit round the tube | `pads` |
//! | every arm, lead and pad keeps the clearance from every cut and every other trace (see `clearance`) | `clearance` |
//! | `r_o − r_i ≥ min_wall_mm` of the notch and parting sets (run by the laser planner, which has the sets) | `wall` |
//! | warning: sensor strain at the notch-closing angle past the saturation strain; backbone strain past its limit | `strain` |
//!
//! # Examples
//! ```no_run
//! use dlw::{design::Design, layout::Layout, rules};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let design = Design::load("designs/joint-a.toml".as_ref())?;
//! let layout = Layout::from_design(&design)?;
//! let warnings = rules::check(&design, &layout).into_result(&design.file.name)?;
//! # Ok(()) }
//! ```

mod clearance;
mod dimensions;
mod drawing;
mod inspection;
mod length;
mod notch_layout;
mod pads;
mod parts;
mod section;
mod strain;
mod violation;
mod wall;

use crate::design::{Design, DesignFile};
use crate::layout::Layout;

pub(crate) use drawing::derive;
/// A drawing checked against its design, and the joint's numbers as drawn.
pub use drawing::{check_drawing, check_imported, CheckedDrawing, Derived, DrawingReport};
/// How far the joint length may differ from the notch pattern (mm).
pub use length::LENGTH_TOLERANCE_MM;
pub(crate) use strain::check as strain_warnings;
/// A broken design rule, and a warning.
pub use violation::{Violation, Warning};
/// The tube wall against the cutting sets' `min_wall_mm`.
pub use wall::check_wall;

/// What the rules found.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    /// Broken rules: nothing may be written while there are any.
    pub errors: Vec<Violation>,
    /// Things to print.
    pub warnings: Vec<Warning>,
}

/// A design broke one or more rules; the message lists every one.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("design {name:?} breaks {} design rule{}:{}", .violations.len(), if .violations.len() == 1 { "" } else { "s" }, list(.violations))]
pub struct RulesError {
    /// The design's name.
    pub name: String,
    /// Every broken rule.
    pub violations: Vec<Violation>,
}

fn list(violations: &[Violation]) -> String {
    violations.iter().map(|v| format!("\n  - {v}")).collect()
}

impl Report {
    /// The warnings if no rule is broken, else a [`RulesError`] listing every broken rule.
    ///
    /// # Errors
    /// [`RulesError`] when `errors` is not empty.
    pub fn into_result(self, name: &str) -> Result<Vec<Warning>, RulesError> {
        if self.errors.is_empty() {
            Ok(self.warnings)
        } else {
            Err(RulesError {
                name: name.to_string(),
                violations: self.errors,
            })
        }
    }
}

/// A checked design's derived numbers, as `dlw inspect` reports them.
pub use inspection::Inspection;

/// A design that passed every rule, with its layout and warnings.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The validated design.
    pub design: Design,
    /// Its layout.
    pub layout: Layout,
    /// Warnings to print.
    pub warnings: Vec<Warning>,
}

/// Every rule on the design's parameters alone (no layout needed). Runs on a file that may not
/// even make a valid [`Design`], so that every problem is reported at once.
pub fn check_parameters(file: &DesignFile) -> Vec<Violation> {
    let mut out = Vec::new();
    dimensions::check(file, &mut out);
    section::check(file, &mut out);
    length::check(file, &mut out);
    pads::check(file, &mut out);
    pads::check_size(file, &mut out);
    if out.is_empty() {
        section::check_geometry(file, &mut out);
    }
    out
}

/// The notch rules and the clearance rules on a layout, with `clearance_mm` edge to edge (for a design,
/// `Fabrication::clearance_mm()`). Works on any layout, generated or read from a DXF.
pub fn check_layout(layout: &Layout, clearance_mm: f64) -> Vec<Violation> {
    let mut out = Vec::new();
    notch_layout::check(layout, &mut out);
    clearance::check(layout, clearance_mm, &mut out);
    out
}

/// Every rule and warning for a design and its layout.
pub fn check(design: &Design, layout: &Layout) -> Report {
    let mut errors = check_parameters(&design.file);
    errors.extend(check_layout(layout, design.file.fabrication.clearance_mm()));
    let mut warnings = Vec::new();
    strain::check(design, &mut warnings);
    Report { errors, warnings }
}

/// The whole pipeline every command runs: parameter rules, the design, its layout, then the
/// layout rules.
///
/// # Errors
/// [`RulesError`] listing every broken rule.
pub fn check_file(file: DesignFile) -> Result<Checked, RulesError> {
    let name = file.name.clone();
    let refuse = |violations| RulesError {
        name: name.clone(),
        violations,
    };
    let errors = check_parameters(&file);
    if !errors.is_empty() {
        return Err(refuse(errors));
    }
    let design = Design::from_file(file).map_err(|e| match e {
        crate::design::DesignError::Geometry { reason, .. } => {
            refuse(vec![Violation::Geometry(reason)])
        }
        crate::design::DesignError::TooManyNotches { count, max, .. } => {
            refuse(vec![Violation::TooMany {
                name: "notch_count",
                value: count,
                max,
            }])
        }
        // from_file only fails on geometry; keep any other reason's text.
        other => refuse(vec![Violation::Other(other.to_string())]),
    })?;
    let layout = Layout::from_design(&design).map_err(|e| refuse(vec![Violation::Layout(e)]))?;
    let warnings = check(&design, &layout).into_result(&name)?;
    Ok(Checked {
        design,
        layout,
        warnings,
    })
}

#[cfg(test)]
mod tests;
