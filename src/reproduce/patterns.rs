//! The paper's patterns as named checks: each one computed from the run, held or not, with the
//! paper's numbers and `dlw`'s beside it. `dlw reproduce` prints them, the report lists them at
//! the top, and `--json` carries them as `"patterns"`.

use serde::Serialize;

use super::paper::{RATE_CORRELATION, TABLE_IV, TWO_SENSOR_RMSE};
use super::{joints, Reproduction};
use crate::control::PAPER_TABLE_VI;

/// |corr(GF, rise time)| at or below this is "no rate dependence" (the paper's Fig. 5 shows
/// 0.0062, 0.0010 and 0.0011 for Joints A-C).
pub const MAX_RATE_CORRELATION: f64 = 0.1;

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
}

fn pattern(name: impl Into<String>, held: bool, paper: &str, dlw: String) -> Pattern {
    Pattern {
        name: name.into(),
        held,
        paper: paper.to_owned(),
        dlw,
    }
}

/// The RMSE (°) of `config` estimated from `sensors` on the joint `letter`, if it ran.
fn rmse(r: &Reproduction, letter: char, config: &str, sensors: &str) -> Option<f64> {
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
    let Some(sensor) = r
        .joints
        .iter()
        .find(|j| j.letter == letter)
        .and_then(|j| j.loops.sensors.first())
    else {
        return String::new();
    };
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
        (Some(pi), Some(lin)) if pi.is_finite() && lin.is_finite() => format!(
            "; characterization fit: PI {pi:.1} Ω, linear {lin:.1} Ω (the simulated sensor is a PI model)"
        ),
        _ => String::new(),
    }
}

fn missing(what: &str) -> String {
    format!("{what} did not run")
}

/// Every pattern of the paper, in the order of its tables and figures.
#[must_use]
pub fn patterns(r: &Reproduction) -> Vec<Pattern> {
    let mut out = Vec::new();
    // Table IV: PI against linear.
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
        let (lin, pi) = (
            rmse(r, letter, "linear", "one sensor"),
            rmse(r, letter, "PI", "one sensor"),
        );
        out.push(match (lin, pi) {
            (Some(lin), Some(pi)) => pattern(
                name,
                if pi_wins { pi < lin } else { lin < pi },
                paper,
                format!(
                    "Joint {letter}: PI {pi:.2}°, linear {lin:.2}°{}",
                    fit_residuals(r, letter)
                ),
            ),
            _ => pattern(name, false, paper, missing("an estimation")),
        });
    }
    // Table V: both sensors against each alone.
    let cfg = "linear, two-sensor config";
    let name = "both sensors beat each sensor alone (Joint C, Table V)";
    let [t, c, b] = TWO_SENSOR_RMSE;
    let paper = &format!("both {b:.2}°, tension {t:.2}°, compression {c:.2}°");
    out.push(
        match (
            rmse(r, 'C', cfg, "both"),
            rmse(r, 'C', cfg, "tension"),
            rmse(r, 'C', cfg, "compression"),
        ) {
            (Some(both), Some(t), Some(c)) => pattern(
                name,
                both < t && both < c,
                paper,
                format!("both {both:.2}°, tension {t:.2}°, compression {c:.2}°"),
            ),
            _ => pattern(name, false, paper, missing("the two-sensor estimation")),
        },
    );
    // Fig. 5: no rate dependence in the simulated joints, so the correlation must be small.
    for j in &r.joints {
        let corr = j.rate.sensors.first().map(|s| s.gf_rise_correlation);
        let name = format!(
            "|corr(GF, rise time)| ≤ {MAX_RATE_CORRELATION} without a rate effect (Joint {}, Fig. 5)",
            j.letter
        );
        let paper = &RATE_CORRELATION
            .get(usize::from(j.letter as u8 - b'A'))
            .map_or_else(String::new, |c| format!("{c:.4}"));
        out.push(match corr {
            Some(c) if c.is_finite() => pattern(
                name,
                c.abs() <= MAX_RATE_CORRELATION,
                paper,
                format!("{c:.4}"),
            ),
            _ => pattern(name, false, paper, missing("the rate correlation")),
        });
    }
    // Fig. 6: the relaxation time constant comes back.
    let sims = joints();
    for j in &r.joints {
        let simulated = sims
            .iter()
            .find(|s| s.letter == j.letter)
            .map(|s| s.scenario.plant.relaxation.tau_s * r.settings.duration_scale);
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
    // Table VI: closed loop against open loop, on the joint's actual angle.
    let [open, closed] = &r.control.run.metrics;
    out.push(pattern(
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
    ));
    out
}
