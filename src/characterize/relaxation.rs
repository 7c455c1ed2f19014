//! Relaxation (Section IV-A3, Fig. 6): the holds of the tendon stroke, how the strain decays
//! during each, and whether the resistance follows.
//!
//! - **Holds** are runs of the recorded stroke that stay within [`HOLD_TOLERANCE`] of the
//!   stroke's span for at least `min_hold_s`, away from zero stroke (a hold at zero is a rest).
//!   The prefilter's window after the ramp is skipped, so the ramp is not averaged in.
//! - **Strain decay**: `ε(t) = ε_∞ + A·e^(−t/τ)` fitted to the hold's strain (from the tracker
//!   angle, Eq. 3) by least squares: for each `τ` the model is linear in `ε_∞` and `A`, so `τ`
//!   is searched on a logarithmic grid from a fiftieth of the hold to ten holds and refined by
//!   golden section. The decay over the hold is `ε(0) − ε(T)` of the fitted curve. A `τ` at the
//!   top of the range means the decay is not resolved within the hold.
//! - **Correlation**: Pearson's coefficient of the change in resistance with the change in strain
//!   from the start to the end of each hold, across holds (the paper: 0.118 for Joint A). The
//!   share of the strain change the resistance followed is `ΔR/(R₀·GF·Δε)` with the whole
//!   recording's linear fit: 1 for a sensor that reads the relaxed strain, 0 for one that does
//!   not.

use dlw_estimator::SensorPlane;
use dlw_geometry::Joint;
use serde::Serialize;

use super::{figure_name, min_max, pearson, sensor_label, titled};
use super::{CharacterizeError, Options};
use crate::recording::Recording;
use crate::report::{Chart, Legend, Page, Series, SeriesStyle, Table, PALETTE};
use crate::signal::{fit_linear, observe, Prefilter};

/// A hold's stroke stays within this share of the stroke's span.
pub const HOLD_TOLERANCE: f64 = 1e-3;
/// A hold at a stroke within this share of the span from zero is a rest.
pub const REST_SHARE: f64 = 0.02;
/// Fewest holds the correlation needs.
pub const MIN_HOLDS: usize = 3;

/// One hold of one sensor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Hold {
    /// 1-based number.
    pub number: usize,
    /// Start and end of the analysed part (s).
    pub start_s: f64,
    /// End (s).
    pub end_s: f64,
    /// The held stroke (mm).
    pub stroke_mm: f64,
    /// Strain at the start of the hold, fitted (fraction).
    pub strain_start: f64,
    /// Decay of the strain over the hold, `ε(0) − ε(T)` of the fit (fraction; negative when the
    /// strain rises).
    pub strain_decay: f64,
    /// The decay's time constant `τ` (s).
    pub tau_s: f64,
    /// Whether `τ` came out at the top of the searched range (decay not resolved).
    pub tau_unresolved: bool,
    /// Change of the strain, last sample minus first (fraction).
    pub delta_strain: f64,
    /// Change of the resistance, last sample minus first (Ω).
    pub delta_ohm: f64,
}

/// One sensor's relaxation analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RelaxationSensor {
    /// `v1_V`, ….
    pub sensor: String,
    /// The holds.
    pub holds: Vec<Hold>,
    /// Pearson's coefficient of `ΔR` with `Δε` across the holds.
    pub correlation: f64,
    /// Median of `ΔR/(R₀·GF·Δε)` over the holds.
    pub followed_share: f64,
    /// Median time constant of the resolved decays (s).
    pub median_tau_s: Option<f64>,
    /// The whole recording's linear gauge factor.
    pub gauge_factor: f64,
    /// Its `R₀` (Ω).
    pub r0_ohm: f64,
    /// The hold samples for Fig. 6: `(time, strain, resistance)` per hold.
    #[serde(skip)]
    pub traces: Vec<Vec<(f64, f64, f64)>>,
}

/// The relaxation analysis of every sensor.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RelaxationResult {
    /// The shortest hold accepted (s).
    pub min_hold_s: f64,
    /// One per sensor.
    pub sensors: Vec<RelaxationSensor>,
}

/// Finds the holds, as sample index ranges, and the longest non-zero constant run (s).
fn holds(recording: &Recording, min_hold_s: f64) -> (Vec<(usize, usize)>, f64) {
    let s = &recording.samples;
    let (lo, hi) = min_max(&s.stroke_mm);
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    let tol = HOLD_TOLERANCE * span;
    let mut out = Vec::new();
    let mut longest = 0.0f64;
    let mut start = 0;
    let n = s.len();
    for i in 1..=n {
        let ends = i == n || (s.stroke_mm[i] - s.stroke_mm[start]).abs() > tol;
        if ends {
            let end = i - 1;
            let held = s.stroke_mm[start];
            if held.abs() > REST_SHARE * span && end > start {
                let length = s.time_s[end] - s.time_s[start];
                longest = longest.max(length);
                if length >= min_hold_s {
                    out.push((start, end));
                }
            }
            start = i;
        }
    }
    (out, longest)
}

/// `ε(t) = c + A·e^(−t/τ)`: the least-squares `(c, A, SSE)` for one `τ`.
fn exp_fit(t: &[f64], y: &[f64], tau: f64) -> (f64, f64, f64) {
    let n = t.len() as f64;
    let (mut sx, mut sxx, mut sy, mut sxy) = (0.0, 0.0, 0.0, 0.0);
    for (ti, yi) in t.iter().zip(y) {
        let x = (-ti / tau).exp();
        sx += x;
        sxx += x * x;
        sy += yi;
        sxy += x * yi;
    }
    let det = n * sxx - sx * sx;
    let (c, a) = if det.abs() > 1e-300 {
        ((sxx * sy - sx * sxy) / det, (n * sxy - sx * sy) / det)
    } else {
        (sy / n, 0.0)
    };
    let sse = t
        .iter()
        .zip(y)
        .map(|(ti, yi)| {
            let r = yi - c - a * (-ti / tau).exp();
            r * r
        })
        .sum();
    (c, a, sse)
}

/// The best `τ` in `[lo, hi]` (log grid, then golden section on `ln τ`).
fn fit_tau(t: &[f64], y: &[f64], lo: f64, hi: f64) -> f64 {
    let grid = 60;
    let at = |k: usize| (lo.ln() + (hi.ln() - lo.ln()) * k as f64 / grid as f64).exp();
    let best = (0..=grid)
        .min_by(|&a, &b| exp_fit(t, y, at(a)).2.total_cmp(&exp_fit(t, y, at(b)).2))
        .unwrap_or(0);
    let (mut a, mut b) = (
        at(best.saturating_sub(1)).ln(),
        at((best + 1).min(grid)).ln(),
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let f = |x: f64| exp_fit(t, y, x.exp()).2;
    for _ in 0..60 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if f(c) < f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    (0.5 * (a + b)).exp()
}

/// Finds the holds and analyses each sensor over them.
///
/// # Errors
/// [`CharacterizeError::NoHolds`], [`CharacterizeError::TooFewHolds`], or the observations'
/// [`CharacterizeError::Fit`].
pub fn relaxation(
    recording: &Recording,
    joint: &Joint,
    planes: &[SensorPlane],
    options: &Options,
) -> Result<RelaxationResult, CharacterizeError> {
    let min_hold_s = options.min_hold_s;
    let (found, longest_s) = holds(recording, min_hold_s);
    if found.is_empty() {
        return Err(CharacterizeError::NoHolds {
            min_hold_s,
            longest_s,
        });
    }
    if found.len() < MIN_HOLDS {
        return Err(CharacterizeError::TooFewHolds {
            found: found.len(),
            min: MIN_HOLDS,
            min_hold_s,
        });
    }
    let window = match options.prefilter {
        Prefilter::None => 0,
        Prefilter::MovingAverage(n) => n as usize,
    };
    let two = planes.len() > 1;
    let mut sensors = Vec::new();
    for &plane in planes {
        let obs = observe(recording, joint, plane, options.prefilter, None)?;
        let linear = fit_linear(&obs.strain, &obs.ohm)?;
        let mut out = Vec::new();
        let mut traces = Vec::new();
        for &(i0, i1) in &found {
            // The hold's observations by their rows (rows the tracker did not measure are not
            // observations, so a row is not always `j·decimation`).
            let j0 = obs.rows.partition_point(|&i| i < i0 + window);
            let Some(j1) = obs.rows.partition_point(|&i| i <= i1).checked_sub(1) else {
                continue;
            };
            if j1 < j0 + 4 {
                continue;
            }
            let r = j0..=j1;
            let t0 = obs.time_s[j0];
            let t: Vec<f64> = obs.time_s[r.clone()].iter().map(|x| x - t0).collect();
            let y = &obs.strain[r.clone()];
            let length = t[t.len() - 1].max(1e-9);
            let (lo, hi) = (length / 50.0, length * 10.0);
            let tau = fit_tau(&t, y, lo, hi);
            let (c, a, _) = exp_fit(&t, y, tau);
            let fitted = |x: f64| c + a * (-x / tau).exp();
            out.push(Hold {
                number: out.len() + 1,
                start_s: t0,
                end_s: obs.time_s[j1],
                stroke_mm: recording.samples.stroke_mm[i0],
                strain_start: fitted(0.0),
                strain_decay: fitted(0.0) - fitted(length),
                tau_s: tau,
                tau_unresolved: tau > 0.9 * hi,
                delta_strain: obs.strain[j1] - obs.strain[j0],
                delta_ohm: obs.ohm[j1] - obs.ohm[j0],
            });
            traces.push(
                r.map(|j| (obs.time_s[j] - t0, obs.strain[j], obs.ohm[j]))
                    .collect(),
            );
        }
        let de: Vec<f64> = out.iter().map(|h| h.delta_strain).collect();
        let dr: Vec<f64> = out.iter().map(|h| h.delta_ohm).collect();
        let sensitivity = linear.r0_ohm * linear.gauge_factor;
        let shares: Vec<f64> = out
            .iter()
            .filter(|h| h.delta_strain.abs() > 0.0)
            .map(|h| h.delta_ohm / (sensitivity * h.delta_strain))
            .collect();
        let taus: Vec<f64> = out
            .iter()
            .filter(|h| !h.tau_unresolved)
            .map(|h| h.tau_s)
            .collect();
        sensors.push(RelaxationSensor {
            sensor: sensor_label(plane, two),
            correlation: pearson(&de, &dr).unwrap_or(0.0),
            followed_share: median(&shares).unwrap_or(f64::NAN),
            median_tau_s: median(&taus),
            gauge_factor: linear.gauge_factor,
            r0_ohm: linear.r0_ohm,
            holds: out,
            traces,
        });
    }
    Ok(RelaxationResult {
        min_hold_s,
        sensors,
    })
}

use crate::stats::median;

impl RelaxationResult {
    /// Adds the holds' table and Fig. 6(b), (c) for each sensor.
    fn section(&self, page: &mut Page, label: &str, prefix: &str) {
        let mut t = Table::new([
            "sensor",
            "holds",
            "median τ (s)",
            "corr(ΔR, Δε)",
            "share of Δε in ΔR",
        ]);
        for s in &self.sensors {
            t.row([
                s.sensor.clone(),
                s.holds.len().to_string(),
                s.median_tau_s
                    .map_or_else(|| "not resolved".into(), |x| format!("{x:.2}")),
                format!("{:.3}", s.correlation),
                format!("{:.2}", s.followed_share),
            ]);
        }
        page.table(t);
        for s in &self.sensors {
            let stem = s
                .sensor
                .split(' ')
                .next()
                .unwrap_or("v1_V")
                .trim_end_matches("_V")
                .to_owned();
            let mut holds = Table::new([
                "hold",
                "start (s)",
                "stroke (mm)",
                "strain (%)",
                "decay (% strain)",
                "τ (s)",
                "ΔR (Ω)",
            ]);
            for h in &s.holds {
                holds.row([
                    h.number.to_string(),
                    format!("{:.1}", h.start_s),
                    format!("{:.3}", h.stroke_mm),
                    format!("{:.4}", h.strain_start * 100.0),
                    format!("{:+.4}", h.strain_decay * 100.0),
                    if h.tau_unresolved {
                        "–".into()
                    } else {
                        format!("{:.2}", h.tau_s)
                    },
                    format!("{:+.1}", h.delta_ohm),
                ]);
            }
            // Only the first repetition's holds, so the table stays readable.
            let shown = s.holds.len().min(8);
            holds.rows.truncate(shown);
            let mut decay = Chart::new(
                titled(label, &format!("Strain during each hold, {}", s.sensor)),
                "time since the hold began (s)",
                "strain − strain at the start (% strain)",
            );
            decay.size = (900, 380);
            decay.legend = Legend::LowerLeft;
            let mut scatter = Chart::new(
                titled(label, &format!("ΔR against Δε during holds, {}", s.sensor)),
                "Δε since the hold began (% strain)",
                "ΔR since the hold began (Ω)",
            );
            scatter.size = (900, 380);
            for (k, tr) in s.traces.iter().enumerate() {
                let Some(&(_, e0, r0)) = tr.first() else {
                    continue;
                };
                let color = PALETTE[k % PALETTE.len()];
                decay.push(Series::line(
                    "",
                    tr.iter().map(|&(t, e, _)| (t, (e - e0) * 100.0)).collect(),
                    color,
                ));
                scatter.push(Series {
                    label: String::new(),
                    points: tr
                        .iter()
                        .map(|&(_, e, r)| ((e - e0) * 100.0, r - r0))
                        .collect(),
                    color,
                    style: SeriesStyle::Dots(1),
                });
            }
            page.table(holds);
            if s.holds.len() > shown {
                page.text(format!(
                    "The table shows the first {shown} of {} holds; --json lists all.",
                    s.holds.len()
                ));
            }
            page.figure(
                figure_name(prefix, &format!("relax-strain-{stem}")),
                decay,
                "(b) The change in strain during each hold of the stroke, one colour per hold.",
            );
            page.figure(
                figure_name(prefix, &format!("relax-r-{stem}")),
                scatter,
                format!(
                    "(c) Resistance against strain during each hold; the correlation of ΔR with \
                     Δε across holds is {:.3}.",
                    s.correlation
                ),
            );
        }
    }
}

impl crate::analysis::Analysis for RelaxationResult {
    fn summary(&self) -> String {
        use std::fmt::Write;
        let r = self;
        let mut out = String::new();
        for s in &r.sensors {
            let _ = writeln!(
                out,
                "sensor {}: {} holds of at least {} s",
                s.sensor,
                s.holds.len(),
                r.min_hold_s
            );
            for h in &s.holds {
                let _ = writeln!(out,
                "  hold {:>2} at {:>7.1} s  stroke {:.3} mm  strain decay {:+.4} %  tau {}  ΔR {:+.1} Ω",
                h.number,
                h.start_s,
                h.stroke_mm,
                h.strain_decay * 100.0,
                if h.tau_unresolved {
                    "not resolved".to_owned()
                } else {
                    format!("{:.2} s", h.tau_s)
                },
                h.delta_ohm
            );
            }
            let _ = writeln!(out,
            "  correlation of ΔR with Δε over the holds {:.3}; share of Δε the resistance followed {:.2}",
            s.correlation, s.followed_share
        );
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: crate::analysis::Placement<'_>) {
        self.section(page, at.label, at.figure_prefix);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn exponential_fit_recovers_tau_and_amplitude() {
        for (tau, a) in [(3.0, 2e-4), (20.0, -5e-4), (0.8, 1e-3)] {
            let t: Vec<f64> = (0..600).map(|i| i as f64 * 0.1).collect();
            let y: Vec<f64> = t
                .iter()
                .enumerate()
                .map(|(i, x)| 0.01 + a * (-x / tau).exp() + 1e-6 * ((i * 7919 % 13) as f64 - 6.0))
                .collect();
            let found = fit_tau(&t, &y, 60.0 / 50.0 / 10.0, 600.0);
            assert_relative_eq!(found, tau, max_relative = 0.03);
            let (c, amp, _) = exp_fit(&t, &y, found);
            assert_relative_eq!(c, 0.01, max_relative = 1e-3);
            assert_relative_eq!(amp, a, max_relative = 0.03);
        }
    }

    #[test]
    fn medians() {
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), Some(2.5));
    }
}
