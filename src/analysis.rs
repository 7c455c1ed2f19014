//! One interface for every analysis: `fit`, `characterize`, `control`, `discover`, `reproduce`.
//!
//! An analysis's result is a typed struct that
//! - serializes to the JSON its command prints with `--json` (the same keys the Python binding
//!   returns as a dict), so no projection lives in `cli/`;
//! - writes a few lines for the terminal with [`Analysis::summary`], every number in them taken
//!   from the result;
//! - adds its section to an HTML report with [`Analysis::add_to_page`].
//!
//! Implemented by [`crate::fit::FitResult`]; the characterize kinds'
//! [`crate::characterize::LoopsResult`], [`crate::characterize::RateResult`],
//! [`crate::characterize::RelaxationResult`] and [`crate::characterize::EstimationResult`];
//! [`crate::control::ControlResult`]; and [`crate::reproduce::Reproduction`], whose section is
//! the whole report, composed from the others' sections.

use serde::Serialize;

use crate::report::Page;

/// Where an analysis's section lands on a page shared with other sections.
#[derive(Debug, Clone, Copy, Default)]
pub struct Placement<'a> {
    /// Put before the section's headings (for example `Joint A`); empty on a page of its own.
    pub label: &'a str,
    /// Put before the section's figure file names so that sections do not collide (for example
    /// `joint-a-`); empty on a page of its own.
    pub figure_prefix: &'a str,
}

impl<'a> Placement<'a> {
    /// A section on a page of its own.
    pub const ALONE: Placement<'static> = Placement {
        label: "",
        figure_prefix: "",
    };

    /// `title` with the label in front (`Joint D: Setup`), or `title` alone.
    pub fn titled(&self, title: &str) -> String {
        if self.label.is_empty() {
            title.to_owned()
        } else {
            format!("{}: {title}", self.label)
        }
    }

    /// The figure file stem `name` with the prefix in front (`d-control-stroke`), or `name`
    /// alone.
    pub fn figure_name(&self, name: &str) -> String {
        if self.figure_prefix.is_empty() {
            name.to_owned()
        } else {
            format!("{}-{name}", self.figure_prefix)
        }
    }
}

/// A result of an analysis: its JSON, its summary, its report section.
pub trait Analysis: Serialize {
    /// A few lines for the terminal: the headline numbers and what they say, computed from the
    /// result (never fixed prose with numbers in it).
    fn summary(&self) -> String;

    /// Adds the analysis's headings, text, tables and figures to `page`.
    fn add_to_page(&self, page: &mut Page, at: Placement<'_>);

    /// The JSON that the command's `--json` prints.
    ///
    /// # Errors
    /// When a number is not finite (`serde_json` writes it as `null`): the caller reports that
    /// instead of printing a partial document.
    fn to_json(&self) -> Result<serde_json::Value, serde_json::Error> {
        serde_json::to_value(self)
    }
}
