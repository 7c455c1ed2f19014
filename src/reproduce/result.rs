//! A reproduction as one [`Analysis`]: the numbers `dlw reproduce --json` prints, the terminal
//! summary, and the report.

use std::fmt::Write as _;
use std::path::Path;

use serde::{Serialize, Serializer};

use super::{agreement, patterns, report, Reproduction};
use crate::analysis::{Analysis, Placement};
use crate::characterize::EstimationRun;
use crate::control::SchemeMetrics;
use crate::fit::Characteristic;
use crate::report::{Page, PAGE_FILE};

/// What `dlw reproduce --json` prints; the keys are part of the interface.
#[derive(Serialize)]
struct Json<'a> {
    duration_scale: f64,
    bench: &'static str,
    seed: u64,
    patterns: Vec<patterns::Pattern>,
    agreement: AgreementJson,
    /// The calibration's parameters, each with its move from the ideal bench (empty for the
    /// ideal bench).
    moved: Vec<agreement::Moved>,
    seconds: f64,
    joints: Vec<JointNumbers<'a>>,
    control_open_loop: SchemeMetrics,
    control_closed_loop: SchemeMetrics,
    #[serde(skip_serializing_if = "Option::is_none")]
    report: Option<&'a Path>,
}

/// Every checked number against the paper's, the names of those outside, and the finding.
#[derive(Serialize)]
struct AgreementJson {
    checks: Vec<agreement::Check>,
    outside: Vec<String>,
    finding: String,
}

impl Reproduction {
    /// The run's numbers against the paper's, each with its limit ([`agreement::checks`]).
    pub fn checks(&self) -> Vec<agreement::Check> {
        agreement::checks(self)
    }

    /// The sentence on the numbers outside their agreement ([`agreement::finding`]), with the
    /// bench file's measured trade-offs.
    pub fn finding(&self) -> String {
        let explain = if self.settings.duration_scale == 1.0 {
            agreement::Explain::FullSize
        } else {
            agreement::Explain::Shorter
        };
        agreement::finding_at(&self.checks(), self.tradeoffs(), explain)
    }

    /// The trade-offs the bench file records (none for the ideal bench).
    pub fn tradeoffs(&self) -> &[super::Tradeoff] {
        match &self.settings.bench {
            super::Bench::Twin(file) => file
                .calibration
                .as_ref()
                .map_or(&[], |c| c.tradeoffs.as_slice()),
            super::Bench::Ideal => &[],
        }
    }
}

/// One of Joints A-C: its sensor 1's fit, rate and relaxation numbers, and every estimation run.
#[derive(Serialize)]
struct JointNumbers<'a> {
    joint: char,
    gauge_factor: f64,
    r0_ohm: f64,
    /// r² of each sensor's line on the characterization, sensor 1 first (the paper's Table V
    /// gives Joint C's: 0.888 and 0.892).
    line_r2: Vec<f64>,
    characteristic: Option<Characteristic>,
    gf_rise_correlation: f64,
    r0_std_ohm: f64,
    relaxation_correlation: f64,
    relaxation_median_tau_s: Option<f64>,
    estimation: &'a [EstimationRun],
}

impl Serialize for Reproduction {
    /// The tables' numbers, not every trace.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let [open, closed] = self.control.run.metrics;
        let checks = self.checks();
        Json {
            duration_scale: self.settings.duration_scale,
            bench: self.settings.bench.name(),
            seed: self.settings.seed,
            patterns: patterns::patterns(self),
            agreement: AgreementJson {
                outside: checks
                    .iter()
                    .filter(|c| c.outside)
                    .map(|c| c.name.clone())
                    .collect(),
                finding: self.finding(),
                checks,
            },
            moved: agreement::moved(&self.settings.bench),
            seconds: self.seconds,
            joints: self
                .joints
                .iter()
                .map(|j| {
                    let l = &j.loops.sensors[0].summary;
                    JointNumbers {
                        joint: j.letter,
                        gauge_factor: l.gauge_factor,
                        r0_ohm: l.r0_ohm,
                        line_r2: j.loops.sensors.iter().map(|s| s.summary.r2).collect(),
                        characteristic: l.characteristic,
                        gf_rise_correlation: j.rate.sensors[0].gf_rise_correlation,
                        r0_std_ohm: j.rate.sensors[0].r0_std_ohm,
                        relaxation_correlation: j.relaxation.sensors[0].correlation,
                        relaxation_median_tau_s: j.relaxation.sensors[0].median_tau_s,
                        estimation: &j.estimation.runs,
                    }
                })
                .collect(),
            control_open_loop: open,
            control_closed_loop: closed,
            report: self.report.as_deref(),
        }
        .serialize(serializer)
    }
}

impl Reproduction {
    /// Records that the [`report::page`] was written into `dir`.
    pub fn written_to(&mut self, dir: &Path) {
        self.report = Some(dir.join(PAGE_FILE));
    }
}

impl Analysis for Reproduction {
    /// Per joint its fit, rate, relaxation and estimation numbers; Joint D's Table VI; every
    /// pattern held or not, and their tally; the report and the time taken.
    fn summary(&self) -> String {
        let mut out = String::new();
        for j in &self.joints {
            let l = &j.loops.sensors[0].summary;
            let est = |name: &str| {
                j.estimation
                    .runs
                    .iter()
                    .find(|x| x.config == name && !x.split)
                    .map_or(f64::NAN, |x| x.metrics.rmse_deg)
            };
            let _ = writeln!(
                out,
                "Joint {}: GF {:.2}, R0 {:.1} kΩ; corr(GF, rise) {:.4}, std R0 {:.3} kΩ; relaxation corr {:.3}; RMSE linear {:.2}°, PI {:.2}°",
                j.letter,
                l.gauge_factor,
                l.r0_ohm / 1e3,
                j.rate.sensors[0].gf_rise_correlation,
                j.rate.sensors[0].r0_std_ohm / 1e3,
                j.relaxation.sensors[0].correlation,
                est("linear"),
                est("PI")
            );
        }
        let [o, c] = self.control.run.metrics.map(|m| m.table_vi());
        let _ = writeln!(
            out,
            "Joint D control RMSE (°): open loop {:.2} / {:.2} / {:.2}, closed loop {:.2} / {:.2} / {:.2} (sensed-actual / actual-desired / sensed-desired)",
            o[0], o[1], o[2], c[0], c[1], c[2]
        );
        let list = patterns::patterns(self);
        for p in &list {
            let _ = writeln!(
                out,
                "pattern {}: {} (paper: {}; dlw: {})",
                p.verdict(),
                p.name,
                p.paper,
                p.dlw
            );
            if let Some(why) = &p.cannot_show {
                let _ = writeln!(out, "  why: {why}");
            }
        }
        let _ = writeln!(out, "{}", patterns::tally(&list));
        let _ = writeln!(out, "{}", self.finding());
        let moved = agreement::moved(&self.settings.bench);
        if !moved.is_empty() {
            let _ = writeln!(out, "{}", agreement::moved_text(&moved));
        }
        match &self.report {
            Some(report) => {
                let _ = writeln!(out, "report {} ({:.1} s)", report.display(), self.seconds);
            }
            None => {
                let _ = writeln!(out, "ran in {:.1} s", self.seconds);
            }
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: Placement<'_>) {
        report::add_sections(page, self, at);
    }
}
