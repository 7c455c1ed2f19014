//! A calibration's result: the parameters moved (ideal → calibrated, and how far), every
//! target short-sized and at full size against the paper's, Table III's agreements, and, for a
//! target the bounds do not let the twin reach, what the paper's bench must have had. Every
//! sentence is built from these numbers.

use std::fmt::Write as _;

use serde::Serialize;

use super::{Calibration, Evaluation, Metric, Space, HELD};
use crate::reproduce::BenchFile;

/// A parameter, ideal and calibrated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterRow {
    /// Its name.
    pub name: String,
    /// The ideal bench's value.
    pub ideal: f64,
    /// The calibrated value.
    pub calibrated: f64,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
    /// How far it moved, as a share of its range (−1 … 1).
    pub moved_share: f64,
    /// `lower`/`upper` when it ended within 2 % of a bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_bound: Option<&'static str>,
}

/// A target: the paper's value, the twin's short-sized and full-size values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetRow {
    /// `table4.A.pi`, ….
    pub name: String,
    /// The paper's.
    pub paper: f64,
    /// The ideal bench at full size.
    pub ideal: Option<f64>,
    /// The twin, short-sized, at the shipped point.
    pub short: Option<f64>,
    /// The twin at full size.
    pub full: Option<f64>,
    /// Whether the full-size value is within the tolerance.
    pub met: bool,
    /// For a target not met: why, and what the paper's bench must have had (computed from the
    /// surrogate's slopes at the bounds).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finding: Option<String>,
}

/// A Table III number: paper, ideal bench and twin at full size, allowed distance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AgreementRow {
    /// `table3.A.GF`, ….
    pub name: String,
    /// The paper's.
    pub paper: f64,
    /// The ideal bench's.
    pub ideal: Option<f64>,
    /// The twin's.
    pub twin: Option<f64>,
    /// The largest relative distance allowed.
    pub max_relative: f64,
    /// Whether the twin keeps it.
    pub kept: bool,
}

/// What `dlw calibrate` reports and writes as `calibration.json`.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrationResult {
    /// Short-sized evaluations made.
    pub evaluations: usize,
    /// Full-size runs made (the ideal bench's and the checks).
    pub full_runs: usize,
    /// The parameters.
    pub parameters: Vec<ParameterRow>,
    /// The parameters held, with why.
    pub held: Vec<super::Held>,
    /// The targets.
    pub targets: Vec<TargetRow>,
    /// Table III.
    pub agreements: Vec<AgreementRow>,
    /// Joint C's line-over-PI residual ratio at full size (the patterns read it; below 2 the
    /// run can show which model estimates it better).
    pub residual_ratio_c: Option<f64>,
    /// Seconds the calibration took.
    pub seconds: f64,
    /// The bench file.
    #[serde(skip)]
    pub bench: BenchFile,
}

impl CalibrationResult {
    /// The result of `c`, shipping the full-size evaluation `full`.
    pub fn new(c: &Calibration, full: &Evaluation, seconds: f64) -> Self {
        let all = Metric::all();
        let index = |m: Metric| all.iter().position(|x| *x == m);
        let short = c
            .evaluations
            .iter()
            .find(|e| e.u == full.u)
            .map(|e| e.values.clone());
        let models = c.surrogates();
        let targets = c
            .targets
            .iter()
            .map(|t| {
                let k = index(t.metric);
                let value = k.and_then(|k| full.values[k]);
                let met = value.is_some_and(|v| t.met(v));
                TargetRow {
                    name: t.metric.name(),
                    paper: t.paper,
                    ideal: k.and_then(|k| c.ideal_full[k]),
                    short: k.and_then(|k| short.as_ref().and_then(|s| s[k])),
                    full: value,
                    met,
                    finding: match (met, value, k) {
                        (false, Some(v), Some(k)) => models[k]
                            .as_ref()
                            .map(|m| finding(&c.space, m, &full.u, v, t.paper, t.tolerance)),
                        _ => None,
                    },
                }
            })
            .collect();
        let agreements = c
            .agreements
            .iter()
            .map(|a| {
                let k = index(a.metric);
                let twin = k.and_then(|k| full.values[k]);
                AgreementRow {
                    name: a.metric.name(),
                    paper: a.paper,
                    ideal: k.and_then(|k| c.ideal_full[k]),
                    twin,
                    max_relative: a.max_relative,
                    kept: twin.is_some_and(|v| a.kept(v)),
                }
            })
            .collect();
        let parameters = c
            .space
            .parameters
            .iter()
            .zip(&full.u)
            .map(|(p, &u)| ParameterRow {
                name: p.name(),
                ideal: p.ideal,
                calibrated: p.value(u),
                lo: p.lo,
                hi: p.hi,
                moved_share: u - p.unit(p.ideal),
                at_bound: if u < 0.02 && p.lo != p.ideal {
                    Some("lower")
                } else if u > 0.98 {
                    Some("upper")
                } else {
                    None
                },
            })
            .collect();
        Self {
            evaluations: c.evaluations.len(),
            full_runs: 1 + c.full.len(),
            parameters,
            held: HELD.to_vec(),
            targets,
            agreements,
            residual_ratio_c: index(Metric::LineOverPiResidual { joint: 'C' })
                .and_then(|k| full.values[k]),
            seconds,
            bench: c.bench_file(full),
        }
    }

    /// The terminal text: every target, parameter and agreement, and the findings.
    pub fn summary(&self) -> String {
        let mut out = String::new();
        let met = self.targets.iter().filter(|t| t.met).count();
        let _ = writeln!(
            out,
            "{met} of {} targets within their tolerance at full size; {} short-sized \
             evaluations and {} full-size runs in {:.0} s",
            self.targets.len(),
            self.evaluations,
            self.full_runs,
            self.seconds
        );
        let f = |x: Option<f64>| x.map_or("–".to_owned(), |v| format!("{v:.2}"));
        for t in &self.targets {
            let _ = writeln!(
                out,
                "target {}: paper {:.2}, ideal {}, twin short {} full {} ({})",
                t.name,
                t.paper,
                f(t.ideal),
                f(t.short),
                f(t.full),
                if t.met { "met" } else { "NOT met" }
            );
            if let Some(why) = &t.finding {
                let _ = writeln!(out, "  {why}");
            }
        }
        for p in &self.parameters {
            let _ = writeln!(
                out,
                "parameter {}: {} -> {} (range {} to {}; moved {:+.0} % of it){}",
                p.name,
                p.ideal,
                significant(p.calibrated),
                p.lo,
                p.hi,
                100.0 * p.moved_share,
                p.at_bound
                    .map_or(String::new(), |b| format!(", at its {b} bound"))
            );
        }
        let kept = self.agreements.iter().filter(|a| a.kept).count();
        let _ = writeln!(
            out,
            "Table III: {kept} of {} numbers within their current agreement",
            self.agreements.len()
        );
        for a in self.agreements.iter().filter(|a| !a.kept) {
            let _ = writeln!(
                out,
                "  {}: paper {}, ideal {}, twin {} (allowed {:.0} % off)",
                a.name,
                significant(a.paper),
                a.ideal.map_or("–".into(), significant),
                a.twin.map_or("–".into(), significant),
                100.0 * a.max_relative
            );
        }
        out
    }
}

fn significant(x: f64) -> String {
    format!("{:.4}", x)
        .trim_end_matches('0')
        .trim_end_matches('.')
        .to_owned()
}

/// Why a target is out of reach, from the surrogate at the shipped point: which parameters at
/// a bound would move it the needed way, and how far past the bound the surrogate says each
/// alone would have to go.
fn finding(
    space: &Space,
    model: &super::Quadratic,
    u: &[f64],
    value: f64,
    paper: f64,
    tolerance: f64,
) -> String {
    let needed = (paper / value).ln();
    let direction = if needed > 0.0 { "higher" } else { "lower" };
    let mut pushes = Vec::new();
    for (i, p) in space.parameters.iter().enumerate() {
        let slope = model.log_slope(u, i);
        let at_top = u[i] > 0.98;
        let at_bottom = u[i] < 0.02;
        // A parameter at a bound can help only by leaving the box in the direction that moves
        // the metric the needed way.
        let helps = (at_top && slope * needed > 0.0) || (at_bottom && slope * needed < 0.0);
        if helps && slope.abs() > 1e-3 {
            let du = (needed.abs() - (1.0 + tolerance).ln()).max(0.0) / slope.abs();
            let beyond = if at_top { 1.0 + du } else { -du };
            pushes.push(format!(
                "{} at its {} bound {} (the surrogate: {} needs about {})",
                p.name(),
                if at_top { "upper" } else { "lower" },
                significant(if at_top { p.hi } else { p.lo }),
                direction,
                significant(extrapolate(p, beyond))
            ));
        }
    }
    let head = format!(
        "{} is {:.0} % of the paper's {}: it needs to be {direction}",
        significant(value),
        100.0 * value / paper,
        significant(paper)
    );
    if pushes.is_empty() {
        format!(
            "{head}; no parameter at a bound moves it that way on the surrogate, so the other \
             targets and side conditions hold it here"
        )
    } else {
        format!("{head}; {}", pushes.join("; "))
    }
}

fn extrapolate(p: &super::Parameter, u: f64) -> f64 {
    if p.log {
        p.lo * (p.hi / p.lo).powf(u)
    } else {
        p.lo + (p.hi - p.lo) * u
    }
}
