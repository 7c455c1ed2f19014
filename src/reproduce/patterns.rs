//! The paper's patterns as named checks: each one computed from the run, held or not, with the
//! paper's numbers and `dlw`'s beside it. `dlw reproduce` prints them, the report lists them at
//! the top, and `--json` carries them as `"patterns"`.

use serde::Serialize;

use super::paper::{RATE_CORRELATION, TABLE_IV, TWO_SENSOR_RMSE};
use super::Reproduction;
use crate::control::PAPER_TABLE_VI;
use crate::sensor::{Sensor, Sensors};

/// A one-sensor config's reading (sensor 1), and a two-sensor config's tension (sensor 1) and
/// compression (sensor 2) sensors alone.
pub(super) const ONE: Sensors = Sensors::Single(Sensor::One);
pub(super) const TENSION: Sensors = Sensors::Single(Sensor::One);
pub(super) const COMPRESSION: Sensors = Sensors::Single(Sensor::Two);

/// The normal quantile of a two-sided 5 % test: a correlation of `n` cycles is significant
/// above `tanh(1.96/√(n − 3))` (Fisher's z).
const Z_975: f64 = 1.959_964;

/// The largest |corr(GF, rise time)| of `cycles` cycles that is not significant at 5 %
/// (two-sided): of 25 cycles with no rate effect, 0.39. The paper's Fig. 5 shows 0.0062,
/// 0.0010 and 0.0011 for Joints A-C; a fixed bound such as 0.1 would fail on noise alone most of
/// the time (the correlation of 25 unrelated values has a standard deviation of about 0.2).
pub fn max_rate_correlation(cycles: usize) -> f64 {
    if cycles <= 3 {
        return 1.0;
    }
    (Z_975 / ((cycles - 3) as f64).sqrt()).tanh()
}

/// The relaxation τ fitted from the run must lie within this fraction of the simulated one.
pub const RELAXATION_TAU_TOLERANCE: f64 = 0.10;

/// One of the paper's patterns, checked on the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pattern {
    /// What the pattern says, e.g. "closed loop beats open loop on actual vs desired".
    pub name: String,
    /// Whether the run shows it.
    pub held: bool,
    /// The paper's numbers for it.
    pub paper: String,
    /// The run's numbers for it.
    pub dlw: String,
    /// Why the simulated joints cannot show the pattern, computed from the run: a stated
    /// property of the simulated joints (for example, a sensor built as a PI model cannot be
    /// estimated better by a line). `None` when they can; then `held` says whether they did.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cannot_show: Option<String>,
}

impl Pattern {
    /// Whether the simulated joints can show the pattern and did not: a failure of `dlw`.
    pub fn failed(&self) -> bool {
        !self.held && self.cannot_show.is_none()
    }

    /// `held`, `NOT held`, or `not held: the simulated joints cannot show it`.
    pub fn verdict(&self) -> &'static str {
        match (self.held, &self.cannot_show) {
            (true, _) => "held",
            (false, None) => "NOT held",
            (false, Some(_)) => "cannot show",
        }
    }
}

/// One sentence over the list: how many patterns held, how many the simulated joints cannot
/// show, how many failed.
pub fn tally(list: &[Pattern]) -> String {
    let held = list.iter().filter(|p| p.held).count();
    let cannot = list
        .iter()
        .filter(|p| !p.held && p.cannot_show.is_some())
        .count();
    let failed = list.iter().filter(|p| p.failed()).count();
    let mut text = format!(
        "{held} of the paper's {} patterns hold in this run",
        list.len()
    );
    if cannot > 0 {
        text +=
            &format!("; {cannot} the simulated joints cannot show, for the reason given with each");
    }
    if failed > 0 {
        text += &format!("; {failed} that they can show did NOT hold");
    } else {
        text += "; every pattern they can show holds";
    }
    text + "."
}

fn pattern(name: impl Into<String>, held: bool, paper: &str, dlw: String) -> Pattern {
    Pattern {
        name: name.into(),
        held,
        paper: paper.to_owned(),
        dlw,
        cannot_show: None,
    }
}

/// A sensor whose linear fit leaves at least this many times the PI fit's resistance RMSE on
/// its own characterization is hysteretic in a way the line cannot follow: it cannot be
/// estimated better by the line (Table IV's pattern for Joint C).
pub const HYSTERETIC_RESIDUAL_RATIO: f64 = 2.0;

/// With independent errors, an equal-weight average of two estimates beats the better one only
/// when the worse one's RMSE is below √3 times the better one's (`(a² + b²)/4 < b²`). Eq. 7
/// weighs Joint C's two sensors equally (their `Δy` are equal).
pub const TWO_SENSOR_ERROR_RATIO: f64 = 1.732_050_8;

/// The RMSE (°) of `config` estimated from `sensors` on the joint `letter`, if it ran.
pub(super) fn rmse(r: &Reproduction, letter: char, config: &str, sensors: Sensors) -> Option<f64> {
    r.joints
        .iter()
        .find(|j| j.letter == letter)?
        .estimation
        .runs
        .iter()
        .find(|x| x.config == config && x.sensors == sensors)
        .map(|x| x.metrics.rmse_deg)
}

/// The resistance RMSE of the PI and linear fits to joint `letter`'s characterization, the
/// evidence behind which model estimates better: `; characterization fit: PI … Ω, linear … Ω`
/// (empty when a fit is missing). The simulated sensors are PI models (Table III's points), so
/// a PI fit that finds its optimum follows them more closely than the line.
fn fit_residuals(r: &Reproduction, letter: char) -> String {
    match characterization_rmse(r, letter) {
        Some((pi, lin)) => format!(
            "; characterization fit: PI {pi:.1} Ω, linear {lin:.1} Ω (the simulated sensor is a PI model)"
        ),
        None => String::new(),
    }
}

/// The resistance RMSE (Ω) of the PI and the linear fit to joint `letter`'s characterization.
fn characterization_rmse(r: &Reproduction, letter: char) -> Option<(f64, f64)> {
    let sensor = r
        .joints
        .iter()
        .find(|j| j.letter == letter)
        .and_then(|j| j.loops.sensors.first())?;
    let rmse = |model| {
        sensor
            .fit
            .summaries
            .iter()
            .find(|s| s.model == model && s.skipped.is_none())
            .map(|s| s.rmse_ohm)
    };
    match (
        rmse(crate::fit::ModelKind::Pi),
        rmse(crate::fit::ModelKind::Linear),
    ) {
        (Some(pi), Some(lin)) if pi.is_finite() && lin.is_finite() => Some((pi, lin)),
        _ => None,
    }
}

/// Why joint `letter`'s simulated sensor cannot be estimated better by the line: its linear fit
/// leaves [`HYSTERETIC_RESIDUAL_RATIO`] times the PI fit's residual or more on its own
/// characterization, so the sensor is a loop the line cannot follow. `None` when it can.
fn line_cannot_win(r: &Reproduction, letter: char) -> Option<String> {
    let (pi, lin) = characterization_rmse(r, letter)?;
    (lin >= HYSTERETIC_RESIDUAL_RATIO * pi).then(|| {
        format!(
            "the simulated sensor is Table III's PI model: on its characterization the line \
             leaves {lin:.1} Ω, {:.1} times the PI fit's {pi:.1} Ω, so a line cannot estimate it \
             better; the paper's Joint C sensor showed little hysteresis",
            lin / pi
        )
    })
}

fn missing(what: &str) -> String {
    format!("{what} did not run")
}

/// Every pattern of the paper, in the order of its tables and figures.
#[must_use]
pub fn patterns(r: &Reproduction) -> Vec<Pattern> {
    let mut out = table_iv(r);
    out.push(table_v(r));
    out.extend(rate_independence(r));
    out.extend(relaxation_tau(r));
    out.push(table_vi(r));
    out
}

/// Table IV: PI against linear, per joint.
fn table_iv(r: &Reproduction) -> Vec<Pattern> {
    let mut out = Vec::new();
    for (i, (letter, pi_wins)) in [('A', true), ('B', true), ('C', false)]
        .into_iter()
        .enumerate()
    {
        let [paper_lin, paper_pi] = TABLE_IV[i];
        let paper = &format!("Joint {letter}: PI {paper_pi:.2}°, linear {paper_lin:.2}°");
        let name = if pi_wins {
            format!("PI beats linear for Joint {letter} (Table IV)")
        } else {
            format!("linear beats PI for Joint {letter} (Table IV)")
        };
        let (lin, pi) = (rmse(r, letter, "linear", ONE), rmse(r, letter, "PI", ONE));
        out.push(match (lin, pi) {
            (Some(lin), Some(pi)) => {
                let mut p = pattern(
                    name,
                    if pi_wins { pi < lin } else { lin < pi },
                    paper,
                    format!(
                        "Joint {letter}: PI {pi:.2}°, linear {lin:.2}°{}",
                        fit_residuals(r, letter)
                    ),
                );
                if !pi_wins {
                    p.cannot_show = line_cannot_win(r, letter);
                }
                p
            }
            _ => pattern(name, false, paper, missing("an estimation")),
        });
    }
    out
}

/// Table V: both sensors against each alone (Joint C).
fn table_v(r: &Reproduction) -> Pattern {
    let cfg = "linear, two-sensor config";
    let name = "both sensors beat each sensor alone (Joint C, Table V)";
    let [t, c, b] = TWO_SENSOR_RMSE;
    let paper = &format!("both {b:.2}°, tension {t:.2}°, compression {c:.2}°");
    match (
        rmse(r, 'C', cfg, Sensors::Both),
        rmse(r, 'C', cfg, TENSION),
        rmse(r, 'C', cfg, COMPRESSION),
    ) {
        (Some(both), Some(t), Some(c)) => {
            let mut p = pattern(
                name,
                both < t && both < c,
                paper,
                format!("both {both:.2}°, tension {t:.2}°, compression {c:.2}°"),
            );
            let ratio = t.max(c) / t.min(c);
            if ratio >= TWO_SENSOR_ERROR_RATIO {
                p.cannot_show = Some(format!(
                    "one sensor alone is {ratio:.2} times as far off as the other (tension \
                     {t:.2}°, compression {c:.2}°; the paper's {:.2}); Eq. 7 weighs the two \
                     equally, and an equal-weight average beats the better one only when the \
                     worse one's error is under √3 = {TWO_SENSOR_ERROR_RATIO:.2} times the \
                     better one's. The simulated tension sensor carries Table III's PI \
                     hysteresis, while the compression sensor is simulated linear (the paper \
                     gives only its linear fit)",
                    TWO_SENSOR_RMSE[0] / TWO_SENSOR_RMSE[1]
                ));
            }
            p
        }
        _ => pattern(name, false, paper, missing("the two-sensor estimation")),
    }
}

/// Fig. 5: no rate dependence in the simulated joints, so GF must not follow the rise time
/// beyond what noise gives.
fn rate_independence(r: &Reproduction) -> Vec<Pattern> {
    let mut out = Vec::new();
    for j in &r.joints {
        let sensor = j.rate.sensors.first();
        let name = format!(
            "GF does not follow the rise time without a rate effect (Joint {}, Fig. 5)",
            j.letter
        );
        let paper = &RATE_CORRELATION
            .get(usize::from(j.letter as u8 - b'A'))
            .map_or_else(String::new, |c| format!("corr {c:.4}"));
        out.push(match sensor {
            Some(s) if s.gf_rise_correlation.is_finite() => {
                let bound = max_rate_correlation(s.cycles.len());
                pattern(
                    name,
                    s.gf_rise_correlation.abs() <= bound,
                    paper,
                    format!(
                        "corr {:.4} over {} cycles ({} at 5 %: the bound is |{bound:.2}|), GF \
                         {:+.2} % from the fastest cycle to the slowest",
                        s.gf_rise_correlation,
                        s.cycles.len(),
                        if s.gf_rise_correlation.abs() <= bound {
                            "not significant"
                        } else {
                            "significant"
                        },
                        100.0 * s.gf_relative_change
                    ),
                )
            }
            _ => pattern(name, false, paper, missing("the rate correlation")),
        });
    }
    out
}

/// Fig. 6: the relaxation time constant comes back.
fn relaxation_tau(r: &Reproduction) -> Vec<Pattern> {
    let mut out = Vec::new();
    for j in &r.joints {
        let simulated = Some(j.simulated_tau_s);
        let fitted = j.relaxation.sensors.first().and_then(|s| s.median_tau_s);
        let name = format!(
            "relaxation τ within {:.0} % of the simulated one (Joint {}, Fig. 6)",
            RELAXATION_TAU_TOLERANCE * 100.0,
            j.letter
        );
        let paper = "the paper fits τ to its joints; the simulator's τ is known";
        out.push(match (simulated, fitted) {
            (Some(s), Some(f)) if s > 0.0 => pattern(
                name,
                ((f - s) / s).abs() <= RELAXATION_TAU_TOLERANCE,
                paper,
                format!("fitted {f:.2} s, simulated {s:.2} s"),
            ),
            _ => pattern(name, false, paper, missing("the relaxation fit")),
        });
    }
    out
}

/// Table VI: closed loop against open loop, on the joint's actual angle (Joint D).
fn table_vi(r: &Reproduction) -> Pattern {
    let [open, closed] = &r.control.run.metrics;
    pattern(
        "closed loop beats open loop on actual vs desired (Joint D, Table VI)",
        closed.actual_vs_desired_rmse_deg < open.actual_vs_desired_rmse_deg,
        &format!(
            "open {:.2}° → closed {:.2}°",
            PAPER_TABLE_VI[0].1, PAPER_TABLE_VI[1].1
        ),
        format!(
            "open {:.2}° → closed {:.2}°",
            open.actual_vs_desired_rmse_deg, closed.actual_vs_desired_rmse_deg
        ),
    )
}
