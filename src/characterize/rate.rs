//! Rate dependence (Section IV-A2, Fig. 5): the linear model fitted to each loading/unloading
//! cycle of equal amplitude, its gauge factor against the cycle's rise time with their
//! correlation coefficient, and its `R₀` against the cycle number with their standard
//! deviation.
//!
//! - **Cycles** are cut at the strain's turning points (`crate::signal::phases`, a turn needs the
//!   strain to come back by a tenth of its span). Only cycles whose rise reaches
//!   [`EQUAL_AMPLITUDE`] of the largest count, as the paper's protocol has one amplitude.
//! - **Rise time** is the time from 10 % to 90 % of the cycle's rise, divided by 0.8: the
//!   turning point at the start of a rise lies anywhere in the rest before it (the strain is
//!   flat there), so the time between turning points would add the rest's noise.
//! - **Per-cycle fit**: `R = R₀·GF·ε + R₀` by least squares on the cycle's loading samples
//!   (Eqs. 5-6) inside **one strain range shared by every cycle**: from the highest rest floor
//!   (where a rise leaves its rest, by [`REST_BAND`] of the rise) to [`MATCHED_SHARE`] of the
//!   way to the lowest peak. The rests around a cycle take a larger share of a fast cycle, and
//!   on a hysteretic sensor they would tilt the line differently for fast and slow cycles; a
//!   slow rise relaxes to a lower peak, so each cycle's own range would give a curved sensor's
//!   secant a GF that follows the rise time with no rate effect; and a hysteretic sensor's
//!   unloading branch depends on the peak it starts from, so only the loading branch, which
//!   starts from the same rest every time, is fitted. (Fitted over each cycle's whole moving
//!   part, the reproduction's joints showed corr 0.48, 0.91 and −0.22 with no rate effect.)
//! - The **correlation coefficient** (Pearson's) of GF with rise time is scale-free: when GF
//!   barely varies it is the correlation of noise and can take any value. The relative change
//!   of GF over the range of rise times, from the least-squares slope, says how large the
//!   effect is; both are reported.

use dlw_estimator::SensorPlane;
use dlw_geometry::Joint;
use serde::Serialize;

use super::{figure_name, min_max, pearson, sensor_label, slope, std_dev, titled};
use super::{CharacterizeError, Options};
use crate::recording::Recording;
use crate::report::{Chart, Page, Series, SeriesStyle, Table, PALETTE};
use crate::signal::{cycles, fit_linear, observe, phases, Cycle, TURN_THRESHOLD};

/// A cycle counts when its rise reaches this share of the largest rise.
pub const EQUAL_AMPLITUDE: f64 = 0.75;
/// Samples within this share of the rise from the cycle's start are rest, not fitted.
pub const REST_BAND: f64 = 0.02;
/// Each cycle is fitted from the common rest floor up to this share of the way to the lowest
/// peak of all cycles: the top of the range is left out, where a cycle turns.
pub const MATCHED_SHARE: f64 = 0.95;
/// Fewest samples of a cycle inside the matched strain range for it to be fitted.
pub const MIN_MATCHED_SAMPLES: usize = 10;
/// Fewest equal-amplitude cycles the analysis needs.
pub const MIN_CYCLES: usize = 3;
/// The longest rise must be at least this many times the shortest.
pub const MIN_SPEED_RATIO: f64 = 1.5;

/// One cycle's fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RateCycle {
    /// 1-based number among the equal-amplitude cycles.
    pub number: usize,
    /// Time the rise starts (s).
    pub start_s: f64,
    /// Rise time (s), from 10 % to 90 % of the rise over 0.8.
    pub rise_s: f64,
    /// Strain rise of the cycle (fraction).
    pub amplitude_strain: f64,
    /// The cycle's gauge factor, over the matched strain range of its loading branch.
    pub gauge_factor: f64,
    /// The cycle's `R₀` (Ω), from the line through its whole moving part.
    pub r0_ohm: f64,
    /// r² of the cycle's GF fit.
    pub r2: f64,
}

/// One sensor's rate analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RateSensor {
    /// `v1_V`, ….
    pub sensor: String,
    /// The equal-amplitude cycles.
    pub cycles: Vec<RateCycle>,
    /// Cycles left out for a smaller amplitude.
    pub smaller_cycles: usize,
    /// Pearson's correlation coefficient of GF with the rise time (the paper: 0.0062, 0.0010,
    /// 0.0011 for Joints A-C).
    pub gf_rise_correlation: f64,
    /// Least-squares slope of GF on the rise time (1/s).
    pub gf_slope_per_s: f64,
    /// The slope times the range of rise times, over the mean GF (fraction): how much GF
    /// changes from the fastest cycle to the slowest.
    pub gf_relative_change: f64,
    /// Mean GF of the cycles.
    pub gf_mean: f64,
    /// Standard deviation of the cycles' `R₀` (Ω; the paper: 1.10, 0.596, 0.038 kΩ).
    pub r0_std_ohm: f64,
    /// The strain range every cycle is fitted over (fraction, the sensor's own sign): from the
    /// highest rest floor to [`MATCHED_SHARE`] of the way to the lowest peak.
    pub matched_strain: [f64; 2],
}

/// One equal-amplitude cycle before its fit.
struct Moving {
    /// The loading rows, from where the rise leaves the rest to the peak.
    rows: std::ops::RangeInclusive<usize>,
    /// The moving rows, from where the rise leaves the rest to where the fall comes back to it.
    whole: std::ops::RangeInclusive<usize>,
    /// The rest floor: the strain where the rise leaves the rest.
    floor: f64,
    /// The cycle's peak strain.
    peak: f64,
    /// The strain rise.
    amplitude: f64,
    /// Time at 10 % of the rise (s).
    t10: f64,
    /// Rise time (s), from 10 % to 90 % of the rise over 0.8.
    rise_s: f64,
}

/// The loading part of cycle `c` whose rise is `amp`: from where the rise leaves the rest to the
/// peak. The rests vary in share with the speed, and on a hysteretic sensor they would pull the
/// line differently; the unloading branch starts from the cycle's own peak, which a slow rise
/// lowers by relaxing, and a hysteretic sensor's unloading branch depends on that peak.
fn moving_part(c: &Cycle, strain: &[f64], time_s: &[f64], amp: f64) -> Option<Moving> {
    let base = strain[c.loading.start];
    let load = c.loading.start..=c.loading.end;
    let cross = |share: f64| {
        load.clone()
            .find(|&i| strain[i] >= base + share * amp)
            .map(|i| time_s[i])
    };
    let (t10, t90) = (cross(0.1)?, cross(0.9)?);
    let floor = base + REST_BAND * amp;
    // The rise leaves the rest where the strain last crossed the floor before it reached a
    // tenth of the rise. Searching forward from the turning point instead would start in the
    // rest whenever the turning point lies below the rest (a relaxed joint undershoots after
    // unloading and recovers while it rests): the rest's noise then crosses the floor, and its
    // samples, many more for a fast cycle than its rise, pull the line towards the sensor's
    // steeper start (at --short, Joint A's GF fell 7 % from the fastest cycle to the slowest).
    let ten = load.clone().find(|&i| strain[i] >= base + 0.1 * amp)?;
    let first = (c.loading.start..=ten)
        .rev()
        .find(|&i| strain[i] < floor)
        .map_or(c.loading.start, |i| i + 1);
    let last = (c.unloading.start..=c.unloading.end)
        .rev()
        .find(|&i| strain[i] >= floor)?;
    Some(Moving {
        rows: first..=c.loading.end,
        whole: first..=last,
        floor,
        peak: strain[c.loading.end],
        amplitude: amp,
        t10,
        rise_s: (t90 - t10) / 0.8,
    })
}

/// The rate analysis of every sensor.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RateResult {
    /// One per sensor.
    pub sensors: Vec<RateSensor>,
}

/// Fits every equal-amplitude cycle of each sensor.
///
/// # Errors
/// [`CharacterizeError::TooFewCycles`], [`CharacterizeError::OneSpeed`], or the observations'
/// or a cycle fit's [`CharacterizeError::Fit`].
pub fn rate(
    recording: &Recording,
    joint: &Joint,
    planes: &[SensorPlane],
    options: &Options,
) -> Result<RateResult, CharacterizeError> {
    let two = planes.len() > 1;
    let mut sensors = Vec::new();
    for &plane in planes {
        let obs = observe(recording, joint, plane, options.prefilter, Some(1))?;
        // The joint's strain drives the cycles, for both sensors (sensor 2 reads −ε).
        let joint_strain: Vec<f64> = obs.strain.iter().map(|e| plane.sign() * e).collect();
        let (lo, hi) = min_max(&joint_strain);
        let all = cycles(&phases(&joint_strain, TURN_THRESHOLD * (hi - lo)));
        let rise_of = |c: &Cycle| joint_strain[c.loading.end] - joint_strain[c.loading.start];
        let largest = all.iter().map(rise_of).fold(0.0, f64::max);
        // The equal-amplitude cycles, with the samples where each moves.
        let mut kept = Vec::new();
        let mut smaller = 0;
        for c in &all {
            let amp = rise_of(c);
            if amp < EQUAL_AMPLITUDE * largest {
                smaller += 1;
                continue;
            }
            if let Some(k) = moving_part(c, &joint_strain, &obs.time_s, amp) {
                kept.push(k);
            }
        }
        // One strain range for every cycle: from the highest rest floor to the lowest peak.
        // A curved sensor's secant slope depends on the range it spans, and a slow rise relaxes
        // to a lower peak, so fitting each cycle over its own range correlates GF with the rise
        // time with no rate effect at all.
        let floor = kept
            .iter()
            .map(|k| k.floor)
            .fold(f64::NEG_INFINITY, f64::max);
        let top = kept.iter().map(|k| k.peak).fold(f64::INFINITY, f64::min);
        let matched = (floor, floor + MATCHED_SHARE * (top - floor));
        let mut out = Vec::new();
        for k in &kept {
            let rows: Vec<usize> = k
                .rows
                .clone()
                .filter(|&i| (matched.0..=matched.1).contains(&joint_strain[i]))
                .collect();
            if rows.len() < MIN_MATCHED_SAMPLES {
                continue;
            }
            let strain: Vec<f64> = rows.iter().map(|&i| obs.strain[i]).collect();
            let ohm: Vec<f64> = rows.iter().map(|&i| obs.ohm[i]).collect();
            let fit = fit_linear(&strain, &ohm)?;
            // R₀ from the whole moving cycle, loading and unloading: the intercept of the
            // matched loading range alone is an extrapolation, noisier than the drift it is
            // there to show.
            let whole = fit_linear(&obs.strain[k.whole.clone()], &obs.ohm[k.whole.clone()])?;
            out.push(RateCycle {
                number: out.len() + 1,
                start_s: k.t10,
                rise_s: k.rise_s,
                amplitude_strain: k.amplitude,
                gauge_factor: fit.gauge_factor,
                r0_ohm: whole.r0_ohm,
                r2: fit.r2,
            });
        }
        if out.len() < MIN_CYCLES {
            return Err(CharacterizeError::TooFewCycles {
                found: out.len(),
                min: MIN_CYCLES,
                share: EQUAL_AMPLITUDE * 100.0,
            });
        }
        let rise: Vec<f64> = out.iter().map(|c| c.rise_s).collect();
        let gf: Vec<f64> = out.iter().map(|c| c.gauge_factor).collect();
        let r0: Vec<f64> = out.iter().map(|c| c.r0_ohm).collect();
        let (min_s, max_s) = min_max(&rise);
        if max_s < MIN_SPEED_RATIO * min_s || !max_s.is_finite() {
            return Err(CharacterizeError::OneSpeed {
                cycles: out.len(),
                min_s,
                max_s,
                ratio: MIN_SPEED_RATIO,
            });
        }
        let gf_mean = gf.iter().sum::<f64>() / gf.len() as f64;
        let gf_slope = slope(&rise, &gf).unwrap_or(0.0);
        sensors.push(RateSensor {
            sensor: sensor_label(plane, two),
            matched_strain: [plane.sign() * matched.0, plane.sign() * matched.1],
            smaller_cycles: smaller,
            gf_rise_correlation: pearson(&rise, &gf).unwrap_or(0.0),
            gf_slope_per_s: gf_slope,
            gf_relative_change: gf_slope * (max_s - min_s) / gf_mean,
            gf_mean,
            r0_std_ohm: std_dev(&r0).unwrap_or(0.0),
            cycles: out,
        });
    }
    Ok(RateResult { sensors })
}

impl RateResult {
    /// Adds the summary table and Fig. 5(d), (e) for each sensor.
    fn section(&self, page: &mut Page, label: &str, prefix: &str) {
        let mut t = Table::new([
            "sensor",
            "cycles",
            "rise times (s)",
            "mean GF",
            "corr(GF, rise time)",
            "GF change, fastest → slowest",
            "std dev R₀ (kΩ)",
        ]);
        for s in &self.sensors {
            let rise: Vec<f64> = s.cycles.iter().map(|c| c.rise_s).collect();
            let (lo, hi) = min_max(&rise);
            t.row([
                s.sensor.clone(),
                format!("{} (+{} smaller)", s.cycles.len(), s.smaller_cycles),
                format!("{lo:.1} – {hi:.1}"),
                format!("{:.4}", s.gf_mean),
                format!("{:.4}", s.gf_rise_correlation),
                format!("{:+.2} %", s.gf_relative_change * 100.0),
                format!("{:.3}", s.r0_std_ohm / 1e3),
            ]);
        }
        page.table(t);
        for s in &self.sensors {
            let column = s.sensor.split(' ').next().unwrap_or("v1_V").to_owned();
            let stem = column.trim_end_matches("_V").to_owned();
            let dot = |label: &str, points: Vec<(f64, f64)>, color| Series {
                label: label.to_owned(),
                points,
                color,
                style: SeriesStyle::Dots(5),
            };
            let mut gf = Chart::new(
                titled(label, &format!("Gauge factor per cycle, {}", s.sensor)),
                "rise time (s)",
                "gauge factor",
            );
            gf.size = (440, 340);
            gf.push(dot(
                "",
                s.cycles
                    .iter()
                    .map(|c| (c.rise_s, c.gauge_factor))
                    .collect(),
                PALETTE[0],
            ));
            let mut r0 = Chart::new(
                titled(label, &format!("R₀ per cycle, {}", s.sensor)),
                "cycle",
                "R₀ (kΩ)",
            );
            r0.size = (440, 340);
            let pts: Vec<(f64, f64)> = s
                .cycles
                .iter()
                .map(|c| (c.number as f64, c.r0_ohm / 1e3))
                .collect();
            r0.push(Series::line("", pts.clone(), PALETTE[7]));
            r0.push(dot("", pts, PALETTE[1]));
            page.figure(
                figure_name(prefix, &format!("rate-gf-{stem}")),
                gf,
                format!(
                    "(d) The linear gauge factor of each cycle against its rise time; \
                     correlation coefficient {:.4}.",
                    s.gf_rise_correlation
                ),
            );
            page.figure(
                figure_name(prefix, &format!("rate-r0-{stem}")),
                r0,
                format!(
                    "(e) The initial resistance R₀ of each cycle against the cycle number; \
                     standard deviation {:.3} kΩ.",
                    s.r0_std_ohm / 1e3
                ),
            );
        }
    }
}

impl crate::analysis::Analysis for RateResult {
    fn summary(&self) -> String {
        use std::fmt::Write;
        let r = self;
        let mut out = String::new();
        for s in &r.sensors {
            let _ = writeln!(
                out,
                "sensor {}: {} equal-amplitude cycles ({} smaller left out)",
                s.sensor,
                s.cycles.len(),
                s.smaller_cycles
            );
            for c in &s.cycles {
                let _ = writeln!(
                    out,
                    "  cycle {:>2}  rise {:>6.2} s  GF {:.4}  R0 {:.1} Ω",
                    c.number, c.rise_s, c.gauge_factor, c.r0_ohm
                );
            }
            let _ = writeln!(out,
            "  correlation of GF with rise time {:.4}; GF changes {:+.2} % from the fastest to the slowest",
            s.gf_rise_correlation,
            s.gf_relative_change * 100.0
        );
            let _ = writeln!(out, "  std dev of R0 {:.3} kΩ", s.r0_std_ohm / 1e3);
        }
        out
    }

    fn add_to_page(&self, page: &mut Page, at: crate::analysis::Placement<'_>) {
        self.section(page, at.label, at.figure_prefix);
    }
}
