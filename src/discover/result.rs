//! A discovery's result as one [`Analysis`]: the JSON `dlw discover --json` prints (the keys of
//! [`DiscoverySummary`], plus the paths of the files written), the terminal summary, and the report's
//! sections.

use std::fmt::Write as _;
use std::path::PathBuf;

use serde::Serialize;

use super::calibrate::SCREEN_NATS;
use super::{report, scenario_text, DiscoverySummary, Outcome};
use crate::analysis::{Analysis, Placement};
use crate::design::Design;
use crate::recording::Recording;
use crate::report::Page;
use crate::sim::Scenario;

/// Where `dlw discover` wrote its files.
#[derive(Debug, Clone, Serialize)]
pub struct Written {
    /// The discovered scenario (`scenario.toml`).
    pub scenario: PathBuf,
    /// The report (`report.html`).
    pub report: PathBuf,
}

/// What discovery found, with the files it was written to once they are.
#[derive(Debug, Clone, Serialize)]
pub struct DiscoverResult {
    /// The named effects, candidates, ambiguities, unexplained structure and gaps.
    #[serde(flatten)]
    pub summary: DiscoverySummary,
    /// The files written (absent until they are, and in the Python binding).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub written: Option<Written>,
    /// The full outcome, for the report and the scenario.
    #[serde(skip)]
    pub outcome: Outcome,
}

impl DiscoverResult {
    /// The result of `outcome`, not yet written anywhere.
    pub fn new(outcome: Outcome) -> Self {
        Self {
            summary: DiscoverySummary::of(&outcome),
            written: None,
            outcome,
        }
    }

    /// The report page for the recording called `name`.
    pub fn report_page(&self, name: &str) -> Page {
        let mut page = Page::new(format!("Discovery: {name}"));
        self.add_to_page(&mut page, Placement::ALONE);
        page
    }

    /// The text of `scenario.toml` ([`scenario_text`]).
    ///
    /// # Errors
    /// A message naming what failed: building the scenario, serializing it, or its validation.
    pub fn scenario_text(
        &self,
        base: &Scenario,
        recording: &Recording,
        design: &Design,
    ) -> Result<String, String> {
        scenario_text(base, recording, design, &self.outcome)
    }
}

impl Analysis for DiscoverResult {
    fn summary(&self) -> String {
        let o = &self.outcome;
        let mut out = String::new();
        if o.discovered.is_empty() {
            out.push_str("discovered: none\n");
        }
        for d in &o.discovered {
            let _ = writeln!(
                out,
                "discovered {} on {} (evidence {:.1}{})",
                d.effect.name(),
                d.channel.name(),
                d.evidence,
                d.runner_up.map_or(String::new(), |(e, v)| format!(
                    "; runner-up {} {v:.1}",
                    e.name()
                ))
            );
            if let Some(c) = &d.calibration {
                let _ = writeln!(out, "  calibrated: {}", c.sentence());
            }
            for r in &d.rivals {
                let _ = writeln!(out, "  against {}: {}", r.rival.name(), r.sentence());
            }
            if let Some(t) = &d.time {
                let _ = writeln!(out, "  against {}: {}", t.rival_name(), t.sentence());
            }
        }
        for x in &o.declined {
            let why = match (&x.out_of_range, &x.calibration, x.over_richer) {
                (Some(r), ..) => r.sentence(),
                (None, Some(c), Some(richer)) => format!(
                    "{}; but over the richer form of the effect named before it, {richer:.1} \
                     nats, short of the {SCREEN_NATS}-nat screen or of the bound: it explains \
                     that form's misfit",
                    c.sentence()
                ),
                (None, Some(c), None) => c.sentence(),
                (None, None, _) => "not calibrated".to_owned(),
            };
            let _ = writeln!(
                out,
                "not named: {} on {} ({why})",
                x.effect.name(),
                x.channel.name(),
            );
            if let Some(t) = &x.time {
                let _ = writeln!(out, "  against {}: {}", t.rival_name(), t.sentence());
            }
        }
        for a in &o.ambiguous {
            let contenders: Vec<String> = a
                .contenders
                .iter()
                .map(|(e, v)| format!("{} {v:.1}", e.name()))
                .collect();
            let _ = writeln!(
                out,
                "ambiguous on {}: {}",
                a.channel.name(),
                contenders.join(", ")
            );
            for s in &a.separate {
                let _ = writeln!(out, "  to tell them apart: {s}");
            }
        }
        for u in &o.unexplained {
            let _ = writeln!(
                out,
                "unexplained on {}: evidence {:.1} for structure no candidate explains, {}",
                u.channel.name(),
                u.evidence,
                u.place
            );
        }
        for g in &o.gaps {
            let deg = match (g.before_deg, g.after_deg) {
                (Some(b), Some(a)) => format!(" ({b:.3}° → {a:.3}° of estimate)"),
                _ => String::new(),
            };
            let _ = writeln!(
                out,
                "gap {:<8} {:.4} → {:.4} {} on {}{deg}",
                g.channel.name(),
                g.before,
                g.after,
                g.unit,
                g.on
            );
        }
        if let Some(w) = &self.written {
            let _ = writeln!(out, "scenario {}", w.scenario.display());
            let _ = writeln!(out, "report   {}", w.report.display());
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        report::add_sections(page, &self.outcome, at);
    }
}
