//! The run's numbers against the paper's, each with its limit: Tables IV-VI's ten headline
//! numbers within [`HEADLINE_TOLERANCE`] of the paper's, and, where the bench file records
//! them, Table III's numbers within the distance its calibration allowed. For a number outside,
//! [`finding`] says by how much and, from the trade-offs the bench file records as measured,
//! why the bench cannot bring it in and what the paper's bench must have had instead. What the
//! calibration moved comes from the same file ([`moved`]). Every sentence is built from these
//! numbers.

use serde::Serialize;

use super::paper::{table_iii_as_read, TABLE_IV, TWO_SENSOR_RMSE};
use super::patterns::{rmse, COMPRESSION, ONE};
use super::twin::Tradeoff;
use super::{Bench, Reproduction};
use crate::control::PAPER_TABLE_VI;
use crate::sensor::Sensors;

/// The agreement for Tables IV-VI: within 25 % of the paper's value.
pub const HEADLINE_TOLERANCE: f64 = 0.25;

/// Table III's rows as checks name them (`table3.A.m_c`), in the table's order.
pub const TABLE3_ROWS: [&str; 7] = ["GF", "R0", "R_c", "eps_c", "m_c", "R_peak", "eps_peak"];

/// How a checked number is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Unit {
    /// An angle RMSE (°).
    Deg,
    /// A gauge factor (no unit).
    Plain,
    /// A resistance (Ω), shown in kΩ.
    Ohm,
    /// A slope (Ω per unit strain), shown in MΩ.
    OhmPerStrain,
    /// A strain (fraction), shown in %.
    Strain,
}

impl Unit {
    fn show(self, v: f64) -> String {
        match self {
            Self::Deg => format!("{v:.2}°"),
            Self::Plain => format!("{v:.3}"),
            Self::Ohm => format!("{:.1} kΩ", v / 1e3),
            Self::OhmPerStrain => format!("{:.2} MΩ", v / 1e6),
            Self::Strain => format!("{:.3} %", v * 100.0),
        }
    }
}

/// One of the run's numbers against the paper's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// `table4.A.pi`, `table5.both`, `table6.closed`, `table3.A.m_c` (the calibration's names).
    pub name: String,
    /// What it is, in words: `Joint A's PI estimation error (Table IV)`.
    pub what: String,
    /// How it is shown.
    pub unit: Unit,
    /// The paper's value.
    pub paper: f64,
    /// The run's (`None`: the run did not give it).
    pub dlw: Option<f64>,
    /// `dlw / paper − 1`.
    pub relative: Option<f64>,
    /// The largest |relative| that agrees.
    pub limit: f64,
    /// Whether the run's number is outside its limit (or missing).
    pub outside: bool,
}

impl Check {
    /// A check of `dlw` against `paper` within `limit` (relative).
    pub fn new(
        name: String,
        what: String,
        unit: Unit,
        paper: f64,
        dlw: Option<f64>,
        limit: f64,
    ) -> Self {
        let dlw = dlw.filter(|v| v.is_finite());
        let relative = dlw.map(|v| v / paper - 1.0);
        Self {
            name,
            what,
            unit,
            paper,
            dlw,
            relative,
            limit,
            outside: !relative.is_some_and(|r| r.abs() <= limit),
        }
    }

    /// Whether `v` keeps this number's limit.
    fn within(&self, v: f64) -> bool {
        (v / self.paper - 1.0).abs() <= self.limit
    }

    /// `v` in this number's unit.
    pub fn show(&self, v: f64) -> String {
        self.unit.show(v)
    }

    /// The band that agrees, `lo–hi`.
    fn band(&self) -> String {
        format!(
            "{} to {}",
            self.show(self.paper * (1.0 - self.limit)),
            self.show(self.paper * (1.0 + self.limit))
        )
    }
}

/// Tables IV-VI's ten numbers, each against the paper's within [`HEADLINE_TOLERANCE`]; then
/// Table III's of Joints A-C whose allowed distance the bench file records.
pub fn checks(r: &Reproduction) -> Vec<Check> {
    let mut out = Vec::new();
    let headline = |name: String, what: String, paper: f64, dlw: Option<f64>| {
        Check::new(name, what, Unit::Deg, paper, dlw, HEADLINE_TOLERANCE)
    };
    for (i, letter) in ['A', 'B', 'C'].into_iter().enumerate() {
        for (m, (key, config)) in [("linear", "linear"), ("pi", "PI")].into_iter().enumerate() {
            out.push(headline(
                format!("table4.{letter}.{key}"),
                format!("Joint {letter}'s {config} estimation error (Table IV)"),
                TABLE_IV[i][m],
                rmse(r, letter, config, ONE),
            ));
        }
    }
    let two = "linear, two-sensor config";
    out.push(headline(
        "table5.compression".into(),
        "Joint C's compression-sensor error (Table V)".into(),
        TWO_SENSOR_RMSE[1],
        rmse(r, 'C', two, COMPRESSION),
    ));
    out.push(headline(
        "table5.both".into(),
        "Joint C's two-sensor error (Table V)".into(),
        TWO_SENSOR_RMSE[2],
        rmse(r, 'C', two, Sensors::Both),
    ));
    for (k, (key, scheme)) in [("open", "open"), ("closed", "closed")]
        .into_iter()
        .enumerate()
    {
        out.push(headline(
            format!("table6.{key}"),
            format!("Joint D's {scheme}-loop actual-vs-desired error (Table VI)"),
            [PAPER_TABLE_VI[0].1, PAPER_TABLE_VI[1].1][k],
            Some(r.control.run.metrics[k].actual_vs_desired_rmse_deg),
        ));
    }
    let Bench::Twin(file) = &r.settings.bench else {
        return out;
    };
    let Some(agreements) = file.calibration.as_ref().map(|c| &c.agreements) else {
        return out;
    };
    for (i, j) in r.joints.iter().enumerate() {
        let s = &j.loops.sensors[0].summary;
        let c = s.characteristic.as_ref();
        let rows: [(Option<f64>, Unit, &str); 7] = [
            (Some(s.gauge_factor), Unit::Plain, "line's gauge factor"),
            (Some(s.r0_ohm), Unit::Ohm, "line's R₀"),
            (c.map(|c| c.center_ohm), Unit::Ohm, "loop's centre R_c"),
            (
                c.map(|c| c.center_strain),
                Unit::Strain,
                "loop's centre ε_c",
            ),
            (
                c.map(|c| c.center_slope_ohm),
                Unit::OhmPerStrain,
                "loop's steepest slope m_c",
            ),
            (c.map(|c| c.peak_ohm), Unit::Ohm, "loop's peak R_peak"),
            (c.map(|c| c.peak_strain), Unit::Strain, "loop's peak ε_peak"),
        ];
        let papers = table_iii_as_read(i);
        for ((row, paper), (dlw, unit, what)) in TABLE3_ROWS.iter().zip(papers).zip(rows) {
            let name = format!("table3.{}.{row}", j.letter);
            if let Some(&limit) = agreements.get(&name) {
                let what = format!("Joint {}'s {what} (Table III)", j.letter);
                out.push(Check::new(name, what, unit, paper, dlw, limit));
            }
        }
    }
    out
}

/// The numbers outside their limit, each with how far, and why: for each, the bench file's
/// measured trade-offs that move it. Where every measured point that brings it within its limit
/// puts another checked number outside its own, the sentence says so and names the error the
/// paper's bench must have had: one that sets the other number without moving this one.
/// With every number within, it says that.
pub fn finding(checks: &[Check], tradeoffs: &[Tradeoff]) -> String {
    finding_at(checks, tradeoffs, Explain::FullSize)
}

/// Whether a run may be explained by the bench file's trade-offs, which were measured at the
/// paper's full durations.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Explain {
    /// A full-size run: the trade-offs apply.
    FullSize,
    /// A shorter run: its numbers differ from full size's, so the trade-offs do not explain them.
    Shorter,
}

/// [`finding`] for a run of the given size: a shorter run's numbers outside are named, and no
/// reason is given from trade-offs measured at full size.
pub fn finding_at(checks: &[Check], tradeoffs: &[Tradeoff], explain: Explain) -> String {
    let outside: Vec<&Check> = checks.iter().filter(|c| c.outside).collect();
    if outside.is_empty() {
        return format!(
            "All {} checked numbers are within their agreement with the paper.",
            checks.len()
        );
    }
    let mut text = format!(
        "{} of {} checked numbers are outside their agreement with the paper.",
        outside.len(),
        checks.len()
    );
    // One paragraph per number: a reader (and the report, which splits on them) finds each.
    for c in outside {
        text += PARAGRAPH;
        text += &one_finding(c, checks, tradeoffs, explain);
    }
    text
}

/// What separates the finding's paragraphs: the count, then one per number outside.
pub const PARAGRAPH: &str = "\n\n";

fn one_finding(c: &Check, checks: &[Check], tradeoffs: &[Tradeoff], explain: Explain) -> String {
    let (Some(v), Some(rel)) = (c.dlw, c.relative) else {
        return format!("{}: the run gave no value.", capitalized(&c.what));
    };
    let mut reading = Reading {
        text: format!(
            "{} is {}, {:.1} % {} the paper's {}; its limit is {:.1} % ({}), so it is {:.1} \
             points outside.",
            capitalized(&c.what),
            c.show(v),
            100.0 * rel.abs(),
            if rel > 0.0 { "above" } else { "below" },
            c.show(c.paper),
            100.0 * c.limit,
            c.band(),
            100.0 * (rel.abs() - c.limit)
        ),
        blocked_everywhere: true,
        blockers: Vec::new(),
    };
    let relevant: Vec<&Tradeoff> = tradeoffs
        .iter()
        .filter(|t| t.metrics.contains_key(&c.name))
        .collect();
    if explain == Explain::Shorter {
        reading.text += " The limits and the bench file's trade-offs are for the paper's full \
             durations and this run is shorter, so it does not say why.";
        return reading.text;
    }
    if relevant.is_empty() {
        reading.text +=
            " No trade-off the bench file records moves it, so this run cannot say why.";
        return reading.text;
    }
    for t in relevant {
        reading.read(c, t, checks);
    }
    if reading.blocked_everywhere {
        reading.text += &reading.conclusion(c, rel);
    }
    reading.text
}

/// What the trade-offs say of one number outside its limit, read one trade-off at a time.
struct Reading<'a> {
    /// The sentences so far.
    text: String,
    /// Whether every measured point that brings the number within its limit put another
    /// checked number outside its own.
    blocked_everywhere: bool,
    /// Each number that blocked a point, with its values at those points.
    blockers: Vec<(&'a Check, Vec<f64>)>,
}

impl<'a> Reading<'a> {
    /// The trade-off `t`'s series, and what happens where it brings `c` within its limit.
    fn read(&mut self, c: &Check, t: &Tradeoff, checks: &'a [Check]) {
        let partners: Vec<(&'a Check, &Vec<f64>)> = t
            .metrics
            .iter()
            .filter(|(name, _)| **name != c.name)
            .filter_map(|(name, vs)| Some((checks.iter().find(|x| x.name == *name)?, vs)))
            .collect();
        let mine = &t.metrics[&c.name];
        let series = |x: &Check, vs: &[f64]| {
            let shown: Vec<String> = vs.iter().map(|v| x.show(*v)).collect();
            format!("{} {}", x.name, shown.join(", "))
        };
        let all: Vec<String> = std::iter::once(series(c, mine))
            .chain(partners.iter().map(|(p, vs)| series(p, vs)))
            .collect();
        let values: Vec<String> = t.values.iter().map(|x| format!("{x}")).collect();
        self.text += &format!(
            " Measured with {} at {} ({}): {}.",
            t.parameter,
            values.join(", "),
            t.measured,
            all.join("; ")
        );
        let within: Vec<usize> = (0..mine.len()).filter(|&k| c.within(mine[k])).collect();
        if within.is_empty() {
            let distance = |k: usize| (mine[k] / c.paper).ln().abs();
            let nearest = (0..mine.len())
                .min_by(|&a, &b| distance(a).total_cmp(&distance(b)))
                .map(|k| format!(" (nearest: {} at {})", c.show(mine[k]), t.values[k]));
            self.text += &format!(
                " No value of {} brings {} within its limit{}.",
                t.parameter,
                c.name,
                nearest.unwrap_or_default()
            );
            return;
        }
        for k in within {
            let out: Vec<(&'a Check, f64)> = partners
                .iter()
                .filter_map(|(p, vs)| vs.get(k).filter(|x| !p.within(**x)).map(|x| (*p, *x)))
                .collect();
            if out.is_empty() {
                self.blocked_everywhere = false;
                self.text += &format!(
                    " At {} = {} {} is within its limit and every other measured number within \
                     its own: the bench could be moved there.",
                    t.parameter, t.values[k], c.name
                );
                continue;
            }
            let outside: Vec<String> = out
                .iter()
                .map(|(p, x)| format!("{} is {}, outside its {}", p.name, p.show(*x), p.band()))
                .collect();
            self.text += &format!(
                " At {} = {}, where {} is within its limit ({}), {}.",
                t.parameter,
                t.values[k],
                c.name,
                c.show(mine[k]),
                outside.join(" and ")
            );
            for (p, x) in out {
                match self.blockers.iter_mut().find(|(b, _)| b.name == p.name) {
                    Some((_, xs)) => xs.push(x),
                    None => self.blockers.push((p, vec![x])),
                }
            }
        }
    }

    /// What the paper's bench must have had, when no measured point keeps every number: an
    /// error that moves each blocking number the way it missed, without moving `c` the way it
    /// is off (`rel`).
    fn conclusion(&self, c: &Check, rel: f64) -> String {
        let must: Vec<String> = self
            .blockers
            .iter()
            .map(|(p, xs)| {
                let verb = if xs.iter().all(|x| *x < p.paper) {
                    "raises"
                } else if xs.iter().all(|x| *x > p.paper) {
                    "lowers"
                } else {
                    "sets"
                };
                format!("{verb} {} to the paper's {}", p.what, p.show(p.paper))
            })
            .collect();
        if must.is_empty() {
            return format!(
                " So no measured value brings {} within its limit: the paper's bench must have \
                 had an error this bench does not model, one that does not {} it.",
                c.what,
                if rel > 0.0 { "raise" } else { "lower" }
            );
        }
        format!(
            " So this bench cannot bring {} within its limit without moving another number out \
             of its own: the paper's bench must have had an error that {} without {} {}.",
            c.what,
            must.join(" and "),
            if rel > 0.0 { "raising" } else { "lowering" },
            c.what
        )
    }
}

fn capitalized(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map(|f| f.to_uppercase().collect::<String>() + c.as_str())
        .unwrap_or_default()
}

/// A calibrated parameter's move from the ideal bench.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Moved {
    /// Its calibration name.
    pub name: String,
    /// The ideal bench's value (`None`: the file does not record it).
    pub ideal: Option<f64>,
    /// The bench file's value.
    pub twin: f64,
    /// The bounds searched.
    pub bounds: Option<[f64; 2]>,
    /// How far it moved, as a share of its range (of `ln(hi/lo)` for a log-scale one).
    pub moved_share: Option<f64>,
}

/// Every parameter the bench file's calibration set, with its move from the ideal bench, the
/// largest move first; empty for the ideal bench or a file that records no calibration.
pub fn moved(bench: &Bench) -> Vec<Moved> {
    let Bench::Twin(file) = bench else {
        return Vec::new();
    };
    let Some(cal) = &file.calibration else {
        return Vec::new();
    };
    let mut out: Vec<Moved> = cal
        .parameters
        .iter()
        .map(|(name, &twin)| {
            let range = cal.ranges.get(name);
            Moved {
                name: name.clone(),
                ideal: range.map(|r| r.ideal),
                twin,
                bounds: range.map(|r| [r.lo, r.hi]),
                moved_share: range
                    .filter(|r| r.hi > r.lo)
                    .map(|r| r.unit(twin) - r.unit(r.ideal)),
            }
        })
        .collect();
    out.sort_by(|a, b| {
        let m = |x: &Moved| x.moved_share.map_or(f64::INFINITY, f64::abs);
        m(b).total_cmp(&m(a))
    });
    out
}

/// A parameter's move counts as one when it is at least this share of its range (a value
/// written with the calibration's rounding stays put).
const MOVED_SHARE: f64 = 1e-6;

/// `x` with at most four decimals and no trailing zeros.
pub fn show_value(x: f64) -> String {
    let s = format!("{x:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_owned()
}

/// The parameters that moved and those that stayed at the ideal bench's value.
pub fn split_moved(moved: &[Moved]) -> (Vec<&Moved>, Vec<&Moved>) {
    moved
        .iter()
        .partition(|m| !m.moved_share.is_some_and(|s| s.abs() < MOVED_SHARE))
}

/// The sentence on [`moved`]: how many moved, each with ideal → calibrated and the share of
/// its range, and which stayed.
pub fn moved_text(moved: &[Moved]) -> String {
    let (went, stayed) = split_moved(moved);
    let went: Vec<String> = went
        .iter()
        .map(|m| match (m.ideal, m.moved_share) {
            (Some(ideal), Some(share)) => format!(
                "{} {} → {} ({:+.0} % of its range)",
                m.name,
                show_value(ideal),
                show_value(m.twin),
                100.0 * share
            ),
            _ => format!(
                "{} = {} (its ideal value is not recorded)",
                m.name,
                show_value(m.twin)
            ),
        })
        .collect();
    let mut text = format!(
        "The calibration moved {} of {} parameters from the ideal bench, the largest move \
         first: {}.",
        went.len(),
        moved.len(),
        went.join("; ")
    );
    if !stayed.is_empty() {
        text += &format!(" At the ideal bench's value: {}.", names(&stayed));
    }
    text
}

/// The parameters' names, comma-separated.
pub fn names(moved: &[&Moved]) -> String {
    moved
        .iter()
        .map(|m| m.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    fn check(name: &str, what: &str, unit: Unit, paper: f64, dlw: f64, limit: f64) -> Check {
        Check::new(name.into(), what.into(), unit, paper, Some(dlw), limit)
    }

    /// The shipped twin's situation, in constructed numbers: m_c outside its limit; the noise
    /// that would bring it in puts the PI error outside its band.
    fn twin_like(m_c: f64) -> (Vec<Check>, Vec<Tradeoff>) {
        let checks = vec![
            check(
                "table4.A.pi",
                "Joint A's PI estimation error (Table IV)",
                Unit::Deg,
                1.76,
                1.78,
                0.25,
            ),
            check(
                "table3.A.m_c",
                "Joint A's loop's steepest slope m_c (Table III)",
                Unit::OhmPerStrain,
                5.136e6,
                m_c,
                0.139,
            ),
        ];
        let tradeoffs = vec![Tradeoff {
            parameter: "A.sensor1.noise_ppm".into(),
            measured: "constructed".into(),
            values: vec![0.0, 2500.0, 5100.0],
            metrics: BTreeMap::from([
                ("table3.A.m_c".to_owned(), vec![4.68e6, 5.5e6, m_c]),
                ("table4.A.pi".to_owned(), vec![0.47, 1.0, 1.78]),
            ]),
        }];
        (checks, tradeoffs)
    }

    #[test]
    fn a_number_outside_is_named_with_its_distance_and_the_benchs_missing_error() {
        let (checks, tradeoffs) = twin_like(6.5e6);
        let f = finding(&checks, &tradeoffs);
        assert!(f.starts_with("1 of 2 checked numbers are outside"), "{f}");
        assert!(
            f.contains("Joint A's loop's steepest slope m_c (Table III) is 6.50 MΩ, 26.6 % above the paper's 5.14 MΩ; its limit is 13.9 %"),
            "{f}"
        );
        assert!(f.contains("so it is 12.7 points outside"), "{f}");
        assert!(
            f.contains("At A.sensor1.noise_ppm = 0, where table3.A.m_c is within its limit (4.68 MΩ), table4.A.pi is 0.47°, outside its 1.32° to 2.20°"),
            "{f}"
        );
        assert!(
            f.contains("must have had an error that raises Joint A's PI estimation error (Table IV) to the paper's 1.76° without raising Joint A's loop's steepest slope m_c (Table III)"),
            "{f}"
        );
    }

    #[test]
    fn all_within_says_so_and_names_nothing() {
        let (checks, tradeoffs) = twin_like(5.5e6);
        let f = finding(&checks, &tradeoffs);
        assert_eq!(
            f,
            "All 2 checked numbers are within their agreement with the paper."
        );
    }

    #[test]
    fn a_measured_point_that_keeps_both_is_not_called_unreachable() {
        let (checks, mut tradeoffs) = twin_like(6.5e6);
        tradeoffs[0].metrics.get_mut("table4.A.pi").unwrap()[1] = 1.7;
        let f = finding(&checks, &tradeoffs);
        assert!(f.contains("the bench could be moved there"), "{f}");
        assert!(!f.contains("must have had"), "{f}");
    }

    /// A shorter run's numbers differ from full size's: the trade-offs measured at full size
    /// give no reason for them (a `--short` run once read "this bench cannot bring Joint A's
    /// linear error within its limit", a number within it at full size).
    #[test]
    fn a_shorter_run_is_not_explained_by_full_size_tradeoffs() {
        let (checks, tradeoffs) = twin_like(6.50);
        let text = finding_at(&checks, &tradeoffs, Explain::Shorter);
        assert!(
            text.contains("this run is shorter, so it does not say why"),
            "{text}"
        );
        assert!(!text.contains("must have had"), "{text}");
        assert!(!text.contains("Measured with"), "{text}");
        let full = finding_at(&checks, &tradeoffs, Explain::FullSize);
        assert!(full.contains("must have had"), "{full}");
    }

    #[test]
    fn without_a_tradeoff_the_reason_is_cannot_tell() {
        let (checks, _) = twin_like(6.5e6);
        let f = finding(&checks, &[]);
        assert!(f.contains("cannot say why"), "{f}");
        assert!(!f.contains("must have had"), "{f}");
    }

    #[test]
    fn moved_lists_the_largest_move_first_and_what_stayed() {
        use super::super::twin::{BenchFile, Provenance, Range};
        let file = BenchFile {
            calibration: Some(Provenance {
                method: "test".into(),
                evaluations: 1,
                objective: 0.0,
                parameters: BTreeMap::from([
                    ("a".to_owned(), 0.5),
                    ("b".to_owned(), 2.0),
                    ("c".to_owned(), 0.3),
                    ("d".to_owned(), 20.0),
                ]),
                corrections: BTreeMap::new(),
                ranges: BTreeMap::from([
                    (
                        "a".to_owned(),
                        Range {
                            ideal: 0.3,
                            lo: 0.0,
                            hi: 1.0,
                            log: false,
                        },
                    ),
                    (
                        "b".to_owned(),
                        Range {
                            ideal: 0.0,
                            lo: 0.0,
                            hi: 4.0,
                            log: false,
                        },
                    ),
                    (
                        "d".to_owned(),
                        Range {
                            ideal: 2.0,
                            lo: 0.5,
                            hi: 100.0,
                            log: true,
                        },
                    ),
                    (
                        "c".to_owned(),
                        Range {
                            ideal: 0.3,
                            lo: 0.0,
                            hi: 1.0,
                            log: false,
                        },
                    ),
                ]),
                agreements: BTreeMap::new(),
                tradeoffs: Vec::new(),
            }),
            joint: BTreeMap::new(),
        };
        let m = moved(&Bench::Twin(file.into()));
        assert_eq!(
            m.iter().map(|x| x.name.as_str()).collect::<Vec<_>>(),
            ["b", "d", "a", "c"]
        );
        let t = moved_text(&m);
        assert!(
            t.starts_with("The calibration moved 3 of 4 parameters"),
            "{t}"
        );
        assert!(
            t.contains("b 0 → 2 (+50 % of its range); d 2 → 20 (+43 % of its range); a 0.3 → 0.5 (+20 % of its range)"),
            "{t}"
        );
        assert!(t.contains("At the ideal bench's value: c."), "{t}");
        assert!(moved(&Bench::Ideal).is_empty());
    }
}
