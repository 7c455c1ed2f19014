//! A channel's model: its base (a line) plus the terms named so far, built as columns over a
//! recording and fitted by whitened least squares.

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use super::data::Data;
use super::noise::ArNoise;
use super::signed::{self, Sign};
use super::terms::{hinges, low_pass, play, rate, Term, LOG_REFERENCE_RATE};
use crate::sensor::Sensor;

/// Which stage of the bench's chain a model explains: the plant (stroke → angle) or a sensor
/// (angle → resistance). What users see calls it a **channel** (the JSON's `channel` and
/// `channels`, the report's tables, the messages), which the outputs fix; in the code a
/// channel is a DAQ's (`import`), so the type has its own name (`docs/architecture.md`,
/// "Names").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    /// Stroke → tracker angle.
    Plant,
    /// Tracker angle → resistance of sensor 1 or 2.
    Sensor(Sensor),
}

impl Stage {
    /// `plant`, `sensor1`, `sensor2`.
    pub fn name(self) -> String {
        match self {
            Stage::Plant => "plant".to_owned(),
            Stage::Sensor(sensor) => sensor.key().to_owned(),
        }
    }

    /// The channel's unit.
    pub fn unit(self) -> &'static str {
        match self {
            Stage::Plant => "deg",
            Stage::Sensor(_) => "ohm",
        }
    }
}

impl Serialize for Stage {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

/// A channel's model: the base line and the terms.
#[derive(Debug, Clone, PartialEq)]
pub struct StageModel {
    /// The channel.
    pub channel: Stage,
    /// Terms in the order they were added.
    pub terms: Vec<Term>,
}

/// The columns and the target of a model over one recording.
#[derive(Debug, Clone)]
pub struct Design {
    /// Regressors, one per coefficient; the first is the constant, the second the input.
    pub columns: Vec<Vec<f64>>,
    /// The measured channel.
    pub target: Vec<f64>,
    /// What each column is (for the parameters).
    pub labels: Vec<&'static str>,
}

impl StageModel {
    /// The base model of `channel`.
    pub fn base(channel: Stage) -> Self {
        Self {
            channel,
            terms: Vec::new(),
        }
    }

    /// This model with `term` added (a shape term replaces one of its kind).
    pub fn with(&self, term: Term) -> Self {
        let mut m = self.clone();
        m.terms.retain(|t| t.effect() != term.effect());
        m.terms.push(term);
        m
    }

    /// The felt strain of a sensor channel (sensor 2 of a BSN joint reads `−ε`).
    pub fn felt(&self, data: &Data) -> Vec<f64> {
        let sign = if self.channel == Stage::Sensor(Sensor::Two) {
            -1.0
        } else {
            1.0
        };
        data.strain.iter().map(|e| sign * e).collect()
    }

    /// The columns over `data`. A sensor's candidate terms (plays, rate, creep) are built from
    /// `proxy`, the strain of an angle with the tracker's fast noise taken out
    /// ([`super::proxy`]); its base input stays the strain of the tracker angle itself.
    pub fn design(&self, data: &Data, proxy: &[f64]) -> Design {
        let n = data.len();
        let mut columns = vec![vec![1.0; n]];
        let mut labels = vec!["offset"];
        let (target, input, driver) = self.inputs(data, proxy);
        for t in &self.terms {
            term_columns(t, &driver, &input, data, &mut columns, &mut labels);
        }
        columns.insert(1, input);
        labels.insert(1, "gain");
        if let Stage::Sensor(_) = self.channel {
            // The proxy beside the tracker strain: the base may already weigh the noise-free
            // input against the noisy one, so no candidate gains by denoising the input.
            columns.insert(2, driver.clone());
            labels.insert(2, "gain_proxy");
        }
        Design {
            columns,
            target,
            labels,
        }
    }

    /// The channel's target, its base input and the input its candidate terms are built from
    /// (after a backlash or a saturation already named).
    fn inputs(&self, data: &Data, proxy: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        match self.channel {
            Stage::Plant => {
                let mut u = data.stroke_mm.clone();
                for t in &self.terms {
                    if let Term::Backlash { half_mm } = t {
                        u = play(&u, *half_mm);
                    }
                }
                (data.angle_deg.clone(), u.clone(), u)
            }
            Stage::Sensor(sensor) => {
                let sign = sensor.plane().sign();
                let mut x = self.felt(data);
                let mut xp: Vec<f64> = proxy.iter().map(|e| sign * e).collect();
                for t in &self.terms {
                    if let Term::Saturation { strain } = t {
                        let sat = |v: &f64| strain * (v / strain).tanh();
                        x = x.iter().map(sat).collect();
                        xp = xp.iter().map(sat).collect();
                    }
                }
                (data.ohm[sensor.index()].clone(), x, xp)
            }
        }
    }
}

/// The columns one term adds to a design, built from `driver` (a gain drift from `input`).
fn term_columns(
    t: &Term,
    driver: &[f64],
    input: &[f64],
    data: &Data,
    columns: &mut Vec<Vec<f64>>,
    labels: &mut Vec<&'static str>,
) {
    match t {
        Term::Relaxation { tau_s } => {
            columns.push(low_pass(driver, *tau_s, data.dt_s));
            labels.push("relaxation");
        }
        Term::Creep { tau_s, fast_tau_s } => {
            columns.push(low_pass(driver, *tau_s, data.dt_s));
            labels.push("creep");
            if let Some(f) = fast_tau_s {
                columns.push(low_pass(driver, *f, data.dt_s));
                labels.push("creep_fast");
            }
        }
        Term::Prony { taus_s } => {
            for tau in taus_s {
                columns.push(low_pass(driver, *tau, data.dt_s));
                labels.push("prony");
            }
        }
        Term::RelaxationSpread { taus_s } => {
            for tau in taus_s {
                columns.push(low_pass(driver, *tau, data.dt_s));
                labels.push("relaxation_term");
            }
        }
        Term::Hysteresis {
            radii,
            center,
            width,
            memory,
            knots,
        } => {
            let nu: Vec<f64> = driver
                .iter()
                .map(|x| width * ((x - center) / width).tanh())
                .collect();
            columns.push(nu.clone());
            labels.push("curve");
            for hinge in hinges(driver, knots) {
                columns.push(hinge);
                labels.push("static");
            }
            if !memory {
                return;
            }
            for &r in radii {
                columns.push(play(&nu, r));
                labels.push("play");
            }
            // The generalized PI's direction switch (Eq. 10): the slope differs
            // between loading and unloading. The direction is how far the input sits
            // from its smallest play, −1 (unloading) to 1 (loading).
            if let Some(&r) = radii.first() {
                let p = play(&nu, r);
                columns.push(nu.iter().zip(&p).map(|(x, y)| (x - y) / r * x).collect());
                labels.push("direction");
            }
        }
        Term::Rate { signed, tau_s } => {
            let r = rate(driver, data.dt_s);
            if *signed {
                columns.push(low_pass(&r, *tau_s, data.dt_s));
            } else {
                let abs: Vec<f64> = r.iter().map(|v| v.abs()).collect();
                let smooth = low_pass(&abs, *tau_s, data.dt_s);
                columns.push(
                    driver
                        .iter()
                        .zip(&smooth)
                        .map(|(x, s)| x * (1.0 + s / LOG_REFERENCE_RATE).log10())
                        .collect(),
                );
            }
            labels.push("rate");
        }
        Term::Drift { settle_tau_s } => {
            let t0 = data.time_s[0];
            columns.push(
                data.time_s
                    .iter()
                    .map(|t| match settle_tau_s {
                        None => t - t0,
                        Some(tau) => 1.0 - (-(t - t0) / tau).exp(),
                    })
                    .collect(),
            );
            labels.push("drift");
        }
        Term::Wander { knot_s } => {
            for c in super::unexplained::wander_splines(data, *knot_s) {
                columns.push(c);
                labels.push("wander");
            }
        }
        Term::GainDrift => {
            let t0 = data.time_s[0];
            columns.push(
                input
                    .iter()
                    .zip(&data.time_s)
                    .map(|(x, t)| x * (t - t0))
                    .collect(),
            );
            labels.push("gain_drift");
        }
        Term::Backlash { .. } | Term::Saturation { .. } => {}
    }
}

/// A model fitted on one recording's training samples.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// Coefficients, one per column.
    pub coef: Vec<f64>,
    /// Column labels.
    pub labels: Vec<&'static str>,
    /// Whitened sum of squares on the training samples.
    pub train_ss: f64,
}

/// Whitened least squares of `design` over the samples where `train` holds.
pub fn fit(design: &Design, noise: &ArNoise, train: &[bool]) -> Option<Fitted> {
    let rows: Vec<usize> = (0..train.len()).filter(|&i| train[i]).collect();
    let p = design.columns.len();
    if rows.len() <= p {
        return None;
    }
    let white_cols: Vec<Vec<f64>> = design.columns.iter().map(|c| noise.whiten(c)).collect();
    let white_y = noise.whiten(&design.target);
    // Scale the columns so the solve is well conditioned whatever the units.
    let scales: Vec<f64> = white_cols
        .iter()
        .map(|c| {
            let s = (rows.iter().map(|&i| c[i] * c[i]).sum::<f64>() / rows.len() as f64).sqrt();
            if s > 0.0 && s.is_finite() {
                s
            } else {
                1.0
            }
        })
        .collect();
    let x = DMatrix::from_fn(rows.len(), p, |r, c| white_cols[c][rows[r]] / scales[c]);
    let y = DVector::from_iterator(rows.len(), rows.iter().map(|&i| white_y[i]));
    let mut solution = x.clone().svd(true, true).solve(&y, 1e-10).ok()?;
    if let Some(signs) = relaxation_signs(&design.labels, &solution) {
        solution = signed::least_squares(&x, &y, &signs)?;
    }
    let coef: Vec<f64> = solution.iter().zip(&scales).map(|(b, s)| b / s).collect();
    if !coef.iter().all(|c| c.is_finite()) {
        return None;
    }
    let residual = &y - &x * &solution;
    Some(Fitted {
        coef,
        labels: design.labels.clone(),
        train_ss: residual.norm_squared(),
    })
}

/// The signs a relaxation's spread must have ([`Term::RelaxationSpread`]), when its free fit
/// breaks them: each term's share of the elastic angle at least zero, so each coefficient of
/// the sign opposite to the gain's (`θ = g·u − Σ fₖ·g·LP_τk(u)`). `None` when the design has
/// no spread or the free fit already keeps them.
pub(super) fn relaxation_signs(labels: &[&'static str], free: &DVector<f64>) -> Option<Vec<Sign>> {
    let gain = labels.iter().position(|l| *l == "gain").map(|j| free[j])?;
    let held = if gain >= 0.0 {
        Sign::NonPositive
    } else {
        Sign::NonNegative
    };
    let spread = |l: &&str| *l == "relaxation_term";
    let broken = labels
        .iter()
        .zip(free.iter())
        .any(|(l, c)| spread(l) && c * gain > 0.0);
    broken.then(|| {
        labels
            .iter()
            .map(|l| if spread(l) { held } else { Sign::Free })
            .collect()
    })
}

impl Fitted {
    /// The model's prediction over `design`'s recording.
    pub fn predict(&self, design: &Design) -> Vec<f64> {
        let n = design.target.len();
        (0..n)
            .map(|i| {
                design
                    .columns
                    .iter()
                    .zip(&self.coef)
                    .map(|(c, b)| c[i] * b)
                    .sum()
            })
            .collect()
    }

    /// The residual `measured − model` over `design`'s recording.
    pub fn residual(&self, design: &Design) -> Vec<f64> {
        let p = self.predict(design);
        design.target.iter().zip(&p).map(|(y, m)| y - m).collect()
    }

    /// The input's gain: `gain`, plus `gain_proxy` for a sensor (Ω per unit strain, or °/mm).
    pub fn gain(&self) -> f64 {
        self.get("gain").unwrap_or(f64::NAN) + self.get("gain_proxy").unwrap_or(0.0)
    }

    /// The coefficient of the first column labelled `label`.
    pub fn get(&self, label: &str) -> Option<f64> {
        self.labels
            .iter()
            .position(|l| *l == label)
            .map(|i| self.coef[i])
    }

    /// Coefficients of every column labelled `label`.
    pub fn all(&self, label: &str) -> Vec<f64> {
        self.labels
            .iter()
            .zip(&self.coef)
            .filter(|(l, _)| **l == label)
            .map(|(_, c)| *c)
            .collect()
    }
}

/// How many correlated samples count as one in `residual` (whitened) over `mask`: the
/// integrated autocorrelation `1 + 2·Σₖ ρₖ` over lags up to `max_lag` (at least 1).
///
/// The noise model is frozen from a rest of seconds, too short to see the slowest wander of
/// the noise; what it leaves correlated would count as independent evidence. Dividing the
/// evidence by this factor, measured on the candidate model's own training residual (noise,
/// if the candidate captured the effect), keeps the evidence in units of independent samples.
pub fn correlation_time(residual: &[f64], noise: &ArNoise, mask: &[bool], max_lag: usize) -> f64 {
    correlation_time_white(&noise.whiten(residual), mask, max_lag)
}

/// [`correlation_time`] of a residual already whitened.
///
/// Every lag's sum over the masked pairs comes from one FFT of the zero-filled residual and the
/// mask, in O(n log n) where a sum per lag cost O(n) for each of up to n/100 lags. The result
/// agrees with the per-lag sums to rounding (`tests::the_fft_correlation_time_is_the_summed_one`).
pub fn correlation_time_white(w: &[f64], mask: &[bool], max_lag: usize) -> f64 {
    let mask = &mask[..w.len()];
    let n = mask.iter().filter(|&&m| m).count();
    if n < 2 * max_lag + 2 {
        return 1.0;
    }
    let masked = || w.iter().zip(mask).filter(|(_, &m)| m).map(|(x, _)| *x);
    let mean = masked().sum::<f64>() / n as f64;
    let var = masked().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
    if var.is_nan() || var <= 0.0 {
        return 1.0;
    }
    // Past `max_lag`, the sum goes on as long as the window stays under a hundredth of the
    // samples (the partial sums' noise grows as √(window/n)), and the largest partial sum counts:
    // noise slower than the rest could show leaves correlation there.
    let longest = max_lag
        .max((n / LONG_WINDOW_DIVISOR).min(LONG_WINDOW_FACTOR * max_lag))
        .min(w.len() - 1);
    let sd = var.sqrt();
    let standardized: Vec<f64> = w
        .iter()
        .zip(mask)
        .map(|(x, &m)| if m { (x - mean) / sd } else { 0.0 })
        .collect();
    let mut tau: f64 = 1.0;
    let mut largest: f64 = 1.0;
    for (k, (c, m)) in (1..).zip(masked_autocorrelation(&standardized, mask, longest)) {
        if m == 0 {
            break;
        }
        tau += 2.0 * c / m as f64;
        if k >= max_lag {
            largest = largest.max(tau);
        }
    }
    largest.max(1.0)
}

/// For lags 1..=`longest`: the sum of `x[i]·x[i+k]` (zero outside the mask) and the number of
/// pairs with both samples in `mask`. One complex FFT carries both real sequences (`x` as the
/// real part, the mask as the imaginary part); their power spectra, real and even, come back
/// together from one inverse FFT. The pair counts are integers, rounded from the transform.
fn masked_autocorrelation(x: &[f64], mask: &[bool], longest: usize) -> Vec<(f64, usize)> {
    use rustfft::num_complex::Complex;
    let len = (x.len() + longest + 1).next_power_of_two();
    let mut planner = rustfft::FftPlannerScalar::<f64>::new();
    let mut z: Vec<Complex<f64>> = x
        .iter()
        .zip(mask)
        .map(|(&v, &m)| Complex::new(v, f64::from(u8::from(m))))
        .chain(std::iter::repeat(Complex::new(0.0, 0.0)))
        .take(len)
        .collect();
    planner.plan_fft_forward(len).process(&mut z);
    let mut power: Vec<Complex<f64>> = (0..len)
        .map(|k| {
            let (zk, zr) = (z[k], z[(len - k) % len].conj());
            let signal = (zk + zr) * 0.5;
            let indicator = (zk - zr) * Complex::new(0.0, -0.5);
            Complex::new(signal.norm_sqr(), indicator.norm_sqr())
        })
        .collect();
    planner.plan_fft_inverse(len).process(&mut power);
    let scale = 1.0 / len as f64;
    power[1..=longest]
        .iter()
        .map(|p| (p.re * scale, (p.im * scale).round().max(0.0) as usize))
        .collect()
}

/// The long window is at most this fraction (1/…) of the samples…
pub const LONG_WINDOW_DIVISOR: usize = 100;
/// …and at most this many times the base window.
pub const LONG_WINDOW_FACTOR: usize = 15;

/// Whitened sum of squares and plain RMS of `residual` over `mask`.
pub fn score(residual: &[f64], noise: &ArNoise, mask: &[bool]) -> (f64, f64, usize) {
    let w = noise.whiten(residual);
    let (mut ss, mut plain, mut n) = (0.0, 0.0, 0usize);
    for i in 0..residual.len() {
        if mask[i] {
            ss += w[i] * w[i];
            plain += residual[i] * residual[i];
            n += 1;
        }
    }
    (ss, (plain / n.max(1) as f64).sqrt(), n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discover::noise::tests::ar1;

    /// The sums as they were written before the FFT: one lag at a time, over the masked
    /// samples' indices.
    fn correlation_time_by_index(w: &[f64], mask: &[bool], max_lag: usize) -> f64 {
        let idx: Vec<usize> = (0..w.len()).filter(|&i| mask[i]).collect();
        if idx.len() < 2 * max_lag + 2 {
            return 1.0;
        }
        let mean = idx.iter().map(|&i| w[i]).sum::<f64>() / idx.len() as f64;
        let var = idx.iter().map(|&i| (w[i] - mean).powi(2)).sum::<f64>() / idx.len() as f64;
        if var.is_nan() || var <= 0.0 {
            return 1.0;
        }
        let longest =
            max_lag.max((idx.len() / LONG_WINDOW_DIVISOR).min(LONG_WINDOW_FACTOR * max_lag));
        let (mut tau, mut largest) = (1.0f64, 1.0f64);
        for k in 1..=longest {
            let (mut c, mut m) = (0.0, 0usize);
            for &i in &idx {
                if i + k < w.len() && mask[i + k] {
                    c += (w[i] - mean) * (w[i + k] - mean);
                    m += 1;
                }
            }
            if m == 0 {
                break;
            }
            tau += 2.0 * (c / m as f64 / var);
            if k >= max_lag {
                largest = largest.max(tau);
            }
        }
        largest.max(1.0)
    }

    proptest::proptest! {
        /// Any residual (slow or white, with NaN outside the mask, at any scale), any mask of
        /// blocks and holes, any window: the FFT's correlation time is the summed one to
        /// within 1e-9 of it.
        #[test]
        fn the_fft_correlation_time_is_the_summed_one(
            n in 1usize..3000,
            phi in 0.0f64..0.99,
            seed in 0u64..1000,
            block in 1usize..400,
            keep in 0.05f64..1.0,
            max_lag in 1usize..60,
            scale in -12i32..12,
        ) {
            let skip = seed as usize % 97;
            let mut w = ar1(phi, n + skip).split_off(skip);
            let mask: Vec<bool> = (0..n)
                .map(|i| ((i / block) as f64 * 0.618_034 + seed as f64 * 0.1).fract() < keep)
                .collect();
            for (x, &m) in w.iter_mut().zip(&mask) {
                *x = 1e3 + *x * 10f64.powi(scale);
                if !m && (x.to_bits() % 3 == 0) {
                    *x = f64::NAN;
                }
            }
            let fast = correlation_time_white(&w, &mask, max_lag);
            let slow = correlation_time_by_index(&w, &mask, max_lag);
            proptest::prop_assert!(fast.is_finite() && fast >= 1.0, "{}", fast);
            proptest::prop_assert!((fast - slow).abs() <= 1e-9 * slow, "{} vs {}", fast, slow);
        }
    }

    /// White residual: about one sample per sample. Noise slower than the base window (an
    /// AR(1) with a correlation time of 50 samples, whitened as if white, base window 10 lags)
    /// counts as its integrated autocorrelation, `(1 + φ)/(1 − φ)` = 39, which the base window
    /// alone misses by half.
    #[test]
    fn slow_leftover_correlation_counts_beyond_the_base_window() {
        let n = 40_000;
        let all = vec![true; n];
        let white = ArNoise::white(1.0);
        let tau = correlation_time(&ar1(0.0, n), &white, &all, 10);
        assert!((tau - 1.0).abs() < 0.3, "white: {tau}");
        let slow = ar1(0.95, n);
        let tau = correlation_time(&slow, &white, &all, 10);
        assert!((25.0..55.0).contains(&tau), "slow: {tau}");
        let base_only = {
            let short = &slow[..2 * 10 + 2 + LONG_WINDOW_DIVISOR * 10 - 1];
            correlation_time(short, &white, &all[..short.len()], 10)
        };
        assert!(base_only < 0.6 * tau, "base window {base_only} vs {tau}");
    }
}
