//! Rate dependence (Section IV-A2, Fig. 5): the linear model fitted to each loading/unloading
//! cycle of equal amplitude, its gauge factor against the cycle's rise time with their
//! correlation coefficient, and its `R₀` against the cycle number with their standard
//! deviation.
//!
//! - **Cycles** are cut at the strain's turning points (`crate::fit::phases`, a turn needs the
//!   strain to come back by a tenth of its span). Only cycles whose rise reaches
//!   [`EQUAL_AMPLITUDE`] of the largest count, as the paper's protocol has one amplitude.
//! - **Rise time** is the time from 10 % to 90 % of the cycle's rise, divided by 0.8: the
//!   turning point at the start of a rise lies anywhere in the rest before it (the strain is
//!   flat there), so the time between turning points would add the rest's noise.
//! - **Per-cycle fit**: `R = R₀·GF·ε + R₀` by least squares on the cycle's moving samples
//!   (Eqs. 5-6): from where the rise leaves the rest (by [`REST_BAND`] of the rise) to where the
//!   fall comes back to it. The rests around a cycle take a larger share of a fast cycle, and on
//!   a hysteretic sensor they would tilt the line differently for fast and slow cycles.
//! - The **correlation coefficient** (Pearson's) of GF with rise time is scale-free: when GF
//!   barely varies it is the correlation of noise and can take any value. The relative change
//!   of GF over the range of rise times, from the least-squares slope, says how large the
//!   effect is; both are reported.

use dlw_estimator::SensorPlane;
use dlw_geometry::Joint;
use serde::Serialize;

use super::{figure_name, min_max, pearson, sensor_label, slope, std_dev, titled};
use super::{CharacterizeError, Options};
use crate::fit::{cycles, fit_linear, observe, phases, TURN_THRESHOLD};
use crate::report::{Chart, Page, Series, SeriesStyle, Table, PALETTE};
use crate::sim::Recording;

/// A cycle counts when its rise reaches this share of the largest rise.
pub const EQUAL_AMPLITUDE: f64 = 0.75;
/// Samples within this share of the rise from the cycle's start are rest, not fitted.
pub const REST_BAND: f64 = 0.02;
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
    /// The cycle's gauge factor.
    pub gauge_factor: f64,
    /// The cycle's `R₀` (Ω).
    pub r0_ohm: f64,
    /// r² of the cycle's fit.
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
        let obs = observe(recording, joint, plane, options.prefilter, None)?;
        // The joint's strain drives the cycles, for both sensors (sensor 2 reads −ε).
        let joint_strain: Vec<f64> = obs.strain.iter().map(|e| plane.sign() * e).collect();
        let (lo, hi) = min_max(&joint_strain);
        let all = cycles(&phases(&joint_strain, TURN_THRESHOLD * (hi - lo)));
        let rise_of =
            |c: &crate::fit::Cycle| joint_strain[c.loading.end] - joint_strain[c.loading.start];
        let largest = all.iter().map(rise_of).fold(0.0, f64::max);
        let mut out = Vec::new();
        let mut smaller = 0;
        for c in &all {
            let amp = rise_of(c);
            if amp < EQUAL_AMPLITUDE * largest {
                smaller += 1;
                continue;
            }
            let base = joint_strain[c.loading.start];
            let load = c.loading.start..=c.loading.end;
            let cross = |share: f64| {
                load.clone()
                    .find(|&i| joint_strain[i] >= base + share * amp)
                    .map(|i| obs.time_s[i])
            };
            let (Some(t10), Some(t90)) = (cross(0.1), cross(0.9)) else {
                continue;
            };
            // The moving part of the cycle: from where the rise leaves the rest to where the
            // fall reaches it again. The rests before and after vary in share with the
            // speed, and on a hysteretic sensor they would pull the line differently.
            let floor = base + REST_BAND * amp;
            let first = load.clone().find(|&i| joint_strain[i] >= floor);
            let last = (c.unloading.start..=c.unloading.end)
                .rev()
                .find(|&i| joint_strain[i] >= floor);
            let (Some(first), Some(last)) = (first, last) else {
                continue;
            };
            let r = first..=last;
            let fit = fit_linear(&obs.strain[r.clone()], &obs.ohm[r])?;
            out.push(RateCycle {
                number: out.len() + 1,
                start_s: t10,
                rise_s: (t90 - t10) / 0.8,
                amplitude_strain: amp,
                gauge_factor: fit.gauge_factor,
                r0_ohm: fit.r0_ohm,
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
    pub fn add_to_page(&self, page: &mut Page, label: &str, prefix: &str) {
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
