//! The tracker's clock against the DAQ's: a tracker whose angle reaches the recording late (an
//! EM tracker's latency, a clock offset the import left) makes the joint's angle lag its stroke
//! and the sensors' voltages by the same time.
//!
//! Every analysis that fits a model would take that for physics. On Joint A's clean recordings
//! (third generator) an angle 50 ms late made `discover` name `backlash` on the plant (seed 3),
//! and 200 ms late `rate` and `creep` on sensor 1 (seeds 3 and 4); `fit` wrote a gauge factor
//! 1 % low and a Prandtl-Ishlinskii loop the sensor does not have. Each with exit 0.
//!
//! Physics cannot do it, which is the property the check rests on. A plant effect makes the
//! angle lag the stroke, but the sensors (on the joint) then follow the angle, not the stroke; a
//! sensor effect makes a voltage lag or lead the angle, but leaves the angle on time against
//! the stroke. Only the angle's own timing moves both by one delay. So the delay of the angle
//! is measured twice, each by least squares over a grid of shifts (the angle against the
//! stroke, a line; each voltage's resistance against the angle, a parabola), in each of
//! [`BLOCKS`] blocks of the motion, and the recording is refused when both delays are
//! non-zero by at least [`Z_NONZERO`] standard errors (the spread of the blocks'), with the
//! same sign, and agree within [`Z_AGREE`] standard errors of their difference.
//!
//! It works on the recording block-averaged to about [`TARGET_HZ`] ([`Timeline`]), from the end
//! of the rest at the start ([`super::rest::rest_end`]), on the rows the tracker measured.
//! Where the motion is too slow to time the angle (a characterization's slow cycles: 200 ms
//! measured as 109 ± 37 ms against the stroke), the check cannot tell, and accepts.

use std::path::{Path, PathBuf};

use super::{Recording, RecordingError, DATA_FILE};
use crate::sensor::Sensor;
use crate::stats::interpolate_held;

/// The rate the delays are measured at (Hz): each sample is the mean of `sample_hz/TARGET_HZ`
/// recorded ones. A 5 ms grid is refined below a sample by the parabola through its minimum.
pub const TARGET_HZ: f64 = 25.0;
/// Blocks of the motion, each giving one estimate of each delay.
pub const BLOCKS: usize = 11;
/// The largest delay looked for (s).
pub const MAX_DELAY_S: f64 = 0.3;
/// The grid's step (s); the least squares' minimum is refined by a parabola through its
/// neighbours.
pub const STEP_S: f64 = 0.005;
/// How many standard errors from zero each delay must be.
pub const Z_NONZERO: f64 = 4.0;
/// How many standard errors of their difference the two delays may differ by.
pub const Z_AGREE: f64 = 3.0;

/// A delay measured over the blocks: their mean and its standard error (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Delay {
    /// Mean over the blocks (s).
    pub mean_s: f64,
    /// Standard error of the mean (s).
    pub se_s: f64,
}

impl Delay {
    fn of(estimates: &[f64]) -> Option<Self> {
        let n = estimates.len();
        if n < 3 {
            return None;
        }
        let mean_s = estimates.iter().sum::<f64>() / n as f64;
        let var = estimates.iter().map(|d| (d - mean_s).powi(2)).sum::<f64>() / (n - 1) as f64;
        let se_s = (var / n as f64).sqrt();
        (mean_s.is_finite() && se_s.is_finite()).then_some(Self { mean_s, se_s })
    }

    /// How many standard errors from zero (infinite for an exact, non-zero delay).
    fn z(self) -> f64 {
        if self.se_s > 0.0 {
            self.mean_s.abs() / self.se_s
        } else if self.mean_s != 0.0 {
            f64::INFINITY
        } else {
            0.0
        }
    }
}

/// A recording block-averaged to about [`TARGET_HZ`]: what the delays are measured on, and what
/// discovery works on (`discover::data::Data` adds the strain and its checks).
#[derive(Debug, Clone)]
pub struct Timeline {
    /// Time (s).
    pub time_s: Vec<f64>,
    /// Tendon stroke (mm).
    pub stroke_mm: Vec<f64>,
    /// Tracker angle (°).
    pub angle_deg: Vec<f64>,
    /// Each divider's sensor resistance (Ω).
    pub ohm: Vec<Vec<f64>>,
    /// Whether every row of each sample's block has a tracker angle (`tracker_valid`).
    pub measured: Vec<bool>,
    /// Samples `0..rest` are the rest at the start: up to the stroke's first motion
    /// ([`super::rest::rest_end`]).
    pub rest: usize,
    /// Sample spacing (s).
    pub dt_s: f64,
}

/// A block whose mean voltage no finite sensor resistance explains ([`Timeline::of`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rail {
    /// The voltage column (1-based).
    pub column: usize,
    /// The block's first time (s).
    pub time_s: f64,
    /// The block's mean voltage (V).
    pub volts: f64,
}

impl Timeline {
    /// `rec` block-averaged: each sample the mean of `sample_hz/TARGET_HZ` rows.
    ///
    /// # Errors
    /// The first block whose mean voltage no finite resistance explains.
    pub fn of(rec: &Recording) -> Result<Self, Rail> {
        let s = &rec.samples;
        let step = ((rec.rig.sample_hz / TARGET_HZ).round() as usize).max(1);
        let n = s.time_s.len() / step;
        let mean =
            |v: &[f64], k: usize| v[k * step..(k + 1) * step].iter().sum::<f64>() / step as f64;
        let column = |v: &[f64]| -> Vec<f64> { (0..n).map(|k| mean(v, k)).collect() };
        let mut ohm = Vec::with_capacity(s.volts.len());
        // A recording holds one voltage column per divider, one or two (`Recording::read`).
        for ((c, volts), sensor) in s.volts.iter().enumerate().zip(Sensor::ALL) {
            let Some(divider) = rec.rig.divider(sensor) else {
                continue;
            };
            let r: Vec<f64> = (0..n)
                .map(|k| {
                    let v = mean(volts, k);
                    divider
                        .resistance(v)
                        .ok()
                        .filter(|r| r.is_finite())
                        .ok_or(Rail {
                            column: c + 1,
                            time_s: s.time_s[k * step],
                            volts: v,
                        })
                })
                .collect::<Result<_, _>>()?;
            ohm.push(r);
        }
        let stroke_mm = column(&s.stroke_mm);
        let dt_s = step as f64 / rec.rig.sample_hz;
        Ok(Self {
            time_s: column(&s.time_s),
            rest: super::rest::rest_end(&stroke_mm, dt_s),
            stroke_mm,
            angle_deg: column(&s.angle_deg),
            ohm,
            measured: (0..n)
                .map(|k| (k * step..(k + 1) * step).all(|i| s.angle_valid(i)))
                .collect(),
            dt_s,
        })
    }

    fn len(&self) -> usize {
        self.time_s.len()
    }
}

/// The angle's delay against the stroke, and against the voltages (their resistances pooled
/// by inverse variance), over `data`'s motion; `None` when a block cannot be fitted.
pub fn delays(data: &Timeline) -> Option<(Delay, Delay)> {
    let first = data.rest.min(data.len());
    let moving = data.len() - first;
    let size = moving / BLOCKS;
    if size < 10 {
        return None;
    }
    let mut plant = Vec::with_capacity(BLOCKS);
    let mut sensors = vec![Vec::with_capacity(BLOCKS); data.ohm.len()];
    for b in 0..BLOCKS {
        let rows = first + b * size..first + (b + 1) * size;
        let rows: Vec<usize> = rows.filter(|&i| data.measured[i]).collect();
        if rows.len() < 10 {
            return None;
        }
        let t: Vec<f64> = rows.iter().map(|&i| data.time_s[i]).collect();
        let column = |v: &[f64]| -> Vec<f64> { rows.iter().map(|&i| v[i]).collect() };
        let angle = column(&data.angle_deg);
        // The angle later than the stroke by `d`: the stroke shifted by `d` explains it.
        plant.push(best_shift(&t, &column(&data.stroke_mm), &angle, 1)?);
        for (s, ohm) in sensors.iter_mut().zip(&data.ohm) {
            // The resistance later than the angle by `d`: the angle is late by `-d`.
            s.push(-best_shift(&t, &angle, &column(ohm), 2)?);
        }
    }
    let sensor_delays: Vec<Delay> = sensors
        .iter()
        .map(|s| Delay::of(s))
        .collect::<Option<_>>()?;
    Some((Delay::of(&plant)?, pooled(&sensor_delays)?))
}

/// Inverse-variance pooling of several measurements of one delay.
fn pooled(delays: &[Delay]) -> Option<Delay> {
    if delays.len() == 1 {
        return Some(delays[0]);
    }
    let weights: Vec<f64> = delays
        .iter()
        .map(|d| 1.0 / d.se_s.powi(2).max(f64::MIN_POSITIVE))
        .collect();
    let total: f64 = weights.iter().sum();
    let mean_s = delays
        .iter()
        .zip(&weights)
        .map(|(d, w)| d.mean_s * w)
        .sum::<f64>()
        / total;
    let se_s = (1.0 / total).sqrt();
    (mean_s.is_finite() && se_s.is_finite()).then_some(Delay { mean_s, se_s })
}

/// The shift `d` (s) of the grid, refined, for which `y(t)` is best fitted by a polynomial of
/// `degree` in `x(t − d)` (linear interpolation of `x`; held at its ends).
fn best_shift(t: &[f64], x: &[f64], y: &[f64], degree: usize) -> Option<f64> {
    let steps = (MAX_DELAY_S / STEP_S).round() as i64;
    let ss: Vec<f64> = (-steps..=steps)
        .map(|k| {
            let d = k as f64 * STEP_S;
            let shifted: Vec<f64> = t
                .iter()
                .map(|&ti| interpolate_held(t, x, ti - d).unwrap_or(f64::NAN))
                .collect();
            residual_ss(&shifted, y, degree)
        })
        .collect();
    let (i, _) = ss
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .min_by(|a, b| a.1.total_cmp(b.1))?;
    let refine = if i > 0 && i + 1 < ss.len() {
        let curvature = ss[i - 1] - 2.0 * ss[i] + ss[i + 1];
        if curvature > 0.0 {
            0.5 * (ss[i - 1] - ss[i + 1]) / curvature
        } else {
            0.0
        }
    } else {
        0.0
    };
    Some((i as f64 - steps as f64 + refine) * STEP_S)
}

/// The residual sum of squares of `y` fitted by a polynomial of `degree` in `x` (least
/// squares on centred, scaled `x`, by its normal equations: at most three columns, well
/// conditioned once scaled).
fn residual_ss(x: &[f64], y: &[f64], degree: usize) -> f64 {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let scale = (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    if scale.is_nan() || scale <= 0.0 {
        return f64::NAN;
    }
    // `y` centred too: the intercept takes its mean, and `yᵀy` below stays of the order of
    // the residual's.
    let y_mean = y.iter().sum::<f64>() / n;
    let p = degree + 1;
    let mut gram = nalgebra::DMatrix::<f64>::zeros(p, p);
    let mut xty = nalgebra::DVector::<f64>::zeros(p);
    let mut yty = 0.0;
    let mut powers = vec![0.0; p];
    for (&xi, &y_raw) in x.iter().zip(y) {
        let yi = y_raw - y_mean;
        let u = (xi - mean) / scale;
        powers[0] = 1.0;
        for k in 1..p {
            powers[k] = powers[k - 1] * u;
        }
        for r in 0..p {
            xty[r] += powers[r] * yi;
            for c in 0..p {
                gram[(r, c)] += powers[r] * powers[c];
            }
        }
        yty += yi * yi;
    }
    let Some(beta) = gram.clone().cholesky().map(|c| c.solve(&xty)) else {
        return f64::NAN;
    };
    // ‖y − Xβ‖² = yᵀy − 2βᵀXᵀy + βᵀXᵀXβ = yᵀy − βᵀXᵀy at the least-squares β.
    (yty - beta.dot(&xty)).max(0.0)
}

/// The angle's delays against the stroke and the voltages, when they show the tracker's clock
/// off the DAQ's (module docs): both non-zero, of one sign, and agreeing.
pub fn tracker_delay(data: &Timeline) -> Option<(Delay, Delay)> {
    let (plant, sensors) = delays(data)?;
    let both = plant.z() >= Z_NONZERO && sensors.z() >= Z_NONZERO;
    let same_sign = plant.mean_s.signum() == sensors.mean_s.signum();
    let apart = (plant.mean_s - sensors.mean_s).abs();
    let agree = apart <= Z_AGREE * plant.se_s.hypot(sensors.se_s);
    (both && same_sign && agree).then_some((plant, sensors))
}

/// A recording whose tracker's clock is off the DAQ's ([`RecordingError::TrackerDelay`]).
#[derive(Debug, thiserror::Error)]
#[error("{path}: the tracker's angle is {late} by one delay against both the DAQ's channels: {stroke_ms:.1} ± {stroke_se_ms:.1} ms against the stroke and {voltage_ms:.1} ± {voltage_se_ms:.1} ms against the sensors' voltages (each at least {z} standard errors from zero, and within {agree} of each other). No plant effect moves the sensors with the angle, and no sensor effect moves the angle against the stroke: the tracker's clock is off the DAQ's, and a model fitted to it would take the delay for physics (`discover` a plant's play or a sensor's rate, `fit` a loop the sensor does not have). Align the clocks (shift angle_deg by the delay) and run it again", late = if *stroke_ms > 0.0 { "late" } else { "early" }, agree = Z_AGREE)]
pub struct TrackerDelay {
    /// The recording's data file.
    pub path: PathBuf,
    /// The angle's delay against the stroke (ms).
    pub stroke_ms: f64,
    /// Its standard error (ms).
    pub stroke_se_ms: f64,
    /// The angle's delay against the voltages (ms).
    pub voltage_ms: f64,
    /// Its standard error (ms).
    pub voltage_se_ms: f64,
    /// Standard errors each must be from zero.
    pub z: f64,
}

/// Refuses `rec` (read from folder `dir`) when its angle is late (or early) against both the
/// stroke and the voltages by one delay (module docs).
///
/// # Errors
/// [`RecordingError::TrackerDelay`] with both delays and their standard errors.
pub fn check(rec: &Recording, dir: &Path) -> Result<(), RecordingError> {
    let Some((plant, sensors)) = Timeline::of(rec).ok().and_then(|t| tracker_delay(&t)) else {
        return Ok(());
    };
    Err(RecordingError::TrackerDelay(Box::new(TrackerDelay {
        path: dir.join(DATA_FILE),
        stroke_ms: 1e3 * plant.mean_s,
        stroke_se_ms: 1e3 * plant.se_s,
        voltage_ms: 1e3 * sensors.mean_s,
        voltage_se_ms: 1e3 * sensors.se_s,
        z: Z_NONZERO,
    })))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recording::clipping::tests::uniform;

    /// A motion of two sines after a 10 s rest at 25 Hz: the stroke, the joint's angle
    /// `plant_lag_s` behind it, the tracker's reading `tracker_lag_s` behind the angle, and a
    /// resistance `sensor_lag_s` behind the angle, each with noise.
    fn data(plant_lag_s: f64, tracker_lag_s: f64, sensor_lag_s: f64) -> Timeline {
        let dt_s = 0.04;
        let n = 7500;
        let stroke = |t: f64| {
            if t < 10.0 {
                0.0
            } else {
                let u = t - 10.0;
                0.3 * (1.0 - (0.9 * u).cos()) + 0.1 * (2.3 * u).sin().powi(2)
            }
        };
        let angle = |t: f64| 35.0 * stroke(t - plant_lag_s);
        let mut state = 7_u64;
        let mut noise = |scale: f64| scale * uniform(&mut state);
        let time_s: Vec<f64> = (0..n).map(|i| i as f64 * dt_s).collect();
        Timeline {
            stroke_mm: time_s.iter().map(|&t| stroke(t)).collect(),
            angle_deg: time_s
                .iter()
                .map(|&t| angle(t - tracker_lag_s) + noise(0.2))
                .collect(),
            ohm: vec![time_s
                .iter()
                .map(|&t| 180e3 + 400.0 * angle(t - sensor_lag_s) + noise(100.0))
                .collect()],
            rest: 250,
            measured: vec![true; n],
            time_s,
            dt_s,
        }
    }

    /// No tracker delay found.
    fn quiet(data: &Timeline) {
        assert_eq!(tracker_delay(data), None);
    }

    #[test]
    fn a_late_tracker_is_refused_with_both_delays() {
        let (plant, sensors) = tracker_delay(&data(0.0, 0.08, 0.0)).unwrap();
        assert!((plant.mean_s - 0.08).abs() < 0.005, "{plant:?}");
        assert!((sensors.mean_s - 0.08).abs() < 0.01, "{sensors:?}");
        let (plant, sensors) = tracker_delay(&data(0.0, -0.08, 0.0)).unwrap();
        assert!(
            plant.mean_s < 0.0 && sensors.mean_s < 0.0,
            "{plant:?} {sensors:?}"
        );
    }

    #[test]
    fn a_lagging_joint_or_sensor_is_physics_and_is_accepted() {
        // The joint lags its stroke: the sensor follows the joint, not the stroke.
        let (plant, sensors) = delays(&data(0.08, 0.0, 0.0)).unwrap();
        assert!((plant.mean_s - 0.08).abs() < 0.005, "{plant:?}");
        assert!(sensors.mean_s.abs() < 0.01, "{sensors:?}");
        quiet(&data(0.08, 0.0, 0.0));
        // The sensor lags the joint, or leads it (a rate term): the angle is on time.
        quiet(&data(0.0, 0.0, 0.08));
        quiet(&data(0.0, 0.0, -0.08));
        // On time.
        quiet(&data(0.0, 0.0, 0.0));
    }
}
