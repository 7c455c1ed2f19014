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

use super::robot::RobotRecording;
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

/// Block averages at about [`TARGET_HZ`]: `n` blocks of `step` consecutive rows each.
struct Blocks {
    step: usize,
    n: usize,
    dt_s: f64,
}

impl Blocks {
    /// The blocks of `rows` rows recorded at `sample_hz`.
    fn of(rows: usize, sample_hz: f64) -> Self {
        let step = ((sample_hz / TARGET_HZ).round() as usize).max(1);
        Self {
            step,
            n: rows / step,
            dt_s: step as f64 / sample_hz,
        }
    }

    /// The mean of block `k` of `v`.
    fn mean(&self, v: &[f64], k: usize) -> f64 {
        v[k * self.step..(k + 1) * self.step].iter().sum::<f64>() / self.step as f64
    }

    /// Every block's mean of `v`.
    fn column(&self, v: &[f64]) -> Vec<f64> {
        (0..self.n).map(|k| self.mean(v, k)).collect()
    }

    /// Whether every row of each block is `valid`.
    fn all(&self, valid: impl Fn(usize) -> bool) -> Vec<bool> {
        (0..self.n)
            .map(|k| (k * self.step..(k + 1) * self.step).all(&valid))
            .collect()
    }

    /// Each block's sensor resistance through `divider`, from voltage column `column` (1-based)
    /// at times `time_s`.
    ///
    /// # Errors
    /// The first block whose mean voltage no finite resistance explains.
    fn resistance(
        &self,
        volts: &[f64],
        divider: dlw_geometry::Divider,
        column: usize,
        time_s: &[f64],
    ) -> Result<Vec<f64>, Rail> {
        (0..self.n)
            .map(|k| {
                let v = self.mean(volts, k);
                divider
                    .resistance(v)
                    .ok()
                    .filter(|r| r.is_finite())
                    .ok_or(Rail {
                        column,
                        time_s: time_s[k * self.step],
                        volts: v,
                    })
            })
            .collect()
    }
}

impl Timeline {
    /// `rec` block-averaged: each sample the mean of `sample_hz/TARGET_HZ` rows.
    ///
    /// # Errors
    /// The first block whose mean voltage no finite resistance explains.
    pub fn of(rec: &Recording) -> Result<Self, Rail> {
        let s = &rec.samples;
        let blocks = Blocks::of(s.time_s.len(), rec.rig.sample_hz);
        let mut ohm = Vec::with_capacity(s.volts.len());
        // A recording holds one voltage column per divider, one or two (`Recording::read`).
        for ((c, volts), sensor) in s.volts.iter().enumerate().zip(Sensor::ALL) {
            let Some(divider) = rec.rig.divider(sensor) else {
                continue;
            };
            ohm.push(blocks.resistance(volts, divider, c + 1, &s.time_s)?);
        }
        let stroke_mm = blocks.column(&s.stroke_mm);
        Ok(Self {
            time_s: blocks.column(&s.time_s),
            rest: super::rest::rest_end(&stroke_mm, blocks.dt_s),
            stroke_mm,
            angle_deg: blocks.column(&s.angle_deg),
            ohm,
            measured: blocks.all(|i| s.angle_valid(i)),
            dt_s: blocks.dt_s,
        })
    }

    /// The columns the delays are measured on.
    pub fn columns(&self) -> Columns<'_> {
        Columns {
            time_s: &self.time_s,
            strokes: vec![&self.stroke_mm],
            angles: vec![&self.angle_deg],
            ohm: self.ohm.iter().map(Vec::as_slice).collect(),
            measured: &self.measured,
            rest: self.rest,
        }
    }
}

/// What the delays are measured on: block-averaged columns, one stroke and angle per joint (one
/// for a joint, several for a robot) and one resistance per sensor, borrowed from a
/// [`Timeline`] or a robot's.
#[derive(Debug, Clone)]
pub struct Columns<'a> {
    /// Time (s).
    pub time_s: &'a [f64],
    /// Each joint's stroke (mm).
    pub strokes: Vec<&'a [f64]>,
    /// Each joint's angle (°), read by one tracker: one clock.
    pub angles: Vec<&'a [f64]>,
    /// Each sensor's resistance (Ω).
    pub ohm: Vec<&'a [f64]>,
    /// Whether each sample's block has a tracker reading.
    pub measured: &'a [bool],
    /// Samples `0..rest` are the rest at the start.
    pub rest: usize,
}

/// The angle's delay against the stroke, and against the voltages (their resistances pooled
/// by inverse variance), over `data`'s motion; `None` when a block cannot be fitted.
pub fn delays(data: &Timeline) -> Option<(Delay, Delay)> {
    delays_of(&data.columns())
}

/// [`delays`] of several joints read by one tracker: each joint's angle against every stroke (a
/// line in each: a tendon may pass other joints), each resistance against every angle (a
/// parabola in each: a sensor also feels the joints it does not sit on), all shifted by one
/// delay; the joints' and the sensors' delays each pooled by inverse variance.
pub fn delays_of(data: &Columns) -> Option<(Delay, Delay)> {
    let n = data.time_s.len();
    let first = data.rest.min(n);
    let size = (n - first) / BLOCKS;
    if size < 10 || data.angles.is_empty() {
        return None;
    }
    let mut plant = vec![Vec::with_capacity(BLOCKS); data.angles.len()];
    let mut sensors = vec![Vec::with_capacity(BLOCKS); data.ohm.len()];
    for b in 0..BLOCKS {
        let rows = first + b * size..first + (b + 1) * size;
        let rows: Vec<usize> = rows.filter(|&i| data.measured[i]).collect();
        if rows.len() < 10 {
            return None;
        }
        let t: Vec<f64> = rows.iter().map(|&i| data.time_s[i]).collect();
        let columns = |vs: &[&[f64]]| -> Vec<Vec<f64>> {
            vs.iter()
                .map(|v| rows.iter().map(|&i| v[i]).collect())
                .collect()
        };
        let (strokes, angles) = (columns(&data.strokes), columns(&data.angles));
        for (p, angle) in plant.iter_mut().zip(&angles) {
            // The angle later than the strokes by `d`: the strokes shifted by `d` explain it.
            p.push(best_shift(&t, &strokes, angle, 1)?);
        }
        for (s, ohm) in sensors.iter_mut().zip(columns(&data.ohm)) {
            // The resistance later than the angles by `d`: the angles are late by `-d`.
            s.push(-best_shift(&t, &angles, &ohm, 2)?);
        }
    }
    let each = |estimates: &[Vec<f64>]| -> Option<Delay> {
        let delays: Vec<Delay> = estimates
            .iter()
            .map(|e| Delay::of(e))
            .collect::<Option<_>>()?;
        pooled(&delays)
    };
    Some((each(&plant)?, each(&sensors)?))
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
/// `degree` in each of `xs(t − d)` (linear interpolation of each `x`; held at its ends).
fn best_shift(t: &[f64], xs: &[Vec<f64>], y: &[f64], degree: usize) -> Option<f64> {
    let steps = (MAX_DELAY_S / STEP_S).round() as i64;
    let ss: Vec<f64> = (-steps..=steps)
        .map(|k| {
            let d = k as f64 * STEP_S;
            let shifted: Vec<Vec<f64>> = xs
                .iter()
                .map(|x| {
                    t.iter()
                        .map(|&ti| interpolate_held(t, x, ti - d).unwrap_or(f64::NAN))
                        .collect()
                })
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

/// The residual sum of squares of `y` fitted by an intercept and a polynomial of `degree` in
/// each of `xs` (least squares on centred, scaled `x`s, by its normal equations: a few columns,
/// well conditioned once scaled). A column that does not vary is left out; none varying gives
/// NaN.
fn residual_ss(xs: &[Vec<f64>], y: &[f64], degree: usize) -> f64 {
    let n = y.len() as f64;
    // Each varying `x`'s mean and scale.
    let scaled: Vec<(&Vec<f64>, f64, f64)> = xs
        .iter()
        .filter_map(|x| {
            let mean = x.iter().sum::<f64>() / n;
            let scale = (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
            (scale.is_finite() && scale > 0.0).then_some((x, mean, scale))
        })
        .collect();
    if scaled.is_empty() {
        return f64::NAN;
    }
    // `y` centred too: the intercept takes its mean, and `yᵀy` below stays of the order of
    // the residual's.
    let y_mean = y.iter().sum::<f64>() / n;
    let p = 1 + degree * scaled.len();
    let mut gram = nalgebra::DMatrix::<f64>::zeros(p, p);
    let mut xty = nalgebra::DVector::<f64>::zeros(p);
    let mut yty = 0.0;
    let mut row = vec![0.0; p];
    for (i, &y_raw) in y.iter().enumerate() {
        let yi = y_raw - y_mean;
        row[0] = 1.0;
        for (c, (x, mean, scale)) in scaled.iter().enumerate() {
            let u = (x[i] - mean) / scale;
            let mut power = 1.0;
            for k in 0..degree {
                power *= u;
                row[1 + c * degree + k] = power;
            }
        }
        for r in 0..p {
            xty[r] += row[r] * yi;
            for c in 0..p {
                gram[(r, c)] += row[r] * row[c];
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
pub fn tracker_delay(data: &Columns) -> Option<(Delay, Delay)> {
    let (plant, sensors) = delays_of(data)?;
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

/// Refuses the robot recording `rec` (read from folder `dir`) when its joints' angles, read by
/// one tracker, are late (or early) by one delay against both the strokes and the voltages
/// ([`delays_of`]: each angle against every stroke, each voltage against every angle, for the
/// tendons and sensors that pass other joints). A recording without per-joint angles is not
/// checked.
///
/// # Errors
/// [`RecordingError::TrackerDelay`] with both delays and their standard errors.
pub fn check_robot(rec: &RobotRecording, dir: &Path) -> Result<(), RecordingError> {
    let s = &rec.samples;
    if s.angle_deg.iter().any(Vec::is_empty) {
        return Ok(());
    }
    let blocks = Blocks::of(s.time_s.len(), rec.rig.sample_hz);
    let mut ohm = Vec::with_capacity(s.volts.len());
    for (c, (volts, &fixed_ohm)) in s.volts.iter().zip(&rec.rig.divider_ohm).enumerate() {
        let divider = dlw_geometry::Divider {
            fixed_ohm,
            supply_v: rec.rig.supply_v,
        };
        // A voltage no resistance explains: the analysis refuses it on its own terms.
        let Ok(r) = blocks.resistance(volts, divider, c + 1, &s.time_s) else {
            return Ok(());
        };
        ohm.push(r);
    }
    let strokes: Vec<Vec<f64>> = s.stroke_mm.iter().map(|v| blocks.column(v)).collect();
    let angles: Vec<Vec<f64>> = s.angle_deg.iter().map(|v| blocks.column(v)).collect();
    let time_s = blocks.column(&s.time_s);
    let measured = blocks.all(|i| s.tracker_valid_at(i));
    let columns = Columns {
        time_s: &time_s,
        strokes: strokes.iter().map(Vec::as_slice).collect(),
        angles: angles.iter().map(Vec::as_slice).collect(),
        ohm: ohm.iter().map(Vec::as_slice).collect(),
        measured: &measured,
        // The rest ends where the first joint moves.
        rest: strokes
            .iter()
            .map(|v| super::rest::rest_end(v, blocks.dt_s))
            .min()
            .unwrap_or(0),
    };
    refuse(dir, tracker_delay(&columns))
}

/// The refusal of [`check`] and [`check_robot`], when `found` holds the delays.
fn refuse(dir: &Path, found: Option<(Delay, Delay)>) -> Result<(), RecordingError> {
    let Some((plant, sensors)) = found else {
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

/// Refuses `rec` (read from folder `dir`) when its angle is late (or early) against both the
/// stroke and the voltages by one delay (module docs).
///
/// # Errors
/// [`RecordingError::TrackerDelay`] with both delays and their standard errors.
pub fn check(rec: &Recording, dir: &Path) -> Result<(), RecordingError> {
    let found = Timeline::of(rec)
        .ok()
        .and_then(|t| tracker_delay(&t.columns()));
    refuse(dir, found)
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
        assert_eq!(tracker_delay(&data.columns()), None);
    }

    #[test]
    fn a_late_tracker_is_refused_with_both_delays() {
        let (plant, sensors) = tracker_delay(&data(0.0, 0.08, 0.0).columns()).unwrap();
        assert!((plant.mean_s - 0.08).abs() < 0.005, "{plant:?}");
        assert!((sensors.mean_s - 0.08).abs() < 0.01, "{sensors:?}");
        let (plant, sensors) = tracker_delay(&data(0.0, -0.08, 0.0).columns()).unwrap();
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
